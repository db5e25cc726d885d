// Impacts decide every mode again (analysis/impact.hpp, analysis/run.cpp), bounces that accumulate
// rest with a warning (elements/contact.hpp Landing), and decisions that must find the consistent
// mode where one exists (a freewheel's drag at rest, a released brake). Regressions of issue 27's
// campaign, each against a closed form derived in its comment, on both integrators.
#include <cmath>
#include <string>
#include <vector>
#include <gtest/gtest.h>

#include "support/support.hpp"

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

class Impact : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, Impact, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

std::vector<ModeEvent> events_of(const SimulationResult& r, const std::string& element) {
  std::vector<ModeEvent> out;
  for (const auto& e : r.hybrid.events)
    if (e.element == element && e.kind != "initial") out.push_back(e);
  return out;
}

// Claim: a block (m = 1 kg, v0 = 1 m/s) sliding on a floor with F_k = F_s = 0.5 N hits an end stop at
// x = 0.1 m with e = 0.5; friction decelerates it before (v = 1 − t/2, x = t − t²/4: the impact at
// t_i = 2 (1 − √0.9), v⁻ = √0.9) and after the rebound (v⁺ = −e v⁻, sliding backwards the friction
// pushes forward: v = v⁺ + (t − t_i)/2 until rest at t_s = t_i + 2|v⁺|, at x = 0.1 − v⁺²). The
// contact reverses at the impact (it was left sliding forward: friction accelerated the block
// backwards to −0.92 m/s at 1 s). Books: friction F_k (0.1 + v⁺²), impact ½ v⁻² (1 − e²), their
// sum ½ m v0².
TEST_P(Impact, ReboundReversesTheSlidingContact) {
  Model m = test::model_text(R"(
bodies: {b: {type: translational, mass: 1, velocity: 1}}
contacts: {W: {between: [b, ground], static: 0.5, kinetic: 0.5}}
stops: {S: {body: b, max: 0.1, restitution: 0.5}}
simulation: {t_end: 1.2, dt_out: 0.001, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const double e = 0.5, t_i = 2.0 * (1.0 - std::sqrt(0.9)), v_in = std::sqrt(0.9), v_out = -e * v_in;
  const double t_s = t_i + 2.0 * std::abs(v_out);
  const auto w = events_of(r, "W");
  ASSERT_EQ(w.size(), 2u);
  EXPECT_EQ(w[0].kind, "reversal");
  EXPECT_NEAR(w[0].t, t_i, 1e-9);
  EXPECT_EQ(w[1].kind, "stick");
  EXPECT_NEAR(w[1].t, t_s, 1e-8);
  const double err = test::max_error(r, "b.velocity_m_s", [&](double t) {
    return t < t_i ? 1.0 - 0.5 * t : t < t_s ? v_out + 0.5 * (t - t_i) : 0.0;
  });
  EXPECT_LT(err, 1e-7);  // the rows beside the two events: the located instants to 1e-9
  EXPECT_NEAR(test::at(r, "b.position_m", 1.2), 0.1 - v_out * v_out, 1e-8);
  const EnergyBalance& E = r.hybrid.energy;
  EXPECT_NEAR(E.friction_loss, 0.5 * (0.1 + v_out * v_out), 1e-8);
  EXPECT_NEAR(E.impact_loss, 0.5 * v_in * v_in * (1 - e * e), 1e-9);
  EXPECT_LT(std::abs(E.residual()), 1e-8);
}

// Claim: b0 drives b1 (1 kg each, 1 m/s) through a freewheel [b0, b1]; b0 hits an end stop (e = 0 at
// x = 0.1 m, t = 0.1 s). The stop's impulse stops b0; the freewheel would have to pull b1 back
// (against its lock) to stop it too, so b1 overruns at 1 m/s: x1(0.5) = 0.5 m. The impact loses b0's
// ½ J only; b1 keeps its ½ J (it vanished from the books before).
TEST_P(Impact, StoppedDriverLetsTheFreewheelsPartnerOverrun) {
  Model m = test::model_text(R"(
bodies:
  b0: {type: translational, mass: 1, velocity: 1}
  b1: {type: translational, mass: 1, velocity: 1}
freewheels: {F: {between: [b0, b1]}}
stops: {S: {body: b0, max: 0.1}}
simulation: {t_end: 0.5, dt_out: 0.001, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const auto f = events_of(r, "F");
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].kind, "slip");
  EXPECT_NEAR(f[0].t, 0.1, 1e-9);
  EXPECT_NEAR(test::at(r, "b1.position_m", 0.5), 0.5, 1e-9);
  EXPECT_NEAR(test::at(r, "b1.velocity_m_s", 0.5), 1.0, 1e-12);
  EXPECT_EQ(test::at(r, "b0.velocity_m_s", 0.5), 0.0);
  const EnergyBalance& E = r.hybrid.energy;
  EXPECT_NEAR(E.impact_loss, 0.5, 1e-9);
  EXPECT_NEAR(E.kinetic_end, 0.5, 1e-9);
  EXPECT_LT(std::abs(E.residual()), 1e-9);
}

// Claim: the same pair with the stop on the driven body b1 (e = 0.5): b0 cannot overtake b1, so the
// freewheel carries the impulse (lock·Λ ≥ 0) and both rebound together with −e v = −0.5 m/s (a
// plastic tie: Λ_F = m0 (1 + e) v). Loss: ½ (m0 + m1) v² (1 − e²) = 0.75 J; the freewheel stays
// locked (no event of its own).
TEST_P(Impact, FreewheelCarriesTheImpulseInItsLockedDirection) {
  Model m = test::model_text(R"(
bodies:
  b0: {type: translational, mass: 1, velocity: 1}
  b1: {type: translational, mass: 1, velocity: 1}
freewheels: {F: {between: [b0, b1]}}
stops: {S: {body: b1, max: 0.1, restitution: 0.5}}
simulation: {t_end: 0.5, dt_out: 0.001, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  EXPECT_TRUE(events_of(r, "F").empty());
  const auto s = events_of(r, "S");
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].kind, "impact");
  for (const char* b : {"b0", "b1"}) {
    EXPECT_NEAR(test::at(r, std::string(b) + ".velocity_m_s", 0.5), -0.5, 1e-12) << b;
    EXPECT_NEAR(test::at(r, std::string(b) + ".position_m", 0.5), 0.1 - 0.5 * 0.4, 1e-9) << b;
  }
  EXPECT_NEAR(r.hybrid.energy.impact_loss, 0.75, 1e-9);
  EXPECT_LT(std::abs(r.hybrid.energy.residual()), 1e-9);
}

// Claim: a backstop with drag D = 10 N ([ground, b]: b moves forward only) on a body at rest under a
// rising forward push P = 20 t N: the drag is the static limit of its free direction, so b stays at
// rest (the backstop carrying P: pushed forward, neither locked nor overrunning was consistent and
// the run stopped with "no consistent stick/slip modes") until P = D at t = 0.5 s; then it overruns
// with m v' = 20 t − 10: v = 10 (t − 0.5)², x = (10/3)(t − 0.5)³.
TEST_P(Impact, BackstopWithDragStaysAtRestUntilThePushReachesTheDrag) {
  Model m = test::model_text(R"(
bodies: {b: {type: translational, mass: 1}}
freewheels: {F: {between: [ground, b], drag: 10}}
loads: {P: {type: ramp, body: b, value: 20, end: 1}}
simulation: {t_end: 1, dt_out: 0.01, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const auto f = events_of(r, "F");
  ASSERT_EQ(f.size(), 1u);
  EXPECT_EQ(f[0].kind, "slip");
  EXPECT_NEAR(f[0].t, 0.5, 1e-9);
  EXPECT_LT(test::max_error(r, "b.velocity_m_s", [](double t) { return t < 0.5 ? 0.0 : 10 * (t - 0.5) * (t - 0.5); }),
            1e-8);
  EXPECT_NEAR(test::at(r, "b.position_m", 1.0), 10.0 / 3.0 * 0.125, 1e-9);
  // It carries the push: stored as (b, ground), its load λ acts on b with −λ, so λ = P = 6 N at 0.3 s.
  EXPECT_NEAR(test::at(r, "F.force_N", 0.3), 6.0, 1e-9);
  EXPECT_LT(std::abs(r.hybrid.energy.residual()), 1e-8);
}

// Claim: a bouncing ball with e = 0.99 (m = 2 kg dropped from 1 m onto a floor at 0 under g = 9.81):
// the flights 2 v_k/g shrink by e and sum to the rest time t1 (1 + e)/(1 − e) = 199 t1, t1 = √(2/g),
// reached after thousands of impacts; the bounces accumulate there (Zeno) and the ball rests with a
// warning — finitely many events (the flights below 1e-10 s are not run), every joule lost in impacts.
TEST_P(Impact, BouncingBallWithHighRestitutionRestsAtTheAccumulationPoint) {
  Model m = test::model_text(R"(
bodies: {ball: {type: translational, mass: 2 kg, position: 1 m}}
stops: {floor: {body: ball, min: 0 m, restitution: 0.99}}
loads: {G: {type: constant, body: ball, value: -19.62 N}}
simulation: {t_end: 100 s, dt_out: 0.5 s, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const double g = 9.81, e = 0.99, t1 = std::sqrt(2.0 / g), t_rest = t1 * (1 + e) / (1 - e);
  const SimulationResult r = simulate(m);
  const auto rest = events_of(r, "floor");
  ASSERT_FALSE(rest.empty());
  EXPECT_EQ(rest.back().kind, "stick");
  // log(1e-10 s / 0.9 s)/log(0.99) ≈ 2300 flights; BDF restarts at order 1 after every one.
  EXPECT_LT(rest.size(), 3000u);
  EXPECT_NEAR(rest.back().t, t_rest, GetParam() == IntegratorChoice::dopri5 ? 1e-6 * t_rest : 1e-4 * t_rest);
  ASSERT_EQ(r.hybrid.warnings.size(), 1u);
  EXPECT_NE(r.hybrid.warnings[0].find("accumulate"), std::string::npos) << r.hybrid.warnings[0];
  EXPECT_EQ(test::at(r, "ball.velocity_m_s", 100.0), 0.0);
  EXPECT_NEAR(r.hybrid.energy.impact_loss, 19.62, 1e-6);
  EXPECT_LT(std::abs(r.hybrid.energy.residual()), 1e-6);
}

// Claim: a body pressed (P = 1 N, m = 1 kg) from rest against a stop 0.01 m away with e = 0.5 hits
// at t1 = √(2·0.01) and its bounces accumulate at t1 (1 + e)/(1 − e) = 3 t1 (the run hung on dopri5
// with impacts 1e-9 s apart: the flights' apex heights fell below the last bits of the position
// 0.01 m). It rests there with a warning and the stop carries P.
TEST_P(Impact, PressedBodyBouncesToRestOnAStopAwayFromZero) {
  Model m = test::model_text(R"(
bodies: {b: {type: translational, mass: 1}}
loads: {P: {type: constant, body: b, value: 1}}
stops: {S: {body: b, max: 0.01, restitution: 0.5}}
simulation: {t_end: 1, dt_out: 0.001, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const auto s = events_of(r, "S");
  ASSERT_FALSE(s.empty());
  EXPECT_EQ(s.back().kind, "stick");
  EXPECT_NEAR(s.back().t, 3.0 * std::sqrt(0.02), GetParam() == IntegratorChoice::dopri5 ? 1e-6 : 1e-4);
  EXPECT_EQ(r.hybrid.warnings.size(), 1u);
  EXPECT_EQ(test::at(r, "b.position_m", 1.0), 0.01);
  EXPECT_NEAR(test::at(r, "S.force_N", 1.0), 1.0, 1e-9);
}

// Claim: a brake released until 0.1 s (application 0) transmits nothing, so before 0.1 s the only
// external force on the pair b0 (1000 kg, braked) – gap link – b1 (4000 kg) is P = 2000 N on b1 and
// the momentum is m0 v0 + m1 v1 = P t (Newton's second law of the pair; the link is internal): b0 is
// dragged along once the gap closes. The released brake used to stay stuck from t = 0 with a share
// of the link's load (2 kN by 0.1 s: its event F_s ∓ λ with F_s = 0 is negative on one side as soon
// as λ ≠ 0, never armed), holding b0.
TEST_P(Impact, ReleasedBrakeDoesNotHoldItsBody) {
  Model m = test::model_text(R"(
bodies:
  b0: {type: translational, mass: 1000}
  b1: {type: translational, mass: 4000}
links:
  l0: {type: spring-damper, between: [b0, b1], stiffness: 1.0e+7, damping: 40000, gap: 0.001, gap_start: 0}
loads: {P: {type: constant, body: b1, value: 2000}}
brakes: {K: {body: b0, holding: 5400, braking: 5000, time: 0.1, ramp: 0.1}}
simulation: {t_end: 0.3, dt_out: 0.0005, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const auto& t = test::series(r, "t_s");
  const auto& v0 = test::series(r, "b0.velocity_m_s");
  const auto& v1 = test::series(r, "b1.velocity_m_s");
  const auto& F = test::series(r, "K.force_N");
  double err = 0.0, force = 0.0;
  for (size_t j = 0; j < t.size() && t[j] < 0.1; ++j) {
    err = std::max(err, std::abs(1000 * v0[j] + 4000 * v1[j] - 2000 * t[j]));
    force = std::max(force, std::abs(F[j]));
  }
  EXPECT_LT(err, 1e-6);  // N·s, of 200 N·s at 0.1 s
  EXPECT_EQ(force, 0.0);
  EXPECT_GT(test::at(r, "b0.velocity_m_s", 0.0995), 0.0);  // dragged along
  EXPECT_LT(std::abs(r.hybrid.energy.residual()), 1e-6);
}

}  // namespace
}  // namespace machdyn
