// The Modelica Standard Library examples shipped under examples/msl (docs/msl.md), each run from
// its file and checked against an independent answer: the closed form of every phase (derived in
// the comment over each test) or a semi-analytic solution written here without the library's
// engine. Every example runs on both integrators. CoupledClutches is in clutch_test.cpp, First and
// FirstGrounded in ideal_gear_test.cpp; the one-sided link of ElastoGap and PreLoad has its own
// closed-form tests in one_sided_link_test.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>
#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/rk4.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::max_error;
using test::sci;
using test::series;

class MslExample : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, MslExample, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

Model example(const std::string& name, IntegratorChoice integrator) {
  Model m = load_model(std::string(MACHDYN_SOURCE_DIR) + "/examples/msl/" + name);
  m.simulation.integrator = integrator;
  return m;
}


// ---------------------------------------------------------------------------------------------
// Claim: examples/msl/damper.yaml (MSL Translational.Examples.Damper) follows the closed forms.
// Each mass (m = 1 kg) starts at x = 0 with v0 = 10 m/s.
//   mass1, damper only: m ẍ = −d ẋ  ⇒  v = v0 e^(−k t), x = (v0/k)(1 − e^(−k t)), k = d/m = 25 1/s.
//   mass2 (damper ∥ spring) and mass3 (spring-damper) obey the same m ẍ + d ẋ + c x = 0 with
//   c = 1 N/m: overdamped (d² = 625 > 4 m c = 4), roots r± = (−d ± √(d² − 4 m c))/(2 m), and with
//   x(0) = 0, ẋ(0) = v0: x = v0 (e^(r+ t) − e^(r− t))/(r+ − r−), v = v0 (r+ e^(r+ t) − r− e^(r− t))/(r+ − r−).
// Tolerance: 1e-8 m and 1e-7 m/s at every output row (rtol 1e-10 in the file; the result is 0.4 m, 10 m/s).
TEST_P(MslExample, DamperFollowsTheClosedForms) {
  const SimulationResult r = simulate(example("damper.yaml", GetParam()));
  const double m = 1.0, d = 25.0, c = 1.0, v0 = 10.0, k = d / m;
  const double disc = std::sqrt(d * d - 4 * m * c);
  const double rp = (-d + disc) / (2 * m), rm = (-d - disc) / (2 * m);
  auto x1 = [&](double t) { return v0 / k * (1 - std::exp(-k * t)); };
  auto v1 = [&](double t) { return v0 * std::exp(-k * t); };
  auto x2 = [&](double t) { return v0 * (std::exp(rp * t) - std::exp(rm * t)) / (rp - rm); };
  auto v2 = [&](double t) { return v0 * (rp * std::exp(rp * t) - rm * std::exp(rm * t)) / (rp - rm); };
  EXPECT_LT(max_error(r, "mass1.position_m", x1), 1e-8);
  EXPECT_LT(max_error(r, "mass1.velocity_m_s", v1), 1e-7);
  for (const char* b : {"mass2", "mass3"}) {
    EXPECT_LT(max_error(r, std::string(b) + ".position_m", x2), 1e-8) << b;
    EXPECT_LT(max_error(r, std::string(b) + ".velocity_m_s", v2), 1e-7) << b;
  }
  // The spring keeps mass2 and mass3 short of mass1's end point v0/k = 0.4 m, and pulls them back.
  EXPECT_LT(series(r, "mass2.position_m").back(), x1(1.0));
}

// ---------------------------------------------------------------------------------------------
// Claim: examples/msl/oscillator.yaml (MSL Translational.Examples.Oscillator) follows the closed
// forms of a driven oscillator started at rest, m ẍ + d ẋ + c x = F0 sin Ω t, m = 1 kg,
// c = 10⁴ N/m (ω0 = 100 rad/s), F0 = 1 N, Ω = 2π·15.9155 Hz = 100.0000357 rad/s (just off
// resonance, as in MSL).
//   mass1, d = 0: particular X sin Ω t with X = (F0/m)/(ω0² − Ω²); the free part B sin ω0 t with
//     ẋ(0) = 0 ⇒ B = −X Ω/ω0: x = X (sin Ω t − (Ω/ω0) sin ω0 t). (ω0² − Ω² is formed as
//     (ω0 − Ω)(ω0 + Ω).) Its amplitude grows like F0 t/(2 m ω0): 5 mm at 1 s.
//   mass2, d = 10 N·s/m: particular a sin Ω t + b cos Ω t with D = (ω0² − Ω²)² + (dΩ/m)²,
//     a = (F0/m)(ω0² − Ω²)/D, b = −(F0/m)(dΩ/m)/D; free part e^(−σt)(C cos ω_d t + S sin ω_d t),
//     σ = d/(2m), ω_d = √(ω0² − σ²); x(0) = 0 ⇒ C = −b; ẋ(0) = 0 ⇒ aΩ − σC + ω_d S = 0.
// Tolerance 1e-9 m, 1e-7 m/s at every output row (the amplitudes are 5 mm and 1 mm).
TEST_P(MslExample, OscillatorFollowsTheClosedForms) {
  const SimulationResult r = simulate(example("oscillator.yaml", GetParam()));
  const double m = 1.0, c = 1e4, F0 = 1.0, d = 10.0;
  const double w0 = std::sqrt(c / m), W = 2 * std::numbers::pi * 15.9155;
  const double den = (w0 - W) * (w0 + W);
  const double X = F0 / m / den;
  auto x1 = [&](double t) { return X * (std::sin(W * t) - W / w0 * std::sin(w0 * t)); };
  auto v1 = [&](double t) { return X * W * (std::cos(W * t) - std::cos(w0 * t)); };
  const double D = den * den + (d * W / m) * (d * W / m);
  const double a = F0 / m * den / D, b = -F0 / m * (d * W / m) / D;
  const double sg = d / (2 * m), wd = std::sqrt(w0 * w0 - sg * sg);
  const double C = -b, S = (sg * C - a * W) / wd;
  auto x2 = [&](double t) {
    return a * std::sin(W * t) + b * std::cos(W * t) + std::exp(-sg * t) * (C * std::cos(wd * t) + S * std::sin(wd * t));
  };
  auto v2 = [&](double t) {
    return a * W * std::cos(W * t) - b * W * std::sin(W * t) +
           std::exp(-sg * t) * ((-sg * C + wd * S) * std::cos(wd * t) + (-sg * S - wd * C) * std::sin(wd * t));
  };
  EXPECT_LT(max_error(r, "mass1.position_m", x1), 1e-9);
  EXPECT_LT(max_error(r, "mass1.velocity_m_s", v1), 1e-7);
  EXPECT_LT(max_error(r, "mass2.position_m", x2), 1e-9);
  EXPECT_LT(max_error(r, "mass2.velocity_m_s", v2), 1e-7);
  // Near resonance: mass1's swing at 1 s is close to F0 t/(2 m ω0) = 5 mm; mass2's is near F0/(d Ω) = 1 mm.
  double peak1 = 0, peak2 = 0;
  const auto& ts = series(r, "t_s");
  for (size_t i = 0; i < ts.size(); ++i)
    if (ts[i] > 0.9) {
      peak1 = std::max(peak1, std::abs(series(r, "mass1.position_m")[i]));
      peak2 = std::max(peak2, std::abs(series(r, "mass2.position_m")[i]));
    }
  EXPECT_NEAR(peak1, F0 * 1.0 / (2 * m * w0), 0.05 * F0 / (2 * m * w0));
  EXPECT_NEAR(peak2, F0 / (d * W), 0.01 * F0 / (d * W));
}

// ---------------------------------------------------------------------------------------------
// Claim: examples/msl/brake.yaml (MSL Translational.Examples.Brake): both masses (m = 1 kg,
// v0 = 1 m/s) coast to t1 = 0.1 s (x = 0.1 m), then slide against F = μ fn = 0.5 · 2 N = 1 N:
// v = v0 − (F/m)(t − t1), x = t1 v0 + v0 (t − t1) − F/(2m) (t − t1)², until v = 0 at
// t_s = t1 + m v0/F = 1.1 s, x = 0.1 + 0.5 = 0.6 m; stuck after (no load), both brakes alike.
TEST_P(MslExample, BrakeStopsAtTheClosedFormInstant) {
  const SimulationResult r = simulate(example("brake.yaml", GetParam()));
  const double m = 1.0, v0 = 1.0, t1 = 0.1, F = 0.5 * 2.0, ts = t1 + m * v0 / F;
  auto v = [&](double t) { return t < t1 ? v0 : t < ts ? v0 - F / m * (t - t1) : 0.0; };
  auto x = [&](double t) {
    const double s = std::min(std::max(t - t1, 0.0), ts - t1);
    return std::min(t, t1) * v0 + v0 * s - F / (2 * m) * s * s;
  };
  for (const char* b : {"mass1", "mass2"}) {
    EXPECT_LT(max_error(r, std::string(b) + ".velocity_m_s", v), 1e-9) << b;
    EXPECT_LT(max_error(r, std::string(b) + ".position_m", x), 1e-9) << b;
  }
  int stuck = 0;
  for (const auto& e : r.hybrid.events)
    if (e.kind == "stick") {
      ++stuck;
      EXPECT_NEAR(e.t, ts, 1e-9) << e.element;
    }
  EXPECT_EQ(stuck, 2);
  EXPECT_NEAR(series(r, "mass1.position_m").back(), 0.6, 1e-9);
}

