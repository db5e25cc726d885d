// The quasi-static load at an extreme with a link off its flank (analysis/run.cpp summarize_links,
// analysis/static_loads.hpp): a slack rope, an open gap or a one-sided link off its flank transmits
// nothing at that instant, so it is no coupling of the quasi-static problem — the bodies on its two
// sides accelerate rigidly apart, and its own quasi-static load is 0. Both integrators, against the
// closed forms of the two-mass drive.
#include <cmath>
#include <numbers>
#include <string>
#include <gtest/gtest.h>

#include "support/support.hpp"

#include "machdyn/analysis/simulate.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

class SlackStatic : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, SlackStatic, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

const LinkSummary& link(const SimulationResult& r, const Model& m, const std::string& name) {
  for (size_t k = 0; k < m.links.size(); ++k)
    if (m.links[k].name == name) return r.links[k];
  ADD_FAILURE() << "no link " << name;
  return r.links.front();
}

// A hoist switched on with its rope slack: motor I1 = 2 kg·m², shaft c_s = 10 kN·m/rad, drum
// I2 = 6 kg·m², rope (ratio 5 rad/m, 2 MN/m, 0.5 m of slack) to a 500 kg load on the floor; a motor
// torque M = 100 N·m from t = 0. The rope takes up its slack at drum angle 2.5 rad, i.e. after
// √(2 · 2.5 / (M/(I1 + I2))) = 0.63 s, after the end of the run (0.2 s).
const char* kSlackHoist = R"(gravity: 9.81 m/s^2
bodies:
  motor: {inertia: 2 kg*m^2}
  drum: {inertia: 6 kg*m^2}
  load: {type: translational, mass: 500 kg, vertical: up}
links:
  shaft: {type: spring, between: [motor, drum], stiffness: 10 kN*m/rad}
  rope: {type: rope, between: [drum, load], ratio: 5 rad/m, stiffness: 2 MN/m, slack: 0.5 m}
loads: {M: {type: constant, body: motor, value: 100 N*m}}
stops: {ground: {body: load, min: 0 m}}
simulation: {t_end: 0.2 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
)";

// Claim: while the rope is slack, motor and drum alone are the two-mass drive under a step torque:
// the rigid acceleration is a = M/(I1 + I2), the shaft's quasi-static load I2 a = M I2/(I1 + I2)
// = 75 N·m, and its load M I2/(I1 + I2) (1 − cos ω t), ω = √(c_s (1/I1 + 1/I2)), peaks at twice that
// at t = π/ω: dynamic factor 2 exactly. (Counted as a spring, the slack rope would tie the drum to the
// grounded load and give the quasi-static load M = 100 N·m, factor 1.5.) The slack rope carries 0
// and its quasi-static load at both its extremes is 0.
TEST_P(SlackStatic, SlackRopeIsNoCouplingOfTheQuasiStaticLoad) {
  Model m = test::model_text(kSlackHoist, "slack.yaml");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const double M = 100.0, I1 = 2.0, I2 = 6.0, cs = 1e4;
  const double w = std::sqrt(cs * (1 / I1 + 1 / I2)), F_static = M * I2 / (I1 + I2);
  const LinkSummary& shaft = link(r, m, "shaft");
  const double tol = GetParam() == IntegratorChoice::bdf ? 1e-7 : 1e-9;
  EXPECT_NEAR(shaft.peak, 2 * F_static, tol * F_static);
  EXPECT_NEAR(std::fmod(shaft.t_peak, 2 * std::numbers::pi / w), std::numbers::pi / w, 1e-6);
  EXPECT_NEAR(shaft.static_load, F_static, 1e-9 * F_static);
  EXPECT_NEAR(shaft.dynamic_factor, 2.0, tol);
  const LinkSummary& rope = link(r, m, "rope");
  EXPECT_EQ(rope.max, 0.0);
  EXPECT_EQ(rope.min, 0.0);
  EXPECT_EQ(rope.static_at_min, 0.0);
  EXPECT_EQ(rope.static_at_max, 0.0);
}

// Claim: the same drive through a backlash gap (0.1 rad, starting in its middle, ±0.05 rad) open: the motor alone
// accelerates first (M/I1 = 50 rad/s², the gap closes after √(2 · 0.05 / 50) = 44.7 ms); every extreme
// of the gap link before that has the quasi-static load 0 (it is open), and its minimum — 0, at
// t = 0 while open — keeps static_at_min = 0 instead of the load of a closed shaft.
TEST_P(SlackStatic, OpenGapIsNoCoupling) {
  Model m = test::model_text(R"(bodies:
  motor: {inertia: 2 kg*m^2}
  drum: {inertia: 6 kg*m^2}
links:
  shaft: {type: spring, between: [motor, drum], stiffness: 10 kN*m/rad, gap: 0.1 rad, gap_start: 0.05 rad}
loads: {M: {type: constant, body: motor, value: 100 N*m}}
simulation: {t_end: 0.04 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
)",
                             "gap.yaml");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const LinkSummary& shaft = link(r, m, "shaft");
  EXPECT_EQ(shaft.max, 0.0);
  EXPECT_EQ(shaft.static_at_min, 0.0);
  EXPECT_EQ(shaft.static_at_max, 0.0);
}

}  // namespace
}  // namespace machdyn
