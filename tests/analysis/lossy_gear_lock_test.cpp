// A lossy gear decided together with the friction elements to the ground on its bodies
// (analysis/gear_lock.hpp): a brake holding a gear against a ramped load breaks away at the closed-form
// instant and carries the closed-form share of the holding torque, on either side of the gear; a brake
// stopping a rolling gear at the closed-form instant; MSL's
// LossyGearDemo2 against an independent piecewise closed form of MSL's equations written here; and
// the located errors of the friction elements that remain unsupported on a lossy gear's bodies.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/gear_phases.hpp"
#include "support/events.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::events_of;
using test::series;

class GearLockSim : public ::testing::TestWithParam<const char*> {};
INSTANTIATE_TEST_SUITE_P(BothIntegrators, GearLockSim, ::testing::Values("dopri5", "bdf"));

// A gear (ratio i = 3, η_mf1 = 0.9, η_mf2 = 0.6, no bearing friction) between A (0.4 kg·m²) and B
// (2.5 kg·m²), at rest, B loaded by M_B = −c t (c = 10 N·m/s), a brake of H = 2 N·m (holding =
// braking) on one side. In a's coordinate F_b' = M_B / i.
// Brake on A: B's load turns the gear backward with B driving; the gear's backward margin is
// m_−1 = (F_a + η_mf2 F_b')/η_mf2 (elements/lossy_gear.hpp). With the brake at its limit against that
// start (+H on A) the pair holds while H + η_mf2 M_B/i ≥ 0, so it breaks away at
//   t* = H i / (η_mf2 c) = 1 s.
// Before, the gear holds what it can (nothing: alone it would start at once) and the brake the rest:
// its load λ with m_−1 = (−λ + η_mf2 M_B/i)/η_mf2 = 0, λ = −η_mf2 c t / i (it pushes A forward).
// Brake on B: with its limit against the backward start (+H on B) m_−1 = (η_mf2 (M_B + H)/i)/η_mf2 ⇒
// t* = H/c = 0.2 s; the gear cannot hold B's load (A has no load to hold it against), so the brake
// carries all of it: its force F (−F on B) = M_B = −c t.
// After t*, rolling backward with B driving and the brake sliding at H against the motion:
//   (I_A + η_mf2 I_B/i²) a_A = F_a + η_mf2 F_b' = −(η_mf2 c / i)(t − t*)   (both cases), so
//   v_A = −(η_mf2 c / i) (t − t*)² / (2 (I_A + η_mf2 I_B / i²)),  v_B = v_A / i.
struct BrakedGear {
  static constexpr double IA = 0.4, IB = 2.5, i = 3.0, eta1 = 0.9, eta2 = 0.6, H = 2.0, c = 10.0;
  bool on_a = true;
  [[nodiscard]] double t_star() const { return on_a ? H * i / (eta2 * c) : H / c; }
  [[nodiscard]] double speed_a(double t) const {
    const double ts = t_star();
    return t <= ts ? 0.0 : -(eta2 * c / i) * (t - ts) * (t - ts) / (2.0 * (IA + eta2 * IB / (i * i)));
  }
  /// The brake's force F (machdyn: −F on its body) while stuck.
  [[nodiscard]] double brake_force(double t) const { return on_a ? -eta2 * c * t / i : -c * t; }
  [[nodiscard]] std::string yaml(const char* integrator) const {
    return fmt::format(R"(bodies:
  A: {{inertia: {} kg*m^2}}
  B: {{inertia: {} kg*m^2}}
links:
  G: {{type: lossy-gear, between: [A, B], ratio: {}, efficiency: {}, efficiency_reverse: {}}}
brakes:
  br: {{body: {}, holding: {} N*m}}
loads:
  MB: {{type: ramp, body: B, before: 0 N*m, value: {} N*m, start: 0 s, end: 2 s}}
simulation: {{t_end: 2, dt_out: 0.01, rtol: 1e-11, atol: 1e-13, integrator: {}}}
)", IA, IB, i, eta1, eta2, on_a ? "A" : "B", H, -2.0 * c, integrator);
  }
};

