#pragma once
/// @file
/// The summary values of every spatial rope in one run (summary.json `sway`, SimulationResult::sway;
/// elements/spatial_rope.hpp, docs/sway.md), taken during the run from each row of its output grid
/// (SwayObserver: no time series needed or kept):
///   largest sway   max over the rows of |θ| over the rope's sway outputs (x, y; radial, tangential
///                  with a jib), rad, and its time (the earliest row that reaches it)
///   residual sway  the same over the rows at t ≥ t_r (the rope's `sway_after`: the end of a move) —
///                  the residual amplitude, rad
///   horizontal     the largest horizontal force on the suspension point, N, and its time; the
///                  largest tension, N
///   dynamic factor the horizontal force's peak over the force of rigid acceleration m a of the load
///                  (EN 13001-2's φ5 for drive forces), a the largest horizontal acceleration of the
///                  suspension point's travel (trolley and bridge; from their velocities' differences
///                  between consecutive rows, |Δv|/Δt); absent for a rope without a trolley or bridge,
///                  with a jib, or when the suspension point never accelerates
#include <optional>
#include <string>
#include <vector>

#include "machdyn/model/model.hpp"

namespace machdyn {

class DriveSystem;
class SpatialRope;
struct SimulationResult;

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

/// The run's observer of the sway summary: one call per output row, in time order, with the state
/// the row is written from; the summaries at the end. Holds a few numbers per rope, never a series.
class SwayObserver {
 public:
  /// The spatial ropes of `m` (model order); none: empty().
  explicit SwayObserver(const Model& m);
  [[nodiscard]] bool empty() const { return ropes_.empty(); }
  /// The row at t of the state y (positions, then velocities, then the elements' states) of the run's
  /// drive system `sys`, whose elements are `m`'s drives.
  void row(const DriveSystem& sys, double t, const double* y);
  /// One entry per spatial rope (model order).
  [[nodiscard]] std::vector<SwaySummary> summaries() const;

 private:
  struct Rope {
    int drive = 0;                  ///< its index in Model::drives
    const SpatialRope* law = nullptr;
    std::vector<int> sway;          ///< the sway angles' places in its outputs
    int horizontal = 0;             ///< the horizontal force's place
    std::vector<int> travel;        ///< the velocity states (y index) of its trolley and bridge (no jib)
    std::vector<double> v_prev;     ///< their velocities at the previous row
    double t_prev = 0.0;
    bool started = false;           ///< a previous row exists
    double a_max = 0.0;             ///< the largest horizontal acceleration so far, m/s²
    SwaySummary s;
  };
  std::vector<Rope> ropes_;
  std::vector<double> out_;  ///< one rope's outputs
};

/// The names of the ropes SimulationResult::sway reports on for a run of `m`, in its order (known before
/// the run: a sweep's table columns).
std::vector<std::string> sway_rope_names(const Model& m);

}  // namespace machdyn
