// The quasi-static load at a link's extreme with held elements (analysis/static_loads.hpp): a stuck
// brake, clutch or self-locked lossy gear is a constraint of the quasi-static problem, not a force
// equal to its reaction at the extreme (which holds the dynamic part too); a sliding brake's kinetic
// torque stays a force; a rolling lossy gear keeps its ratio, its reaction following its mode's
// efficiency. Every claim on both integrators, against closed forms or an RK4 in the test.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>
#include <gtest/gtest.h>

#include "support/rk4.hpp"
#include "support/support.hpp"

#include "machdyn/analysis/simulate.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

class HeldStatic : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, HeldStatic, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

SimulationResult run(const std::string& yaml, IntegratorChoice integrator) {
  Model m = test::model_text(yaml, "held.yaml");
  m.simulation.integrator = integrator;
  return simulate(m);
}

const LinkSummary& link(const SimulationResult& r, const Model& m, const std::string& name) {
  for (size_t k = 0; k < m.links.size(); ++k)
    if (m.links[k].name == name) return r.links[k];
  ADD_FAILURE() << "no link " << name;
  return r.links.front();
}

// How many mode changes element `name` had after the start.
int changes(const SimulationResult& r, const std::string& name) {
  return static_cast<int>(std::count_if(r.hybrid.events.begin(), r.hybrid.events.end(), [&](const ModeEvent& e) {
    return e.element == name && e.kind != "initial";
  }));
}

const double g = 9.81, m_hook = 500.0, c_rope = 2e6, i_rope = 5.0;

const char* kBrakeHeld = R"(gravity: 9.81 m/s^2
bodies:
  drum: {type: rotational, inertia: 2 kg*m^2}
  hook: {type: translational, mass: 500 kg, vertical: up}
links:
  rope: {type: rope, between: [drum, hook], ratio: 5 rad/m, stiffness: 2 MN/m}
brakes:
  B: {body: drum, holding: 5 kN*m}
simulation: {t_end: 0.1 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)";

// Claim: a hook (m = 500 kg) dropped on a taut rope at zero load (c = 2 MN/m) from a drum a brake
// holds has the quasi-static rope load m g exactly and the dynamic factor 2.
// Derivation: the brake holds (rope torque ≤ 2 m g / i = 1962 N·m < 5 kN·m), so the drum stays at
// rest and the hook's stretch x obeys m x'' = m g − c x, x(0) = x'(0) = 0: F = c x = m g (1 − cos ωt),
// ω = √(c/m), largest 2 m g at t = π/ω. Quasi-statically the held drum is a support: K q = f gives
// F = m g. (Taken as a force equal to its torque at the extreme, the brake gave 9364 N, factor 1.048.)
TEST_P(HeldStatic, BrakeHeldDrumHasStaticWeightAndFactorTwo) {
  const SimulationResult r = run(kBrakeHeld, GetParam());
  const Model m = test::model_text(kBrakeHeld, "held.yaml");
  const LinkSummary& rope = link(r, m, "rope");
  const double W = m_hook * g, omega = std::sqrt(c_rope / m_hook);
  EXPECT_EQ(changes(r, "B"), 0);  // held throughout
  EXPECT_NEAR(rope.static_at_max, W, 1e-9 * W);
  EXPECT_NEAR(rope.max, 2 * W, 1e-6 * W);
  EXPECT_NEAR(rope.t_max, std::numbers::pi / omega, 1e-6);
  EXPECT_NEAR(rope.dynamic_factor, 2.0, 1e-6);
}