// Claim: a brake on the input (or on the output) of a lossy gear holds it against a ramped load until
// the closed-form breakaway t*, within 1e-8 s; the gear and the brake switch together (stuck → rolling
// backward, stuck → sliding backward at the same instant); while stuck the brake carries the
// closed-form share (within 1e-9 N·m) and the bodies stay at rest; afterwards the speeds follow the
// closed form within 1e-8 rad/s (1e-6 on BDF).
TEST_P(GearLockSim, BrakeHoldsTheGearUntilTheClosedFormBreakaway) {
  for (bool on_a : {true, false}) {
    BrakedGear ref;
    ref.on_a = on_a;
    const SimulationResult r = simulate(test::model_text(ref.yaml(GetParam()), "gear.yaml"));
    const auto gear = events_of(r, "G"), brake = events_of(r, "br");
    ASSERT_EQ(gear.size(), 1u) << on_a;
    ASSERT_EQ(brake.size(), 1u) << on_a;
    EXPECT_NEAR(gear[0].t, ref.t_star(), 1e-8) << on_a;
    EXPECT_EQ(gear[0].from, "stuck");
    EXPECT_EQ(gear[0].to, "backward_b_drives");
    EXPECT_EQ(brake[0].t, gear[0].t);
    EXPECT_EQ(brake[0].to, "slip-");
    const double tol = std::string(GetParam()) == "bdf" ? 1e-6 : 1e-8;
    const auto& t = series(r, "t_s");
    const auto& wa = series(r, "A.velocity_rad_s");
    const auto& wb = series(r, "B.velocity_rad_s");
    const auto& F = series(r, "br.force_N_m");
    for (size_t k = 0; k < t.size(); ++k) {
      EXPECT_NEAR(wa[k], ref.speed_a(t[k]), tol) << on_a << " " << t[k];
      EXPECT_NEAR(wb[k], wa[k] / BrakedGear::i, 1e-12 * (1.0 + std::abs(wa[k])));
      if (t[k] < ref.t_star() - 1e-9) {
        EXPECT_EQ(wa[k], 0.0) << t[k];
        EXPECT_NEAR(F[k], ref.brake_force(t[k]), 1e-9) << on_a << " " << t[k];
      } else if (t[k] > ref.t_star() + 1e-9) {
        EXPECT_NEAR(F[k], -BrakedGear::H, 1e-12) << t[k];  // sliding backward: F = −H
      }
    }
  }
}

