// A lossy gear decided together with a clutch on one of its bodies (analysis/gear_clutch.hpp), against
// closed forms derived here from the gear's law (elements/lossy_gear.hpp) and the clutch's: a sliding
// clutch locks onto a rolling gear's output at the closed-form instant; a gear starts from rest with
// its clutch holding and the clutch slips at the closed-form instant; a flywheel beyond a stuck clutch
// drives the gear from its output side; a massless output side; and the
// located errors of the combinations that remain unsupported.
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "support/events.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::events_of;
using test::series;

class GearClutchSim : public ::testing::TestWithParam<const char*> {};
INSTANTIATE_TEST_SUITE_P(BothIntegrators, GearClutchSim, ::testing::Values("dopri5", "bdf"));

// A motor torque M on A (I_A), a lossy gear A → B (ratio i, η_mf1 = 0.9, η_mf2 = 0.7, no bearing
// friction), a clutch from B to C (I_C) whose torque limit rises as T(t) = k t (μ_s = μ_k = 0.5,
// radius 1 m, normal force 2 k t), everything at rest at t = 0.
// At t = 0 the gear cannot hold M (its forward margin −η M < 0) and the clutch carries nothing
// (T(0) = 0): the gear starts forward with the clutch sliding (u = v_B − v_C > 0).
// Sliding: the clutch puts −k t on B (F_b' = −k t / i in A's coordinate) and +k t on C. A drives
// (D = M J_B + I_A k t / i > 0), so with E = η_mf1 I_A + J_B, J_B = I_B / i²:
//   E a_A = η_mf1 M − k t / i  ⇒  v_A = (η_mf1 M t − k t² / (2 i)) / E,   v_B = v_A / i,
//   I_C a_C = k t              ⇒  v_C = k t² / (2 I_C).
// The clutch sticks where v_B = v_C, i.e. (dividing by t > 0)
//   t* = (η_mf1 M / (i E)) / (k / (2 I_C) + k / (2 i² E)).
// Stuck, C joins B's side: E₂ a_A = η_mf1 M with E₂ = η_mf1 I_A + (I_B + I_C)/i² (A still drives), and
// the clutch holds C's torque λ = I_C a_A / i (+λ on C), which stays below k t* for these numbers.
struct LockingClutch {
  static constexpr double IA = 1.0, IC = 2.0, i = 2.0, eta = 0.9, M = 10.0, k = 20.0;
  double IB = 0.5;  ///< 0: B is a massless flange (MSL's LossyGear – Clutch), J_B = 0 below
  [[nodiscard]] double E() const { return eta * IA + IB / (i * i); }
  [[nodiscard]] double E2() const { return eta * IA + (IB + IC) / (i * i); }
  [[nodiscard]] double t_star() const { return (eta * M / (i * E())) / (k / (2.0 * IC) + k / (2.0 * i * i * E())); }
  [[nodiscard]] double speed_a(double t) const {
    const double ts = t_star();
    if (t <= ts) return (eta * M * t - k * t * t / (2.0 * i)) / E();
    return speed_a(ts) + eta * M / E2() * (t - ts);
  }
  [[nodiscard]] double speed_c(double t) const {
    const double ts = t_star();
    return t <= ts ? k * t * t / (2.0 * IC) : speed_a(t) / i;
  }
  [[nodiscard]] std::string yaml(const char* integrator) const {
    return fmt::format(R"(bodies:
  A: {{inertia: {} kg*m^2}}
  B: {{inertia: {} kg*m^2}}
  C: {{inertia: {} kg*m^2}}
links:
  G: {{type: lossy-gear, between: [A, B], ratio: {}, efficiency: {}, efficiency_reverse: 0.7}}
clutches:
  K: {{between: [B, C], normal_force: {{type: ramp, value: {} N, end: 2 s}}, mu_s: 0.5, mu_k: 0.5, radius: 1 m}}
loads:
  M: {{type: constant, body: A, value: {} N*m}}
simulation: {{t_end: 1, dt_out: 0.01, rtol: 1e-11, atol: 1e-13, integrator: {}}}
)", IA, IB, IC, i, eta, 2.0 * 2.0 * k, M, integrator);
  }
};

// Claim, with I_B = 0.5 and with B massless (I_B = 0): the clutch sticks once, at t* within 1e-8 s, and
// stays stuck while the gear rolls forward with A driving throughout (no gear event); A's and C's speeds follow the closed form at every row within
// 1e-8 rad/s (1e-6 on BDF), B's is A's / i within rounding, and the stuck clutch's torque equals
// I_C a_A / i within 1e-8 N·m.
TEST_P(GearClutchSim, SlidingClutchLocksOntoTheRollingGearAtTheClosedFormInstant) {
  for (double IB : {0.5, 0.0}) {  // 0: B massless (the gear's block of C needs no 1/I_B)
    LockingClutch R;
    R.IB = IB;
    const SimulationResult r = simulate(test::model_text(R.yaml(GetParam()), "gear.yaml"));
    const auto clutch = events_of(r, "K");
    ASSERT_EQ(clutch.size(), 1u) << IB;
    EXPECT_EQ(clutch[0].to, "stuck");
    EXPECT_NEAR(clutch[0].t, R.t_star(), 1e-8) << IB;
    EXPECT_TRUE(events_of(r, "G").empty()) << IB;
    const double tol = std::string(GetParam()) == "bdf" ? 1e-6 : 1e-8;
    const auto& t = series(r, "t_s");
    const auto& wa = series(r, "A.velocity_rad_s");
    const auto& wb = series(r, "B.velocity_rad_s");
    const auto& wc = series(r, "C.velocity_rad_s");
    const auto& F = series(r, "K.force_N_m");
    const auto& mode = series(r, "G.mode");
    for (size_t j = 0; j < t.size(); ++j) {
      EXPECT_NEAR(wa[j], R.speed_a(t[j]), tol) << IB << " " << t[j];
      EXPECT_NEAR(wc[j], R.speed_c(t[j]), tol) << IB << " " << t[j];
      EXPECT_NEAR(wb[j], wa[j] / R.i, 1e-12 * (1.0 + std::abs(wa[j])));
      EXPECT_EQ(mode[j], 1.0) << t[j];
      if (t[j] > R.t_star() + 1e-9) {
        EXPECT_NEAR(F[j], R.IC * (R.eta * R.M / R.E2()) / R.i, 1e-8) << IB << " " << t[j];
      }
    }
  }
}

