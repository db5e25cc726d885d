// Lossy gears (`type: lossy-gear`, elements/lossy_gear.hpp): against closed forms of the power balance
// in each direction of the power flow (both integrators), a self-locking gear that holds its load and
// stops at the closed-form instant, MSL's LossyGearDemo1 against an independent piecewise closed form
// of MSL's own equations written here, LossyGearDemo3 (bearing friction), the modes (the ideal gear's)
// and the located errors of bad input.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "support/gear_phases.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::series;

Model compile_text(const std::string& text) { return test::model_text(text, "gear.yaml"); }

std::string errors_of(const std::string& text) { return test::compile_errors(text, "gear.yaml"); }

class LossyGearSim : public ::testing::TestWithParam<const char*> {
 protected:
  SimulationResult run(const std::string& yaml, double t_end) const {
    const Model m = compile_text(yaml + fmt::format("simulation: {{t_end: {}, dt_out: {}, rtol: 1e-11, atol: 1e-13, "
                                                    "integrator: {}}}\n", t_end, t_end / 100, GetParam()));
    return simulate(m);
  }
};

INSTANTIATE_TEST_SUITE_P(BothIntegrators, LossyGearSim, ::testing::Values("dopri5", "bdf"));

constexpr double kIA = 0.3, kIB = 2.0, kI = 3.5;  // kg·m², kg·m², v_A = i v_B

std::string two_bodies(double eta1, double eta2, double MA, double MB, const std::string& extra_b = "") {
  return fmt::format(R"(bodies:
  A: {{inertia: {} kg*m^2}}
  B: {{inertia: {} kg*m^2{}}}
links:
  G: {{type: lossy-gear, between: [A, B], ratio: {}, efficiency: {}, efficiency_reverse: {}}}
loads:
  MA: {{type: constant, body: A, value: {} N*m}}
  MB: {{type: constant, body: B, value: {} N*m}}
)", kIA, kIB, extra_b, kI, eta1, eta2, MA, MB);
}

/// The gear's events after the initial modes.
std::vector<ModeEvent> gear_events(const SimulationResult& r, const std::string& gear) {
  std::vector<ModeEvent> out;
  for (const auto& e : r.hybrid.events)
    if (e.element == gear && e.kind != "initial") out.push_back(e);
  return out;
}

// Claim: power flowing from A to B (A drives forward) arrives at B reduced by η_mf1. From rest with
// constant torques M_A on A and M_B on B: the torque A delivers into the gear is X = M_A − I_A ω_A', the
// power the gear delivers to B is (I_B ω_B' − M_B) ω_B, and η_mf1 X ω_A = (I_B ω_B' − M_B) ω_B with
// ω_A = i ω_B gives
//   ω_B' = (η_mf1 i M_A + M_B) / (η_mf1 i² I_A + I_B)      (η_mf2 plays no part),
// valid while X > 0 (A drives). Heat (1 − η_mf1) X ω_A; MSL's flange_b.tau = M_B − I_B ω_B'.
// M_A = 10, M_B = −4, η_mf1 = 0.8: ω_B' = 24/4.94 rad/s², X = 4.90 N·m. Every row to 1e-9 relative.
TEST_P(LossyGearSim, ForwardPowerFlowLosesOneMinusEtaOne) {
  const double eta1 = 0.8, MA = 10.0, MB = -4.0;
  const SimulationResult r = run(two_bodies(eta1, 0.3, MA, MB), 2.0);
  const double aB = (eta1 * kI * MA + MB) / (eta1 * kI * kI * kIA + kIB), X = MA - kIA * kI * aB;
  ASSERT_GT(X, 0.0);
  const auto& t = series(r, "t_s");
  const auto& wA = series(r, "A.velocity_rad_s");
  const auto& wB = series(r, "B.velocity_rad_s");
  const auto& mode = series(r, "G.mode");
  const auto& ta = series(r, "G.torque_a_N_m");
  const auto& tb = series(r, "G.torque_b_N_m");
  const auto& loss = series(r, "G.loss_power_W");
  ASSERT_EQ(t.size(), 101u);
  for (size_t k = 1; k < t.size(); ++k) {
    EXPECT_NEAR(wB[k], aB * t[k], 1e-9 * aB * t[k]);
    EXPECT_NEAR(wA[k], kI * aB * t[k], 1e-9 * kI * aB * t[k]);
    EXPECT_EQ(mode[k], 1.0);
    EXPECT_NEAR(ta[k], X, 1e-9 * X);
    EXPECT_NEAR(tb[k], MB - kIB * aB, 1e-9 * std::abs(MB - kIB * aB));
    EXPECT_NEAR(loss[k], (1.0 - eta1) * X * kI * aB * t[k], 1e-8 * X * kI * aB * t[k]);
  }
  // The energy books count the heat: W_src = ΔT + ∫ loss dt.
  EXPECT_NEAR(r.hybrid.energy.residual(), 0.0, 1e-8 * r.hybrid.energy.source_work);
  EXPECT_GT(r.hybrid.energy.friction_loss, 0.1 * r.hybrid.energy.source_work);
}

