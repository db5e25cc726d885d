// Engine defects the random campaign found (issue 27, tests/reference): each claim is the class of a
// shrunk campaign model, checked against a closed form derived in its comment, on both integrators.
#include "machdyn/analysis/simulate.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <utility>
#include <gtest/gtest.h>

#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "support/models.hpp"
#include "support/events.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::model_of;
using test::integrator_name;

using test::at;
using test::events_of;
using test::series;


class CampaignDefects : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, CampaignDefects,
                         ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf), integrator_name);

SimulationResult run(Model m, IntegratorChoice ic) { return simulate(test::with_integrator(std::move(m), ic)); }

// Claim: a free body of 1 kg at rest under a force step 0 → 1 N at t = 0.5 s stays exactly at rest up
// to the step and then moves as x = ½ (t − 0.5)², v = t − 0.5. A step of the integrator that ends on
// the breakpoint sees the load's left limit there (0 N): the value after the jump on its last stage
// (dopri5's c = 1, BDF's implicit end point) used to start the body moving before the step, an error
// of O(h ΔF/m) in the state the next piece starts from (campaign: a brake applied at a step on a body
// at rest set it sliding at 1e-11 m/s and logged `applied` + `stick` 2e-12 s apart).
TEST_P(CampaignDefects, AStepLoadActsFromItsBreakpointOnly) {
  const Model m = model_of(R"(
bodies: {m: {type: translational, mass: 1 kg}}
loads: {P: {type: step, body: m, value: 1 N, before: 0 N, time: 0.5 s}}
contacts: {c: {between: [m, ground], static: 2 N, kinetic: 0 N}}
simulation: {t_end: 1 s, dt_out: 0.25 s, rtol: 1e-10, atol: 1e-12}
)");
  // With the contact (F_s = 2 N > 1 N) the body stays stuck: the step must not move it at all.
  const SimulationResult r = run(m, GetParam());
  EXPECT_EQ(at(r, "m.velocity_m_s", 0.5), 0.0);
  EXPECT_EQ(at(r, "m.position_m", 1.0), 0.0);
  EXPECT_EQ(events_of(r, "c").size(), 0u);  // no event after the initial mode
  // Without it: x(1) = ½ 0.5² = 0.125 m, v(1) = 0.5 m/s; exactly at rest at the step.
  const SimulationResult f = run(model_of(R"(
bodies: {m: {type: translational, mass: 1 kg}}
loads: {P: {type: step, body: m, value: 1 N, before: 0 N, time: 0.5 s}}
simulation: {t_end: 1 s, dt_out: 0.25 s, rtol: 1e-10, atol: 1e-12}
)"),
                                 GetParam());
  EXPECT_EQ(at(f, "m.velocity_m_s", 0.5), 0.0);
  EXPECT_EQ(at(f, "m.position_m", 0.5), 0.0);
  EXPECT_NEAR(at(f, "m.position_m", 1.0), 0.125, 1e-9);
  EXPECT_NEAR(at(f, "m.velocity_m_s", 1.0), 0.5, 1e-9);
}

// Claim: a brake applied (a step at 0.3 s) on a body at rest holds it silently — no event: the brake
// rests as its body did (docs/hybrid.md: applied at u = 0 it is decided with the others, stuck without
// an event, or an `applied` event into its slide). A load step of 15 N at 0.6 s beyond its holding
// force 10 N starts the slide there: one `slip` at 0.6 s, then m v' = 15 − 8 (braking 8 N), so
// v(1) = 7/2 · 0.4 = 1.4 m/s.
TEST_P(CampaignDefects, ABrakeAppliedOnABodyAtRestHoldsItWithoutAnEvent) {
  const Model m = model_of(R"(
bodies: {m: {type: translational, mass: 2 kg}}
loads: {P: {type: step, body: m, value: 15 N, before: 0 N, time: 0.6 s}}
brakes: {B: {body: m, holding: 10 N, braking: 8 N, time: 0.3 s}}
simulation: {t_end: 1 s, dt_out: 0.01 s, rtol: 1e-10, atol: 1e-12}
)");
  const SimulationResult r = run(m, GetParam());
  const auto ev = events_of(r, "B");
  ASSERT_EQ(ev.size(), 1u);  // after the initial `released`: the slip at the load step only
  EXPECT_EQ(ev[0].kind, "slip");
  EXPECT_EQ(ev[0].from, "stuck");
  EXPECT_DOUBLE_EQ(ev[0].t, 0.6);
  EXPECT_EQ(at(r, "m.velocity_m_s", 0.6), 0.0);
  EXPECT_NEAR(at(r, "m.velocity_m_s", 1.0), 1.4, 1e-9);
}