// ---------------------------------------------------------------------------------------------
// An independent integration of one inertia J on a backlash link to the ground (MSL Backlash),
// written from MSL's torque laws as functions of the state, not from the library's engine:
// e = φ − s b/2 past the flank s = ±1,
//   ElastoBacklash:  τ = c e + min(c e, d ω) (s = +1) or c e + max(c e, d ω) (s = −1), 0 once c e + d ω ≤ 0 (≥ 0);
//   ElastoBacklash2: τ = c e + d ω, with the same cut-off; inside the gap τ = 0; J φ̈ = −τ.
// Fixed-step RK4 (h = 1e-5 s) with the contact state held along a step; a step in which the
// contact starts (beyond a flank and pressing, s (c e + d ω) > 0) or ends (s (c e + d ω) < 0) is
// shortened by bisection to the switching instant, so the jump of ElastoBacklash2's torque at
// contact falls between steps. (ElastoBacklash's torque is continuous; its cap is a kink.)
struct BacklashReference {
  double J = 5, c = 20e3, d = 50, half = std::numbers::pi / 8;
  bool capped = true;
  int s = 0;  // contact: +1, −1, or 0 (in the gap)
  std::vector<double> contact_times;

  double torque(int sc, double phi, double w) const {
    if (sc == 0) return 0.0;
    const double e = phi - sc * half, tc = c * e, td = d * w;
    if (!capped) return tc + td;
    return sc > 0 ? tc + std::min(tc, td) : tc + std::max(tc, td);
  }
  bool switches(double phi, double w) const {
    if (s != 0) return s * (c * (phi - s * half) + d * w) < 0;
    const int side = phi > half ? 1 : phi < -half ? -1 : 0;
    return side != 0 && side * (c * (phi - side * half) + d * w) > 0;
  }
  std::array<double, 2> step(const std::array<double, 2>& y, double h) const {
    auto f = [&](const std::array<double, 2>& x) { return std::array<double, 2>{x[1], -torque(s, x[0], x[1]) / J}; };
    const auto k1 = f(y);
    const auto k2 = f({y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]});
    const auto k3 = f({y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]});
    const auto k4 = f({y[0] + h * k3[0], y[1] + h * k3[1]});
    return {y[0] + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]), y[1] + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])};
  }
  /// (φ, ω) on the grid k dt, k = 0 … n, from rest at φ0 (on a flank or in the gap).
  std::vector<std::array<double, 2>> run(double phi0, double dt, int n) {
    std::array<double, 2> y{phi0, 0.0};
    s = phi0 > half ? 1 : phi0 < -half ? -1 : 0;
    std::vector<std::array<double, 2>> out{y};
    double t = 0;
    for (int k = 1; k <= n; ++k) {
      const double stop = k * dt;
      while (t < stop) {
        double h = std::min(1e-5, stop - t);
        auto y1 = step(y, h);
        if (switches(y1[0], y1[1])) {
          double lo = 0, hi = h;  // the first instant at which the contact state is wrong
          for (int it = 0; it < 80 && std::nextafter(lo, hi) < hi; ++it) {
            const double mid = 0.5 * (lo + hi);
            const auto ym = step(y, mid);
            (switches(ym[0], ym[1]) ? hi : lo) = mid;
          }
          h = hi;
          y1 = step(y, h);
          s = s != 0 ? 0 : (y1[0] > 0 ? 1 : -1);
          if (s != 0) contact_times.push_back(t + h);
        }
        y = y1;
        t += h;
      }
      out.push_back(y);
    }
    return out;
  }
};

// Claim: examples/msl/backlash.yaml (MSL Rotational.Examples.Backlash) follows
//   inertia1: the damped oscillation J φ̈ + d φ̇ + c φ = 0 from φ0 = π/2 at rest,
//     φ = e^(−σt) φ0 (cos ω_d t + (σ/ω_d) sin ω_d t), σ = d/(2J) = 5 1/s, ω_d = √(c/J − σ²);
//   inertia2 (ElastoBacklash) and inertia3 (ElastoBacklash2): the independent integration above,
// within 1e-6 rad and 1e-5 rad/s at every output row, with the same contact instants. MSL's point
// is visible too: the capped law (inertia2) loses less energy per impact than ElastoBacklash2
// (inertia3), whose torque jumps by d ω at contact, so inertia2 swings wider at the end.
TEST_P(MslExample, BacklashFollowsIndependentSolutions) {
  const SimulationResult r = simulate(example("backlash.yaml", GetParam()));
  const double J = 5, c = 20e3, d = 50, phi0 = std::numbers::pi / 2;
  const double sg = d / (2 * J), wd = std::sqrt(c / J - sg * sg);
  auto x1 = [&](double t) { return std::exp(-sg * t) * phi0 * (std::cos(wd * t) + sg / wd * std::sin(wd * t)); };
  auto v1 = [&](double t) { return -std::exp(-sg * t) * phi0 * (sg * sg / wd + wd) * std::sin(wd * t); };
  EXPECT_LT(max_error(r, "inertia1.position_rad", x1), 1e-8);
  EXPECT_LT(max_error(r, "inertia1.velocity_rad_s", v1), 1e-6);

  const auto& ts = series(r, "t_s");
  ASSERT_EQ(ts.size(), 1001u);
  double amp[2] = {0, 0};
  for (int k = 0; k < 2; ++k) {
    BacklashReference ref;
    ref.capped = k == 0;
    const auto y = ref.run(phi0, 1e-3, 1000);
    const std::string b = k == 0 ? "inertia2" : "inertia3";
    const std::string link = k == 0 ? "elastoBacklash" : "elastoBacklash2";
    const auto& q = series(r, b + ".position_rad");
    const auto& w = series(r, b + ".velocity_rad_s");
    double eq = 0, ew = 0;
    for (size_t i = 0; i < ts.size(); ++i) {
      eq = std::max(eq, std::abs(q[i] - y[i][0]));
      ew = std::max(ew, std::abs(w[i] - y[i][1]));
      if (ts[i] > 0.8) amp[k] = std::max(amp[k], std::abs(q[i]));
    }
    EXPECT_LT(eq, 1e-6) << b;
    EXPECT_LT(ew, 1e-5) << b;
    std::vector<double> got;
    for (const auto& e : r.hybrid.events)
      if (e.element == link && e.kind == "gap_closed") got.push_back(e.t);
    ASSERT_EQ(got.size(), ref.contact_times.size()) << b;
    for (size_t i = 0; i < got.size(); ++i) EXPECT_NEAR(got[i], ref.contact_times[i], 1e-8) << b << " contact " << i;
  }
  EXPECT_GT(amp[0], amp[1]);
}

// ---------------------------------------------------------------------------------------------
// An independent solution of MSL OneWayClutch, written from the MSL parameters: two unit inertias,
// a (inertiaIn) driven by M(t) = 10 sin(6π t) N·m, b (inertiaOut); the relative speed
// g = ω_b − ω_a ≥ 0 (b may overrun a). The clutch is applied by u(t) = 1 on [0.3, 0.95) and
// [1.6, 2.25) s, else 0: sliding torque F_k = 1.5 u N·m, stuck limit F_s = 37.5 u N·m.
//   Sliding (g > 0): ω_a = ω_a0 + P(t) − P(t0) + F_k (t − t0), ω_b = ω_b0 − F_k (t − t0), with
//     P(t) = −(10/(6π)) cos(6π t) the integral of M; it locks where g falls to 0.
//   Locked: ω = ω0 + (P(t) − P(t0))/2; b is carried by λ = J_b ω̇ = M/2 (a pushes b forward: λ > 0
//     held by the freewheel without limit; λ < 0 only by the clutch, up to F_s). It releases
//     where M/2 + F_s turns negative.
// Each phase is in closed form; its end is the first sign change of its event function on a scan
// of 1e-4 s, bisected to the last bit; the phases also end at the edges of u. At an edge while
// locked the lock is kept if λ ≥ −F_s.
struct OneWayClutchReference {
  static constexpr double kTwoPi = 2 * std::numbers::pi;
  static double M(double t) { return 10 * std::sin(3 * kTwoPi * t); }
  static double P(double t) { return -10 / (3 * kTwoPi) * std::cos(3 * kTwoPi * t); }
  static double u(double t) {
    return (t >= 0.3 && t < 0.95) || (t >= 1.6 && t < 2.25) ? 1.0 : 0.0;  // the pulse's windows before 2.9 s
  }
  struct Phase {
    double t0, t1;
    bool locked;
    double wa0, wb0, Fk;
  };
  std::vector<Phase> phases;
  std::vector<double> lock_times, release_times;

  static double wa(const Phase& p, double t) {
    return p.locked ? p.wa0 + (P(t) - P(p.t0)) / 2 : p.wa0 + P(t) - P(p.t0) + p.Fk * (t - p.t0);
  }
  static double wb(const Phase& p, double t) {
    return p.locked ? p.wa0 + (P(t) - P(p.t0)) / 2 : p.wb0 - p.Fk * (t - p.t0);
  }
  /// The event function of phase p at t: g while sliding, M/2 + F_s while locked (F_s of the phase).
  static double event(const Phase& p, double t) { return p.locked ? M(t) / 2 + 37.5 * u(p.t0) : wb(p, t) - wa(p, t); }

