// Engine defects the random campaign found in the families `mixed` and `stop` (issue 27,
// tests/reference), part H: each claim is checked against a closed form derived in its comment or
// the reference simulator, on both integrators.
#include "machdyn/analysis/simulate.hpp"

#include <cmath>
#include <string>
#include <utility>
#include <gtest/gtest.h>

#include "reference/campaign.hpp"
#include "reference/generator.hpp"
#include "reference/reference.hpp"
#include "support/dropped_ball.hpp"
#include "support/events.hpp"
#include "support/models.hpp"
#include "support/support.hpp"

#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::at;
using test::events_of;
using test::dropped_ball;
using test::integrator_name;
using test::integrator_word;
using test::model_of;
namespace ref = reference;

class CampaignDefectsH : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, CampaignDefectsH,
                         ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf), integrator_name);

// The model of the first claim: b1 pushed back by 10 N against a ground contact f1 (F_s = 6 N) and
// a backstop F3 (b1 may move forward only); b2 pushed forward by P2 = 4 t N against a backstop F4
// whose drag is 2 N.
constexpr const char* kBackstopBesideAContact = R"(
bodies:
  b1: {type: translational, mass: 2 kg}
  b2: {type: translational, mass: 3 kg}
loads:
  P1: {body: b1, type: constant, value: -10 N}
  P2: {body: b2, type: ramp, value: 4 N, end: 1 s}
contacts:
  f1: {between: [b1, ground], static: 6 N, kinetic: 5 N}
freewheels:
  F3: {between: [ground, b1], drag: 0 N}
  F4: {between: [ground, b2], drag: 2 N}
simulation: {t_end: 1 s, dt_out: 0.01 s, rtol: 1e-10, atol: 1e-12}
)";

// Claim (campaign `mixed` seed 1 #69, the engine): a friction contact whose body a stuck freewheel
// holds cannot slide — its row is in the span of the stuck rows, u ≡ 0 — so it is stuck with them
// (docs/hybrid.md, step 4). b1 is held by f1 and F3: the split (weights F_s = 6 and 1) would give f1
// 10·6/7 N, beyond its limit, so f1 carries its limit 6 N and F3 the other 4 N, for the whole run.
// F4 holds b2 while P2 ≤ its drag: it overruns at 4 t = 2 N, t* = 0.5 s (its event: the hold rule's
// 1e-9 N allowance, 2.5e-10 s), and then 3 ẍ = 4 t − 2: ẋ = 2 (t − t*)²/3, x = 2 (t − t*)³/9. At t*
// the stuck set {f1, F3, F4} has no split within its bounds (F4 beyond its drag), and the weighted
// share put f1 at 10·6/7 N, overloaded 1.43 against F4's 1.000: f1 was released first and left
// "sliding" at u ≡ 0 beside the backstop that holds b1 (a `slip` of f1 at 0.5 s, its force 5 N and
// F3's 5 N), since the lock test took two-sided rows only.
TEST_P(CampaignDefectsH, AContactBesideAStuckBackstopStaysStuckWhereAnotherFreewheelOverruns) {
  SimulateOptions so;
  so.check = true;
  const SimulationResult r = simulate(test::with_integrator(model_of(kBackstopBesideAContact), GetParam()), so);
  EXPECT_TRUE(events_of(r, "f1").empty());
  EXPECT_TRUE(events_of(r, "F3").empty());
  const auto ev = events_of(r, "F4");
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].kind, "slip");
  EXPECT_NEAR(ev[0].t, 0.5, 1e-9);
  for (double t : {0.25, 0.5, 0.75, 1.0}) {
    EXPECT_NEAR(std::abs(at(r, "f1.force_N", t)), 6.0, 1e-9) << t;
    EXPECT_NEAR(std::abs(at(r, "F3.force_N", t)), 4.0, 1e-9) << t;
    EXPECT_EQ(at(r, "b1.velocity_m_s", t), 0.0) << t;
  }
  for (double t : {0.75, 1.0}) {
    EXPECT_NEAR(at(r, "b2.velocity_m_s", t), 2.0 * std::pow(t - 0.5, 2) / 3.0, 1e-8) << t;
    EXPECT_NEAR(at(r, "b2.position_m", t), 2.0 * std::pow(t - 0.5, 3) / 9.0, 1e-8) << t;
  }
}

