// The peak tracker (analysis/peak_tracker.hpp) on a known solution, fed by the one driver: the
// extremes lie between output points and between steps, and the pieces a breakpoint cuts a step
// into must give the same extremes.
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/analysis/peak_tracker.hpp"
#include "machdyn/solve/driver.hpp"
#include "support/oscillator.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

/// y'' = −ω² y, y(0) = 1, y'(0) = 0: y = cos ωt, signal s = 2 y − 0.5 y' (w = [2, −0.5]) =
/// 2 cos ωt + 0.5 ω sin ωt = A cos(ωt − φ) with A = sqrt(4 + ω²/4), tan φ = ω/4: maximum A at
/// t = φ/ω, minimum −A at t = (φ + π)/ω. Optional breakpoints cut the steps into pieces.
using test::Oscillator;

struct Feed final : StepObserver {
  explicit Feed(PeakTracker& p) : peaks(p) {}
  void on_segment(const Stepper& s, double ta, double tb) override { peaks.on_segment(s, ta, tb, {}); }
  void on_event(double, const double*, const std::vector<int>&) override { peaks.restart(); }
  void on_output(double, const double*) override {}
  PeakTracker& peaks;
};

class Peaks : public ::testing::TestWithParam<Method> {};
INSTANTIATE_TEST_SUITE_P(BothIntegrators, Peaks, ::testing::Values(Method::dopri5, Method::bdf));

// Claim: the extremes of a linear signal are located on the dense output to ~1e-8 in value and
// ~1e-6 s in time (a maximum is flat: its time is conditioned by sqrt of the value error), with and
// without breakpoints cutting steps into pieces (0.3 s and one just before the minimum).
TEST_P(Peaks, ExtremesOfAKnownSignal) {
  const double w = 3.0, A = std::sqrt(4 + w * w / 4), phi = std::atan2(w / 2, 2.0);
  for (int cut = 0; cut < 2; ++cut) {
    Oscillator osc(w);
    if (cut) osc.bps = {0.3, (phi + std::numbers::pi) / w - 1e-3};
    StepperOptions o;
    o.rtol = 1e-11;
    o.atol = 1e-13;
    auto st = make_stepper(GetParam(), osc, o);
    const LinearSignals signal({SparseWeights{{0, 1}, {2.0, -0.5}}});
    PeakTracker peaks(2, signal);
    Feed feed(peaks);
    DriveOptions d;
    d.dt_out = 0.5;  // coarse: the extremes are not on the output grid
    const double y0[2] = {1.0, 0.0};
    integrate(*st, osc, 0.0, y0, 1.5, d, feed);
    const double tol = GetParam() == Method::dopri5 ? 1e-8 : 1e-6;
    EXPECT_NEAR(peaks.max(0), A, tol * A) << cut;
    EXPECT_NEAR(peaks.t_max(0), phi / w, 1e-4) << cut;
    EXPECT_NEAR(peaks.min(0), -A, tol * A) << cut;
    EXPECT_NEAR(peaks.t_min(0), (phi + std::numbers::pi) / w, 1e-4) << cut;
  }
}

/// y'' = −ω² y − 2ζω y' from y(0) = 1, y'(0) = 0: ζ > 0 decays (every extremum after the first
/// two lies inside them), ζ < 0 grows (every extremum is a new one).
class Damped final : public EventSystem {
 public:
  Damped(double w, double zeta) : w_(w), z_(zeta) {}
  int size() const override { return 2; }
  void rhs(double, const double* y, double* dy) override {
    dy[0] = y[1];
    dy[1] = -w_ * w_ * y[0] - 2 * z_ * w_ * y[1];
  }

 private:
  double w_, z_;
};

/// s = 2 y − 0.5 y', counting the rate evaluations; `reads_state` declares the rate as reading the
/// state, which keeps the tracker from bounding the signal: it then locates every extremum.
class Counted final : public PeakSignals {
 public:
  explicit Counted(bool reads_state) : reads_(reads_state) {}
  int count() const override { return 1; }
  double value(int j, const double* y) const override { return s_.value(j, y); }
  double rate(int j, const double* y, const double* dy) const override {
    ++rates;
    return s_.rate(j, y, dy);
  }
  bool rate_reads_state(int) const override { return reads_; }
  mutable long rates = 0;

 private:
  bool reads_;
  LinearSignals s_{{SparseWeights{{0, 1}, {2.0, -0.5}}}};
};