  void run(double t_end) {
    const std::vector<double> edges{0.3, 0.95, 1.6, 2.25};
    double t = 0, a = -0.5, b = 0.0;
    bool locked = false;
    while (t < t_end) {
      double edge = t_end;
      for (double e : edges)
        if (e > t) {
          edge = std::min(edge, e);
          break;
        }
      Phase p{t, edge, locked, a, b, 1.5 * u(t)};
      // Scan for the first sign change after t (the start itself may be a zero of g).
      const double h = 1e-4;
      double lo = t, end = edge;
      bool hit = false;
      for (double s = t + h;; s += h) {
        const double s1 = std::min(s, edge);
        if (event(p, s1) < 0) {
          double x0 = lo, x1 = s1;
          while (x1 - x0 > 0 && std::nextafter(x0, x1) < x1) {
            const double mid = 0.5 * (x0 + x1);
            (event(p, mid) < 0 ? x1 : x0) = mid;
          }
          end = x1;
          hit = true;
          break;
        }
        lo = s1;
        if (s1 >= edge) break;
      }
      p.t1 = end;
      phases.push_back(p);
      a = wa(p, end);
      b = wb(p, end);
      t = end;
      if (hit) {
        locked = !locked;
        if (locked) b = a;
        (locked ? lock_times : release_times).push_back(end);
      } else if (locked && t < t_end && M(t) / 2 < -37.5 * u(t)) {
        locked = false;  // an edge of u (the clutch opens) while b is held back
        release_times.push_back(t);
      }
    }
  }
  /// Speeds (ω_a, ω_b) at t.
  std::pair<double, double> at(double t) const {
    for (const auto& p : phases)
      if (t <= p.t1) return {wa(p, t), wb(p, t)};
    return {NAN, NAN};
  }
};

// Claim: examples/msl/one-way-clutch.yaml (MSL Rotational.Examples.OneWayClutch, a freewheel and a
// clutch in parallel) has the speeds of the independent solution above within 1e-7 rad/s (dopri5)
// or 1e-5 rad/s (bdf) at every output row. The sequence: overrun with the clutch open until the
// input catches up and locks (0.080 s), release when the torque turns negative at 1/6 s, the
// clutch drags the pair together after 0.3 s and holds them (|λ| ≤ 5 < 37.5 N·m) until it opens
// at 0.95 s under a negative torque; lock again at 1.067 s, release at 7/6 s, clutch from 1.6 s.
TEST_P(MslExample, OneWayClutchMatchesAnIndependentSolution) {
  const SimulationResult r = simulate(example("one-way-clutch.yaml", GetParam()));
  OneWayClutchReference ref;
  ref.run(2.0);
  ASSERT_GE(ref.lock_times.size(), 3u);
  EXPECT_NEAR(ref.lock_times[0], std::acos(1 - 0.5 * 3 * OneWayClutchReference::kTwoPi / 10) / (3 * OneWayClutchReference::kTwoPi), 1e-12);
  ASSERT_GE(ref.release_times.size(), 2u);
  EXPECT_NEAR(ref.release_times[0], 1.0 / 6, 1e-12);
  EXPECT_DOUBLE_EQ(ref.release_times[1], 0.95);
  const double tol = GetParam() == IntegratorChoice::dopri5 ? 1e-7 : 1e-5;
  EXPECT_LT(max_error(r, "inertiaIn.velocity_rad_s", [&](double t) { return ref.at(t).first; }), tol);
  EXPECT_LT(max_error(r, "inertiaOut.velocity_rad_s", [&](double t) { return ref.at(t).second; }), tol);
  // The locking instants: the freewheel sticks where the reference's phases lock.
  std::vector<double> locks;
  for (const auto& e : r.hybrid.events)
    if (e.element == "freewheel" && e.kind == "stick") locks.push_back(e.t);
  ASSERT_EQ(locks.size(), ref.lock_times.size());
  for (size_t i = 0; i < locks.size(); ++i) EXPECT_NEAR(locks[i], ref.lock_times[i], 1e-8) << "lock " << i;
}

// ---------------------------------------------------------------------------------------------
// Claim (the share of a redundant stuck pair, analysis/drive_system.hpp): in one-way-clutch.yaml,
// while the clutch holds the two inertias together the freewheel in parallel is stuck too — never
// labelled as slipping with zero sliding speed — and carries no load against its lock: its force
// is ≥ 0 at every row, and where both are stuck the two forces add up to the load that keeps
// inertiaOut with inertiaIn, λ = J_out ω̇ = M(t)/2 (M = 10 sin 6πt N·m on inertiaIn, equal inertias),
// all of it on the clutch when M < 0. Before the fix the freewheel went stuck → slip at 0.5 s
// (M turning negative) and stayed "slip-" with u ≡ 0 until the clutch opened at 0.95 s.
TEST_P(MslExample, OneWayClutchFreewheelStaysStuckWhileTheClutchHolds) {
  const SimulationResult r = simulate(example("one-way-clutch.yaml", GetParam()));
  const auto& ts = series(r, "t_s");
  const auto& cm = series(r, "clutch.mode");
  const auto& fm = series(r, "freewheel.mode");
  const auto& cf = series(r, "clutch.force_N_m");
  const auto& ff = series(r, "freewheel.force_N_m");
  int held = 0, held_negative = 0;
  for (size_t i = 0; i < ts.size(); ++i) {
    EXPECT_GE(ff[i], 0.0) << "t = " << ts[i];
    if (cm[i] != 0.0) continue;
    ++held;
    EXPECT_EQ(fm[i], 0.0) << "freewheel not stuck at t = " << ts[i] << " while the clutch holds";
    const double M = 10 * std::sin(6 * std::numbers::pi * ts[i]);
    EXPECT_NEAR(cf[i] + ff[i], M / 2, 1e-9) << "t = " << ts[i];
    if (M < 0) {
      ++held_negative;
      EXPECT_NEAR(cf[i], M / 2, 1e-9) << "t = " << ts[i];
    }
  }
  EXPECT_GT(held, 500);          // [0.4307, 0.95) and [1.7562, 2] s
  EXPECT_GT(held_negative, 300);  // M < 0 on (0.5, 0.6667) and (0.8333, 0.95) s, (1.8333, 2) s
  // No freewheel slip event at an instant where the clutch stays stuck.
  for (const auto& e : r.hybrid.events) {
    if (e.element != "freewheel" || e.kind != "slip") continue;
    const size_t i = static_cast<size_t>(std::lround(e.t / 1e-3));
    if (i + 1 < ts.size()) {
      EXPECT_NE(cm[i + 1], 0.0) << "freewheel slips at " << e.t << " while the clutch holds";
    }
  }
}

// ---------------------------------------------------------------------------------------------
// An independent solution of MSL OneWayClutchDisengaged: inertiaIn a and inertiaOut b (J = 1 kg·m²
// each), M(t) = 0.3 + 10 sin(4π t) N·m on a, the constant −0.3 N·m on b, only the freewheel
// (g = ω_b − ω_a ≥ 0). Phases in closed form, P(t) = −(10/(4π)) cos(4π t):
//   free (g > 0):  ω_a = ω_a0 + 0.3 (t − t0) + P(t) − P(t0),  ω_b = ω_b0 − 0.3 (t − t0); it locks
//                  where g falls to 0;
//   locked:        2 ω̇ = M − 0.3 = 10 sin 4πt  ⇒  ω = ω0 + (P(t) − P(t0))/2; the freewheel carries
//                  λ = J_b ω̇ + 0.3 = 0.3 + 5 sin(4π t) ≥ 0 and releases where it turns negative,
//                  at t = k/2 + 1/4 + asin(0.06)/(4π).
// Each phase ends at the first sign change of its event function on a 1e-4 s scan, bisected to the
// last bit.
struct DisengagedReference {
  static constexpr double kW = 4 * std::numbers::pi;
  static double P(double t) { return -10 / kW * std::cos(kW * t); }
  struct Phase {
    double t0, t1, wa0, wb0;
    bool locked;
  };
  std::vector<Phase> phases;
  std::vector<double> lock_times, release_times;
  static double wa(const Phase& p, double t) {
    return p.locked ? p.wa0 + (P(t) - P(p.t0)) / 2 : p.wa0 + 0.3 * (t - p.t0) + P(t) - P(p.t0);
  }
  static double wb(const Phase& p, double t) { return p.locked ? wa(p, t) : p.wb0 - 0.3 * (t - p.t0); }
  static double event(const Phase& p, double t) { return p.locked ? 0.3 + 5 * std::sin(kW * t) : wb(p, t) - wa(p, t); }
  void run(double t_end) {
    double t = 0, a = -0.5, b = 0.0;
    bool locked = false;
    while (t < t_end) {
      Phase p{t, t_end, a, b, locked};
      double lo = t, end = t_end;
      bool hit = false;
      for (double s = t + 1e-4;; s += 1e-4) {
        const double s1 = std::min(s, t_end);
        if (event(p, s1) < 0) {
          double x0 = lo, x1 = s1;
          while (std::nextafter(x0, x1) < x1) {
            const double mid = 0.5 * (x0 + x1);
            (event(p, mid) < 0 ? x1 : x0) = mid;
          }
          end = x1;
          hit = true;
          break;
        }
        lo = s1;
        if (s1 >= t_end) break;
      }
      p.t1 = end;
      phases.push_back(p);
      a = wa(p, end);
      b = wb(p, end);
      t = end;
      if (!hit) break;
      locked = !locked;
      (locked ? lock_times : release_times).push_back(end);
    }
  }
  std::pair<double, double> at(double t) const {
    for (const auto& p : phases)
      if (t <= p.t1) return {wa(p, t), wb(p, t)};
    return {NAN, NAN};
  }
};

