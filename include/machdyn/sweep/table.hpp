#pragma once
/// @file
/// The sweep table: one CSV row per run,
///   run, [case], <one column per --vary, SI>, <summary columns>, status, message
/// Numbers are written with `%.17g` (exact round trip), NaN as `nan`; an error row leaves the
/// summary columns empty. The row of a run depends only on the plan and the run, never on the
/// thread or rank that computed it, so tables are byte-identical whatever the parallelism.
///
/// Summary columns come in groups (SummaryColumns). The standard groups are the link peaks
/// (`L.max_U`, `L.min_U`, `L.t_max_s`, `L.static_U` at the peak, `L.dynamic_factor` = peak / static
/// (LinkSummary) for every link L, U its load
/// unit `N_m` or `N`), for event-driven runs (runs_event_driven()) the peaks of larger magnitude
/// (peak_summary_columns()) and the hybrid figures (hybrid_summary_columns()), the sway summary of
/// every spatial rope (sway_summary_columns()), and the solver statistics (`steps`, `rejected_steps`, `rhs_evals`). A new
/// analysis adds a group: a header function over a model and a value function over one run's model
/// and result. The table's columns of a group are the union of its header over the sweep's models
/// (column_models(): the base, or every case); a run fills the columns its own model has and leaves
/// the others empty (e.g. the brake columns of a case without the brake).

#include <functional>
#include <string>
#include <vector>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/model/model.hpp"
#include "machdyn/common/csv.hpp"
#include "machdyn/sweep/plan.hpp"

namespace machdyn {

/// One group of summary columns: the extension point for new per-run figures.
struct SummaryColumns {
  /// Column names for a model (--vary changes no element, so a run has those of its case).
  std::function<std::vector<std::string>(const Model& m)> header;
  /// The values of one run, as many as header(run_model) gave, in its order; NaN is written `nan`.
  std::function<void(const Model& run_model, const SimulationResult& result, std::vector<double>& values)> values;
};

/// The link peaks, the peaks of larger magnitude and the hybrid figures (event-driven runs only),
/// then the solver statistics.
std::vector<SummaryColumns> standard_summary_columns();

/// Whether a run of this model keeps the energy books and event report (SimulateOptions::event_driven): a model with a gap, a contact or
/// a brake, and every run of a case sweep (Model::load_case set), smooth or not, as `simulate
/// --all-cases` runs its cases.
bool runs_event_driven(const Model& m);

/// For event-driven runs, per link L (U its load unit), as the table of `simulate --all-cases`:
/// `L.peak_U` the extreme of larger magnitude (max or min), `L.t_peak_s` its time,
/// `L.peak_static_U` the quasi-static load there and `L.peak_dynamic_factor` their ratio
/// (LinkSummary: the one definition; nan when the static load is ~0). The dynamic factor of
/// a link loaded mostly in the negative direction (hoist mode 6). No columns for a smooth run.
SummaryColumns peak_summary_columns();

/// Figures of an event-driven run (analysis/hybrid_stats.hpp); no columns for a smooth model:
///   `events_K` for K in gap_closed, gap_opened, stick, slip, reversal: events of that kind;
///   per contact or brake C: `C.slips` (slip phases), `C.period_s` (self-oscillation period, the
///   mean interval between slip starts in the second half of the run; nan with fewer than two),
///   and per link L `C.L_max_over_static_limit` (peak load of L / static limit of C: F_max/F_sc).
SummaryColumns hybrid_summary_columns();

/// The sway summary of every spatial rope R (analysis/sway_summary.hpp; summary.json's `sway`, the same
/// numbers: the run's observer of its output rows, SimulationResult::sway): `R.max_sway_rad` (the largest
/// sway angle), `R.residual_sway_rad` (the largest from the rope's `sway_after` on; nan without it),
/// `R.max_horizontal_force_N` (on the suspension point) and `R.horizontal_dynamic_factor` (that peak over
/// m a; nan where summary.json has none: a jib, no travel, no acceleration). Taken during the run: the
/// sweep's runs keep no time series.
SummaryColumns sway_summary_columns();

/// The column names of each group: the union of its header over column_models(plan), first seen first.
std::vector<std::vector<std::string>> summary_column_names(const SweepPlan& plan,
                                                           const std::vector<SummaryColumns>& columns);

/// The table's header line (no newline).
std::string sweep_header(const SweepPlan& plan, const std::vector<SummaryColumns>& columns);

/// Runs one point of the sweep: run_spec → compile → simulate → summary, and returns its CSV row
/// (no newline). Never throws for a failing run: an InputError (a value the field rejects, or the
/// model refused at the start of the run), SolverError or any other exception gives status `error`
/// and its message (on one line: line breaks become spaces, the journal is read line by line).
std::string execute_run(const SweepPlan& plan, const SweepRun& run, const std::vector<SummaryColumns>& columns);
/// The same with the table's column names computed once (summary_column_names), for many runs;
/// `input_error`, when given, is set to whether the run failed on its input (an InputError).
std::string execute_run(const SweepPlan& plan, const SweepRun& run, const std::vector<SummaryColumns>& columns,
                        const std::vector<std::vector<std::string>>& names, bool* input_error = nullptr);

/// Splits one CSV line written by this module (quoted fields allowed) into fields.
std::vector<std::string> split_csv_line(const std::string& line);

}  // namespace machdyn
