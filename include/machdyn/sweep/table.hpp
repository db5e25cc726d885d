#pragma once
/// @file
/// The sweep table: one CSV row per run,
///   run, [case], <one column per --vary, SI>, <summary columns>, status, message
/// Numbers are written with `%.17g` (exact round trip), NaN as `nan`; an error row leaves the
/// summary columns empty. The row of a run depends only on the plan and the run, never on the
/// thread or rank that computed it, so tables are byte-identical whatever the parallelism.
///
/// Summary columns come in groups (SummaryColumns). The standard groups are the link peaks
/// (`L.max_U`, `L.min_U`, `L.t_max_s`, `L.static_U`, `L.dynamic_factor` for every link L, U its load
/// unit `N_m` or `N`) and the solver statistics (`steps`, `rejected_steps`, `rhs_evals`). Later
/// analyses (event counts, self-oscillation period) add a group: a header function over the base
/// model and a value function over one run's model and result.

#include <functional>
#include <string>
#include <vector>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/model/model.hpp"
#include "machdyn/sweep/plan.hpp"

namespace machdyn {

/// One group of summary columns: the extension point for new per-run figures.
struct SummaryColumns {
  /// Column names, from the base model (every run of a sweep has the same bodies and links).
  std::function<std::vector<std::string>(const Model& base)> header;
  /// The values of one run, as many as header() gave; NaN is written `nan`.
  std::function<void(const Model& run_model, const SimulationResult& result, std::vector<double>& values)> values;
};

/// The link peaks, then the solver statistics.
std::vector<SummaryColumns> standard_summary_columns();

/// The table's header line (no newline).
std::string sweep_header(const SweepPlan& plan, const std::vector<SummaryColumns>& columns);

/// Runs one point of the sweep: run_spec → compile → simulate → summary, and returns its CSV row
/// (no newline). Never throws for a failing run: an InputError (a value the field rejects),
/// SolverError or any other exception gives status `error` and its message.
std::string execute_run(const SweepPlan& plan, const SweepRun& run, const std::vector<SummaryColumns>& columns);

/// Quotes a CSV field when it holds a comma, quote or space at an end; newlines become spaces.
std::string csv_field(const std::string& text);

/// Splits one CSV line written by this module (quoted fields allowed) into fields.
std::vector<std::string> split_csv_line(const std::string& line);

}  // namespace machdyn