// A motor torque M = h t on A, the gear of the test above with a bearing friction τ = 1 N·m (both
// directions: τ_bf,a = 0, τ_bf,b = τ), a clutch of constant torque T0 (μ_s = μ_k) from B to C.
// At rest C has no load, so the stuck clutch carries nothing and the gear starts when its forward
// margin −(η M − τ) reaches 0: t1 = τ / (η h), with the clutch stuck (C joins B's side; A drives):
//   E₂ a_A = η h t − τ = η h (t − t1)  ⇒  v_A = η h (t − t1)² / (2 E₂),   λ = I_C a_A / i.
// The clutch slips when λ = T0: t2 = t1 + T0 E₂ i / (I_C η h). Then C accelerates at T0 / I_C and
//   E a_A = η h t − τ − T0 / i  ⇒  v_A(t) = v_A(t2) + (η h (t² − t2²)/2 − (τ + T0/i)(t − t2)) / E,
//   v_C(t) = v_A(t2)/i + T0 (t − t2) / I_C.
struct SlippingClutch {
  static constexpr double IA = 1.0, IB = 0.5, IC = 2.0, i = 2.0, eta = 0.9, h = 10.0, tau = 1.0, T0 = 3.0;
  static constexpr double E = eta * IA + IB / (i * i), E2 = eta * IA + (IB + IC) / (i * i);
  static constexpr double t1 = tau / (eta * h), t2 = t1 + T0 * E2 * i / (IC * eta * h);
  [[nodiscard]] static double speed_a(double t) {
    if (t <= t1) return 0.0;
    if (t <= t2) return eta * h * (t - t1) * (t - t1) / (2.0 * E2);
    return speed_a(t2) + (eta * h * (t * t - t2 * t2) / 2.0 - (tau + T0 / i) * (t - t2)) / E;
  }
  [[nodiscard]] static double speed_c(double t) {
    return t <= t2 ? speed_a(t) / i : speed_a(t2) / i + T0 * (t - t2) / IC;
  }
  [[nodiscard]] static std::string yaml(const char* integrator) {
    return fmt::format(R"(bodies:
  A: {{inertia: {} kg*m^2}}
  B: {{inertia: {} kg*m^2}}
  C: {{inertia: {} kg*m^2}}
links:
  G: {{type: lossy-gear, between: [A, B], ratio: {}, efficiency: {}, efficiency_reverse: 0.7,
      bearing_friction: {} N*m}}
clutches:
  K: {{between: [B, C], normal_force: {} N, mu_s: 0.5, mu_k: 0.5, radius: 1 m}}
loads:
  M: {{type: ramp, body: A, value: {} N*m, end: 1 s}}
simulation: {{t_end: 1, dt_out: 0.01, rtol: 1e-11, atol: 1e-13, integrator: {}}}
)", IA, IB, IC, i, eta, tau, 2.0 * T0, h, integrator);
  }
};

// Claim: the gear starts forward at t1 and the clutch slips forward at t2, each once and within 1e-8 s;
// A's and C's speeds follow the closed form at every row within 1e-8 rad/s (1e-6 on BDF); the stuck
// clutch carries I_C a_A / i (0 at rest) within 1e-8 N·m, the sliding one T0.
TEST_P(GearClutchSim, GearStartsWithItsClutchHoldingAndTheClutchSlipsAtTheClosedFormInstant) {
  using R = SlippingClutch;
  const SimulationResult r = simulate(test::model_text(R::yaml(GetParam()), "gear.yaml"));
  const auto gear = events_of(r, "G"), clutch = events_of(r, "K");
  ASSERT_EQ(gear.size(), 1u);
  EXPECT_EQ(gear[0].from, "stuck");
  EXPECT_EQ(gear[0].to, "forward");
  EXPECT_NEAR(gear[0].t, R::t1, 1e-8);
  ASSERT_EQ(clutch.size(), 1u);
  EXPECT_EQ(clutch[0].to, "slip+");
  EXPECT_NEAR(clutch[0].t, R::t2, 1e-8);
  const double tol = std::string(GetParam()) == "bdf" ? 1e-6 : 1e-8;
  const auto& t = series(r, "t_s");
  const auto& wa = series(r, "A.velocity_rad_s");
  const auto& wc = series(r, "C.velocity_rad_s");
  const auto& F = series(r, "K.force_N_m");
  for (size_t j = 0; j < t.size(); ++j) {
    EXPECT_NEAR(wa[j], R::speed_a(t[j]), tol) << t[j];
    EXPECT_NEAR(wc[j], R::speed_c(t[j]), tol) << t[j];
    const double aA = t[j] <= R::t1 ? 0.0 : R::eta * R::h * (t[j] - R::t1) / R::E2;
    if (t[j] < R::t2 - 1e-9) {
      EXPECT_NEAR(F[j], R::IC * aA / R::i, 1e-8) << t[j];
    } else if (t[j] > R::t2 + 1e-9) {
      EXPECT_NEAR(F[j], R::T0, 1e-12) << t[j];
    }
  }
}