// Claim: two brakes on one body, ramped at different rates (B1: 10 N over 1 s, F_s1 = 10 t; B2: 10 N
// over 0.1 s, F_s2 = min(100 t, 10)), hold it against a ramp load F = 24 t while F ≤ F_s1 + F_s2: the
// load locked by both is shared by their limits at the instant (docs/hybrid.md), so both break away
// together at 24 t* = 10 t* + 10, t* = 5/7 s. Then m v' = 24 t − 5 t − 10 (kinetic 5 t and 10 N):
// v(1) = 9.5 (1 − t*²) − 10 (1 − t*). (Shared by the full limits F_s0 — 12 t each — B1 was overloaded
// from the start, released, and slid at u ≡ 0 beside B2 with its kinetic 5 t: the pair broke away at
// F_s2 + F_k1, 19 t = 10, t = 0.526 s. Campaign: two clutches in parallel, `clutch` seed 1 model 1.)
// Never stuck beyond its limit at the instant.
TEST_P(CampaignDefects, ParallelBrakesRampedAtDifferentRatesShareByTheirLimitsAtTheInstant) {
  const Model m = model_of(R"(
bodies: {m: {type: translational, mass: 1 kg}}
loads: {P: {type: ramp, body: m, value: 48 N, before: 0 N, start: 0 s, end: 2 s}}
brakes:
  B1: {body: m, holding: 10 N, braking: 5 N, time: 0 s, ramp: 1 s}
  B2: {body: m, holding: 10 N, braking: 10 N, time: 0 s, ramp: 0.1 s}
simulation: {t_end: 1 s, dt_out: 0.001 s, rtol: 1e-10, atol: 1e-12}
)");
  const SimulationResult r = run(m, GetParam());
  const double ts = 5.0 / 7.0;
  for (const char* b : {"B1", "B2"}) {
    const auto slips = events_of(r, b, "slip");
    ASSERT_EQ(slips.size(), 1u) << b;
    EXPECT_NEAR(slips[0].t, ts, 1e-9) << b;
  }
  EXPECT_NEAR(at(r, "m.velocity_m_s", 1.0), 9.5 * (1 - ts * ts) - 10 * (1 - ts), 1e-8);
  const auto& t = series(r, "t_s");
  for (const char* b : {"B1", "B2"}) {
    const auto& F = series(r, std::string(b) + ".force_N");
    const auto& md = series(r, std::string(b) + ".mode");
    const double T = std::string(b) == "B1" ? 1.0 : 0.1;
    for (size_t i = 0; i < t.size(); ++i)
      if (md[i] == 0.0) {
        EXPECT_LE(std::abs(F[i]), 10.0 * std::min(1.0, t[i] / T) * (1 + 1e-9) + 1e-12) << b << " " << t[i];
      }
  }
}

