// The one driver loop (solve/driver.hpp) on systems with known solutions: event times, the state
// jump at an event, breakpoints, statistics summed over restarts, max_steps per run. On both
// integrators.
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/solve/driver.hpp"
#include "machdyn/solve/stepper.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

/// A ball falling under gravity onto the floor: x'' = −g, event function x ≥ 0, at impact the speed
/// reverses with restitution e (v⁺ = −e v⁻). Closed form: from rest at height h the first impact is
/// at t1 = sqrt(2h/g) with speed v1 = g t1; each flight after impact k lasts 2 e^k v1 / g.
/// Optional breakpoints (the rhs does not change there) record the times handle_events saw them.
class Ball final : public EventSystem {
 public:
  Ball(double g, double e) : g_(g), e_(e) {}
  int size() const override { return 2; }
  void rhs(double, const double* y, double* dy) override {
    dy[0] = y[1];
    dy[1] = -g_;
  }
  int event_count() const override { return 1; }
  void event_functions(double, const double* y, double* g) override { g[0] = y[0]; }
  std::vector<double> breakpoints(double, double) const override { return bps; }
  bool handle_events(double t, double* y, const std::vector<int>& fired) override {
    if (fired.empty()) {
      at_bp.push_back(t);
      return false;
    }
    impacts.push_back(t);
    y[0] = 0.0;
    y[1] = -e_ * y[1];
    return true;
  }
  std::vector<double> bps, at_bp, impacts;

 private:
  double g_, e_;
};

/// Counts what the driver shows its observer.
struct Counter final : StepObserver {
  long steps = 0;
  std::vector<double> seg_end, out_t, out_x;
  void on_step(const Stepper&) override { ++steps; }
  void on_segment(const Stepper&, double, double tb) override { seg_end.push_back(tb); }
  void on_output(double t, const double* y) override { out_t.push_back(t), out_x.push_back(y[0]); }
};

class Driver : public ::testing::TestWithParam<Method> {};
INSTANTIATE_TEST_SUITE_P(BothIntegrators, Driver, ::testing::Values(Method::dopri5, Method::bdf));

StepperOptions tight() {
  StepperOptions o;
  o.rtol = 1e-10;
  o.atol = 1e-12;
  return o;
}

// Claim: the driver locates the impacts at the closed-form times (1e-9 relative, the solution is a
// parabola so the dense output is exact up to rounding and tolerance), applies the jump, and the
// observer never sees the ball below the floor (no output beyond an event in the old mode).
TEST_P(Driver, LocatesEventsOfAKnownSolution) {
  const double g = 9.81, e = 0.8, h = 2.0;
  Ball ball(g, e);
  auto st = make_stepper(GetParam(), ball, tight());
  const double y0[2] = {h, 0.0};
  Counter c;
  DriveOptions d;
  d.dt_out = 0.01;
  const double t_end = 3.0;
  const RunStats rs = integrate(*st, ball, 0.0, y0, t_end, d, c);
  const double t1 = std::sqrt(2 * h / g), v1 = g * t1;
  std::vector<double> want{t1};
  for (double ek = e; want.back() + 2 * ek * v1 / g < t_end; ek *= e) want.push_back(want.back() + 2 * ek * v1 / g);
  ASSERT_EQ(ball.impacts.size(), want.size());
  for (size_t k = 0; k < want.size(); ++k) EXPECT_NEAR(ball.impacts[k], want[k], 1e-9 * want[k]) << k;
  EXPECT_EQ(rs.events, static_cast<long>(want.size()));
  for (double x : c.out_x) EXPECT_GE(x, -1e-9);
  EXPECT_EQ(c.out_t.back(), t_end);
}