// Claim: power flowing from B to A (a load lowering against a holding torque) arrives at A reduced by
// η_mf2. B delivers P_B = (M_B − I_B ω_B') ω_B into the gear, A receives −X ω_A = η_mf2 P_B with
// X = M_A − I_A ω_A'; with ω_A = i ω_B:
//   ω_B' = (i M_A + η_mf2 M_B) / (i² I_A + η_mf2 I_B)      (η_mf1 plays no part),
// here M_A = 2, M_B = −20, η_mf2 = 0.6: ω_B' = −5/4.875 < 0 (backward), heat (1 − η_mf2) P_B.
TEST_P(LossyGearSim, BackwardPowerFlowLosesOneMinusEtaTwo) {
  const double eta2 = 0.6, MA = 2.0, MB = -20.0;
  const SimulationResult r = run(two_bodies(0.9, eta2, MA, MB), 2.0);
  const double aB = (kI * MA + eta2 * MB) / (kI * kI * kIA + eta2 * kIB);
  ASSERT_LT(aB, 0.0);
  const auto& t = series(r, "t_s");
  const auto& wB = series(r, "B.velocity_rad_s");
  const auto& mode = series(r, "G.mode");
  const auto& ta = series(r, "G.torque_a_N_m");
  const auto& loss = series(r, "G.loss_power_W");
  for (size_t k = 1; k < t.size(); ++k) {
    EXPECT_NEAR(wB[k], aB * t[k], 1e-9 * std::abs(aB) * t[k]);
    EXPECT_EQ(mode[k], -1.0);
    const double X = MA - kIA * kI * aB, PB = (MB - kIB * aB) * aB * t[k];
    EXPECT_NEAR(ta[k], X, 1e-9 * std::abs(X));
    EXPECT_NEAR(-X * kI * aB * t[k], eta2 * PB, 1e-12 * PB);  // the closed form itself: A receives η_mf2 P_B
    EXPECT_NEAR(loss[k], (1.0 - eta2) * PB, 1e-8 * PB);
  }
  const auto ev = gear_events(r, "G");
  EXPECT_TRUE(ev.empty());  // rolling backward from t = 0, b driving, without a switch
  ASSERT_FALSE(r.hybrid.events.empty());
  EXPECT_EQ(r.hybrid.events.front().to, "backward_b_drives");
}

