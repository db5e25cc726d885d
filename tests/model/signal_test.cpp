// Signals (model/signal.hpp): every kind against its closed form, exact breakpoints, slopes against
// finite differences, the levels of piecewise-constant signals.
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/common/expression.hpp"
#include "machdyn/model/signal.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

constexpr double kPi = std::numbers::pi;

// Claim: constant, step and ramp follow their definitions; a step takes its new value at t0 itself.
TEST(Signal, ConstantStepRampClosedForms) {
  EXPECT_EQ(Signal::constant(3.5).value(-7.0), 3.5);
  EXPECT_EQ(Signal().value(1.0), 0.0);
  const Signal s = Signal::step(1.0, 5.0, 2.0);
  EXPECT_EQ(s.value(std::nextafter(2.0, 0.0)), 1.0);
  EXPECT_EQ(s.value(2.0), 5.0);
  const Signal r = Signal::ramp(-2.0, 10.0, 1.0, 4.0);
  EXPECT_EQ(r.value(1.0), -2.0);
  for (double t : {1.3, 2.0, 3.7}) EXPECT_NEAR(r.value(t), -2.0 + 12.0 * (t - 1.0) / 3.0, 1e-14);
  EXPECT_EQ(r.value(4.0), 10.0);
  EXPECT_EQ(r.value(9.0), 10.0);
  EXPECT_THROW(Signal::ramp(0, 1, 2.0, 2.0), std::invalid_argument);
}

// Claim: a table interpolates linearly; two points at one time are a jump whose second value holds
// from that time on; outside it holds the end values, or continues the end segments.
TEST(Signal, TableJumpsHoldAndExtrapolate) {
  // 0 → 10 over [0, 1], jump to 4 at 1, 4 → −2 over [1, 3].
  const std::vector<double> t{0, 1, 1, 3}, v{0, 10, 4, -2};
  const Signal held = Signal::table(t, v);
  EXPECT_DOUBLE_EQ(held.value(0.25), 2.5);
  EXPECT_EQ(held.value(std::nextafter(1.0, 0.0)) > 9.99, true);
  EXPECT_EQ(held.value(1.0), 4.0);
  EXPECT_DOUBLE_EQ(held.value(2.0), 1.0);
  EXPECT_EQ(held.value(-5.0), 0.0);
  EXPECT_EQ(held.value(3.0), -2.0);
  EXPECT_EQ(held.value(8.0), -2.0);
  const Signal ex = Signal::table(t, v, true);
  EXPECT_DOUBLE_EQ(ex.value(-1.0), -10.0);  // slope 10 of the first segment
  EXPECT_DOUBLE_EQ(ex.value(5.0), -8.0);    // slope −3 of the last
  EXPECT_THROW(Signal::table({0, 1, 1, 1}, {0, 1, 2, 3}), std::invalid_argument);  // three at one time
  EXPECT_THROW(Signal::table({0, 2, 1}, {0, 1, 2}), std::invalid_argument);
  EXPECT_THROW(Signal::table({0, 1, 1}, {0, 1, 2}, true), std::invalid_argument);  // last segment empty
}

// Claim: the sine is offset + A sin(ω (t − t_s) + φ) from its start, the offset before.
TEST(Signal, SineClosedForm) {
  const double A = 3.0, w = 2 * kPi * 1.5, ph = 0.4, off = -1.0, ts = 0.2;
  const Signal s = Signal::sine(A, w, ph, off, ts);
  EXPECT_EQ(s.value(0.1), off);
  for (double t : {0.2, 0.37, 1.0, 2.55}) EXPECT_NEAR(s.value(t), off + A * std::sin(w * (t - ts) + ph), 1e-14);
}

