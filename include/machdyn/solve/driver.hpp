#pragma once
/// @file
/// Drives a Stepper from t0 to t_end: after each accepted step the observer sees the step (for
/// peaks or events on the dense output) and every output time inside it.

#include <string>

#include "machdyn/solve/stepper.hpp"

namespace machdyn {

class StepObserver {
 public:
  virtual ~StepObserver() = default;
  /// After each accepted step [stepper.t_prev(), stepper.t()].
  virtual void on_step(const Stepper& /*stepper*/) {}
  /// At each output time t_k = t0 + k·dt_out (and t_end), with the state there.
  virtual void on_output(double t, const double* y) = 0;
};

/// State jumps at events (the speed jump of a stepwise gear at a sector boundary). The driver
/// asks after every step whether an event lies inside it; if so it integrates that stretch again up
/// to the event time exactly (so observers never see the solution beyond an event), applies the
/// jump and restarts the stepper there.
class StepEvents {
 public:
  virtual ~StepEvents() = default;
  /// Prepares the events ahead of the state (t, y), after the start and after every jump.
  virtual void arm(double t, const double* y) = 0;
  /// The first event time in (t_prev, t] of the stepper's last step, or NaN if there is none.
  virtual double locate(const Stepper& stepper) = 0;
  /// Maps the state just before the event at t to the state just after, in place.
  virtual void apply(double t, double* y) = 0;
};

struct RunStats {
  StepperStats stepper;
  std::string method;
  double wall_time_s = 0.0;
};

/// Integrates from (t0, y0) to t_end. Outputs are interpolated, so dt_out does not limit steps.
/// Throws SolverError from the stepper.
RunStats integrate(Stepper& stepper, double t0, const double* y0, double t_end, double dt_out,
                   StepObserver& observer);
/// The same with state jumps at events (null: none). Output times at an event get the state
/// before the jump.
RunStats integrate(Stepper& stepper, double t0, const double* y0, double t_end, double dt_out,
                   StepObserver& observer, StepEvents* events);

}  // namespace machdyn