// Claim: examples/msl/one-way-clutch-disengaged.yaml (MSL Rotational.Examples.OneWayClutchDisengaged)
// has the speeds of the independent solution above within 1e-7 rad/s (dopri5) or 1e-5 rad/s (bdf)
// at every output row, locks where it locks (within 1e-8 s) and releases at the closed-form
// instants k/2 + 1/4 + asin(0.06)/(4π) (within 1e-9 s).
TEST_P(MslExample, OneWayClutchDisengagedMatchesAnIndependentSolution) {
  const SimulationResult r = simulate(example("one-way-clutch-disengaged.yaml", GetParam()));
  DisengagedReference ref;
  ref.run(2.0);
  ASSERT_EQ(ref.lock_times.size(), 4u);
  ASSERT_EQ(ref.release_times.size(), 4u);
  const double tol = GetParam() == IntegratorChoice::dopri5 ? 1e-7 : 1e-5;
  EXPECT_LT(max_error(r, "inertiaIn.velocity_rad_s", [&](double t) { return ref.at(t).first; }), tol);
  EXPECT_LT(max_error(r, "inertiaOut.velocity_rad_s", [&](double t) { return ref.at(t).second; }), tol);
  std::vector<double> locks, releases;
  for (const auto& e : r.hybrid.events)
    if (e.element == "freewheel") {
      if (e.kind == "stick") locks.push_back(e.t);
      if (e.kind == "slip") releases.push_back(e.t);
    }
  ASSERT_EQ(locks.size(), ref.lock_times.size());
  for (size_t i = 0; i < locks.size(); ++i) EXPECT_NEAR(locks[i], ref.lock_times[i], 1e-8) << "lock " << i;
  ASSERT_EQ(releases.size(), 4u);
  for (size_t k = 0; k < releases.size(); ++k) {
    const double closed = 0.5 * static_cast<double>(k) + 0.25 + std::asin(0.06) / DisengagedReference::kW;
    EXPECT_NEAR(releases[k], closed, 1e-9) << "release " << k;
    EXPECT_NEAR(ref.release_times[k], closed, 1e-12) << "reference release " << k;
  }
}

// ---------------------------------------------------------------------------------------------
// An independent integration of one MSL MassWithStopAndFriction (Translational Friction example),
// written from MSL's equations as functions of the state, not from the library's engine:
//   m ẍ = F(t) − c x − F_prop ẋ − f,   sliding in direction s = sign ẋ: f = s (F_C + F_S e^(−fexp |ẋ|));
//   stuck (ẋ ≡ 0) while |F(t) − c x| ≤ f0_max = peak (F_C + F_S) (peak = 1.001, MSL's default), on a
//   stop while the net force presses it on (or is within f0_max pulling it off); reaching a stop: x set on the stop, ẋ = 0 (MSL's reinit).
// At ẋ = 0 (end of a slide or an impact) the next mode is decided from the net force n = F − c x:
// stuck within the limit, else sliding in the direction of n. Fixed-step RK4 (h = 1e-5 s) with the
// mode held along a step; a step at whose end an event function of the mode is negative (sliding:
// s ẋ and the distance to the stop ahead; stuck: the margin to the limit) is shortened by bisection
// to the switching instant.
struct StopFrictionReference {
  double m = 1, c = 0, d = 1, Fc = 0, FS = 0, fexp = 2, xmin = 0, xmax = 0, peak = 1.001;
  double (*F)(double) = nullptr;
  int s = 0;  // +1, −1 sliding; 0 stuck
  std::vector<double> stick_times, impact_times;

  double limit() const { return peak * (Fc + FS); }  // MSL's f0_max = peak f0
  double acc(int md, double t, double x, double v) const {
    if (md == 0) return 0.0;
    return (F(t) - c * x - d * v - md * (Fc + FS * std::exp(-fexp * std::abs(v)))) / m;
  }
  double margin(double t, double x) const {
    const double n = F(t) - c * x;
    if (x >= xmax) return limit() + n;
    if (x <= xmin) return limit() - n;
    return limit() - std::abs(n);
  }
  /// The smallest event function of the current mode at (t, x, v).
  double event(double t, double x, double v) const {
    if (s == 0) return margin(t, x);
    return std::min(s * v, s > 0 ? xmax - x : x - xmin);
  }
  int decide(double t, double x) const {
    if (margin(t, x) >= 0) return 0;
    return F(t) - c * x > 0 ? 1 : -1;
  }
  std::array<double, 2> step(const std::array<double, 2>& y, double t, double h) const {
    auto f = [&](double tt, const std::array<double, 2>& z) { return std::array<double, 2>{s == 0 ? 0.0 : z[1], acc(s, tt, z[0], z[1])}; };
    const auto k1 = f(t, y);
    const auto k2 = f(t + h / 2, {y[0] + 0.5 * h * k1[0], y[1] + 0.5 * h * k1[1]});
    const auto k3 = f(t + h / 2, {y[0] + 0.5 * h * k2[0], y[1] + 0.5 * h * k2[1]});
    const auto k4 = f(t + h, {y[0] + h * k3[0], y[1] + h * k3[1]});
    return {y[0] + h / 6 * (k1[0] + 2 * k2[0] + 2 * k3[0] + k4[0]), y[1] + h / 6 * (k1[1] + 2 * k2[1] + 2 * k3[1] + k4[1])};
  }
  /// (x, ẋ) on the grid k dt, k = 0 … n.
  std::vector<std::array<double, 2>> run(double x0, double v0, double dt, int n) {
    std::array<double, 2> y{x0, v0};
    s = v0 > 0 ? 1 : v0 < 0 ? -1 : decide(0.0, x0);
    std::vector<std::array<double, 2>> out{y};
    double t = 0;
    for (int k = 1; k <= n; ++k) {
      const double stop = k * dt;
      while (t < stop) {
        double h = std::min(1e-5, stop - t);
        auto y1 = step(y, t, h);
        if (event(t + h, y1[0], y1[1]) < 0) {
          double lo = 0, hi = h;
          for (int it = 0; it < 100 && std::nextafter(lo, hi) < hi; ++it) {
            const double mid = 0.5 * (lo + hi);
            const auto ym = step(y, t, mid);
            (event(t + mid, ym[0], ym[1]) < 0 ? hi : lo) = mid;
          }
          h = hi;
          y1 = step(y, t, h);
          if (s == 0) {
            s = F(t + h) - c * y1[0] > 0 ? 1 : -1;  // breaks away
          } else {
            if ((s > 0 ? xmax - y1[0] : y1[0] - xmin) < 0) {
              y1[0] = s > 0 ? xmax : xmin;  // reaches the stop: reinit
              impact_times.push_back(t + h);
            }
            y1[1] = 0.0;
            s = decide(t + h, y1[0]);
            if (s == 0) stick_times.push_back(t + h);
          }
        }
        y = y1;
        t += h;
      }
      out.push_back(y);
    }
    return out;
  }
};

double sine_force(double t) { return 25 * std::sin(2 * std::numbers::pi * 0.25 * t); }
double no_force(double) { return 0.0; }

