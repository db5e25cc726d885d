// Gravity (`gravity:` + `vertical: up|down`, model/compile.cpp) and the start from static
// equilibrium (`initial: equilibrium`, analysis/equilibrium.hpp): closed forms of free fall, hanging
// masses on springs and ropes, a preloaded gear chain in steady rotation, and the located errors when
// no equilibrium exists. Runs on both integrators.
#include <algorithm>
#include <cmath>
#include <string>
#include <gtest/gtest.h>

#include "machdyn/analysis/equilibrium.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::series;

Model model_of(const std::string& yaml) { return compile_model(parse_yaml_string(yaml, "eq.yaml"), "eq.yaml"); }

std::string error_of(const std::string& yaml, bool run = false) {
  try {
    const Model m = model_of(yaml);
    if (run) (void)static_equilibrium(m);
  } catch (const InputError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no error";
  return "";
}

double max_deviation(const std::vector<double>& s, double value) {
  double d = 0.0;
  for (double x : s) d = std::max(d, std::abs(x - value));
  return d;
}

class Equilibrium : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, Equilibrium, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

// Claim: `vertical: up` gives the body the constant load −m g (named "NAME.weight"), `down` +m g;
// a free body falls as x = −g t²/2 (up) and x = +g t²/2 (down). g defaults to 9.80665 m/s².
TEST_P(Equilibrium, GravityGivesTheWeightOfVerticalBodies) {
  Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies:
  up: {type: translational, mass: 3 kg, vertical: up}
  down: {type: translational, mass: 2 kg, vertical: down}
  flat: {type: translational, mass: 1 kg}
simulation: {t_end: 2 s, dt_out: 0.1 s, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  EXPECT_EQ(m.gravity, 9.81);
  ASSERT_EQ(m.loads.size(), 2u);
  EXPECT_EQ(m.loads[0].name, "up.weight");
  EXPECT_EQ(m.loads[0].value, -3 * 9.81);
  EXPECT_EQ(m.loads[1].value, 2 * 9.81);
  const SimulationResult r = simulate(m);
  EXPECT_NEAR(series(r, "up.position_m").back(), -0.5 * 9.81 * 4, 1e-9);
  EXPECT_NEAR(series(r, "down.position_m").back(), 0.5 * 9.81 * 4, 1e-9);
  EXPECT_EQ(series(r, "flat.position_m").back(), 0.0);
  const Model d = model_of("bodies: {b: {type: translational, mass: 2 kg, vertical: up}}\n");
  EXPECT_EQ(d.gravity, 9.80665);
  EXPECT_EQ(d.loads.at(0).value, -2 * 9.80665);
}

// Claim: gravity input errors are located and listed together: `vertical` on a rotational body, a
// word other than up/down, a gravity of the wrong dimension.
TEST(EquilibriumInput, GravityErrorsAreLocated) {
  const std::string s = error_of(R"(
gravity: 9.81 m/s
bodies:
  wheel: {inertia: 1 kg*m^2, vertical: up}
  load: {type: translational, mass: 1 kg, vertical: sideways}
)");
  EXPECT_NE(s.find("eq.yaml:2:"), std::string::npos) << s;
  EXPECT_NE(s.find("expected an acceleration (m/s^2)"), std::string::npos) << s;
  EXPECT_NE(s.find("eq.yaml:4:"), std::string::npos) << s;
  EXPECT_NE(s.find("a rotational body has none"), std::string::npos) << s;
  EXPECT_NE(s.find("sideways"), std::string::npos) << s;
  // gravity without any vertical body would silently do nothing
  const std::string t = error_of("gravity: 9.81 m/s^2\nbodies: {b: {type: translational, mass: 1 kg}}\n");
  EXPECT_NE(t.find("eq.yaml:1:"), std::string::npos) << t;
  EXPECT_NE(t.find("no body is 'vertical"), std::string::npos) << t;
}

// Claim: a mass m hanging on a spring c from the ground starts at x = −m g / c (the spring carries
// m g) and does not move: over the run |x − x_e| and |v| stay below 1e-9 (m, m/s); the spring's load
// is m g throughout.
TEST_P(Equilibrium, HangingMassOnASpringStartsAtRest) {
  Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies: {load: {type: translational, mass: 1000 kg, vertical: up}}
links: {spring: {type: spring-damper, between: [ground, load], stiffness: 2e6 N/m, damping: 1e3 N*s/m}}
simulation: {t_end: 1 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12, initial: equilibrium}
)");
  m.simulation.integrator = GetParam();
  const double xe = -1000 * 9.81 / 2e6;
  const EquilibriumStart e = static_equilibrium(m);
  EXPECT_NEAR(e.q0[0], xe, 1e-15);
  EXPECT_EQ(e.v0[0], 0.0);
  const SimulationResult r = simulate(m);
  EXPECT_LT(max_deviation(series(r, "load.position_m"), xe), 1e-9);
  EXPECT_LT(max_deviation(series(r, "load.velocity_m_s"), 0.0), 1e-9);
  EXPECT_NEAR(r.links[0].max, 9810, 1e-9 * 9810);
  EXPECT_NEAR(r.links[0].min, 9810, 1e-9 * 9810);
}

// Claim: two masses hang in series, m1 on a rope (c1, slack s) from the ground and m2 on a spring c2
// below m1. Statics: the rope carries (m1 + m2) g, so x1 = −s − (m1 + m2) g / c1, and the spring
// m2 g, so x2 = x1 − m2 g / c2. The start settles the rope's mode (taut, beyond its slack) and the
// run stays there.
TEST_P(Equilibrium, RopeAndSpringChainHangsStretched) {
  Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies:
  m1: {type: translational, mass: 200 kg, vertical: up}
  m2: {type: translational, mass: 800 kg, vertical: up}
links:
  rope: {type: rope, between: [ground, m1], stiffness: 5e6 N/m, slack: 5 mm}
  spring: {type: spring, between: [m1, m2], stiffness: 1e6 N/m}
simulation: {t_end: 0.5 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-13, initial: equilibrium}
)");
  m.simulation.integrator = GetParam();
  const double g = 9.81, x1 = -0.005 - 1000 * g / 5e6, x2 = x1 - 800 * g / 1e6;
  const EquilibriumStart e = static_equilibrium(m);
  EXPECT_NEAR(e.q0[0], x1, 1e-15);
  EXPECT_NEAR(e.q0[1], x2, 1e-15);
  EXPECT_GE(e.iterations, 2);
  const SimulationResult r = simulate(m);
  EXPECT_LT(max_deviation(series(r, "m1.position_m"), x1), 1e-9);
  EXPECT_LT(max_deviation(series(r, "m2.position_m"), x2), 1e-9);
  EXPECT_NEAR(r.links[0].max, 1000 * g, 1e-9 * 1000 * g);
  EXPECT_NEAR(r.links[0].min, 1000 * g, 1e-9 * 1000 * g);
}