// Claim (campaign `mixed` seed 1 #61, #67, the reference): the reference's tie rule likewise takes
// the stuck freewheels and stops as ties — on the model above it lists F4's overrun at 0.5 s and
// nothing of f1 (it slid f1 at u ≡ 0 where stuck freewheels tied its body to the ground), and the
// engine agrees with it by the campaign's rules.
TEST_P(CampaignDefectsH, TheReferenceTiesABodyByItsStuckFreewheelsToo) {
  ref::RefModel rm;
  rm.t_end = 1.0, rm.dt_out = 0.01;
  rm.bodies = {{"b1", 2.0, 0.0, 0.0}, {"b2", 3.0, 0.0, 0.0}};
  ref::Load P1{"P1", 0, {}}, P2{"P2", 1, {}};
  P1.s.kind = ref::Signal::Kind::constant, P1.s.value = -10.0;
  P2.s.kind = ref::Signal::Kind::ramp, P2.s.value = 4.0, P2.s.t0 = 0.0, P2.s.t1 = 1.0;
  rm.loads = {P1, P2};
  ref::Friction f1, F3, F4;
  f1.kind = ref::Friction::Kind::contact, f1.name = "f1", f1.a = 0, f1.b = ref::kGround, f1.Fs = 6.0, f1.Fk = 5.0;
  F3.kind = ref::Friction::Kind::freewheel, F3.name = "F3", F3.a = ref::kGround, F3.b = 0;
  F4.kind = ref::Friction::Kind::freewheel, F4.name = "F4", F4.a = ref::kGround, F4.b = 1, F4.drag = 2.0;
  rm.frictions = {f1, F3, F4};
  const ref::RefResult rr = ref::simulate_reference(rm);
  ASSERT_TRUE(rr.error.empty()) << rr.error;
  ASSERT_EQ(rr.events.size(), 1u);
  EXPECT_EQ(rr.events[0].element, "F4");
  EXPECT_EQ(rr.events[0].kind, "slip");
  EXPECT_NEAR(rr.events[0].t, 0.5, 1e-9);
  const ref::Outcome o = ref::compare(rm, integrator_word(GetParam()), rr);
  EXPECT_EQ(o.kind, ref::Outcome::Kind::pass) << o.detail;
}

// ---- `mixed` seed 1 #52: an unloaded freewheel's mode is a label (tests/reference/campaign.cpp) ----

// Claim (the comparison, campaign `mixed` seed 1 #52, bdf): a backstop without drag (F6) on a body
// the stuck contacts f4, f3, f0 tie to the ground overruns at u = 0 with no load from t = 0. BDF's
// Newton corrections leave that body 1e-20 m/s off rest, its overrun function fires at 6e-5 s and the
// decision sticks it with λ = 0 exactly until it slips with f0 at 5.3 ms; the reference's body
// stays at 0 exactly and lists neither. Stuck with λ = 0 or overrunning at u = 0, a freewheel
// without drag exerts no force on the same velocities: one motion. The engine's phase is checked
// unloaded at every row, and the run agrees by the campaign's rules on both integrators.
TEST_P(CampaignDefectsH, AnUnloadedFreewheelsStuckPhaseIsALabelNotAnEvent) {
  const ref::RefModel rm = ref::random_model("mixed", 1, 52);
  const ref::RefResult rr = ref::simulate_reference(rm);
  ASSERT_TRUE(rr.error.empty()) << rr.error;
  const std::string ic = integrator_word(GetParam());
  SimulateOptions so;
  so.check = true;
  const SimulationResult r = simulate(compile_model(parse_yaml_string(ref::to_yaml(rm, ic), "m52.yaml"), "m52.yaml"), so);
  const auto F6 = events_of(r, "F6");
  for (size_t i = 0; i + 1 < F6.size(); ++i)
    if (F6[i].kind == "stick" && F6[i + 1].kind == "slip" && F6[i].t < 0.06)
      for (int k = 1; 0.003 * k < F6[i + 1].t; ++k) {
        if (0.003 * k > F6[i].t) {
          EXPECT_EQ(at(r, "F6.force_N", 0.003 * k), 0.0) << 0.003 * k;
        }
      }
  const ref::Outcome o = ref::compare_results(rm, rr, r);
  EXPECT_FALSE(o.failed()) << o.detail;
}

/// A block of 1 kg moving forward at 1 m/s over a backstop (no drag) under P = −10 + 20 (t − t₀) N
/// from t₀ (−10 N before).
ref::RefModel block_on_backstop(double t0) {
  ref::RefModel m;
  m.bodies = {{"b", 1.0, 0.0, 1.0}};
  ref::Signal P;
  P.kind = ref::Signal::Kind::ramp, P.before = -10.0, P.value = 10.0, P.t0 = t0, P.t1 = t0 + 1.0;
  m.loads = {{"P", 0, P}};
  ref::Friction F;
  F.kind = ref::Friction::Kind::freewheel, F.name = "F", F.a = ref::kGround, F.b = 0;
  m.frictions = {F};
  m.t_end = 1.0, m.dt_out = 0.01;
  return m;
}