// Claim: examples/msl/friction.yaml (MSL Translational.Examples.Friction, parts stop1 and stop2)
// follows the independent integration above, with MSL's peak 1.001 (stop2's reference in x = s +
// 0.25 m, its spring unstretched at x = 0; the file has MSL's s and the spring's free length):
// positions within 1e-6 m and velocities within 1e-5 m/s at every output row, the same instants of
// sticking (within 1e-8 s). stop2 hits its lower stop once (at 0.0606 s, from −6.2 m/s) and is
// pushed off at once by the spring (75 N > 8.008 N).
TEST_P(MslExample, TranslationalFrictionFollowsAnIndependentSolution) {
  const SimulationResult r = simulate(example("friction.yaml", GetParam()));
  const auto& ts = series(r, "t_s");
  ASSERT_EQ(ts.size(), 5001u);
  for (int k = 0; k < 2; ++k) {
    StopFrictionReference ref;
    if (k == 0) ref.c = 0, ref.Fc = 5, ref.FS = 10, ref.xmin = -24.5, ref.xmax = 24.5, ref.F = sine_force;
    else ref.c = 500, ref.Fc = 3, ref.FS = 5, ref.xmin = -0.15, ref.xmax = 0.65, ref.F = no_force;
    const auto y = k == 0 ? ref.run(0.0, 0.0, 1e-3, 5000) : ref.run(0.25, -5.0, 1e-3, 5000);
    const std::string b = k == 0 ? "stop1" : "stop2", fr = k == 0 ? "friction1" : "friction2";
    const auto& q = series(r, b + ".position_m");
    const auto& w = series(r, b + ".velocity_m_s");
    double eq = 0, ew = 0;
    const double shift = k == 0 ? 0.0 : 0.25;  // s = x − 0.25 m for stop2
    for (size_t i = 0; i < ts.size(); ++i) {
      eq = std::max(eq, std::abs(q[i] - (y[i][0] - shift)));
      ew = std::max(ew, std::abs(w[i] - y[i][1]));
    }
    EXPECT_LT(eq, 1e-6) << b;
    EXPECT_LT(ew, 1e-5) << b;
    RecordProperty(b + "_position_error", sci(eq));
    RecordProperty(b + "_velocity_error", sci(ew));
    std::vector<double> sticks;
    for (const auto& e : r.hybrid.events)
      if (e.element == fr && e.kind == "stick") sticks.push_back(e.t);
    ASSERT_EQ(sticks.size(), ref.stick_times.size()) << b;
    double et = 0;
    for (size_t i = 0; i < sticks.size(); ++i) {
      EXPECT_NEAR(sticks[i], ref.stick_times[i], 1e-8) << b << " stick " << i;
      et = std::max(et, std::abs(sticks[i] - ref.stick_times[i]));
    }
    RecordProperty(b + "_stick_time_error", sci(et));
    if (k == 1) {
      ASSERT_EQ(ref.impact_times.size(), 1u);
      EXPECT_NEAR(ref.impact_times[0], 0.0606, 1e-3);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// An independent solution of MSL Rotational.Examples.Friction, written from MSL's equations as
// functions of the state, not from the library's engine. Bodies 3 (J3 = 1), 2 (J2 = 0.05), 1 (J1 = 1)
// in a row; τ = 200 sin(100 t) N·m on 3 until 0.5 s, 0 after; the clutch between 3 and 2 (80 N·m
// sliding and holding), the spring-damper T_s = c (φ2 − φ1) + d (ω2 − ω1) between 2 and 1, the brake
// of 1 (released before 0.5 s, 800 N·m after):
//   J3 ω̇3 = τ − T_c,   J2 ω̇2 = T_c − T_s,   J1 ω̇1 = T_s − T_b.
// Sliding, T_c = 80 sign(ω3 − ω2) and T_b = 800 sign ω1. Stuck, the torque that keeps the element
// stuck: the clutch T_c = (J2 τ + J3 T_s)/(J2 + J3) (equal accelerations (τ − T_s)/(J2 + J3)), the
// brake T_b = T_s (ω1 ≡ 0). The two stuck torques depend on no acceleration of the other element,
// so each element is decided on its own, though their motions are coupled through the spring.
// Events (≥ 0 while the mode holds): sliding s (relative speed), stuck 80 − |T_c| or 800 − |T_b|.
// Fixed-step RK4 (h = 1e-5 s, steps end on 0.5 s), a step in which an event function turns
// negative bisected to its instant; there a slide that ends sets the speeds equal (momentum kept)
// and the element sticks if its stuck torque is within the limit, else slides in that torque's
// direction; a stuck element that is overloaded slides in the direction of its torque.
struct RotationalFrictionReference {
  static constexpr double J3 = 1, J2 = 0.05, J1 = 1, c = 160, d = 1, Tc = 80, Tb = 800, t_off = 0.5;
  int mc = 1, mb = 2;  // clutch: 0 stuck, ±1 sliding; brake: the same, 2 released
  struct Event {
    double t;
    std::string element, kind;
  };
  std::vector<Event> events;
  using Y = std::array<double, 6>;  // φ3, ω3, φ2, ω2, φ1, ω1

  static double tau(double t, bool off) { return off ? 0.0 : 200 * std::sin(100 * t); }
  static double spring(const Y& y) { return c * (y[2] - y[4]) + d * (y[3] - y[5]); }
  static double clutch_stuck(double t, bool off, const Y& y) { return (J2 * tau(t, off) + J3 * spring(y)) / (J2 + J3); }
  Y rate(double t, bool off, const Y& y) const {
    const double Ts = spring(y), M = tau(t, off);
    double a3, a2;
    if (mc == 0) a3 = a2 = (M - Ts) / (J2 + J3);
    else a3 = (M - Tc * mc) / J3, a2 = (Tc * mc - Ts) / J2;
    const double a1 = mb == 0 ? 0.0 : (Ts - (mb == 2 ? 0.0 : Tb * mb)) / J1;
    return {y[1], a3, y[3], a2, mb == 0 ? 0.0 : y[5], a1};
  }
  double event(double t, bool off, const Y& y) const {
    const double ec = mc == 0 ? Tc - std::abs(clutch_stuck(t, off, y)) : mc * (y[1] - y[3]);
    const double eb = mb == 2 ? 1.0 : mb == 0 ? Tb - std::abs(spring(y)) : mb * y[5];
    return std::min(ec, eb);
  }
  Y step(double t, bool off, const Y& y, double h) const {
    return test::rk4_step([this, off](double s, const Y& z) { return rate(s, off, z); }, t, y, h);
  }
  void record(double t, const char* element, int from, int to) {
    events.push_back({t, element, to == 0 ? "stick" : from == 0 ? "slip" : "reversal"});
  }
  /// Re-decides the elements whose event function is negative (or, at 0.5 s, the brake applied).
  void decide(double t, bool off, Y& y) {
    const int oc = mc, ob = mb;
    if (mc != 0 && mc * (y[1] - y[3]) <= 0) {  // the slide ended: equal speeds
      y[1] = y[3] = (J3 * y[1] + J2 * y[3]) / (J3 + J2);
      mc = 0;
    }
    if (mc == 0 && std::abs(clutch_stuck(t, off, y)) > Tc) mc = clutch_stuck(t, off, y) > 0 ? 1 : -1;
    if (mb == 1 || mb == -1) {
      if (mb * y[5] <= 0) y[5] = 0.0, mb = 0;
    }
    if (mb == 0 && std::abs(spring(y)) > Tb) mb = spring(y) > 0 ? 1 : -1;
    if (mc != oc) record(t, "clutch", oc, mc);
    if (mb != ob && ob != 2) record(t, "brake", ob, mb);
  }
  /// The state at k dt, k = 0 … n.
  std::vector<Y> run(double dt, int n) {
    Y y{0, 100, 0, 90, 0, 90};
    std::vector<Y> out{y};
    double t = 0;
    for (int k = 1; k <= n; ++k) {
      const double stop = k * dt;
      const bool off = stop > t_off;  // the output grid holds 0.5 s: no interval crosses it
      if (off && mb == 2) {           // the brake is applied at 0.5 s
        mb = y[5] > 0 ? 1 : y[5] < 0 ? -1 : 0;
        decide(t, off, y);
      }
      while (t < stop) {
        const bool last = stop - t <= 1.000001e-5;
        double h = last ? stop - t : 1e-5;
        Y y1 = step(t, off, y, h);
        if (event(t + h, off, y1) < 0) {
          double lo = 0, hi = h;
          while (std::nextafter(lo, hi) < hi) {
            const double mid = 0.5 * (lo + hi);
            (event(t + mid, off, step(t, off, y, mid)) < 0 ? hi : lo) = mid;
          }
          y = step(t, off, y, hi);
          t += hi;
          decide(t, off, y);
          continue;
        }
        y = y1;
        t = last ? stop : t + h;
      }
      out.push_back(y);
    }
    return out;
  }
};

// Claim: examples/msl/rotational-friction.yaml (MSL Rotational.Examples.Friction, a clutch and a
// brake coupled through a spring-damper) follows the independent solution above: speeds within
// 1e-7 rad/s (dopri5) or 1e-5 rad/s (bdf) and angles within 1e-7 rad / 1e-5 rad at every output row,
// and the same stick, slip and reversal events of the clutch and the brake, in order, each within
// 1e-8 s. The brake is applied at 0.5 s while inertia1 turns (an `applied` event).
TEST_P(MslExample, RotationalFrictionFollowsAnIndependentSolution) {
  const SimulationResult r = simulate(example("rotational-friction.yaml", GetParam()));
  const auto& ts = series(r, "t_s");
  ASSERT_EQ(ts.size(), 3001u);
  RotationalFrictionReference ref;
  const auto y = ref.run(1e-3, 3000);
  const bool dopri = GetParam() == IntegratorChoice::dopri5;
  const double tol = dopri ? 1e-7 : 1e-5;
  const char* bodies[3] = {"inertia3", "inertia2", "inertia1"};
  for (int b = 0; b < 3; ++b) {
    const auto& q = series(r, std::string(bodies[b]) + ".position_rad");
    const auto& w = series(r, std::string(bodies[b]) + ".velocity_rad_s");
    double eq = 0, ew = 0;
    for (size_t i = 0; i < ts.size(); ++i) {
      eq = std::max(eq, std::abs(q[i] - y[i][static_cast<size_t>(2 * b)]));
      ew = std::max(ew, std::abs(w[i] - y[i][static_cast<size_t>(2 * b + 1)]));
    }
    EXPECT_LT(eq, tol) << bodies[b];
    EXPECT_LT(ew, tol) << bodies[b];
    RecordProperty(std::string(bodies[b]) + "_angle_error", sci(eq));
    RecordProperty(std::string(bodies[b]) + "_speed_error", sci(ew));
  }
  std::vector<RotationalFrictionReference::Event> got;
  bool applied = false;
  for (const auto& e : r.hybrid.events) {
    if (e.kind == "stick" || e.kind == "slip" || e.kind == "reversal") got.push_back({e.t, e.element, e.kind});
    if (e.kind == "applied" && e.element == "brake") applied = std::abs(e.t - 0.5) < 1e-12;
  }
  EXPECT_TRUE(applied);
  ASSERT_GE(ref.events.size(), 4u);
  ASSERT_EQ(got.size(), ref.events.size());
  double et = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].element, ref.events[i].element) << "event " << i;
    EXPECT_EQ(got[i].kind, ref.events[i].kind) << "event " << i;
    EXPECT_NEAR(got[i].t, ref.events[i].t, 1e-8) << "event " << i << " " << ref.events[i].element;
    et = std::max(et, std::abs(got[i].t - ref.events[i].t));
  }
  RecordProperty("event_time_error", sci(et));
}