// Claim: a clutch applied beside a stuck one on the same pair of moving bodies is decided at rest:
// it sticks silently (no event), the pair moving as one body. a (1 kg, on a spring of 300 N/m to the
// ground) and b (2 kg) start together at 1 m/s with K1 (1000 N) holding them: x = (v0/ω) sin ωt,
// ω = √(300/3) = 10 rad/s, and K1 carries b's inertia force 2 ẍ, |λ| ≤ 20 N. K0, ramped from 0.24 s,
// finds u = 0 and holds with it. (On BDF the Newton corrections mixed the states: the stuck pair's
// speeds drifted apart by 1e-17 over a piece, K0 read u ≠ 0 at its application and was set sliding at
// u ≡ 0 beside K1 — the audit's `contact.locked_slide`; campaign `clutch` seed 1 model 44.)
TEST_P(CampaignDefects, AClutchAppliedBesideAStuckOneOnAMovingPairSticksSilently) {
  const Model m = model_of(R"(
bodies:
  a: {type: translational, mass: 1 kg, velocity: 1 m/s}
  b: {type: translational, mass: 2 kg, velocity: 1 m/s}
links: {k: {type: spring, between: [ground, a], stiffness: 300 N/m}}
contacts: {K1: {between: [a, b], static: 1000 N, kinetic: 800 N}}
clutches:
  K0: {between: [b, a], normal_force: {type: ramp, value: 100 N, before: 0 N, start: 0.24 s, end: 0.4 s}, mu_s: 0.5, mu_k: 0.3}
simulation: {t_end: 1 s, dt_out: 0.01 s, rtol: 1e-10, atol: 1e-12}
)");
  const SimulationResult r = run(m, GetParam());
  EXPECT_EQ(events_of(r, "K0").size(), 0u);
  EXPECT_EQ(events_of(r, "K1").size(), 0u);
  for (const double t : {0.3, 0.6, 1.0}) {
    EXPECT_NEAR(at(r, "a.position_m", t), 0.1 * std::sin(10 * t), 1e-8) << t;
    EXPECT_NEAR(at(r, "b.velocity_m_s", t), std::cos(10 * t), 1e-7) << t;
  }
}

// The bounded split of a redundant stuck set (docs/hybrid.md "Redundant locks"): the weighted
// least-norm share, and where it leaves a contact beyond its limit the least-norm share within every
// contact's bounds; a contact slides only when no share within the bounds exists.
void expect_at_rest_and_stuck(const SimulationResult& r, std::initializer_list<const char*> bodies,
                              std::initializer_list<const char*> contacts) {
  for (const char* c : contacts) {
    EXPECT_EQ(events_of(r, c).size(), 0u) << c;
    for (const double md : series(r, std::string(c) + ".mode")) ASSERT_EQ(md, 0.0) << c;
  }
  for (const char* b : bodies)
    for (const double v : series(r, std::string(b) + ".velocity_m_s")) ASSERT_EQ(v, 0.0) << b;
}

// Claim: a brake (holding 10 N) beside a stopped backstop on a body of 1 kg holds it at rest under a
// load P = −30 min(t, 1) N against the backstop: B and S share λ_B + λ_S = P by the least Σ λ²/w²
// (w² = F_s = 10 for B, 1 for S), λ_B = 10 P/11, while |λ_B| ≤ 10 (|P| ≤ 11 N); beyond, the bounded
// split holds B at its limit and the backstop, unbounded in its locking direction, carries the rest:
// λ_B = −10, λ_S = P + 10. (The weighted share gave B 10/11 of the load; from P = −11 N it was beyond
// its limit, B was released and slid at u ≡ 0 beside the backstop that held the body.)
TEST_P(CampaignDefects, ABrakeBesideAStoppedBackstopHoldsUpToItsLimitAndTheLockCarriesTheRest) {
  const Model m = model_of(R"(
bodies: {m: {type: translational, mass: 1 kg}}
loads: {P: {type: ramp, body: m, value: -30 N, before: 0 N, start: 0 s, end: 1 s}}
brakes: {B: {body: m, holding: 10 N}}
freewheels: {S: {between: [ground, m]}}
simulation: {t_end: 2 s, dt_out: 0.01 s, rtol: 1e-10, atol: 1e-12}
)");
  const SimulationResult r = run(m, GetParam());
  expect_at_rest_and_stuck(r, {"m"}, {"B", "S"});
  const auto& t = series(r, "t_s");
  const auto &FB = series(r, "B.force_N"), &FS = series(r, "S.force_N");
  for (size_t i = 0; i < t.size(); ++i) {
    const double P = -30.0 * std::min(t[i], 1.0), lb = std::max(10.0 * P / 11.0, -10.0);
    EXPECT_NEAR(FB[i], lb, 1e-9) << t[i];
    EXPECT_NEAR(FS[i], P - lb, 1e-9) << t[i];
  }
}

