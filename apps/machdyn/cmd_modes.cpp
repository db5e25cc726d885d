// `machdyn modes MODEL [--case NAME] [--topology ELEMENT=MODE,... ...] [--from-run] [--json] [--plot]
// [-o DIR] [--frf INPUT [--output OUT ...] [--omega LO:HI[:N]]] [--over BODY [--range LO:HI] [--points N]]
// [--campbell LO:HI --order NAME=K ... [--shaft BODY]]`: the linear analysis per topology
// (analysis/linear_analysis.hpp), docs/modes.md.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <numbers>
#include <fmt/format.h>

#include "commands.hpp"
#include "machdyn/io/folder_lock.hpp"
#include "machdyn/analysis/frequency_response.hpp"
#include "machdyn/analysis/linear_analysis.hpp"
#include "machdyn/analysis/hanging_rest.hpp"
#include "machdyn/analysis/mode_kinds.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/elements/linearize.hpp"
#include "machdyn/io/figures.hpp"
#include "machdyn/io/linear_results.hpp"
#include "machdyn/io/model_file.hpp"

namespace machdyn::cli {
namespace {

constexpr double kTwoPi = 2.0 * std::numbers::pi;

struct ModesArgs {
  std::string model, out_dir, load_case;
  bool json = false, plot = false, from_run = false;
  std::vector<std::string> sets, topologies;
  std::string frf_input, omega_range, over_body, position_range, campbell_range, shaft;
  std::vector<std::string> outputs, orders;
  int points = 361;
};

/// "LO:HI" or "LO:HI:N" of an option, located at the option (column of the bad part).
std::vector<double> parse_range(const std::string& option, const std::string& text, size_t parts_min, size_t parts_max) {
  std::vector<double> v;
  size_t start = 0;
  Diagnostics diag;
  while (start <= text.size()) {
    const size_t end = std::min(text.find(':', start), text.size());
    const std::string item = text.substr(start, end - start);
    try {
      size_t used = 0;
      v.push_back(std::stod(item, &used));
      if (used != item.size() || !std::isfinite(v.back())) throw std::invalid_argument(item);
    } catch (const std::exception&) {
      diag.error(Location{option, 1, static_cast<int>(start) + 1}, fmt::format("'{}' is not a number", item));
    }
    start = end + 1;
  }
  if (diag.empty() && (v.size() < parts_min || v.size() > parts_max || v[1] < v[0]))
    diag.error(Location{option, 1, 1}, fmt::format("expected {} with LO <= HI, got '{}'",
                                                   parts_max == 3 ? "LO:HI or LO:HI:N" : "LO:HI", text));
  diag.throw_if_any();
  return v;
}

std::vector<TopologyModes> analyse(const Model& m, const ModesArgs& a) {
  std::vector<TopologyModes> list;
  if (a.from_run) {
    SimulateOptions opt;
    opt.record_series = false;
    list = run_topology_modes(m, simulate(m, opt).hybrid, m.simulation.t_end);
  } else if (!a.topologies.empty()) {
    for (const auto& text : a.topologies) list.push_back(analyse_topology(m, parse_topology(m, text, Location{"--topology", 1, 0})));
  } else {
    for (const Topology& t : all_topologies(m)) list.push_back(analyse_topology(m, t));
  }
  return list;
}

void print_topology(const Model& m, const TopologyModes& t, size_t index, size_t count) {
  std::cout << fmt::format("\ntopology {} of {}: {}\n", index + 1, count,
                           t.label.empty() ? "(no gap, contact or brake)" : t.label);
  if (!t.intervals.empty()) {
    std::string iv;
    for (const auto& [a, b] : t.intervals) iv += fmt::format("{}[{:.6g}, {:.6g}]", iv.empty() ? "" : " ", a, b);
    std::cout << fmt::format("  in the run: {} s\n", iv);
  }
  std::cout << fmt::format("  constraints (stuck contacts): {}, coordinates: {}, rigid-body modes: {}\n",
                           t.modes.constraints, t.modes.dof, t.modes.rigid_body_modes);
  if (t.modes.omega.size() == 0) {
    std::cout << "  no elastic mode\n";
    return;
  }
  std::string names;
  for (const auto& b : m.bodies) names += (names.empty() ? "" : ", ") + b.name;
  // A swinging load's model: each mode's kind (pendulum, rope stretch, drive line; analysis/mode_kinds.hpp).
  const bool kinds = has_swinging_load(m);
  const std::vector<ModeKind> kind = kinds ? mode_kinds(m, t.modes.shapes) : std::vector<ModeKind>{};
  std::cout << fmt::format("  {:>4} {:>16} {:>14} {}  mass-normalized shape ({})\n", "mode", "omega [rad/s]", "f [Hz]",
                           kinds ? fmt::format("{:<12} ", "kind") : std::string(), names);
  const Eigen::Index shown = std::min<Eigen::Index>(t.modes.omega.size(), 20);
  for (Eigen::Index k = 0; k < shown; ++k) {
    std::string shape;
    if (kinds) shape = fmt::format(" {:<12}", to_string(kind[static_cast<size_t>(k)]));
    for (Eigen::Index i = 0; i < std::min<Eigen::Index>(t.modes.shapes.rows(), 12); ++i)
      shape += fmt::format(" {:+.4f}", t.modes.shapes(i, k));
    if (t.modes.shapes.rows() > 12) shape += " ...";
    std::cout << fmt::format("  {:>4} {:>16.10g} {:>14.8g}  {}\n", k + 1, t.modes.omega(k), t.modes.omega(k) / kTwoPi, shape);
  }
  if (shown < t.modes.omega.size()) std::cout << fmt::format("  ... {} more (--json)\n", t.modes.omega.size() - shown);
  if (t.damped_skipped) std::cout << "  damped modes skipped: more than 400 coordinates (docs/modes.md)\n";
  if (t.damped) {
    std::cout << fmt::format("  damped: {:>4} {:>16} {:>16} {:>12} {:>14}\n", "mode", "omega_n [rad/s]", "omega_d [rad/s]",
                             "zeta", "decay [1/s]");
    int k = 0;
    for (const DampedMode& d : t.damped_modes.modes) {
      if (++k > 20) break;
      std::cout << fmt::format("          {:>4} {:>16.10g} {:>16.10g} {:>12.6g} {:>14.6g}{}\n", k, d.omega_n, d.omega_d,
                               d.oscillatory ? d.zeta : std::nan(""), d.decay_rate,
                               d.oscillatory ? "" : "  (overdamped, real root)");
    }
  }
}

/// The frequency grid of --omega, or 0.1 × the lowest to 3 × the highest natural frequency.
Eigen::VectorXd omega_grid(const ModesArgs& a, const UndampedModes& md) {
  if (!a.omega_range.empty()) {
    const auto v = parse_range("--omega", a.omega_range, 2, 3);
    const int n = v.size() == 3 ? static_cast<int>(v[2]) : 400;
    if (n < 2 || n > 1'000'000 || (v.size() == 3 && v[2] != n))
      throw InputError(Location{"--omega", 1, 1}, "N must be an integer from 2 to 1e6");
    if (v[0] < 0) throw InputError(Location{"--omega", 1, 1}, "frequencies must be >= 0 rad/s");
    return frequency_grid(v[0], v[1], n, v[0] > 0);
  }
  if (md.omega.size() == 0)
    throw InputError(Location{"--omega", 1, 1}, "this topology has no elastic mode: give the range --omega LO:HI");
  return frequency_grid(0.1 * md.omega.minCoeff(), 3.0 * md.omega.maxCoeff(), 400, true);
}

int run(const ModesArgs& a) {
  const Model m = load_model_case(a.model, a.sets, a.load_case);
  const bool write = !a.out_dir.empty() || a.plot;
  const std::filesystem::path dir = write ? output_dir(a.model, a.out_dir, a.load_case) : std::filesystem::path();
  // Everything the options name is checked before any computing or writing.
  Diagnostics diag;
  std::vector<ExcitationOrder> orders;
  for (const auto& o : a.orders) {
    const size_t eq = o.find('=');
    double k = 0;
    try {
      if (eq != std::string::npos) k = std::stod(o.substr(eq + 1));
    } catch (const std::exception&) {
      k = 0;
    }
    if (eq == std::string::npos || eq == 0 || !(k > 0) || !std::isfinite(k))
      diag.error(Location{"--order", 1, 1}, fmt::format("'{}': expected NAME=K with K > 0 (e.g. mesh=23)", o));
    else
      orders.push_back({o.substr(0, eq), k});
  }
  if (!a.campbell_range.empty() && orders.empty() && a.orders.empty()) orders.push_back({"1x", 1.0});
  if (a.campbell_range.empty() && !a.orders.empty()) diag.error(Location{"--order", 1, 1}, "--order needs --campbell LO:HI");
  if (a.over_body.empty() && !a.position_range.empty()) diag.error(Location{"--range", 1, 1}, "--range needs --over BODY");
  if (a.from_run && !a.topologies.empty())
    diag.error(Location{"--from-run", 1, 1}, "give either --from-run (the run's topologies) or --topology");
  diag.throw_if_any();
  const Topology lin_topo = a.topologies.empty() ? initial_topology(m)
                                                 : parse_topology(m, a.topologies.front(), Location{"--topology", 1, 0});
  int over = -2;
  if (!a.over_body.empty()) {
    over = m.body_index(a.over_body);
    if (over < 0) throw InputError(Location{"--over", 1, 1}, fmt::format("no body '{}'", a.over_body));
  }
  int shaft = 0;
  if (!a.shaft.empty()) {
    shaft = m.body_index(a.shaft);
    if (shaft < 0) throw InputError(Location{"--shaft", 1, 1}, fmt::format("no body '{}'", a.shaft));
  }
  FrequencyResponse frf;
  const bool want_frf = !a.frf_input.empty();
  if (!want_frf && (!a.outputs.empty() || !a.omega_range.empty()))
    throw InputError(Location{"--output", 1, 1}, "--output and --omega need --frf INPUT");
  if (want_frf) {
    const LinearSignal in = linear_input(m, a.frf_input, Location{"--frf", 1, 1});
    std::vector<LinearSignal> outs;
    Diagnostics od;
    for (const auto& o : a.outputs) try {
        outs.push_back(linear_output(m, lin_topo, o, Location{"--output", 1, 1}));
      } catch (const InputError& e) {
        for (const auto& d : e.diagnostics()) od.error(d.where, d.message);
      }
    od.throw_if_any();
    if (outs.empty())
      for (const Link& l : m.links) outs.push_back(linear_output(m, lin_topo, l.name + ".load", Location{"--output", 1, 1}));
    const std::vector<double> y = linearization_state(m, lin_topo);  // a load that starts on the floor hangs
    const LinearModel lin = linearize(m, lin_topo, 0.0, y.empty() ? nullptr : y.data());
    frf = frequency_response(lin, in, outs, omega_grid(a, undamped_modes(lin)));
  }
  if (a.plot) plot::find_gnuplot();

  const std::vector<TopologyModes> list = analyse(m, a);
  nlohmann::json j = linear_modes_json(m, list);
  std::vector<plot::Figure> figures;
  const std::string lin_label = topology_label(m, lin_topo);
  if (!list.empty() && list.front().modes.shapes.cols() > 0) {
    Modes md;
    md.omega = list.front().modes.omega, md.shapes = list.front().modes.shapes;
    figures.push_back(mode_shapes_figure(m, md));
    // Name the topology the shapes belong to (the first listed; --topology chooses another).
    if (!list.front().label.empty()) figures.back().title += fmt::format(" — {}", list.front().label);
  }
  if (want_frf) {
    j["frequency_response"] = frequency_response_json(frf);
    j["frequency_response"]["topology"] = lin_label;
    figures.push_back(bode_magnitude_figure(m, frf, lin_label));
    figures.push_back(bode_phase_figure(m, frf, lin_label));
  }
  PositionFrequencies pf;
  if (over >= 0) {
    const Body& b = m.bodies[static_cast<size_t>(over)];
    double lo = b.q0, hi = b.q0 + kTwoPi;
    if (!a.position_range.empty()) {
      const auto v = parse_range("--range", a.position_range, 2, 2);
      lo = v[0], hi = v[1];
    } else if (b.kind != BodyKind::rotational) {
      throw InputError(Location{"--range", 1, 1}, fmt::format("body '{}' translates: give its positions --range LO:HI (m)", b.name));
    }
    if (a.points < 2 || a.points > 100000) throw InputError(Location{"--points", 1, 1}, "expected 2 to 100000 points");
    pf = frequencies_over_position(m, lin_topo, over, frequency_grid(lo, hi, a.points, false));
    nlohmann::json rows = nlohmann::json::array();
    for (Eigen::Index i = 0; i < pf.positions.size(); ++i) {
      nlohmann::json w = nlohmann::json::array();
      for (Eigen::Index k = 0; k < pf.omega.cols(); ++k) w.push_back(std::isfinite(pf.omega(i, k)) ? nlohmann::json(pf.omega(i, k)) : nlohmann::json(nullptr));
      rows.push_back({{"position", pf.positions(i)}, {"omega_rad_s", w}});
    }
    j["frequencies_over_position"] = {{"body", pf.body}, {"topology", lin_label}, {"rows", rows}};
    figures.push_back(position_frequencies_figure(m, pf, lin_label));
  }
  std::vector<CampbellCrossing> crossings;
  if (!a.campbell_range.empty()) {
    const auto v = parse_range("--campbell", a.campbell_range, 2, 2);
    const double lo = v[0] / 60.0 * kTwoPi, hi = v[1] / 60.0 * kTwoPi;  // rpm → rad/s
    const TopologyModes t = analyse_topology(m, lin_topo);
    crossings = campbell(t.modes.omega, orders, lo, hi);
    j["campbell"] = campbell_json(crossings, m.bodies[static_cast<size_t>(shaft)].name);
    j["campbell"]["topology"] = lin_label;
    figures.push_back(campbell_figure(m, t.modes.omega, orders, lo, hi, crossings, m.bodies[static_cast<size_t>(shaft)].name));
  }

  std::vector<std::string> written;
  if (write) {
    const FolderLock lock(dir, kFolderLockWriteWait_s);  // one writer at a time (io/folder_lock.hpp)
    std::vector<std::string> files;
    if (a.plot) files = write_figures(dir, figures);
    write_file_atomic((dir / "modes.json").string(), j.dump(2) + "\n");
    write_file_atomic((dir / "modes.csv").string(), linear_modes_csv(list));
    written = {"modes.json", "modes.csv"};
    if (want_frf) write_file_atomic((dir / "frf.csv").string(), frequency_response_csv(frf)), written.push_back("frf.csv");
    if (over >= 0)
      write_file_atomic((dir / "frequencies_over_position.csv").string(), position_frequencies_csv(m, pf)),
          written.push_back("frequencies_over_position.csv");
    written.insert(written.end(), files.begin(), files.end());
  }
  if (a.json) {
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  std::cout << fmt::format("model: {} ({})\n", m.name, m.source);
  std::cout << fmt::format("{} topolog{}{}\n", list.size(), list.size() == 1 ? "y" : "ies",
                           a.from_run ? " in the run" : a.topologies.empty() && list.size() > 1 ? " (every combination of stuck/sliding contacts and closed/open gaps)" : "");
  for (size_t k = 0; k < list.size(); ++k) print_topology(m, list[k], k, list.size());
  if (want_frf) {
    std::cout << fmt::format("\nfrequency response from {} ({}) in topology {}: {} frequencies {:.6g} to {:.6g} rad/s\n",
                             frf.input.name, frf.input.unit, lin_label.empty() ? "-" : lin_label, frf.omega.size(),
                             frf.omega(0), frf.omega(frf.omega.size() - 1));
    for (const auto& p : resonance_peaks(frf))
      std::cout << fmt::format("  peak of {}: {:.6g} {}/{} at {:.6g} rad/s ({:.6g} Hz), phase {:.4g}°\n",
                               frf.outputs[static_cast<size_t>(p.output)].name, p.magnitude,
                               frf.outputs[static_cast<size_t>(p.output)].unit, frf.input.unit, p.omega,
                               p.omega / kTwoPi, p.phase_deg);
  }
  if (over >= 0) {
    std::cout << fmt::format("\nfrequencies over the position of {} ({} points):\n", pf.body, pf.positions.size());
    for (Eigen::Index k = 0; k < pf.omega.cols(); ++k) {
      double lo = INFINITY, hi = -INFINITY;
      for (Eigen::Index i = 0; i < pf.omega.rows(); ++i)
        if (std::isfinite(pf.omega(i, k))) lo = std::min(lo, pf.omega(i, k)), hi = std::max(hi, pf.omega(i, k));
      std::cout << fmt::format("  mode {}: {:.6g} to {:.6g} rad/s\n", k + 1, lo, hi);
    }
  }
  if (!a.campbell_range.empty()) {
    std::cout << fmt::format("\nresonances (Campbell, speed of {}): {}\n", m.bodies[static_cast<size_t>(shaft)].name,
                             crossings.empty() ? "none in the range" : "");
    for (const auto& c : crossings)
      std::cout << fmt::format("  {} (order {:g}) meets mode {} ({:.6g} Hz) at {:.6g} rpm ({:.6g} rad/s)\n", c.order_name,
                               c.order, c.mode, c.omega / kTwoPi, c.speed * 60.0 / kTwoPi, c.speed);
  }
  if (!written.empty()) std::cout << fmt::format("\nwrote {}/{{{}}}\n", dir.string(), fmt::join(written, ","));
  return 0;
}

}  // namespace

int run_modes(const std::string& model_path, const std::vector<std::string>& sets, bool json) {
  ModesArgs a;
  a.model = model_path, a.sets = sets, a.json = json;
  return run(a);
}

void register_modes(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<ModesArgs>();
  auto* cmd = app.add_subcommand("modes", "Natural frequencies, damping and frequency response per topology (docs/modes.md)");
  cmd->add_option("MODEL", a->model, "Model file (YAML)")->required();
  cmd->add_flag("--json", a->json, "Print JSON to stdout");
  cmd->add_flag("--plot", a->plot, "Write the figures (mode_shapes, bode_magnitude/phase, frequencies_over_position, "
                                   "campbell; .svg/.png; needs gnuplot)");
  cmd->add_option("-o,--out", a->out_dir, "Folder for modes.json, modes.csv, frf.csv, ... (default with --plot: out/MODEL)");
  add_set_option(*cmd, a->sets);
  cmd->add_option("--case", a->load_case, "Analyse one load case of the file's 'cases:'");
  cmd->add_option("--topology", a->topologies,
                  "The mode of each gap, contact and brake: ELEMENT=MODE,... (open, closed, closed+, closed-; stuck, "
                  "applied, slip+, slip-, sliding, released); repeat for several. Default: every topology");
  cmd->add_flag("--from-run", a->from_run, "Simulate, then analyse each topology the run passed through, with its times");
  cmd->add_option("--frf", a->frf_input, "Frequency response from this load or body (a force/torque on it)");
  cmd->add_option("--output", a->outputs, "FRF output: LINK.load, BODY.position or BODY.speed (repeatable; default: "
                                          "every link load)");
  cmd->add_option("--omega", a->omega_range, "FRF frequencies LO:HI[:N] in rad/s (log-spaced if LO > 0; default 400 "
                                             "from 0.1 x lowest to 3 x highest natural frequency)");
  cmd->add_option("--over", a->over_body, "Frequencies over the position of this body (a machine with I(q))");
  cmd->add_option("--range", a->position_range, "Positions LO:HI for --over (default: one revolution from its start)");
  cmd->add_option("--points", a->points, "Positions for --over (default 361)");
  cmd->add_option("--campbell", a->campbell_range, "Campbell diagram over shaft speeds LO:HI in rpm");
  cmd->add_option("--order", a->orders, "Excitation order NAME=K (frequency K x shaft speed; e.g. mesh=23), repeatable");
  cmd->add_option("--shaft", a->shaft, "Reference shaft of --campbell (default: the first body)");
  cmd->callback([a, &exit_code] { exit_code = guarded([&] { return run(*a); }); });
}

}  // namespace machdyn::cli