// ---------------------------------------------------------------------------------------------
// Claim: examples/msl/elasto-gap.yaml (MSL Translational.Examples.ElastoGap) follows
//   mass1: the damped oscillation m ẍ + 2 d ẋ + 2 c x = 0 from x0 = 2 m at rest (the two preloads
//     cancel): x = e^(−σt) x0 (cos ω_d t + (σ/ω_d) sin ω_d t), σ = d/m = 1.5 1/s, ω_d = √(2c/m − σ²);
//   mass2: free between ±0.5 m, one ElastoGap beyond each (the capped law, c = 10 N/m, d = 1.5 N·s/m):
//     the independent integration of BacklashReference above with J = m = 1, half gap 0.5 m (the
//     two one-sided links to the ground act like one centred gap: their contact ranges are apart),
// within 1e-8 m (mass1), 1e-6 m and 1e-5 m/s (mass2) at every output row, with the same contact
// instants within 5e-8 s (the reference does not bisect the cap's kink: its error grows over the
// 5 s). MSL's point: mass2 oscillates more slowly (free flight in the gap).
TEST_P(MslExample, ElastoGapFollowsIndependentSolutions) {
  const SimulationResult r = simulate(example("elasto-gap.yaml", GetParam()));
  const double m = 1, c = 10, d = 1.5, x0 = 2;
  const double sg = d / m, wd = std::sqrt(2 * c / m - sg * sg);
  auto x1 = [&](double t) { return std::exp(-sg * t) * x0 * (std::cos(wd * t) + sg / wd * std::sin(wd * t)); };
  auto v1 = [&](double t) { return -std::exp(-sg * t) * x0 * (sg * sg / wd + wd) * std::sin(wd * t); };
  EXPECT_LT(max_error(r, "mass1.position_m", x1), 1e-8);
  EXPECT_LT(max_error(r, "mass1.velocity_m_s", v1), 1e-7);

  const auto& ts = series(r, "t_s");
  ASSERT_EQ(ts.size(), 5001u);
  BacklashReference ref;
  ref.J = m, ref.c = c, ref.d = d, ref.half = 0.5, ref.capped = true;
  const auto y = ref.run(x0, 1e-3, 5000);
  const auto& q = series(r, "mass2.position_m");
  const auto& w = series(r, "mass2.velocity_m_s");
  double eq = 0, ew = 0;
  for (size_t i = 0; i < ts.size(); ++i) {
    eq = std::max(eq, std::abs(q[i] - y[i][0]));
    ew = std::max(ew, std::abs(w[i] - y[i][1]));
  }
  EXPECT_LT(eq, 1e-6);
  EXPECT_LT(ew, 1e-5);
  RecordProperty("mass2_position_error", sci(eq));
  RecordProperty("mass2_velocity_error", sci(ew));
  std::vector<double> got;
  for (const auto& e : r.hybrid.events)
    if (e.kind == "gap_closed") got.push_back(e.t);
  ASSERT_GE(ref.contact_times.size(), 2u);
  ASSERT_EQ(got.size(), ref.contact_times.size());
  double et = 0;
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_NEAR(got[i], ref.contact_times[i], 5e-8) << "contact " << i;
    et = std::max(et, std::abs(got[i] - ref.contact_times[i]));
  }
  RecordProperty("contact_time_error", sci(et));
  // The first return through x = 0 comes later for mass2 than for mass1 (lower eigenfrequency).
  size_t i1 = 0, i2 = 0;
  while (i1 < ts.size() && series(r, "mass1.position_m")[i1] > 0) ++i1;
  while (i2 < ts.size() && q[i2] > 0) ++i2;
  EXPECT_GT(i2, i1);
}

// ---------------------------------------------------------------------------------------------
// Claim: examples/msl/sign-convention.yaml (MSL Translational.Examples.SignConvention): each of the
// three masses (m = 1 kg, at rest at 0) under its force F = 1 N moves forward as x = F t²/(2m),
// v = F t/m — 0.5 m and 1 m/s at 1 s — within 1e-10 m and 1e-10 m/s at every row.
TEST_P(MslExample, SignConventionFollowsTheClosedForm) {
  const SimulationResult r = simulate(example("sign-convention.yaml", GetParam()));
  for (const char* b : {"mass1", "mass2", "mass3"}) {
    EXPECT_LT(max_error(r, std::string(b) + ".position_m", [](double t) { return 0.5 * t * t; }), 1e-10) << b;
    EXPECT_LT(max_error(r, std::string(b) + ".velocity_m_s", [](double t) { return t; }), 1e-10) << b;
    EXPECT_NEAR(series(r, std::string(b) + ".position_m").back(), 0.5, 1e-10) << b;
  }
}

// Claim: examples/msl/accelerate.yaml (MSL Translational.Examples.Accelerate): the mass (1 kg) whose
// acceleration is prescribed as a = 1 m/s² from rest moves as x = t²/2, v = t, and the source pushes
// with m a = 1 N throughout (no other force acts): within 1e-10 m, 1e-10 m/s and 1e-12 N at every row.
TEST_P(MslExample, AccelerateFollowsTheClosedForm) {
  const SimulationResult r = simulate(example("accelerate.yaml", GetParam()));
  EXPECT_LT(max_error(r, "mass.position_m", [](double t) { return 0.5 * t * t; }), 1e-10);
  EXPECT_LT(max_error(r, "mass.velocity_m_s", [](double t) { return t; }), 1e-10);
  EXPECT_LT(max_error(r, "mass.motion_force_N", [](double) { return 1.0; }), 1e-12);
  EXPECT_NEAR(series(r, "mass.position_m").back(), 0.5, 1e-10);
}

// Claim: examples/msl/rolling-wheel.yaml (MSL Rotational.Examples.RollingWheel) follows the closed
// form. The rolling wheel (R = 1 m) ties v = R ω, so in the mass's coordinate the wheel's inertia adds
// J/R² and the torque acts as M/R: (J/R² + m) v' = M/R − k v|v| with J/R² + m = 2 kg, M = 10 N·m
// from 0.1 s, k = 0.4 N·s²/m². For t ≥ 0.1 s, v ≥ 0: v' = 5 − 0.2 v² = 0.2 (25 − v²), whose solution
// from rest is v = 5 tanh(t − 0.1) (d/dt: 5 sech² = 5 (1 − tanh²) ✓), x = 5 ln cosh(t − 0.1); at
// rest before. ω = v/R, φ = x/R. Within 1e-8 m, 1e-8 m/s (1e-7 bdf) at every 1 ms row; v(5 s) =
// 5 tanh 4.9 = 4.9978 m/s: MSL's equilibrium at 5 m/s.
TEST_P(MslExample, RollingWheelFollowsTheClosedForm) {
  const SimulationResult r = simulate(example("rolling-wheel.yaml", GetParam()));
  auto v = [](double t) { return t < 0.1 ? 0.0 : 5.0 * std::tanh(t - 0.1); };
  auto x = [](double t) { return t < 0.1 ? 0.0 : 5.0 * std::log(std::cosh(t - 0.1)); };
  const double tol = GetParam() == IntegratorChoice::bdf ? 1e-7 : 1e-8;
  EXPECT_LT(max_error(r, "mass.velocity_m_s", v), tol);
  EXPECT_LT(max_error(r, "mass.position_m", x), tol);
  EXPECT_LT(max_error(r, "inertia.velocity_rad_s", v), tol);
  EXPECT_LT(max_error(r, "inertia.position_rad", x), tol);
  EXPECT_NEAR(series(r, "mass.velocity_m_s").back(), 5.0 * std::tanh(4.9), tol);
}

