// `machdyn report MODEL [-o FILE.html] [--case NAME | --all-cases] [--links A,B] [--frf-input NAME]
// [--frf-output NAME ...] [--frf-band LO:HI] [--set NAME.FIELD=VALUE ...] [--quiet]`:
// simulate, compute the modes, and write one self-contained HTML report (io/report.hpp) that opens
// offline. With --all-cases every load case of the file gets its own section, and one table compares
// the peak link loads and dynamic factors of all cases.
#include <cstdlib>
#include <deque>
#include <filesystem>
#include <iostream>
#include <optional>
#include <fmt/format.h>
#include <fmt/ranges.h>

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
#include "machdyn/io/report_run.hpp"
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
  FrfChoice frf;              ///< --frf-input, --frf-output, --frf-band
  std::string frf_band;       ///< --frf-band LO:HI (Hz)
  std::vector<std::string> links;  ///< --links
  std::string command_line;
};

/// The `description:` of case `name` in the file, or "".
std::string case_description(const SpecNode& root, const std::string& name) {
  const SpecNode* cases = root.is_map() ? root.find("cases") : nullptr;
  const SpecNode* c = cases && cases->is_map() ? cases->find(name) : nullptr;
  const SpecNode* d = c && c->is_map() ? c->find("description") : nullptr;
  return d && d->is_scalar() ? d->scalar : std::string();
}

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
  std::deque<report::ReportRun> runs;  // stable addresses for report::Case
  for (const auto& name : names) {
    runs.emplace_back();
    runs.back().name = name, runs.back().description = name.empty() ? "" : case_description(root, name);
    runs.back().model = load_model_case(a.model, a.sets, name);
  }
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
  report::ReportOptions options;
  options.simulate.event_driven = a.all_cases;  // every case alike, as `simulate --all-cases`
  options.simulate.check = a.check;
  options.frf = a.frf;
  options.links = a.links;
  for (const auto& run : runs) report::check_report_choices(run.model, options);
  for (auto& run : runs) {
    ProgressBar bar(a.quiet);
    options.simulate.progress = bar.callback();
    report::run_report_case(run, options);
    bar.clear();
  }
  std::vector<report::Case> cases;
  for (const auto& run : runs) cases.push_back(run.as_case());
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
  cmd->add_option("--links", args->links,
                  "The links whose loads are drawn (names, comma-separated; default: all, in panels by unit and size)")
      ->delimiter(',');
  cmd->add_option("--frf-input", args->frf.input,
                  "The frequency response's input: a load or a body (default: the drive — the first motor or drive)");
  cmd->add_option("--frf-output", args->frf.outputs,
                  "Its outputs: LINK.load, BODY.position or BODY.speed (repeatable or comma-separated; default: every link load)")
      ->delimiter(',');
  cmd->add_option("--frf-band", args->frf_band,
                  "Its band LO:HI in Hz (default: 0.1 x the lowest mode to 2 x the highest resonance the outputs show)");
  add_set_option(*cmd, args->sets);
  cmd->callback([args, &exit_code] {
    exit_code = guarded([&] {
      if (!args->frf_band.empty()) {
        const auto colon = args->frf_band.find(':');
        char* end = nullptr;
        const std::string lo = args->frf_band.substr(0, colon), hi = colon == std::string::npos ? "" : args->frf_band.substr(colon + 1);
        args->frf.f_lo_hz = std::strtod(lo.c_str(), &end);
        const bool lo_ok = !lo.empty() && *end == '\0';
        args->frf.f_hi_hz = std::strtod(hi.c_str(), &end);
        if (!lo_ok || hi.empty() || *end != '\0' || !(args->frf.f_lo_hz > 0.0 && args->frf.f_hi_hz > args->frf.f_lo_hz))
          throw InputError(Location{"--frf-band", 0, 0},
                           fmt::format("expected LO:HI in Hz with 0 < LO < HI, e.g. 0.1:20; got '{}'", args->frf_band));
      }
      args->command_line = "machdyn report " + std::filesystem::path(args->model).filename().string();
      if (!args->load_case.empty()) args->command_line += " --case " + args->load_case;
      if (args->all_cases) args->command_line += " --all-cases";
      if (!args->duty.empty()) args->command_line += " --duty " + std::filesystem::path(args->duty).filename().string();
      for (const auto& s : args->sets) args->command_line += " --set " + s;
      if (!args->links.empty()) args->command_line += " --links " + fmt::format("{}", fmt::join(args->links, ","));
      if (!args->frf.input.empty()) args->command_line += " --frf-input " + args->frf.input;
      for (const auto& o : args->frf.outputs) args->command_line += " --frf-output " + o;
      if (!args->frf_band.empty()) args->command_line += " --frf-band " + args->frf_band;
      return run_report(*args);
    });
  });
}

}  // namespace machdyn::cli
