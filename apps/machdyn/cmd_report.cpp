// `machdyn report MODEL [-o FILE.html] [--case NAME | --all-cases] [--set NAME.FIELD=VALUE ...] [--quiet]`:
// simulate, compute the modes, and write one self-contained HTML report (io/report.hpp) that opens
// offline. With --all-cases every load case of the file gets its own section, and one table compares
// the peak link loads and dynamic factors of all cases.
#include <deque>
#include <filesystem>
#include <iostream>
#include <optional>
#include <fmt/format.h>

#include "commands.hpp"
#include "progress.hpp"
#include "machdyn/analysis/energy.hpp"
#include "machdyn/elements/modes.hpp"
#include "machdyn/analysis/machine_outputs.hpp"
#include "machdyn/analysis/linear_analysis.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/duty_figures.hpp"
#include "machdyn/io/report.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/io/output_file.hpp"
#include "machdyn/model/cases.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn::cli {

namespace {

struct ReportArgs {
  std::string model;
  std::string out;    ///< the HTML file (default out/MODEL/report.html)
  bool quiet = false;
  std::vector<std::string> sets;
  std::string duty;        ///< --duty DUTY: a duty section (io/duty_figures.hpp)
  std::string load_case;   ///< --case
  bool all_cases = false;  ///< --all-cases
  bool large_output = false;  ///< --large-output: embed series above the size limit
  bool check = false;         ///< --check: the invariant audit (analysis/audit.hpp)
  std::string command_line;
};

/// The `description:` of case `name` in the file, or "".
std::string case_description(const SpecNode& root, const std::string& name) {
  const SpecNode* cases = root.is_map() ? root.find("cases") : nullptr;
  const SpecNode* c = cases && cases->is_map() ? cases->find(name) : nullptr;
  const SpecNode* d = c && c->is_map() ? c->find("description") : nullptr;
  return d && d->is_scalar() ? d->scalar : std::string();
}

/// Everything one case of the report holds (kept alive while the document is built).
struct CaseRun {
  std::string name, description;
  Model model;
  SimulationResult result;
  Modes modes;
  std::optional<EnergyResult> energy;
  std::vector<TopologyModes> topologies;  ///< of each topology the run passed through
  std::unique_ptr<FrequencyResponse> frf;
  std::string frf_topology;
  std::optional<CraneReport> crane;  ///< the crane analysis of a model with `crane:`
};

int run_report(const ReportArgs& a) {
  if (!report::assets_available())
    throw std::runtime_error("this machdyn was built without the report's charting library (MACHDYN_REPORT=OFF)");
  if (a.all_cases && !a.load_case.empty()) throw InputError(Location{"--case", 0, 0}, "give either --case NAME or --all-cases");
  // Compile every case first, so bad input stops before anything runs or is written.
  std::vector<std::string> names;
  if (a.all_cases) {
    const SpecNode root = read_yaml_file(a.model);
    names = case_names(root);
    if (names.empty()) throw InputError(Location{a.model, 0, 0}, "--all-cases: the model file has no 'cases:'");
  } else {
    names.push_back(a.load_case);  // "" = the model as written
  }
  const SpecNode root = names.size() > 1 || !names[0].empty() ? read_yaml_file(a.model) : SpecNode{};
  std::deque<CaseRun> runs;  // stable addresses for report::Case
  for (const auto& name : names)
    runs.push_back(CaseRun{name, name.empty() ? "" : case_description(root, name), load_model_case(a.model, a.sets, name),
                           {}, {}, std::nullopt, {}, {}, {}, std::nullopt});
  // One convention with simulate: out/MODEL/report.html, for one case out/MODEL/CASE/report.html.
  // Never over an input file or a device (io/output_file.hpp): said now, not after the runs.
  const std::string out = a.out.empty() ? (output_dir(a.model, "", a.load_case) / "report.html").string() : a.out;
  if (const std::string problem = output_target_problem(out); !problem.empty())
    throw InputError(Location{a.out.empty() ? out : "-o " + out, 0, 0}, "refusing to write the report here: " + problem);
  // A duty (--duty): run first, so that a bad duty file stops before the report's own runs.
  std::optional<DutyResult> duty;
  if (!a.duty.empty()) duty = run_duty(a.model, a.duty, a.sets);
  // The report embeds every series: the same size limit as simulate's time series, before any run.
  if (!a.large_output) {
    std::uint64_t total = 0;
    for (const auto& run : runs) total += estimate_timeseries(run.model).csv_bytes;
    if (total > kDefaultOutputLimitBytes)
      throw InputError(Location{a.model, 0, 0},
                       fmt::format("the report would embed about {} of time series, more than the limit of {}; raise "
                                   "simulation.dt_out or pass --large-output",
                                   byte_size_text(total), byte_size_text(kDefaultOutputLimitBytes)));
  }
  for (auto& run : runs) {
    ProgressBar bar(a.quiet);
    SimulateOptions options;
    options.progress = bar.callback();
    options.event_driven = a.all_cases;  // every case alike, as `simulate --all-cases`
    options.check = a.check;
    run.result = simulate(run.model, options);
    bar.clear();
    run.modes = compute_modes(run.model);
    run.energy = machine_energy(run.model);
    run.topologies = run_topology_modes(run.model, run.result.hybrid, run.model.simulation.t_end);
    run.frf = default_frequency_response(run.model, run.topologies, &run.frf_topology);
    if (run.model.crane.given) run.crane = crane_analysis(run.model);
  }
  std::vector<report::Case> cases;
  for (const auto& run : runs) {
    report::Case c;
    c.name = run.name, c.description = run.description;
    c.model = &run.model, c.result = &run.result, c.modes = &run.modes;
    c.energy = run.energy ? &*run.energy : nullptr;
    c.topologies = &run.topologies;
    c.frf = run.frf.get(), c.frf_topology = run.frf_topology;
    c.crane = run.crane ? &*run.crane : nullptr;
    cases.push_back(c);
  }
  report::Document doc = report::simulation_report(cases, a.command_line);
  if (duty) doc.sections.push_back(duty_report_section(*duty));
  const std::string html = report::to_html(doc);
  write_file_atomic(out, html);
  std::cout << fmt::format("wrote {} ({:.1f} kB{}); open it in any browser, it needs no network\n", out,
                           static_cast<double>(html.size()) / 1e3,
                           names.size() > 1 ? fmt::format(", {} cases", names.size()) : "");
  return 0;
}

}  // namespace