// Claim: with bearing friction, B driving forward follows MSL's quadrant-2 loss. MSL's equations in A's
// coordinate (w_a > 0, tau_eta = τ_a − τ_bf,a < 0): L = (1 − 1/η_mf2) τ_a + τ_bf2, 0 = τ_b + i (τ_a − L),
// I_A a = M_A − τ_a, I_B a/i = M_B − τ_b, so
//   a (I_B/i + i I_A/η_mf2) = M_B + i M_A/η_mf2 − i τ_bf2,   lossPower = L w_a.
// i = 2, M_A = 0, M_B = 6, η = 0.8/0.5, τ_bf1 = 0.3, τ_bf2 = 0.6, ω_A(0) = 4: a = 4.8/2.2 rad/s², τ_a =
// −0.3 a, and τ_bf,a = (τ_bf1 − τ_bf2)/(η_mf1 − 1/η_mf2) = 0.25, so tau_eta < 0 indeed (B drives).
TEST_P(LossyGearSim, BearingFrictionWhileBDrivesFollowsMslQuadrantTwo) {
  const SimulationResult r = run(R"(bodies:
  A: {inertia: 0.3 kg*m^2, velocity: 4 rad/s}
  B: {inertia: 2 kg*m^2}
links:
  G: {type: lossy-gear, between: [A, B], ratio: 2, efficiency: 0.8, efficiency_reverse: 0.5,
      bearing_friction: 0.3 N*m, bearing_friction_reverse: 0.6 N*m}
loads:
  MB: {type: constant, body: B, value: 6 N*m}
)", 1.0);
  const double i = 2.0, eta2 = 0.5, bf2 = 0.6;
  const double a = (6.0 - i * bf2) / (kIB / i + i * kIA / eta2), ta = -kIA * a;
  ASSERT_LT(ta - 0.25, 0.0);
  const auto& t = series(r, "t_s");
  const auto& wA = series(r, "A.velocity_rad_s");
  const auto& torque = series(r, "G.torque_a_N_m");
  const auto& loss = series(r, "G.loss_power_W");
  for (size_t k = 0; k < t.size(); ++k) {
    const double w = 4.0 + a * t[k], L = (1.0 - 1.0 / eta2) * ta + bf2;
    EXPECT_NEAR(wA[k], w, 1e-9 * w);
    EXPECT_NEAR(torque[k], ta, 1e-9);
    EXPECT_NEAR(loss[k], L * w, 1e-8 * L * w);
  }
  ASSERT_FALSE(r.hybrid.events.empty());
  EXPECT_EQ(r.hybrid.events.front().to, "forward_b_drives");
  EXPECT_TRUE(gear_events(r, "G").empty());
}

// Claim: a lossy gear on a body slaved by an ideal gear acts through the ideal gear's ratio. A2 is tied
// to A by an ideal gear q_A = 2 q_A2; the lossy gear [A2, B] has q_A2 = 3 q_B and bearing friction
// 0.2 N·m in A2's coordinate. Reduced by hand to A's coordinate (q_A2 = q_A/2): inertia I_A + I_A2/4, the
// load 5 N·m on A2 is 2.5 N·m on A, the gear [A, B] has ratio 6 and bearing friction 0.1 N·m (power
// τ ω_A2 = (τ/2) ω_A). Both models give the same speeds and heat to 1e-10, and the gear's torque at its
// first body is A2's in the first model, twice A's.
TEST_P(LossyGearSim, OnAnIdealGearSlaveActsThroughItsRatio) {
  const SimulationResult r1 = run(R"(bodies:
  A: {inertia: 0.3 kg*m^2}
  A2: {inertia: 0.4 kg*m^2}
  B: {inertia: 2 kg*m^2}
links:
  I: {type: ideal-gear, between: [A, A2], ratio: 2}
  G: {type: lossy-gear, between: [A2, B], ratio: 3, efficiency: 0.7, efficiency_reverse: 0.4, bearing_friction: 0.2 N*m}
loads:
  M: {type: constant, body: A2, value: 5 N*m}
  MB: {type: constant, body: B, value: -3 N*m}
)", 1.0);
  const SimulationResult r2 = run(R"(bodies:
  A: {inertia: 0.4 kg*m^2}
  B: {inertia: 2 kg*m^2}
links:
  G: {type: lossy-gear, between: [A, B], ratio: 6, efficiency: 0.7, efficiency_reverse: 0.4, bearing_friction: 0.1 N*m}
loads:
  M: {type: constant, body: A, value: 2.5 N*m}
  MB: {type: constant, body: B, value: -3 N*m}
)", 1.0);
  const auto& w1 = series(r1, "B.velocity_rad_s");
  const auto& w2 = series(r2, "B.velocity_rad_s");
  const auto& wa2 = series(r1, "A2.velocity_rad_s");
  const auto& wa = series(r2, "A.velocity_rad_s");
  const auto& t1 = series(r1, "G.torque_a_N_m");
  const auto& t2 = series(r2, "G.torque_a_N_m");
  const auto& l1 = series(r1, "G.loss_power_W");
  const auto& l2 = series(r2, "G.loss_power_W");
  ASSERT_EQ(w1.size(), w2.size());
  ASSERT_GT(w2.back(), 0.1);  // it moves
  for (size_t k = 0; k < w1.size(); ++k) {
    EXPECT_NEAR(w1[k], w2[k], 1e-10 * (1.0 + std::abs(w2[k])));
    EXPECT_NEAR(wa2[k], wa[k] / 2.0, 1e-10 * (1.0 + std::abs(wa[k])));
    EXPECT_NEAR(t1[k], 2.0 * t2[k], 1e-10 * (1.0 + std::abs(t2[k])));
    EXPECT_NEAR(l1[k], l2[k], 1e-10 * (1.0 + std::abs(l2[k])));
  }
}

