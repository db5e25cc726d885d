#pragma once
/// @file
/// The stop of every brake in one run (summary.json `brakes`, the `simulate` printout, the report's
/// table, Python's `r.summary["brakes"]`), read from the run's events and its output columns:
///   applied  t_a: the first application that meets its body moving (its event from `released` into
///            slip±, or its initial mode slip± when applied from t = 0); without one, the first time
///            it is applied (to a body at rest, which it holds: a stop of 0 s)
///   stopped  t_s: its next event into `stuck` (the braked body at rest against its housing)
///   stopping time t_s − t_a; the travel from t_a to t_s of the braked body and of every translational
///            body joined to it by links, lossy gears or contacts (the load: a hoist's hook), rad or m
///   energy   E = ∫ |F u| dt over the run (F the brake's force, u its sliding speed: the heat it takes), J
///   peak power max |F u|, W, and its time
///   temperature (a brake with a thermal model, elements/thermal.hpp): its largest value, its time and
///            the value at t_end, °C
/// On the output grid: the power by the trapezoid rule on the rows, with the pieces cut at the brake's
/// own events — at t_s the power is 0 (u = 0), at t_a it jumps to |F(t_a⁺)| |u(t_a)|, F the first row's
/// force after t_a; positions and speeds at an event are extended from the rows before it
/// (q + v τ + ½ a τ², a from the last two rows), because the motion is smooth up to the event. So a
/// stop under a constant force from a uniform motion (u linear in t) is exact; otherwise the error is
/// O(dt_out²). A brake that does not stop its body before t_end has `stopped` false and its travel up
/// to t_end; one never applied has no stop (only its energy, 0, and temperature).
#include <optional>
#include <string>
#include <vector>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

struct BrakeStop {
  std::string brake;                ///< the brake's name
  std::string unit;                 ///< of its force: N·m or N
  std::optional<double> t_applied;  ///< t_a, s (none: never applied in the run)
  std::optional<double> t_stopped;  ///< t_s, s (none: not at rest by t_end)
  std::optional<double> stopping_time;  ///< t_s − t_a, s
  struct Travel {
    std::string body, unit;
    double value = 0.0;             ///< q(t_s) − q(t_a) (q(t_end) − q(t_a) without a stop), rad or m
  };
  std::vector<Travel> travel;       ///< the braked body first, then the translational bodies joined to it
  double energy_J = 0.0;            ///< ∫ |F u| dt over the run
  double peak_power_W = 0.0;
  double t_peak_power = 0.0;        ///< s
  bool thermal = false;             ///< the temperatures below are set
  double temperature_max_degC = 0.0, t_temperature_max = 0.0, temperature_end_degC = 0.0;
};

/// One entry per brake of `m` (model order) for the run `r` of `m` (see above). Empty without brakes.
/// Needs the run's time series (SimulateOptions::time_series) and its events (models with a brake
/// always keep them).
std::vector<BrakeStop> brake_stops(const Model& m, const SimulationResult& r);

}  // namespace machdyn