// Claim: a load resting on the ground (stop, e = 0) below a slack rope from a free hoist body stays
// where it is: the stop holds it (its weight presses into the ground), the rope stays slack, the free
// hoist body keeps its given position and speed.
TEST(EquilibriumStart, LoadOnTheGroundStaysBelowASlackRope) {
  const Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies:
  hook: {type: translational, mass: 50 kg, position: 0.2 m, velocity: 0.3 m/s}
  load: {type: translational, mass: 1000 kg, vertical: up}
links: {rope: {type: rope, between: [hook, load], stiffness: 1e6 N/m, slack: 0.5 m}}
stops: {ground: {body: load, min: 0 m}}
simulation: {initial: equilibrium}
)");
  const EquilibriumStart e = static_equilibrium(m);
  EXPECT_EQ(e.q0[0], 0.2);
  EXPECT_EQ(e.v0[0], 0.3);
  EXPECT_EQ(e.q0[1], 0.0);
  EXPECT_EQ(e.v0[1], 0.0);
}

// Claim: a free gear chain I1 —(i = 3, c)— I2 driven by M1 = 100 N·m against M2 = −300 N·m is
// balanced (M1 i + M2 = 0) and starts preloaded: the link carries F = −M2 = 300 N·m, so
// δ = φ1/i − φ2 = F/c = 0.03 rad; its rigid motion R = (i, 1) keeps the given position, Rᵀ M q =
// Rᵀ M q0 (I1 i φ1 + I2 φ2 unchanged), and it turns steadily at the given, consistent speeds ω1 = 3 ω2: the link load stays 300 N·m to 1e-9.
TEST_P(Equilibrium, PreloadedGearChainTurnsSteadily) {
  Model m = model_of(R"(
bodies:
  I1: {inertia: 0.5 kg*m^2, position: 0.1, velocity: 30 rad/s}
  I2: {inertia: 4 kg*m^2, velocity: 10 rad/s}
links: {c: {type: spring-damper, between: [I1, I2], ratio: 3, stiffness: 1e4 N*m/rad, damping: 5 N*m*s/rad}}
loads:
  M1: {type: constant, body: I1, value: 100 N*m}
  M2: {type: constant, body: I2, value: -300 N*m}
simulation: {t_end: 1 s, dt_out: 1 ms, rtol: 1e-13, atol: 1e-14, initial: equilibrium}
)");
  // (tight tolerances: the positions grow to 30 rad, and the load c δ = 300 N·m is to hold to 1e-9
  // relative, δ to 3e-11 rad)
  m.simulation.integrator = GetParam();
  const EquilibriumStart e = static_equilibrium(m);
  const double i = 3, I1 = 0.5, I2 = 4;
  EXPECT_NEAR(e.q0[0] / i - e.q0[1], 0.03, 1e-14);
  // Rᵀ M q with R = (i, 1): I1 i φ1 + I2 φ2 is kept.
  EXPECT_NEAR(I1 * i * e.q0[0] + I2 * e.q0[1], I1 * i * 0.1, 1e-13);
  EXPECT_NEAR(e.v0[0], 30, 1e-12);
  EXPECT_NEAR(e.v0[1], 10, 1e-12);
  const SimulationResult r = simulate(m);
  EXPECT_NEAR(r.links[0].max, 300, 1e-9 * 300);
  EXPECT_NEAR(r.links[0].min, 300, 1e-9 * 300);
  EXPECT_LT(max_deviation(series(r, "I2.velocity_rad_s"), 10), 1e-9);
}

