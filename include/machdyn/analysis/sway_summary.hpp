#pragma once
/// @file
/// The summary values of every spatial rope in one run (summary.json `sway`; elements/spatial_rope.hpp,
/// docs/sway.md), read from the run's output columns:
///   largest sway   max over the rows of |θ| over the rope's sway columns (x, y; radial, tangential
///                  with a jib), rad, and its time
///   residual sway  the same over the rows at t ≥ t_r (the rope's `sway_after`: the end of a move) —
///                  the residual amplitude, rad
///   horizontal     the largest horizontal force on the suspension point, N, and its time; the
///                  largest tension, N
///   dynamic factor the horizontal force's peak over the force of rigid acceleration m a of the load
///                  (EN 13001-2's φ5 for drive forces), a the largest horizontal acceleration of the
///                  suspension point's travel (trolley and bridge; from their velocity columns'
///                  differences between rows); absent for a rope without a trolley or bridge, with a
///                  jib, or when the suspension point never accelerates
#include <optional>
#include <string>
#include <vector>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

struct SwaySummary {
  std::string rope;                          ///< the rope's name
  double max_sway_rad = 0.0, t_max_sway = 0.0;
  std::optional<double> residual_after;      ///< t_r, s (the rope's `sway_after`)
  double residual_sway_rad = 0.0;            ///< max |θ| at t ≥ t_r
  double max_horizontal_force_N = 0.0, t_max_horizontal_force = 0.0;
  double max_tension_N = 0.0;
  std::optional<double> rigid_force_N;       ///< m a
  std::optional<double> dynamic_factor;      ///< max horizontal force / (m a)
};

/// One entry per spatial rope of `m` (model order) for the run `r` of `m`; empty without one. Needs
/// the run's time series.
std::vector<SwaySummary> sway_summaries(const Model& m, const SimulationResult& r);

/// The names of the ropes sway_summaries() reports on for a run of `m`, in its order (known before
/// the run: a sweep's table columns).
std::vector<std::string> sway_rope_names(const Model& m);

}  // namespace machdyn
