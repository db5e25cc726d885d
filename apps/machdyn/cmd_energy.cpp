// `machdyn energy MODEL [--json] [--to S] [--points N] [-o DIR] [--delta D [--mean-speed W]] [--plot]`:
// the energy integral ω(q) of a 1-DOF machine (analysis/energy.hpp) and, with --delta, steady
// running of a periodic machine with the flywheel that brings the speed fluctuation to D.
// Like every command it writes into one folder, -o DIR (default out/MODEL): energy.csv (the ω(q)
// table), energy.json (what --json prints) and with --plot the figures. `--plot-dir DIR` is the
// deprecated spelling of `-o DIR`.
#include <cmath>
#include <filesystem>
#include <iostream>
#include <fmt/format.h>

#include "commands.hpp"
#include "machdyn/io/folder_lock.hpp"
#include "machdyn/common/csv.hpp"
#include "machdyn/analysis/energy.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/units.hpp"
#include "machdyn/io/energy_results.hpp"
#include "machdyn/io/figures.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn::cli {
namespace {

struct EnergyArgs {
  std::string model, to, mean_speed;
  std::string out;       ///< -o: the output folder (default out/MODEL)
  bool plot = false;     ///< write the figures (SVG + PNG, gnuplot)
  std::string plot_dir;  ///< --plot-dir: deprecated alias of -o
  int points = 201;
  double delta = 0.0;
  bool json = false;
  std::vector<std::string> sets;
};

double quantity_arg(const std::string& option, const std::string& text, const Dim& d) {
  std::string err;
  auto v = parse_as(text, d, &err);
  if (!v) throw InputError(Location{option, 0, 0}, err);
  return *v;
}

std::string table_csv(const nlohmann::json& t) {
  std::vector<std::string> cols;
  for (const auto& [k, v] : t.items()) cols.push_back(k);
  std::string s = csv_line(cols) + '\n';  // RFC 4180 (common/csv.hpp)
  const size_t rows = t["q"].size();
  for (size_t i = 0; i < rows; ++i) {
    for (size_t c = 0; c < cols.size(); ++c) s += fmt::format("{}{:.17g}", c ? "," : "", t[cols[c]][i].get<double>());
    s += '\n';
  }
  return s;
}

/// The output folder from -o and the deprecated --plot-dir.
std::filesystem::path energy_out_dir(const EnergyArgs& a) {
  if (a.out.size() >= 4 && a.out.ends_with(".csv"))
    throw InputError(Location{"-o", 0, 0}, fmt::format("-o names the output folder, as for every command; the table "
                                                       "is written to DIR/energy.csv (e.g. -o {})",
                                                       std::filesystem::path(a.out).parent_path().empty()
                                                           ? std::string("out")
                                                           : std::filesystem::path(a.out).parent_path().string()));
  if (!a.plot_dir.empty()) {
    if (!a.out.empty() && a.out != a.plot_dir)
      throw InputError(Location{"--plot-dir", 0, 0}, "give the output folder once, with -o DIR");
    std::cerr << "machdyn: warning: --plot-dir is deprecated; use -o DIR (one folder for every output)\n";
    return a.plot_dir;
  }
  return output_dir(a.model, a.out, "");
}

int run_energy(const EnergyArgs& a) {
  const std::filesystem::path out_dir = energy_out_dir(a);
  const Model m = load_model(a.model, a.sets);
  if (a.plot) plot::find_gnuplot();  // before the work, not after
  EnergyOptions opt;
  opt.points = a.points;
  if (!a.to.empty()) opt.s_to = quantity_arg("--to", a.to, dim::none);
  const EnergyResult r = energy_analysis(m, opt);
  nlohmann::json j = energy_json(m, r);
  if (a.delta > 0) {
    const double wm = a.mean_speed.empty() ? std::abs(m.bodies[0].v0)
                                           : quantity_arg("--mean-speed", a.mean_speed, dim::angular_velocity);
    j["steady"] = steady_json(steady_running(m, wm, a.delta));
  }
  // Render the figures before anything is written: a failing gnuplot leaves no partial results.
  std::vector<plot::Rendered> rendered;
  const auto figures = a.plot ? energy_figures(m, r) : std::vector<plot::Figure>{};
  for (const auto& f : figures) rendered.push_back(plot::render(f));
  const FolderLock lock(out_dir, kFolderLockWriteWait_s);  // one writer at a time (io/folder_lock.hpp)
  write_file_atomic((out_dir / "energy.csv").string(), table_csv(j["table"]));
  write_file_atomic((out_dir / "energy.json").string(), j.dump(2) + "\n");
  std::vector<std::string> files;
  for (std::size_t k = 0; k < figures.size(); ++k) {
    write_file_atomic((out_dir / (figures[k].id + ".svg")).string(), rendered[k].svg);
    write_file_atomic((out_dir / (figures[k].id + ".png")).string(), rendered[k].png);
    files.push_back(figures[k].id + ".svg"), files.push_back(figures[k].id + ".png");
  }
  if (a.json) {
    std::cout << j.dump(2) << '\n';
    return 0;
  }
  std::cout << fmt::format("model: {} ({})\nbody '{}': {}, q0 = {:.9g} rad, omega0 = {:.9g} rad/s\n", m.name, m.source,
                           r.body, r.machine, r.q0, r.omega0);
  auto list = [](const nlohmann::json& v) {
    std::string s;
    for (const auto& x : v) s += fmt::format("{}{:.9g}", s.empty() ? "" : ", ", x.get<double>());
    return "[" + s + "]";
  };
  std::cout << fmt::format("turning points q [rad]: {}\n", list(j["turning_points"]));
  std::cout << fmt::format("omega_max = {:.9g} rad/s at q = {:.9g} rad\n", r.omega_max, r.q_at_omega_max);
  std::cout << fmt::format("omega_min = {:.9g} rad/s at q = {:.9g} rad\n", r.omega_min, r.q_at_omega_min);
  std::cout << fmt::format("omega_limit: {} ({})\n", r.omega_limit ? fmt::format("{:.9g} rad/s", *r.omega_limit) : "-",
                           r.limit_kind);
  if (r.epsilon_limit)
    std::cout << fmt::format("epsilon_limit = {:.9g} rad/s^2 (the angular acceleration the unbounded motion tends to)\n",
                             *r.epsilon_limit);
  for (const auto& [k, v] : j.items())
    if (k.find('_') != std::string::npos && (k.rfind(r.s_name + "_", 0) == 0 || (!r.point_name.empty() && k.rfind(r.point_name + "_", 0) == 0)) && r.s_name != "q")
      std::cout << fmt::format("{} = {}\n", k, v.is_array() ? list(v) : fmt::format("{:.9g}", v.get<double>()));
  if (r.work_per_period) std::cout << fmt::format("work per period = {:.9g} J\n", *r.work_per_period);
  if (j.contains("steady")) {
    const auto& s = j["steady"];
    std::cout << fmt::format(
        "steady running at omega_mean = {:.6g} rad/s (balancing torque {:.6g} N*m): delta = {:.6g} "
        "(omega {:.6g} .. {:.6g})\nflywheel for delta = {:.6g}: {:.6g} kg*m^2 (classic estimate {:.6g}); "
        "omega {:.6g} .. {:.6g}\n",
        s["omega_mean"].get<double>(), s["balancing_torque"].get<double>(), s["delta"].get<double>(),
        s["omega_min"].get<double>(), s["omega_max"].get<double>(), s["delta_target"].get<double>(),
        s["flywheel_inertia"].get<double>(), s["flywheel_estimate"].get<double>(),
        s["omega_min_with_flywheel"].get<double>(), s["omega_max_with_flywheel"].get<double>());
  }
  std::cout << fmt::format("{:>16} {:>16} {:>16}\n", "q [rad]", "omega [rad/s]", "I [kg*m^2]");
  const auto& t = j["table"];
  const size_t rows = t["q"].size(), stride = std::max<size_t>(1, rows / 20);
  for (size_t i = 0; i < rows; i += (i + stride < rows || i + 1 == rows) ? stride : rows - 1 - i)
    std::cout << fmt::format("{:>16.9g} {:>16.9g} {:>16.9g}\n", t["q"][i].get<double>(), t["omega"][i].get<double>(),
                             t["I"][i].get<double>());
  std::cout << fmt::format("wrote {0}/energy.csv and {0}/energy.json\n", out_dir.string());
  if (!files.empty()) std::cout << fmt::format("figures: {}/{{{}}}\n", out_dir.string(), fmt::join(files, ","));
  return 0;
}

}  // namespace