/// A worm hoist: motor (I_a = 0.05 kg·m²) —worm 40:1 with the fields `worm` (efficiencies, bearing
/// friction)— wheel (0.5 kg·m²) —shaft 1e5 N·m/rad— drum (I_d = 2 kg·m²) —rope 5 rad/m, 2 MN/m— hook
/// (500 kg), from rest on an unstretched rope; `rest` follows the links (loads, simulation).
std::string worm_model(const std::string& worm, const std::string& rest) {
  return R"(gravity: 9.81 m/s^2
bodies:
  motor: {type: rotational, inertia: 0.05 kg*m^2}
  wheel: {type: rotational, inertia: 0.5 kg*m^2}
  drum: {type: rotational, inertia: 2 kg*m^2}
  hook: {type: translational, mass: 500 kg, vertical: up}
links:
  worm: {type: lossy-gear, between: [motor, wheel], ratio: 40, )" +
         worm + R"(}
  shaft: {type: spring, between: [wheel, drum], stiffness: 1e5 N*m/rad}
  rope: {type: rope, between: [drum, hook], ratio: 5 rad/m, stiffness: 2 MN/m}
)" + rest;
}

const std::string kWormHeld = worm_model("efficiency: 0.45, efficiency_reverse: 0",
                                         "simulation: {t_end: 0.1 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}\n");

// Claim: behind a self-locking worm gear (η_mf2 = 0) at rest, the same drop gives the rope the
// quasi-static load m g and the shaft from the worm wheel to the drum m g / i_rope = m g R
// (R = 1/i = 0.2 m: the drum's torque balance, shaft torque = rope force · R) = 981 N·m.
// Derivation: stuck, the gear holds both sides at rest (elements/lossy_gear.hpp: a = 0, X = F_a,
// Y = −F_b'; η_mf2 = 0 holds any torque from the wheel), so quasi-statically the wheel is a support:
// K q = f along wheel–shaft–drum–rope–hook. The peaks are checked against an RK4 of the drum and hook
// with the wheel at rest (I_d q_d'' = −k_s q_d − F_r/i, m q_h'' = F_r − m g, F_r = max(0, c (q_d/i − q_h)),
// shaft load −k_s q_d), so each factor is the RK4's peak over the static load above.
// (With the gear left out, as before, the wheel, drum and hook fell as one body: rope 446 N, factor 22.)
TEST_P(HeldStatic, SelfLockedWormGearHoldsLikeASupport) {
  const SimulationResult r = run(kWormHeld, GetParam());
  const Model m = test::model_text(kWormHeld, "held.yaml");
  const double W = m_hook * g, k_s = 1e5, I_d = 2.0;
  // Reference: RK4, h = 1e-6 s, the largest sampled loads.
  using Y = std::array<double, 4>;  // q_d, v_d, q_h, v_h
  auto f = [&](double, const Y& y) {
    const double Fr = std::max(0.0, c_rope * (y[0] / i_rope - y[2]));
    return Y{y[1], (-k_s * y[0] - Fr / i_rope) / I_d, y[3], (Fr - W) / m_hook};
  };
  Y y{0, 0, 0, 0};
  double rope_max = 0.0, shaft_max = 0.0;
  const double h = 1e-6;
  for (int k = 0; k < 100000; ++k) {
    y = test::rk4_step(f, k * h, y, h);
    rope_max = std::max(rope_max, c_rope * (y[0] / i_rope - y[2]));
    shaft_max = std::max(shaft_max, -k_s * y[0]);
  }
  const LinkSummary& rope = link(r, m, "rope");
  const LinkSummary& shaft = link(r, m, "shaft");
  EXPECT_EQ(changes(r, "worm"), 0);  // at rest throughout
  EXPECT_NEAR(rope.static_at_max, W, 1e-9 * W);
  EXPECT_NEAR(shaft.static_at_max, W / i_rope, 1e-9 * W);
  EXPECT_NEAR(rope.max, rope_max, 1e-6 * W);
  EXPECT_NEAR(shaft.max, shaft_max, 1e-6 * W);
  EXPECT_NEAR(rope.dynamic_factor, rope_max / W, 1e-6);
  EXPECT_NEAR(shaft.dynamic_factor, shaft_max / (W / i_rope), 1e-6);
}