// Claim: no equilibrium, located errors: a free group whose loads do not balance (names every body
// of the group and the net load), velocities that contradict a link's ratio (names the body and the
// speed of the rigid motion), and a friction contact whose force at rest the law does not decide.
TEST(EquilibriumInput, NoEquilibriumIsALocatedError) {
  const std::string s = error_of(R"(
bodies:
  a: {inertia: 1}
  b: {inertia: 1, velocity: 2 rad/s}
links: {c: {type: spring, between: [a, b], stiffness: 100}}
loads: {M: {type: constant, body: a, value: 10 N*m}}
simulation: {initial: equilibrium}
)", true);
  EXPECT_NE(s.find("eq.yaml:3:"), std::string::npos) << s;
  EXPECT_NE(s.find("the free group of bodies 'a', 'b'"), std::string::npos) << s;
  EXPECT_NE(s.find("net load 10 N*m"), std::string::npos) << s;
  const std::string v = error_of(R"(
bodies:
  a: {inertia: 1}
  b: {inertia: 1, velocity: 2 rad/s}
links: {c: {type: spring, between: [a, b], stiffness: 100}}
simulation: {initial: equilibrium}
)", true);
  EXPECT_NE(v.find("eq.yaml:4:"), std::string::npos) << v;
  EXPECT_NE(v.find("body 'b' starts at 2 rad/s"), std::string::npos) << v;
  EXPECT_NE(v.find("gives 1 rad/s"), std::string::npos) << v;
  const std::string c = error_of(R"(
bodies: {a: {inertia: 1}}
contacts: {f: {between: [a, ground], static: 10 N*m, kinetic: 8 N*m}}
simulation: {initial: equilibrium}
)", true);
  EXPECT_NE(c.find("eq.yaml:3:"), std::string::npos) << c;
  EXPECT_NE(c.find("contact 'f'"), std::string::npos) << c;
  // a brake applied at t = 0 holds its body, up to its static limit: the rope's pull m g / i =
  // 1000 · 9.81 / 10 = 981 N·m on the drum is more than 500 N·m
  const std::string b = error_of(R"(
gravity: 9.81 m/s^2
bodies:
  drum: {inertia: 50 kg*m^2}
  load: {type: translational, mass: 1000 kg, vertical: up}
links: {rope: {type: spring, between: [drum, load], ratio: 10 rad/m, stiffness: 2e6 N/m}}
brakes: {hold: {body: drum, holding: 500 N*m}}
simulation: {initial: equilibrium}
)", true);
  EXPECT_NE(b.find("eq.yaml:7:"), std::string::npos) << b;
  EXPECT_NE(b.find("brake 'hold' would have to hold 981 N*m, more than its static limit 500 N*m"), std::string::npos) << b;
}

