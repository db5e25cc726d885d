// Engine defects and comparison rules the random campaign found (issue 27, tests/reference), part E —
// the families signals, mixed, freewheel and planetary: each engine claim is checked against a closed
// form derived in its comment and the reference simulator, on both integrators; each comparison rule
// against a shift of 1e-3 s that it must still catch.
#include "machdyn/analysis/simulate.hpp"

#include <cmath>
#include <cstdint>
#include <numbers>
#include <string>
#include <utility>
#include <gtest/gtest.h>

#include "reference/campaign.hpp"
#include "reference/generator.hpp"
#include "support/events.hpp"
#include "support/support.hpp"

#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

namespace ref = reference;
using test::events_of;

class CampaignDefectsE : public ::testing::TestWithParam<std::string> {};
INSTANTIATE_TEST_SUITE_P(Integrators, CampaignDefectsE, ::testing::Values("dopri5", "bdf"),
                         [](const ::testing::TestParamInfo<std::string>& i) { return i.param; });

/// The engine's run of m on `integrator`, the audit on.
SimulationResult engine(const ref::RefModel& m, const std::string& integrator) {
  Model model = compile_model(parse_yaml_string(ref::to_yaml(m, integrator), "random.yaml"), "random.yaml");
  SimulateOptions so;
  so.check = true;
  return simulate(model, so);
}

