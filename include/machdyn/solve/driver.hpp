#pragma once
/// @file
/// The one driver loop of every simulation: drives a Stepper from t0 to t_end over an EventSystem
/// (solve/event_system.hpp). It never steps across a breakpoint; after each step it looks for
/// event functions that went from ≥ 0 to < 0, locates the earliest crossing on the dense output
/// (Illinois, solve/roots.hpp), truncates the step there, lets the system decide its modes and map
/// the state, and restarts the stepper. Observers see the solution piece by piece (each piece lies
/// in one mode), the output grid and the events; they never see the solution beyond an event.
/// Statistics are summed over the whole run; StepperOptions::max_steps bounds the whole run.

#include <string>
#include <vector>

#include "machdyn/solve/event_system.hpp"
#include "machdyn/solve/stepper.hpp"

namespace machdyn {

class StepObserver {
 public:
  virtual ~StepObserver() = default;
  /// After each accepted step, before events in it are looked for (progress reports).
  virtual void on_step(const Stepper& /*stepper*/) {}
  /// The solution on [ta, tb] ⊂ [stepper.t_prev(), stepper.t()] belongs to the current modes (the
  /// whole step, or its part up to an event). Consecutive pieces of one mode share their ends:
  /// tb of one piece is ta of the next unless an event or breakpoint lies between.
  virtual void on_segment(const Stepper& /*stepper*/, double /*ta*/, double /*tb*/) {}
  /// At each output time t_k = t0 + k·dt_out (and t_end), with the state there. An output time at
  /// an event gets the state before it.
  virtual void on_output(double t, const double* y) = 0;
  /// After the system handled an event or a breakpoint at t (`fired` empty), before the stepper
  /// restarts: y is the state after it. The next piece starts a new mode.
  virtual void on_event(double /*t*/, const double* /*y*/, const std::vector<int>& /*fired*/) {}
};

struct RunStats {
  StepperStats stepper;  ///< summed over every restart of the run
  long events = 0;       ///< located events (not breakpoints)
  std::string method;
  double wall_time_s = 0.0;
};

struct DriveOptions {
  double dt_out = 0.0;       ///< output grid step, s (> 0)
  bool outputs = true;       ///< false: on_output is never called (summaries only)
  double event_tol = 1e-13;  ///< final bracket of an event time, relative to max(1, |t|)
};

/// Integrates `system` (the one the stepper was made for) from (t0, y0) to t_end. Throws
/// SolverError from the stepper.
RunStats integrate(Stepper& stepper, EventSystem& system, double t0, const double* y0, double t_end,
                   const DriveOptions& options, StepObserver& observer);

}  // namespace machdyn