// Claim: examples/msl/vehicle.yaml (MSL Translational.Examples.Vehicle) follows an independent RK4 of
// MSL's Vehicle equations. Per vehicle (m = 100 kg, J = 0, R = 0.25 m), with the example's tables
// y1(t) (torque factor) and y2(t) = tan α (grade), both piecewise constant with jumps at 5, 10.8, 20,
// 25, 50, 55 s:
//   m v' = τ(t)/R − (Cd A ρ/2) v|v| − Cr m g cos α sat(v/v_reg) − m g sin α,   s' = v,
//   τ = k y1, k = (Cd A 1.18 vNom²/2 + Cr m g) R, vNom = 25/3.5 m/s (the gain of the example, with its
//   ρ = 1.18), the vehicles' own ρ = 1.2, v_reg = 1e-3 m/s (Regularization.Linear), g = 9.80665.
// vehicle1 with 2τ pulls the trailer rigidly: 2m v' = 2τ/R − 2 (resistances), the same equation, so
// vehicle1 and the trailer move exactly as vehicle. The RK4 runs row by row (10 ms rows; the tables
// taken at each row's midpoint, every jump is a row time), 1000 steps per row, 10⁵ in the rows where
// v passes the regularization's kink at ±v_reg (after 5 s, and at the stop near 55.9 s). Within 1e-6 m and 1e-7 m/s (dopri5), 1e-5 m
// and 1e-6 m/s (bdf) at every row.
TEST_P(MslExample, VehicleFollowsAnRk4OfMslsEquations) {
  const SimulationResult r = simulate(example("vehicle.yaml", GetParam()));
  const double m = 100, g = 9.80665, R = 0.25, Cr = 0.01, vreg = 1e-3, kd = 0.5 * 1.0 * 1.2 / 2;
  const double vNom = 25 / 3.5, k = (0.5 * 1.0 * 1.18 * vNom * vNom / 2 + Cr * m * g) * R;
  auto y1 = [](double t) {
    return t < 5 ? 0.0 : t < 10.8 ? 5.6 : t < 20 ? 1.0 : t < 25 ? 2.8 : t < 50 ? 1.0 : t < 55 ? -5.0 : 0.0;
  };
  auto y2 = [](double t) { return t >= 20 && t < 25 ? 0.05 : 0.0; };
  const auto& ts = series(r, "t_s");
  std::vector<double> sref(ts.size()), vref(ts.size());
  double x = 0, v = 0;
  for (size_t i = 1; i < ts.size(); ++i) {
    const double tm = 0.5 * (ts[i - 1] + ts[i]), alpha = std::atan(y2(tm)), tau = k * y1(tm);
    auto acc = [&](double w) {
      const double sat = std::clamp(w / vreg, -1.0, 1.0);
      return (tau / R - kd * w * std::abs(w) - Cr * m * g * std::cos(alpha) * sat - m * g * std::sin(alpha)) / m;
    };
    // Fine steps where v may pass the kink at ±v_reg: the row after 5 s (start) and rows starting
    // at v_reg/2 < |v| < 0.01 m/s (the stop after 55 s).
    const bool kink = std::abs(ts[i - 1] - 5.0) < 1e-9 || (std::abs(v) > 0.5 * vreg && std::abs(v) < 0.01);
    const int nsub = kink ? 100000 : 1000;
    const double h = (ts[i] - ts[i - 1]) / nsub;
    for (int j = 0; j < nsub; ++j) {
      const double k1x = v, k1v = acc(v);
      const double k2x = v + 0.5 * h * k1v, k2v = acc(v + 0.5 * h * k1v);
      const double k3x = v + 0.5 * h * k2v, k3v = acc(v + 0.5 * h * k2v);
      const double k4x = v + h * k3v, k4v = acc(v + h * k3v);
      x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
      v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
    }
    sref[i] = x, vref[i] = v;
  }
  const bool bdf = GetParam() == IntegratorChoice::bdf;
  for (const char* b : {"vehicle", "vehicle1", "trailer"}) {
    const auto& s = series(r, std::string(b) + ".position_m");
    const auto& w = series(r, std::string(b) + ".velocity_m_s");
    double es = 0, ev = 0;
    for (size_t i = 0; i < ts.size(); ++i) es = std::max(es, std::abs(s[i] - sref[i])), ev = std::max(ev, std::abs(w[i] - vref[i]));
    EXPECT_LT(es, bdf ? 1e-5 : 1e-6) << b << " " << sci(es);
    EXPECT_LT(ev, bdf ? 1e-6 : 1e-7) << b << " " << sci(ev);
  }
  // The story of MSL's documentation: near vNom = 7.14 m/s by 20 s and still at 50 s, braked from 50 s,
  // then stopped by the driving resistances before 60 s.
  EXPECT_NEAR(test::at(r, "vehicle.velocity_m_s", 20.0), vNom, 0.3);
  EXPECT_NEAR(test::at(r, "vehicle.velocity_m_s", 50.0), vNom, 0.3);
  EXPECT_LT(std::abs(series(r, "vehicle.velocity_m_s").back()), 1e-6);
  // The massless wheel turns as v/R.
  EXPECT_NEAR(series(r, "vehicle_wheel.velocity_rad_s").back(), series(r, "vehicle.velocity_m_s").back() / R, 1e-9);
}

// Claim: examples/msl/initial-conditions.yaml (MSL Translational.Examples.InitialConditions) starts
// where MSL's initial conditions put it and follows the closed forms, in MSL's positions s with the
// springs' free lengths (docs/model-files.md, Links):
//   system 1 (m3 at 4.5 m, m4 at 12.5 m, every spring at its free length, at rest) stays exactly at
//   rest (F = c (δ − δ₀) is exactly 0: every number is a binary fraction);
//   system 2, u = (x1, x2) the displacements from where both springs are unstretched (s1 = 0.5 m,
//   s2 = 3 m), from u(0) = (−0.5, −0.5) m at rest: M ü + D u̇ + K u = 0 with M = I,
//     K = [[c1 + c, −c], [−c, c]], D = [[d, −d], [−d, d]] (c1 = 1e3, c = 111 N/m, d = 1 N·s/m).
//     With y = (u, u̇), ẏ = A y, A = [[0, I], [−K, −D]]: y(t) = V e^(Λt) V⁻¹ y(0) from the
//     eigen-decomposition A = V Λ V⁻¹ (four distinct complex eigenvalues; the damping is not
//     proportional, so no real modal decoupling).
// Within 1e-8 m and 1e-7 m/s (dopri5), 1e-7 m and 1e-5 m/s (bdf) at every output row (amplitudes
// 0.5 m, ~16 m/s).
TEST_P(MslExample, InitialConditionsFollowTheClosedForms) {
  const SimulationResult r = simulate(example("initial-conditions.yaml", GetParam()));
  for (const char* b : {"m3", "m4"}) {
    const double s0 = b[1] == '3' ? 4.5 : 12.5;
    EXPECT_EQ(max_error(r, std::string(b) + ".position_m", [&](double) { return s0; }), 0.0) << b;
    EXPECT_EQ(max_error(r, std::string(b) + ".velocity_m_s", [](double) { return 0.0; }), 0.0) << b;
  }
  const double c1 = 1e3, c = 111, d = 1;
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
  A(0, 2) = A(1, 3) = 1;
  A(2, 0) = -(c1 + c), A(2, 1) = c, A(3, 0) = c, A(3, 1) = -c;
  A(2, 2) = -d, A(2, 3) = d, A(3, 2) = d, A(3, 3) = -d;
  const Eigen::EigenSolver<Eigen::Matrix4d> es(A);
  const Eigen::Matrix4cd V = es.eigenvectors();
  const Eigen::Vector4cd lambda = es.eigenvalues();
  const Eigen::Vector4cd w0 = V.inverse() * Eigen::Vector4cd(-0.5, -0.5, 0, 0);
  auto y = [&](double t, int i) {
    Eigen::Vector4cd e;
    for (int k = 0; k < 4; ++k) e(k) = std::exp(lambda(k) * t) * w0(k);
    return (V * e)(i).real();
  };
  EXPECT_NEAR(y(0, 0), -0.5, 1e-12);  // the decomposition reproduces the start
  EXPECT_NEAR(y(0, 3), 0.0, 1e-12);
  const char* names[4] = {"m1.position_m", "m2.position_m", "m1.velocity_m_s", "m2.velocity_m_s"};
  const bool dopri = GetParam() == IntegratorChoice::dopri5;
  const double offset[4] = {0.5, 3.0, 0.0, 0.0};  // s = u + the unstretched position
  for (int i = 0; i < 4; ++i) {
    const double e = max_error(r, names[i], [&](double t) { return y(t, i) + offset[i]; });
    EXPECT_LT(e, i < 2 ? (dopri ? 1e-8 : 1e-7) : (dopri ? 1e-7 : 1e-5)) << names[i];
    RecordProperty(names[i], sci(e));
  }
}

// ---------------------------------------------------------------------------------------------
// An independent integration of MSL PreLoad, written from MSL's equations as functions of the
// state, not from the library's engine. Displacements x = (spool, plate A, plate B) from MSL's start;
// each ElastoGap k between its flanges a, b (−1: the housing) with e = δ − flank_k, δ = x_a − x_b:
//   e ≤ 0: P = 0;   e > 0: P = c e + clamp(d ė, −c e, c e)   (MSL: f_d limited to |f_c|),
// pushing b forward and a back (c = 1e6 N/m, d = 250 N·s/m); the spring between the plates pushes
// B forward and A back with 65 N + 20e3 (x_A − x_B) N (c (s_rel0 − s_rel)); the damper −2500 v on
// the spool, and 150 sin(2π 0.01 t) N on it. The clamp makes four branches per contact (apart,
// linear, damper at +c e, at −c e); a fixed-step RK4 (h = 2e-5 s) holds each contact's branch along a
// step, and a step at whose end a branch differs is bisected to the switching instant. A contact
// closes where its branch leaves {apart, −c e} (P turns positive) and opens where it enters it.
struct PreLoadReference {
  static constexpr int kS = 0, kA = 1, kB = 2;
  static constexpr double m[3] = {0.15, 0.01, 0.01};
  static constexpr double c = 1e6, d = 250;
  struct Contact {
    const char* name;
    int a, b;
    double flank;
  };
  static constexpr Contact contacts[4] = {{"outerContactA", -1, kA, 0.0},
                                          {"outerContactB", kB, -1, 1.75e-3},
                                          {"innerContactA", kS, kA, 0.0},
                                          {"innerContactB", kB, kS, 1.75e-3}};
  using Y = std::array<double, 6>;  // x_S, x_A, x_B, v_S, v_A, v_B
  std::array<int, 4> branch{0, 0, 0, 0};
  struct Event {
    double t;
    bool closed;
  };
  std::array<std::vector<Event>, 4> events;

