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

struct RunStats {
  StepperStats stepper;
  std::string method;
  double wall_time_s = 0.0;
};

/// Integrates from (t0, y0) to t_end. Outputs are interpolated, so dt_out does not limit steps.
/// Throws SolverError from the stepper.
RunStats integrate(Stepper& stepper, double t0, const double* y0, double t_end, double dt_out,
                   StepObserver& observer);

}  // namespace machdyn