// Claim: a self-locking gear (η_mf2 = 0: B cannot drive A) holds any load on B at rest, and MSL's
// flange_b.tau is the holding torque M_B. A motor torque lifts the load only when η_mf1 i M_A > −M_B
// (the forward numerator above): M_A = 30 N·m gives 0.4 · 3.5 · 30 = 42 < 50 and stays stuck; M_A =
// 40 N·m gives 56 > 50 and accelerates forward with ω_B' = (56 − 50)/(0.4 · 3.5² · 0.3 + 2).
TEST_P(LossyGearSim, SelfLockingGearHoldsTheLoad) {
  for (double MA : {0.0, 30.0}) {
    const SimulationResult r = run(two_bodies(0.4, 0.0, MA, -50.0), 1.0);
    const auto& wA = series(r, "A.velocity_rad_s");
    const auto& wB = series(r, "B.velocity_rad_s");
    const auto& mode = series(r, "G.mode");
    const auto& tb = series(r, "G.torque_b_N_m");
    const auto& ta = series(r, "G.torque_a_N_m");
    for (size_t k = 0; k < wB.size(); ++k) {
      EXPECT_EQ(wA[k], 0.0);
      EXPECT_EQ(wB[k], 0.0);
      EXPECT_EQ(mode[k], 0.0);
      EXPECT_NEAR(tb[k], -50.0, 1e-12);  // holds the load
      EXPECT_EQ(ta[k], MA);     // and the motor
    }
    EXPECT_TRUE(gear_events(r, "G").empty());
  }
  const SimulationResult r = run(two_bodies(0.4, 0.0, 40.0, -50.0), 1.0);
  const double aB = (0.4 * kI * 40.0 - 50.0) / (0.4 * kI * kI * kIA + kIB);
  EXPECT_NEAR(test::at(r, "B.velocity_rad_s", 1.0), aB, 1e-9 * aB);
  EXPECT_EQ(test::at(r, "G.mode", 1.0), 1.0);
}