// A (I_A = 1) braked by M = 5 N·m, the gear (i = 2, η_mf1 = 0.9, η_mf2 = 0.7, no bearing friction) to B
// (I_B = 0.5, or massless), a clutch (10 N·m) held stuck to C (I_C = 2); everything turning forward,
// v_A0 = 10 rad/s. The stuck clutch joins C to B's side, J = (I_B + I_C)/i². A is braked and C's
// inertia keeps the train turning: D = −M J < 0 in forward rolling, so B drives and
//   (I_A + η_mf2 J) a = −M  ⇒  v_A = v_A0 − M t / (I_A + η_mf2 J),  rest at t_s = v_A0 (I_A + η_mf2 J)/M;
// then M turns A backward with A driving (no bearing friction: it cannot hold),
//   (η_mf1 I_A + J) a = −η_mf1 M  ⇒  v_A = −η_mf1 M (t − t_s)/(η_mf1 I_A + J),
// and the clutch carries C's torque I_C a / i throughout (|·| < 10 N·m: it stays stuck).
// Claim, with I_B = 0.5 and 0: the gear starts on B's side (initial mode forward_b_drives), reverses once
// at t_s within 1e-8 s to `backward` (A driving); A's speed and the clutch's torque follow the closed
// form at every row within 1e-8 (1e-6 rad/s on BDF); the clutch never switches.
TEST_P(GearClutchSim, FlywheelBeyondAStuckClutchDrivesTheGearFromItsOutputSide) {
  for (double IB : {0.5, 0.0}) {
    const double IA = 1.0, IC = 2.0, i = 2.0, e1 = 0.9, e2 = 0.7, M = 5.0, v0 = 10.0;
    const double J = (IB + IC) / (i * i), ts = v0 * (IA + e2 * J) / M;
    const double a1 = -M / (IA + e2 * J), a2 = -e1 * M / (e1 * IA + J);
    const SimulationResult r = simulate(test::model_text(fmt::format(R"(bodies:
  A: {{inertia: {} kg*m^2, velocity: {} rad/s}}
  B: {{inertia: {} kg*m^2}}
  C: {{inertia: {} kg*m^2, velocity: {} rad/s}}
links:
  G: {{type: lossy-gear, between: [A, B], ratio: {}, efficiency: {}, efficiency_reverse: {}}}
clutches:
  K: {{between: [B, C], normal_force: 20 N, mu_s: 0.5, mu_k: 0.5, radius: 1 m}}
loads:
  M: {{type: constant, body: A, value: {} N*m}}
simulation: {{t_end: 4, dt_out: 0.01, rtol: 1e-11, atol: 1e-13, integrator: {}}}
)", IA, v0, IB, IC, v0 / i, i, e1, e2, -M, GetParam()), "gear.yaml"));
    std::string initial;
    for (const auto& e : r.hybrid.events)
      if (e.element == "G" && e.kind == "initial") initial = e.to;
    EXPECT_EQ(initial, "forward_b_drives") << IB;
    const auto gear = events_of(r, "G");
    ASSERT_EQ(gear.size(), 1u) << IB;
    EXPECT_EQ(gear[0].to, "backward");
    EXPECT_NEAR(gear[0].t, ts, 1e-8) << IB;
    EXPECT_TRUE(events_of(r, "K").empty()) << IB;
    const double tol = std::string(GetParam()) == "bdf" ? 1e-6 : 1e-8;
    const auto& t = series(r, "t_s");
    const auto& wa = series(r, "A.velocity_rad_s");
    const auto& F = series(r, "K.force_N_m");
    for (size_t j = 0; j < t.size(); ++j) {
      const bool before = t[j] < ts;
      EXPECT_NEAR(wa[j], before ? v0 + a1 * t[j] : a2 * (t[j] - ts), tol) << IB << " " << t[j];
      if (std::abs(t[j] - ts) > 1e-9) {
        EXPECT_NEAR(F[j], IC * (before ? a1 : a2) / i, 1e-8) << IB << " " << t[j];
      }
    }
  }
}

// A motor M (I_M) drives a self-locking worm gear A → B (i = 10, η_mf1 = 0.5, η_mf2 = 0, no bearing
// friction; I_A, I_B) through a freewheel [M, A] (M drives A forward, A may overrun M; no drag); a
// load −L on B, the motor torque τ0 until t_off, −τ_r until t_on, τ0 again; everything at rest at 0.
// 1. At rest the gear's forward margin −(η τ0 − L/i) < 0: it starts forward, the freewheel locked
//    (M joins A's side; A drives):  (η (I_M + I_A) + J_B) a1 = η τ0 − L/i,  J_B = I_B/i²,
//    its load λ = τ0 − I_M a1 > 0 (it holds).
// 2. At t_off the motor alone would decelerate at −τ_r/I_M, faster than the gear alone does, so the
//    freewheel overruns at once (λ of the locked pair < 0) and the gear coasts with A driving
//    (A's inertia passes its energy to B):  (η I_A + J_B) a_c = −L/i,  rest at
//    t_s = t_off + a1 t_off / |a_c|, where the self-locking gear holds the load (η_mf2 = 0).
//    The motor: v_M = a1 t_off − τ_r (t − t_off)/I_M, below v_A throughout (overrunning).
// 3. At t_on the motor accelerates at τ0/I_M and reaches A's rest at t_lock = t_on − v_M(t_on) I_M/τ0:
//    the freewheel locks with the gear at rest, both decided together, and they start as in 1:
//    v_A = a1 (t − t_lock).
struct FreewheelWorm {
  static constexpr double IM = 0.5, IA = 0.1, IB = 4.0, i = 10.0, eta = 0.5, L = 20.0, tau0 = 30.0, taur = 20.0;
  static constexpr double t_off = 1.0, t_on = 3.5;
  static constexpr double a1 = (eta * tau0 - L / i) / (eta * (IM + IA) + IB / (i * i));
  static constexpr double ac = -(L / i) / (eta * IA + IB / (i * i));
  static constexpr double ts = t_off - a1 * t_off / ac;
  static constexpr double vm_on = a1 * t_off - taur * (t_on - t_off) / IM;
  static constexpr double t_lock = t_on - vm_on * IM / tau0;
  [[nodiscard]] static double speed_a(double t) {
    if (t <= t_off) return a1 * t;
    if (t <= ts) return a1 * t_off + ac * (t - t_off);
    return t <= t_lock ? 0.0 : a1 * (t - t_lock);
  }
  [[nodiscard]] static double speed_m(double t) {
    if (t <= t_off) return a1 * t;
    if (t <= t_on) return a1 * t_off - taur * (t - t_off) / IM;
    return t <= t_lock ? vm_on + tau0 * (t - t_on) / IM : speed_a(t);
  }
  [[nodiscard]] static std::string yaml(const char* integrator) {
    return fmt::format(R"(bodies:
  M: {{inertia: {} kg*m^2}}
  A: {{inertia: {} kg*m^2}}
  B: {{inertia: {} kg*m^2}}
links:
  G: {{type: lossy-gear, between: [A, B], ratio: {}, efficiency: {}, efficiency_reverse: 0}}
freewheels:
  F: {{between: [M, A]}}
loads:
  motor: {{type: table, body: M, points: [[0, {}], [{}, {}], [{}, {}], [{}, {}], [{}, {}], [6, {}]]}}
  weight: {{type: constant, body: B, value: {} N*m}}
simulation: {{t_end: 5, dt_out: 0.01, rtol: 1e-11, atol: 1e-13, integrator: {}}}
)", IM, IA, IB, i, eta, tau0, t_off, tau0, t_off, -taur, t_on, -taur, t_on, tau0, tau0, -L, integrator);
  }
};

// Claim: the freewheel overruns at t_off and locks again at t_lock, the gear stops at t_s and starts
// forward at t_lock (each once, within 1e-8 s; these are all their events); A's and M's speeds follow
// the closed form at every row within 1e-8 rad/s (1e-6 on BDF), B's is A's / i within rounding; the
// locked freewheel carries τ0 − I_M a1 within 1e-8 N·m, the overrunning one nothing.
TEST_P(GearClutchSim, MotorFreewheelWormGearOverrunsStopsAndRelocksAtTheClosedFormInstants) {
  using R = FreewheelWorm;
  static_assert(-R::taur / R::IM < R::ac && R::vm_on < 0.0 && R::t_lock > R::ts && R::ts < R::t_on);
  const SimulationResult r = simulate(test::model_text(R::yaml(GetParam()), "gear.yaml"));
  const auto gear = events_of(r, "G"), fw = events_of(r, "F");
  ASSERT_EQ(fw.size(), 2u);
  EXPECT_EQ(fw[0].to, "slip-");
  EXPECT_NEAR(fw[0].t, R::t_off, 1e-8);
  EXPECT_EQ(fw[1].to, "stuck");
  EXPECT_NEAR(fw[1].t, R::t_lock, 1e-8);
  ASSERT_EQ(gear.size(), 2u);
  EXPECT_EQ(gear[0].to, "stuck");
  EXPECT_NEAR(gear[0].t, R::ts, 1e-8);
  EXPECT_EQ(gear[1].to, "forward");
  EXPECT_NEAR(gear[1].t, R::t_lock, 1e-8);
  const double tol = std::string(GetParam()) == "bdf" ? 1e-6 : 1e-8;
  const auto& t = series(r, "t_s");
  const auto& wm = series(r, "M.velocity_rad_s");
  const auto& wa = series(r, "A.velocity_rad_s");
  const auto& wb = series(r, "B.velocity_rad_s");
  const auto& F = series(r, "F.force_N_m");
  for (size_t j = 0; j < t.size(); ++j) {
    EXPECT_NEAR(wa[j], R::speed_a(t[j]), tol) << t[j];
    EXPECT_NEAR(wm[j], R::speed_m(t[j]), tol) << t[j];
    EXPECT_NEAR(wb[j], wa[j] / R::i, 1e-12 * (1.0 + std::abs(wa[j])));
    const bool locked = t[j] < R::t_off - 1e-9 || t[j] > R::t_lock + 1e-9;
    if (locked || (t[j] > R::t_off + 1e-9 && t[j] < R::t_lock - 1e-9)) {
      EXPECT_NEAR(F[j], locked ? R::tau0 - R::IM * R::a1 : 0.0, 1e-8) << t[j];
    }
  }
}

// A gear A → B (i = 2, η_mf1 = 0.9, η_mf2 = 0.7, no bearing friction) with a brake on A (holding =
// braking = H) and a clutch of constant torque T0 (μ_s = μ_k) from B to C; a ramp torque h t on C;
// everything at rest. The brake and the clutch are decided in one decision with the gear.
// 1. At rest C's torque passes the stuck clutch (λ = h t < T0 here): F_a = 0, F_b' = h t / i, so B
//    drives forward, numerator N₊ = F_a + η_mf2 F_b'. The gear alone has N₊ > 0 at once: the brake
//    carries the rest, the split rule's θ with N₊(F + θ d) = 0, d_a = −H: a brake torque of
//    |λ_br| = η_mf2 h t / i, until it reaches H: the pair starts at t1 = H i / (η_mf2 h).
// 2. Rolling forward, B driving (D = −H J − I_A h t / i < 0), the brake sliding at H, C stuck to B:
//    (I_A + η_mf2 J) a = −H + η_mf2 h t / i,  J = (I_B + I_C)/i²  ⇒  a = η_mf2 h (t − t1) / (i E),
//    E = I_A + η_mf2 J, v_A = η_mf2 h (t − t1)² / (2 i E); the clutch carries λ = h t − I_C a / i,
//    which reaches T0 at t2 = (T0/h − κ t1)/(1 − κ), κ = I_C η_mf2 / (i² E).
// 3. The clutch slides (C runs ahead), B still drives (D = −H J_B − I_A T0/i < 0):
//    (I_A + η_mf2 J_B) a = −H + η_mf2 T0 / i, J_B = I_B / i²;  I_C a_C = h t − T0.
struct BrakeAndClutch {
  static constexpr double IA = 1.0, IB = 0.5, IC = 2.0, i = 2.0, e1 = 0.9, e2 = 0.7, H = 2.0, T0 = 8.0, h = 10.0;
  static constexpr double J = (IB + IC) / (i * i), E = IA + e2 * J, t1 = H * i / (e2 * h);
  static constexpr double kappa = IC * e2 / (i * i * E), t2 = (T0 / h - kappa * t1) / (1.0 - kappa);
  static constexpr double a3 = (-H + e2 * T0 / i) / (IA + e2 * IB / (i * i));
  [[nodiscard]] static double speed_a(double t) {
    if (t <= t1) return 0.0;
    if (t <= t2) return e2 * h * (t - t1) * (t - t1) / (2.0 * i * E);
    return speed_a(t2) + a3 * (t - t2);
  }
  [[nodiscard]] static double speed_c(double t) {
    return t <= t2 ? speed_a(t) / i : speed_a(t2) / i + (h * (t * t - t2 * t2) / 2.0 - T0 * (t - t2)) / IC;
  }
};

// Claim: the brake carries η_mf2 h t / i while everything holds (within 1e-8 N·m), the gear and the
// brake start together at t1 (gear to forward_b_drives, brake to sliding) and the clutch slips at t2,
// each once within 1e-8 s; A's and C's speeds follow the closed form at every row within 1e-8 rad/s
// (1e-6 on BDF); the brake slides at H, the clutch carries h t − I_C a / i, then T0.
TEST_P(GearClutchSim, BrakeAndClutchOnOneGearAreDecidedTogether) {
  using R = BrakeAndClutch;
  static_assert(R::h * R::t1 < R::T0 && R::t2 > R::t1 && R::a3 > 0.0);
  const SimulationResult r = simulate(test::model_text(fmt::format(R"(bodies:
  A: {{inertia: {} kg*m^2}}
  B: {{inertia: {} kg*m^2}}
  C: {{inertia: {} kg*m^2}}
links:
  G: {{type: lossy-gear, between: [A, B], ratio: {}, efficiency: {}, efficiency_reverse: {}}}
brakes:
  br: {{body: A, holding: {} N*m}}
clutches:
  K: {{between: [B, C], normal_force: {} N, mu_s: 0.5, mu_k: 0.5, radius: 1 m}}
loads:
  P: {{type: ramp, body: C, value: {} N*m, end: 2 s}}
simulation: {{t_end: 1.5, dt_out: 0.01, rtol: 1e-11, atol: 1e-13, integrator: {}}}
)", R::IA, R::IB, R::IC, R::i, R::e1, R::e2, R::H, 2.0 * R::T0, 2.0 * R::h, GetParam()), "gear.yaml"));
  const auto gear = events_of(r, "G"), brake = events_of(r, "br"), clutch = events_of(r, "K");
  ASSERT_EQ(gear.size(), 1u);
  EXPECT_EQ(gear[0].to, "forward_b_drives");
  EXPECT_NEAR(gear[0].t, R::t1, 1e-8);
  ASSERT_EQ(brake.size(), 1u);
  EXPECT_NE(brake[0].to, "stuck");
  EXPECT_NEAR(brake[0].t, R::t1, 1e-8);
  ASSERT_EQ(clutch.size(), 1u);
  EXPECT_NE(clutch[0].to, "stuck");
  EXPECT_NEAR(clutch[0].t, R::t2, 1e-8);
  const double tol = std::string(GetParam()) == "bdf" ? 1e-6 : 1e-8;
  const auto& t = series(r, "t_s");
  const auto& wa = series(r, "A.velocity_rad_s");
  const auto& wc = series(r, "C.velocity_rad_s");
  const auto& Fbr = series(r, "br.force_N_m");
  const auto& FK = series(r, "K.force_N_m");
  for (size_t j = 0; j < t.size(); ++j) {
    EXPECT_NEAR(wa[j], R::speed_a(t[j]), tol) << t[j];
    EXPECT_NEAR(wc[j], R::speed_c(t[j]), tol) << t[j];
    const double a = t[j] <= R::t1 ? 0.0 : R::e2 * R::h * (t[j] - R::t1) / (R::i * R::E);
    if (t[j] < R::t1 - 1e-9) {
      EXPECT_NEAR(std::abs(Fbr[j]), R::e2 * R::h * t[j] / R::i, 1e-8) << t[j];
    } else if (t[j] > R::t1 + 1e-9) {
      EXPECT_NEAR(std::abs(Fbr[j]), R::H, 1e-12) << t[j];
    }
    if (t[j] < R::t2 - 1e-9) {
      EXPECT_NEAR(std::abs(FK[j]), R::h * t[j] - R::IC * a / R::i, 1e-8) << t[j];
    } else if (t[j] > R::t2 + 1e-9) {
      EXPECT_NEAR(std::abs(FK[j]), R::T0, 1e-12) << t[j];
    }
  }
}

// The gear, clutch and ramp above with a backstop on A ([ground, A]: A may turn forward only) in place of
// the brake, and the ramp reversed, −h t on C; everything at rest. One decision holds gear, backstop and
// clutch (analysis/gear_clutch.hpp), one bounded split shares their loads (analysis/gear_lock.hpp).
// 1. C's torque passes the stuck clutch to B (λ_K = h t < T0): F_a = 0, F_b' = −h t / i. The gear alone
//    starts backward at once (B driving: N₋ = F_a + η_mf2 F_b' < 0); the backstop blocks that start (its
//    margin is 1) and the forward margin holds. The split: the backstop's torque T ≥ 0 on A, the least
//    with the gear in its locking range, on the B-driving piece T + η_mf2 F_b' ≥ 0 (the A-driving one
//    needs T ≥ h t/(η_mf1 i), more): T = η_mf2 h t / i.
// 2. The clutch slips at t_s = T0/h; C then runs alone, I_C a_C = −h t + T0 (kinetic = static):
//    ω_C = −(h (t² − t_s²)/2 − T0 (t − t_s)) / I_C; B keeps the load −T0: T = η_mf2 T0 / i.
// Claim: no event of the gear or the backstop, the clutch slips once at t_s (within 1e-8 s); A and B stay
// at rest, C's speed follows the closed form (1e-8 rad/s, 1e-6 on BDF); the backstop carries η_mf2 h t/i,
// then η_mf2 T0/i, the clutch h t, then T0 (1e-8 N·m).
TEST_P(GearClutchSim, BackstopAndClutchOnOneGearHoldItWithTheSplitsShare) {
  const double IA = 1.0, IB = 0.5, IC = 2.0, i = 2.0, e1 = 0.9, e2 = 0.7, T0 = 8.0, h = 10.0, ts = T0 / h;
  const SimulationResult r = simulate(test::model_text(fmt::format(R"(bodies:
  A: {{inertia: {} kg*m^2}}
  B: {{inertia: {} kg*m^2}}
  C: {{inertia: {} kg*m^2}}
links:
  G: {{type: lossy-gear, between: [A, B], ratio: {}, efficiency: {}, efficiency_reverse: {}}}
freewheels:
  bs: {{between: [ground, A]}}
clutches:
  K: {{between: [B, C], normal_force: {} N, mu_s: 0.5, mu_k: 0.5, radius: 1 m}}
loads:
  P: {{type: ramp, body: C, value: {} N*m, end: 2 s}}
simulation: {{t_end: 1.5, dt_out: 0.01, rtol: 1e-11, atol: 1e-13, integrator: {}}}
)", IA, IB, IC, i, e1, e2, 2.0 * T0, -2.0 * h, GetParam()), "gear.yaml"));
  EXPECT_TRUE(events_of(r, "G").empty());
  EXPECT_TRUE(events_of(r, "bs").empty());
  const auto clutch = events_of(r, "K");
  ASSERT_EQ(clutch.size(), 1u);
  EXPECT_NE(clutch[0].to, "stuck");
  EXPECT_NEAR(clutch[0].t, ts, 1e-8);
  const double tol = std::string(GetParam()) == "bdf" ? 1e-6 : 1e-8;
  const auto& t = series(r, "t_s");
  const auto &wa = series(r, "A.velocity_rad_s"), &wb = series(r, "B.velocity_rad_s"), &wc = series(r, "C.velocity_rad_s");
  const auto &Fbs = series(r, "bs.force_N_m"), &FK = series(r, "K.force_N_m");
  for (size_t j = 0; j < t.size(); ++j) {
    EXPECT_NEAR(wa[j], 0.0, tol) << t[j];
    EXPECT_NEAR(wb[j], 0.0, tol) << t[j];
    const double w = t[j] <= ts ? 0.0 : -(h * (t[j] * t[j] - ts * ts) / 2.0 - T0 * (t[j] - ts)) / IC;
    EXPECT_NEAR(wc[j], w, tol) << t[j];
    if (t[j] < ts - 1e-9) {
      EXPECT_NEAR(std::abs(Fbs[j]), e2 * h * t[j] / i, 1e-8) << t[j];
      EXPECT_NEAR(std::abs(FK[j]), h * t[j], 1e-8) << t[j];
    } else if (t[j] > ts + 1e-9) {
      EXPECT_NEAR(std::abs(Fbs[j]), e2 * T0 / i, 1e-8) << t[j];
      EXPECT_NEAR(std::abs(FK[j]), T0, 1e-12) << t[j];
    }
  }
}

// MSL's Rotational HeatLosses with its BearingFriction moved onto the gear's input inertia4: the gear,
// the bearing friction and the clutch on its flange in one decision, while the chain flange – clutch –
// inertia5 – one-way clutch – inertia6 – brake can hold the gear's output side against the ground.
// There it used to stall: the gear "started" with the chain holding its output (a = 0), its rest event
// fired again every 1e-13 s. No independent reference here (heat_losses_rotational_test.cpp has one
// for MSL's own placement). Claim: the run completes on both integrators within 200 000 steps, the
// bearing friction switches with the gear (the same instants), the two integrators agree on every
// speed within 1e-6 rad/s at every row, and the energy books close within 1e-8 of the source work.
TEST(GearClutchBearing, HeatLossesWithBearingFrictionOnTheGearRunsOnBothIntegrators) {
  std::ifstream in(test::example("msl/heat-losses.yaml"));
  std::stringstream text;
  text << in.rdbuf();
  std::string yaml = text.str();
  const std::string from = "bearingFriction: {between: [inertia3, ground]";
  ASSERT_NE(yaml.find(from), std::string::npos);
  yaml.replace(yaml.find(from), from.size(), "bearingFriction: {between: [inertia4, ground]");
  std::vector<SimulationResult> runs;
  for (IntegratorChoice integrator : {IntegratorChoice::dopri5, IntegratorChoice::bdf}) {
    Model m = test::model_text(yaml, "heat-losses.yaml");
    m.simulation.integrator = integrator;
    m.simulation.max_steps = 200'000;
    runs.push_back(simulate(m));
    const auto& E = runs.back().hybrid.energy;
    EXPECT_LT(std::abs(E.residual()), 1e-8 * E.source_work);
    std::vector<double> gear, bearing;
    for (const auto& e : runs.back().hybrid.events)
      if (e.kind != "initial" && e.element == "lossyGear") gear.push_back(e.t);
      else if (e.kind != "initial" && e.element == "bearingFriction") bearing.push_back(e.t);
    ASSERT_FALSE(bearing.empty());
    for (double t : bearing) EXPECT_NE(std::find(gear.begin(), gear.end(), t), gear.end()) << t;
  }
  for (const char* body : {"inertia1", "inertia4", "inertia5", "inertia6"}) {
    const std::string col = std::string(body) + ".velocity_rad_s";
    const auto& a = series(runs[0], col);
    const auto& b = series(runs[1], col);
    ASSERT_EQ(a.size(), b.size());
    for (size_t j = 0; j < a.size(); ++j) EXPECT_NEAR(a[j], b[j], 1e-6) << col << " " << j;
  }
}

// A clutch between two lossy gears: motor M (J1) –G1 (i1, η1, η'1)– X (JX) =K= Y (JY) –G2 (i2, η2, η'2)–
// drum D (JD), motor torque T on M, load L on D, the clutch's limits μ N r. In M's coordinate (α the
// motor's acceleration; no bearing friction):
//  - K stuck: the two-stage train of analysis/gear_train.hpp with the shaft J2 = JX + JY:
//      forward (M drives both)   M_f α = η1 η2 T + L/(i1 i2),  M_f = η1 η2 J1 + η2 J2/i1² + JD/(i1 i2)²,
//      back-driven (D drives)    M_b α = T + η'1 η'2 L/(i1 i2), M_b = J1 + η'1 J2/i1² + η'1 η'2 JD/(i1 i2)²;
//    K carries, from X's equation JX α/i1 = i1 Y1 − K with Y1 = η1 (T − J1 α) forward:
//      K = i1 η1 (T − J1 α) − JX α/i1.
//  - K sliding (X faster than Y) with τ = μ_k N r: −τ on X, +τ on Y, each gear alone (a drives):
//      E1 α = η1 T − τ/i1,  E1 = η1 J1 + JX/i1²;    E2 α_Y = η2 τ + L/i2,  E2 = η2 JY + JD/i2²
//    (a self-locking G2 holds Y while η2 τ + L/i2 ≤ 0).
struct TwoGearsClutch {
  double J1 = 0.2, JX = 0.05, JY = 0.05, JD = 8.0, i1 = 4.0, i2 = 5.0;
  double e1 = 0.9, r1 = 0.8, e2 = 0.85, r2 = 0.0, mu_s = 0.3, mu_k = 0.25, radius = 0.1;
  [[nodiscard]] double Mf() const { return e1 * e2 * J1 + e2 * (JX + JY) / (i1 * i1) + JD / (i1 * i1 * i2 * i2); }
  [[nodiscard]] double Mb() const { return J1 + r1 * (JX + JY) / (i1 * i1) + r1 * r2 * JD / (i1 * i1 * i2 * i2); }
  [[nodiscard]] double forward_acc(double T, double L) const { return (e1 * e2 * T + L / (i1 * i2)) / Mf(); }
  [[nodiscard]] double back_acc(double T, double L) const { return (T + r1 * r2 * L / (i1 * i2)) / Mb(); }
  [[nodiscard]] double clutch_forward(double T, double a) const { return i1 * e1 * (T - J1 * a) - JX * a / i1; }
  [[nodiscard]] double E1() const { return e1 * J1 + JX / (i1 * i1); }
  [[nodiscard]] double E2() const { return e2 * JY + JD / (i2 * i2); }
  [[nodiscard]] std::string yaml(const std::string& torque, double L, const std::string& normal, double v0, double t_end,
                                 const char* integrator) const {
    return fmt::format(R"(bodies:
  M: {{inertia: {} kg*m^2, velocity: {} rad/s}}
  X: {{inertia: {} kg*m^2}}
  Y: {{inertia: {} kg*m^2}}
  D: {{inertia: {} kg*m^2}}
links:
  G1: {{type: lossy-gear, between: [M, X], ratio: {}, efficiency: {}, efficiency_reverse: {}}}
  G2: {{type: lossy-gear, between: [Y, D], ratio: {}, efficiency: {}, efficiency_reverse: {}}}
clutches:
  K: {{between: [X, Y], normal_force: {}, mu_s: {}, mu_k: {}, radius: {} m}}
loads:
  T: {}
  L: {{type: constant, body: D, value: {} N*m}}
simulation: {{t_end: {}, dt_out: 0.01, rtol: 1e-11, atol: 1e-13, integrator: {}}}
)",
                       J1, v0, JX, JY, JD, i1, e1, r1, i2, e2, r2, normal, mu_s, mu_k, radius, torque, L, t_end,
                       integrator);
  }
};

double gc_tol(const char* integrator, double scale) { return (std::string(integrator) == "bdf" ? 1e-6 : 1e-8) * scale; }

// Claim: a stuck clutch between two gears carries the geared load: a motor torque ramp T = k t lifts
// the load through both (G2 self-locking) from t* = −L/(i1 i2 η1 η2 k) on (both gears slip forward
// there, within 1e-8 s; the clutch stays stuck, no event of it), v_M = η1 η2 k (t − t*)²/(2 M_f) and the
// clutch torque the closed form K above; back-driven (η'2 = 0.7, T = 5 N·m below the load's share)
// it lowers from rest at once with both gears on side b, v_M = α_b t.
TEST_P(GearClutchSim, AStuckClutchBetweenTwoGearsCarriesTheGearedLoad) {
  const TwoGearsClutch c;
  const double L = -300.0, k = 40.0, ts = -L / (c.i1 * c.i2 * c.e1 * c.e2 * k);
  const SimulationResult r = simulate(test::model_text(
      c.yaml(fmt::format("{{type: ramp, body: M, before: 0 N*m, value: {} N*m, start: 0 s, end: 2 s}}", 2.0 * k), L,
             "4 kN", 0.0, 1.0, GetParam()),
      "two-gears.yaml"));
  EXPECT_EQ(events_of(r, "K").size(), 0u);
  for (const char* g : {"G1", "G2"}) {
    const auto ev = events_of(r, g);
    ASSERT_EQ(ev.size(), 1u) << g;
    EXPECT_EQ(ev[0].kind, "slip");
    EXPECT_EQ(ev[0].to, "forward");
    EXPECT_NEAR(ev[0].t, ts, 1e-8) << g;
  }
  const auto t = series(r, "t_s"), vM = series(r, "M.velocity_rad_s"), vD = series(r, "D.velocity_rad_s"),
             K = series(r, "K.force_N_m");
  for (size_t n = 0; n < t.size(); ++n) {
    if (t[n] <= ts) {
      EXPECT_EQ(vM[n], 0.0) << "t " << t[n];
      EXPECT_EQ(vD[n], 0.0) << "t " << t[n];
      continue;
    }
    const double a = c.forward_acc(k * t[n], L);
    EXPECT_NEAR(vM[n], c.e1 * c.e2 * k * (t[n] - ts) * (t[n] - ts) / (2.0 * c.Mf()), gc_tol(GetParam(), 10.0)) << t[n];
    EXPECT_NEAR(std::abs(K[n]), c.clutch_forward(k * t[n], a), 1e-8 * std::abs(L)) << t[n];
  }
  TwoGearsClutch b = c;
  b.r2 = 0.7;
  const double T = 5.0, ab = b.back_acc(T, L);
  ASSERT_LT(ab, 0.0);
  const SimulationResult rb = simulate(test::model_text(
      b.yaml(fmt::format("{{type: constant, body: M, value: {} N*m}}", T), L, "4 kN", 0.0, 1.0, GetParam()), "two-gears.yaml"));
  for (const char* g : {"G1", "G2", "K"}) EXPECT_EQ(events_of(rb, g).size(), 0u) << g;
  const auto tb = series(rb, "t_s"), vb = series(rb, "M.velocity_rad_s"), Kb = series(rb, "K.mode");
  for (size_t n = 0; n < tb.size(); ++n) {
    EXPECT_NEAR(vb[n], ab * tb[n], gc_tol(GetParam(), 10.0)) << tb[n];
    EXPECT_EQ(Kb[n], 0.0) << tb[n];
  }
}

// Claim: a clutch too weak for the load slides between the two gears with its kinetic torque τ: the
// motor side and the drum side accelerate independently at the closed forms E1 α = η1 T − τ/i1 and
// E2 α_Y = η2 τ + L/i2 (no event), the clutch's torque is τ.
TEST_P(GearClutchSim, ASlidingClutchBetweenTwoGearsPassesItsKineticTorque) {
  const TwoGearsClutch c;
  const double T = 30.0, L = -30.0, N = 400.0, tau = c.mu_k * N * c.radius;
  const SimulationResult r = simulate(test::model_text(
      c.yaml(fmt::format("{{type: constant, body: M, value: {} N*m}}", T), L, "400 N", 0.0, 1.0, GetParam()), "two-gears.yaml"));
  const double aM = (c.e1 * T - tau / c.i1) / c.E1(), aY = (c.e2 * tau + L / c.i2) / c.E2();
  ASSERT_GT(aM / c.i1, aY);
  ASSERT_GT(aY, 0.0);
  for (const char* g : {"G1", "G2", "K"}) EXPECT_EQ(events_of(r, g).size(), 0u) << g;
  const auto t = series(r, "t_s"), vM = series(r, "M.velocity_rad_s"), vY = series(r, "Y.velocity_rad_s"),
             K = series(r, "K.force_N_m");
  for (size_t n = 1; n < t.size(); ++n) {
    EXPECT_NEAR(vM[n], aM * t[n], gc_tol(GetParam(), 10.0)) << t[n];
    EXPECT_NEAR(vY[n], aY * t[n], gc_tol(GetParam(), 1.0)) << t[n];
    EXPECT_NEAR(std::abs(K[n]), tau, 1e-9 * tau) << t[n];
  }
}

// Claim: the clutch engages between two gears at the closed-form instants. The motor runs at v0, no
// torque; the clutch's normal force ramps, τ = c t (c = μ_k r dN/dt); the self-locking G2 holds the
// load until η2 c t1 = −L/i2, then Y accelerates, E2 α_Y = η2 c t + L/i2, while the motor decelerates,
// E1 α = −c t/i1: v_M = v0 − c t²/(2 i1 E1), v_Y = (η2 c (t² − t1²)/2 + (L/i2)(t − t1))/E2. The clutch
// sticks where v_M/i1 = v_Y (the root beyond t1 of that quadratic); both instants within 1e-8 s.
TEST_P(GearClutchSim, AClutchBetweenTwoGearsEngagesAtTheClosedFormInstant) {
  const TwoGearsClutch g;
  const double v0 = 50.0, L = -30.0, c = g.mu_k * g.radius * 2000.0;  // N = 2 kN t
  const double t1 = -L / (g.i2 * g.e2 * c);
  const double A = -c / (2.0 * g.i1 * g.i1 * g.E1()) - g.e2 * c / (2.0 * g.E2()), B = -(L / g.i2) / g.E2(),
               C = v0 / g.i1 + g.e2 * c * t1 * t1 / (2.0 * g.E2()) + (L / g.i2) * t1 / g.E2();
  const double t2 = (-B - std::sqrt(B * B - 4.0 * A * C)) / (2.0 * A);
  ASSERT_GT(t2, t1);
  const SimulationResult r = simulate(test::model_text(
      g.yaml("{type: constant, body: M, value: 0 N*m}", L, "{type: ramp, value: 2 kN, end: 1 s}", v0, t2 + 0.02, GetParam()),
      "two-gears.yaml"));
  const auto e2 = events_of(r, "G2"), eK = events_of(r, "K");
  EXPECT_EQ(events_of(r, "G1").size(), 0u);
  ASSERT_EQ(e2.size(), 1u);
  EXPECT_EQ(e2[0].kind, "slip");
  EXPECT_NEAR(e2[0].t, t1, 1e-8);
  ASSERT_EQ(eK.size(), 1u);
  EXPECT_EQ(eK[0].kind, "stick");
  EXPECT_NEAR(eK[0].t, t2, 1e-8);
  const auto t = series(r, "t_s"), vM = series(r, "M.velocity_rad_s"), vY = series(r, "Y.velocity_rad_s");
  for (size_t n = 0; n < t.size() && t[n] < t2; ++n) {
    EXPECT_NEAR(vM[n], v0 - c * t[n] * t[n] / (2.0 * g.i1 * g.E1()), gc_tol(GetParam(), 10.0)) << t[n];
    const double y = t[n] <= t1 ? 0.0 : (g.e2 * c * (t[n] * t[n] - t1 * t1) / 2.0 + (L / g.i2) * (t[n] - t1)) / g.E2();
    EXPECT_NEAR(vY[n], y, gc_tol(GetParam(), 1.0)) << t[n];
  }
}

// Claim: two gears tied by a stuck clutch come to rest together and hold (their starts decided
// together, analysis/gear_clutch.hpp). The motor at v0 (X at v0/i1, Y at rest), no torque, the
// clutch's τ = μ_k N r: the motor side decelerates (E1 α = −τ/i1), Y lifts (E2 α_Y = η2 τ + L/i2), the
// clutch sticks at t_s = (v0/i1)/(α_Y − α/i1); then the train coasts, α = (L/(i1 i2))/M_f, to rest at
// t_s − v_M(t_s)/α, where both gears stick in the same event (within 1e-8 s) and the self-locking G2
// holds everything exactly at rest, with no event after it. With η'2 = 0.7 instead the load lowers from
// there: both gears reverse together onto side b in that event, v_M = α_b (t − t_stop), M_b α_b =
// η'1 η'2 L/(i1 i2) (their start enumerated together: neither starts alone while the clutch holds).
TEST_P(GearClutchSim, TwoGearsTiedByAStuckClutchComeToRestTogetherAndHoldOrReverse) {
  const TwoGearsClutch g;
  const double v0 = 20.0, L = -300.0, tau = g.mu_k * 4000.0 * g.radius;
  const double a1 = -(tau / g.i1) / g.E1(), aY = (g.e2 * tau + L / g.i2) / g.E2();
  ASSERT_GT(aY, 0.0);
  const double ts = (v0 / g.i1) / (aY - a1 / g.i1), vs = v0 + a1 * ts, ac = g.forward_acc(0.0, L);
  const double tstop = ts - vs / ac;
  const SimulationResult r = simulate(test::model_text(
      g.yaml("{type: constant, body: M, value: 0 N*m}", L, "4 kN", v0, tstop + 0.3, GetParam()), "two-gears.yaml"));
  const auto eK = events_of(r, "K");
  ASSERT_EQ(eK.size(), 1u);
  EXPECT_EQ(eK[0].kind, "stick");
  EXPECT_NEAR(eK[0].t, ts, 1e-8);
  for (const char* n : {"G1", "G2"}) {
    const auto ev = events_of(r, n);
    ASSERT_EQ(ev.size(), 1u) << n;
    EXPECT_EQ(ev[0].kind, "stick") << n;
    EXPECT_NEAR(ev[0].t, tstop, 1e-8) << n;
  }
  const auto t = series(r, "t_s"), vM = series(r, "M.velocity_rad_s"), vX = series(r, "X.velocity_rad_s"),
             vY = series(r, "Y.velocity_rad_s"), vD = series(r, "D.velocity_rad_s");
  for (size_t n = 0; n < t.size(); ++n) {
    if (t[n] > tstop) {
      for (double v : {vM[n], vX[n], vY[n], vD[n]}) EXPECT_EQ(v, 0.0) << "t " << t[n];
    } else if (t[n] > ts) {
      EXPECT_NEAR(vM[n], vs + ac * (t[n] - ts), gc_tol(GetParam(), 10.0)) << t[n];
    }
  }
  TwoGearsClutch b = g;
  b.r2 = 0.7;
  const double ab = b.back_acc(0.0, L);
  ASSERT_LT(ab, 0.0);
  const SimulationResult rb = simulate(test::model_text(
      b.yaml("{type: constant, body: M, value: 0 N*m}", L, "4 kN", v0, tstop + 0.3, GetParam()), "two-gears.yaml"));
  EXPECT_EQ(events_of(rb, "K").size(), 1u);
  for (const char* n : {"G1", "G2"}) {
    const auto ev = events_of(rb, n);
    ASSERT_EQ(ev.size(), 1u) << n;
    EXPECT_EQ(ev[0].kind, "reversal") << n;
    EXPECT_EQ(ev[0].to, "backward_b_drives") << n;
    EXPECT_NEAR(ev[0].t, tstop, 1e-8) << n;
  }
  const auto tb = series(rb, "t_s"), vb = series(rb, "M.velocity_rad_s");
  for (size_t n = 0; n < tb.size(); ++n)
    if (tb[n] > tstop) {
      EXPECT_NEAR(vb[n], ab * (tb[n] - tstop), gc_tol(GetParam(), 10.0)) << tb[n];
    }
}

// Claim: the combinations that remain unsupported are located errors at the gear's key, each
// saying why: both sides massless, a massless side with a prescribed motion, a clutch between the
// bodies of two lossy gears compiles, a freewheel there is refused, a clutch on a gear in a model with a prescribed motion; a massless side
// beside a body with inertia compiles.
TEST(GearClutchCompile, UnsupportedCombinationsAreLocatedErrors) {
  auto check = [](const std::string& text, const std::string& why) {
    const std::string e = test::compile_errors(text, "gear.yaml");
    EXPECT_NE(e.find("gear.yaml:6:"), std::string::npos) << text << "\n" << e;
    EXPECT_NE(e.find(why), std::string::npos) << text << "\n" << e;
  };
  const std::string massless = "bodies:\n  A: {inertia: 0}\n  B: {inertia: 0}\n  C: {inertia: 3}\nlinks:\n"
                               "  G: {type: lossy-gear, between: [A, B], efficiency: 0.9}\n";
  check(massless, "both 'A' and 'B' have zero inertia");
  const std::string moved = "bodies:\n  A: {inertia: 1}\n  B: {inertia: 0, motion: {speed: 1 rad/s}}\n  C: {inertia: 3}\n"
                            "links:\n  G: {type: lossy-gear, between: [A, B], efficiency: 0.9}\n";
  check(moved, "'B' has zero inertia and a prescribed motion");
  const std::string two = "bodies:\n  A: {inertia: 1}\n  B: {inertia: 2}\n  C: {inertia: 3}\n  D: {inertia: 1}\nlinks:\n"
                          "  G: {type: lossy-gear, between: [A, B], efficiency: 0.9}\n"
                          "  H: {type: lossy-gear, between: [C, D], efficiency: 0.9}\nclutches:\n"
                          "  K: {between: [B, C], normal_force: 10 N, mu_s: 0.3, mu_k: 0.3, radius: 1 m}\n";
  EXPECT_EQ(test::compile_errors(two, "gear.yaml"), "");  // a clutch between two gears compiles (tests above)
  std::string fw = two;  // a freewheel there does not yet, reported at each gear's key
  fw.replace(fw.find("clutches:\n  K: {between: [B, C]"), std::string::npos, "freewheels:\n  K: {between: [B, C]}\n");
  const std::string e = test::compile_errors(fw, "gear.yaml");
  EXPECT_NE(e.find("gear.yaml:7:"), std::string::npos) << e;
  EXPECT_NE(e.find("gear.yaml:8:"), std::string::npos) << e;
  EXPECT_NE(e.find("joins it to lossy gear 'G'; a freewheel between two lossy gears is not supported yet"), std::string::npos) << e;
  check("bodies:\n  A: {inertia: 1}\n  B: {inertia: 2}\n  C: {inertia: 3, motion: {speed: 1 rad/s}}\nlinks:\n"
        "  G: {type: lossy-gear, between: [A, B], efficiency: 0.9}\nclutches:\n"
        "  K: {between: [B, C], normal_force: 10 N, mu_s: 0.3, mu_k: 0.3, radius: 1 m}\n",
        "a clutch on its body ('K') in a model with a prescribed motion ('C') is not supported yet");
  const Model ok = test::model_text("bodies:\n  A: {inertia: 1}\n  B: {inertia: 0}\n  C: {inertia: 3}\nlinks:\n"
                                    "  G: {type: lossy-gear, between: [A, B], efficiency: 0.9}\nclutches:\n"
                                    "  K: {between: [B, C], normal_force: 10 N, mu_s: 0.3, mu_k: 0.3, radius: 1 m}\n",
                                    "gear.yaml");
  ASSERT_EQ(ok.lossy_gears.size(), 1u);
  EXPECT_EQ(ok.bodies[static_cast<size_t>(ok.lossy_gears[0].b)].inertia, 0.0);
}

}  // namespace
}  // namespace machdyn