// Claim: a brake that can hold the drum does: the hanging load stretches the rope by m g / c while
// the drum stays at its given angle, and the run stays there (the brake stuck, nothing moves).
TEST_P(Equilibrium, BrakeHoldsTheDrumOfAHangingLoad) {
  Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies:
  drum: {inertia: 50 kg*m^2, position: 0.2 rad}
  load: {type: translational, mass: 1000 kg, vertical: up}
links: {rope: {type: spring, between: [drum, load], ratio: 10 rad/m, stiffness: 2e6 N/m}}
brakes: {hold: {body: drum, holding: 2000 N*m}}
simulation: {t_end: 0.5 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12, initial: equilibrium}
)");
  m.simulation.integrator = GetParam();
  const EquilibriumStart e = static_equilibrium(m);
  EXPECT_EQ(e.q0[0], 0.2);
  const double x = 0.2 / 10 - 1000 * 9.81 / 2e6;  // δ = φ/i − x = m g / c
  EXPECT_NEAR(e.q0[1], x, 1e-15);
  const SimulationResult r = simulate(m);
  EXPECT_LT(max_deviation(series(r, "load.position_m"), x), 1e-9);
  EXPECT_LT(max_deviation(series(r, "drum.position_rad"), 0.2), 1e-12);
}

double max_abs(const std::vector<double>& s) { return max_deviation(s, 0.0); }

// Claim: a self-locking worm gear (η_mf2 = 0) holds a hanging load at rest: the equilibrium pins
// the gear's two sides where they are (stuck: a = 0, elements/lossy_gear.hpp) and K q = f stretches
// the rest. By hand, with the worm wheel at q_w = 0.7/40 (the gear's q_A = i q_B from the motor's
// given angle): the drum's balance F_s = F_r / i_r with the rope's F_r = m g, so the shaft
// [wheel, drum] (δ = q_w − q_d) turns the drum to q_d = q_w − m g/(i_r k_s) and the rope
// (δ = q_d/i_r − x) puts the hook at x = q_d/i_r − m g/c. The run stays at rest.
TEST_P(Equilibrium, SelfLockingWormGearHoldsTheHangingLoad) {
  Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies:
  motor: {inertia: 0.05 kg*m^2, position: 0.7 rad}
  wheel: {inertia: 0.5 kg*m^2}
  drum: {inertia: 2 kg*m^2}
  hook: {type: translational, mass: 500 kg, vertical: up}
links:
  worm: {type: lossy-gear, between: [motor, wheel], ratio: 40, efficiency: 0.45, efficiency_reverse: 0}
  shaft: {type: spring, between: [wheel, drum], stiffness: 1e5 N*m/rad}
  rope: {type: rope, between: [drum, hook], ratio: 5 rad/m, stiffness: 2 MN/m}
simulation: {t_end: 0.2 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-13, initial: equilibrium}
)");
  m.simulation.integrator = GetParam();
  const double W = 500 * 9.81, q_w = 0.7 / 40, q_d = q_w - W / (5 * 1e5), x = q_d / 5 - W / 2e6;
  const EquilibriumStart e = static_equilibrium(m);
  EXPECT_EQ(e.q0[0], 0.7);
  EXPECT_NEAR(e.q0[1], q_w, 1e-15);
  EXPECT_NEAR(e.q0[2], q_d, 1e-12 * std::abs(q_d));
  EXPECT_NEAR(e.q0[3], x, 1e-12 * std::abs(x));
  const SimulationResult r = simulate(m);
  for (const char* v : {"motor.velocity_rad_s", "wheel.velocity_rad_s", "drum.velocity_rad_s", "hook.velocity_m_s"})
    EXPECT_LT(max_abs(series(r, v)), 1e-9) << v;
  EXPECT_LT(max_deviation(series(r, "hook.position_m"), x), 1e-9);
  EXPECT_LT(max_deviation(series(r, "rope.load_N"), W), 1e-6 * W);
}