// Claim: a pulse train is high for `width` at the start of each period, low otherwise, for `count`
// periods; at each edge (as listed by breakpoints()) the value is the one after the edge.
TEST(Signal, PulseEdgesAndCount) {
  const Signal p = Signal::pulse(-1.0, 2.0, 0.3, 0.1, 0.05, 3);
  EXPECT_EQ(p.value(0.0), -1.0);
  EXPECT_EQ(p.value(0.06), 2.0);
  EXPECT_EQ(p.value(0.2), -1.0);
  EXPECT_EQ(p.value(0.36), 2.0);
  EXPECT_EQ(p.value(0.95 + 0.01), -1.0);  // after the third period: low for good
  const std::vector<double> b = p.breakpoints(0.0, 10.0);
  ASSERT_EQ(b.size(), 6u);
  for (std::size_t k = 0; k < 3; ++k) {
    EXPECT_DOUBLE_EQ(b[2 * k], 0.05 + 0.3 * static_cast<double>(k));
    EXPECT_DOUBLE_EQ(b[2 * k + 1], 0.15 + 0.3 * static_cast<double>(k));
    EXPECT_EQ(p.value(b[2 * k]), 2.0);       // rising edge: high from there
    EXPECT_EQ(p.value(b[2 * k + 1]), -1.0);  // falling edge: low from there
  }
  // An unending train, edges in a window only: (1.0, 1.7) holds rises at 1.25, 1.55 and falls at 1.05, 1.35, 1.65.
  const Signal q = Signal::pulse(0.0, 1.0, 0.3, 0.1, 0.05, -1);
  const std::vector<double> w = q.breakpoints(1.0, 1.7);
  const std::vector<double> expect{1.05, 1.25, 1.35, 1.55, 1.65};
  ASSERT_EQ(w.size(), expect.size());
  for (std::size_t k = 0; k < w.size(); ++k) EXPECT_NEAR(w[k], expect[k], 1e-12);
  EXPECT_GE(q.breakpoint_count(1.0, 1.7), static_cast<double>(w.size()));
  EXPECT_THROW(Signal::pulse(0, 1, 0.3, 0.3, 0, -1), std::invalid_argument);  // width = period
  // A vanishing period with a count: low long after its few pulses, no overflow of the period index.
  const Signal tiny = Signal::pulse(0.0, 1.0, 1e-300, 5e-301, 0.0, 5);
  EXPECT_EQ(tiny.value(1.0), 0.0);
  EXPECT_EQ(tiny.breakpoints(0.5, 2.0).size(), 0u);
}

// Claim: an expression signal is f(t); a sum is the sum of its terms, with every term's breakpoints.
TEST(Signal, ExpressionAndSum) {
  const Signal e = Signal::expression(std::make_shared<const Expression>("2*t^2 - 1", "t"));
  EXPECT_DOUBLE_EQ(e.value(3.0), 17.0);
  EXPECT_TRUE(e.breakpoints(0, 10).empty());
  const Signal s = Signal::sum({Signal::constant(1.0), Signal::step(0, 2, 0.5), Signal::ramp(0, 3, 1, 2), e});
  for (double t : {0.2, 0.5, 1.5, 3.0}) {
    const double ref = 1.0 + (t >= 0.5 ? 2.0 : 0.0) + (t <= 1 ? 0.0 : t >= 2 ? 3.0 : 3.0 * (t - 1)) + 2 * t * t - 1;
    EXPECT_DOUBLE_EQ(s.value(t), ref);
  }
  EXPECT_EQ(s.breakpoints(0.0, 10.0), (std::vector<double>{0.5, 1.0, 2.0}));
  EXPECT_EQ(s.breakpoints(0.7, 1.5), (std::vector<double>{1.0}));  // only inside the open interval
}

// Claim: breakpoints are exactly the jumps and kinks: step t0, ramp ends, table times (a jump once),
// the sine's start; nothing at the interval's ends.
TEST(Signal, BreakpointsExact) {
  EXPECT_EQ(Signal::step(0, 1, 0.3).breakpoints(0, 1), (std::vector<double>{0.3}));
  EXPECT_TRUE(Signal::step(0, 1, 0.3).breakpoints(0.3, 1).empty());
  EXPECT_EQ(Signal::ramp(0, 1, 0.2, 0.7).breakpoints(0, 1), (std::vector<double>{0.2, 0.7}));
  EXPECT_EQ(Signal::table({0, 0.4, 0.4, 2}, {0, 1, 3, 3}).breakpoints(0, 5), (std::vector<double>{0.4, 2.0}));
  EXPECT_EQ(Signal::sine(1, 1, 0, 0, 0.25).breakpoints(0, 1), (std::vector<double>{0.25}));
  EXPECT_TRUE(Signal::constant(4).breakpoints(0, 1).empty());
}

/// Signals of every kind with derivatives (piecewise linear, sine, expression, sum), for the
/// finite-difference checks of slope() and curvature().
std::vector<Signal> derivative_probes() {
  return {Signal::ramp(1, 4, 0.5, 2.5), Signal::table({0, 1, 1, 3}, {0, 10, 4, -2}, true),
          Signal::sine(2, 7, 0.3, 1, 0.1), Signal::expression(std::make_shared<const Expression>("exp(-t)*sin(3*t)", "t")),
          Signal::sum({Signal::sine(2, 7, 0.3, 1, 0.1), Signal::ramp(1, 4, 0.5, 2.5)})};
}