// A clutch K (limit 0.5 · 10 kN · 0.1 m = 500 N·m) stuck between A (1 kg·m²) and B (3 kg·m²), a
// spring (1e4 N·m/rad) from B to C (2 kg·m²), a torque T = 100 N·m on A from rest; and the same drive
// with A and B merged into one body AB (4 kg·m²).
const char* kClutched = R"(bodies: {A: {inertia: 1}, B: {inertia: 3}, C: {inertia: 2}}
links: {s: {type: spring, between: [B, C], stiffness: 1e4 N*m/rad}}
clutches: {K: {between: [A, B], normal_force: 10 kN, mu_s: 0.5, mu_k: 0.4, radius: 0.1 m}}
loads: {T: {type: constant, body: A, value: 100 N*m}}
simulation: {t_end: 0.05 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)";
const char* kMerged = R"(bodies: {AB: {inertia: 4}, C: {inertia: 2}}
links: {s: {type: spring, between: [AB, C], stiffness: 1e4 N*m/rad}}
loads: {T: {type: constant, body: AB, value: 100 N*m}}
simulation: {t_end: 0.05 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)";

// Claim: a stuck clutch makes its pair one rigid body for the quasi-static load too: the spring's
// static load and peak equal those of the merged model, and the closed form. Derivation: the pair
// AB (I = 4) and C under T: static F_st = T I_C / (I_AB + I_C) = 100/3 N·m (C's share of the rigid
// acceleration); dynamic F = F_st (1 − cos ωt), ω² = k (1/I_AB + 1/I_C), peak 2 F_st. The clutch holds:
// its torque T − I_A a ≤ 100 N·m < 500 N·m. (As a force equal to its torque at the peak, 91.7 N·m, it
// gave 36.7 N·m.)
TEST_P(HeldStatic, StuckClutchTiesItsBodiesLikeOneBody) {
  const SimulationResult a = run(kClutched, GetParam()), b = run(kMerged, GetParam());
  const double F_st = 100.0 * 2.0 / 6.0;
  ASSERT_EQ(a.links.size(), 1u);
  ASSERT_EQ(b.links.size(), 1u);
  EXPECT_EQ(changes(a, "K"), 0);
  EXPECT_NEAR(a.links[0].static_at_max, F_st, 1e-9 * F_st);
  EXPECT_NEAR(a.links[0].static_at_max, b.links[0].static_at_max, 1e-9 * F_st);
  EXPECT_NEAR(a.links[0].max, 2 * F_st, 1e-6 * F_st);
  EXPECT_NEAR(a.links[0].max, b.links[0].max, 1e-6 * F_st);
  EXPECT_NEAR(a.links[0].dynamic_factor, 2.0, 1e-6);
}

// Claim: a sliding brake's kinetic torque stays a force of the quasi-static problem. A drum
// (1 kg·m²) turning at 100 rad/s with a spring (1e4 N·m/rad) to B (3 kg·m², same speed); a brake on
// the drum slides with M_k = 200 N·m (holding 250). Derivation: while it slides (until ≈ 2 s) the pair
// decelerates rigidly at M_k/4: static spring load −M_k I_B/(I_d + I_B) = −150 N·m; dynamic
// F = −150 (1 − cos ωt), ω² = k (1 + 1/3): least −300 N·m at π/ω, factor 2.
TEST_P(HeldStatic, SlidingBrakeTorqueStaysAForce) {
  const char* yaml = R"(bodies:
  drum: {inertia: 1, velocity: 100 rad/s}
  B: {inertia: 3, velocity: 100 rad/s}
links: {s: {type: spring, between: [drum, B], stiffness: 1e4 N*m/rad}}
brakes: {P: {body: drum, holding: 250 N*m, braking: 200 N*m}}
simulation: {t_end: 0.05 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)";
  const SimulationResult r = run(yaml, GetParam());
  const double omega = std::sqrt(1e4 * (1.0 + 1.0 / 3.0));
  ASSERT_EQ(r.links.size(), 1u);
  EXPECT_EQ(changes(r, "P"), 0);  // sliding throughout
  EXPECT_NEAR(r.links[0].static_at_min, -150.0, 1e-9 * 150.0);
  EXPECT_NEAR(r.links[0].min, -300.0, 1e-6 * 150.0);
  EXPECT_NEAR(r.links[0].t_min, std::numbers::pi / omega, 1e-6);
  EXPECT_NEAR(r.links[0].dynamic_factor, 2.0, 1e-6);
}

