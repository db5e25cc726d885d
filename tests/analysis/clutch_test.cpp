// Clutches and brakes applied by signals (model/model.hpp FrictionContact, elements/contact.hpp):
// the MSL CoupledClutches example against an independent event-driven integration written here,
// a clutch closing on a ramp of its normal force against its closed form, a brake against a
// housing body, the Stribeck law, and located input errors. Event-driven claims on both
// integrators.
#include <algorithm>
#include <array>
#include <cstdio>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/support.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/elements/contact.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::at;
using test::series;

Model model_of(const std::string& yaml) { return compile_model(parse_yaml_string(yaml, "cl.yaml"), "cl.yaml"); }

class Clutch : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, Clutch, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

// ---------------------------------------------------------------------------------------------
// An independent solution of MSL CoupledClutches: four unit inertias in a chain, clutch k between
// J_k and J_{k+1}, written from the MSL parameters without the library's engine. Fixed-step RK4
// (h = 1e-4 s) on the speeds, with the modes of the clutches fixed along a step; the groups of bodies
// joined by stuck clutches move as one rigid body (a = Σ torques / Σ I), and a stuck clutch's
// torque is what the bodies on its left need: λ_k = Σ_{j in group, j ≤ k} (M_j − I_j a). Events:
// a sliding clutch's u = ω_k − ω_{k+1} reaching 0, a stuck one's |λ_k| reaching its limit; each is
// located by bisection of the step length to the last bit. At an event and at the breakpoints
// (the steps at 0.4 s and 0.9 s, the zero of clutch1's normal force) the modes of all clutches at
// zero sliding speed are chosen by enumerating the 3^n combinations, fewest sliding first: stuck
// ones must hold (|λ| ≤ F_s), sliding ones must accelerate in their direction (s u̇ ≥ 0).
struct CoupledClutchesReference {
  static constexpr double kMuK = 0.5, kMuS = 0.55, kFnMax = 20.0;
  static constexpr double kT2 = 0.4, kT3 = 0.9;
  /// The normal force of clutch k (fn ≤ 0: open) at t; the steps of clutch2 and clutch3 are read at
  /// `side`, a time inside the current step (a step never crosses them), so that the last stage of
  /// a step that ends on T2 or T3 sees the value before the step.
  static double fn(int k, double t, double side) {
    if (k == 0) return kFnMax * std::sin(2 * std::numbers::pi * 0.2 * t + 1.57);
    return side >= (k == 1 ? kT2 : kT3) ? kFnMax : 0.0;
  }
  static double fn(int k, double t) { return fn(k, t, t); }
  static double open_time() { return (std::numbers::pi - 1.57) / (2 * std::numbers::pi * 0.2); }

  std::array<double, 4> w{10, 0, 0, 0};
  std::array<int, 3> mode{1, 0, 0};  // 0 stuck, ±1 sliding
  struct Switch {
    double t;
    int clutch;
    int to;
  };
  std::vector<Switch> switches;

  /// Accelerations and stuck torques in the current modes.
  void accel(double t, double side, const std::array<int, 3>& md, std::array<double, 4>& a,
             std::array<double, 3>& lam) const {
    std::array<double, 4> M{10 * std::sin(2 * std::numbers::pi * 5 * t), 0, 0, 0};
    for (int k = 0; k < 3; ++k)
      if (md[k] != 0) {
        const double F = md[k] * kMuK * std::max(0.0, fn(k, t, side));  // on J_k −F, on J_{k+1} +F
        M[k] -= F;
        M[k + 1] += F;
      }
    lam = {0, 0, 0};
    for (int g0 = 0; g0 < 4;) {
      int g1 = g0;
      while (g1 < 3 && md[g1] == 0) ++g1;  // the group g0..g1
      double sum = 0;
      for (int j = g0; j <= g1; ++j) sum += M[j];
      const double acc = sum / (g1 - g0 + 1);
      double left = 0;
      for (int j = g0; j <= g1; ++j) {
        a[j] = acc;
        left += M[j] - acc;
        if (j < g1) lam[j] = left;
      }
      g0 = g1 + 1;
    }
  }