// Claim: a lossy gear that does not self-lock (η_mf2 = 0.8) cannot hold the hanging load alone, but a
// brake on the motor holds the chain, and the equilibrium is determined: the gear at rest on the verge
// of the motion it would start — the load drives it backward (side b drives), so its torques follow
// that mode's relation at v = 0, X = η_mf2 Y (docs/model-files.md, "initial: equilibrium"). By hand:
// rope (δ = q_d/i_r − x) F_r = m g = 9810 N, x = q_d/i_r − m g/c_r; drum torque T_d = F_r/i_r =
// 981 N·m twists the shaft [gout, drum] by T_d/k_s; the gear (i = 20) passes Y = T_d/i = 49.05 N·m to
// its input side as X = η_mf2 Y = 39.24 N·m, which the coupling [motor, gin] carries with the twist
// X/k_c (q_gin = q_motor − X/k_c) and the brake holds (not the ideal gear's 49.05 N·m). The run stays
// at rest. (The chain is given unstretched: held there, the gear would start backward, the load
// driving it; given with the coupling wound up, it would start forward and rest on that verge, X =
// Y/η_mf1: the direction is the one it would start in from the given positions.)
TEST_P(Equilibrium, BrakeHoldsALossyGearThatDoesNotSelfLock) {
  Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies:
  motor: {inertia: 0.5 kg*m^2, position: 0.1 rad}
  gin: {inertia: 0.1 kg*m^2, position: 0.1 rad}
  gout: {inertia: 5 kg*m^2, position: 0.005 rad}
  drum: {inertia: 50 kg*m^2, position: 0.005 rad}
  load: {type: translational, mass: 1000 kg, vertical: up}
links:
  coupling: {type: spring, between: [motor, gin], stiffness: 1e4 N*m/rad}
  gear: {type: lossy-gear, between: [gin, gout], ratio: 20, efficiency: 0.9, efficiency_reverse: 0.8}
  shaft: {type: spring, between: [gout, drum], stiffness: 1e6 N*m/rad}
  rope: {type: rope, between: [drum, load], ratio: 10 rad/m, stiffness: 2e6 N/m}
brakes: {hold: {body: motor, holding: 100 N*m}}
simulation: {t_end: 0.2 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-13, initial: equilibrium}
)");
  m.simulation.integrator = GetParam();
  const double W = 1000 * 9.81, Td = W / 10, X = 0.8 * Td / 20;
  const double q_gin = 0.1 - X / 1e4, q_gout = q_gin / 20, q_d = q_gout - Td / 1e6, x = q_d / 10 - W / 2e6;
  const EquilibriumStart e = static_equilibrium(m);
  EXPECT_EQ(e.q0[0], 0.1);
  EXPECT_NEAR(e.q0[1], q_gin, 1e-13);
  EXPECT_NEAR(e.q0[2], q_gout, 1e-14);
  EXPECT_NEAR(e.q0[3], q_d, 1e-13);
  EXPECT_NEAR(e.q0[4], x, 1e-14);
  const SimulationResult r = simulate(m);
  EXPECT_LT(max_deviation(series(r, "coupling.load_N_m"), X), 1e-6 * X);
  EXPECT_LT(max_deviation(series(r, "shaft.load_N_m"), Td), 1e-6 * Td);
  EXPECT_LT(max_deviation(series(r, "rope.load_N"), W), 1e-6 * W);
  EXPECT_LT(max_abs(series(r, "load.velocity_m_s")), 1e-6);
  // A brake too weak for the 39.24 N·m the gear passes is a located error naming that reaction.
  const std::string yaml = R"(
gravity: 9.81 m/s^2
bodies:
  motor: {inertia: 0.5 kg*m^2, position: 0.1 rad}
  gin: {inertia: 0.1 kg*m^2, position: 0.1 rad}
  gout: {inertia: 5 kg*m^2, position: 0.005 rad}
  drum: {inertia: 50 kg*m^2, position: 0.005 rad}
  load: {type: translational, mass: 1000 kg, vertical: up}
links:
  coupling: {type: spring, between: [motor, gin], stiffness: 1e4 N*m/rad}
  gear: {type: lossy-gear, between: [gin, gout], ratio: 20, efficiency: 0.9, efficiency_reverse: 0.8}
  shaft: {type: spring, between: [gout, drum], stiffness: 1e6 N*m/rad}
  rope: {type: rope, between: [drum, load], ratio: 10 rad/m, stiffness: 2e6 N/m}
brakes: {hold: {body: motor, holding: 30 N*m}}
simulation: {initial: equilibrium}
)";
  const std::string err = error_of(yaml, true);
  EXPECT_NE(err.find("brake 'hold' would have to hold 39.24 N*m, more than its static limit 30 N*m"), std::string::npos)
      << err;
}

