#pragma once
/// @file
/// Figures of a hybrid run for tables (sweeps) and summaries: how many mode events of each kind,
/// and per friction contact (or brake) the number of slips, the self-oscillation period and the
/// peak link loads over the contact's static limit (F_max / F_sc of paper 001). The same
/// definitions as the `contacts` block of `summary.json` (io/results.hpp).

#include <string>
#include <vector>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// The kinds of ModeEvent counted (all but `initial`), in table order:
/// gap_closed, gap_opened, stick, slip, reversal.
const std::vector<std::string>& counted_event_kinds();

/// Number of events of each kind of counted_event_kinds() in the run (`initial` entries excluded).
std::vector<long> event_counts(const HybridReport& h);

struct ContactStatistics {
  std::string name;
  /// Slip phases that start in the run (each phase is one direction of sliding; a reversal starts
  /// a new phase).
  long slips = 0;
  /// Self-oscillation period, s: the mean interval between the starts of the slips in the second
  /// half of the run (t ≥ t_end/2, after the start-up); NaN with fewer than two such slips.
  double period_s = 0.0;
  /// Per link (Model::links order): its largest load over the run / the contact's static limit F_s0;
  /// NaN when the two have different units (a link force in N and a brake torque in N·m).
  std::vector<double> link_max_over_static_limit;
};

/// One entry per friction contact or brake of Model::contacts (gear joints left out), in that order.
std::vector<ContactStatistics> contact_statistics(const Model& m, const SimulationResult& r);

}  // namespace machdyn