  static double rel(const Contact& k, const Y& y, int off) {
    return (k.a >= 0 ? y[static_cast<size_t>(k.a + off)] : 0.0) - (k.b >= 0 ? y[static_cast<size_t>(k.b + off)] : 0.0);
  }
  /// 0 apart (e ≤ 0), 1 linear, 2 damper capped at +c e, 3 at −c e (P = 0).
  static int classify(const Contact& k, const Y& y) {
    const double e = rel(k, y, 0) - k.flank, fd = d * rel(k, y, 3);
    return e <= 0 ? 0 : fd > c * e ? 2 : fd < -c * e ? 3 : 1;
  }
  static double force(int br, const Contact& k, const Y& y) {
    const double e = rel(k, y, 0) - k.flank;
    return br == 1 ? c * e + d * rel(k, y, 3) : br == 2 ? 2 * c * e : 0.0;
  }
  Y rate(double t, const Y& y) const {
    double f[3] = {150 * std::sin(2 * std::numbers::pi * 0.01 * t) - 2500 * y[3], 0.0, 0.0};
    const double Fs = 65 + 20e3 * (y[1] - y[2]);
    f[kA] -= Fs, f[kB] += Fs;
    for (size_t j = 0; j < 4; ++j) {
      const double P = force(branch[j], contacts[j], y);
      if (contacts[j].a >= 0) f[contacts[j].a] -= P;
      if (contacts[j].b >= 0) f[contacts[j].b] += P;
    }
    return {y[3], y[4], y[5], f[0] / m[0], f[1] / m[1], f[2] / m[2]};
  }
  Y step(double t, const Y& y, double h) const {
    return test::rk4_step([this](double s, const Y& z) { return rate(s, z); }, t, y, h);
  }
  bool changed(const Y& y) const {
    for (size_t j = 0; j < 4; ++j)
      if (classify(contacts[j], y) != branch[j]) return true;
    return false;
  }
  static bool pressing(int br) { return br == 1 || br == 2; }
  /// The state at k dt, k = 0 … n, from x = 0 at rest.
  std::vector<Y> run(double dt, int n, double h) {
    Y y{};
    std::vector<Y> out{y};
    double t = 0;
    for (int k = 1; k <= n; ++k) {
      const double stop = k * dt;
      while (t < stop) {
        const bool last = stop - t <= 1.000001 * h;
        double hs = last ? stop - t : h;
        Y y1 = step(t, y, hs);
        if (changed(y1)) {
          double lo = 0, hi = hs;
          while (std::nextafter(lo, hi) < hi) {
            const double mid = 0.5 * (lo + hi);
            (changed(step(t, y, mid)) ? hi : lo) = mid;
          }
          y = step(t, y, hi);
          t += hi;
          for (size_t j = 0; j < 4; ++j) {
            const int now = classify(contacts[j], y);
            if (pressing(now) != pressing(branch[j])) events[j].push_back({t, pressing(now)});
            branch[j] = now;
          }
          continue;
        }
        y = y1;
        t = last ? stop : t + hs;
      }
      out.push_back(y);
    }
    return out;
  }
};

// Claim: examples/msl/preload.yaml (MSL Translational.Examples.PreLoad) follows the independent
// integration above: positions within 1e-8 m and velocities within 1e-6 m/s at every output row
// (0.1 s), every contact closing and opening at the same instants within 1e-8 s. MSL's point holds:
// plate B settles on the housing after 1.75 mm, which leaves the spring a preload of
// 65 N − 20e3 N/m · 1.75 mm = 30 N; while |F| < 25 N all four contacts hold the spool within
// |F|/c_contact ≤ 25 µm (c = 1e6 N/m), and at the peak F = 150 N (t = 25 s, where the damper's
// force vanishes with the speed) the spool stands, quasi-statically, at 1.75 mm (plate B's travel)
// + 150 N/c (outer contact B) + (150 − 65) N / 20e3 N/m (the spring) + 150 N/c (inner contact A)
// = 6.3 mm, within 2 µm (the damper's force there, about 0.01 N, moves it by about 0.5 µm).
TEST_P(MslExample, PreLoadFollowsAnIndependentSolution) {
  const SimulationResult r = simulate(example("preload.yaml", GetParam()));
  const auto& ts = series(r, "t_s");
  ASSERT_EQ(ts.size(), 1001u);
  // The reference is the same for both integrators: computed once (5·10⁶ RK4 steps).
  static const std::pair<PreLoadReference, std::vector<PreLoadReference::Y>> solved = [] {
    PreLoadReference p;
    auto states = p.run(0.1, 1000, 2e-5);
    return std::pair{p, states};
  }();
  const PreLoadReference& ref = solved.first;
  const auto& y = solved.second;
  const char* bodies[3] = {"spool", "springPlateA", "springPlateB"};
  for (size_t b = 0; b < 3; ++b) {
    const auto& q = series(r, std::string(bodies[b]) + ".position_m");
    const auto& w = series(r, std::string(bodies[b]) + ".velocity_m_s");
    double eq = 0, ew = 0;
    for (size_t i = 0; i < ts.size(); ++i) {
      eq = std::max(eq, std::abs(q[i] - y[i][b]));
      ew = std::max(ew, std::abs(w[i] - y[i][b + 3]));
    }
    EXPECT_LT(eq, 1e-8) << bodies[b];
    EXPECT_LT(ew, 1e-6) << bodies[b];
    RecordProperty(std::string(bodies[b]) + "_position_error", sci(eq));
    RecordProperty(std::string(bodies[b]) + "_velocity_error", sci(ew));
  }
  double et = 0;
  for (size_t j = 0; j < 4; ++j) {
    const std::string name = PreLoadReference::contacts[j].name;
    std::vector<std::pair<double, bool>> got;
    for (const auto& e : r.hybrid.events)
      if (e.element == name && (e.kind == "gap_closed" || e.kind == "gap_opened")) got.push_back({e.t, e.kind == "gap_closed"});
    ASSERT_EQ(got.size(), ref.events[j].size()) << name;
    for (size_t i = 0; i < got.size(); ++i) {
      EXPECT_EQ(got[i].second, ref.events[j][i].closed) << name << " event " << i;
      EXPECT_NEAR(got[i].first, ref.events[j][i].t, 1e-8) << name << " event " << i;
      et = std::max(et, std::abs(got[i].first - ref.events[j][i].t));
    }
  }
  RecordProperty("contact_time_error", sci(et));
  // The dead band and the linear branch (positions at 0.1 s rows; F = 150 sin(2π 0.01 t)).
  const auto& xs = series(r, "spool.position_m");
  int held = 0;
  for (size_t i = 0; i < ts.size(); ++i) {
    const double F = 150 * std::sin(2 * std::numbers::pi * 0.01 * ts[i]);
    if (ts[i] < 0.1 || std::abs(F) >= 25) continue;
    ++held;
    EXPECT_LT(std::abs(xs[i]), 25e-6) << "t = " << ts[i];
  }
  EXPECT_GT(held, 100);
  EXPECT_NEAR(test::at(r, "spool.position_m", 25.0), 1.75e-3 + 2 * 150 / 1e6 + (150 - 65) / 20e3, 2e-6);
}

// ---------------------------------------------------------------------------------------------
// Claim (the event log, analysis/run.cpp): a released clutch logs no mode changes of its own. In
// one-way-clutch.yaml the clutch is open before 0.3 s and on [0.95, 1.6) s while the freewheel
// beside it locks and releases (0.080, 1/6, 1.050, 7/6 s): the clutch's log is exactly its initial
// `released`, `applied` at 0.3 and 1.6 s, `stick` while applied, and `released` from `stuck` at
// 0.95 s (the pulse ends while it holds). Before the fix each freewheel switch also logged the open
// clutch as "reversal released→released", and the opening at 0.95 s read "slip released→released".
// In coupled-clutches.yaml clutch3, open until 0.9 s, no longer logs "slip released→released" at
// 0.4 s (when clutch2 closes and starts turning J3).
TEST_P(MslExample, ReleasedClutchLogsNoModeChanges) {
  const SimulationResult r = simulate(example("one-way-clutch.yaml", GetParam()));
  std::vector<std::string> log;
  for (const auto& e : r.hybrid.events) {
    if (e.element != "clutch") continue;
    EXPECT_FALSE(e.from == "released" && e.to == "released") << e.kind << " at " << e.t;
    log.push_back(e.kind + " " + e.from + ">" + e.to);
  }
  const std::vector<std::string> expected{"initial >released", "applied released>slip-", "stick slip->stuck",
                                          "released stuck>released", "applied released>slip-", "stick slip->stuck"};
  EXPECT_EQ(log, expected);
  for (const auto& e : r.hybrid.events) {
    if (e.element == "clutch" && e.kind == "released") {
      EXPECT_DOUBLE_EQ(e.t, 0.95);
    }
  }
  const SimulationResult c = simulate(example("coupled-clutches.yaml", GetParam()));
  for (const auto& e : c.hybrid.events)
    EXPECT_FALSE(e.from == "released" && e.to == "released") << e.element << " " << e.kind << " at " << e.t;
}

}  // namespace
}  // namespace machdyn