void register_report(CLI::App& app, int& exit_code) {
  auto args = std::make_shared<ReportArgs>();
  auto* cmd = app.add_subcommand("report",
                                 "One self-contained HTML report: model tables, run settings, results, interactive plots");
  cmd->add_option("MODEL", args->model, "Model file (YAML)")->required();
  cmd->add_option("-o,--out", args->out, "The HTML file to write (default out/MODEL/report.html)");
  cmd->add_flag("-q,--quiet", args->quiet, "No progress bar on stderr");
  cmd->add_flag("--large-output", args->large_output, "Embed the time series even when they would exceed 1 GB");
  cmd->add_option("--case", args->load_case, "Report one load case of the file's 'cases:'");
  cmd->add_flag("--all-cases", args->all_cases,
                "Report every load case: a section each, and one table comparing peak link loads and dynamic factors");
  cmd->add_option("--duty", args->duty, "A duty file: add its section (cycles, k_m and classes, exceedance diagrams; docs/duty.md)");
  cmd->add_flag("--check", args->check,
                "Audit every run against the documented laws, as `simulate --check` (exit 3 on a violation)");
  add_set_option(*cmd, args->sets);
  cmd->callback([args, &exit_code] {
    exit_code = guarded([&] {
      args->command_line = "machdyn report " + std::filesystem::path(args->model).filename().string();
      if (!args->load_case.empty()) args->command_line += " --case " + args->load_case;
      if (args->all_cases) args->command_line += " --all-cases";
      if (!args->duty.empty()) args->command_line += " --duty " + std::filesystem::path(args->duty).filename().string();
      for (const auto& s : args->sets) args->command_line += " --set " + s;
      return run_report(*args);
    });
  });
}

}  // namespace machdyn::cli