  std::array<double, 4> rk4(double t, const std::array<double, 4>& y, double h) const {
    std::array<double, 4> k1, k2, k3, k4, tmp;
    std::array<double, 3> l;
    const double side = t + 0.5 * h;
    auto f = [&](double tt, const std::array<double, 4>&, std::array<double, 4>& k) { accel(tt, side, mode, k, l); };
    f(t, y, k1);
    for (int i = 0; i < 4; ++i) tmp[i] = y[i] + 0.5 * h * k1[i];
    f(t + 0.5 * h, tmp, k2);
    for (int i = 0; i < 4; ++i) tmp[i] = y[i] + 0.5 * h * k2[i];
    f(t + 0.5 * h, tmp, k3);
    for (int i = 0; i < 4; ++i) tmp[i] = y[i] + h * k3[i];
    f(t + h, tmp, k4);
    std::array<double, 4> out;
    for (int i = 0; i < 4; ++i) out[i] = y[i] + h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    return out;
  }

  /// Which clutches' event functions are negative at (t, y) in the current modes.
  std::vector<int> fired(double t, const std::array<double, 4>& y, double side) const {
    std::array<double, 4> a;
    std::array<double, 3> lam;
    accel(t, side, mode, a, lam);
    std::vector<int> out;
    for (int k = 0; k < 3; ++k) {
      const double g = mode[k] == 0 ? kMuS * std::max(0.0, fn(k, t, side)) - std::abs(lam[k]) : mode[k] * (y[k] - y[k + 1]);
      if (g < (mode[k] == 0 ? -1e-12 : 0.0)) out.push_back(k);
    }
    return out;
  }

  /// Chooses the modes of the clutches in Z (zero sliding speed); `strict`: those whose stuck limit
  /// just fired (they may not stay stuck on the rounding allowance).
  void decide(double t, const std::vector<int>& Z, const std::vector<int>& strict) {
    const int n = static_cast<int>(Z.size());
    int total = 1;
    for (int i = 0; i < n; ++i) total *= 3;
    std::vector<int> codes(static_cast<size_t>(total));
    for (int c = 0; c < total; ++c) codes[static_cast<size_t>(c)] = c;
    auto nslide = [&](int c) {
      int s = 0;
      for (int i = 0; i < n; ++i, c /= 3) s += c % 3 != 0;
      return s;
    };
    std::stable_sort(codes.begin(), codes.end(), [&](int x, int y) { return nslide(x) < nslide(y); });
    const std::array<int, 3> old = mode;
    for (int code : codes) {
      std::array<int, 3> md = old;
      for (int i = 0, c = code; i < n; ++i, c /= 3) md[Z[static_cast<size_t>(i)]] = c % 3 == 0 ? 0 : c % 3 == 1 ? 1 : -1;
      std::array<double, 4> a;
      std::array<double, 3> lam;
      accel(t, t, md, a, lam);
      bool ok = true;
      for (int k : Z) {
        const double Fs = kMuS * std::max(0.0, fn(k, t));
        const bool is_strict = std::find(strict.begin(), strict.end(), k) != strict.end();
        if (md[k] == 0) ok = ok && std::abs(lam[k]) <= Fs + (is_strict ? 0.0 : 1e-9);
        else ok = ok && md[k] * (a[k] - a[k + 1]) >= 0.0;
      }
      if (!ok) continue;
      for (int k = 0; k < 3; ++k)
        if (md[k] != old[k]) switches.push_back({t, k, md[k]});
      mode = md;
      return;
    }
    ADD_FAILURE() << "no consistent modes at t = " << t;
  }

  std::vector<int> at_rest() const {
    std::vector<int> Z;
    for (int k = 0; k < 3; ++k)
      if (mode[k] == 0 || w[k] == w[k + 1]) Z.push_back(k);
    return Z;
  }

