#pragma once
/// @file
/// The stops of every brake in one run (summary.json `brakes`, the `simulate` printout, the report's
/// table, Python's `r.brakes`), read from the run's events and its output columns. A brake's run is
/// cut into stops, each reported on its own:
///   a stop   starts where the applied brake begins to slide (its event into slip± from `released`:
///            applied to its body moving; from `stuck`: its holding level overcome; or its initial mode
///            slip±) at t_a, and ends at its next event into `stuck` (the body at rest against its
///            housing: stopped, stopping time t_e − t_a) or into `released` (lifted while sliding), or
///            at t_end (still sliding). A brake that never slides but is applied in the run (to a body
///            at rest, which it holds) has one stop of 0 s at its first application.
///   per stop the travel from t_a to t_e of the braked body and of every translational body joined to
///            it by links, lossy gears or contacts (the load: a hoist's hook), rad or m; the energy
///            ∫ |F u| dt over [t_a, t_e] (F the brake's force, u its sliding speed: the heat it takes),
///            J; the peak power max |F u| in it and its time; with a thermal model the temperatures at
///            t_a and t_e and the rise between them
///   per run  the energy over the whole run, its peak power, and the largest and the last temperature
/// On the output grid: the power by the trapezoid rule on the rows, with the pieces cut at each of the
/// brake's events — on each side of an event the power is |F| |u(t)| of the mode on that side (0 stuck
/// or released), F the nearest row's force on that side; positions, speeds and temperatures at an
/// event are extended from the rows before it (a polynomial through up to three rows after the
/// previous event: q + v τ + ½ a τ² for positions), because the motion is smooth up to the event. So a
/// stop under a constant force from a uniform motion (u linear in t) is exact; otherwise the error is
/// O(dt_out²).
#include <optional>
#include <string>
#include <vector>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// One stop of a brake (above).
struct BrakeStop {
  enum class Start { applied, overcome, initial };  ///< from released, from stuck, sliding at t = 0
  enum class End { stuck, released, run_end };
  Start start = Start::applied;
  double t_applied = 0.0;               ///< t_a, s
  double t_end = 0.0;                   ///< t_e, s: the event into stuck or released, or t_end
  End end = End::run_end;
  std::optional<double> stopping_time;  ///< t_e − t_a when it ended stuck, s
  struct Travel {
    std::string body, unit;
    double value = 0.0;                 ///< q(t_e) − q(t_a), rad or m
  };
  std::vector<Travel> travel;           ///< the braked body first, then the translational bodies joined to it
  double energy_J = 0.0;                ///< ∫ |F u| dt over [t_a, t_e]
  double peak_power_W = 0.0;
  double t_peak_power = 0.0;            ///< s
  double temperature_applied_degC = 0.0, temperature_end_degC = 0.0;  ///< at t_a and t_e (thermal only)
};

/// The words of a stop's start and end in the outputs: applied, overcome, initial; stuck, released,
/// t_end.
const char* start_name(BrakeStop::Start s);
const char* end_name(BrakeStop::End e);

/// Every stop of one brake in a run, and the run's totals.
struct BrakeSummary {
  std::string brake;               ///< the brake's name
  std::string unit;                ///< of its force: N·m or N
  std::vector<BrakeStop> stops;    ///< in time order; empty: never applied in the run
  double energy_J = 0.0;           ///< ∫ |F u| dt over the run
  double peak_power_W = 0.0;
  double t_peak_power = 0.0;       ///< s
  bool thermal = false;            ///< the temperatures are set (the stops' too)
  double temperature_max_degC = 0.0, t_temperature_max = 0.0, temperature_end_degC = 0.0;
};

/// One entry per brake of `m` (model order) for the run `r` of `m` (see above). Empty without brakes.
/// Needs the run's time series (SimulateOptions::time_series) and its events (models with a brake
/// always keep them).
std::vector<BrakeSummary> brake_summaries(const Model& m, const SimulationResult& r);

}  // namespace machdyn
