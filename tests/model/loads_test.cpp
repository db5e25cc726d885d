#include <cmath>
#include <gtest/gtest.h>

#include "machdyn/model/model.hpp"

namespace machdyn {
namespace {

Load kloss(double Mk, double sk, double w0) {
  Load l;
  l.kind = LoadKind::motor_kloss;
  l.value = Mk;
  l.s_k = sk;
  l.omega0 = w0;
  return l;
}

// Claim: the Kloss torque peaks at the breakdown slip with the breakdown torque, is zero at
// synchronous speed, and at standstill equals 2 M_k / (1/s_k + s_k) (s = 1).
TEST(Loads, KlossFormulaBreakdownPointAndStandstill) {
  const double Mk = 800, sk = 0.25, w0 = 157.08;
  const Load l = kloss(Mk, sk, w0);
  EXPECT_NEAR(l.evaluate(0, w0 * (1 - sk)), Mk, 1e-12 * Mk);
  EXPECT_EQ(l.evaluate(0, w0), 0.0);
  EXPECT_NEAR(l.evaluate(0, 0.0), 2 * Mk / (1 / sk + sk), 1e-12 * Mk);
  // Maximum: no slip near s_k gives more torque.
  for (double s : {0.2, 0.24, 0.26, 0.3}) EXPECT_LT(l.evaluate(0, w0 * (1 - s)), Mk);
  // Generator region (ω > ω0) brakes.
  EXPECT_LT(l.evaluate(0, 1.05 * w0), 0.0);
}

// Claim: dM/dω of the motors agrees with a central finite difference.
TEST(Loads, MotorSlopesAgreeWithFiniteDifference) {
  Load lin;
  lin.kind = LoadKind::motor_linear;
  lin.value = 300;
  lin.omega0 = 100;
  for (const Load& l : {kloss(800, 0.25, 157.08), lin})
    for (double w : {0.0, 40.0, 120.0, 150.0, 170.0}) {
      const double h = 1e-5;
      const double fd = (l.evaluate(0, w + h) - l.evaluate(0, w - h)) / (2 * h);
      EXPECT_NEAR(l.slope(0, w), fd, 1e-6 * std::max(1.0, std::abs(fd)));
    }
}

// Claim: step, ramp and table loads follow their definitions, holding end values outside.
TEST(Loads, TimeFunctions) {
  Load s;
  s.kind = LoadKind::step, s.before = 1, s.value = 5, s.t0 = 2;
  EXPECT_EQ(s.evaluate(1.999, 0), 1);
  EXPECT_EQ(s.evaluate(2.0, 0), 5);
  Load r;
  r.kind = LoadKind::ramp, r.before = 0, r.value = 10, r.t0 = 1, r.t1 = 3;
  EXPECT_EQ(r.evaluate(0.5, 0), 0);
  EXPECT_DOUBLE_EQ(r.evaluate(2.0, 0), 5);
  EXPECT_EQ(r.evaluate(4, 0), 10);
  Load t;
  t.kind = LoadKind::table, t.times = {0, 1, 3}, t.values = {0, 10, -10};
  EXPECT_DOUBLE_EQ(t.evaluate(0.5, 0), 5);
  EXPECT_DOUBLE_EQ(t.evaluate(2, 0), 0);
  EXPECT_DOUBLE_EQ(t.evaluate(9, 0), -10);
  EXPECT_DOUBLE_EQ(t.evaluate(-1, 0), 0);
}

}  // namespace
}  // namespace machdyn