// The mode of lossy gear `name` at t: the target of its last event at or before t.
std::string gear_mode_at(const SimulationResult& r, const std::string& name, double t) {
  std::string md;
  for (const ModeEvent& e : r.hybrid.events)
    if (e.element == name && e.t <= t) md = e.to;
  return md;
}

// The worm hoist of worm_model with η_mf1 = 0.9, η_mf2 = 0.8, `M` on the motor and bearing friction
// τ_bf1 = τ_bf2 = `bf`.
std::string worm_hoist(double M, double bf) {
  return worm_model("efficiency: 0.9, efficiency_reverse: 0.8, bearing_friction: " + std::to_string(bf) + " N*m",
                    "loads:\n  M: {type: constant, body: motor, value: " + std::to_string(M) +
                        " N*m}\nsimulation: {t_end: 0.5 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}\n");
}

// The rigid worm hoist's quasi-static loads in a rolling mode of the worm (elements/lossy_gear.hpp).
// In the motor's coordinate (a = motor's acceleration, i = 40, i_r = 5): side b carries the wheel,
// drum and hook as J_b = (0.5 + I_d + m/i_r²)/i² and the hook's weight as F_b' = −(m g / i_r)/i; side a
// has I_a and F_a = M. Eliminating the gear torques X (into the gear from a) and Y (out to b) from
// I_a a = F_a − X, J_b a = F_b' + Y with the mode's relation (MSL's quadrant losses, bearing
// torques τ_bf1 = τ_bf2 = bf, direction s):
//   a drives (lifting, s = +1):   Y = η_mf1 X − s bf      ⇒  (η_mf1 I_a + J_b) a = η_mf1 F_a + F_b' − s bf
//   b drives (lowering, s = −1):  X = η_mf2 (Y + s bf)    ⇒  (I_a + η_mf2 J_b) a = F_a + η_mf2 F_b' − s η_mf2 bf
// The hook accelerates at a_h = a/(i i_r): the rope's static load is m (g + a_h); the drum's balance
// gives the shaft's, I_d a/i + m (g + a_h)/i_r. Returns {rope, shaft}.
std::array<double, 2> rigid_worm_hoist(double M, double bf, bool b_drives) {
  const double I_a = 0.05, I_d = 2.0, i = 40.0, eta1 = 0.9, eta2 = 0.8;
  const double J_b = (0.5 + I_d + m_hook / (i_rope * i_rope)) / (i * i), Fb = -(m_hook * g / i_rope) / i;
  const double a = b_drives ? (M + eta2 * Fb + eta2 * bf) / (I_a + eta2 * J_b) : (eta1 * M + Fb - bf) / (eta1 * I_a + J_b);
  const double a_h = a / (i * i_rope), rope = m_hook * (g + a_h);
  return {rope, I_d * a / i + rope / i_rope};
}

