// The Modelica Standard Library examples shipped under examples/msl (docs/msl.md), each run from
// its file and checked against an independent answer: the closed form of every phase (derived in
// the comment over each test) or a semi-analytic solution written here without the library's
// engine. Every example runs on both integrators. CoupledClutches is in clutch_test.cpp.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace {

using test::series;

class MslExample : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, MslExample, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         [](const auto& p) { return std::string(p.param == IntegratorChoice::bdf ? "bdf" : "dopri5"); });

Model example(const std::string& name, IntegratorChoice integrator) {
  Model m = load_model(std::string(MACHDYN_SOURCE_DIR) + "/examples/msl/" + name);
  m.simulation.integrator = integrator;
  return m;
}

/// The largest |column − f(t)| over all output rows.
template <class F>
double max_error(const SimulationResult& r, const std::string& name, F f) {
  const auto& ts = series(r, "t_s");
  const auto& v = series(r, name);
  double e = 0.0;
  for (size_t i = 0; i < ts.size() && i < v.size(); ++i) e = std::max(e, std::abs(v[i] - f(ts[i])));
  return ts.empty() ? INFINITY : e;
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
//   stuck (ẋ ≡ 0) while |F(t) − c x| ≤ F_C + F_S, on a stop while the net force presses it on (or is
//   within F_C + F_S pulling it off); reaching a stop: x set on the stop, ẋ = 0 (MSL's reinit).
// At ẋ = 0 (end of a slide or an impact) the next mode is decided from the net force n = F − c x:
// stuck within the limit, else sliding in the direction of n. Fixed-step RK4 (h = 1e-5 s) with the
// mode held along a step; a step at whose end an event function of the mode is negative (sliding:
// s ẋ and the distance to the stop ahead; stuck: the margin to the limit) is shortened by bisection
// to the switching instant.
struct StopFrictionReference {
  double m = 1, c = 0, d = 1, Fc = 0, FS = 0, fexp = 2, xmin = 0, xmax = 0;
  double (*F)(double) = nullptr;
  int s = 0;  // +1, −1 sliding; 0 stuck
  std::vector<double> stick_times, impact_times;

  double limit() const { return Fc + FS; }
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
// follows the independent integration above: positions within 1e-6 m and velocities within 1e-5 m/s
// at every output row, the same instants of sticking (within 1e-8 s). stop2 hits its lower stop
// once (at 0.0606 s, from −6.2 m/s) and is pushed off at once by the spring (75 N > 8 N).
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
    for (size_t i = 0; i < ts.size(); ++i) {
      eq = std::max(eq, std::abs(q[i] - y[i][0]));
      ew = std::max(ew, std::abs(w[i] - y[i][1]));
    }
    EXPECT_LT(eq, 1e-6) << b;
    EXPECT_LT(ew, 1e-5) << b;
    std::vector<double> sticks;
    for (const auto& e : r.hybrid.events)
      if (e.element == fr && e.kind == "stick") sticks.push_back(e.t);
    ASSERT_EQ(sticks.size(), ref.stick_times.size()) << b;
    for (size_t i = 0; i < sticks.size(); ++i) EXPECT_NEAR(sticks[i], ref.stick_times[i], 1e-8) << b << " stick " << i;
    if (k == 1) {
      ASSERT_EQ(ref.impact_times.size(), 1u);
      EXPECT_NEAR(ref.impact_times[0], 0.0606, 1e-3);
    }
  }
}

}  // namespace
}  // namespace machdyn