// Claim: a clutch applied at t = 0 ties its two bodies: a brake holds the motor, the clutch the drum
// to it at the given relative angle, and the load hangs (x = q_d/i − m g/c by hand). The clutch carries
// m g / i = 981 N·m. The run stays at rest.
TEST_P(Equilibrium, AppliedClutchTiesItsBodies) {
  Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies:
  motor: {inertia: 0.5 kg*m^2, position: 0.1 rad}
  drum: {inertia: 50 kg*m^2, position: 0.3 rad}
  load: {type: translational, mass: 1000 kg, vertical: up}
links: {rope: {type: spring, between: [drum, load], ratio: 10 rad/m, stiffness: 2e6 N/m}}
brakes: {hold: {body: motor, holding: 2000 N*m}}
clutches: {K: {between: [motor, drum], normal_force: 10 kN, mu_s: 0.5, mu_k: 0.4, radius: 0.3 m}}
simulation: {t_end: 0.2 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-13, initial: equilibrium}
)");
  m.simulation.integrator = GetParam();
  const double x = 0.3 / 10 - 1000 * 9.81 / 2e6;
  const EquilibriumStart e = static_equilibrium(m);
  EXPECT_EQ(e.q0[0], 0.1);
  EXPECT_EQ(e.q0[1], 0.3);
  EXPECT_NEAR(e.q0[2], x, 1e-12 * std::abs(x));
  const SimulationResult r = simulate(m);
  for (const char* v : {"motor.velocity_rad_s", "drum.velocity_rad_s", "load.velocity_m_s"})
    EXPECT_LT(max_abs(series(r, v)), 1e-9) << v;
  EXPECT_LT(max_deviation(series(r, "load.position_m"), x), 1e-9);
}

// Claim: a held element that cannot hold the equilibrium's reaction is a located error naming the
// reaction and the limit: a clutch of 0.5 · 2 kN · 0.3 m = 300 N·m under the 981 N·m the load pulls;
// a lossy gear that is not self-locking (η_mf2 = 0.9) under the same load (F_b = −981 N·m on the
// drum), nothing on the worm (F_a = 0): b drives backward (s = −1), and its start margin
// (elements/lossy_gear.hpp) −s N_s/η_mf2 with N_s = F_a + η_mf2 F_b/i is F_b/i = −24.525 N·m < 0.
TEST(EquilibriumInput, HeldElementsBeyondTheirLimitAreLocatedErrors) {
  const std::string c = error_of(R"(
gravity: 9.81 m/s^2
bodies:
  motor: {inertia: 0.5 kg*m^2}
  drum: {inertia: 50 kg*m^2}
  load: {type: translational, mass: 1000 kg, vertical: up}
links: {rope: {type: spring, between: [drum, load], ratio: 10 rad/m, stiffness: 2e6 N/m}}
brakes: {hold: {body: motor, holding: 2000 N*m}}
clutches: {K: {between: [motor, drum], normal_force: 2 kN, mu_s: 0.5, mu_k: 0.4, radius: 0.3 m}}
simulation: {initial: equilibrium}
)", true);
  EXPECT_NE(c.find("eq.yaml:9:"), std::string::npos) << c;
  EXPECT_NE(c.find("clutch 'K' would have to hold 981 N*m, more than its static limit 300 N*m"), std::string::npos) << c;
  const std::string g = error_of(R"(
gravity: 9.81 m/s^2
bodies:
  motor: {inertia: 0.05 kg*m^2}
  drum: {inertia: 2 kg*m^2}
  load: {type: translational, mass: 1000 kg, vertical: up}
links:
  worm: {type: lossy-gear, between: [motor, drum], ratio: 40, efficiency: 0.45, efficiency_reverse: 0.9}
  rope: {type: spring, between: [drum, load], ratio: 10 rad/m, stiffness: 2e6 N/m}
simulation: {initial: equilibrium}
)", true);
  EXPECT_NE(g.find("eq.yaml:8:"), std::string::npos) << g;
  EXPECT_NE(g.find("lossy gear 'worm' cannot hold at rest"), std::string::npos) << g;
  EXPECT_NE(g.find("-981 N*m on 'drum'"), std::string::npos) << g;
  EXPECT_NE(g.find("by 24.525 N*m"), std::string::npos) << g;
  EXPECT_NE(g.find("would start backward"), std::string::npos) << g;
}

}  // namespace
}  // namespace machdyn
