// A lossy gear with a prescribed side whose motion leaves rest and comes back to rest smoothly (speed and
// acceleration both 0 there, no kink: an S-curve speed reference). The gear's mode is a function of t
// alone (elements/lossy_gear.hpp "Mode law"), so the torques, the mode column, the heat and the source's
// torque follow the motion from the first instant of the start to the hold, on both integrators, with
// the motion on the worm (a) and on the drum (b), lifting and lowering; the shipped S-curve example.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <utility>
#include <vector>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::series;

/// Checks gear `gear`'s mode changes (time, new mode) against `want` (times to 1e-8 s); returns the
/// largest time error.
double check_switches(const SimulationResult& r, const std::string& gear,
                      const std::vector<std::pair<double, std::string>>& want) {
  std::vector<std::pair<double, std::string>> got;
  for (const auto& e : r.hybrid.events)
    if (e.element == gear && e.kind != "initial") got.emplace_back(e.t, e.to);
  EXPECT_EQ(got.size(), want.size());
  double e_t = 0.0;
  for (size_t k = 0; k < want.size() && k < got.size(); ++k) {
    EXPECT_NEAR(got[k].first, want[k].first, 1e-8) << got[k].second;
    EXPECT_EQ(got[k].second, want[k].second);
    e_t = std::max(e_t, std::abs(got[k].first - want[k].first));
  }
  return e_t;
}

class SmoothStartGear : public ::testing::TestWithParam<std::pair<IntegratorChoice, int>> {};
INSTANTIATE_TEST_SUITE_P(IntegratorsAndDirections, SmoothStartGear,
                         ::testing::Values(std::pair{IntegratorChoice::dopri5, 1}, std::pair{IntegratorChoice::bdf, 1},
                                           std::pair{IntegratorChoice::dopri5, -1},
                                           std::pair{IntegratorChoice::bdf, -1}));

/// The root of f on [lo, hi] (f(lo), f(hi) of opposite signs) by bisection.
template <class F>
double bisect(F f, double lo, double hi) {
  const bool neg_lo = f(lo) < 0.0;
  for (int k = 0; k < 200 && hi - lo > 1e-15; ++k) {
    const double mid = 0.5 * (lo + hi);
    if ((f(mid) < 0.0) == neg_lo) lo = mid;
    else hi = mid;
  }
  return 0.5 * (lo + hi);
}