// Claim: slope() is ds/dt: it agrees with a central finite difference away from breakpoints.
TEST(Signal, SlopesAgreeWithFiniteDifference) {
  const std::vector<Signal> signals = derivative_probes();
  const double h = 1e-6;
  for (const Signal& s : signals)
    for (double t : {-0.5, 0.3, 0.77, 1.6, 2.2, 4.0}) {
      const double fd = (s.value(t + h) - s.value(t - h)) / (2 * h);
      EXPECT_NEAR(s.slope(t), fd, 1e-6 * std::max(1.0, std::abs(fd))) << s.describe("") << " at " << t;
    }
}

// Claim: curvature() is d²s/dt²: it agrees with a central finite difference of slope() away from
// breakpoints (a sine's −A ω² sin, an expression's jet, a sum's terms), and is 0 for the piecewise
// linear kinds.
TEST(Signal, CurvaturesAgreeWithFiniteDifferenceOfTheSlope) {
  const std::vector<Signal> signals = derivative_probes();
  const double h = 1e-6;
  for (const Signal& s : signals)
    for (double t : {-0.5, 0.3, 0.77, 1.6, 2.2, 4.0}) {
      const double fd = (s.slope(t + h) - s.slope(t - h)) / (2 * h);
      EXPECT_NEAR(s.curvature(t), fd, 1e-5 * std::max(1.0, std::abs(fd))) << s.describe("") << " at " << t;
    }
  EXPECT_NE(signals[2].curvature(0.77), 0.0);  // not trivially zero
}

// Claim: levels() lists the values of piecewise-constant signals (what a contactor or a direction
// may be checked against) and is empty for signals that vary continuously.
TEST(Signal, LevelsOfPiecewiseConstantSignals) {
  EXPECT_EQ(Signal::step(1, -1, 2).levels(), (std::vector<double>{-1, 1}));
  EXPECT_EQ(Signal::pulse(0, 1, 1, 0.5, 0, -1).levels(), (std::vector<double>{0, 1}));
  EXPECT_EQ(Signal::table({0, 0, 1, 1}, {0, 1, 1, 0}).levels(), (std::vector<double>{0, 1}));
  EXPECT_TRUE(Signal::table({0, 1}, {0, 1}).levels().empty());
  EXPECT_TRUE(Signal::sine(1, 1, 0, 0, 0).levels().empty());
  EXPECT_EQ(Signal::sum({Signal::step(0, 1, 1), Signal::step(0, 1, 2)}).levels(), (std::vector<double>{0, 1, 2}));
  EXPECT_TRUE(Signal::constant(2).is_constant());
  EXPECT_FALSE(Signal::step(0, 1, 2).is_constant());
}

// Claim: crossings() finds where s crosses a level with a change of sign, in closed form for a
// ramp (linear interpolation), a table (per segment and on the extrapolated tails) and a sine
// (A sin(ω t + φ) = L − d: θ = asin r, π − asin r), by bisection for a sum; a jump is no crossing.
TEST(Signal, CrossingsOfALevel) {
  EXPECT_EQ(Signal::ramp(-1, 3, 1, 2).crossings(0.0, 0, 5), std::vector<double>{1.25});
  EXPECT_TRUE(Signal::step(-1, 1, 1).crossings(0.0, 0, 5).empty());
  const auto tab = Signal::table({0, 1, 2}, {1, -1, 3}, true).crossings(0.0, -5, 5);
  ASSERT_EQ(tab.size(), 2u);  // the tails move away from 0
  EXPECT_DOUBLE_EQ(tab[0], 0.5);
  EXPECT_DOUBLE_EQ(tab[1], 1.25);
  EXPECT_EQ(Signal::table({0, 1}, {1, 2}, true).crossings(0.0, -5, 5), std::vector<double>{-1.0});  // left tail
  const double w = 2 * std::numbers::pi;  // 1 Hz, offset 0.5, amplitude 1: sin θ = −0.5
  const auto sn = Signal::sine(1, w, 0, 0.5, 0).crossings(0.0, 0, 2);
  const std::vector<double> want{7.0 / 12, 11.0 / 12, 19.0 / 12, 23.0 / 12};
  ASSERT_EQ(sn.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) EXPECT_NEAR(sn[i], want[i], 1e-14);
  const auto sm = Signal::sum({Signal::sine(1, w, 0, 0, 0), Signal::constant(0.5)}).crossings(0.0, 0, 2);
  ASSERT_EQ(sm.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) EXPECT_NEAR(sm[i], want[i], 1e-14);
  EXPECT_DOUBLE_EQ(Signal::sine(2, w, 0, -1, 0).magnitude_bound(0, 1), 3.0);
}

}  // namespace
}  // namespace machdyn
