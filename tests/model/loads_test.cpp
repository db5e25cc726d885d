#include <cmath>
#include <gtest/gtest.h>

#include "machdyn/model/model.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

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
  EXPECT_NEAR(test::load_at(l, 0, 0, w0 * (1 - sk)), Mk, 1e-12 * Mk);
  EXPECT_EQ(test::load_at(l, 0, 0, w0), 0.0);
  EXPECT_NEAR(test::load_at(l, 0, 0, 0.0), 2 * Mk / (1 / sk + sk), 1e-12 * Mk);
  // Maximum: no slip near s_k gives more torque.
  for (double s : {0.2, 0.24, 0.26, 0.3}) EXPECT_LT(test::load_at(l, 0, 0, w0 * (1 - s)), Mk);
  // Generator region (ω > ω0) brakes.
  EXPECT_LT(test::load_at(l, 0, 0, 1.05 * w0), 0.0);
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
      const double fd = (test::load_at(l, 0, 0, w + h) - test::load_at(l, 0, 0, w - h)) / (2 * h);
      double dq, dv;
      test::load_slopes(l, 0, 0, w, &dq, &dv);
      EXPECT_NEAR(dv, fd, 1e-6 * std::max(1.0, std::abs(fd)));
    }
}

// Claim: a signal load is its signal at t, whatever the state (step, ramp and table kinds compile
// into signals; each signal kind is checked against its closed form in signal_test.cpp).
TEST(Loads, SignalLoadIsItsSignal) {
  Load s;
  s.kind = LoadKind::signal, s.signal = Signal::step(1, 5, 2);
  EXPECT_EQ(test::load_at(s, 1.999, 3.0, 7.0), 1);
  EXPECT_EQ(test::load_at(s, 2.0, -3.0, 0.0), 5);
  double dq, dv;
  test::load_slopes(s, 2.5, 1.0, 1.0, &dq, &dv);
  EXPECT_EQ(dv, 0.0);
  EXPECT_EQ(dq, 0.0);
  const std::vector<double> b = s.breakpoints(0.0, 10.0);
  ASSERT_EQ(b.size(), 1u);
  EXPECT_EQ(b[0], 2.0);
}

}  // namespace
}  // namespace machdyn
