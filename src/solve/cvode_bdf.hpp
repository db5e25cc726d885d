#pragma once
// CVODE (SUNDIALS) variable-order BDF with Newton iteration and a dense direct linear solver, driven
// one step at a time (CV_ONE_STEP with a stop time) so the driver sees the same dense output as for
// the explicit method (CVodeGetDky).
#include <vector>

#include "machdyn/solve/stepper.hpp"

namespace machdyn {

class CvodeBdf final : public Stepper {
 public:
  CvodeBdf(OdeSystem& system, const StepperOptions& options);
  ~CvodeBdf() override;
  CvodeBdf(const CvodeBdf&) = delete;
  CvodeBdf& operator=(const CvodeBdf&) = delete;

  void reset(double t0, const double* y0) override;
  void step(double t_limit) override;
  [[nodiscard]] int size() const override { return static_cast<int>(y_.size()); }
  [[nodiscard]] double t() const override { return t_; }
  [[nodiscard]] double t_prev() const override { return t_old_; }
  [[nodiscard]] const double* y() const override { return y_.data(); }
  [[nodiscard]] const double* dydt() const override { return dy_.data(); }
  void interpolate(double t, double* y_out) const override;
  void derivative(double t, double* dy_out) const override;
  [[nodiscard]] StepperStats stats() const override;
  [[nodiscard]] std::string name() const override { return "cvode-bdf"; }

  struct Impl;
  /// From this many states on, a system with a sparse Jacobian is solved with KLU.
  static constexpr int kSparseFrom = 64;

 private:
  Impl* impl_;
  OdeSystem& sys_;
  StepperOptions opt_;
  double t_ = 0.0, t_old_ = 0.0;
  bool still_ = false;  // the last step spanned less than CVODE resolves: the state stood still
  std::vector<double> y_, dy_;
  StepperStats done_;  // counts before the last CVodeReInit
};

}  // namespace machdyn