struct FeedTwo final : StepObserver {
  void on_segment(const Stepper& s, double ta, double tb) override {
    bounded.on_segment(s, ta, tb, {});
    located.on_segment(s, ta, tb, {});
  }
  void on_output(double, const double*) override {}
  Counted sb{false}, sl{true};
  PeakTracker bounded{2, sb}, located{2, sl};
};

// Claim: not locating the extrema that the dense output's Bernstein bound keeps inside the extremes
// so far changes no reported value or time — the same bits as locating every one — on a decaying
// oscillation (where it skips) and a growing one (where every extremum is a
// new extreme), 20 periods each; with the default degree 6 and, for dopri5, with its own degree 4
// (five samples instead of seven: what a run uses).
TEST_P(Peaks, BoundedExtremaChangeNothing) {
  std::vector<int> degrees{6};
  if (GetParam() == Method::dopri5) degrees.push_back(4);
  for (const int degree : degrees)
    for (const double zeta : {0.02, -0.02}) {
      Damped sys(3.0, zeta);
      StepperOptions o;
      o.rtol = 1e-9;
      o.atol = 1e-12;
      auto st = make_stepper(GetParam(), sys, o);
      FeedTwo feed;
      feed.bounded.set_dense_degree(degree);
      DriveOptions d;
      d.dt_out = 1.0;
      const double y0[2] = {1.0, 0.0};
      integrate(*st, sys, 0.0, y0, 40.0, d, feed);
      EXPECT_EQ(feed.bounded.max(0), feed.located.max(0)) << zeta << " degree " << degree;
      EXPECT_EQ(feed.bounded.t_max(0), feed.located.t_max(0)) << zeta << " degree " << degree;
      EXPECT_EQ(feed.bounded.min(0), feed.located.min(0)) << zeta << " degree " << degree;
      EXPECT_EQ(feed.bounded.t_min(0), feed.located.t_min(0)) << zeta << " degree " << degree;
      // Locating one takes at least one rate evaluation: ≥ 30 of the ~40 extrema were not located.
      if (zeta > 0) EXPECT_GE(feed.sl.rates - feed.sb.rates, 30) << degree;
      else EXPECT_GT(feed.bounded.max(0), 10.0) << degree;  // the growth: e^(ζω·40) ≈ 11
    }
}

/// The decaying oscillation with breakpoints at which a test opens and closes a window.
class DampedCut final : public EventSystem {
 public:
  DampedCut(double w, double zeta, std::vector<double> cuts) : w_(w), z_(zeta), cuts_(std::move(cuts)) {}
  int size() const override { return 2; }
  void rhs(double, const double* y, double* dy) override {
    dy[0] = y[1];
    dy[1] = -w_ * w_ * y[0] - 2 * z_ * w_ * y[1];
  }
  std::vector<double> breakpoints(double, double) const override { return cuts_; }

 private:
  double w_, z_;
  std::vector<double> cuts_;
};

/// Two trackers (bounded and locating every extremum) with a window open over [t1, t2].
struct FeedWindow final : StepObserver {
  FeedWindow(double a, double b) : t1(a), t2(b) {}
  void on_segment(const Stepper& s, double ta, double tb) override {
    bounded.on_segment(s, ta, tb, {});
    located.on_segment(s, ta, tb, {});
  }
  void on_event(double t, const double*, const std::vector<int>&) override {
    bounded.restart(), located.restart();
    if (t == t1) wb = bounded.open_window(t), wl = located.open_window(t);
    if (t == t2) {
      in_bounded = bounded.window(wb), in_located = located.window(wl);
      bounded.close_window(wb), located.close_window(wl);
    }
  }
  void on_output(double, const double*) override {}
  double t1, t2;
  Counted sb{false}, sl{true};
  PeakTracker bounded{2, sb}, located{2, sl};
  int wb = -1, wl = -1;
  PeakTracker::Window in_bounded, in_located;
};