// Claim: a speed source on the worm A (I_A = 0.02 kg·m²) at rest until 0.5 s, then the bump
//   v_a = σ 800 u² (1 − u)²,  u = t − 0.5 ∈ [0, 1]  (σ = ±1: lifting or lowering; 50 rad/s at u = ½),
// at rest again from 1.5 s; v and a = σ 1600 u (1 − u)(1 − 2u) are 0 at both ends (no kink). The gear
// (i = 20, η_mf1 = 0.9, η_mf2 = 0.4) drives the drum B (I_B = 40 kg·m²) with M_B = −60 N·m. In A's
// coordinate J_b = I_B/i² = 0.1 kg·m², −F_b' = 3 N·m, and B's equation gives in every mode
//   Y = J_b a + 3.
// Rolling (0 < u < 1, s = σ): A drives while s Y > 0, X = Y/η_mf1; else B drives, X = η_mf2 Y; mode σ.
// At rest (a = 0, Y = 3): the locking range is [X_−, X_+] = [η_mf2 Y, Y/η_mf1] = [1.2, 3.33] N·m and the
// source delivers the least torque, X = clamp(0, ·) = 1.2 N·m; mode 0. The source's torque closes A's
// equation: R = I_A a + X (nothing else acts on A). Heat (X − Y) v_a = c Y v_a with c = 1/η_mf1 − 1 (A
// drives) or η_mf2 − 1 (B drives), and Y v_a = P'(t) with P = J_b v²/2 + 3 q, q = σ 800 (u³/3 − u⁴/2 +
// u⁵/5) (∫ v dt), so the heat is Σ_phases c [P(end) − P(start)], the phases split at the roots of Y
// (found here by bisection). Mode changes: a start at 0.5 s, the driving side at each root of Y, a
// stop at 1.5 s. Every row to 1e-6 N·m, switch instants to 1e-8 s, the heat to 1e-7 relative.
TEST_P(SmoothStartGear, TorquesModeHeatAndSourceFollowTheMotionFromRestToRest) {
  const auto [integrator, sigma] = GetParam();
  Model m = test::model_text(fmt::format(R"(bodies:
  A: {{inertia: 0.02 kg*m^2, motion: {{speed: {{type: expression, expression: "{}800*((t-0.5+abs(t-0.5))/2)^2*((1.5-t+abs(1.5-t))/2)^2"}}}}}}
  B: {{inertia: 40 kg*m^2}}
links:
  G: {{type: lossy-gear, between: [A, B], ratio: 20, efficiency: 0.9, efficiency_reverse: 0.4}}
loads:
  MB: {{type: constant, body: B, value: -60 N*m}}
simulation: {{t_end: 2.5 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}}
)", sigma < 0 ? "-" : ""), "gear.yaml");
  m.simulation.integrator = integrator;
  const SimulationResult r = simulate(m);
  const double IA = 0.02, Jb = 0.1, eta1 = 0.9, eta2 = 0.4, sg = sigma;
  auto moving = [](double u) { return u > 0.0 && u < 1.0; };
  auto v = [&](double u) { return moving(u) ? sg * 800.0 * u * u * (1 - u) * (1 - u) : 0.0; };
  auto a = [&](double u) { return moving(u) ? sg * 1600.0 * u * (1 - u) * (1 - 2 * u) : 0.0; };
  auto Y = [&](double u) { return Jb * a(u) + 3.0; };
  auto a_drives = [&](double u) { return sg * Y(u) > 0.0; };
  auto X = [&](double u) { return !moving(u) ? eta2 * 3.0 : a_drives(u) ? Y(u) / eta1 : eta2 * Y(u); };
  auto P = [&](double u) {
    return 0.5 * Jb * v(u) * v(u) + 3.0 * sg * 800.0 * (u * u * u / 3 - u * u * u * u / 2 + u * u * u * u * u / 5);
  };
  // The roots of Y on (0, 1): a sign scan on a 1e-3 grid, then bisection.
  std::vector<double> cuts = {0.0};
  for (double u0 = 1e-3; u0 + 1e-3 < 1.0; u0 += 1e-3)
    if ((Y(u0) < 0.0) != (Y(u0 + 1e-3) < 0.0)) cuts.push_back(bisect(Y, u0, u0 + 1e-3));
  cuts.push_back(1.0);
  // Y = 0 where σ u (1 − u)(1 − 2u) = −0.01875: twice for either σ (|u (1 − u)(1 − 2u)| peaks at 0.096).
  ASSERT_EQ(cuts.size(), 4u);
  double heat = 0.0;
  std::vector<std::pair<double, std::string>> want;  // (t, mode) of every change after the initial one
  for (size_t k = 0; k + 1 < cuts.size(); ++k) {
    const bool ad = a_drives(0.5 * (cuts[k] + cuts[k + 1]));
    heat += (ad ? 1.0 / eta1 - 1.0 : eta2 - 1.0) * (P(cuts[k + 1]) - P(cuts[k]));
    want.emplace_back(0.5 + cuts[k], std::string(sg > 0 ? "forward" : "backward") + (ad ? "" : "_b_drives"));
  }
  want.emplace_back(1.5, "stuck");

  const auto& t = series(r, "t_s");
  const auto& ta = series(r, "G.torque_a_N_m");
  const auto& tb = series(r, "G.torque_b_N_m");
  const auto& loss = series(r, "G.loss_power_W");
  const auto& md = series(r, "G.mode");
  const auto& R = series(r, "A.motion_torque_N_m");
  const auto& wB = series(r, "B.velocity_rad_s");
  ASSERT_GT(t.size(), 2400u);
  double e_x = 0.0;
  size_t at_rest = 0;
  for (size_t k = 0; k < t.size(); ++k) {
    const double u = t[k] - 0.5;
    at_rest += !moving(u);
    EXPECT_NEAR(ta[k], X(u), 1e-6) << "t = " << t[k];
    EXPECT_NEAR(tb[k], -20.0 * Y(u), 20e-6) << "t = " << t[k];
    EXPECT_NEAR(R[k], IA * a(u) + X(u), 1e-6) << "t = " << t[k];
    EXPECT_NEAR(loss[k], (X(u) - Y(u)) * v(u), 1e-4) << "t = " << t[k];
    EXPECT_NEAR(wB[k], v(u) / 20.0, 1e-7) << "t = " << t[k];
    EXPECT_EQ(md[k], moving(u) ? sg : 0.0) << "t = " << t[k];
    e_x = std::max({e_x, std::abs(ta[k] - X(u)), std::abs(R[k] - IA * a(u) - X(u))});
  }
  EXPECT_GE(at_rest, 1499u);  // [0, 0.5] and [1.5, 2.5] s: the holds before and after are checked too
  const double e_t = check_switches(r, "G", want);
  EXPECT_NEAR(r.hybrid.energy.friction_loss, heat, 1e-7 * heat);
  EXPECT_NEAR(r.hybrid.energy.residual(), 0.0, 1e-8 * r.hybrid.energy.source_work);
  std::printf("SmoothStartGear %s sigma %+d: X, R %.2e N*m; switches %.2e s; heat %.6f J vs %.6f\n",
              integrator == IntegratorChoice::bdf ? "bdf" : "dopri5", sigma, e_x, e_t, r.hybrid.energy.friction_loss,
              heat);
}

// Claim: the same bump prescribed on the drum B instead, v_b = v_a/20 (I_B = 40 kg·m², M_B = −60 N·m), the
// worm A free (I_A = 0.02 kg·m², nothing else on it). A's own equation gives in every mode
//   X = −I_A a,   a = σ 1600 u (1 − u)(1 − 2u)  (A's acceleration, = 20 a_b).
// Rolling (s = σ): A drives while s X > 0 (the worm is braked: the second half, u > ½), Y = η_mf1 X; else
// B drives (the drum accelerates the worm), Y = X/η_mf2; the switch where a = 0, at u = ½ (t = 1 s).
// At rest X = 0 and the locking range of Y is [Y_+(0), Y_−(0)] = [0, 0]: Y = 0, the drum's source holds
// the load alone. B's source closes B's equation: R_B = I_B a_b + 60 − 20 Y. Heat (X − Y) v_a: with
// ∫ X v_a dt = −I_A v_a²/2 over each half and v_a(½) = 50 rad/s, it is
//   I_A/2 · 50² · [(1/η_mf2 − 1) + (1 − η_mf1)] = 25 · 1.6 = 40 J.
// Every row to 1e-6 N·m; the start, the driving side at 1 s and the stop to 1e-8 s; the heat to 1e-7.
TEST_P(SmoothStartGear, OnTheDrumTheWormsEquationDecides) {
  const auto [integrator, sigma] = GetParam();
  Model m = test::model_text(fmt::format(R"(bodies:
  A: {{inertia: 0.02 kg*m^2}}
  B: {{inertia: 40 kg*m^2, motion: {{speed: {{type: expression, expression: "{}40*((t-0.5+abs(t-0.5))/2)^2*((1.5-t+abs(1.5-t))/2)^2"}}}}}}
links:
  G: {{type: lossy-gear, between: [A, B], ratio: 20, efficiency: 0.9, efficiency_reverse: 0.4}}
loads:
  MB: {{type: constant, body: B, value: -60 N*m}}
simulation: {{t_end: 2.5 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}}
)", sigma < 0 ? "-" : ""), "gear.yaml");
  m.simulation.integrator = integrator;
  const SimulationResult r = simulate(m);
  const double IA = 0.02, IB = 40.0, eta1 = 0.9, eta2 = 0.4, sg = sigma;
  auto moving = [](double u) { return u > 0.0 && u < 1.0; };
  auto v = [&](double u) { return moving(u) ? sg * 800.0 * u * u * (1 - u) * (1 - u) : 0.0; };
  auto a = [&](double u) { return moving(u) ? sg * 1600.0 * u * (1 - u) * (1 - 2 * u) : 0.0; };
  auto X = [&](double u) { return -IA * a(u); };
  auto Y = [&](double u) { return !moving(u) ? 0.0 : sg * X(u) > 0.0 ? eta1 * X(u) : X(u) / eta2; };
  const auto& t = series(r, "t_s");
  const auto& ta = series(r, "G.torque_a_N_m");
  const auto& tb = series(r, "G.torque_b_N_m");
  const auto& loss = series(r, "G.loss_power_W");
  const auto& md = series(r, "G.mode");
  const auto& R = series(r, "B.motion_torque_N_m");
  const auto& wA = series(r, "A.velocity_rad_s");
  ASSERT_GT(t.size(), 2400u);
  double e_x = 0.0;
  for (size_t k = 0; k < t.size(); ++k) {
    const double u = t[k] - 0.5;
    EXPECT_NEAR(ta[k], X(u), 1e-6) << "t = " << t[k];
    EXPECT_NEAR(tb[k], -20.0 * Y(u), 20e-6) << "t = " << t[k];
    EXPECT_NEAR(R[k], IB * a(u) / 20.0 + 60.0 - 20.0 * Y(u), 20e-6) << "t = " << t[k];
    EXPECT_NEAR(loss[k], (X(u) - Y(u)) * v(u), 1e-4) << "t = " << t[k];
    EXPECT_NEAR(wA[k], v(u), 2e-6) << "t = " << t[k];
    EXPECT_EQ(md[k], moving(u) ? sg : 0.0) << "t = " << t[k];
    e_x = std::max({e_x, std::abs(tb[k] + 20.0 * Y(u)), std::abs(R[k] - IB * a(u) / 20.0 - 60.0 + 20.0 * Y(u))});
  }
  const std::string dir = sg > 0 ? "forward" : "backward";
  const std::vector<std::pair<double, std::string>> want = {{0.5, dir + "_b_drives"}, {1.0, dir}, {1.5, "stuck"}};
  const double e_t = check_switches(r, "G", want);
  const double heat = 0.5 * IA * 50.0 * 50.0 * ((1.0 / eta2 - 1.0) + (1.0 - eta1));
  EXPECT_NEAR(r.hybrid.energy.friction_loss, heat, 1e-7 * heat);
  EXPECT_NEAR(r.hybrid.energy.residual(), 0.0, 1e-8 * r.hybrid.energy.source_work);
  std::printf("SmoothStartGear drum %s sigma %+d: Y, R %.2e N*m; switches %.2e s; heat %.6f J vs %.6f\n",
              integrator == IntegratorChoice::bdf ? "bdf" : "dopri5", sigma, e_x, e_t, r.hybrid.energy.friction_loss,
              heat);
}

// Claim: examples/worm-hoist-s-curve.yaml does what its comment says. The motor's speed is 150 (S(c₁) −
// S(c₂)), S(c) = 3c² − 2c³, c₁ = clamp(t − 0.5, 0, 1), c₂ = clamp(t − 4, 0, 1); a = 150 · 6c(1 − c) on the
// ramps (− on the second). J_b = 4/40² = 0.0025 kg·m², −F_b' = 150/40 = 3.75 N·m, so Y = 0.0025 a + 3.75
// ≥ 3.75 − 0.0025 · 225 > 0: A drives whenever it moves (X = Y/0.45, R = 0.02 a + X, mode +1), and at
// rest the self-locking gear (η_mf2 = 0) holds the weight alone (X = 0, R = 0, mode 0). Every row to
// 1e-6 N·m; the gear's changes are exactly a start at 0.5 s and a stop at 5 s (to 1e-8 s): a signal at
// rest only up to its rounding makes no chatter.
TEST(SmoothStartGearExample, WormHoistOnAnSCurveStartsAndStopsOnce) {
  for (const IntegratorChoice integrator : {IntegratorChoice::dopri5, IntegratorChoice::bdf}) {
    Model m = load_model(std::string(MACHDYN_SOURCE_DIR) + "/examples/worm-hoist-s-curve.yaml");
    m.simulation.integrator = integrator;
    const SimulationResult r = simulate(m);
    auto clamp01 = [](double x) { return std::clamp(x, 0.0, 1.0); };
    auto ramp_a = [](double c) { return c > 0.0 && c < 1.0 ? 150.0 * 6.0 * c * (1.0 - c) : 0.0; };
    const auto& t = series(r, "t_s");
    const auto& ta = series(r, "worm.torque_a_N_m");
    const auto& R = series(r, "motor.motion_torque_N_m");
    const auto& md = series(r, "worm.mode");
    ASSERT_GT(t.size(), 590u);
    for (size_t k = 0; k < t.size(); ++k) {
      const double c1 = clamp01(t[k] - 0.5), c2 = clamp01(t[k] - 4.0);
      const bool moving = c1 > 0.0 && c2 < 1.0;
      const double a = ramp_a(c1) - ramp_a(c2);
      const double X = moving ? (0.0025 * a + 3.75) / 0.45 : 0.0;
      EXPECT_NEAR(ta[k], X, 1e-6) << "t = " << t[k];
      EXPECT_NEAR(R[k], moving ? 0.02 * a + X : 0.0, 1e-6) << "t = " << t[k];
      EXPECT_EQ(md[k], moving ? 1.0 : 0.0) << "t = " << t[k];
    }
    check_switches(r, "worm", {{0.5, "forward"}, {5.0, "stuck"}});
  }
}

}  // namespace
}  // namespace machdyn