// Claim: a self-locking hoist coasting up stops at the closed-form instant and stays locked. B starts
// at ω_B = 2 rad/s with M_A = 20 N·m, M_B = −50 N·m, η_mf1 = 0.4, η_mf2 = 0: A drives while it rolls
// forward, ω_B' = (0.4 · 3.5 · 20 − 50)/(0.4 · 3.5² · 0.3 + 2) = −22/3.47, so it comes to rest at
// t* = 2 · 3.47/22 and, as 28 < 50 and B cannot drive A, stays stuck holding M_B.
TEST_P(LossyGearSim, StopsAtTheClosedFormInstantAndLocks) {
  const SimulationResult r = run(two_bodies(0.4, 0.0, 20.0, -50.0, ", velocity: 2 rad/s"), 1.0);
  const double aB = (0.4 * kI * 20.0 - 50.0) / (0.4 * kI * kI * kIA + kIB), ts = -2.0 / aB;
  const auto ev = gear_events(r, "G");
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].kind, "stick");
  EXPECT_NEAR(ev[0].t, ts, 1e-9);
  const auto& t = series(r, "t_s");
  const auto& wB = series(r, "B.velocity_rad_s");
  const auto& wA = series(r, "A.velocity_rad_s");
  const auto& tb = series(r, "G.torque_b_N_m");
  for (size_t k = 0; k < t.size(); ++k) {
    if (t[k] < ts) {
      EXPECT_NEAR(wB[k], 2.0 + aB * t[k], 1e-9);
      EXPECT_NEAR(wA[k], kI * (2.0 + aB * t[k]), 1e-8);
    } else {
      EXPECT_EQ(wB[k], 0.0);
      EXPECT_EQ(wA[k], 0.0);
      EXPECT_NEAR(tb[k], -50.0, 1e-12);
    }
  }
  EXPECT_NEAR(r.hybrid.energy.residual(), 0.0, 1e-8 * std::abs(r.hybrid.energy.kinetic_start));
}

// ---- MSL's LossyGearDemo1, by a piecewise closed form of MSL's equations ----
//
// MSL's LossyGear (ratio r, flange torques τ_a, τ_b, tauLoss L):  0 = τ_b + r (τ_a − L), and while
// w_a ≠ 0 the quadrant loss L = (1 − k) τ_a with k = η_mf1 when τ_a w_a ≥ 0 (w_a > 0) or τ_a w_a > 0
// (w_a < 0), else k = 1/η_mf2 (tau_eta = flange_a.tau without bearing friction). With Inertia1
// J1 a = τ1 − τ_a and Inertia2 J2 a/r = τ2 − τ_b (a = w_a'):
//   a = (τ2 + r k τ1) / (J2/r + r k J1),   τ_a = τ1 − J1 a,
// so w_a(t) = w0 + [∫τ2 + r k ∫τ1] / (J2/r + r k J1) in closed form for τ1 = 10 sin 2πt,
// τ2 = −10 + 2.5 t. Stuck (w_a = 0, a = 0): sa = L = τ1 + τ2/r; it starts forward when sa >
// tauLossMax_p = (1 − η_mf1) τ1 (τ1 > 0) or (1 − 1/η_mf2) τ1, backward when sa < tauLossMin_m =
// (1 − 1/η_mf2) τ1 (τ1 > 0) or (1 − η_mf1) τ1. The switches are located by scanning (1e-4 s) and
// bisection to 1e-15 s on these closed forms.
struct Demo1Reference : test::GearPhases {
  static constexpr double J1 = 1.0, J2 = 1.5, r = 2.0, eta1 = 0.5, eta2 = 0.5, kPi = 3.14159265358979323846;
  using Segment = test::GearPhase;

  static double tau1(double t) { return 10.0 * std::sin(2 * kPi * t); }
  static double tau2(double t) { return -10.0 + 2.5 * t; }
  static double int1(double t) { return 10.0 * (1.0 - std::cos(2 * kPi * t)) / (2 * kPi); }
  static double int2(double t) { return -10.0 * t + 1.25 * t * t; }
  static double acc(double t, double k) { return (tau2(t) + r * k * tau1(t)) / (J2 / r + r * k * J1); }
  static double w(const Segment& g, double t) {
    return g.w0 + (int2(t) - int2(g.t0) + r * g.k * (int1(t) - int1(g.t0))) / (J2 / r + r * g.k * J1);
  }
  static double start_fwd(double t) {  // > 0: starts forward
    const double sa = tau1(t) + tau2(t) / r;
    return sa - (tau1(t) > 0 ? (1 - eta1) * tau1(t) : (1 - 1 / eta2) * tau1(t));
  }
  static double start_bwd(double t) {  // > 0: starts backward
    const double sa = tau1(t) + tau2(t) / r;
    return (tau1(t) > 0 ? (1 - 1 / eta2) * tau1(t) : (1 - eta1) * tau1(t)) - sa;
  }
  /// k of the quadrant consistent with direction s at t (τ_a of either k has the same sign).
  static double quadrant(int s, double t) {
    const double ta = tau1(t) - J1 * acc(t, eta1);
    const bool a_drives = s > 0 ? ta >= 0 : ta < 0;
    return a_drives ? eta1 : 1 / eta2;
  }