// Claim: a window keeps the extremes of the signal over its own time span — here a local minimum
// of a decaying oscillation inside [t1, t2] that is no extreme of the whole run (the run's minimum
// came one period earlier and was deeper), so the run's Bernstein bound alone would skip it — equal
// to the closed form y = e^(−ζωt) (cos ω_d t + ζω/ω_d sin ω_d t), s = 2 y − 0.5 y', its minimum
// found by bisection on s′ = 0, and bit for bit equal to a tracker that locates every extremum.
TEST_P(Peaks, WindowKeepsTheExtremesOfItsSpan) {
  const double w = 3.0, zeta = 0.02, wd = w * std::sqrt(1 - zeta * zeta);
  auto y = [&](double t) { return std::exp(-zeta * w * t) * (std::cos(wd * t) + zeta * w / wd * std::sin(wd * t)); };
  auto yd = [&](double t) { return -w * w / wd * std::exp(-zeta * w * t) * std::sin(wd * t); };
  auto s = [&](double t) { return 2 * y(t) - 0.5 * yd(t); };
  // s′ = 2 y′ − 0.5 y″ with y″ = −ω² y − 2ζω y′.
  auto sd = [&](double t) { return 2 * yd(t) - 0.5 * (-w * w * y(t) - 2 * zeta * w * yd(t)); };
  const double t1 = 5.0, t2 = 6.3;  // the second minimum of s lies near 5.47 (the first near 1.27)
  double lo = t1 + 0.1, hi = t2 - 0.1;  // s′ < 0 before the minimum, > 0 after it
  ASSERT_LT(sd(lo), 0.0);
  ASSERT_GT(sd(hi), 0.0);
  for (int i = 0; i < 200; ++i) (sd(0.5 * (lo + hi)) < 0 ? lo : hi) = 0.5 * (lo + hi);
  const double t_min = 0.5 * (lo + hi), s_min = s(t_min);
  const double s_max = std::max(s(t1), s(t2)), t_max = s(t1) > s(t2) ? t1 : t2;  // s falls, then rises

  DampedCut sys(w, zeta, {t1, t2});
  StepperOptions o;
  o.rtol = 1e-11;
  o.atol = 1e-13;
  auto st = make_stepper(GetParam(), sys, o);
  FeedWindow feed(t1, t2);
  if (GetParam() == Method::dopri5) feed.bounded.set_dense_degree(4);
  DriveOptions d;
  d.dt_out = 1.0;
  const double y0[2] = {1.0, 0.0};
  integrate(*st, sys, 0.0, y0, 8.0, d, feed);
  ASSERT_EQ(feed.in_bounded.min.size(), 1u);
  const double tol = GetParam() == Method::dopri5 ? 1e-8 : 1e-6;
  EXPECT_LT(feed.bounded.min(0), s_min - 0.1);  // the run's minimum is deeper: the window's is its own
  EXPECT_NEAR(feed.in_bounded.min[0], s_min, tol);
  EXPECT_NEAR(feed.in_bounded.max[0], s_max, tol);
  EXPECT_NEAR(feed.in_bounded.t_max[0], t_max, 1e-12);
  EXPECT_EQ(feed.in_bounded.min[0], feed.in_located.min[0]);
  EXPECT_EQ(feed.in_bounded.max[0], feed.in_located.max[0]);
  EXPECT_EQ(feed.in_bounded.t_max[0], feed.in_located.t_max[0]);
  EXPECT_EQ(feed.bounded.min(0), feed.located.min(0));
  EXPECT_EQ(feed.bounded.max(0), feed.located.max(0));
}

// Claim: a window that saw no value reports max −∞, min +∞ and its opening time; a closed
// window's handle is handed out again.
TEST(PeakTracker, EmptyWindowAndHandleReuse) {
  const LinearSignals signal({SparseWeights{{0}, {1.0}}});
  PeakTracker peaks(1, signal);
  const int a = peaks.open_window(0.5);
  EXPECT_EQ(peaks.window(a).max[0], -std::numeric_limits<double>::infinity());
  EXPECT_EQ(peaks.window(a).min[0], std::numeric_limits<double>::infinity());
  EXPECT_EQ(peaks.window(a).t_max[0], 0.5);
  const int b = peaks.open_window(0.7);
  EXPECT_NE(a, b);
  peaks.close_window(a);
  EXPECT_EQ(peaks.open_window(0.9), a);
}

// Claim: a dense-output degree the tracker has no bound for is refused.
TEST(PeakTracker, RefusesAnUnknownDenseDegree) {
  const LinearSignals signal({SparseWeights{{0}, {1.0}}});
  PeakTracker peaks(1, signal);
  EXPECT_THROW(peaks.set_dense_degree(5), std::invalid_argument);
  EXPECT_NO_THROW(peaks.set_dense_degree(4));
}

}  // namespace
}  // namespace machdyn
