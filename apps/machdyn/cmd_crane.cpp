// `machdyn crane MODEL [-o DIR] [--json] [--case NAME | --all-cases] [--set ...]`: the crane analysis (analysis/crane.hpp) of a
// model with a `crane:` section — each dynamic factor simulated beside the EN 13001-2 value. Writes
// DIR/crane.json and DIR/crane.csv (default out/MODEL) and prints the table (or the JSON);
// --phi2-speeds FROM:TO:N adds φ2(vh) beside the standard's line (DIR/phi2_sweep.csv; with --plot
// also the figure crane_phi2_sweep.svg/.png).
#include <iostream>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "commands.hpp"
#include "machdyn/analysis/crane.hpp"
#include "machdyn/analysis/crane_standard.hpp"
#include "machdyn/io/crane_results.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/units.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/cases.hpp"

namespace machdyn::cli {
namespace {

struct CraneArgs {
  std::string model, out;
  std::string phi2_speeds;  ///< --phi2-speeds FROM:TO:N (m/s)
  std::string drive_classes;  ///< --drive-classes HD1,HD4 | all
  bool json = false;
  bool plot = false;  ///< --plot: one figure per factor (SVG + PNG, gnuplot)
  std::string load_case;   ///< --case NAME
  bool all_cases = false;  ///< --all-cases
  std::vector<std::string> sets;
};

/// FROM:TO:N with speeds in m/s (plain numbers or quantities such as `0.1 m/s`), N ≥ 2 evenly
/// spaced, or one speed.
std::vector<double> speed_list(const std::string& text) {
  const auto bad = [&](const std::string& why) {
    return InputError(Location{"--phi2-speeds", 0, 0}, fmt::format("'{}': {}; expected FROM:TO:N, e.g. 0.1:0.5:5", text, why));
  };
  std::vector<std::string> parts;
  for (size_t start = 0;;) {
    const size_t colon = text.find(':', start);
    parts.push_back(text.substr(start, colon == std::string::npos ? std::string::npos : colon - start));
    if (colon == std::string::npos) break;
    start = colon + 1;
  }
  if (parts.size() != 1 && parts.size() != 3) throw bad("give one speed or three fields");
  std::string err;
  auto speed = [&](const std::string& s) {
    auto v = parse_as(s, dim::velocity, &err);
    if (!v || !(*v > 0.0)) throw bad(v ? "a speed must be > 0" : err);
    return *v;
  };
  if (parts.size() == 1) return {speed(parts[0])};
  const double from = speed(parts[0]), to = speed(parts[1]);
  int n = 0;
  try {
    n = std::stoi(parts[2]);
  } catch (const std::exception&) {
    throw bad("N is not a whole number");
  }
  if (n < 2 || n > 10000) throw bad("N must lie in [2, 10000]");
  std::vector<double> out;
  for (int k = 0; k < n; ++k) out.push_back(from + (to - from) * k / (n - 1));
  return out;
}

/// "all" (HD1…HD5) or a comma list of HD1…HD5, in the order given.
std::vector<int> drive_class_list(const std::string& text) {
  if (text.empty()) return {};
  if (text == "all") return {1, 2, 3, 4, 5};
  std::vector<int> out;
  for (size_t start = 0;;) {
    const size_t comma = text.find(',', start);
    const std::string word = text.substr(start, comma == std::string::npos ? std::string::npos : comma - start);
    try {
      out.push_back(static_cast<int>(crane::parse_hoist_drive_class(word)));
    } catch (const std::invalid_argument&) {
      throw InputError(Location{"--drive-classes", 0, 0},
                       fmt::format("'{}': expected 'all' or a comma list of HD1, HD2, HD3, HD4, HD5", word));
    }
    if (comma == std::string::npos) break;
    start = comma + 1;
  }
  return out;
}

/// The crane analysis of one model (the file, or one of its load cases), held until every case ran.
struct CraneRun {
  std::string case_name;  ///< "" for the file as written
  CraneReport report;
  nlohmann::json json;
  std::string sweep_csv;
  std::vector<plot::Figure> figures;
};

CraneRun crane_run(const CraneArgs& a, const Model& m, const std::string& case_name) {
  CraneRun run;
  run.case_name = case_name;
  run.report = crane_analysis(m, drive_class_list(a.drive_classes));
  run.json = crane_json(run.report);
  if (a.plot) run.figures = crane_figures(run.report);
  if (!a.phi2_speeds.empty()) {  // φ2(vh) beside the standard's line
    const std::vector<double> speeds = speed_list(a.phi2_speeds);
    run.sweep_csv = "vh_m_s,phi2_simulated,phi2_standard\n";
    nlohmann::json pts = nlohmann::json::array();
    const std::vector<Phi2Point> sweep = phi2_sweep(m, speeds);
    if (a.plot) run.figures.push_back(phi2_sweep_figure(sweep));
    for (const Phi2Point& p : sweep) {
      run.sweep_csv += fmt::format("{:.17g},{:.17g},{:.17g}\n", p.vh, p.simulated, p.standard);
      pts.push_back({{"vh_m_s", p.vh}, {"simulated", p.simulated}, {"standard", p.standard}});
    }
    run.json["phi2_sweep"] = pts;
  }
  return run;
}

int run_crane(const CraneArgs& a) {
  if (a.all_cases && !a.load_case.empty()) throw InputError(Location{"--case", 0, 0}, "give either --case NAME or --all-cases");
  // Every case is compiled first, so bad input stops before anything runs or is written.
  std::vector<std::string> names{a.load_case};
  if (a.all_cases) {
    names = case_names(read_yaml_file(a.model));
    if (names.empty()) throw InputError(Location{a.model, 0, 0}, "--all-cases: the model file has no 'cases:'");
  }
  std::vector<Model> models;
  std::vector<std::string> skipped;  // --all-cases: the cases without a crane section
  std::vector<std::string> ran;
  for (const auto& name : names) {
    Model m = name.empty() ? load_model(a.model, a.sets) : load_model_case(a.model, a.sets, name);
    if (a.all_cases && !m.crane.given) {
      skipped.push_back(name);
      continue;
    }
    models.push_back(std::move(m));
    ran.push_back(name);
  }
  if (models.empty())
    throw InputError(Location{a.model, 0, 0}, "--all-cases: no load case has a 'crane:' section (docs/crane-factors.md)");
  if (a.plot) plot::find_gnuplot();  // before the work, not after
  // All or nothing: every case runs before the first file is written.
  std::vector<CraneRun> runs;
  for (size_t k = 0; k < models.size(); ++k) {
    try {
      runs.push_back(crane_run(a, models[k], ran[k]));
    } catch (const SolverError&) {
      if (!ran[k].empty()) std::cerr << fmt::format("machdyn: load case '{}' failed; nothing was written\n", ran[k]);
      throw;
    }
  }
  nlohmann::json all = nlohmann::json::array();
  std::string text;
  for (const CraneRun& run : runs) {
    const std::filesystem::path out_dir = output_dir(a.model, a.out, run.case_name);
    write_file_atomic((out_dir / "crane.csv").string(), crane_csv(run.report));
    if (!run.sweep_csv.empty()) write_file_atomic((out_dir / "phi2_sweep.csv").string(), run.sweep_csv);
    const std::vector<std::string> files = a.plot ? write_figures(out_dir, run.figures) : std::vector<std::string>{};
    write_file_atomic((out_dir / "crane.json").string(), run.json.dump(2) + "\n");
    for (const auto& x : run.report.rows)
      if (!x.warning.empty())
        std::cerr << fmt::format("machdyn: warning: {}{} ({}): {}\n",
                                 run.case_name.empty() ? "" : fmt::format("load case '{}': ", run.case_name), x.factor,
                                 x.case_name, x.warning);
    all.push_back(run.json);
    text += crane_table(run.report);
    text += fmt::format("wrote {0}/crane.csv and {0}/crane.json\n", out_dir.string());
    if (!files.empty()) text += fmt::format("figures: {}/{{{}}}\n", out_dir.string(), fmt::join(files, ","));
    if (runs.size() > 1) text += "\n";
  }
  for (const auto& name : skipped)
    text += fmt::format("load case '{}': no 'crane:' section (the case drops it): no crane analysis\n", name);
  if (a.json) {
    std::cout << (a.all_cases ? all : all[0]).dump(2) << '\n';
    return 0;
  }
  std::cout << text;
  return 0;
}

}  // namespace

void register_crane(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<CraneArgs>();
  auto* cmd = app.add_subcommand("crane", "Crane dynamic factors (phi2, phi3, phi5, phi7) simulated beside EN 13001-2");
  cmd->add_option("MODEL", a->model, "Model file (YAML) with a 'crane:' section (docs/crane-factors.md)")->required();
  cmd->add_flag("--json", a->json, "Print JSON to stdout");
  cmd->add_flag("--plot", a->plot, "Write crane_FACTOR_K.svg/.png: each factor's time history with the standard's "
                                   "value dashed (needs gnuplot)");
  cmd->add_option("-o,--out", a->out, "Output folder (default out/MODEL): crane.csv, crane.json");
  cmd->add_option("--phi2-speeds", a->phi2_speeds,
                  "phi2 over hoisting speeds FROM:TO:N (m/s) beside the standard's line: phi2_sweep.csv and "
                  "'phi2_sweep' in the JSON (with --plot: crane_phi2_sweep.svg/.png)");
  cmd->add_option("--drive-classes", a->drive_classes,
                  "phi2 in each of these hoist drive classes instead of the section's own: 'all' or e.g. HD1,HD2,HD4 "
                  "(vh,max, the creep speed, 0.5 vh,max; HD5 starts from zero speed and is not simulated)");
  cmd->add_option("--case", a->load_case,
                  "The crane analysis of one load case of the file's 'cases:' (outputs in OUT/NAME; a case may change "
                  "or drop the 'crane:' section)");
  cmd->add_flag("--all-cases", a->all_cases,
                "The crane analysis of every load case with a 'crane:' section, one table each (outputs in OUT/CASE)");
  add_set_option(*cmd, a->sets);
  cmd->callback([a, &exit_code] { exit_code = guarded([&] { return run_crane(*a); }); });
}

}  // namespace machdyn::cli