// Claim: a freewheel's stuck phase that carries a load is compared. The block above (t₀ = 0) slows
// as v = 1 − 10 t + 10 t², stops on the backstop at t = (10 − √60)/20 = 0.1127 s (`stick`), is held
// with λ = 10 − 20 t (up to 7.7 N) and overruns where P passes 0, t = 0.5 s (`slip`). The engine's
// run agrees; its block under the ramp 1e-3 s late (t₀ = 1e-3) is a mismatch.
TEST_P(CampaignDefectsH, ALoadedFreewheelsStuckPhaseShiftedByAMillisecondIsStillAMismatch) {
  const ref::RefModel m = block_on_backstop(0.0);
  const ref::RefResult rr = ref::simulate_reference(m);
  ASSERT_TRUE(rr.error.empty()) << rr.error;
  ASSERT_EQ(rr.events.size(), 2u);
  EXPECT_NEAR(rr.events[0].t, (10.0 - std::sqrt(60.0)) / 20.0, 1e-9);
  EXPECT_NEAR(rr.events[1].t, 0.5, 1e-9);
  const std::string ic = integrator_word(GetParam());
  const ref::Outcome same = ref::compare(m, ic, rr);
  EXPECT_FALSE(same.failed()) << same.detail;
  const ref::Outcome late = ref::compare(block_on_backstop(1e-3), ic, rr);
  EXPECT_TRUE(late.failed()) << ref::to_string(late.kind);
}

// ---- `stop` seed 1 #75: beyond the reference's resolution (tests/reference/campaign.hpp) ------------

// Claim (the comparison, campaign `stop` seed 1 #75): six bodies whose b2 hits a plastic stop and b4
// bounces on a stop with e = 0.78 (a Zeno series of ~100 impacts at 0.56–0.66 s, another from
// 0.81 s): each impact multiplies a phase error, so the reference itself at its step h and at h/4
// lists the series' impacts up to 0.02 s apart and its states differ by 1.8e4 state tolerances
// (RK4's error falls 256 times from h to h/4: this is the reference's own error at h). The
// comparison rests on that error being below a tenth of the tolerance; here neither run fixes the
// states to it, so the tightened mismatch is `reference_error` ("unresolved"), no agreement.
TEST_P(CampaignDefectsH, AModelTheReferenceDoesNotResolveIsNotCompared) {
  const ref::RefModel rm = ref::random_model("stop", 1, 75);
  const ref::RefResult rr = ref::simulate_reference(rm);
  ASSERT_TRUE(rr.error.empty()) << rr.error;
  ref::RefOptions fine;
  fine.omega_h /= ref::kTightStep;
  const ref::RefResult r4 = ref::simulate_reference(rm, fine);
  EXPECT_GT(ref::reference_spread(rm, rr, r4), 1e3);
  const std::string ic = integrator_word(GetParam());
  const ref::Outcome tight = ref::tightened(rm, rm, ic);
  ASSERT_EQ(tight.kind, ref::Outcome::Kind::state_mismatch) << tight.detail;
  const ref::Outcome o = ref::unless_unresolved(rm, rr, tight);
  EXPECT_EQ(o.kind, ref::Outcome::Kind::reference_error) << o.detail;
}


// Claim: the rule does not hide a real difference where the reference resolves the model. A ball
// dropped from 1 m (impacts at √(2/g) = 0.4515 s and then every e times the flight before) is
// resolved by the reference (h against h/4 far below the state tolerance); the engine's ball dropped
// so that it lands 1e-3 s later (h' = g (t₁ + 1e-3)²/2) is still a mismatch after tightening, and
// the rule leaves it one.
TEST_P(CampaignDefectsH, AMotionShiftedByAMillisecondIsStillAMismatchWhereTheReferenceResolves) {
  const double g = 9.81, t1 = std::sqrt(2.0 / g), h_shift = 0.5 * g * (t1 + 1e-3) * (t1 + 1e-3);
  const ref::RefModel m = dropped_ball(1.0);
  const ref::RefResult rr = ref::simulate_reference(m);
  ASSERT_TRUE(rr.error.empty()) << rr.error;
  ref::RefOptions fine;
  fine.omega_h /= ref::kTightStep;
  EXPECT_LT(ref::reference_spread(m, rr, ref::simulate_reference(m, fine)), 0.1);
  const std::string ic = integrator_word(GetParam());
  const ref::Outcome tight = ref::tightened(m, dropped_ball(h_shift), ic);
  EXPECT_TRUE(tight.failed()) << ref::to_string(tight.kind);
  const ref::Outcome o = ref::unless_unresolved(m, rr, tight);
  EXPECT_TRUE(o.failed()) << ref::to_string(o.kind) << " " << o.detail;
  // A state mismatch stays one (the rule's own branch, not only an event mismatch passed through).
  const ref::Outcome states{ref::Outcome::Kind::state_mismatch, "ball 1e-3 s late", 0.5};
  EXPECT_EQ(ref::unless_unresolved(m, rr, states).kind, ref::Outcome::Kind::state_mismatch);
}

}  // namespace MACHDYN_UNITY_ID
}  // namespace machdyn