// Claim: a loop of stuck contacts with one weak brake holds: body b (2 kg) is braked to the ground by
// B2 (1 N) and held through K (100 N, b against a) and B1 (100 N, a to the ground), under
// P = 80 min(t, 1) N on b. The load goes to the ground by B2 (x) or by K and B1 in series (P − x); the
// least x²/1 + 2 (P − x)²/100 gives x = P/51 while x ≤ 1 N (P ≤ 51 N); beyond, B2 stays at its limit
// 1 N and K, B1 carry P − 1 (≤ 79 N, within their 100 N). (The weighted share overloaded B2 from
// P = 51 N, t = 0.6375 s: it slid at u ≡ 0, the audit's `contact.locked_slide`.)
TEST_P(CampaignDefects, ALoopOfStuckContactsWithOneWeakBrakeHoldsItAtItsLimit) {
  const Model m = model_of(R"(
bodies: {a: {type: translational, mass: 1 kg}, b: {type: translational, mass: 2 kg}}
loads: {P: {type: ramp, body: b, value: 80 N, before: 0 N, start: 0 s, end: 1 s}}
brakes:
  B1: {body: a, holding: 100 N}
  B2: {body: b, holding: 1 N}
  K: {body: b, housing: a, holding: 100 N}
simulation: {t_end: 2 s, dt_out: 0.01 s, rtol: 1e-10, atol: 1e-12}
)");
  const SimulationResult r = run(m, GetParam());
  expect_at_rest_and_stuck(r, {"a", "b"}, {"B1", "B2", "K"});
  const auto& t = series(r, "t_s");
  const auto &F1 = series(r, "B1.force_N"), &F2 = series(r, "B2.force_N"), &FK = series(r, "K.force_N");
  for (size_t i = 0; i < t.size(); ++i) {
    const double P = 80.0 * std::min(t[i], 1.0), x = std::min(P / 51.0, 1.0);
    EXPECT_NEAR(F2[i], x, 1e-9) << t[i];
    EXPECT_NEAR(F1[i], P - x, 1e-9) << t[i];
    EXPECT_NEAR(FK[i], P - x, 1e-9) << t[i];
  }
}

// Claim: as above with constant levels on a spring (the affine path of models without time-varying
// terms): m (1 kg) held by a contact (10 N) and a backstop, n (1 kg) on a spring of 100 N/m from m
// under −30 N from rest. m at rest: x_n = −0.3 (1 − cos 10 t), the spring pulls m with
// −c(t), c = 30 (1 − cos 10 t) N up to 60 N; λ_B = −min(10 c/11, 10), λ_S = −c − λ_B. (The affine map
// of the mode was compiled with the one-sided rule's split at its probes: B carried all of c while
// S was unloaded, then slid at u ≡ 0 from c = 10 N.)
TEST_P(CampaignDefects, AContactBesideABackstopOnTheAffinePathHoldsUpToItsLimit) {
  const Model m = model_of(R"(
bodies: {m: {type: translational, mass: 1 kg}, n: {type: translational, mass: 1 kg}}
links: {c: {type: spring, between: [m, n], stiffness: 100 N/m}}
loads: {P: {type: constant, body: n, value: -30 N}}
contacts: {B: {between: [m, ground], static: 10 N, kinetic: 10 N}}
freewheels: {S: {between: [ground, m]}}
simulation: {t_end: 2 s, dt_out: 0.01 s, rtol: 1e-10, atol: 1e-12}
)");
  const SimulationResult r = run(m, GetParam());
  expect_at_rest_and_stuck(r, {"m"}, {"B", "S"});
  const auto& t = series(r, "t_s");
  const auto &xn = series(r, "n.position_m"), &FB = series(r, "B.force_N"), &FS = series(r, "S.force_N");
  for (size_t i = 0; i < t.size(); ++i) {
    const double c = 30.0 * (1.0 - std::cos(10.0 * t[i])), lb = -std::min(10.0 * c / 11.0, 10.0);
    EXPECT_NEAR(xn[i], -0.3 * (1.0 - std::cos(10.0 * t[i])), 1e-8) << t[i];
    EXPECT_NEAR(FB[i], lb, 1e-6) << t[i];
    EXPECT_NEAR(FS[i], -c - lb, 1e-6) << t[i];
  }
}

