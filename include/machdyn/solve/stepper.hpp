#pragma once
/// @file
/// One interface for every integrator: advance one accepted step at a time with dense output, so
/// the driver (solve/driver.hpp) samples outputs, tracks peaks and locates events on the continuous
/// solution, independent of the method.

#include <memory>
#include <string>

#include "machdyn/solve/ode_system.hpp"

namespace machdyn {

struct StepperOptions {
  double rtol = 1e-8;   ///< relative tolerance
  double atol = 1e-10;  ///< absolute tolerance
  double h_max = 0.0;   ///< largest step, s (0: no limit)
  long max_steps = 50'000'000;
};

struct StepperStats {
  long steps = 0;      ///< accepted steps
  long rejected = 0;   ///< rejected steps (error test or convergence failures)
  long rhs_evals = 0;  ///< evaluations of f
  long jac_evals = 0;  ///< evaluations of ∂f/∂y
};

class Stepper {
 public:
  virtual ~Stepper() = default;
  /// Starts (or restarts, e.g. after an event) at (t0, y0).
  virtual void reset(double t0, const double* y0) = 0;
  /// Takes one accepted step, never past t_limit. Throws SolverError when the step size underflows,
  /// f returns a non-finite value, or max_steps is exceeded.
  virtual void step(double t_limit) = 0;
  [[nodiscard]] virtual int size() const = 0;       ///< number of states
  [[nodiscard]] virtual double t() const = 0;       ///< end of the last step
  [[nodiscard]] virtual double t_prev() const = 0;  ///< start of the last step
  [[nodiscard]] virtual const double* y() const = 0;
  /// f(t(), y()), the derivative at the end of the last step.
  [[nodiscard]] virtual const double* dydt() const = 0;
  /// The dense-output solution at t ∈ [t_prev(), t()]: a polynomial in t of degree ≤ 6 (dopri5: 4;
  /// BDF: its order ≤ 5), which the peak tracker's bounds rely on (analysis/peak_tracker.hpp).
  virtual void interpolate(double t, double* y_out) const = 0;
  /// The time derivative of the dense-output solution at t ∈ [t_prev(), t()]; at the step ends it
  /// equals f(t, y).
  virtual void derivative(double t, double* dy_out) const = 0;
  /// Counts over the stepper's whole life, summed across reset() (a run restarted at every event
  /// reports all its steps); max_steps bounds the same count, so it holds per run.
  [[nodiscard]] virtual StepperStats stats() const = 0;
  [[nodiscard]] virtual std::string name() const = 0;
};

enum class Method { dopri5, bdf };

/// Dormand–Prince 5(4) with 4th-order dense output (solve/dopri5.cpp) or CVODE BDF with a dense
/// direct linear solver and the analytic Jacobian if the system has one (solve/cvode_bdf.cpp).
std::unique_ptr<Stepper> make_stepper(Method method, OdeSystem& system, const StepperOptions& options);

}  // namespace machdyn
