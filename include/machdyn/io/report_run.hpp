#pragma once
/// @file
/// One case of a report, run and analysed: the simulation, the modes, the modes of each topology
/// the run passed through, the frequency response (analysis/linear_analysis.hpp FrfChoice), the
/// energy integral of a 1-DOF machine and the crane analysis of a model with `crane:`. The CLI's
/// `machdyn report` and Python's `machdyn.report()` both build their reports from it, so both
/// hold the same sections.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "machdyn/analysis/crane.hpp"
#include "machdyn/analysis/energy.hpp"
#include "machdyn/analysis/frequency_response.hpp"
#include "machdyn/analysis/linear_analysis.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/report.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::report {

/// The choices of a report beside the model: the simulation's options (progress, event-driven,
/// audit), the frequency response's input, outputs and band, and the links drawn (`--links`).
struct ReportOptions {
  SimulateOptions simulate;
  FrfChoice frf;
  std::vector<std::string> links;  ///< empty: every link, in panels (io/figures.hpp link_load_groups)
  std::string links_option = "--links";  ///< where `links` was written, for its errors (`links=` in Python)
};

/// Everything one case of a report holds; kept alive while the document is built (as_case() points
/// into it, so keep it at a stable address: a std::deque or a local).
struct ReportRun {
  std::string name, description;
  Model model;
  SimulationResult result;
  Modes modes;
  std::optional<EnergyResult> energy;
  std::vector<TopologyModes> topologies;
  std::unique_ptr<FrequencyResponse> frf;
  std::string frf_topology;
  std::optional<CraneReport> crane;
  std::vector<std::string> links;

  /// The report::Case of this run (pointers into *this).
  [[nodiscard]] Case as_case() const;
};

/// Checks the names in opt (links, the frequency response's input) against `m`: an InputError
/// naming the option and the known names. run_report_case calls it first; a caller with several
/// cases calls it for each before the first run.
void check_report_choices(const Model& m, const ReportOptions& opt);

/// Runs and analyses run.model (name and description as given) with `opt`. A name in opt.frf or
/// opt.links that the model does not have is an InputError before the simulation runs.
void run_report_case(ReportRun& run, const ReportOptions& opt);

}  // namespace machdyn::report