// Claim: the statistics of a run are the sum over every restart: the accepted steps equal the
// number of steps the observer saw (CVODE's CVodeReInit zeroes its own counters; the issue's
// travel start-up reported 78 of ~5100 steps), and a second run on the same stepper counts only
// its own steps.
TEST_P(Driver, StatisticsAreSummedOverRestarts) {
  Ball ball(9.81, 0.9);
  auto st = make_stepper(GetParam(), ball, tight());
  const double y0[2] = {1.0, 0.0};
  DriveOptions d;
  d.dt_out = 0.1;
  Counter c;
  const RunStats rs = integrate(*st, ball, 0.0, y0, 4.0, d, c);
  ASSERT_GE(rs.events, 5);
  EXPECT_EQ(rs.stepper.steps, c.steps);
  Counter c2;
  const RunStats rs2 = integrate(*st, ball, 0.0, y0, 4.0, d, c2);
  EXPECT_EQ(rs2.stepper.steps, c2.steps);
}

// Claim: steps end exactly at each breakpoint and the system is asked there (fired empty).
TEST_P(Driver, StepsEndAtBreakpoints) {
  Ball ball(9.81, 0.5);
  ball.bps = {0.123456789, 0.3, 0.7};
  auto st = make_stepper(GetParam(), ball, tight());
  const double y0[2] = {1.0, 0.0};
  DriveOptions d;
  d.dt_out = 0.25;
  Counter c;
  integrate(*st, ball, 0.0, y0, 1.0, d, c);
  EXPECT_EQ(ball.at_bp, ball.bps);
  for (double b : ball.bps) EXPECT_NE(std::find(c.seg_end.begin(), c.seg_end.end(), b), c.seg_end.end()) << b;
}

// Claim: max_steps bounds the whole run, not one segment between events: a bouncing ball whose
// segments each take few steps still stops with a SolverError once the run's total passes it.
TEST_P(Driver, MaxStepsHoldsPerRun) {
  Ball ball(9.81, 1.0);  // elastic: it bounces every 0.9 s forever
  StepperOptions o = tight();
  o.max_steps = 300;
  auto st = make_stepper(GetParam(), ball, o);
  const double y0[2] = {1.0, 0.0};
  DriveOptions d;
  d.dt_out = 0.1;
  Counter c;
  EXPECT_THROW(integrate(*st, ball, 0.0, y0, 1000.0, d, c), SolverError);
  // Each segment between impacts took fewer steps than the limit.
  EXPECT_GT(ball.impacts.size(), 3u);
  EXPECT_LT(c.steps / static_cast<long>(ball.impacts.size() + 1), 300);
}

/// A body moving at unit speed, x = t, with a mode m and one event function per mode:
///   mode 0: g = 1 − x (fires at x = 1); its decision picks mode 1;
///   mode 1: g = (1 − x) − 1e-12: already negative where mode 0 ended — a decision its own event
///           function contradicts (as a contact kept stuck at λ = F_s whose limit function reads
///           −1e-11). With `settles` the second decision picks mode 2 (g = 2 − x, fires at x = 2),
///           else it keeps mode 1 forever. Mode 3 (after x = 2) has no more events (g = 1).
class Misdecided final : public EventSystem {
 public:
  explicit Misdecided(bool settles) : settles_(settles) {}
  int size() const override { return 1; }
  void rhs(double, const double*, double* dy) override { dy[0] = 1.0; }
  int event_count() const override { return 1; }
  void event_functions(double, const double* y, double* g) override {
    g[0] = mode == 0 ? 1.0 - y[0] : mode == 1 ? (1.0 - y[0]) - 1e-12 : mode == 2 ? 2.0 - y[0] : 1.0;
  }
  bool handle_events(double t, double*, const std::vector<int>& fired) override {
    if (fired.empty()) return false;
    decisions.push_back(t);
    modes.push_back(mode = mode == 0 ? 1 : mode == 1 ? (settles_ ? 2 : 1) : 3);
    return true;
  }
  int mode = 0;
  std::vector<double> decisions;
  std::vector<int> modes;

 private:
  bool settles_;
};

