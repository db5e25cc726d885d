// A lossy gear with a prescribed side (elements/lossy_gear.hpp "Prescribed side"): a speed source on
// one body of a worm gear, the load on the other. The torques X, Y, the mode, the heat and the source's
// force against closed forms derived in each test's comment, on both integrators (also with bearing
// friction, against MSL's quadrant equations, and with the motion reaching the gear through an ideal
// gear); the holding torque at rest; the shipped example; the located errors of what stays refused.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::series;

class PrescribedGear : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, PrescribedGear,
                         ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf), test::IntegratorName{});

SimulationResult run(const std::string& yaml, IntegratorChoice integrator) {
  Model m = test::model_text(yaml, "gear.yaml");
  m.simulation.integrator = integrator;
  return simulate(m);
}

/// The gear's mode changes after the initial decision: (t, to).
std::vector<std::pair<double, std::string>> gear_changes(const SimulationResult& r) {
  std::vector<std::pair<double, std::string>> out;
  for (const auto& e : r.hybrid.events)
    if (e.element == "G" && e.kind != "initial") out.emplace_back(e.t, e.to);
  return out;
}

constexpr double kPi = std::numbers::pi;

// Claim: a speed source v_a = V sin Ωt on the worm A (I_A = 0.02 kg·m², V = 100 rad/s, Ω = 2 rad/s)
// drives a drum B (I_B = 40 kg·m²) with a constant load M_B = −60 N·m through a lossy gear v_a = i v_b,
// i = 20, η_mf1 = 0.9, η_mf2 = 0.4, no bearing friction. In A's coordinate J_b = I_B/i² = 0.1 kg·m²,
// F_b' = M_B/i = −3 N·m, and B's own equation gives the gear's output torque whatever the mode:
//   Y = J_b a − F_b' = 0.1 · 200 cos 2t + 3 = 20 cos 2t + 3.
// A drives while s Y > 0 (s = sign v_a): X = Y/η_mf1; else B drives: X = η_mf2 Y. So, by hand:
//   (0, t1)    forward,  a drives (the drum accelerated and lifted)      t1 = acos(−0.15)/2 = 0.8607 s
//   (t1, π/2)  forward,  b drives (the decelerating drum overhauls)
//   (π/2, t2)  backward, a drives (lowered faster than the load falls)   t2 = π − t1
//   (t2, π)    backward, b drives (the load overhauls the lowering)      then forward, a drives, from π.
// The source's torque closes A's equation I_A a = R − X: R = I_A a + X. Heat (X − Y) v_a; with
// Y v_a = 1000 sin 4t + 300 sin 2t = P'(t), P = −250 cos 4t − 150 cos 2t, the heat up to T is
//   Σ_phases (1/η_mf1 − 1 or η_mf2 − 1) [P(end) − P(start)],
// and the source's work ∫ R v_a dt = ½ I_A v_a(T)² + P(T) − P(0) + heat.
// Every row to 1e-6 N·m (torques up to 26 N·m); switch instants to 1e-8 s; heat and work to 1e-7 rel.
TEST_P(PrescribedGear, SpeedSourceOnTheWormFollowsTheQuadrantsByHand) {
  const SimulationResult r = run(R"(bodies:
  A: {inertia: 0.02 kg*m^2, motion: {speed: {type: sine, amplitude: 100 rad/s, frequency: 2 rad/s}}}
  B: {inertia: 40 kg*m^2}
links:
  G: {type: lossy-gear, between: [A, B], ratio: 20, efficiency: 0.9, efficiency_reverse: 0.4}
loads:
  MB: {type: constant, body: B, value: -60 N*m}
simulation: {t_end: 3.5 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)", GetParam());
  const double IA = 0.02, V = 100.0, W = 2.0, i = 20.0, eta1 = 0.9, eta2 = 0.4;
  const double t1 = std::acos(-0.15) / 2.0, t2 = kPi - t1;
  auto Y = [](double t) { return 20.0 * std::cos(2.0 * t) + 3.0; };
  auto va = [&](double t) { return V * std::sin(W * t); };
  auto X = [&](double t) { return va(t) * Y(t) > 0.0 ? Y(t) / eta1 : eta2 * Y(t); };
  auto mode = [&](double t) { return va(t) > 0.0 ? 1.0 : -1.0; };
  const auto& t = series(r, "t_s");
  const auto& ta = series(r, "G.torque_a_N_m");
  const auto& tb = series(r, "G.torque_b_N_m");
  const auto& loss = series(r, "G.loss_power_W");
  const auto& md = series(r, "G.mode");
  const auto& R = series(r, "A.motion_torque_N_m");
  const auto& wB = series(r, "B.velocity_rad_s");
  ASSERT_GT(t.size(), 3000u);
  double work = 0.0;  // ∫ R v_a dt of the rows (trapezoid), against the closed form below
  double e_x = 0.0, e_t = 0.0;
  for (size_t k = 0; k < t.size(); ++k) {
    if (k > 0) work += 0.5 * (t[k] - t[k - 1]) * (R[k] * va(t[k]) + R[k - 1] * va(t[k - 1]));
    if (std::abs(std::remainder(t[k], kPi / 2.0)) < 1e-6) continue;  // at rest for an instant: X jumps
    const double a = V * W * std::cos(W * t[k]);
    EXPECT_NEAR(ta[k], X(t[k]), 1e-6) << "t = " << t[k];
    EXPECT_NEAR(tb[k], -i * Y(t[k]), 1e-6 * i) << "t = " << t[k];
    EXPECT_NEAR(loss[k], (X(t[k]) - Y(t[k])) * va(t[k]), 1e-4) << "t = " << t[k];
    EXPECT_NEAR(R[k], IA * a + X(t[k]), 1e-6) << "t = " << t[k];
    e_x = std::max({e_x, std::abs(ta[k] - X(t[k])), std::abs(R[k] - IA * a - X(t[k]))});
    EXPECT_NEAR(wB[k], va(t[k]) / i, 1e-7) << "t = " << t[k];
    EXPECT_EQ(md[k], mode(t[k])) << "t = " << t[k];
  }
  // The switches: the driving side at t1, t2 (events), the direction at π/2, π.
  const auto ch = gear_changes(r);
  const std::vector<std::pair<double, std::string>> want = {
      {t1, "forward_b_drives"}, {kPi / 2, "backward"}, {t2, "backward_b_drives"}, {kPi, "forward"}};
  ASSERT_EQ(ch.size(), want.size());
  for (size_t k = 0; k < want.size(); ++k) {
    EXPECT_NEAR(ch[k].first, want[k].first, 1e-8);
    EXPECT_EQ(ch[k].second, want[k].second);
    e_t = std::max(e_t, std::abs(ch[k].first - want[k].first));
  }
  const double T = 3.5;
  auto P = [](double s) { return -250.0 * std::cos(4.0 * s) - 150.0 * std::cos(2.0 * s); };
  const double fa = 1.0 / eta1 - 1.0, fb = eta2 - 1.0;
  const double heat = fa * (P(t1) - P(0)) + fb * (P(kPi / 2) - P(t1)) + fa * (P(t2) - P(kPi / 2)) +
                      fb * (P(kPi) - P(t2)) + fa * (P(T) - P(kPi));
  EXPECT_NEAR(r.hybrid.energy.friction_loss, heat, 1e-7 * heat);
  const double W_src = 0.5 * IA * va(T) * va(T) + P(T) - P(0) + heat;
  EXPECT_NEAR(work, W_src, 1e-5 * W_src);  // the trapezoid's error on the 1 ms rows: ~1e-7 relative
  EXPECT_NEAR(r.hybrid.energy.residual(), 0.0, 1e-8 * r.hybrid.energy.source_work);
  std::printf("PrescribedGear worm %s: X, R %.2e N*m; switches %.2e s; heat %.6f J vs %.6f; source work %.4f J vs "
              "%.4f\n", GetParam() == IntegratorChoice::bdf ? "bdf" : "dopri5", e_x, e_t,
              r.hybrid.energy.friction_loss, heat, work, W_src);
}

// Claim: the prescribed motion may reach the gear through an ideal gear. The first test's worm split in
// two: a motor (I = 0.01 kg·m², the prescribed speed 100 sin 2t) turns the worm (I = 0.04 kg·m²) through
// an ideal gear q_motor = 2 q_worm, the lossy gear q_worm = 10 q_drum. In the motor's coordinate the
// group's inertia is 0.01 + 0.04/4 = 0.02 kg·m² and the lossy gear's ratio 2 · 10 = 20: the first test's
// model, so X, Y are its closed forms; the gear's torque at the worm is X in the worm's coordinate,
// 2 X, and the motor's source torque 0.02 a + X. Rows to 1e-6 N·m.
TEST_P(PrescribedGear, MotionThroughAnIdealGearIsTheSameGear) {
  const SimulationResult r = run(R"(bodies:
  motor: {inertia: 0.01 kg*m^2, motion: {speed: {type: sine, amplitude: 100 rad/s, frequency: 2 rad/s}}}
  worm: {inertia: 0.04 kg*m^2}
  B: {inertia: 40 kg*m^2}
links:
  pre: {type: ideal-gear, between: [motor, worm], ratio: 2}
  G: {type: lossy-gear, between: [worm, B], ratio: 10, efficiency: 0.9, efficiency_reverse: 0.4}
loads:
  MB: {type: constant, body: B, value: -60 N*m}
simulation: {t_end: 3 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)", GetParam());
  auto Y = [](double t) { return 20.0 * std::cos(2.0 * t) + 3.0; };
  auto va = [](double t) { return 100.0 * std::sin(2.0 * t); };
  auto X = [&](double t) { return va(t) * Y(t) > 0.0 ? Y(t) / 0.9 : 0.4 * Y(t); };
  const auto& t = series(r, "t_s");
  const auto& ta = series(r, "G.torque_a_N_m");
  const auto& R = series(r, "motor.motion_torque_N_m");
  ASSERT_GT(t.size(), 2000u);
  for (size_t k = 0; k < t.size(); ++k) {
    if (std::abs(std::remainder(t[k], kPi / 2.0)) < 1e-6) continue;
    EXPECT_NEAR(ta[k], 2.0 * X(t[k]), 1e-6) << "t = " << t[k];
    EXPECT_NEAR(R[k], 0.02 * 200.0 * std::cos(2.0 * t[k]) + X(t[k]), 1e-6) << "t = " << t[k];
  }
  EXPECT_EQ(gear_changes(r).size(), 3u);  // t1, π/2, t2 of the first test
}

// Claim: with bearing friction the prescribed worm follows MSL's quadrant equations (the lossTable form,
// written here without the library's split of the bearing torques): in A's coordinate
//   a drives:  Y = η_mf1 X − s τ_bf1  ⇒  X = (Y + s τ_bf1)/η_mf1
//   b drives:  X = η_mf2 (Y + s τ_bf2)
// and a drives while s (X − s τ_bf,a) > 0, τ_bf,a = η_mf2 (τ_bf1 − τ_bf2)/(η_mf1 η_mf2 − 1) (MSL's
// tau_bf_a). The model of the first test with τ_bf1 = 0.5, τ_bf2 = 0.8 N·m: τ_bf,a = 0.1875 N·m, and the
// side changes where Y = −s τ_bf,b, τ_bf,b = τ_bf1 − η_mf1 τ_bf,a = 0.33125 N·m:
//   t1 = acos(−3.33125/20)/2 (forward),  t2 = π − acos(−2.66875/20)/2 (backward).
// Heat: (X − Y) v_a per row; its integral Σ_phases (1/η_mf1 − 1)[P] + τ_bf1/η_mf1 [S], or
// (η_mf2 − 1)[P] + η_mf2 τ_bf2 [S], with P as in the first test and S = ∫ s v_a dt = ∫ |v_a| dt.
// Rows to 1e-6 N·m, switch instants to 1e-8 s, heat to 1e-7 relative.
TEST_P(PrescribedGear, BearingFrictionFollowsMslsQuadrantEquations) {
  const SimulationResult r = run(R"(bodies:
  A: {inertia: 0.02 kg*m^2, motion: {speed: {type: sine, amplitude: 100 rad/s, frequency: 2 rad/s}}}
  B: {inertia: 40 kg*m^2}
links:
  G: {type: lossy-gear, between: [A, B], ratio: 20, efficiency: 0.9, efficiency_reverse: 0.4,
      bearing_friction: 0.5 N*m, bearing_friction_reverse: 0.8 N*m}
loads:
  MB: {type: constant, body: B, value: -60 N*m}
simulation: {t_end: 3 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)", GetParam());
  const double eta1 = 0.9, eta2 = 0.4, bf1 = 0.5, bf2 = 0.8;
  const double bfa = eta2 * (bf1 - bf2) / (eta1 * eta2 - 1.0);
  auto Y = [](double t) { return 20.0 * std::cos(2.0 * t) + 3.0; };
  auto va = [](double t) { return 100.0 * std::sin(2.0 * t); };
  auto a_drives = [&](double t) {
    const double s = va(t) > 0.0 ? 1.0 : -1.0, Xa = (Y(t) + s * bf1) / eta1;
    return s * (Xa - s * bfa) > 0.0;
  };
  auto X = [&](double t) {
    const double s = va(t) > 0.0 ? 1.0 : -1.0;
    return a_drives(t) ? (Y(t) + s * bf1) / eta1 : eta2 * (Y(t) + s * bf2);
  };
  const auto& t = series(r, "t_s");
  const auto& ta = series(r, "G.torque_a_N_m");
  const auto& loss = series(r, "G.loss_power_W");
  ASSERT_GT(t.size(), 2000u);
  for (size_t k = 0; k < t.size(); ++k) {
    if (std::abs(std::remainder(t[k], kPi / 2.0)) < 1e-6) continue;
    EXPECT_NEAR(ta[k], X(t[k]), 1e-6) << "t = " << t[k];
    EXPECT_NEAR(loss[k], (X(t[k]) - Y(t[k])) * va(t[k]), 1e-4) << "t = " << t[k];
  }
  const double bfb = bf1 - eta1 * bfa;
  const double t1 = std::acos((-bfb - 3.0) / 20.0) / 2.0, t2 = kPi - std::acos((bfb - 3.0) / 20.0) / 2.0;
  const auto ch = gear_changes(r);
  const std::vector<std::pair<double, std::string>> want = {
      {t1, "forward_b_drives"}, {kPi / 2, "backward"}, {t2, "backward_b_drives"}};
  ASSERT_EQ(ch.size(), want.size());
  for (size_t k = 0; k < want.size(); ++k) {
    EXPECT_NEAR(ch[k].first, want[k].first, 1e-8);
    EXPECT_EQ(ch[k].second, want[k].second);
  }
  auto P = [](double x) { return -250.0 * std::cos(4.0 * x) - 150.0 * std::cos(2.0 * x); };
  auto A = [](double x) { return -50.0 * std::cos(2.0 * x); };  // ∫ v_a dt
  const double fa = 1.0 / eta1 - 1.0, fb = eta2 - 1.0, T = 3.0;
  const double heat = fa * (P(t1) - P(0)) + bf1 / eta1 * (A(t1) - A(0)) +                 // forward, a drives
                      fb * (P(kPi / 2) - P(t1)) + eta2 * bf2 * (A(kPi / 2) - A(t1)) +     // forward, b drives
                      fa * (P(t2) - P(kPi / 2)) - bf1 / eta1 * (A(t2) - A(kPi / 2)) +     // backward, a drives
                      fb * (P(T) - P(t2)) - eta2 * bf2 * (A(T) - A(t2));                   // backward, b drives
  EXPECT_NEAR(r.hybrid.energy.friction_loss, heat, 1e-7 * heat);
  EXPECT_NEAR(r.hybrid.energy.residual(), 0.0, 1e-8 * r.hybrid.energy.source_work);
}

// Claim: the same with the drum's speed prescribed (side b): v_b = 5 sin 2t rad/s on B (I_B = 40), the
// worm A free (I_A = 0.01 kg·m²) with a constant torque M_A = 1.5 N·m; i = 20, so v_a = 100 sin 2t and
// a = 200 cos 2t. A's own equation gives X whatever the mode: X = M_A − I_A a = 1.5 − 2 cos 2t. A drives
// while s X > 0: Y = η_mf1 X; else B drives: Y = X/η_mf2. By hand:
//   (0, t1) forward, b drives; (t1, π/2) forward, a drives     t1 = acos(0.75)/2 = 0.3614 s
//   (π/2, t2) backward, b drives; (t2, π) backward, a drives   t2 = π − t1.
// B's source closes I_B a_b = R + i Y: R = I_B · 10 cos 2t − i Y; the gear's torque at B is −i Y.
// Rows to 1e-6 (torques to 30 N·m at B), switch instants to 1e-8 s, heat against its closed form
// Σ (1 − η_mf1 or 1 − 1/η_mf2) ∫ X v_a dt with X v_a = 150 sin 2t − 100 sin 4t = Q', Q = −75 cos 2t + 25 cos 4t.
TEST_P(PrescribedGear, SpeedSourceOnTheDrumFollowsTheQuadrantsByHand) {
  const SimulationResult r = run(R"(bodies:
  A: {inertia: 0.01 kg*m^2}
  B: {inertia: 40 kg*m^2, motion: {speed: {type: sine, amplitude: 5 rad/s, frequency: 2 rad/s}}}
links:
  G: {type: lossy-gear, between: [A, B], ratio: 20, efficiency: 0.9, efficiency_reverse: 0.4}
loads:
  MA: {type: constant, body: A, value: 1.5 N*m}
simulation: {t_end: 3 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)", GetParam());
  const double IB = 40.0, i = 20.0, eta1 = 0.9, eta2 = 0.4;
  const double t1 = std::acos(0.75) / 2.0, t2 = kPi - t1;
  auto X = [](double t) { return 1.5 - 2.0 * std::cos(2.0 * t); };
  auto va = [](double t) { return 100.0 * std::sin(2.0 * t); };
  auto Y = [&](double t) { return va(t) * X(t) > 0.0 ? eta1 * X(t) : X(t) / eta2; };
  const auto& t = series(r, "t_s");
  const auto& ta = series(r, "G.torque_a_N_m");
  const auto& tb = series(r, "G.torque_b_N_m");
  const auto& R = series(r, "B.motion_torque_N_m");
  const auto& wA = series(r, "A.velocity_rad_s");
  const auto& md = series(r, "G.mode");
  ASSERT_GT(t.size(), 2000u);
  for (size_t k = 0; k < t.size(); ++k) {
    if (std::abs(std::remainder(t[k], kPi / 2.0)) < 1e-6) continue;
    EXPECT_NEAR(ta[k], X(t[k]), 1e-6) << "t = " << t[k];
    EXPECT_NEAR(tb[k], -i * Y(t[k]), 1e-6 * i) << "t = " << t[k];
    EXPECT_NEAR(R[k], IB * 10.0 * std::cos(2.0 * t[k]) - i * Y(t[k]), 1e-5) << "t = " << t[k];
    EXPECT_NEAR(wA[k], va(t[k]), 1e-6) << "t = " << t[k];
    EXPECT_EQ(md[k], va(t[k]) > 0.0 ? 1.0 : -1.0) << "t = " << t[k];
  }
  const auto ch = gear_changes(r);
  const std::vector<std::pair<double, std::string>> want = {
      {t1, "forward"}, {kPi / 2, "backward_b_drives"}, {t2, "backward"}};
  ASSERT_EQ(ch.size(), want.size());
  for (size_t k = 0; k < want.size(); ++k) {
    EXPECT_NEAR(ch[k].first, want[k].first, 1e-8);
    EXPECT_EQ(ch[k].second, want[k].second);
  }
  auto Q = [](double s) { return -75.0 * std::cos(2.0 * s) + 25.0 * std::cos(4.0 * s); };
  const double fa = 1.0 - eta1, fb = 1.0 - 1.0 / eta2, T = 3.0;
  const double heat = fb * (Q(t1) - Q(0)) + fa * (Q(kPi / 2) - Q(t1)) + fb * (Q(t2) - Q(kPi / 2)) + fa * (Q(T) - Q(t2));
  EXPECT_NEAR(r.hybrid.energy.friction_loss, heat, 1e-7 * heat);
  EXPECT_NEAR(r.hybrid.energy.residual(), 0.0, 1e-8 * r.hybrid.energy.source_work);
}

// Claim: at rest the gear holds the load and the source delivers the least torque that keeps it so.
// The worm's speed ramps 0 → 50 rad/s in 1 s, back to 0 at 2 s and stays there; the drum carries
// M_B = −60 N·m through i = 20 (Y = −F_b' = 3 N·m at rest). Held: X ∈ [X_−(Y), X_+(Y)] with
// X_+ = Y/η_mf1 (lifting, a drives) and X_− = η_mf2 Y (lowering, b drives); the source's least torque
// is X = clamp(0, X_−, X_+) = η_mf2 Y: 1.2 N·m for η_mf2 = 0.4, and 0 for a self-locking gear
// (η_mf2 = 0: it holds the load alone). Mode 0 and R = X at every row of (2, 3] s.
TEST_P(PrescribedGear, AtRestTheSourceHoldsOnlyWhatTheGearCannot) {
  for (const double eta2 : {0.4, 0.0}) {
    const SimulationResult r = run(fmt::format(R"(bodies:
  A: {{inertia: 0.02 kg*m^2, motion: {{speed: {{type: table, unit: rad/s, points: [[0, 0], [1, 50], [2, 0], [3, 0]]}}}}}}
  B: {{inertia: 40 kg*m^2}}
links:
  G: {{type: lossy-gear, between: [A, B], ratio: 20, efficiency: 0.9, efficiency_reverse: {}}}
loads:
  MB: {{type: constant, body: B, value: -60 N*m}}
simulation: {{t_end: 3 s, dt_out: 10 ms, rtol: 1e-10, atol: 1e-12}}
)", eta2), GetParam());
    const auto& t = series(r, "t_s");
    const auto& ta = series(r, "G.torque_a_N_m");
    const auto& md = series(r, "G.mode");
    const auto& R = series(r, "A.motion_torque_N_m");
    const auto& wB = series(r, "B.velocity_rad_s");
    size_t n = 0;
    for (size_t k = 0; k < t.size(); ++k) {
      if (t[k] < 1.0 - 1e-9 && t[k] > 1e-9) {  // lifting, a drives: X = (J_b a + 3)/η_mf1, a = 50
        EXPECT_NEAR(ta[k], (0.1 * 50.0 + 3.0) / 0.9, 1e-6) << "t = " << t[k];
        EXPECT_EQ(md[k], 1.0);
      }
      if (t[k] <= 2.0 + 1e-9) continue;
      ++n;
      EXPECT_EQ(md[k], 0.0) << "t = " << t[k];
      EXPECT_NEAR(ta[k], eta2 * 3.0, 1e-9) << "t = " << t[k];
      EXPECT_NEAR(R[k], eta2 * 3.0, 1e-9) << "t = " << t[k];
      EXPECT_EQ(wB[k], 0.0) << "t = " << t[k];
    }
    EXPECT_GE(n, 99u);
  }
}

// Claim: examples/worm-hoist-speed-source.yaml does what its comment says. J_b = 4/40² = 0.0025 kg·m²,
// −F_b' = 150/40 = 3.75 N·m, η_mf1 = 0.45, η_mf2 = 0: lifting at 150 rad/s (a = 0) X = 3.75/0.45 =
// 8.333 N·m, mode +1; lowering at −150 rad/s the weight drives the self-locking gear (s Y < 0): X = 0,
// mode −1, the heat −Y v_a = 562.5 W is the weight's power, the motor's torque 0; at rest after 10 s
// the gear holds the weight alone (X = 0, R = 0, mode 0). To 1e-6 at the rows of each phase.
TEST_P(PrescribedGear, WormHoistExampleLiftsLowersAndHolds) {
  Model m = load_model(std::string(MACHDYN_SOURCE_DIR) + "/examples/worm-hoist-speed-source.yaml");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  for (const double t : {2.0, 2.5, 3.5}) {
    EXPECT_NEAR(test::at(r, "worm.torque_a_N_m", t), 3.75 / 0.45, 1e-6);
    EXPECT_EQ(test::at(r, "worm.mode", t), 1.0);
  }
  for (const double t : {7.5, 8.0, 8.5}) {
    EXPECT_NEAR(test::at(r, "worm.torque_a_N_m", t), 0.0, 1e-6);
    EXPECT_NEAR(test::at(r, "worm.loss_power_W", t), 562.5, 1e-6);
    EXPECT_NEAR(test::at(r, "motor.motion_torque_N_m", t), 0.0, 1e-6);
    EXPECT_EQ(test::at(r, "worm.mode", t), -1.0);
  }
  for (const double t : {10.5, 11.0, 12.0}) {
    EXPECT_NEAR(test::at(r, "worm.torque_a_N_m", t), 0.0, 1e-9);
    EXPECT_NEAR(test::at(r, "motor.motion_torque_N_m", t), 0.0, 1e-9);
    EXPECT_NEAR(test::at(r, "worm.torque_b_N_m", t), -150.0, 1e-9);  // −i Y: the weight held
    EXPECT_EQ(test::at(r, "worm.mode", t), 0.0);
  }
}

// Claim: what stays refused is a located error: both bodies prescribed, a prescribed drum on a
// self-locking gear (it cannot drive the worm), friction on a prescribed gear's body.
TEST(PrescribedGearCompile, RefusedCombinationsAreLocatedErrors) {
  const std::string head = R"(bodies:
  A: {inertia: 0.02 kg*m^2, motion: {speed: 10 rad/s}}
  B: {inertia: 40 kg*m^2)";
  const std::string gear = R"(links:
  G: {type: lossy-gear, between: [A, B], ratio: 20, efficiency: 0.9, efficiency_reverse: 0.4}
)";
  std::string e = test::compile_errors(head + ", motion: {speed: 0.5 rad/s}}\n" + gear, "gear.yaml");
  EXPECT_NE(e.find("gear.yaml:5:3"), std::string::npos) << e;
  EXPECT_NE(e.find("both 'A' and 'B' have a prescribed motion"), std::string::npos) << e;

  e = test::compile_errors(R"(bodies:
  A: {inertia: 0.02 kg*m^2}
  B: {inertia: 40 kg*m^2, motion: {speed: 0.5 rad/s}}
links:
  G: {type: lossy-gear, between: [A, B], ratio: 20, efficiency: 0.9, efficiency_reverse: 0}
)", "gear.yaml");
  EXPECT_NE(e.find("gear.yaml:5:3"), std::string::npos) << e;
  EXPECT_NE(e.find("self-locking (efficiency_reverse 0): it cannot drive 'A' backwards"), std::string::npos) << e;

  e = test::compile_errors(head + "}\n" + gear + R"(brakes:
  K: {body: B, normal_force: 100 N, mu_s: 0.5, mu_k: 0.5, radius: 1 m, surfaces: 2}
)", "gear.yaml");
  EXPECT_NE(e.find("gear.yaml:5:3"), std::string::npos) << e;
  EXPECT_NE(e.find("the friction element 'K' acts on the gear's bodies"), std::string::npos) << e;
}

}  // namespace
}  // namespace machdyn
