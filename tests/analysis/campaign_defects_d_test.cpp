// Engine defects the random campaign found (issue 27, tests/reference), part D — the families
// freewheel, mixed and planetary: each claim is the class of a campaign model, checked against a
// closed form derived in its comment, on both integrators.
#include "machdyn/analysis/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <string>
#include <utility>
#include <gtest/gtest.h>

#include "reference/campaign.hpp"
#include "reference/generator.hpp"
#include "support/campaign_model.hpp"
#include "support/events.hpp"
#include "support/models.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::against_reference;
using test::events_of;
using test::integrator_name;
using test::model_of;
using test::series;

class CampaignDefectsD : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, CampaignDefectsD,
                         ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf), integrator_name);

SimulationResult run(Model m, IntegratorChoice ic) { return simulate(test::with_integrator(std::move(m), ic)); }

// Claim (campaign `mixed` seed 1 model 94): a brake applied on a body at rest logs no event. b2
// (4.99 kg) is tied to b0 (1.64 kg) by a freewheel F2 that a pulse P0 = 24.8 N on b2 presses into its
// lock; b0 is held by brake B1 (47 N, applied over [0, 0.165) and from 0.305 s) or B0 (105·0.793 N,
// over [0.164, 0.304) and from 0.429 s). P0 acts only while a brake holds b0 ([0, 0.0617), [0.166,
// 0.2277), [0.332, 0.3937), [0.498, 0.5597) s), and 24.8 N < 47 N: b0 and b2 never move, so no link
// is ever deflected and b1 never loaded — every body rests at q = 0, v = 0 for the whole run. Both
// brakes are released and applied at rest: their events are their releases only (docs/hybrid.md: a
// brake applied on a body at rest logs none while it holds). The held bodies' speeds carry the
// rounding of their stuck solve (1e-17 … 1e-30 m/s): B1 applied at 0.305 s read that as a slide,
// logged `applied` into slip± and `stick` 1e-13 s later (on bdf with F2 slipping too).
TEST_P(CampaignDefectsD, ABrakeAppliedOnABodyAtRestUpToRoundingLogsNoEvent) {
  const Model m = model_of(R"(
bodies:
  b0: {type: translational, mass: 1.64 kg}
  b1: {type: translational, mass: 7.36 kg}
  b2: {type: translational, mass: 4.99 kg}
links:
  k1: {type: spring-damper, between: [b0, b1], stiffness: 30400 N/m, damping: 55.1 N*s/m}
  k2: {type: spring-damper, between: [b1, b2], stiffness: 2310 N/m, damping: 10 N*s/m}
  k0: {type: spring, between: [ground, b0], stiffness: 15900 N/m}
loads:
  P0: {body: b2, type: pulse, high: 24.8 N, low: 0 N, period: 0.166 s, width: 0.0617 s, start: 0 s}
brakes:
  B0: {body: b0, holding: 105 N, braking: 105 N, application: {type: pulse, high: 0.793, low: 0, period: 0.265 s, width: 0.14 s, start: 0.164 s}}
  B1: {body: b0, holding: 47 N, braking: 47 N, application: {type: pulse, high: 1, low: 0, period: 0.305 s, width: 0.165 s, start: 0 s, count: 2}}
freewheels:
  F2: {between: [b2, b0], drag: 1.26 N}
simulation: {t_end: 0.63 s, dt_out: 0.00315 s, rtol: 1e-10, atol: 1e-12}
)");
  const SimulationResult r = run(m, GetParam());
  for (const char* b : {"B0", "B1"})
    for (const auto& e : events_of(r, b)) EXPECT_EQ(e.kind, "released") << b << " at " << e.t << ": " << e.from << " -> " << e.to;
  EXPECT_EQ(events_of(r, "B1", "released").size(), 2u);
  EXPECT_TRUE(events_of(r, "F2").empty());
  for (const char* c : {"b0.velocity_m_s", "b1.velocity_m_s", "b2.velocity_m_s", "b0.position_m", "b1.position_m", "b2.position_m"})
    for (const double x : series(r, c)) ASSERT_LE(std::abs(x), 1e-12) << c;
}

