// What may attach to a body with a prescribed motion (elements/prescribed_motion.hpp): friction to
// the ground (kinematic contacts, elements/contact.hpp), ideal gears that make a group prescribed
// (model/compile_rigid.cpp) and releases. Each claim against a closed form derived in its comment,
// on both integrators; the combinations still refused are located errors.
#include <cmath>
#include <string>
#include <tuple>
#include <utility>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/analysis/extra_outputs.hpp"
#include "machdyn/analysis/linear_analysis.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/elements/linearize.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::max_error;
using test::series;

class PrescribedAttachments : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, PrescribedAttachments,
                         ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf), test::IntegratorName{});

SimulationResult run_with_heat(Model m, IntegratorChoice integrator) {
  m.simulation.integrator = integrator;
  SimulateOptions books;
  books.event_driven = true;  // the energy books too
  return simulate(m, books, output_selection({"heat"}));
}

/// The time of the first event of `kind` on `element` at or after t0 (NaN if none).
double event_time(const SimulationResult& r, const std::string& element, const std::string& kind, double t0) {
  for (const ModeEvent& e : r.hybrid.events)
    if (e.element == element && e.kind == kind && e.t >= t0) return e.t;
  return NAN;
}

// Claim: a conveyor belt (m = 10 kg) driven at a prescribed speed, on a ground contact with kinetic
// level F_k = 20 N (static 30 N) and a constant load L = 5 N on the belt, slides at the prescribed
// speed: the contact's force is F = sign(v) F_k while v ≠ 0 and the source delivers it too. The speed
// table [[0,0],[1,2],[3,2],[5,−2],[6,0],[7,0],[7.5,1]] m/s gives a(t) piecewise constant and
//   R = m a − f,  f = L − F  ⇒  R = m a − L + F
// (the contact puts −F on the belt). At t = 4 the speed passes 0 with a = −2: the contact reverses;
// on [6, 7] the speed is 0 and stays 0: the contact sticks and carries no load of its own (F = 0,
// the source holds the load, R = −L, although the static level 30 N could hold it); at 7 the belt
// leaves rest: the contact slides again. The heat is F_k ∫|v| dt: 20 × (1 + 4 + 1 + 1 + 1 + 0 + 0.25
// + 0.5) = 175 J at 8 s; its power at 2 s is F_k v = 40 W. The energy books balance (source work =
// friction loss + kinetic energy at the end, the load's work included).
TEST_P(PrescribedAttachments, ABrakedConveyorSlidesAtThePrescribedSpeedAndSticksAtRest) {
  const Model m = test::model_text(R"(
bodies:
  belt: {type: translational, mass: 10 kg, motion: {speed: {type: table, unit: m/s,
         points: [[0, 0], [1, 2], [3, 2], [5, -2], [6, 0], [7, 0], [7.5, 1]]}}}
contacts:
  c: {between: [belt, ground], static: 30 N, kinetic: 20 N}
loads:
  L: {type: constant, body: belt, value: 5 N}
simulation: {t_end: 8 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)");
  const SimulationResult r = run_with_heat(m, GetParam());
  struct Phase {
    double t, a, F, mode;
  };
  // Mid-phase rows: a, F and the mode from the table above.
  for (const Phase& p : std::vector<Phase>{{0.5, 2, 20, 1}, {2, 0, 20, 1}, {3.5, -2, 20, 1}, {4.5, -2, -20, -1},
                                           {5.5, 2, -20, -1}, {6.5, 0, 0, 0}, {7.25, 2, 20, 1}, {7.75, 0, 20, 1}}) {
    EXPECT_NEAR(test::at(r, "belt.motion_force_N", p.t), 10 * p.a - 5 + p.F, 1e-9) << p.t;
    EXPECT_NEAR(test::at(r, "c.force_N", p.t), p.F, 1e-9) << p.t;
    EXPECT_EQ(test::at(r, "c.mode", p.t), p.mode) << p.t;
  }
  EXPECT_EQ(test::at(r, "belt.velocity_m_s", 6.5), 0.0);  // exactly at rest while stuck
  EXPECT_NEAR(event_time(r, "c", "reversal", 3.9), 4.0, 1e-9);
  EXPECT_NEAR(event_time(r, "c", "stick", 5.9), 6.0, 1e-9);
  EXPECT_NEAR(event_time(r, "c", "slip", 6.9), 7.0, 1e-9);
  EXPECT_NEAR(series(r, "c.heat_J").back(), 175.0, 1e-6);
  EXPECT_NEAR(test::at(r, "c.heat_power_W", 2.0), 40.0, 1e-9);
  const EnergyBalance& e = r.hybrid.energy;
  EXPECT_NEAR(e.friction_loss, 175.0, 1e-6);
  EXPECT_LT(std::abs(e.residual()), 1e-6 * std::abs(e.source_work) + 1e-9);
}

// Claim: a belt (m = 10 kg) whose prescribed speed v = 1 − cos 2t leaves rest with zero acceleration
// (u = 0, u̇ = 0 at t = 0: decided stuck, then its stuck event u fires as it moves) and touches 0 again
// at t = π without turning back slides forward throughout: F = +F_k = 20 N, R = m a + F =
// 20 sin 2t + 20 at every row off the two instants of rest, and the heat is F_k x(t) =
// 20 (t − sin(2t)/2).
TEST_P(PrescribedAttachments, ASmoothStartFromRestSlides) {
  const Model m = test::model_text(R"(
bodies:
  belt: {type: translational, mass: 10 kg, motion: {speed: {type: expression, expression: '1 - cos(2*t)'}}}
contacts:
  c: {between: [belt, ground], static: 30 N, kinetic: 20 N}
simulation: {t_end: 4 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)");
  const SimulationResult r = run_with_heat(m, GetParam());
  const auto& t = series(r, "t_s");
  const auto& R = series(r, "belt.motion_force_N");
  const auto& md = series(r, "c.mode");
  double worst = 0.0;
  for (size_t i = 0; i < t.size(); ++i) {
    if (t[i] < 1e-3 || std::abs(t[i] - M_PI) < 1e-3) continue;
    worst = std::max(worst, std::abs(R[i] - (20 * std::sin(2 * t[i]) + 20)));
    EXPECT_EQ(md[i], 1.0) << t[i];
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(max_error(r, "c.heat_J", [](double s) { return 20 * (s - std::sin(2 * s) / 2); }), 1e-5);
}

// Claim: an ideal gear (q_motor = 5 q_drum) makes the drum and the prescribed motor one prescribed
// group, whichever comes first in the file: the motor's speed ramps as ω_m = 100 t rad/s (to
// 200 rad/s at 2 s, after the run), so the drum turns as θ_d = θ_m/5 = 10 t². A spring
// c = 200 N·m/rad [drum, fly] (fly: I_f = 0.5, ω² = c/I_f = 400 s⁻²) from rest: θ_f'' + ω² θ_f = ω² 10 t² gives θ_f = 10 t² − (20/ω²)(1 − cos ωt).
// The source's torque at the motor's coordinate closes the group's equation: the reduced inertia
// I_m + I_d/25 = 0.1 + 2/25 = 0.18 kg·m², the drum's loads (−30 N·m and the spring's −F, F =
// c (θ_d − θ_f)) reduced by 1/5:  R = 0.18 · 100 + (30 + F)/5.
TEST_P(PrescribedAttachments, AnIdealGearMakesTheGroupPrescribed) {
  Model m = test::model_text(R"(
bodies:
  drum: {inertia: 2 kg*m^2}
  motor: {inertia: 0.1 kg*m^2, motion: {speed: {type: ramp, value: 200 rad/s, end: 2 s}}}
  fly: {inertia: 0.5 kg*m^2}
links:
  g: {type: ideal-gear, between: [motor, drum], ratio: 5}
  s: {type: spring, between: [drum, fly], stiffness: 200 N*m/rad}
loads:
  hold: {type: constant, body: drum, value: -30 N*m}
simulation: {t_end: 1 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const double w = 20.0;
  auto thd = [](double t) { return 10 * t * t; };
  auto thf = [&](double t) { return 10 * t * t - 20 / (w * w) * (1 - std::cos(w * t)); };
  EXPECT_LT(max_error(r, "drum.position_rad", thd), 1e-9);
  EXPECT_LT(max_error(r, "drum.velocity_rad_s", [](double t) { return 20 * t; }), 1e-9);
  EXPECT_LT(max_error(r, "fly.position_rad", thf), GetParam() == IntegratorChoice::bdf ? 1e-6 : 1e-8);
  EXPECT_LT(max_error(r, "motor.motion_torque_N_m", [&](double t) { return 18 + (30 + 200 * (thd(t) - thf(t))) / 5; }),
            GetParam() == IntegratorChoice::bdf ? 1e-3 : 1e-5);
}

// Claim: a release on a prescribed body (m = 10 kg, a = 2 m/s² from rest, x_d = t²) lowers the mass
// its source drives: 4 kg leave at t_r = 0.5 s, so R drops by m_released · a = 8 N there. With a
// spring c = 100 N/m to a free mass m2 = 1 kg (ω = 10 rad/s) from rest, x2'' + ω² x2 = ω² t² gives
// x2 = t² − (2/ω²)(1 − cos ωt), and R = m(t) a + c (x_d − x2), m(t) = 10 before t_r, 6 after.
// The released part carries ½ · 4 · v(t_r)² = ½ · 4 · 1² = 2 J away (the energy books).
TEST_P(PrescribedAttachments, AReleaseLowersTheDrivenMass) {
  Model m = test::model_text(R"(
bodies:
  hook: {type: translational, mass: 10 kg, motion: {acceleration: 2 m/s^2}}
  m2: {type: translational, mass: 1 kg}
links:
  s: {type: spring, between: [hook, m2], stiffness: 100 N/m}
releases:
  drop: {body: hook, mass: 4 kg, time: 0.5 s}
simulation: {t_end: 1 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  SimulateOptions books;
  books.event_driven = true;
  const SimulationResult r = simulate(m, books);
  auto x2 = [](double t) { return t * t - 0.02 * (1 - std::cos(10 * t)); };
  auto R = [&](double t) { return (t < 0.5 ? 10.0 : 6.0) * 2 + 100 * (t * t - x2(t)); };
  const auto& t = series(r, "t_s");
  const auto& col = series(r, "hook.motion_force_N");
  double worst = 0.0;
  for (size_t i = 0; i < t.size(); ++i)
    if (std::abs(t[i] - 0.5) > 1e-9) worst = std::max(worst, std::abs(col[i] - R(t[i])));
  EXPECT_LT(worst, GetParam() == IntegratorChoice::bdf ? 1e-4 : 1e-6);
  // The jump itself: the rows beside t_r differ by −8 N plus the spring's change over 2 ms.
  const double jump = test::at(r, "hook.motion_force_N", 0.501) - test::at(r, "hook.motion_force_N", 0.499);
  EXPECT_NEAR(jump, R(0.501) - R(0.499), GetParam() == IntegratorChoice::bdf ? 1e-4 : 1e-6);
  EXPECT_NEAR(R(0.501) - R(0.499), -8.0, 0.2);  // the closed form's jump is m_released · a
  EXPECT_NEAR(r.hybrid.energy.released_kinetic, 2.0, 1e-9);
  EXPECT_LT(max_error(r, "m2.position_m", x2), GetParam() == IntegratorChoice::bdf ? 1e-6 : 1e-8);
}

// Claim: a clutch between two prescribed bodies (a: 2 kg at v_a = 1 m/s; b: 3 kg, v_b = t m/s, so
// u = 1 − t) slides with F = sign(u) F_k, F_k = 4 N: +4 before t = 1 s, −4 after (a reversal at
// u̇ = −1, located at 1 s). The clutch puts −F on a and +F on b, so the sources deliver
// R_a = m_a · 0 + F and R_b = m_b · 1 − F: (4, −1) before 1 s and (−4, 7) after. Its heat is
// F_k ∫|u| dt = 4 (½ + ½) = 4 J at 2 s.
TEST_P(PrescribedAttachments, AClutchBetweenTwoPrescribedBodiesSlidesAtTheirRelativeSpeed) {
  const Model m = test::model_text(R"(
bodies:
  a: {type: translational, mass: 2 kg, motion: {speed: 1 m/s}}
  b: {type: translational, mass: 3 kg, motion: {acceleration: 1 m/s^2}}
contacts:
  k: {between: [a, b], static: 6 N, kinetic: 4 N}
simulation: {t_end: 2 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)");
  const SimulationResult r = run_with_heat(m, GetParam());
  for (const auto& [t, Ra, Rb] : std::vector<std::tuple<double, double, double>>{{0.5, 4, -1}, {1.5, -4, 7}}) {
    EXPECT_NEAR(test::at(r, "a.motion_force_N", t), Ra, 1e-9) << t;
    EXPECT_NEAR(test::at(r, "b.motion_force_N", t), Rb, 1e-9) << t;
  }
  EXPECT_NEAR(event_time(r, "k", "reversal", 0.0), 1.0, 1e-9);
  EXPECT_NEAR(series(r, "k.heat_J").back(), 4.0, 1e-6);
}

// Claim: in modes a brake stuck to the ground on a prescribed body adds no constraint of its own
// (the body is already a fixed support): driver – spring c = 400 N/m – mass 1 kg keeps its one
// frequency √(c/m) = 20 rad/s with the one constraint of the prescribed motion.
TEST(PrescribedAttachmentsModes, AStuckBrakeOnAPrescribedBodyAddsNoConstraint) {
  const Model m = test::model_text(R"(
bodies:
  driver: {type: translational, mass: 2 kg, motion: {speed: 0 m/s}}
  mass: {type: translational, mass: 1 kg}
links:
  spring: {type: spring, between: [driver, mass], stiffness: 400 N/m}
contacts:
  brake: {between: [driver, ground], static: 30 N, kinetic: 20 N}
)");
  const TopologyModes tm = analyse_topology(m, initial_topology(m));
  ASSERT_EQ(tm.modes.omega.size(), 1);
  EXPECT_NEAR(tm.modes.omega(0), 20.0, 1e-9);
  EXPECT_EQ(tm.modes.constraints, 1);
  EXPECT_EQ(tm.modes.rigid_body_modes, 0);
}

// Claim: the combinations still refused are located errors naming the elements: a freewheel or end
// stop to the ground on a prescribed body, two prescribed bodies in one ideal-gear group, a lossy
// gear prescribed on both sides (directly, or on a body an ideal gear ties to a prescribed one).
TEST(PrescribedAttachmentsCompile, RefusedCombinationsAreLocatedErrors) {
  struct Case {
    const char* yaml;
    const char* expect;
  };
  const std::vector<Case> cases = {
      {"bodies:\n  b: {inertia: 1, motion: {speed: 2 rad/s}}\nfreewheels:\n  fw: {between: [b, ground]}\n",
       "freewheel or end stop"},
      {"bodies:\n  a: {inertia: 1, motion: {speed: 2 rad/s}}\n  b: {inertia: 1, motion: {speed: 1 rad/s}}\n"
       "links:\n  g: {type: ideal-gear, between: [a, b], ratio: 2}\n", "one motion only"},
      {"bodies:\n  a: {inertia: 1, motion: {speed: 2 rad/s}}\n  b: {inertia: 1, motion: {speed: 1 rad/s}}\n"
       "links:\n  lg: {type: lossy-gear, between: [a, b], ratio: 2, efficiency: 0.9}\n", "lossy gear 'lg': both"},
      {"bodies:\n  a: {inertia: 1, motion: {speed: 2 rad/s}}\n  b: {inertia: 1}\n  c: {inertia: 1, motion: {speed: 0.5 rad/s}}\n"
       "links:\n  g: {type: ideal-gear, between: [a, b], ratio: 2}\n"
       "  lg: {type: lossy-gear, between: [b, c], ratio: 2, efficiency: 0.9}\n", "lossy gear 'lg': both"},
      {"bodies:\n  a: {inertia: 1, motion: {speed: 2 rad/s}}\n  b: {inertia: 1, velocity: 3 rad/s}\n"
       "links:\n  g: {type: ideal-gear, between: [a, b], ratio: 2}\n", "contradicts"},
  };
  for (const Case& c : cases) {
    const std::string e = test::compile_errors(c.yaml);
    EXPECT_NE(e.find(c.expect), std::string::npos) << c.yaml << "\n→ " << e;
    EXPECT_NE(e.find("test.yaml:"), std::string::npos) << e;
    EXPECT_EQ(e.find("test.yaml:0:"), std::string::npos) << e;  // a real place, not the file alone
  }
}

}  // namespace
}  // namespace machdyn