  explicit Demo1Reference(double t_end) : GearPhases(t_end, start_fwd, start_bwd, [](int s, double t, double) { return quadrant(s, t); }, w) {}
};

class LossyGearMsl : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, LossyGearMsl, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

Model msl_example(const std::string& name, IntegratorChoice integrator) {
  Model m = load_model(std::string(MACHDYN_SOURCE_DIR) + "/examples/msl/" + name);
  m.simulation.integrator = integrator;
  return m;
}

// Claim: examples/msl/lossy-gear-demo1.yaml (MSL LossyGearDemo1) switches its modes at the reference's
// instants (within 1e-8 s) and follows its speeds at every output row (1e-7 rad/s; BDF 1e-6), the gear
// takes all modes (forward, backward, stuck), and the loss power is never negative.
TEST_P(LossyGearMsl, Demo1MatchesThePiecewiseClosedForm) {
  const SimulationResult r = simulate(msl_example("lossy-gear-demo1.yaml", GetParam()));
  const Demo1Reference ref(0.5);
  const auto ev = gear_events(r, "gear");
  std::string listed;
  for (const auto& e : ev) listed += fmt::format(" {:.9f} {}->{};", e.t, e.from, e.to);
  listed += " reference:";
  for (double x : ref.switches) listed += fmt::format(" {:.9f}", x);
  ASSERT_EQ(ev.size(), ref.switches.size()) << listed;
  for (size_t k = 0; k < ev.size(); ++k) EXPECT_NEAR(ev[k].t, ref.switches[k], 1e-8) << ev[k].kind << " " << ev[k].to;
  const double tol = GetParam() == IntegratorChoice::bdf ? 1e-6 : 1e-7;
  const auto& t = series(r, "t_s");
  const auto& w1 = series(r, "Inertia1.velocity_rad_s");
  const auto& w2 = series(r, "Inertia2.velocity_rad_s");
  const auto& mode = series(r, "gear.mode");
  const auto& loss = series(r, "gear.loss_power_W");
  ASSERT_EQ(t.size(), 501u);
  bool seen[3] = {false, false, false};
  for (size_t k = 0; k < t.size(); ++k) {
    EXPECT_NEAR(w1[k], ref.speed(t[k]), tol) << t[k];
    EXPECT_NEAR(w2[k], w1[k] / 2.0, 1e-12 * (1.0 + std::abs(w1[k])));
    seen[static_cast<int>(mode[k]) + 1] = true;
    EXPECT_GE(loss[k], -1e-9);
  }
  EXPECT_TRUE(seen[0] && seen[1] && seen[2]);
}

