#pragma once
// Dormand–Prince 5(4) (Dormand & Prince 1980) with Hairer's step-size control (PI, β = 0.04) and
// the 4th-order continuous extension of Hairer, Nørsett & Wanner, "Solving ODE I", II.6.
// N > 0 fixes the number of states at compile time (1…16: small chains, hybrid models; loops unroll);
// N = 0 is the general size. make_stepper() picks.
#include <array>
#include <type_traits>
#include <vector>

#include "machdyn/solve/stepper.hpp"

namespace machdyn {

template <int N>
class Dopri5 final : public Stepper {
 public:
  Dopri5(OdeSystem& system, const StepperOptions& options);
  void reset(double t0, const double* y0) override;
  void step(double t_limit) override;
  [[nodiscard]] int size() const override { return n(); }
  [[nodiscard]] double t() const override { return t_; }
  [[nodiscard]] double t_prev() const override { return t_old_; }
  [[nodiscard]] const double* y() const override { return y_.data(); }
  [[nodiscard]] const double* dydt() const override { return k1_.data(); }
  void interpolate(double t, double* y_out) const override;
  void derivative(double t, double* dy_out) const override;
  [[nodiscard]] StepperStats stats() const override { return stats_; }
  [[nodiscard]] std::string name() const override { return "dopri5"; }

 private:
  using Vec = std::conditional_t<(N > 0), std::array<double, (N > 0 ? N : 1)>, std::vector<double>>;
  [[nodiscard]] int n() const {
    if constexpr (N > 0) return N;
    else return n_;
  }
  double initial_step();
  [[noreturn]] void fail(const char* what, int component) const;

  OdeSystem& sys_;
  StepperOptions opt_;
  int n_;
  double t_ = 0.0, t_old_ = 0.0, h_ = 0.0, h_old_ = 0.0, facold_ = 1e-4;
  bool last_rejected_ = false;
  Vec y_{}, y1_{}, k1_{}, k2_{}, k3_{}, k4_{}, k5_{}, k6_{}, k7_{}, ytmp_{}, err_{};
  Vec r1_{}, r2_{}, r3_{}, r4_{}, r5_{};  // dense-output coefficients of the last step
  StepperStats stats_;
};

/// Makes a Dopri5 with a fixed size when the system is small, else the general one.
std::unique_ptr<Stepper> make_dopri5(OdeSystem& system, const StepperOptions& options);

}  // namespace machdyn
