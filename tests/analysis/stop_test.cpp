// Hard end stops (elements/contact.hpp, FrictionContact::stop): impacts at the closed-form instants
// with the restitution's velocity jump, rest on the stop, the energy books, and the hoisting of a
// grounded load through a slack rope — EN 13001-2's φ2 case, whose peak rope force has the closed
// form m g + v_h √(c m). Every claim on both integrators.
#include <cmath>
#include <numbers>
#include <string>
#include <gtest/gtest.h>

#include "support/support.hpp"

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

Model model_of(const std::string& yaml) { return compile_model(parse_yaml_string(yaml, "stop.yaml"), "stop.yaml"); }

class Stop : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, Stop, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

std::vector<ModeEvent> events_of(const SimulationResult& r, const std::string& kind) {
  std::vector<ModeEvent> out;
  for (const auto& e : r.hybrid.events)
    if (e.kind == kind) out.push_back(e);
  return out;
}

double last(const SimulationResult& r, const std::string& name) {
  for (size_t c = 0; c < r.column_names.size(); ++c)
    if (r.column_names[c] == name) return r.columns[c].back();
  ADD_FAILURE() << "no column " << name;
  return NAN;
}

// Claim: a ball (m = 2 kg) dropped from h = 1 m onto a floor with restitution e = 0.5 under its
// weight m g (g = 9.81 m/s²) hits at t1 = √(2h/g); each rebound leaves with e times the impact speed,
// so impact k + 1 follows after the flight 2 v_k / g, v_1 = e √(2 g h), v_{k+1} = e v_k; the flights
// sum to the rest time t∞ = t1 (1 + e)/(1 − e). At rest the floor carries m g; every joule of m g h is
// lost in the impacts.
TEST_P(Stop, BouncingBallImpactsAndRest) {
  Model m = model_of(R"(
bodies: {ball: {type: translational, mass: 2 kg, position: 1 m}}
stops: {floor: {body: ball, min: 0 m, restitution: 0.5}}
loads: {G: {type: constant, body: ball, value: -19.62 N}}
simulation: {t_end: 2 s, dt_out: 0.01 s, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const double g = 9.81, e = 0.5, t1 = std::sqrt(2.0 / g);
  const SimulationResult r = simulate(m);
  const auto impacts = events_of(r, "impact");
  ASSERT_GE(impacts.size(), 3u);
  double t = t1, v = e * std::sqrt(2.0 * g);
  for (size_t k = 0; k < 3; ++k) {
    EXPECT_NEAR(impacts[k].t, t, 1e-9 * t) << k;
    t += 2.0 * v / g, v *= e;
  }
  const auto rest = events_of(r, "stick");
  ASSERT_EQ(rest.size(), 1u);
  // The rest time sums ~40 flights, the last ones shorter than a microsecond; BDF restarts at order
  // 1 after every impact, so its sum carries more error than DOPRI5's (each flight still to 1e-9).
  EXPECT_NEAR(rest[0].t, t1 * (1 + e) / (1 - e), GetParam() == IntegratorChoice::dopri5 ? 1e-9 : 1e-5);
  EXPECT_EQ(last(r, "ball.position_m"), 0.0);
  EXPECT_EQ(last(r, "ball.velocity_m_s"), 0.0);
  EXPECT_NEAR(std::abs(last(r, "floor.force_N")), 19.62, 1e-9);
  EXPECT_NEAR(r.hybrid.energy.impact_loss, 19.62, 1e-8);
  EXPECT_LT(std::abs(r.hybrid.energy.residual()), 1e-9);
}

// Claim: with e = 0 the first impact ends at rest (a plastic impact at t1 = √(2h/g)).
TEST_P(Stop, PlasticImpactRestsAtOnce) {
  Model m = model_of(R"(
bodies: {ball: {type: translational, mass: 2 kg, position: 1 m}}
stops: {floor: {body: ball, min: 0 m}}
loads: {G: {type: constant, body: ball, value: -19.62 N}}
simulation: {t_end: 1 s, dt_out: 0.01 s, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  EXPECT_TRUE(events_of(r, "impact").empty());
  const auto rest = events_of(r, "stick");
  ASSERT_EQ(rest.size(), 1u);
  EXPECT_NEAR(rest[0].t, std::sqrt(2.0 / 9.81), 1e-9);
}

// Claim (EN 13001-2 φ2, the closed form of crane-standards.md): a drive hoisting at constant speed
// v_h (a body of 1e15 kg moving at v_h: its speed changes by < 1e-11 relative) lifts a load m resting
// on the ground through a slack rope of stiffness c (`type: rope`, slack s0: tension only, taut from
// δ = s0). The rope tightens at t1 = s0/v_h, its force rises as c v_h (t − t1) until it carries the
// weight at t2 = t1 + m g/(c v_h), when the load leaves the ground with zero speed; then
// F = m g + (c v_h/ω) sin ω (t − t2), ω = √(c/m): F_max = m g + v_h √(c m) at t2 + π/(2ω), i.e.
// φ2 = F_max/(m g) = 1 + v_h ω/g.
TEST_P(Stop, HoistingAGroundedLoadGivesPhi2ClosedForm) {
  const double mass = 1000, g = 9.81, c = 1e6, vh = 0.5, s0 = 0.01;
  Model m = model_of(R"(
bodies:
  drive: {type: translational, mass: 1e15 kg, velocity: 0.5 m/s}
  load: {type: translational, mass: 1000 kg}
links:
  rope: {type: rope, between: [drive, load], stiffness: 1e6 N/m, slack: 10 mm}
stops: {ground: {body: load, min: 0 m}}
loads: {weight: {type: constant, body: load, value: -9810 N}}
simulation: {t_end: 0.2 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const double w = std::sqrt(c / mass), t1 = s0 / vh, t2 = t1 + mass * g / (c * vh);
  const double F_max = mass * g + vh * std::sqrt(c * mass);
  const auto lift = events_of(r, "slip");
  ASSERT_EQ(lift.size(), 1u);
  EXPECT_NEAR(lift[0].t, t2, 1e-9 * t2);
  EXPECT_NEAR(r.links[0].max, F_max, 1e-9 * F_max);
  EXPECT_NEAR(r.links[0].t_max, t2 + std::numbers::pi / (2 * w), 1e-6);
  EXPECT_NEAR(r.links[0].max / (mass * g), 1 + vh * w / g, 1e-9);
}

// Claim: a rope carries no compression: thrown up past its slack length, a load hanging on a rope
// from a fixed point flies freely (only its weight acts) until the rope is taut again. Load m = 10 kg
// at the taut position moving up at 3 m/s (rope c = 1e5 N/m, slack 0): it rises for 3/g s and
// returns to the taut position at t = 2·3/g with −3 m/s, where the rope takes over.
TEST_P(Stop, RopeCarriesNoCompression) {
  Model m = model_of(R"(
bodies: {load: {type: translational, mass: 10 kg, velocity: 3 m/s}}
links: {rope: {type: rope, between: [ground, load], stiffness: 1e5 N/m}}
loads: {weight: {type: constant, body: load, value: -98.1 N}}
simulation: {t_end: 0.7 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  std::vector<ModeEvent> ev;
  for (const auto& e : r.hybrid.events)
    if (e.element == "rope" && e.kind != "initial") ev.push_back(e);
  ASSERT_GE(ev.size(), 1u);
  EXPECT_EQ(ev[0].kind, "gap_closed");
  EXPECT_NEAR(ev[0].t, 2 * 3.0 / 9.81, 1e-9);
  // While slack the rope's load is exactly zero; taut it is never negative beyond the event's own
  // resolution (it goes slack where F crosses 0, located on the dense output: the piece ends at the
  // right end of the final bracket, a hair past the crossing).
  const double res = GetParam() == IntegratorChoice::dopri5 ? 1e-12 : 1e-9;
  EXPECT_GE(r.links[0].min, -res * r.links[0].max);
  EXPECT_GT(r.links[0].max, 0.0);
}

// Claim: bad stops and ropes are located input errors, all listed: neither min nor max, a
// restitution outside [0, 1], a body starting beyond its stop, an unknown body, a negative rope
// slack, a gap on a rope.
TEST(StopInput, ErrorsAreLocatedAndListedTogether) {
  try {
    model_of(R"(
bodies: {a: {type: translational, mass: 1, position: -1 m}, b: {type: translational, mass: 1}}
stops:
  none: {body: b}
  bouncy: {body: b, min: -1 m, restitution: 1.5}
  below: {body: a, min: 0 m}
  lost: {body: c, max: 1 m}
links:
  r1: {type: rope, between: [a, b], stiffness: 1e5 N/m, slack: -1 mm}
  r2: {type: rope, between: [a, b], stiffness: 1e5 N/m, gap: 2 mm}
)");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string s = e.what();
    EXPECT_NE(s.find("stop.yaml:4:"), std::string::npos) << s;
    EXPECT_NE(s.find("give one of 'min'"), std::string::npos) << s;
    EXPECT_NE(s.find("must lie in [0, 1]"), std::string::npos) << s;
    EXPECT_NE(s.find("lies beyond the stop"), std::string::npos) << s;
    EXPECT_NE(s.find("unknown body 'c'"), std::string::npos) << s;
    EXPECT_NE(s.find("slack"), std::string::npos) << s;          // a negative slack
    EXPECT_NE(s.find("a rope has no 'gap'"), std::string::npos) << s;
  }
}

}  // namespace
}  // namespace machdyn
