// The sampling step of a signal (model/signal_sampling.hpp): the time over which an event function
// reading it may be judged at the ends alone. Claims against the signals' own definitions.
#include "machdyn/model/signal_sampling.hpp"

#include <cmath>
#include <limits>
#include <memory>
#include <numbers>
#include <gtest/gtest.h>

#include "machdyn/common/expression.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

constexpr double inf = std::numeric_limits<double>::infinity();

// Claim: a sine of ω is sampled at its period over 8, 2π/(8ω), whatever its amplitude, phase, offset
// and start (ω read back from s'' = −ω² (s − d), so it must match the ω it was built with); one
// that starts after the interval is constant there (+∞).
TEST(SignalSampling, ASineAtAnEighthOfItsPeriod) {
  for (double w : {0.5, 2 * std::numbers::pi, 377.0, 1e4}) {
    const Signal s = Signal::sine(3.0, w, 0.4, -7.0, 0.25);
    EXPECT_NEAR(sampling_step(s, 0.0, 2.0), 2 * std::numbers::pi / (8 * w), 1e-9 * 2 * std::numbers::pi / (8 * w)) << w;
  }
  EXPECT_EQ(sampling_step(Signal::sine(3.0, 10.0, 0.0, 1.0, 5.0), 0.0, 2.0), inf);
  EXPECT_EQ(sampling_step(Signal::sine(0.0, 10.0, 0.0, 1.0, 0.0), 0.0, 2.0), inf);
}

// Claim: signals linear between their breakpoints need no sampling (+∞); a sum takes its smallest
// term's step; an expression is sampled at (t1 − t0)/4096, as Signal::crossings resolves it.
TEST(SignalSampling, LinearPiecesSumsAndExpressions) {
  EXPECT_EQ(sampling_step(Signal::constant(2.0), 0.0, 1.0), inf);
  EXPECT_EQ(sampling_step(Signal::ramp(0.0, 1.0, 0.1, 0.5), 0.0, 1.0), inf);
  EXPECT_EQ(sampling_step(Signal::table({0.0, 0.5, 1.0}, {0.0, 3.0, -1.0}), 0.0, 1.0), inf);
  EXPECT_EQ(sampling_step(Signal::pulse(0.0, 1.0, 0.1, 0.05, 0.0, -1), 0.0, 1.0), inf);
  const Signal sum = Signal::sum({Signal::ramp(0.0, 1.0, 0.1, 0.5), Signal::sine(1.0, 4.0, 0.0, 0.0, 0.0),
                                  Signal::sine(1.0, 40.0, 0.0, 0.0, 0.0)});
  EXPECT_NEAR(sampling_step(sum, 0.0, 3.0), 2 * std::numbers::pi / (8 * 40.0), 1e-12);
  const Signal e = Signal::expression(std::make_shared<const Expression>("t*t", "t"));
  EXPECT_DOUBLE_EQ(sampling_step(e, 0.0, 2.0), 2.0 / 4096.0);
}

}  // namespace
}  // namespace machdyn
