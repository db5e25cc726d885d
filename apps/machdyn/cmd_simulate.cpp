// `machdyn simulate MODEL [-o DIR] [--json] [--set NAME.FIELD=VALUE ...]` and `machdyn modes MODEL`.
#include <filesystem>
#include <iostream>
#include <fmt/format.h>

#include "commands.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/results.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn::cli {
namespace {

struct SimulateArgs {
  std::string model;
  std::string out_dir;
  bool json = false;
  std::vector<std::string> sets;
};

void print_simulation_table(const Model& m, const SimulationResult& r, std::ostream& os) {
  os << fmt::format("model: {} ({})\n", m.name, m.source);
  os << fmt::format("integrator: {} ({}); {} steps, {} rejected, {} f-evals, {:.3f} ms\n", r.stats.method,
                    r.method_reason, r.stats.stepper.steps, r.stats.stepper.rejected, r.stats.stepper.rhs_evals,
                    r.stats.wall_time_s * 1e3);
  os << fmt::format("{:<12} {:>14} {:>12} {:>14} {:>14} {:>10}  {}\n", "link", "max", "t_max [s]", "min", "static",
                    "dyn.factor", "unit");
  for (size_t l = 0; l < m.links.size(); ++l) {
    const auto& s = r.links[l];
    os << fmt::format("{:<12} {:>14.6g} {:>12.6g} {:>14.6g} {:>14.6g} {:>10.4g}  {}\n", m.links[l].name, s.max,
                      s.t_max, s.min, s.static_load, s.dynamic_factor, link_load_unit(m, m.links[l]));
  }
}

}  // namespace

int run_simulate(const std::string& model_path, const std::vector<std::string>& sets, std::string out_dir,
                 bool json) {
  const Model m = load_model(model_path, sets);
  const SimulationResult r = simulate(m);
  if (out_dir.empty()) out_dir = (std::filesystem::path("out") / std::filesystem::path(model_path).stem()).string();
  const auto summary = simulation_summary(m, r);
  write_file_atomic((std::filesystem::path(out_dir) / "timeseries.csv").string(), timeseries_csv(r));
  write_file_atomic((std::filesystem::path(out_dir) / "summary.json").string(), summary.dump(2) + "\n");
  if (json) {
    std::cout << summary.dump(2) << '\n';
  } else {
    print_simulation_table(m, r, std::cout);
    std::cout << fmt::format("wrote {0}/timeseries.csv and {0}/summary.json\n", out_dir);
  }
  return 0;
}

int run_modes(const std::string& model_path, const std::vector<std::string>& sets, bool json) {
  const Model m = load_model(model_path, sets);
  const Modes modes = compute_modes(m);
  const auto j = modes_summary(m, modes);
  if (json) {
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  std::cout << fmt::format("model: {} ({})\nrigid-body modes: {}\n", m.name, m.source, modes.rigid_body_modes);
  std::cout << fmt::format("{:>4} {:>16} {:>14}   mass-normalized shape ({})\n", "mode", "omega [rad/s]", "f [Hz]",
                           [&] {
                             std::string s;
                             for (const auto& b : m.bodies) s += (s.empty() ? "" : ", ") + b.name;
                             return s;
                           }());
  for (Eigen::Index k = 0; k < modes.omega.size(); ++k) {
    std::string shape;
    for (Eigen::Index i = 0; i < modes.shapes.rows(); ++i) shape += fmt::format(" {:+.4f}", modes.shapes(i, k));
    std::cout << fmt::format("{:>4} {:>16.8g} {:>14.8g}  {}\n", k + 1, modes.omega(k),
                             modes.omega(k) / (2 * 3.14159265358979323846), shape);
  }
  return 0;
}

void register_simulate(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SimulateArgs>();
  auto* cmd = app.add_subcommand("simulate", "Simulate a model: time series, link-load peaks, dynamic factors");
  cmd->add_option("MODEL", args->model, "Model file (YAML)")->required();
  cmd->add_option("-o,--out", args->out_dir, "Output folder for timeseries.csv and summary.json (default out/MODEL)");
  cmd->add_flag("--json", args->json, "Print the summary as JSON to stdout");
  add_set_option(*cmd, args->sets);
  cmd->callback([args, &exit_code] {
    exit_code = guarded([&] { return run_simulate(args->model, args->sets, args->out_dir, args->json); });
  });
}

void register_modes(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<SimulateArgs>();
  auto* cmd = app.add_subcommand("modes", "Natural frequencies and mass-normalized mode shapes");
  cmd->add_option("MODEL", args->model, "Model file (YAML)")->required();
  cmd->add_flag("--json", args->json, "Print JSON to stdout");
  add_set_option(*cmd, args->sets);
  cmd->callback([args, &exit_code] {
    exit_code = guarded([&] { return run_modes(args->model, args->sets, args->json); });
  });
}

}  // namespace machdyn::cli