/// The root of f in [lo, hi] (f(lo), f(hi) of opposite signs) by bisection to 1e-15 s.
template <class F>
double root(F f, double lo, double hi) {
  const bool neg = f(lo) < 0.0;
  while (hi - lo > 1e-15) {
    const double mid = 0.5 * (lo + hi);
    ((f(mid) < 0.0) == neg ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

/// The first event of `kind` of `element` in the reference's list (nullptr: none).
ref::RefEvent* ref_event(ref::RefResult& r, const std::string& kind, const std::string& element) {
  for (auto& e : r.events)
    if (e.kind == kind && e.element == element) return &e;
  return nullptr;
}

// Claim (campaign `signals` seed 1 model 95): a contact breaking away beside a stuck set that ties
// its body to the ground is no slide at u ≡ 0. b0 (11.2 kg) rests on f0 (F_s = F_k = 13.6 N) and is
// tied by the clutch K3 (μ_s 0.0372, N(t) = 485 (t − 0.0257)/0.2183 N from 0.0257 s) to b1, which f1
// and f2 (F_s 13.5 and 27.3 N) hold; the spring k1 between them is unloaded while both rest. The load
// on b0 is P(t) = −14.1 − 2.02 + 12.7 sin(2π 3.7 t + 2.31) N (the table holds its first value before
// 0.137 s). The set holds b0 while |P| ≤ 13.6 + μ_s N(t) (f0 direct, K3 through b1 to f1, f2, each
// within its limit: the bounded split); b0 breaks away at the root t* of
// −P(t) = 13.6 + μ_s N(t), f0 and K3 together (f0 alone sliding would leave K3 at its limit and b0
// locked to b1: its slide at u ≡ 0). f1 and f2 never move: b1 carries only K3's kinetic force μ_k N
// < 13.5 N. The engine released f0 and f1 at t* — b0 locked through K3 to b1 and f2, so f0 "slid" at
// u̇ = −8.8e-17 against a rounding of 1e-12 |u̇| (the audit's contact.locked_slide).
TEST_P(CampaignDefectsE, AContactBreakingAwayBesideAStuckSetThatLocksItSlidesWithItsClutch) {
  const ref::RefModel m = ref::random_model("signals", 1, 95);
  const SimulationResult r = engine(m, GetParam());
  auto P = [](double t) { return -14.1 - 2.02 + 12.7 * std::sin(2 * std::numbers::pi * 3.7 * t + 2.31); };
  auto N = [](double t) { return 485.0 * (t - 0.0257) / (0.244 - 0.0257); };
  const double t_star = root([&](double t) { return -P(t) - (13.6 + 0.0372 * N(t)); }, 0.0257, 0.05);
  for (const char* c : {"f0", "K3"}) {
    const auto s = events_of(r, c, "slip");
    ASSERT_FALSE(s.empty()) << c;
    EXPECT_NEAR(s[0].t, t_star, 1e-9) << c;
  }
  for (const char* c : {"f1", "f2"}) EXPECT_TRUE(events_of(r, c).empty()) << c;
  const ref::Outcome o = ref::check(m, GetParam());
  EXPECT_FALSE(o.failed()) << ref::to_string(o.kind) << ": " << o.detail;
}

// Claim (campaign `signals` seed 1 model 78, BDF): a contact whose body a stuck clutch ties to one
// stopping at an event stops with it. b1 (5.41 kg) and b2 (7.77 kg) are held together by the clutch
// K3 (its limit ≥ 0.173 (279 − 10.1 − 65.1) N = 35 N, far above what it carries) and slide on f0
// (F_k 26.3 N) and f1 (F_k 26.9 N) from v = −0.196 m/s with b0 (7.25 kg), which a spring-damper
// (c = 10600 N/m, d = 56.6 N·s/m) ties to b1; P0 = 12.8 N pushes b2. With C = b1 + b2 (m_C = 13.18 kg,
// force F = 26.3 + 26.9 + 12.8 = 66 N) and b0 (m_0, no force): the centre of mass moves at
// v_cm = −0.196 + F t/M (M = m_0 + m_C), the relative coordinate r = x_0 − x_C obeys
// μ r'' + d r' + c r = −μ F/m_C (μ = m_0 m_C/M) from rest: r' = R (ω²/ω_d) e^(−ζωt) sin ω_d t,
// R = −μ F/(m_C c), ω = √(c/μ), ζ = d/(2μω), ω_d = ω √(1 − ζ²); v_C = v_cm − (m_0/M) r'. Both
// contacts stop at the root t* of v_C (static limits 29.4 and 41.6 N hold C then). BDF's drift of the
// stuck pair's speeds left f1 out of the contacts at zero speed (u = 1e-13 before the projection,
// 0 after it): f1 kept sliding at u ≡ 0 beside the set that locks it (contact.locked_slide).
TEST_P(CampaignDefectsE, AContactTiedToOneStoppingAtAnEventStopsWithIt) {
  const ref::RefModel m = ref::random_model("signals", 1, 78);
  const SimulationResult r = engine(m, GetParam());
  const double m0 = 7.25, mC = 5.41 + 7.77, M = m0 + mC, F = 26.3 + 26.9 + 12.8, c = 10600, d = 56.6;
  const double mu = m0 * mC / M, R = -mu * F / (mC * c), w = std::sqrt(c / mu), z = d / (2 * mu * w), wd = w * std::sqrt(1 - z * z);
  auto vC = [&](double t) { return -0.196 + F * t / M - (m0 / M) * R * (w * w / wd) * std::exp(-z * w * t) * std::sin(wd * t); };
  const double t_star = root(vC, 0.0, 0.1);
  for (const char* k : {"f0", "f1"}) {
    const auto s = events_of(r, k, "stick");
    ASSERT_FALSE(s.empty()) << k;
    EXPECT_NEAR(s[0].t, t_star, 1e-9) << k;
    EXPECT_TRUE(events_of(r, k, "slip").empty()) << k;
  }
  const ref::Outcome o = ref::check(m, GetParam());
  EXPECT_FALSE(o.failed()) << ref::to_string(o.kind) << ": " << o.detail;
}

// Claim: the stick or reversal of a slide is a zero of u, and states within δv move it by δv/|u̇|.
// A block (1 kg) sliding at v₀ = 1 m/s against F_k = 2 N stops at t = 0.5 s with u̇ = −2 m/s²; its
// tolerance is δv/2, δv = kStateTol · 1 m/s + 1e-9 (5e-6 s), and a stick moved by 1e-3 s is a
// mismatch on both integrators.
TEST_P(CampaignDefectsE, AStickIsComparedWithinTheSpeedToleranceOverItsDeceleration) {
  ref::RefModel m;
  m.bodies = {{"block", 1.0, 0.0, 1.0}};
  ref::Friction f;
  f.kind = ref::Friction::Kind::contact, f.name = "f", f.a = 0, f.b = ref::kGround, f.Fs = 3.0, f.Fk = 2.0;
  m.frictions = {f};
  m.t_end = 1.0, m.dt_out = 0.01;
  ref::RefResult rr = ref::simulate_reference(m);
  ASSERT_TRUE(rr.error.empty()) << rr.error;
  ref::RefEvent* stick = ref_event(rr, "stick", "f");
  ASSERT_NE(stick, nullptr);
  EXPECT_NEAR(stick->t, 0.5, 1e-11);
  const ref::StateTolerances st = ref::state_tolerances(m, rr);
  const double want = st.v[0] / 2.0;
  EXPECT_NEAR(ref::event_tolerance(*stick, st, ref::kEventTol), want, 1e-9 * want);
  const SimulationResult r = engine(m, GetParam());
  EXPECT_EQ(ref::compare_results(m, rr, r).kind, ref::Outcome::Kind::pass);
  stick->t += 1e-3;
  EXPECT_EQ(ref::compare_results(m, rr, r).kind, ref::Outcome::Kind::event_mismatch);
}

// Claim (campaign `signals` seed 1 model 64): a clutch applied (its normal force rising from 0) at
// u = −2.9e-7 m/s, which its spring turns at u̇ = 0.028 m/s² 1e-5 s later: the sign of u there is
// fixed only to the states' tolerance δv (1.4e-5 m/s, u's zero to δv/|u̇| ~ 1e-3 s), so applied
// sliding − with a reversal 1e-5 s later (the reference, BDF) and applied sliding + (dopri5, whose u
// is below its resolution 1e3 (atol + rtol S) = 2.9e-7 m/s: decided at rest) are one motion. The
// reversal is not compared; the states are. A reversal whose tolerance does not reach back to the
// application (its tolerance cut to 1e-6 s) is compared: missing on dopri5, and moved by 1e-3 s on
// both, it is a mismatch.
TEST_P(CampaignDefectsE, AReversalWithinItsToleranceOfTheApplicationIsThatApplicationsDirection) {
  const ref::RefModel m = ref::random_model("signals", 1, 64);
  ref::RefResult rr = ref::simulate_reference(m);
  ASSERT_TRUE(rr.error.empty()) << rr.error;
  const SimulationResult r = engine(m, GetParam());
  const ref::Outcome same = ref::compare_results(m, rr, r);
  EXPECT_EQ(same.kind, ref::Outcome::Kind::pass) << same.detail;
  ref::RefEvent* rev = nullptr;
  for (auto& e : rr.events)
    if (e.kind == "reversal" && e.element == "K0" && e.t > 1.0) rev = &e;
  ASSERT_NE(rev, nullptr);
  const ref::StateTolerances st = ref::state_tolerances(m, rr);
  EXPECT_GT(ref::event_tolerance(*rev, st, ref::kEventTol), 1e-4);
  rev->dt_dv = 0.0;  // a steep reversal: 1e-6 s
  const bool engine_has_it = !events_of(r, "K0", "reversal").empty() && events_of(r, "K0", "reversal").back().t > 1.0;
  EXPECT_EQ(ref::compare_results(m, rr, r).kind, engine_has_it ? ref::Outcome::Kind::pass : ref::Outcome::Kind::event_mismatch);
  rev->t += 1e-3;
  EXPECT_EQ(ref::compare_results(m, rr, r).kind, ref::Outcome::Kind::event_mismatch);
}

// Claim (campaign `planetary` seed 2 model 31, dopri5): a brake applied at the start of its ramp
// (limit 0) on a carrier that should rest exactly (beside a held ring, no load) but drifts to
// 4e-10 N·m of spring load (its states 5e-14 rad, within the error control's atol): it slides for
// 1.7e-10 s and sticks. A slide opened by an application and ended by a stick within the instants'
// resolution tol_t is a phase the comparison cannot see (as slip → stick): not compared, the states
// are. The same pair 1e-3 s apart is compared: a mismatch.
TEST_P(CampaignDefectsE, AnApplicationIntoASlideThatSticksWithinTheResolutionIsNotCompared) {
  const ref::RefModel m = ref::random_model("planetary", 2, 31);
  const ref::RefResult rr = ref::simulate_reference(m);
  ASSERT_TRUE(rr.error.empty()) << rr.error;
  SimulationResult r = engine(m, GetParam());
  EXPECT_EQ(ref::compare_results(m, rr, r).kind, ref::Outcome::Kind::pass);
  // The pair as dopri5 lists it, on both integrators: 1.7e-10 s apart, then 1e-3 s apart.
  for (const double dt : {1.7e-10, 1e-3}) {
    SimulationResult s = r;
    std::erase_if(s.hybrid.events, [](const ModeEvent& e) { return e.element == "B1"; });
    s.hybrid.events.push_back({0.433, "applied", "B1", "released", "slip+"});
    s.hybrid.events.push_back({0.433 + dt, "stick", "B1", "slip+", "stuck"});
    EXPECT_EQ(ref::compare_results(m, rr, s).kind, dt < ref::kEventTol ? ref::Outcome::Kind::pass : ref::Outcome::Kind::event_mismatch) << dt;
  }
}

// Claim (campaign `mixed` seed 2 model 68): a stuck clutch in a loop of stuck elements (K0 beside the
// freewheel F3 and the clutch K1 between the same bodies) whose normal force falls to 0: its share,
// weighted by its limit, falls with it, and the reference locates a breakaway on the zero itself,
// where the clutch opens (`slip` and `released` at one instant); the engine lists `released`. A
// breakaway the release ends within tol_t is not compared; one 1e-3 s before the release is.
TEST_P(CampaignDefectsE, ABreakawayAtTheReleaseItselfIsNotCompared) {
  ref::RefModel m = ref::random_model("mixed", 2, 68);
  m.t_end = 0.45;  // up to the clutch's next application (0.4676 s)
  ref::RefResult rr = ref::simulate_reference(m);
  ASSERT_TRUE(rr.error.empty()) << rr.error;
  const SimulationResult r = engine(m, GetParam());
  const ref::Outcome same = ref::compare_results(m, rr, r);
  EXPECT_EQ(same.kind, ref::Outcome::Kind::pass) << same.detail;
  ref::RefEvent* slip = nullptr;
  for (auto& e : rr.events)
    if (e.kind == "slip" && e.element == "K0" && e.t > 0.3) slip = &e;
  ASSERT_NE(slip, nullptr);
  slip->t -= 1e-3;
  EXPECT_EQ(ref::compare_results(m, rr, r).kind, ref::Outcome::Kind::event_mismatch);
}

// Claim (campaign `mixed` seed 2 model 17): a brake whose application 1 − e^(−t/0.159) and load
// −52.6 t both start from 0: the engine decides it sliding at t = 0 (its initial mode), the
// reference stuck there and sliding 7e-14 s later. An event within tol_t of the start is that
// instant's decision: not compared. The same breakaway at 1e-3 s is compared (a mismatch).
TEST_P(CampaignDefectsE, AnEventWithinTheResolutionOfTheStartIsTheInitialDecision) {
  const ref::RefModel m = ref::random_model("mixed", 2, 17);
  ref::RefResult rr = ref::simulate_reference(m);
  ASSERT_TRUE(rr.error.empty()) << rr.error;
  const SimulationResult r = engine(m, GetParam());
  const ref::Outcome same = ref::compare_results(m, rr, r);
  EXPECT_EQ(same.kind, ref::Outcome::Kind::pass) << same.detail;
  ref::RefEvent* slip = ref_event(rr, "slip", "B2");
  ASSERT_NE(slip, nullptr);
  EXPECT_LT(slip->t, ref::kEventTol);
  slip->t = 1e-3;
  EXPECT_EQ(ref::compare_results(m, rr, r).kind, ref::Outcome::Kind::event_mismatch);
}

// Claim (campaign `mixed` seed 3 model 45): a body bouncing on a stop S3 into a Zeno rest slides on
// f1, and every bounce reverses f1. The rest's instant is known to its tolerance (the bounces below
// δq are rest at that tolerance; docs/hybrid.md), so the last bounces' impacts are not compared, nor
// f1's reversals there: the engine rests one bounce earlier than the reference. A reversal of the
// first bounces (outside that window) moved by 1e-3 s, or f1's stick at the rest moved by 1e-3 s, is a
// mismatch.
TEST_P(CampaignDefectsE, TheReversalsOfAZenoTailsBouncesAreNotCompared) {
  const ref::RefModel m = ref::random_model("mixed", 3, 45);
  const ref::RefResult rr = ref::simulate_reference(m);
  ASSERT_TRUE(rr.error.empty()) << rr.error;
  const SimulationResult r = engine(m, GetParam());
  const ref::Outcome same = ref::compare_results(m, rr, r);
  EXPECT_EQ(same.kind, ref::Outcome::Kind::pass) << same.detail;
  for (const char* kind : {"reversal", "stick"}) {
    SimulationResult s = r;
    for (auto& e : s.hybrid.events)
      if (e.element == "f1" && e.kind == kind) {
        e.t += 1e-3;
        break;
      }
    EXPECT_EQ(ref::compare_results(m, rr, s).kind, ref::Outcome::Kind::event_mismatch) << kind;
  }
}

// Claim (campaign `signals` seed 5 model 22; the reference's rule): at 0.595 s the brake B2 on b0
// breaks away while f0 (b1 to the ground) and f1 (b2 to the ground) are stuck: they tie b1 and b2
// together, so the clutch K3 between b1 and b2 cannot slide (u ≡ 0) — it is stuck with them (the
// decision's rule, docs/hybrid.md). The reference let K3 slide at u ≡ 0 from 0.595 s until f1 broke
// away at 0.6036 s (the states agreed: it moved nothing); it now keeps it stuck as the engine does,
// and K3's slip comes with f1's. Both agree on both integrators.
TEST_P(CampaignDefectsE, TheReferenceKeepsAClutchStuckWhileStuckContactsTieItsBodies) {
  const ref::RefModel m = ref::random_model("signals", 5, 22);
  const ref::RefResult rr = ref::simulate_reference(m);
  ASSERT_TRUE(rr.error.empty()) << rr.error;
  double b2_slip = -1.0, f1_slip = -1.0;
  for (const auto& e : rr.events) {
    if (e.kind == "slip" && e.element == "B2" && e.t > 0.59 && e.t < 0.6) b2_slip = e.t;
    if (e.kind == "slip" && e.element == "f1" && e.t > 0.6 && e.t < 0.61) f1_slip = e.t;
  }
  ASSERT_GT(b2_slip, 0.0);
  ASSERT_GT(f1_slip, 0.0);
  for (const auto& e : rr.events) {
    if (e.element == "K3" && e.kind == "slip") {
      EXPECT_FALSE(e.t >= b2_slip && e.t < f1_slip) << e.t;
    }
  }
  const SimulationResult r = engine(m, GetParam());
  const ref::Outcome o = ref::compare_results(m, rr, r);
  EXPECT_EQ(o.kind, ref::Outcome::Kind::pass) << o.detail;
}

}  // namespace MACHDYN_UNITY_ID
}  // namespace machdyn