// Claim: examples/msl/lossy-gear-demo3.yaml (MSL LossyGearDemo3: ratio 1, η = 0.25, τ_bf1 = 0.625,
// τ_bf2 = 2.5, both inertias 0.001 kg·m² at 10 rad/s, no torques until a 1 N·m step on Inertia2 at
// 0.5 s). The bearing split (MSL): τ_bf,a = (τ_bf1 − τ_bf2)/(η1 − 1/η2) = 0.5, τ_bf,b = 0.5; with no
// torques the mesh carries nothing and both quadrants give (MSL, w > 0, τ_a ≥ 0:
// L = (1 − η1) τ_a + τ_bf1; J1 a = −τ_a, J2 a = −τ_b = τ_a − L) a = −τ_bf1/(J1 η1 + J2) = −500 rad/s².
// So w = 10 − 500 t until it sticks at t = 0.02 s; then sa = τ1 + τ2 = 1 N·m lies inside the locking
// range (tauLossMax_p = (1 − 1/η2)·0 + τ_bf2 = 2.5, tauLossMin_m = (1 − η1)·0 − τ_bf1 = −0.625 as
// τ_a = 0 ≤ 0 chooses quadrant 3) and the gear holds the step.
TEST_P(LossyGearMsl, Demo3SticksAndHoldsTheStep) {
  const SimulationResult r = simulate(msl_example("lossy-gear-demo3.yaml", GetParam()));
  const auto ev = gear_events(r, "gear");
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].kind, "stick");
  EXPECT_NEAR(ev[0].t, 0.02, 1e-10);
  const auto& t = series(r, "t_s");
  const auto& w1 = series(r, "Inertia1.velocity_rad_s");
  const auto& tb = series(r, "gear.torque_b_N_m");
  for (size_t k = 0; k < t.size(); ++k) {
    EXPECT_NEAR(w1[k], std::max(0.0, 10.0 - 500.0 * t[k]), 1e-8) << t[k];
    if (t[k] > 0.5 + 1e-9) {
      EXPECT_NEAR(tb[k], 1.0, 1e-12);  // holds the step
    }
  }
}

// Claim: for modes a lossy gear is the ideal gear (its constraint row v_A − i v_B = 0): the natural
// frequencies of A –(gear, i = 2)– B –(spring 4000)– C –(spring 900)– ground equal those of the same
// chain with an ideal gear (merged by compile into one degree of freedom), to 1e-9.
TEST(LossyGearModes, AreThoseOfTheIdealGear) {
  auto model = [&](const std::string& gear) {
    return compile_text("bodies:\n  A: {inertia: 0.7 kg*m^2}\n  B: {inertia: 1.3 kg*m^2}\n  C: {inertia: 2.1 kg*m^2}\n"
                        "links:\n  G: {" + gear + ", between: [A, B], ratio: 2}\n"
                        "  k: {type: spring, between: [B, C], stiffness: 4000 N*m/rad}\n"
                        "  g: {type: spring, between: [C, ground], stiffness: 900 N*m/rad}\n");
  };
  const Model lossy = model("type: lossy-gear, efficiency: 0.7"), ideal = model("type: ideal-gear");
  ASSERT_EQ(lossy.dof(), 3);
  ASSERT_EQ(ideal.dof(), 2);
  const Modes a = compute_modes(lossy), b = compute_modes(ideal);
  ASSERT_EQ(a.omega.size(), 2);
  ASSERT_EQ(b.omega.size(), 2);
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(a.omega[k], b.omega[k], 1e-9 * b.omega[k]);
}