  /// Integrates to t_end, recording the speeds at the `samples`.
  std::vector<std::array<double, 4>> run(double t_end, const std::vector<double>& samples) {
    const double h = 1e-4;
    std::vector<double> stops{kT2, kT3, open_time(), t_end};
    for (double s : samples) stops.push_back(s);
    std::sort(stops.begin(), stops.end());
    std::vector<std::array<double, 4>> out;
    double t = 0;
    decide(0.0, at_rest(), {});
    size_t next = 0;
    while (t < t_end) {
      while (next < stops.size() && stops[next] <= t) ++next;
      const double stop = stops[next];
      const double step = std::min(h, stop - t);
      auto y = rk4(t, w, step);
      auto ev = fired(t + step, y, t + 0.5 * step);
      double t_new = t + step;
      if (!ev.empty()) {
        double lo = 0, hi = step;  // fired at hi, not at lo
        for (int it = 0; it < 200 && std::nextafter(t + lo, t + hi) < t + hi; ++it) {
          const double mid = 0.5 * (lo + hi);
          if (fired(t + mid, rk4(t, w, mid), t + 0.5 * mid).empty()) lo = mid;
          else hi = mid;
        }
        t_new = t + hi;
        y = rk4(t, w, hi);
        ev = fired(t_new, y, t + 0.5 * hi);
      }
      w = y;
      t = t_new;
      if (!ev.empty()) {
        std::vector<int> strict;
        for (int k : ev) {
          if (mode[k] == 0) {
            strict.push_back(k);
          } else {  // u reached 0: the two groups take their common (momentum) mean speed
            const double mean = 0.5 * (w[k] + w[k + 1]);
            for (int j = k; j >= 0 && (j == k || mode[j] == 0); --j) w[j] = mean;
            for (int j = k + 1; j < 4 && (j == k + 1 || mode[j - 1] == 0); ++j) w[j] = mean;
          }
        }
        std::vector<int> Z = at_rest();
        for (int k : ev) Z.push_back(k);
        std::sort(Z.begin(), Z.end());
        Z.erase(std::unique(Z.begin(), Z.end()), Z.end());
        decide(t, Z, strict);
      } else if (t == stop && stop != t_end) {
        decide(t, at_rest(), {});
      }
      for (double s : samples)
        if (s == t) out.push_back(w);
    }
    return out;
  }
};

// Claim: machdyn's run of examples/msl/coupled-clutches.yaml (MSL's CoupledClutches) has the same
// stick and slip instants and the same speeds as the independent RK4 solution above: events within
// 1e-7 s, speeds within 1e-7 rad/s (dopri5) or 1e-5 rad/s (bdf). The sequence itself is a check
// of the exact mode logic: clutch2 closes on J2 at T2 and sticks at 0.71 s; clutch1 sticks, breaks
// away under the 5 Hz torque and sticks again; clutch3 closes at T3 and sticks; clutch1 opens when
// its normal force turns negative at 1.2506 s.
TEST_P(Clutch, CoupledClutchesMatchesAnIndependentIntegration) {
  Model m = load_model(std::string(MACHDYN_SOURCE_DIR) + "/examples/msl/coupled-clutches.yaml");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);

  const std::vector<double> samples{0.3, 0.6, 0.8, 1.0, 1.2, 1.4, 1.5};
  CoupledClutchesReference ref;
  const auto w = ref.run(1.5, samples);
  ASSERT_EQ(w.size(), samples.size());

  // Stick/slip switches of engaged clutches (not the application or release of a normal force).
  std::vector<std::pair<double, std::string>> got, want;
  for (const auto& e : r.hybrid.events)
    if ((e.kind == "stick" || e.kind == "slip") && e.from != "released" && e.to != "released")
      got.emplace_back(e.t, fmt::format("{}:{}", e.element, e.to));
  for (const auto& s : ref.switches) {
    if (s.t == 0.0 || CoupledClutchesReference::fn(s.clutch, s.t) <= 0.0) continue;  // initial or open
    const bool from_released = s.t == CoupledClutchesReference::kT2 || s.t == CoupledClutchesReference::kT3;
    if (from_released && s.to != 0) continue;  // an applied clutch that starts sliding: kind "applied"
    want.emplace_back(s.t, fmt::format("clutch{}:{}", s.clutch + 1, s.to == 0 ? "stuck" : s.to > 0 ? "slip+" : "slip-"));
  }
  ASSERT_EQ(got.size(), want.size());
  for (size_t i = 0; i < got.size(); ++i) {
    EXPECT_EQ(got[i].second, want[i].second) << i;
    EXPECT_NEAR(got[i].first, want[i].first, 1e-7) << got[i].second;
  }
  ASSERT_GE(got.size(), 6u);
  const double tol = GetParam() == IntegratorChoice::dopri5 ? 1e-7 : 1e-5;
  for (size_t i = 0; i < samples.size(); ++i)
    for (int j = 0; j < 4; ++j)
      EXPECT_NEAR(at(r, fmt::format("J{}.velocity_rad_s", j + 1), samples[i]), w[i][static_cast<size_t>(j)], tol)
          << "J" << j + 1 << " at " << samples[i];
  // clutch1 opens where its normal force crosses zero: released, and J1 decouples.
  bool opened = false;
  for (const auto& e : r.hybrid.events)
    if (e.element == "clutch1" && e.kind == "released") {
      opened = true;
      EXPECT_NEAR(e.t, CoupledClutchesReference::open_time(), 1e-12);
    }
  EXPECT_TRUE(opened);
  EXPECT_LT(std::abs(r.hybrid.energy.residual()), 1e-6 * r.hybrid.energy.source_work);
}

