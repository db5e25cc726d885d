// `machdyn simulate MODEL [-o DIR] [--json] [--plot] [--quiet] [--case NAME | --all-cases]
// [--set NAME.FIELD=VALUE ...]` (`modes`: cmd_modes.cpp).
#include <cmath>
#include <set>
#include <filesystem>
#include <memory>
#include <iostream>
#include <fmt/format.h>

#include "commands.hpp"
#include "progress.hpp"
#include "machdyn/elements/modes.hpp"
#include "machdyn/analysis/machine_outputs.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/io/figures.hpp"
#include "machdyn/io/folder_lock.hpp"
#include "machdyn/io/output_file.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/analysis/extra_outputs.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/results.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/cases.hpp"
#include "machdyn/model/compile.hpp"
#include "machdyn/model/machine.hpp"

namespace machdyn::cli {
namespace {

struct SimulateArgs {
  std::string model;
  std::string out_dir;
  bool json = false;
  bool plot = false;   ///< also write the figures (SVG + PNG, gnuplot)
  bool quiet = false;  ///< no progress bar
  std::vector<std::string> sets;
  std::string load_case;   ///< --case
  bool all_cases = false;  ///< --all-cases
  bool large_output = false;  ///< --large-output: write a time series above the size limit
  bool rpm = false;           ///< --rpm: angular speeds of the figures in rpm
  std::vector<std::string> outputs;  ///< --outputs: extra column groups (analysis/extra_outputs.hpp)
  bool check = false;  ///< --check: the invariant audit (analysis/audit.hpp)
  std::vector<std::string> links;  ///< --links: the links drawn by --plot
};

/// A dynamic factor for the tables: "–" where it has no meaning (NaN: no quasi-static load, a buffer).
std::string factor_text(double f) { return std::isfinite(f) ? fmt::format("{:.4g}", f) : std::string("–"); }
std::vector<std::string> split_lines(const std::string& text) {
  std::vector<std::string> out;
  for (size_t a = 0, b; a < text.size(); a = b + 1) {
    b = text.find('\n', a);
    if (b == std::string::npos) b = text.size();
    out.push_back(text.substr(a, b - a));
  }
  return out;
}

void print_simulation_table(const Model& m, const SimulationResult& r, std::ostream& os) {
  os << fmt::format("model: {} ({})\n", m.name, m.source);
  os << fmt::format("integrator: {} ({}); {} steps, {} rejected, {} f-evals, {:.3f} ms\n", r.stats.method,
                    r.method_reason, r.stats.stepper.steps, r.stats.stepper.rejected, r.stats.stepper.rhs_evals,
                    r.stats.wall_time_s * 1e3);
  os << fmt::format("{:<12} {:>14} {:>12} {:>14} {:>14} {:>10}  {}\n", "link", "max", "t_max [s]", "min", "static",
                    "dyn.factor", "unit");
  for (size_t l = 0; l < m.links.size(); ++l) {
    const auto& s = r.links[l];
    os << fmt::format("{:<12} {:>14.6g} {:>12.6g} {:>14.6g} {:>14.6g} {:>10}  {}\n", m.links[l].name, s.max,
                      s.t_max, s.min, s.static_load, factor_text(s.dynamic_factor), link_load_unit(m, m.links[l]));
  }
  if (r.hybrid.active) {
    long events = 0;
    for (const auto& e : r.hybrid.events) events += e.kind != "initial";
    os << fmt::format("hybrid: {} mode events, {} slip phases; energy balance residual {:.3g} J of {:.6g} J source work\n",
                      events, r.hybrid.slip_phases.size(), r.hybrid.energy.residual(), r.hybrid.energy.source_work);
  }
  os << brake_stops_text(brake_summaries(m, r));  // each brake's stops (analysis/brake_summary.hpp)
  os << sway_text(r.sway);           // each spatial rope's sway (analysis/sway_summary.hpp)
  for (const auto& x : r.machines) {
    if (x.jumps > 0)
      os << fmt::format("{}: {} velocity jumps (stepwise ratio), {:.6g} J lost in them\n", x.body, x.jumps, x.jump_loss);
    if (!x.window) {
      os << fmt::format("{}: less than one period ({:.3g} rad) run, no speed uniformity\n", x.body, x.period);
      continue;
    }
    os << fmt::format("{}: last period t = {:.6g} … {:.6g} s ({:.2f} periods run): speed {:.6g} rad/s, δω = {:.4g}\n",
                      x.body, x.t_from, x.t_to, x.periods_run, x.omega_mean, x.omega_delta);
    if (!x.point.empty())
      os << fmt::format("{}: {} speed mean {:.6g} m/s, max {:.6g}, min {:.6g}, δ = (max − min)/mean = {:.4g}{}\n", x.body,
                        x.point, x.v_mean, x.v_max, x.v_min, x.delta,
                        x.delta_previous >= 0 ? fmt::format(" (period before: {:.4g})", x.delta_previous) : "");
  }
}

/// `--all-cases`: every case of the file, outputs in OUT/CASE/, one table of peak link loads and
/// dynamic factors. All or nothing: every case runs (results kept in memory) before the first file
/// is written, so a case that fails leaves no result of this run behind and is named on stderr.
int run_all_cases(const SimulateArgs& a) {
  const std::string& model_path = a.model;
  const auto names = case_names(read_yaml_file(model_path));
  if (names.empty()) throw InputError(Location{model_path, 0, 0}, "--all-cases: the model file has no 'cases:'");
  const std::filesystem::path out_dir = output_dir(model_path, a.out_dir, "");
  // Compile every case first, so bad input stops the run before any result is written.
  std::vector<Model> models;
  for (const auto& name : names) models.push_back(load_model_case(model_path, a.sets, name));
  // Every case runs event-driven; that solver handles position-dependent inertia but not the
  // velocity jumps of a stepwise gear drive.
  for (const auto& m : models)
    if (has_velocity_jumps(m))
      throw InputError(Location{model_path, 0, 0},
                       "--all-cases: the model has velocity jumps (a stepwise gear drive), which only the smooth "
                       "simulation handles; run the cases one by one with --case NAME");
  // The cases' time series are all held until the end: their sum must fit the output limit.
  if (!a.large_output) {
    std::uint64_t total = 0;
    for (const auto& m : models) total += estimate_timeseries(m).csv_bytes;
    if (total > kDefaultOutputLimitBytes)
      throw InputError(Location{model_path, 0, 0},
                       fmt::format("--all-cases: the time series of the {} cases would be about {} together, more "
                                   "than the limit of {}; raise simulation.dt_out or pass --large-output",
                                   models.size(), byte_size_text(total), byte_size_text(kDefaultOutputLimitBytes)));
  }
  if (a.plot) plot::find_gnuplot();  // say it before the runs, not after
  if (!a.links.empty())
    for (const auto& m : models) (void)link_load_groups(m, SimulationResult{}, a.links);
  std::vector<SimulationResult> results;
  for (size_t c = 0; c < names.size(); ++c) {
    try {
      SimulateOptions every_case;
      every_case.event_driven = true;  // event-driven for every case, smooth or not
      every_case.check = a.check;
      results.push_back(simulate(models[c], every_case, output_selection(a.outputs)));
      for (const std::string& w : results.back().hybrid.warnings)
        std::cerr << fmt::format("machdyn: warning: case '{}': {}\n", names[c], w);
    } catch (const SolverError&) {
      std::cerr << fmt::format("machdyn: case '{}' ({} of {}) failed; no result of this run was written\n", names[c],
                               c + 1, names.size());
      throw;
    }
  }
  nlohmann::json all = nlohmann::json::array();
  // The peak is the extreme of larger magnitude; the dynamic factor is peak / quasi-static load there.
  std::string table = fmt::format("{:<20} {:<6} {:>11} {:>11} {:>11} {:>11} {:>9} {:>11} {:>10} {:>6}  {}\n", "case",
                                  "link", "max", "min", "peak", "t_peak [s]", "static", "dyn.factor", "events", "", "unit");
  // OUT and each OUT/CASE are this run's while it writes (a `--case NAME` run writes to OUT/NAME):
  // two runs never mix their files (io/folder_lock.hpp).
  std::vector<std::unique_ptr<FolderLock>> locks;
  locks.push_back(std::make_unique<FolderLock>(out_dir, kFolderLockWriteWait_s));
  for (const auto& name : names) locks.push_back(std::make_unique<FolderLock>(out_dir / name, kFolderLockWriteWait_s));
  // A failure while writing (disk full) removes what this run wrote, so no half set is left.
  std::vector<std::filesystem::path> written;
  std::set<std::string> figure_names;  // --plot: the figure files written in the cases' folders
  std::string brake_lines;  // each case's brake stops and sway, printed under the table
  try {
    for (size_t c = 0; c < names.size(); ++c) {
      const Model& m = models[c];
      const SimulationResult& r = results[c];
      const auto summary = simulation_summary(m, r);
      const auto dir = out_dir / names[c];
      written.push_back(dir / "timeseries.csv");
      write_timeseries_csv(written.back(), r);
      written.push_back(dir / "summary.json");
      write_file_atomic(written.back().string(), summary.dump(2) + "\n");
      if (a.plot) {  // each case's figures in its folder, as `simulate --case NAME --plot`
        FigureOptions fig_options;
        fig_options.rpm = a.rpm;
        fig_options.links = a.links;
        for (const auto& f : write_figures(dir.string(), simulation_figures(m, r, fig_options))) {
          written.push_back(dir / f);
          figure_names.insert(f);
        }
      }
      all.push_back(summary);
      for (const auto& line : split_lines(brake_stops_text(brake_summaries(m, r))))
        brake_lines += fmt::format("case {}: {}\n", names[c], line);
      for (const auto& line : split_lines(sway_text(r.sway)))
        brake_lines += fmt::format("case {}: {}\n", names[c], line);
      long events = 0;
      for (const auto& e : r.hybrid.events) events += e.kind != "initial";
      for (size_t l = 0; l < m.links.size(); ++l) {
        const LinkSummary& s = r.links[l];
        table += fmt::format("{:<20} {:<6} {:>11.5g} {:>11.5g} {:>11.5g} {:>11.4g} {:>9.4g} {:>11} {:>10} {:>6}  {}\n",
                             l == 0 ? names[c] : "", m.links[l].name, s.max, s.min, s.peak, s.t_peak, s.static_load,
                             factor_text(s.dynamic_factor), l == 0 ? std::to_string(events) : "", "", link_load_unit(m, m.links[l]));
      }
    }
    written.push_back(out_dir / "cases.json");
    write_file_atomic(written.back().string(), all.dump(2) + "\n");
  } catch (const OutputError&) {
    for (const auto& p : written) {
      std::error_code ec;
      std::filesystem::remove(p, ec);
    }
    throw;
  }
  if (a.json) {
    std::cout << all.dump(2) << '\n';
  } else {
    std::cout << fmt::format("model: {} ({}), {} cases\n", models[0].name.substr(0, models[0].name.rfind(" [")),
                             model_path, names.size())
              << table << brake_lines
              << fmt::format("wrote {0}/CASE/timeseries.csv, {0}/CASE/summary.json, {0}/cases.json\n", out_dir.string());
    if (!figure_names.empty())
      std::cout << fmt::format("figures: {}/CASE/{{{}}}\n", out_dir.string(), fmt::join(figure_names, ","));
  }
  return 0;
}

int run_simulate(const SimulateArgs& a) {
  const Model m = load_model_case(a.model, a.sets, a.load_case);
  if (!a.large_output) check_output_size(m, kDefaultOutputLimitBytes, "--large-output");
  if (a.plot) plot::find_gnuplot();  // say it before a long run, not after
  if (!a.links.empty()) (void)link_load_groups(m, SimulationResult{}, a.links);  // a typo costs no run
  ProgressBar bar(a.quiet);
  SimulateOptions options;
  options.progress = bar.callback();
  options.check = a.check;
  const SimulationResult r = simulate(m, options, output_selection(a.outputs));
  for (const std::string& w : r.hybrid.warnings) std::cerr << "machdyn: warning: " << w << "\n";
  bar.clear();
  const std::string out_dir = output_dir(a.model, a.out_dir, a.load_case).string();
  // One run at a time writes this folder's files; another writer is waited for (io/folder_lock.hpp).
  const FolderLock lock(out_dir, kFolderLockWriteWait_s);
  const auto summary = simulation_summary(m, r);
  std::vector<std::string> figures;
  FigureOptions fig_options;
  fig_options.rpm = a.rpm;
  fig_options.links = a.links;
  if (a.plot) figures = write_figures(out_dir, simulation_figures(m, r, fig_options));
  write_timeseries_csv(std::filesystem::path(out_dir) / "timeseries.csv", r);
  write_file_atomic((std::filesystem::path(out_dir) / "summary.json").string(), summary.dump(2) + "\n");
  if (a.json) {
    std::cout << summary.dump(2) << '\n';
  } else {
    print_simulation_table(m, r, std::cout);
    std::cout << fmt::format("wrote {0}/timeseries.csv and {0}/summary.json\n", out_dir);
    if (!figures.empty()) std::cout << fmt::format("figures: {}/{{{}}}\n", out_dir, fmt::join(figures, ","));
  }
  return 0;
}

}  // namespace

int run_simulate(const std::string& model_path, const std::vector<std::string>& sets, std::string out_dir,
                 bool json) {
  SimulateArgs a;
  a.model = model_path, a.out_dir = std::move(out_dir), a.json = json, a.sets = sets;
  return run_simulate(a);
}

void register_simulate(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SimulateArgs>();
  auto* cmd = app.add_subcommand("simulate", "Simulate a model: time series, link-load peaks, dynamic factors");
  cmd->add_option("MODEL", args->model, "Model file (YAML)")->required();
  cmd->add_option("-o,--out", args->out_dir,
                  "Output folder OUT (default out/MODEL); timeseries.csv and summary.json go to OUT, with --case NAME "
                  "to OUT/NAME, with --all-cases to OUT/CASE for each case");
  cmd->add_flag("--json", args->json, "Print the summary as JSON to stdout");
  cmd->add_flag("--plot", args->plot,
                "Also write link_loads.svg/.png (link loads against time, static values dashed) and "
                "body_speeds.svg/.png; with friction contacts load_cyclogram and contacts too (needs gnuplot)");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress bar on stderr (it shows only on a terminal, after 1 s)");
  add_set_option(*cmd, args->sets);
  cmd->add_option("--case", args->load_case, "Run one load case of the file's 'cases:' (e.g. a hoist operating mode)");
  cmd->add_flag("--all-cases", args->all_cases,
                "Run every load case: one table of peak link loads and dynamic factors, outputs in OUT/CASE/; "
                "if a case fails nothing is written");
  cmd->add_flag("--rpm", args->rpm, "With --plot: angular speeds in rpm instead of rad/s");
  cmd->add_option("--links", args->links,
                  "With --plot: the links whose loads are drawn (comma-separated; default: all, in panels by unit and size)")
      ->delimiter(',');
  cmd->add_option("--outputs", args->outputs,
                  "Extra columns of timeseries.csv, comma-separated groups: deflection (per link), acceleration "
                  "(per body), power (per load and drive, damping power per damped link), heat (per friction "
                  "element: heat power and heat since t = 0), or all (docs/model-files.md, Outputs)")
      ->delimiter(',');
  cmd->add_flag("--large-output", args->large_output,
                "Write the time series even when it would exceed 1 GB (simulation.t_end/dt_out rows)");
  cmd->add_flag("--check", args->check,
                "Audit the run against the documented laws at every step, event and output row (static limits, "
                "kinetic laws, freewheels, gaps, ropes, end stops, lossy gears, energy books, event list); a "
                "violation names the element, time, values and invariant and exits 3 (docs/hybrid.md)");
  cmd->callback([args, &exit_code] {
    exit_code = guarded([&] {
      if (args->all_cases && !args->load_case.empty())
        throw InputError(Location{"--case", 0, 0}, "give either --case NAME or --all-cases");
      if (args->all_cases) return run_all_cases(*args);
      return run_simulate(*args);
    });
  });
}

}  // namespace machdyn::cli