// Claim: a worm hoist lifting (40 N·m on the motor: the worm rolls forward, the motor driving) has
// the rigid system's quasi-static loads at both links' extremes: rope m (g + a_h) = 5390.7 N, shaft
// 1087.9 N·m (rigid_worm_hoist, a drives). (With the rolling gear left out its two sides were
// separate groups: rope 545 N, factor 19.8; shaft 21.8 N·m, factor 100.9.)
/// Runs the worm hoist with motor torque M and bearing friction bf; checks the worm's mode at both
/// links' maxima and their quasi-static loads against rigid_worm_hoist. Returns the rope's summary.
LinkSummary check_worm_hoist(IntegratorChoice method, double M, double bf, bool b_drives, const char* mode) {
  const std::string yaml = worm_hoist(M, bf);
  const SimulationResult r = run(yaml, method);
  const Model m = test::model_text(yaml, "held.yaml");
  const auto [rope_st, shaft_st] = rigid_worm_hoist(M, bf, b_drives);
  const LinkSummary& rope = link(r, m, "rope");
  const LinkSummary& shaft = link(r, m, "shaft");
  EXPECT_EQ(gear_mode_at(r, "worm", rope.t_max), mode);
  EXPECT_EQ(gear_mode_at(r, "worm", shaft.t_max), mode);
  EXPECT_NEAR(rope.static_at_max, rope_st, 1e-9 * rope_st);
  EXPECT_NEAR(shaft.static_at_max, shaft_st, 1e-9 * shaft_st);
  return rope;
}

TEST_P(HeldStatic, RollingWormGearLiftsWithTheForwardEfficiency) {
  const LinkSummary rope = check_worm_hoist(GetParam(), 40.0, 0.0, false, "forward");
  EXPECT_NEAR(rope.dynamic_factor, rope.max / rigid_worm_hoist(40.0, 0.0, false)[0], 1e-9);
}

// Claim: the same hoist with bearing friction 2 N·m lowering its load (no torque on the motor: the
// hook's weight back-drives the worm, rolling backward with side b driving) has the rigid system's
// quasi-static loads with the reverse efficiency and the bearing torque (the gear's constant part):
// rope m (g + a_h) = 4169.5 N, shaft 819.2 N·m (rigid_worm_hoist, b drives).
TEST_P(HeldStatic, RollingWormGearLowersWithTheReverseEfficiency) {
  check_worm_hoist(GetParam(), 0.0, 2.0, true, "backward_b_drives");
}

// Claim: behind a rolling gear the whole chain is one rigid group of the quasi-static load: m0 (1 kg)
// —lossy gear, ratio 1, η_mf1 = 0.9— m1 —springs— … m20 (1 kg each), 100 N on m0. Rolling forward
// with a driving, (η_mf1 I_a + J_b) a = η_mf1 F_a (J_b = 20 kg, no load on b): a = 90/20.9 m/s², and
// spring c_k carries the masses beyond it, static (20 − k) a.
TEST_P(HeldStatic, ChainBehindARollingGearIsOneRigidGroup) {
  std::ostringstream y;
  y << "bodies:\n  m0: {type: translational, mass: 1 kg}\n";
  for (int k = 1; k <= 20; ++k) y << "  m" << k << ": {type: translational, mass: 1 kg}\n";
  y << "links:\n  g: {type: lossy-gear, between: [m0, m1], ratio: 1, efficiency: 0.9, efficiency_reverse: 0.8}\n";
  for (int k = 1; k < 20; ++k) y << "  c" << k << ": {type: spring, between: [m" << k << ", m" << k + 1 << "], stiffness: 1e4 N/m}\n";
  y << "loads: {P: {type: constant, body: m0, value: 100 N}}\nsimulation: {t_end: 0.2 s, dt_out: 1 ms}\n";
  const std::string yaml = y.str();
  const SimulationResult r = run(yaml, GetParam());
  const Model m = test::model_text(yaml, "held.yaml");
  const double a = 0.9 * 100.0 / (0.9 * 1.0 + 20.0);
  for (int k = 1; k < 20; ++k) {
    std::string name = "c";
    name += std::to_string(k);
    const LinkSummary& c = link(r, m, name);
    ASSERT_EQ(gear_mode_at(r, "g", c.t_max), "forward") << k;
    EXPECT_NEAR(c.static_at_max, (20 - k) * a, 1e-9 * 100.0) << k;
  }
}

}  // namespace
}  // namespace machdyn