// Claim (campaign `mixed` seed 1 model 1): an impact on a stop leaves the contacts of a cluster it
// does not touch stuck. b1 (m₁ = 1.02 kg) under P = −37 N hangs between b0 (spring k₁ = 2930 N/m)
// and b2 (spring-damper k₂ = 71 500 N/m, d = 0.354 N·s/m) and lands plastically on a stop at
// x_s = −3.54 mm; b0, b2, b3 (M_c = 2.84 + 6.31 + 2.48 kg) are one rigid cluster: f0, f1 (F_s 33.3 and
// 21.4 N, in parallel between b2 and b3, written in opposite order) and the clutch K2 (μ_s N =
// 65.6 N, b3–b0) hold it (the reference simulator: none of them ever slides before 0.3 s). Until the
// landing, the relative coordinate r = x₁ − x_c obeys μ r'' + d r' + k r = μ P/m₁ with μ = m₁M_c/(m₁ +
// M_c), k = k₁ + k₂, from rest: r = (μP/(m₁k)) [1 − e^(−ζωt)(cos ω_d t + ζω/ω_d sin ω_d t)], ω = √(k/μ),
// ζ = d/(2μω), ω_d = ω√(1 − ζ²); and x₁ = P t²/(2(m₁ + M_c)) + M_c r/(m₁ + M_c). The landing is where
// x₁ = x_s (bisection below). The impact's jump left the stuck pair's u at the rounding of its bodies'
// speeds, which the re-decision after the impact took as a slide started by the jump: f0 and f1
// "slipped" and stuck again 1e-16 s later at every landing (on bdf K2 too).
TEST_P(CampaignDefectsD, AnImpactLeavesTheContactsOfAClusterItDoesNotTouchStuck) {
  const Model m = model_of(R"(
bodies:
  b0: {type: translational, mass: 2.84 kg}
  b1: {type: translational, mass: 1.02 kg}
  b2: {type: translational, mass: 6.31 kg}
  b3: {type: translational, mass: 2.48 kg}
links:
  k1: {type: spring, between: [b0, b1], stiffness: 2930 N/m}
  k2: {type: spring-damper, between: [b1, b2], stiffness: 71500 N/m, damping: 0.354 N*s/m}
  k3: {type: spring, between: [b2, b3], stiffness: 55600 N/m}
loads:
  P0: {body: b1, type: constant, value: -37 N}
contacts:
  f0: {between: [b2, b3], static: 33.3 N, kinetic: 19.9 N}
  f1: {between: [b3, b2], static: 21.4 N, kinetic: 17.8 N}
clutches:
  K2: {between: [b3, b0], normal_force: {type: constant, value: 1430 N}, mu_s: 0.0459, mu_k: 0.0327}
stops:
  S5: {body: b1, min: -0.00354 m, restitution: 0}
simulation: {t_end: 0.3 s, dt_out: 0.0015 s, rtol: 1e-10, atol: 1e-12}
)");
  const SimulationResult r = run(m, GetParam());
  for (const char* c : {"f0", "f1", "K2"}) EXPECT_TRUE(events_of(r, c).empty()) << c << ": " << events_of(r, c).size() << " events";
  const double m1 = 1.02, Mc = 2.84 + 6.31 + 2.48, k = 2930.0 + 71500.0, d = 0.354, P = -37.0, xs = -0.00354;
  const double mu = m1 * Mc / (m1 + Mc), w = std::sqrt(k / mu), z = d / (2 * mu * w), wd = w * std::sqrt(1 - z * z);
  const auto x1 = [&](double t) {
    const double rel = mu * P / (m1 * k) * (1 - std::exp(-z * w * t) * (std::cos(wd * t) + z * w / wd * std::sin(wd * t)));
    return P * t * t / (2 * (m1 + Mc)) + Mc * rel / (m1 + Mc);
  };
  double lo = 0.0, hi = 0.0;
  while (x1(hi) > xs) lo = hi, hi += 1e-4;  // x₁ falls monotonically to the first landing
  for (int i = 0; i < 100; ++i) (x1(0.5 * (lo + hi)) > xs ? lo : hi) = 0.5 * (lo + hi);
  const auto rests = events_of(r, "S5", "stick");
  ASSERT_GE(rests.size(), 1u);
  EXPECT_NEAR(rests[0].t, hi, 1e-9);
  // The cluster moves as one body: its speeds are equal at every row (up to their rounding).
  const auto &v0 = series(r, "b0.velocity_m_s"), &v2 = series(r, "b2.velocity_m_s"), &v3 = series(r, "b3.velocity_m_s");
  for (size_t i = 0; i < v0.size(); ++i) {
    EXPECT_NEAR(v0[i], v2[i], 1e-14) << i;
    EXPECT_NEAR(v2[i], v3[i], 1e-14) << i;
  }
}