// Claim: a clutch whose normal force rises on a ramp f_N = F t / T (T = 1 s) between a driven body
// a (I_a = 2 kg·m², M = 0 — spinning at 10 rad/s) and a body b at rest (I_b = 1) slides with the
// torque M_k = z r μ_k f_N(t) = z r μ_k F t / T. Hence ω_b = z r μ_k F t² / (2 T I_b) and
// ω_a = 10 − z r μ_k F t² / (2 T I_a); they meet when 10 = K t²/2 (1/I_a + 1/I_b), K = z r μ_k F / T
// (z = 2, r = 0.1 m, μ_k = 0.3, F = 1 kN: K = 60 N·m/s, t_s = sqrt(20 / (60·1.5)) = 0.4714 s), and stay
// stuck (no load to break them apart).
TEST_P(Clutch, RampedNormalForceSticksAtTheClosedFormInstant) {
  Model m = model_of(R"(
bodies: {a: {inertia: 2, velocity: 10 rad/s}, b: {inertia: 1}}
clutches:
  c: {between: [a, b], normal_force: {type: ramp, value: 1 kN, end: 1 s}, mu_s: 0.35, mu_k: 0.3, radius: 0.1 m, surfaces: 2}
simulation: {t_end: 1 s, dt_out: 0.01 s, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const double K = 2 * 0.1 * 0.3 * 1000.0, ts = std::sqrt(10.0 / (0.5 * K * (1.0 / 2 + 1.0)));
  const SimulationResult r = simulate(m);
  std::vector<ModeEvent> ev;
  for (const auto& e : r.hybrid.events)
    if (e.kind == "stick") ev.push_back(e);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_NEAR(ev[0].t, ts, 1e-9);
  const double w_end = 10.0 * 2.0 / 3.0;  // momentum: I_a ω0 / (I_a + I_b)
  EXPECT_NEAR(series(r, "b.velocity_rad_s").back(), w_end, 1e-8);
  EXPECT_NEAR(at(r, "b.velocity_rad_s", 0.3), K * 0.09 / 2, 1e-8);
}

// Claim: a brake whose housing is a body acts on both: a body a (I = 1, 5 rad/s) braked against a
// free housing h (I = 4, at rest) by 8 N·m: ω_a = 5 − 8 t, ω_h = 2 t, equal at t = 0.5 s (ω = 1,
// the momentum mean 5·1/5); the old `time`/`ramp` form and `application: {type: ramp}` agree.
TEST_P(Clutch, BrakeAgainstAHousingBody) {
  for (const char* app : {"time: 0.1 s, ramp: 0.2 s", "application: {type: ramp, value: 1, start: 0.1 s, end: 0.3 s}"}) {
    Model m = model_of(std::string(R"(
bodies: {a: {inertia: 1, velocity: 5 rad/s}, h: {inertia: 4}}
brakes: {B: {body: a, housing: h, holding: 10 N*m, braking: 8 N*m, )") + app + R"(}}
simulation: {t_end: 1 s, dt_out: 0.01 s, rtol: 1e-11, atol: 1e-12}
)");
    m.simulation.integrator = GetParam();
    const SimulationResult r = simulate(m);
    // Applied over the ramp 0.1 … 0.3 s: the torque impulse until t ≥ 0.3 is 8 (t − 0.2); relative
    // speed 5 − 8 (t − 0.2)(1 + 1/4) = 0 at t = 0.2 + 0.5 = 0.7 s.
    std::vector<ModeEvent> ev;
    for (const auto& e : r.hybrid.events)
      if (e.kind == "stick") ev.push_back(e);
    ASSERT_EQ(ev.size(), 1u) << app;
    EXPECT_NEAR(ev[0].t, 0.7, 1e-9) << app;
    EXPECT_NEAR(series(r, "h.velocity_rad_s").back(), 1.0, 1e-8) << app;
    EXPECT_EQ(series(r, "h.velocity_rad_s").back(), series(r, "a.velocity_rad_s").back());
  }
}

// Claim: a translational brake pressed by a normal-force step (100 N at 0.5 s, μ_k = 0.3, two
// surfaces: F = 2·0.3·100 = 60 N) stops a 2 kg mass moving at 3 m/s with 30 m/s² after 0.1 s, at
// t = 0.6 s, and then holds it (no load). Before 0.5 s it is released: the speed stays 3 m/s.
TEST_P(Clutch, BrakeByNormalForceStopsAtTheClosedFormInstant) {
  Model m = model_of(R"(
bodies: {cart: {type: translational, mass: 2 kg, velocity: 3 m/s}}
brakes: {B: {body: cart, normal_force: {type: step, value: 100 N, time: 0.5 s}, mu_s: 0.4, mu_k: 0.3, surfaces: 2}}
simulation: {t_end: 1 s, dt_out: 0.01 s, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  EXPECT_NEAR(at(r, "cart.velocity_m_s", 0.4), 3.0, 1e-12);
  EXPECT_NEAR(at(r, "cart.velocity_m_s", 0.55), 3.0 - 30 * 0.05, 1e-8);
  std::vector<ModeEvent> ev;
  for (const auto& e : r.hybrid.events)
    if (e.kind == "stick") ev.push_back(e);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_NEAR(ev[0].t, 0.6, 1e-9);
  EXPECT_EQ(series(r, "cart.velocity_m_s").back(), 0.0);
}

// Claim: the Stribeck law μ(s) = μ_c + (μ_s − μ_c) exp(−(s/w_s)^δ) gives μ_s at rest, tends to μ_c,
// and its slope is the finite difference of the kinetic force.
TEST(ClutchLaw, StribeckLevelAndSlope) {
  const Model m = model_of(R"(
bodies: {a: {inertia: 1}, b: {inertia: 1}}
clutches: {c: {between: [a, b], normal_force: 100 N, mu_s: 0.5, mu_k: 0.3, radius: 0.2 m, stribeck_speed: 2 rad/s, stribeck_exponent: 2}}
)");
  const ContactLaw c = ContactLaw::of(m.contacts[0]);
  EXPECT_DOUBLE_EQ(c.kinetic_force(ContactMode::slip_pos, 0, 0.0), 0.5 * 100 * 0.2);
  EXPECT_NEAR(c.kinetic_force(ContactMode::slip_pos, 0, 2.0), (0.3 + 0.2 * std::exp(-1.0)) * 20, 1e-12);
  EXPECT_NEAR(c.kinetic_force(ContactMode::slip_neg, 0, -50.0), -0.3 * 20, 1e-9);
  for (double u : {0.5, 1.7, -3.0}) {
    const ContactMode md = u > 0 ? ContactMode::slip_pos : ContactMode::slip_neg;
    const double h = 1e-6;
    const double fd = (c.kinetic_force(md, 0, u + h) - c.kinetic_force(md, 0, u - h)) / (2 * h);
    EXPECT_NEAR(c.kinetic_slope(0, u), fd, 1e-6) << u;
  }
  EXPECT_EQ(c.steepest_kinetic_slope(), 0.0);
}

// Claim: a normal force that turns negative opens the clutch: r(t) = max(0, f_N)/f_N,ref, its zero
// crossings are breakpoints, and it is released while f_N ≤ 0.
TEST(ClutchLaw, NegativeNormalForceOpens) {
  const Model m = model_of(R"(
bodies: {a: {inertia: 1}, b: {inertia: 1}}
clutches: {c: {between: [a, b], normal_force: {type: sine, amplitude: 50 N, frequency: 1 Hz}, mu_s: 0.5, mu_k: 0.4, radius: 1 m}}
simulation: {t_end: 2 s}
)");
  const FrictionContact& c = m.contacts[0];
  EXPECT_DOUBLE_EQ(c.static_limit, 0.5 * 50);
  EXPECT_NEAR(c.scale(0.25), 1.0, 1e-15);
  EXPECT_EQ(c.scale(0.75), 0.0);
  EXPECT_TRUE(c.released(0.75));
  EXPECT_FALSE(c.released(0.25));
  const auto b = m.breakpoints(2.0);
  for (double t : {0.5, 1.0, 1.5}) EXPECT_TRUE(std::any_of(b.begin(), b.end(), [&](double x) { return std::abs(x - t) < 1e-14; })) << t;
}

std::string errors_of(const std::string& yaml) {
  try {
    (void)model_of(yaml);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Claim: bad clutch and brake input is located (file:line:col) and every problem listed.
TEST(ClutchInput, BadInputIsLocated) {
  const std::string e = errors_of(R"(bodies: {a: {inertia: 1}, b: {inertia: 1}}
clutches:
  self: {between: [a, a], normal_force: 1 kN, mu_s: 0.3, mu_k: 0.2, radius: 0.1 m}
  neg: {between: [a, b], normal_force: 1 kN, mu_s: -0.3, mu_k: 0.2, radius: 0.1 m}
  rad: {between: [a, b], normal_force: 1 kN, mu_s: 0.3, mu_k: 0.2, radius: 0 m}
  gnd: {between: [a, ground], normal_force: 1 kN, mu_s: 0.3, mu_k: 0.2, radius: 0.1 m}
  dim: {between: [a, b], normal_force: 3 m, mu_s: 0.3, mu_k: 0.2, radius: 0.1 m}
  kin: {between: [a, b], normal_force: 1 kN, mu_s: 0.3, mu_k: 0.4, radius: 0.1 m}
  stb: {between: [a, b], normal_force: 1 kN, mu_s: 0.3, mu_k: 0.2, radius: 0.1 m, stribeck_speed: 1 rad/s, stribeck_exponent: 0.5}
brakes:
  B: {body: a, housing: a, holding: 10 N*m}
  C: {body: a, holding: 10 N*m, time: 1 s, application: 1}
)");
  EXPECT_NE(e.find("cl.yaml:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("joins 'a' to itself"), std::string::npos) << e;
  EXPECT_NE(e.find("cl.yaml:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("'mu_s' must be positive"), std::string::npos) << e;
  EXPECT_NE(e.find("cl.yaml:5:"), std::string::npos) << e;
  EXPECT_NE(e.find("'radius' must be positive"), std::string::npos) << e;
  EXPECT_NE(e.find("cl.yaml:6:"), std::string::npos) << e;
  EXPECT_NE(e.find("a clutch joins two bodies"), std::string::npos) << e;
  EXPECT_NE(e.find("cl.yaml:7:"), std::string::npos) << e;
  EXPECT_NE(e.find("cl.yaml:8:"), std::string::npos) << e;
  EXPECT_NE(e.find("exceeds the static limit"), std::string::npos) << e;
  EXPECT_NE(e.find("cl.yaml:9:"), std::string::npos) << e;
  EXPECT_NE(e.find("'stribeck_exponent' must be at least 1"), std::string::npos) << e;
  EXPECT_NE(e.find("cl.yaml:11:"), std::string::npos) << e;
  EXPECT_NE(e.find("the brake joins 'a' to itself"), std::string::npos) << e;
  EXPECT_NE(e.find("cl.yaml:12:"), std::string::npos) << e;
  EXPECT_NE(e.find("give either 'application' or 'time'"), std::string::npos) << e;
}

// Claim: a clutch's normal force from a CSV file that does not exist is an input error located at
// the file's `path` field (io resolves the file before compile).
TEST(ClutchInput, MissingCsvIsLocated) {
  const std::string path = std::string(MACHDYN_TEST_OUTPUT) + "/clutch_missing_csv.yaml";
  {
    std::FILE* f = std::fopen(path.c_str(), "w");
    ASSERT_NE(f, nullptr);
    std::fputs("bodies: {a: {inertia: 1}, b: {inertia: 1}}\n"
               "clutches:\n"
               "  c: {between: [a, b], mu_s: 0.3, mu_k: 0.2, radius: 0.1 m,\n"
               "      normal_force: {type: file, path: no-such.csv, time: t, column: fn}}\n",
               f);
    std::fclose(f);
  }
  std::string e;
  try {
    (void)load_model(path);
  } catch (const InputError& err) {
    e = err.what();
  }
  EXPECT_NE(e.find("clutch_missing_csv.yaml:4:"), std::string::npos) << e;
  EXPECT_NE(e.find("no-such.csv"), std::string::npos) << e;
}

}  // namespace
}  // namespace machdyn
