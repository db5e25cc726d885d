#include <cmath>
#include <gtest/gtest.h>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/solve/driver.hpp"
#include "support/oscillator.hpp"
#include "machdyn/solve/stepper.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::Oscillator;

class Steppers : public ::testing::TestWithParam<Method> {};

struct Collect final : StepObserver {
  std::vector<double> t, y;
  void on_output(double tt, const double* yy) override { t.push_back(tt), y.push_back(yy[0]); }
};

// Claim: both integrators reach the exact solution of the harmonic oscillator to near their
// tolerance over 10 periods, on the output grid produced by dense output.
TEST_P(Steppers, HarmonicOscillatorToTolerance) {
  Oscillator osc(2.0);
  StepperOptions opt;
  opt.rtol = 1e-10;
  opt.atol = 1e-12;
  auto s = make_stepper(GetParam(), osc, opt);
  const double y0[2] = {1.0, 0.0};
  Collect c;
  DriveOptions drive;
  drive.dt_out = 0.01;
  const RunStats st = integrate(*s, osc, 0.0, y0, 10 * 3.14159265358979323846, drive, c);
  ASSERT_GT(c.t.size(), 3000u);
  EXPECT_DOUBLE_EQ(c.t.back(), 10 * 3.14159265358979323846);
  double err = 0;
  for (size_t i = 0; i < c.t.size(); ++i) err = std::max(err, std::abs(c.y[i] - std::cos(2.0 * c.t[i])));
  EXPECT_LT(err, GetParam() == Method::dopri5 ? 1e-8 : 1e-7);
  EXPECT_GT(st.stepper.steps, 10);
}

// Claim: the dense-output derivative equals f(t, y) at the end of a step (C¹ continuous
// extension) and approximates it inside the step.
TEST_P(Steppers, DenseDerivativeMatchesRightHandSide) {
  Oscillator osc(3.0);
  StepperOptions opt;
  opt.rtol = 1e-9;
  opt.atol = 1e-12;
  auto s = make_stepper(GetParam(), osc, opt);
  const double y0[2] = {1.0, 0.0};
  s->reset(0.0, y0);
  for (int k = 0; k < 20; ++k) s->step(10.0);
  double dy[2], f[2], y[2];
  s->derivative(s->t(), dy);
  osc.rhs(s->t(), s->y(), f);
  EXPECT_NEAR(dy[0], f[0], 1e-6 * std::abs(f[0]) + 1e-9);
  EXPECT_NEAR(dy[1], f[1], 1e-6 * std::abs(f[1]) + 1e-9);
  const double tm = 0.5 * (s->t_prev() + s->t());
  s->derivative(tm, dy);
  s->interpolate(tm, y);
  EXPECT_NEAR(dy[0], -3.0 * std::sin(3.0 * tm), 1e-5);
  EXPECT_NEAR(y[0], std::cos(3.0 * tm), 1e-7);
}

INSTANTIATE_TEST_SUITE_P(BothMethods, Steppers, ::testing::Values(Method::dopri5, Method::bdf),
                         [](const auto& p) { return p.param == Method::dopri5 ? "dopri5" : "bdf"; });

/// y' = 1/(1 − t) blows up at t = 1.
class BlowUp final : public OdeSystem {
 public:
  int size() const override { return 1; }
  void rhs(double t, const double*, double* dy) override { dy[0] = 1.0 / (1.0 - t) / (1.0 - t); }
  std::string state_name(int) const override { return "body 'X' (position)"; }
};

// Claim: a singular solution ends in a SolverError that names the state and a time near the singularity.
TEST(Dopri5, SingularityIsReportedWithElementAndTime) {
  BlowUp b;
  auto s = make_stepper(Method::dopri5, b, {});
  const double y0[1] = {0.0};
  s->reset(0.0, y0);
  try {
    for (int k = 0; k < 100000; ++k) s->step(2.0);
    FAIL() << "expected SolverError";
  } catch (const SolverError& e) {
    EXPECT_EQ(e.element(), "body 'X' (position)");
    EXPECT_NEAR(e.time(), 1.0, 1e-3);
  }
}

}  // namespace
}  // namespace machdyn