// Claim (campaign `mixed` seed 2 model 83), against the reference simulator: a contact that stuck
// contacts beside it lock does not slide. f0 (68.3 N) and f2 (90 N) hold b1 to the ground in
// parallel, a freewheel F3 ties b1 to b0, f1 (μ N(t) with a sine N) holds b0. Where f1 breaks away
// (0.4417 s) f0's share in the bounded split is at its limit at that instant: the decision released
// it, and its slide was consistent at u̇ = 0 only, by rounding — f2 holds u ≡ 0 (the audit's
// contact.locked_slide, exit 3). The reference keeps f0 and f2 stuck and slips f1 and F3.
TEST_P(CampaignDefectsD, AContactThatAStuckParallelOneLocksDoesNotSlide) {
  const reference::Outcome o = against_reference("mixed", 2, 83, GetParam());
  EXPECT_EQ(o.kind, reference::Outcome::Kind::pass) << o.detail;
}

// Claim (campaign `mixed` seed 2 models 54 and 55), against the reference simulator: a clutch K4
// whose sine normal force rises through 0 beside a stuck clutch K5 on the same two bodies is applied
// at rest and stuck silently. At the left limit of that zero its mode is the label it kept while
// released (r = 0 up to rounding): the audit read it as a slide locked by K5 (contact.locked_slide,
// exit 3).
TEST_P(CampaignDefectsD, AClutchReappliedBesideAStuckOneIsNoLockedSlide) {
  for (const std::uint64_t i : {54u, 55u}) {
    const reference::Outcome o = against_reference("mixed", 2, i, GetParam());
    EXPECT_EQ(o.kind, reference::Outcome::Kind::pass) << i << ": " << o.detail;
  }
}

// Claim (campaign `mixed` seed 1 model 28), the reference's rule for an application at rest: every
// body rests (a load of 15.5 N on b2 held by the stuck contacts f1, f2, f0 to the ground) when the
// clutch K4 between b2 and b0 — two bodies the stuck chain ties together — is applied at 0.073 s. At
// rest it holds silently (docs/hybrid.md), so neither side lists an event; the reference read the
// 1e-19 m/s its projection of the stuck chain leaves between b0 and b2 as a motion and listed
// `applied` (every mixed model of that kind failed on both integrators, "engine: nothing").
TEST_P(CampaignDefectsD, AClutchAppliedBetweenBodiesAStuckChainTiesIsAppliedAtRest) {
  const reference::RefResult ref = reference::simulate_reference(reference::random_model("mixed", 1, 28));
  ASSERT_TRUE(ref.error.empty()) << ref.error;
  for (const auto& e : ref.events) EXPECT_NE(e.kind, "applied") << e.element << " at " << e.t;
  const reference::Outcome o = against_reference("mixed", 1, 28, GetParam());
  EXPECT_EQ(o.kind, reference::Outcome::Kind::pass) << o.detail;
}

}  // namespace MACHDYN_UNITY_ID
}  // namespace machdyn
