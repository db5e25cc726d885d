#pragma once
// Dormand–Prince 5(4) (Dormand & Prince 1980) with Hairer's step-size control (PI, β = 0.04) and
// the 4th-order continuous extension of Hairer, Nørsett & Wanner, "Solving ODE I", II.6.
#include <vector>

#include "machdyn/solve/stepper.hpp"

namespace machdyn {

class Dopri5 final : public Stepper {
 public:
  Dopri5(OdeSystem& system, const StepperOptions& options);
  void reset(double t0, const double* y0) override;
  void step(double t_limit) override;
  [[nodiscard]] int size() const override { return n_; }
  [[nodiscard]] double t() const override { return t_; }
  [[nodiscard]] double t_prev() const override { return t_old_; }
  [[nodiscard]] const double* y() const override { return y_.data(); }
  void interpolate(double t, double* y_out) const override;
  void derivative(double t, double* dy_out) const override;
  [[nodiscard]] StepperStats stats() const override { return stats_; }
  [[nodiscard]] std::string name() const override { return "dopri5"; }

 private:
  double initial_step();
  void fail(const char* what, int component) const;

  OdeSystem& sys_;
  StepperOptions opt_;
  int n_;
  double t_ = 0.0, t_old_ = 0.0, h_ = 0.0, h_old_ = 0.0, facold_ = 1e-4;
  bool last_rejected_ = false;
  std::vector<double> y_, y1_, k1_, k2_, k3_, k4_, k5_, k6_, k7_, ytmp_, err_;
  std::vector<double> r1_, r2_, r3_, r4_, r5_;  // dense-output coefficients of the last step
  StepperStats stats_;
};

}  // namespace machdyn