// A gear (i = 3, η_mf1 = 0.9) rolling forward at v_A0 = 10 rad/s with no loads, a brake of H = 20 N·m
// on its output B. The brake slides against the motion (−H on B, F_b' = −H/i) and A's inertia drives B
// (D = −I_A F_b' > 0), so (η_mf1 I_A + J_B) a = −H/i with J_B = I_B/i²: a constant deceleration, rest at
//   t_s = v_A0 (η_mf1 I_A + J_B) i / H
// and v_A = v_A0 − (H/i) t/(η_mf1 I_A + J_B) before. At rest there is no load: the pair sticks (the
// brake's share 0). Energy: A delivers X = −I_A a into the gear, the mesh loses (1 − η_mf1) X v_A, so
// the gear's heat is (1 − η_mf1) I_A v_A0²/2 and the brake's H ∫v_B = (η_mf1 I_A + J_B) v_A0²/2: the
// friction losses are the kinetic energy ½ (I_A + J_B) v_A0².
// Claim: the stop (gear and brake together) at t_s within 1e-8 s, the speed within 1e-8 rad/s (1e-6
// on BDF) at every row, at rest afterwards with the brake's load 0, and the friction losses equal the
// initial kinetic energy within 1e-9 relative.
TEST_P(GearLockSim, BrakeOnTheOutputStopsARollingGearAtTheClosedFormInstant) {
  const double IA = 0.4, IB = 2.5, i = 3.0, eta1 = 0.9, H = 20.0, v0 = 10.0;
  const double Jb = IB / (i * i), ts = v0 * (eta1 * IA + Jb) * i / H;
  const SimulationResult r = simulate(test::model_text(fmt::format(R"(bodies:
  A: {{inertia: {} kg*m^2, velocity: {} rad/s}}
  B: {{inertia: {} kg*m^2}}
links:
  G: {{type: lossy-gear, between: [A, B], ratio: {}, efficiency: {}, efficiency_reverse: 0.5}}
brakes:
  br: {{body: B, holding: {} N*m}}
simulation: {{t_end: 2, dt_out: 0.01, rtol: 1e-11, atol: 1e-13, integrator: {}}}
)", IA, v0, IB, i, eta1, H, GetParam()), "gear.yaml"));
  const auto gear = events_of(r, "G"), brake = events_of(r, "br");
  ASSERT_EQ(gear.size(), 1u);
  ASSERT_EQ(brake.size(), 1u);
  EXPECT_EQ(gear[0].from, "forward");
  EXPECT_EQ(gear[0].to, "stuck");
  EXPECT_EQ(brake[0].to, "stuck");
  EXPECT_NEAR(gear[0].t, ts, 1e-8);
  EXPECT_EQ(brake[0].t, gear[0].t);
  const double tol = std::string(GetParam()) == "bdf" ? 1e-6 : 1e-8;
  const auto& t = series(r, "t_s");
  const auto& wa = series(r, "A.velocity_rad_s");
  const auto& F = series(r, "br.force_N_m");
  for (size_t k = 0; k < t.size(); ++k) {
    EXPECT_NEAR(wa[k], std::max(0.0, v0 - (H / i) * t[k] / (eta1 * IA + Jb)), tol) << t[k];
    if (t[k] > ts + 1e-9) {
      EXPECT_EQ(wa[k], 0.0) << t[k];
      EXPECT_EQ(F[k], 0.0) << t[k];
    }
  }
  const double T0 = 0.5 * (IA + Jb) * v0 * v0;
  EXPECT_NEAR(r.hybrid.energy.friction_loss, T0, 1e-9 * T0);
}

// MSL's LossyGearDemo2 (Modelica.Mechanics.Rotational.Examples): Demo1 (J1 = 1, J2 = 1.5, ratio r = 2,
// η_mf1 = η_mf2 = 0.5, τ1 = 10 sin 2πt on Inertia1, τ2 = −10 + 2.5 t on Inertia2) plus a
// BearingFriction on Inertia1 with tau_pos = [0, 0.5; 1, 1] (extrapolated through its last two points:
// F(w) = sign(w) (0.5 + 0.5 |w|)) and peak 1 (it holds up to 0.5 N·m).
// Rolling in direction s with quadrant factor k (MSL: L = (1 − k) τ_a, 0 = τ_b + r (τ_a − L)): with
// J1 a = τ1 − F(w) − τ_a and J2 a / r = τ2 − τ_b,
//   a = (τ2 + r k (τ1 − F(w))) / D,  D = J2/r + r k J1,
// linear in w: w' = −β w + p + q t + A sin ωt with β = r k / (2D), p = (−10 − r k s / 2)/D, q = 2.5/D,
// A = 10 r k / D, ω = 2π; so w(t) = w_p(t) + (w0 − w_p(t0)) e^(−β (t − t0)) with
//   w_p(t) = (p − q/β)/β + q t/β + A (β sin ωt − ω cos ωt)/(β² + ω²).
// Quadrant (MSL's tau_etaPos = τ_a ≥ 0): forward k = η_mf1 if τ_a ≥ 0 else 1/η_mf2, backward k = 1/η_mf2
// if τ_a ≥ 0 else η_mf1; eliminating a, τ_a = (τ1 − F − J1 r τ2/J2)/(1 + J1 r² k/J2) has the sign of
// τ1 − F(w) − (J1 r/J2) τ2 for every k > 0.
// At rest both stick. The gear alone, with flange torque τ_a, starts forward when sa = τ_a + τ2/r >
// tauLossMax_p ((1 − η_mf1) τ_a if τ_a > 0, else (1 − 1/η_mf2) τ_a) and backward when sa < tauLossMin_m
// ((1 − 1/η_mf2) τ_a if τ_a > 0, else (1 − η_mf1) τ_a). With the friction torque f ∈ [−0.5, 0.5] the
// flange torque is τ_a = τ1 − f; sa − tauLossMax_p rises with τ_a (slope η_mf1 or 1/η_mf2), so the pair
// starts forward exactly when the gear starts with f = 0.5 (the friction at its limit against the start),
// backward when it starts with f = −0.5. A start is a slide of the friction too (F(0) = 0.5 = its limit).
// Switches: scan (1e-4 s) and bisection to 1e-15 s on these closed forms.
struct Demo2Reference : test::GearPhases {
  static constexpr double J1 = 1.0, J2 = 1.5, r = 2.0, eta1 = 0.5, eta2 = 0.5, Fs = 0.5, kPi = 3.14159265358979323846;
  using Segment = test::GearPhase;

  static double tau1(double t) { return 10.0 * std::sin(2 * kPi * t); }
  static double tau2(double t) { return -10.0 + 2.5 * t; }
  static double friction(int s, double w) { return 0.5 * s + 0.5 * w; }  // w of sign s
  static double w(const Segment& g, double t) {
    const double D = J2 / r + r * g.k * J1, beta = r * g.k / (2 * D), om = 2 * kPi;
    const double p = (-10.0 - r * g.k * g.s / 2) / D, q = 2.5 / D, A = 10.0 * r * g.k / D;
    auto wp = [&](double x) {
      return (p - q / beta) / beta + q * x / beta +
             A * (beta * std::sin(om * x) - om * std::cos(om * x)) / (beta * beta + om * om);
    };
    return wp(t) + (g.w0 - wp(g.t0)) * std::exp(-beta * (t - g.t0));
  }
  /// > 0: the gear alone with flange torque τ_a starts forward (MSL's startForward test).
  static double gear_fwd(double ta, double t) {
    return ta + tau2(t) / r - (ta > 0 ? (1 - eta1) * ta : (1 - 1 / eta2) * ta);
  }
  /// > 0: it starts backward.
  static double gear_bwd(double ta, double t) {
    return (ta > 0 ? (1 - 1 / eta2) * ta : (1 - eta1) * ta) - (ta + tau2(t) / r);
  }
  static double start_fwd(double t) { return gear_fwd(tau1(t) - Fs, t); }
  static double start_bwd(double t) { return gear_bwd(tau1(t) + Fs, t); }
  /// k of the quadrant of direction s at t and speed w.
  static double quadrant(int s, double t, double wt) {
    const double sign_ta = tau1(t) - friction(s, wt) - J1 * r / J2 * tau2(t);
    return s > 0 ? (sign_ta >= 0 ? eta1 : 1 / eta2) : (sign_ta >= 0 ? 1 / eta2 : eta1);
  }

  explicit Demo2Reference(double t_end) : GearPhases(t_end, start_fwd, start_bwd, quadrant, w) {}
  /// The split of the documented rule while both stick: the friction torque f of least |f| with which
  /// the gear holds alone (MSL's start tests ≤ 0 at τ_a = τ1 − f), by bisection on [0, ±0.5].
  [[nodiscard]] static double stuck_friction(double t) {
    const double t1 = tau1(t);
    if (gear_fwd(t1, t) > 0) {  // f > 0 needed: gear_fwd(τ1 − f) falls as f grows
      double lo = 0.0, hi = Fs;
      while (hi - lo > 1e-15) ((gear_fwd(t1 - 0.5 * (lo + hi), t) > 0) ? lo : hi) = 0.5 * (lo + hi);
      return hi;
    }
    if (gear_bwd(t1, t) > 0) {
      double lo = -Fs, hi = 0.0;
      while (hi - lo > 1e-15) ((gear_bwd(t1 - 0.5 * (lo + hi), t) > 0) ? hi : lo) = 0.5 * (lo + hi);
      return lo;
    }
    return 0.0;
  }
};

class GearLockMsl : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, GearLockMsl, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

// Claim: examples/msl/lossy-gear-demo2.yaml (MSL LossyGearDemo2) switches its modes at the reference's
// instants (within 1e-8 s), the bearing friction switches with the gear (its mode equals the gear's
// direction at every row, its events are the gear's direction changes), the speeds follow the
// reference at every 1 ms row (1e-7 rad/s; BDF 1e-6), the friction torque is F(w) while sliding and
// the documented split while stuck (within 1e-9 N·m), the gear takes all three modes and the loss
// power is never negative.
TEST_P(GearLockMsl, Demo2MatchesThePiecewiseClosedForm) {
  Model m = load_model(std::string(MACHDYN_SOURCE_DIR) + "/examples/msl/lossy-gear-demo2.yaml");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const Demo2Reference ref(0.5);
  const auto ev = events_of(r, "gear");
  std::string listed;
  for (const auto& e : ev) listed += fmt::format(" {:.9f} {}->{};", e.t, e.from, e.to);
  listed += " reference:";
  for (double x : ref.switches) listed += fmt::format(" {:.9f}", x);
  ASSERT_EQ(ev.size(), ref.switches.size()) << listed;
  for (size_t k = 0; k < ev.size(); ++k) EXPECT_NEAR(ev[k].t, ref.switches[k], 1e-8) << ev[k].kind << " " << ev[k].to;
  size_t direction_changes = 0;
  for (const auto& e : ev) direction_changes += e.kind != "driving_side";
  const auto fr = events_of(r, "bearingFriction");
  EXPECT_EQ(fr.size(), direction_changes) << listed;
  for (const auto& e : fr)
    EXPECT_TRUE(std::any_of(ev.begin(), ev.end(),
                            [&](const ModeEvent& g) { return g.t == e.t && g.kind != "driving_side"; }))
        << e.t;
  const double tol = GetParam() == IntegratorChoice::bdf ? 1e-6 : 1e-7;
  const auto& t = series(r, "t_s");
  const auto& w1 = series(r, "Inertia1.velocity_rad_s");
  const auto& w2 = series(r, "Inertia2.velocity_rad_s");
  const auto& mode = series(r, "gear.mode");
  const auto& fmode = series(r, "bearingFriction.mode");
  const auto& F = series(r, "bearingFriction.force_N_m");
  const auto& loss = series(r, "gear.loss_power_W");
  ASSERT_EQ(t.size(), 501u);
  bool seen[3] = {false, false, false};
  for (size_t k = 0; k < t.size(); ++k) {
    EXPECT_NEAR(w1[k], ref.speed(t[k]), tol) << t[k];
    EXPECT_NEAR(w2[k], w1[k] / 2.0, 1e-12 * (1.0 + std::abs(w1[k])));
    EXPECT_EQ(fmode[k], mode[k]) << t[k];
    seen[static_cast<int>(mode[k]) + 1] = true;
    EXPECT_GE(loss[k], -1e-9);
    const int s = static_cast<int>(mode[k]);
    if (s != 0) EXPECT_NEAR(F[k], Demo2Reference::friction(s, w1[k]), 1e-12) << t[k];
    else EXPECT_NEAR(F[k], Demo2Reference::stuck_friction(t[k]), 1e-9) << t[k];
  }
  EXPECT_TRUE(seen[0] && seen[1] && seen[2]);
}

// A hoist: motor A (I_A = 0.2) – lossy gear (i = 20, η_mf1 = 0.8, η_mf2 = 0.6: not self-locking, no
// bearing friction) – drum B (I_B = 5) with the load −L = −100 N·m; a backstop [ground, A] (A may turn
// forward only); the motor torque τ0 = 10 N·m until t_off = 1 s, 0 until t_on = 3 s, τ0 again.
// In a's coordinate F_b' = −L/i = −5, J_B = I_B/i² = 0.0125, E = η_mf1 I_A + J_B (A drives: elements/lossy_gear.hpp).
// 1. At rest the gear's forward margin −(η_mf1 τ0 − L/i) = −3 < 0: it starts at once, A driving,
//    a1 = (η_mf1 τ0 − L/i)/E; the backstop runs free.
// 2. From t_off, F_a = 0: D = −I_A F_b' > 0, A still drives: a2 = (−L/i)/E; rest at t_s = t_off (1 − a1/a2).
// 3. At rest the load would turn the gear back with B driving (N₋ = F_a + η_mf2 F_b' = −3 < 0): the
//    backstop holds, carrying what makes the backward margin 0: a torque η_mf2 L/i = 3 N·m on A.
// 4. At t_on the forward margin is −3 again: gear and backstop start together, v_A = a1 (t − t_on).
// Claim: the gear stops at t_s and starts at t_on, the backstop locks and frees with it (each once, within
// 1e-8 s); A's speed follows the closed form at every row within 1e-8 rad/s (1e-6 on BDF) and never
// turns backwards beyond rounding; the locked backstop carries η_mf2 L/i within 1e-9 N·m.
TEST_P(GearLockSim, BackstopHoldsAHoistGearThatIsNotSelfLocking) {
  const double IA = 0.2, IB = 5.0, i = 20.0, e1 = 0.8, e2 = 0.6, L = 100.0, tau0 = 10.0, t_off = 1.0, t_on = 3.0;
  const double E = e1 * IA + IB / (i * i), a1 = (e1 * tau0 - L / i) / E, a2 = (-L / i) / E;
  const double ts = t_off * (1.0 - a1 / a2);
  const SimulationResult r = simulate(test::model_text(fmt::format(R"(bodies:
  A: {{inertia: {} kg*m^2}}
  B: {{inertia: {} kg*m^2}}
links:
  G: {{type: lossy-gear, between: [A, B], ratio: {}, efficiency: {}, efficiency_reverse: {}}}
freewheels:
  bs: {{between: [ground, A]}}
loads:
  motor: {{type: table, body: A, points: [[0, {}], [{}, {}], [{}, 0], [{}, 0], [{}, {}], [5, {}]]}}
  weight: {{type: constant, body: B, value: {} N*m}}
simulation: {{t_end: 4, dt_out: 0.01, rtol: 1e-11, atol: 1e-13, integrator: {}}}
)", IA, IB, i, e1, e2, tau0, t_off, tau0, t_off, t_on, t_on, tau0, tau0, -L, GetParam()), "gear.yaml"));
  const auto gear = events_of(r, "G"), bs = events_of(r, "bs");
  ASSERT_EQ(gear.size(), 2u);
  EXPECT_EQ(gear[0].to, "stuck");
  EXPECT_NEAR(gear[0].t, ts, 1e-8);
  EXPECT_EQ(gear[1].to, "forward");
  EXPECT_NEAR(gear[1].t, t_on, 1e-8);
  ASSERT_EQ(bs.size(), 2u);
  EXPECT_EQ(bs[0].to, "stuck");
  EXPECT_NEAR(bs[0].t, ts, 1e-8);
  EXPECT_NE(bs[1].to, "stuck");
  EXPECT_NEAR(bs[1].t, t_on, 1e-8);
  const double tol = std::string(GetParam()) == "bdf" ? 1e-6 : 1e-8;
  const auto& t = series(r, "t_s");
  const auto& wa = series(r, "A.velocity_rad_s");
  const auto& F = series(r, "bs.force_N_m");
  for (size_t j = 0; j < t.size(); ++j) {
    const double w = t[j] <= t_off ? a1 * t[j] : t[j] <= ts ? a1 * t_off + a2 * (t[j] - t_off) : t[j] <= t_on ? 0.0 : a1 * (t[j] - t_on);
    EXPECT_NEAR(wa[j], w, tol) << t[j];
    EXPECT_GE(wa[j], -1e-12) << t[j];
    if (t[j] > ts + 1e-9 && t[j] < t_on - 1e-9) {
      EXPECT_NEAR(std::abs(F[j]), e2 * L / i, 1e-9) << t[j];
    }
  }
}

// The hoist gear of the test above with a friction contact of H = 20 N·m (static = kinetic) on the drum B
// beside the backstop on A: one bounded split decides both (analysis/gear_lock.hpp). Forward rolling
// (A drives) the contact slides against it with −H on B: F_b' = (−L − H)/i = −6 N·m.
// 1. From rest with τ0: the forward margin η_mf1 τ0 + F_b' = 2 > 0 (the contact at its bound
//    opposing the start), so the gear starts at t = 0: a1 = (η_mf1 τ0 − (L + H)/i)/E, E = η_mf1 I_A + I_B/i².
// 2. From t_off, τ = 0: a2 = (−(L + H)/i)/E (A still drives); rest at t_s = t_off (1 − a1/a2).
// 3. At rest: backward (B driving) the gear holds while T_bs + η_mf2 (T_c − L)/i ≥ 0, T_bs ≥ 0 the
//    backstop's torque on A, |T_c| ≤ H the contact's on B (both forward); the gear alone (−3 N·m) does not.
//    The split takes the least T_bs²/1² + T_c²/(√H)² (the stuck set's weights: 1 for a lock, √F_s) on
//    that line: T_bs = μ, T_c = μ H η_mf2/i, μ = (η_mf2 L/i)/(1 + H (η_mf2/i)²) (within |T_c| ≤ H).
// 4. At t_on the forward margin is 2 again: gear, contact and backstop start together, v_A = a1 (t − t_on).
// Claim: the gear stops at t_s and starts at t_on (each within 1e-8 s), A's speed follows the closed form
// within 1e-8 rad/s (1e-6 on BDF), and while held the backstop carries μ and the contact μ H η_mf2/i
// within 1e-9 N·m.
TEST_P(GearLockSim, BackstopBesideAContactOnTheDrumShareTheHoldingTorqueByTheSplit) {
  const double IA = 0.2, IB = 5.0, i = 20.0, e1 = 0.8, e2 = 0.6, L = 100.0, H = 20.0, tau0 = 10.0, t_off = 1.0,
               t_on = 3.0;
  const double E = e1 * IA + IB / (i * i), a1 = (e1 * tau0 - (L + H) / i) / E, a2 = (-(L + H) / i) / E;
  const double ts = t_off * (1.0 - a1 / a2);
  const double mu = (e2 * L / i) / (1.0 + H * (e2 / i) * (e2 / i)), Tc = mu * H * e2 / i;
  const SimulationResult r = simulate(test::model_text(fmt::format(R"(bodies:
  A: {{inertia: {} kg*m^2}}
  B: {{inertia: {} kg*m^2}}
links:
  G: {{type: lossy-gear, between: [A, B], ratio: {}, efficiency: {}, efficiency_reverse: {}}}
freewheels:
  bs: {{between: [ground, A]}}
contacts:
  c: {{between: [B, ground], static: {} N*m, kinetic: {} N*m}}
loads:
  motor: {{type: table, body: A, points: [[0, {}], [{}, {}], [{}, 0], [{}, 0], [{}, {}], [5, {}]]}}
  weight: {{type: constant, body: B, value: {} N*m}}
simulation: {{t_end: 4, dt_out: 0.01, rtol: 1e-11, atol: 1e-13, integrator: {}}}
)", IA, IB, i, e1, e2, H, H, tau0, t_off, tau0, t_off, t_on, t_on, tau0, tau0, -L, GetParam()), "gear.yaml"));
  const auto gear = events_of(r, "G");
  ASSERT_EQ(gear.size(), 2u);
  EXPECT_EQ(gear[0].to, "stuck");
  EXPECT_NEAR(gear[0].t, ts, 1e-8);
  EXPECT_EQ(gear[1].to, "forward");
  EXPECT_NEAR(gear[1].t, t_on, 1e-8);
  const double tol = std::string(GetParam()) == "bdf" ? 1e-6 : 1e-8;
  const auto& t = series(r, "t_s");
  const auto& wa = series(r, "A.velocity_rad_s");
  const auto& Fbs = series(r, "bs.force_N_m");
  const auto& Fc = series(r, "c.force_N_m");
  int held = 0;
  for (size_t j = 0; j < t.size(); ++j) {
    const double w = t[j] <= t_off ? a1 * t[j] : t[j] <= ts ? a1 * t_off + a2 * (t[j] - t_off) : t[j] <= t_on ? 0.0 : a1 * (t[j] - t_on);
    EXPECT_NEAR(wa[j], w, tol) << t[j];
    if (t[j] > ts + 1e-9 && t[j] < t_on - 1e-9) {
      ++held;
      EXPECT_NEAR(std::abs(Fbs[j]), mu, 1e-9) << t[j];
      EXPECT_NEAR(std::abs(Fc[j]), Tc, 1e-9) << t[j];
    }
  }
  EXPECT_GT(held, 50);
}

// Claim: the friction elements that remain unsupported on a lossy gear's bodies are located errors
// that say why (a clutch between the gear's own bodies, an end stop, a moving ground surface); a brake, a
// ground contact, bearing friction, and a backstop beside a brake or a clutch compile.
TEST(GearLockCompile, UnsupportedFrictionOnAGearBodyIsALocatedError) {
  const std::string head = "bodies:\n  A: {inertia: 1}\n  B: {inertia: 2}\n  C: {inertia: 3}\nlinks:\n"
                           "  G: {type: lossy-gear, between: [A, B], efficiency: 0.9}\n";
  auto check = [&](const std::string& more, const std::string& why) {
    const std::string e = test::compile_errors(head + more, "gear.yaml");
    EXPECT_NE(e.find("gear.yaml:6:"), std::string::npos) << more << "\n" << e;
    EXPECT_NE(e.find(why), std::string::npos) << more << "\n" << e;
  };
  // A clutch to another body is decided with the gear (analysis/gear_clutch.hpp; beside friction to the
  // ground too), but not one between the gear's own bodies.
  check("contacts:\n  c: {between: [B, A], static: 1 N*m, kinetic: 1 N*m}\n", "joins the gear's own two bodies");
  check("stops:\n  s: {body: A, min: -1 rad}\n", "end stops on a lossy gear's bodies are not supported yet");
  check("contacts:\n  c: {between: [A, ground], static: 1 N*m, kinetic: 1 N*m, surface_velocity: 2 rad/s}\n",
        "moving surface");
  const Model ok = test::model_text(head + "brakes:\n  br: {body: B, holding: 5 N*m}\ncontacts:\n"
                                           "  c: {between: [A, ground], static: 1 N*m, kinetic: [[0, 1], [1, 2]]}\n",
                                    "gear.yaml");
  EXPECT_EQ(ok.lossy_gears.size(), 1u);
  EXPECT_EQ(ok.contacts.size(), 2u);
  const Model backstop = test::model_text(head + "freewheels:\n  f: {between: [ground, A]}\nbrakes:\n  br: {body: B, holding: 5 N*m}\n",
                                          "gear.yaml");
  EXPECT_EQ(backstop.contacts.size(), 2u);
  const Model clutched = test::model_text(head + "freewheels:\n  f: {between: [ground, A]}\ncontacts:\n"
                                                 "  k: {between: [B, C], static: 5 N*m, kinetic: 5 N*m}\n", "gear.yaml");
  EXPECT_EQ(clutched.contacts.size(), 2u);
}

}  // namespace
}  // namespace machdyn