void register_energy(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<EnergyArgs>();
  auto* cmd = app.add_subcommand("energy", "Energy integral of a 1-DOF machine: omega(q), turning points, limit "
                                           "speed; with --delta, steady running and flywheel sizing");
  cmd->add_option("MODEL", a->model, "Model file (YAML) with one body and no links")->required();
  cmd->add_flag("--json", a->json, "Print JSON to stdout");
  cmd->add_option("--to", a->to, "End of the scan in the sweep coordinate (beta for the rolling wheel, q otherwise), "
                                 "e.g. '720 deg'");
  cmd->add_option("--points", a->points, "Rows of the omega(q) table (default 201)")->check(CLI::Range(3, 1000000));
  cmd->add_option("-o,--out", a->out,
                  "Output folder (default out/MODEL): energy.csv (the omega(q) table), energy.json, --plot figures");
  cmd->add_option("--delta", a->delta, "Target coefficient of speed fluctuation (ωmax−ωmin)/ωmean: size a flywheel")
      ->check(CLI::PositiveNumber);
  cmd->add_option("--mean-speed", a->mean_speed, "Mean speed for --delta (default: the body's initial velocity)");
  cmd->add_flag("--plot", a->plot,
                "Write speed_distance.svg/.png (rolling wheel: omega against distance, limit speed dashed) or "
                "speed_angle.svg/.png, and for a crank inertia_moments.svg/.png (needs gnuplot)");
  cmd->add_option("--plot-dir", a->plot_dir, "Deprecated: the same as -o DIR");
  add_set_option(*cmd, a->sets);
  cmd->callback([a, &exit_code] { exit_code = guarded([&] { return run_energy(*a); }); });
}

}  // namespace machdyn::cli
