#pragma once
// The harmonic oscillator y'' = −ω² y as a first-order system y = [y, y'], the known solution the
// solver-layer tests integrate: from y(0) = 1, y'(0) = 0 it is y = cos ωt, y' = −ω sin ωt.
// Optional breakpoints (times the driver must not step across) cut the steps into pieces.

#include <vector>

#include <Eigen/Core>

#include "machdyn/solve/event_system.hpp"

namespace machdyn::test {

class Oscillator final : public EventSystem {
 public:
  explicit Oscillator(double w) : w_(w) {}
  int size() const override { return 2; }
  void rhs(double, const double* y, double* dy) override {
    dy[0] = y[1];
    dy[1] = -w_ * w_ * y[0];
  }
  bool has_jacobian() const override { return true; }
  void jacobian(double, const double*, Eigen::Ref<Eigen::MatrixXd> J) override { J << 0, 1, -w_ * w_, 0; }
  std::vector<double> breakpoints(double, double) const override { return bps; }
  std::vector<double> bps;

 private:
  double w_;
};

}  // namespace machdyn::test