// Class A (campaign `signals`, `ground-friction`, `planetary`, `clutch`): a signal that jumps at 0 s acts
// from the start — the run starts with its value at t = 0, the right limit. A block (2 kg) held by a
// contact of F_s = 7 N under a step load 20 N → 5 N at 0 s and a pulse that is high (1 N) from its
// start at 0 s for 0.5 s and low (−10 N) after stays stuck while |P| ≤ F_s: λ = 6 N on [0, 0.5), and
// from 0.5 s the load is −5 N, still within F_s: no event, at rest, λ = P(t) at every row. (The audit
// read the first row at 0⁻, `before` and `low`: 20 − 10 = 10 N "beyond" 7 N, an AuditError at t = 0.)
TEST_P(CampaignDefects, ASignalThatJumpsAtZeroActsFromTheStart) {
  Model m = model_of(R"(
bodies: {m: {type: translational, mass: 2 kg}}
loads:
  S: {type: step, body: m, value: 5 N, before: 20 N, time: 0 s}
  U: {type: pulse, body: m, high: 1 N, low: -10 N, period: 2 s, width: 0.5 s, start: 0 s, count: 1}
contacts: {c: {between: [m, ground], static: 7 N, kinetic: 5 N}}
simulation: {t_end: 1 s, dt_out: 0.05 s, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  SimulateOptions o;
  o.check = true;  // the invariant audit, whatever the environment
  const SimulationResult r = simulate(m, o);
  EXPECT_EQ(events_of(r, "c").size(), 0u);
  const auto& t = series(r, "t_s");
  const auto& F = series(r, "c.force_N");
  const auto& v = series(r, "m.velocity_m_s");
  for (size_t i = 0; i < t.size(); ++i) {
    if (std::abs(t[i] - 0.5) > 1e-9) {  // the jump's row aside
      EXPECT_NEAR(F[i], t[i] < 0.5 ? 6.0 : -5.0, 1e-9) << t[i];
    }
    EXPECT_EQ(v[i], 0.0) << t[i];
  }
}

// Class E (campaign `signals` 46, `clutch` 86): a clutch whose normal force rises through zero is
// applied there. a (1 kg, 1 m/s, pushed by −3 N) and b (1 kg, at rest) with a clutch between them
// whose normal force f_N = −50 + 100 sin(2π (t − 0.5)) N from 0.5 s (−50 N before) rises through 0 at
// t_z = 0.5 + 1/12 s and falls through it at t_2 = 0.5 + 5/12 s. Released before t_z: v_a = 1 − 3t,
// v_b = 0, so u = v_a − v_b < 0 at t_z while the label kept from t = 0 is slip+. Applied at t_z into
// slip−, F = −μ_k f_N (on b +F, on a −F): with I(t) = ∫_{t_z}^{t} f_N dτ
// = (100/2π)(cos π/6 − cos 2π(t − 0.5)) − 50 (t − t_z) (frozen at t_2),
//   v_a = 1 − 3t + μ_k I,  v_b = −μ_k I,  u' = −3 + 2 μ_k f_N < 0 (no reversal),
// and the friction loss is ∫ μ_k f_N |u| dτ over [t_z, t_2] (Simpson below, 2000 panels). Events:
// `applied` released → slip− at t_z, `released` at t_2, nothing else. (A released clutch's event
// function read its stale label within 1e-12 of r's zero, 3e-13 s before t_z: a `reversal` was
// located there, the speeds jumped to u = 0, the energy books lost the jump.)
TEST_P(CampaignDefects, AClutchIsAppliedWhereItsNormalForceRisesThroughZero) {
  Model m = model_of(R"(
bodies:
  a: {type: translational, mass: 1 kg, velocity: 1 m/s}
  b: {type: translational, mass: 1 kg}
loads: {P: {type: constant, body: a, value: -3 N}}
clutches:
  K: {between: [a, b], normal_force: {type: sine, amplitude: 100 N, frequency: 1 Hz, offset: -50 N, start: 0.5 s},
      mu_s: 0.02, mu_k: 0.01}
simulation: {t_end: 1 s, dt_out: 0.01 s, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  SimulateOptions o;
  o.check = true;
  const SimulationResult r = simulate(m, o);
  const double pi = std::acos(-1.0), tz = 0.5 + 1.0 / 12, t2 = 0.5 + 5.0 / 12, mu = 0.01;
  const auto ev = events_of(r, "K");
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].kind, "applied");
  EXPECT_EQ(ev[0].to, "slip-");
  EXPECT_NEAR(ev[0].t, tz, 1e-12);
  EXPECT_EQ(ev[1].kind, "released");
  EXPECT_NEAR(ev[1].t, t2, 1e-12);
  auto I = [&](double t) {
    t = std::clamp(t, tz, t2);
    return 100 / (2 * pi) * (std::cos(pi / 6) - std::cos(2 * pi * (t - 0.5))) - 50 * (t - tz);
  };
  const auto& t = series(r, "t_s");
  const auto &va = series(r, "a.velocity_m_s"), &vb = series(r, "b.velocity_m_s");
  for (size_t i = 0; i < t.size(); ++i) {
    EXPECT_NEAR(va[i], 1 - 3 * t[i] + mu * I(t[i]), 1e-9) << t[i];
    EXPECT_NEAR(vb[i], -mu * I(t[i]), 1e-9) << t[i];
  }
  auto loss = [&](double x) { return mu * (-50 + 100 * std::sin(2 * pi * (x - 0.5))) * -(1 - 3 * x + 2 * mu * I(x)); };
  const int n = 2000;
  const double h = (t2 - tz) / n;
  double q = loss(tz) + loss(t2);
  for (int k = 1; k < n; ++k) q += (k % 2 ? 4 : 2) * loss(tz + k * h);
  EXPECT_NEAR(r.hybrid.energy.friction_loss, q * h / 3, 1e-9);
}

// Class F (campaign `release` 22, 23, 52, 89): a breakaway of a body at rest near the origin. A block
// (1 kg) at x0 = 3e-16 m (the rounding stuck bodies carry) held by a contact (F_s = 2 N, F_k = 1 N)
// under P = t N breaks away at t* = 2 s; then v' = t − 1: v = t²/2 − t, x = x0 + t³/6 − t²/2 + 2/3.
// (dopri5's first step after the restart came from ‖y‖/‖f‖ with |y| = 3e-16 against atol 1e-12:
// h = 6e-16 s, below what the step loop resolves at t = 2 s, and the run ended with "the step size
// became too small" at the breakaway.)
TEST_P(CampaignDefects, ABreakawayOfABodyAtRestNearTheOriginTakesItsFirstStep) {
  const SimulationResult r = run(model_of(R"(
bodies: {m: {type: translational, mass: 1 kg, position: 3e-16 m}}
loads: {P: {type: ramp, body: m, value: 3 N, before: 0 N, start: 0 s, end: 3 s}}
contacts: {c: {between: [m, ground], static: 2 N, kinetic: 1 N}}
simulation: {t_end: 3 s, dt_out: 0.05 s, rtol: 1e-10, atol: 1e-12}
)"),
                                 GetParam());
  const auto slips = events_of(r, "c", "slip");
  ASSERT_EQ(slips.size(), 1u);
  EXPECT_NEAR(slips[0].t, 2.0, 1e-9);
  const auto& t = series(r, "t_s");
  const auto &x = series(r, "m.position_m"), &v = series(r, "m.velocity_m_s");
  for (size_t i = 0; i < t.size(); ++i) {
    const double T = std::max(t[i], 2.0);
    EXPECT_NEAR(v[i], T * T / 2 - T, 1e-8) << t[i];
    EXPECT_NEAR(x[i], 3e-16 + T * T * T / 6 - T * T / 2 + 2.0 / 3, 1e-8) << t[i];
  }
}

}  // namespace
}  // namespace machdyn