// Claim: each misuse is a located error (file:line:col) that says why.
TEST(LossyGearCompile, BadInputIsALocatedError) {
  const std::string head = "bodies:\n  A: {inertia: 1}\n  B: {inertia: 2}\nlinks:\n";
  auto check = [&](const std::string& gear, const std::string& where, const std::string& why,
                   const std::string& more = "") {
    const std::string e = errors_of(head + "  G: {type: lossy-gear, " + gear + "}\n" + more);
    EXPECT_NE(e.find(where), std::string::npos) << gear << "\n" << e;
    EXPECT_NE(e.find(why), std::string::npos) << gear << "\n" << e;
  };
  check("between: [A, B], efficiency: 0", "gear.yaml:5:", "outside (0, 1]");
  check("between: [A, B], efficiency: 1.5", "gear.yaml:5:", "outside (0, 1]");
  check("between: [A, B], efficiency: 0.9, efficiency_reverse: -0.1", "gear.yaml:5:", "outside [0, 1]");
  check("between: [A, B], efficiency: 0.9, efficiency_reverse: 1.2", "gear.yaml:5:", "outside [0, 1]");
  check("between: [A, B]", "gear.yaml:5:", "efficiency");
  check("between: [A, X], efficiency: 0.9", "gear.yaml:5:", "unknown body 'X'");
  check("between: [A, ground], efficiency: 0.9", "gear.yaml:5:", "to the ground");
  check("between: [A, A], efficiency: 0.9", "gear.yaml:5:", "to itself");
  check("between: [A, B], ratio: 0, efficiency: 0.9", "gear.yaml:5:", "not zero");
  check("between: [A, B], efficiency: 0.9, bearing_friction: -1 N*m", "gear.yaml:5:", ">= 0");
  check("between: [A, B], efficiency: 1, bearing_friction: 1 N*m, bearing_friction_reverse: 2 N*m", "gear.yaml:5:",
        "cannot depend on the direction");
  check("between: [A, B], loss_table: [[0.5, 0.9, 0.9, 0, 0]]", "gear.yaml:5:", "increase from 0");
  check("between: [A, B], loss_table: [[0, 0.9, 0.9]]", "gear.yaml:5:", "5 entries");
  check("between: [A, B], efficiency: 0.9, loss_table: [[0, 0.9, 0.9, 0, 0]]", "gear.yaml:5:", "exclude each other");
  check("between: [A, B], efficiency: 0.9", "gear.yaml:5:", "friction element 'f'",
        "stops:\n  f: {body: B, min: -1 rad}\n");
  check("between: [A, B], efficiency: 0.9", "gear.yaml:5:", "move rigidly together",
        "  I: {type: ideal-gear, between: [A, B], ratio: 3}\n");
  // Two lossy gears on one body are a two-stage train (analysis/gear_train.hpp, gear_train_test.cpp);
  // a third stage is a located error.
  const std::string two_stages =
      "bodies:\n  A: {inertia: 1}\n  B: {inertia: 2}\n  C: {inertia: 2}\n  D: {inertia: 2}\nlinks:\n"
      "  G: {type: lossy-gear, between: [A, B], efficiency: 0.9}\n  H: {type: lossy-gear, between: [B, C], efficiency: 0.9}\n";
  EXPECT_EQ(errors_of(two_stages), "");
  const std::string three = errors_of(two_stages + "  K: {type: lossy-gear, between: [C, D], efficiency: 0.9}\n");
  EXPECT_NE(three.find("gear.yaml:9:"), std::string::npos) << three;
  EXPECT_NE(three.find("already geared by lossy gear 'H'"), std::string::npos) << three;
  const std::string speeds = errors_of(
      "bodies:\n  A: {inertia: 1, velocity: 3}\n  B: {inertia: 2, velocity: 2}\nlinks:\n"
      "  G: {type: lossy-gear, between: [A, B], ratio: 2, efficiency: 0.9}\n");
  EXPECT_NE(speeds.find("gear.yaml:5:"), std::string::npos) << speeds;
  EXPECT_NE(speeds.find("contradict"), std::string::npos) << speeds;
  const std::string machine = errors_of(std::string("bodies:\n") + test::kCrankSliderBody +
                                        "  B: {inertia: 2}\nlinks:\n  G: {type: lossy-gear, between: [crank, B], "
                                        "efficiency: 0.9}\n");
  EXPECT_NE(machine.find("variable inertia"), std::string::npos) << machine;
}

// Claim: the initial velocity given on one side only sets the other through the gear (v_A = i v_B).
TEST(LossyGearCompile, OneSidedVelocityFollowsTheRatio) {
  const Model m = compile_text("bodies:\n  A: {inertia: 1}\n  B: {inertia: 2, velocity: 3}\nlinks:\n"
                               "  G: {type: lossy-gear, between: [A, B], ratio: 2, efficiency: 0.9}\n");
  ASSERT_EQ(m.lossy_gears.size(), 1u);
  EXPECT_EQ(m.bodies[0].v0, 6.0);
  EXPECT_EQ(m.lossy_gears[0].ratio, 2.0);
}

}  // namespace
}  // namespace machdyn