// Claim: a function the decision leaves negative at a restart is handed back at once (the same
// instant) and decided again; it is never left disarmed. Mode 0 ends at t = 1, mode 1 contradicts
// itself there and is replaced by mode 2 at t = 1, whose event fires at t = 2 (closed form: x = t).
// Before the restart rule mode 1 stayed on to the end with its function negative and no event.
TEST_P(Driver, ANegativeFunctionAtARestartIsDecidedAgain) {
  Misdecided sys(true);
  auto st = make_stepper(GetParam(), sys, tight());
  const double y0[1] = {0.0};
  DriveOptions d;
  d.dt_out = 0.5;
  Counter c;
  integrate(*st, sys, 0.0, y0, 3.0, d, c);
  ASSERT_EQ(sys.modes, (std::vector<int>{1, 2, 3}));
  EXPECT_NEAR(sys.decisions[0], 1.0, 1e-12);
  EXPECT_EQ(sys.decisions[1], sys.decisions[0]);
  EXPECT_NEAR(sys.decisions[2], 2.0, 1e-12);
}

// Claim: a system whose decision never satisfies its own event function ends with a SolverError
// at that instant after a bounded number of re-decisions (no hang, no silent disarm).
TEST_P(Driver, ADecisionThatNeverSettlesIsAnError) {
  Misdecided sys(false);
  auto st = make_stepper(GetParam(), sys, tight());
  const double y0[1] = {0.0};
  DriveOptions d;
  d.dt_out = 0.5;
  Counter c;
  try {
    integrate(*st, sys, 0.0, y0, 3.0, d, c);
    FAIL() << "no error";
  } catch (const SolverError& e) {
    EXPECT_NEAR(e.time(), 1.0, 1e-12);
  }
  EXPECT_LT(sys.decisions.size(), 40u);
}

/// A state that stands still (y' = 0) and one event function with an explicit dependence on t,
/// g = 0.5 − sin(2π(t − 0.4)): the error control sees nothing, so the steps grow over the whole
/// excursion of g below 0 (t in (0.4 + 1/12, 0.4 + 5/12)): dopri5 steps from 0.111 to 1, bdf from
/// 0.343 to 1. The system states its sampling step, 1/8 of the period unless
/// told otherwise (EventSystem::sampling_step).
class StandingSine final : public EventSystem {
 public:
  explicit StandingSine(double h) : h_(h) {}
  int size() const override { return 1; }
  void rhs(double, const double*, double* dy) override { dy[0] = 0.0; }
  int event_count() const override { return 1; }
  void event_functions(double t, const double*, double* g) override {
    g[0] = done ? 1.0 : 0.5 - std::sin(2.0 * std::numbers::pi * (t - 0.4));  // after the event: no more
  }
  double sampling_step(double, double) const override { return h_; }
  bool handle_events(double t, double*, const std::vector<int>& fired) override {
    if (!fired.empty()) events.push_back(t), done = true;
    return !fired.empty();
  }
  std::vector<double> events;
  bool done = false;

 private:
  double h_;
};

// Claim: with the sampling step of its signal (T/8) the driver finds the first crossing of
// g = 0.5 − sin(2π(t − 0.4)) at the closed form 0.4 + asin(0.5)/(2π) = 0.4 + 1/12 s, whatever dt_out is (here one
// output at the end: the grid of old, checked only in steps longer than 2 dt_out, saw nothing);
// without it (an infinite sampling step) the crossing is stepped over — the claim can fail.
TEST_P(Driver, AnExcursionInsideALongStepIsFoundAtTheSamplingStep) {
  const double y0[1] = {0.0};
  DriveOptions d;
  d.dt_out = 1.0;
  Counter c;
  StandingSine sampled(1.0 / 8.0);
  auto st = make_stepper(GetParam(), sampled, tight());
  integrate(*st, sampled, 0.0, y0, 1.0, d, c);
  ASSERT_GE(sampled.events.size(), 1u);
  EXPECT_NEAR(sampled.events[0], 0.4 + 1.0 / 12.0, 1e-12);
  StandingSine blind(std::numeric_limits<double>::infinity());
  auto st2 = make_stepper(GetParam(), blind, tight());
  Counter c2;
  integrate(*st2, blind, 0.0, y0, 1.0, d, c2);
  EXPECT_TRUE(blind.events.empty()) << "the steps did not cover the excursion: the test proves nothing; steps end at "
                                     << ::testing::PrintToString(c2.seg_end);
}

}  // namespace
}  // namespace machdyn
