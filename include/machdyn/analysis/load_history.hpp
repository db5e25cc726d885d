#pragma once
/// @file
/// The load history of a run for cycle counting: the link loads on the continuous solution, with
/// their turning points located exactly (not read off the output grid, which loses the peaks
/// between rows), counted by rainflow (analysis/rainflow.hpp) while the run goes on.
///
/// The values handed out are those the peak tracker takes (analysis/peak_tracker.hpp): for every
/// driver piece, its start when the piece starts afresh (the run's start, after each event, where a
/// load may jump), every interior extremum — where the load's rate changes sign between the piece's
/// ends, located by the Illinois method on the dense output — and the piece's end. That is a superset
/// of the load's turning points in time order; the counter's turning-point extraction keeps the
/// reversals. Like the peaks, an extremum pair inside one step (rate of the same sign at both ends)
/// is not seen; the steps of an oscillating load are much shorter than its half period.

#include <functional>
#include <string>
#include <vector>

#include "machdyn/analysis/rainflow.hpp"
#include "machdyn/analysis/simulate.hpp"

namespace machdyn {

/// Receives every value of link `link` (Model::links order) at time t, in time order per link.
using LinkValueSink = std::function<void(int link, double t, double value)>;

/// simulate(m, options) that also hands every value the link loads take to `link_values` (above).
SimulationResult simulate(const Model& m, const SimulateOptions& options, const LinkValueSink& link_values);

/// The rainflow cycles of one link load over a run.
struct LinkCycles {
  std::string link;                   ///< the link's name
  std::vector<RainflowCycle> cycles;  ///< in the order counted (N·m or N)
  std::size_t turning_points = 0;     ///< after the gate
  std::size_t max_held = 0;           ///< the counter's memory, turning points
};

/// What to count: the links by index (empty: all), the gate h per link in the load's unit (empty:
/// 0 for all; a single value: for all) and the residue rule.
struct LinkCycleOptions {
  std::vector<int> links;
  std::vector<double> gates;
  RainflowResidue residue = RainflowResidue::half_cycles;
};

/// Runs the model once and counts the chosen link loads over their located turning points (over
/// [options.extremes_from, t_end]). Throws std::invalid_argument on a link index out of range or a
/// gate list of the wrong length.
std::vector<LinkCycles> count_link_cycles(const Model& m, const SimulateOptions& options,
                                          const LinkCycleOptions& count, SimulationResult* result = nullptr);

/// The chosen link loads of one run as parts of a longer history (rainflow_part: whole cycles by the
/// four-point rule, and the residue), to be merged with other runs' parts by merge_parts — the
/// operations of a duty cycle. `count.residue` is not used (merge_parts takes the rule).
std::vector<RainflowPart> link_parts(const Model& m, const SimulateOptions& options, const LinkCycleOptions& count,
                                     SimulationResult* result = nullptr);

}  // namespace machdyn
