// `machdyn report MODEL [-o FILE.html] [--set NAME.FIELD=VALUE ...] [--quiet]`: simulate, compute the
// modes, and write one self-contained HTML report (io/report.hpp) that opens offline.
#include <filesystem>
#include <iostream>
#include <fmt/format.h>

#include "commands.hpp"
#include "progress.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/report.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn::cli {

namespace {

struct ReportArgs {
  std::string model;
  std::string out;    ///< the HTML file (default out/MODEL/report.html)
  bool quiet = false;
  std::vector<std::string> sets;
  std::string command_line;
};

int run_report(const ReportArgs& a) {
  if (!report::assets_available())
    throw std::runtime_error("this machdyn was built without the report's charting library (MACHDYN_REPORT=OFF)");
  // One case today: the model as written, with --set. Issue 3's --case NAME / --all-cases adds a
  // loop here that fills `cases` with one entry per case (name, model, result, modes).
  const Model m = load_model(a.model, a.sets);
  ProgressBar bar(a.quiet);
  SimulateOptions options;
  options.progress = bar.callback();
  const SimulationResult r = simulate(m, options);
  bar.clear();
  const Modes modes = compute_modes(m);
  report::Case run;
  run.model = &m, run.result = &r, run.modes = &modes;
  const std::vector<report::Case> cases{run};
  const std::string html = report::to_html(report::simulation_report(cases, a.command_line));
  const std::string out = a.out.empty() ? (default_out_dir(a.model) / "report.html").string() : a.out;
  write_file_atomic(out, html);
  std::cout << fmt::format("wrote {} ({:.1f} kB); open it in any browser, it needs no network\n", out,
                           static_cast<double>(html.size()) / 1e3);
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
  add_set_option(*cmd, args->sets);
  cmd->callback([args, &exit_code] {
    exit_code = guarded([&] {
      args->command_line = "machdyn report " + std::filesystem::path(args->model).filename().string();
      for (const auto& s : args->sets) args->command_line += " --set " + s;
      return run_report(*args);
    });
  });
}

}  // namespace machdyn::cli
