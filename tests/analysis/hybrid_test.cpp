// The exact hybrid simulation (analysis/drive_system.hpp, analysis/run.cpp): every claim against a closed form derived in
// its comment, a second algorithm or a published number.
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/analysis/hybrid_stats.hpp"

#include <cmath>
#include <numbers>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/models.hpp"
#include "support/travel_start.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "support/events.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::model_of;
using test::integrator_name;

using test::events_of;
using test::at;
using test::series;


// Every event-driven claim holds on both integrators: the test is parameterized over them.
class Hybrid : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, Hybrid, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         integrator_name);

using test::with_integrator;
SimulationResult run(const Model& m, IntegratorChoice ic) { return simulate(with_integrator(m, ic)); }

// Claim: a body stays stuck while the load is within the static limit and slips exactly when it
// reaches it. Load f = 100 t N on a 2 kg block, static limit 30 N: breakaway at t = 30/100 = 0.3 s.
// A second block under a constant load equal to its limit (|λ| = F_s) never slips.
TEST_P(Hybrid, StickAtExactlyTheBreakawayThreshold) {
  const Model m = model_of(R"(
bodies:
  A: {type: translational, mass: 2}
  B: {type: translational, mass: 2}
contacts:
  fa: {between: [A, ground], static: 30 N, kinetic: 20 N}
  fb: {between: [B, ground], static: 30 N, kinetic: 20 N}
loads:
  f: {type: ramp, body: A, before: 0, value: 100 N, start: 0, end: 1 s}
  g: {type: constant, body: B, value: 30 N}
simulation: {t_end: 0.5, dt_out: 0.05, rtol: 1e-10, atol: 1e-12}
)");
  const SimulationResult r = run(m, GetParam());
  const auto slip = events_of(r, "fa");
  ASSERT_EQ(slip.size(), 1u);
  EXPECT_EQ(slip[0].kind, "slip");
  EXPECT_EQ(slip[0].to, "slip+");
  EXPECT_NEAR(slip[0].t, 0.3, 1e-12);
  EXPECT_TRUE(events_of(r, "fb").empty());
  EXPECT_EQ(at(r, "B.velocity_m_s", 0.5), 0.0);
  EXPECT_NEAR(at(r, "fb.force_N", 0.5), 30.0, 1e-12);
  // After breakaway: m x'' = 100 t − 20 from rest at 0.3 s → v(0.5) = [50 t² − 20 t]_{0.3}^{0.5} / 2.
  EXPECT_NEAR(at(r, "A.velocity_m_s", 0.5), (50 * (0.25 - 0.09) - 20 * 0.2) / 2.0, 1e-9);
}

// Claim: a sliding body re-sticks when its sliding speed crosses zero and then stays at rest.
// m = 4 kg, v0 = 3 m/s, kinetic 10 N, no load: stops at t = m v0 / F_k = 1.2 s after
// x = m v0² / (2 F_k) = 1.8 m, then |λ| = 0 ≤ F_s.
TEST_P(Hybrid, ReSticksWhenSlidingSpeedCrossesZero) {
  const Model m = model_of(R"(
bodies: {A: {type: translational, mass: 4, velocity: 3}}
contacts: {f: {between: [A, ground], static: 12 N, kinetic: 10 N}}
simulation: {t_end: 2, dt_out: 0.5, rtol: 1e-10, atol: 1e-12}
)");
  const SimulationResult r = run(m, GetParam());
  const auto ev = events_of(r, "f");
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].kind, "stick");
  EXPECT_NEAR(ev[0].t, 1.2, 1e-12);
  EXPECT_EQ(at(r, "A.velocity_m_s", 2.0), 0.0);
  EXPECT_NEAR(at(r, "A.position_m", 2.0), 1.8, 1e-10);
}

// Claim: a brake stops a body and then holds it while the load stays below its holding torque.
// I = 2 kg m², ω0 = 10 rad/s, driving torque 50 N m; brake (holding 300, braking 200 N m) applied
// at 0.1 s over a 0.2 s ramp. ω(0.1) = 10 + 25·0.1 = 12.5; over the ramp ω' = 25 − 500 (t − 0.1),
// so ω(0.3) = 12.5 + 5 − 10 = 7.5; then ω' = (50 − 200)/2 = −75: at rest at t = 0.3 + 0.1 = 0.4 s.
// Afterwards the brake carries the 50 N m (< 300) and ω ≡ 0.
TEST_P(Hybrid, BodyBrakedToRestStaysAtRest) {
  const Model m = model_of(R"(
bodies: {J: {inertia: 2, velocity: 10}}
brakes: {T: {body: J, holding: 300 N*m, braking: 200 N*m, time: 0.1 s, ramp: 0.2 s}}
loads: {M: {type: constant, body: J, value: 50 N*m}}
simulation: {t_end: 2, dt_out: 0.1, rtol: 1e-10, atol: 1e-12}
)");
  const SimulationResult r = run(m, GetParam());
  const auto ev = events_of(r, "T", "stick");
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_NEAR(ev[0].t, 0.4, 1e-11);
  EXPECT_TRUE(events_of(r, "T", "slip").empty());
  for (double t : {0.5, 1.0, 2.0}) {
    EXPECT_EQ(at(r, "J.velocity_rad_s", t), 0.0) << t;
    EXPECT_NEAR(at(r, "T.force_N_m", t), 50.0, 1e-9) << t;
  }
  EXPECT_NEAR(at(r, "J.velocity_rad_s", 0.3), 7.5, 1e-9);
  // Before 0.1 s the brake is released, not slipping: its one slip phase starts when it is applied
  // (an `applied` event) and ends at the stop; the initial mode says `released`.
  size_t phases = 0;
  for (const auto& p : r.hybrid.slip_phases)
    if (p.contact == "T") {
      ++phases;
      EXPECT_EQ(p.t_start, 0.1);
      EXPECT_NEAR(p.t_end, 0.4, 1e-11);
    }
  EXPECT_EQ(phases, 1u);
  ASSERT_EQ(events_of(r, "T", "applied").size(), 1u);
  EXPECT_EQ(events_of(r, "T", "applied")[0].t, 0.1);
  EXPECT_EQ(r.hybrid.events[0].to, "released");
}

// Claim: a contact's ratio F_max / F_s0 is formed only between like units: a drum (rotational, a
// brake torque in N·m) winding a rope to a load (translational, the rope force in N) gets no ratio
// (NaN, JSON null) for the rope; a brake on the load's own motion would.
TEST_P(Hybrid, ContactRatiosOnlyBetweenLikeUnits) {
  const Model m = model_of(R"(
bodies:
  drum: {inertia: 2, velocity: 1}
  load: {type: translational, mass: 100}
links: {rope: {type: spring, between: [drum, load], ratio: 4 rad/m, stiffness: 1e5 N/m}}
brakes:
  T: {body: drum, holding: 300 N*m, braking: 200 N*m}
contacts:
  guide: {between: [load, ground], static: 1000 N, kinetic: 800 N}
simulation: {t_end: 0.1, dt_out: 0.01}
)");
  const SimulationResult r = run(m, GetParam());
  const auto st = contact_statistics(m, r);
  ASSERT_EQ(st.size(), 2u);
  for (const auto& c : st) {
    if (c.name == "T") {
      EXPECT_TRUE(std::isnan(c.link_max_over_static_limit[0])) << "N over N·m";
    } else {
      EXPECT_EQ(c.link_max_over_static_limit[0], r.links[0].max / 1000.0);
    }
  }
}

// Claim: two friction elements locking one motion do not make the constraint singular: they share
// the load in proportion to their static limits (30 : 70), hold while it is below the sum and both
// break away at the same instant when f = 100 t reaches 100 N, t = 1 s.
TEST_P(Hybrid, TwoLockableElementsOnOneMotion) {
  const Model m = model_of(R"(
bodies: {A: {type: translational, mass: 1}}
contacts:
  f1: {between: [A, ground], static: 30 N, kinetic: 20 N}
  f2: {between: [A, ground], static: 70 N, kinetic: 50 N}
loads: {f: {type: ramp, body: A, value: 200 N, start: 0, end: 2 s}}
simulation: {t_end: 1.5, dt_out: 0.25, rtol: 1e-10, atol: 1e-12}
)");
  const SimulationResult r = run(m, GetParam());
  EXPECT_NEAR(at(r, "f1.force_N", 0.5), 15.0, 1e-9);
  EXPECT_NEAR(at(r, "f2.force_N", 0.5), 35.0, 1e-9);
  EXPECT_EQ(at(r, "A.velocity_m_s", 0.75), 0.0);
  const auto e1 = events_of(r, "f1"), e2 = events_of(r, "f2");
  ASSERT_EQ(e1.size(), 1u);
  ASSERT_EQ(e2.size(), 1u);
  // The stuck events fire at the stick rule's own limit F_s + 1e-12 F_s0 (its rounding allowance,
  // elements/contact.hpp): f = 100 t reaches 100 (1 + 1e-12) N at t = 1 + 1e-12 s.
  EXPECT_NEAR(e1[0].t, 1.0 + 1e-12, 1e-12);
  EXPECT_EQ(e1[0].t, e2[0].t);
  // Both slide after: v(1.5) = ∫_1^1.5 (100 t − 70) dt = 50 (2.25 − 1) − 35 = 27.5 m/s.
  EXPECT_NEAR(at(r, "A.velocity_m_s", 1.5), 27.5, 1e-8);
}

// Claim: friction against a prescribed motion (a block on a belt moving at w, tied to the ground by
// a spring k) sticks, slips at x = F_s/k, t_s = F_s/(k w), and re-sticks when v = w again:
// during the slip x = F_k/k + A cos ωτ + (w/ω) sin ωτ with A = (F_s − F_k)/k, ω = sqrt(k/m);
// v = w cos ωτ − A ω sin ωτ = w ⇔ tan(ωτ/2) = −A ω / w ⇒ τ = 2 (π − atan(A ω / w)) / ω.
TEST_P(Hybrid, FrictionAgainstPrescribedMotion) {
  const double m = 1.0, k = 100.0, w = 0.2, Fs = 5.0, Fk = 3.0;
  const Model mod = model_of(fmt::format(R"(
bodies: {{A: {{type: translational, mass: {}, velocity: {}}}}}
links: {{s: {{type: spring, between: [A, ground], stiffness: {}}}}}
contacts: {{belt: {{between: [A, ground], static: {}, kinetic: {}, surface_velocity: {}}}}}
simulation: {{t_end: 1.0, dt_out: 0.01, rtol: 1e-11, atol: 1e-13}}
)", m, w, k, Fs, Fk, w));
  const SimulationResult r = run(mod, GetParam());
  const auto ev = events_of(r, "belt");
  ASSERT_GE(ev.size(), 3u);
  const double ts = Fs / (k * w), om = std::sqrt(k / m), A = (Fs - Fk) / k;
  const double tau = 2 * (std::numbers::pi - std::atan(A * om / w)) / om;
  EXPECT_EQ(ev[0].kind, "slip");
  EXPECT_EQ(ev[0].to, "slip-");
  EXPECT_NEAR(ev[0].t, ts, 1e-12);
  EXPECT_EQ(ev[1].kind, "stick");
  EXPECT_NEAR(ev[1].t, ts + tau, 1e-9);
  // The cycle repeats: stuck again for the time the spring needs to come back to F_s.
  // At re-stick x = F_k/k + A cos ωτ + (w/ω) sin ωτ; then x grows at w up to F_s/k.
  const double x_re = Fk / k + A * std::cos(om * tau) + w / om * std::sin(om * tau);
  EXPECT_NEAR(ev[2].t, ts + tau + (Fs / k - x_re) / w, 1e-9);
}

// Claim: a gap's start position and a preload work as written. (a) gap Δ = 10 mm centred
// (gap_start 5 mm), link to the ground, P = 200 N on m = 2 kg: the flank is 5 mm away, reached at
// t = sqrt(2 m 0.005 / P) with v² = 2 P 0.005 / m; the peak load is P + sqrt(P² + c m v²).
// (b) a body placed 2 mm into the flank with c = 1e5 N/m and P = 200 N rests in equilibrium: the
// link starts closed and carries exactly P forever, no event.
TEST_P(Hybrid, GapWithOffsetAndPreload) {
  const Model a = model_of(R"(
bodies: {A: {type: translational, mass: 2}}
links: {c: {type: spring, between: [A, ground], stiffness: 1e5 N/m, gap: 10 mm, gap_start: 5 mm}}
loads: {P: {type: constant, body: A, value: 200 N}}
simulation: {t_end: 0.2, dt_out: 0.01, rtol: 1e-11, atol: 1e-13}
)");
  const SimulationResult ra = run(a, GetParam());
  const auto ev = events_of(ra, "c");
  ASSERT_GE(ev.size(), 2u);
  EXPECT_EQ(ev[0].kind, "gap_closed");
  EXPECT_NEAR(ev[0].t, std::sqrt(2 * 2 * 0.005 / 200.0), 1e-12);
  EXPECT_EQ(ev[1].kind, "gap_opened");
  const double v2 = 2 * 200 * 0.005 / 2.0;
  EXPECT_NEAR(ra.links[0].max, 200 + std::sqrt(200.0 * 200 + 1e5 * 2 * v2), 1e-6);
  // Undamped and elastic: it leaves the flank with the speed it arrived at, after half a period
  // of the contact oscillation shifted by the static deflection: t_open − t_close = (π − 2 atan(...)).
  const double om = std::sqrt(1e5 / 2.0), v = std::sqrt(v2), xs = 200 / 1e5;
  EXPECT_NEAR(ev[1].t - ev[0].t, (std::numbers::pi + 2 * std::atan(om * xs / v)) / om, 1e-9);

  const Model b = model_of(R"(
bodies: {A: {type: translational, mass: 2, position: 7 mm}}
links: {c: {type: spring, between: [A, ground], stiffness: 1e5 N/m, gap: 10 mm, gap_start: 5 mm}}
loads: {P: {type: constant, body: A, value: 200 N}}
simulation: {t_end: 0.1, dt_out: 0.01}
)");
  const SimulationResult rb = run(b, GetParam());
  EXPECT_TRUE(events_of(rb, "c").empty());
  ASSERT_EQ(rb.hybrid.events.size(), 1u);
  EXPECT_EQ(rb.hybrid.events[0].to, "closed+");
  EXPECT_NEAR(at(rb, "c.load_N", 0.1), 200.0, 1e-9);
  EXPECT_NEAR(at(rb, "A.velocity_m_s", 0.1), 0.0, 1e-12);
}

paper001::TravelDrive drive_of(const Model& m) {
  paper001::TravelDrive d;
  d.m1 = m.bodies[0].inertia, d.mk = m.bodies[1].inertia, d.m2 = m.bodies[2].inertia;
  d.c = m.links[0].c, d.Delta = m.links[0].gap;
  d.P = m.loads[0].value;
  d.F_sc = m.contacts[0].static_limit, d.F_d = m.contacts[0].kinetic[0];
  d.W = m.contacts[1].static_limit;
  return d;
}

// Claim: the simulated travel start-up passes through the paper's exact stages: the gap closes at
// t1 = sqrt(2 m1 Δ / P), m2 starts moving (W breaks away) at t1 + t2, and the wheels start to
// slip at t1 + t2 + t3 with the link force at the exact slip limit [F_sc (mk + m2) − mk W]/m2 —
// all to 1e-9 relative. The peak link force, reported as a multiple of F_sc, lies near the paper's
// 1.03…1.05 F_sc and its approximation F4max of stage 4 (within 15 %).
TEST_P(Hybrid, TravelStartMatchesPaper001Stages) {
  const Model m = load_model(test::example("travel-start.yaml"));
  const SimulationResult r = run(m, GetParam());
  const auto d = drive_of(m);
  const auto e = paper001::exact_stages(d);
  const auto closed = events_of(r, "c", "gap_closed");
  const auto W = events_of(r, "W", "slip");
  const auto slip = events_of(r, "adhesion", "slip");
  ASSERT_FALSE(closed.empty());
  ASSERT_FALSE(W.empty());
  ASSERT_FALSE(slip.empty());
  EXPECT_NEAR(closed[0].t, e.t1, 1e-9 * e.t1);
  EXPECT_NEAR(W[0].t, e.t1 + e.t2, 1e-9 * (e.t1 + e.t2));
  EXPECT_NEAR(slip[0].t, e.slip_time(), 1e-9 * e.slip_time());
  // The link force at the first slip: the slip phase starts there.
  const SlipPhase* first = nullptr;
  for (const auto& p : r.hybrid.slip_phases)
    if (p.contact == "adhesion") {
      first = &p;
      break;
    }
  ASSERT_NE(first, nullptr);
  const auto a = paper001::approximate_stage4(d, e);
  const double ratio = first->link_max[0] / d.F_sc;
  EXPECT_GT(ratio, e.F_slip / d.F_sc);
  EXPECT_NEAR(first->link_max[0], a.F4_max, 0.15 * a.F4_max);
  EXPECT_GT(ratio, 1.0);
  EXPECT_LT(ratio, 1.3);
  // Self-oscillation: the wheels slip again and again over the 2 s.
  EXPECT_GE(slip.size(), 10u);
  // Every event restarts the stepper and each piece takes at least one step: the run's statistics
  // are summed over the restarts (CVODE once reported only the last piece's 78 steps here).
  long located = 0;
  for (const auto& ev : r.hybrid.events) located += ev.kind != "initial";
  EXPECT_GT(r.stats.stepper.steps, located);
  EXPECT_GE(r.stats.events, located > 0 ? 1 : 0);
  RecordProperty("F_max_over_F_sc", fmt::format("{:.4f}", r.links[0].max / d.F_sc));
}

// Claim: the energy balance W_sources = ΔT + ΔV + friction + damping losses holds to 1e-8 of
// the source work (dopri5; 1e-7 with BDF) over a run with hundreds of stick, slip, gap events (travel start, 12 s, P
// raised so the gap reopens every cycle).
TEST_P(Hybrid, EnergyBalanceOverHundredsOfEvents) {
  const Model m = load_model(test::example("travel-start.yaml"), {"simulation.t_end=12", "P.value=6.9 kN"});
  const SimulationResult r = run(m, GetParam());
  long events = 0;
  for (const auto& e : r.hybrid.events) events += e.kind != "initial";
  EXPECT_GE(events, 200);
  const auto& E = r.hybrid.energy;
  EXPECT_GT(E.friction_loss, 0.0);
  // The residual is the integration error of the energy quadratures: 1e-8 for dopri5 at rtol 1e-10;
  // CVODE's BDF keeps its local error less tightly at the same rtol (measured 1.3e-8): 1e-7.
  const double tol = GetParam() == IntegratorChoice::bdf ? 1e-7 : 1e-8;
  EXPECT_LT(std::abs(E.residual()), tol * E.source_work) << "residual " << E.residual() << " of " << E.source_work;
  // Second check, independent of the quadrature: the work of P is P · x1(t_end) exactly. The friction
  // loss is W's plus the adhesion's: W = 1.5 kN (static = kinetic) dissipates W · x2(t_end) because
  // m2 never moves backwards; the adhesion dissipates F_d ∫|u| dt with F_d = 0.11 · 50 kN = 5.5 kN,
  // and since it only ever slides forwards (u = v_k − v_2 > 0) and u ≡ 0 while stuck, ∫|u| dt is
  // the relative travel x_k − x_2 at t_end (both start at 0).
  const double x1 = series(r, "m1.position_m").back(), xk = series(r, "mk.position_m").back();
  const double x2 = series(r, "m2.position_m").back();
  EXPECT_NEAR(E.source_work, 6900.0 * x1, tol * E.source_work);
  for (double v2 : series(r, "m2.velocity_m_s")) ASSERT_GE(v2, 0.0) << "m2 moved backwards";
  for (const auto& p : r.hybrid.slip_phases)
    if (p.contact == "adhesion") {
      ASSERT_EQ(p.direction, 1) << "adhesion slid backwards at " << p.t_start;
    }
  EXPECT_GT(x2, 0.0);
  EXPECT_GT(xk - x2, 0.0);
  EXPECT_NEAR(E.friction_loss, 1500.0 * x2 + 5500.0 * (xk - x2), tol * E.friction_loss);
}

// Claim (friction law edge): a kinetic table that rises above the applied force right after
// breakaway (μ_s 0.3, μ_k 0.2 at rest rising to 0.9 at 1e-9 m/s, N = 10 N, P = 5 N on 1 kg) never
// makes the body slide backwards. F_s = 3 N < P: it breaks away; the friction F_k(u) = 2 + 7e9 u N
// then balances P at u* = 3/7e9 m/s, a stable creep (dF_k/du > 0), reached within ~1e-9 s. The
// table is a damper of 7e9 N·s/m: `auto` takes BDF for it, which must give u → u*, F → P;
// dopri5, forced, may not return a backwards slide — it ends at its step limit (SolverError).
// Second part: the same contact with P = 1 N < F_k(0) from 1 m/s decelerates at (9 − 1) m/s² and
// re-sticks when u returns to zero at t ≈ 1/8 s (the last 1e-9 m/s with F_k falling to 2 N takes
// < 1e-9 s), then stays stuck (|λ| = 1 N ≤ 3 N).
TEST_P(Hybrid, RisingKineticTableNeverSlidesBackwards) {
  const std::string contact =
      "contacts: {f: {between: [A, ground], normal_force: 10 N, mu_s: 0.3, mu_k: [[0, 0.2], [1e-9 m/s, 0.9], [1 m/s, 0.9]]}}\n";
  Model m = model_of("bodies: {A: {type: translational, mass: 1 kg}}\n" + contact +
                     "loads: {P: {type: constant, body: A, value: 5 N}}\nsimulation: {t_end: 1 s, dt_out: 0.1 s}\n");
  std::string reason;
  EXPECT_EQ(choose_method(m, &reason), Method::bdf) << reason;
  if (GetParam() == IntegratorChoice::dopri5) {
    m.simulation.max_steps = 200'000;
    try {
      const SimulationResult r = run(m, GetParam());
      for (double v : series(r, "A.velocity_m_s")) EXPECT_GE(v, 0.0);
    } catch (const SolverError& e) {
      EXPECT_NE(std::string(e.what()).find("maximum number of steps"), std::string::npos) << e.what();
    }
  } else {
    const SimulationResult r = run(m, GetParam());
    const double u_star = 3.0 / 7e9;
    for (double v : series(r, "A.velocity_m_s")) EXPECT_GE(v, 0.0);
    for (double md : series(r, "f.mode")) EXPECT_EQ(md, 1.0);
    EXPECT_NEAR(series(r, "A.velocity_m_s").back(), u_star, 1e-6 * u_star);
    EXPECT_NEAR(series(r, "f.force_N").back(), 5.0, 1e-6);
  }
  const Model b = model_of("bodies: {A: {type: translational, mass: 1 kg, velocity: 1 m/s}}\n" + contact +
                           "loads: {P: {type: constant, body: A, value: 1 N}}\n"
                           "simulation: {t_end: 0.5 s, dt_out: 0.05 s, rtol: 1e-10, atol: 1e-12}\n");
  const SimulationResult rb = run(b, GetParam());
  const auto ev = events_of(rb, "f");
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].kind, "stick");
  EXPECT_NEAR(ev[0].t, 0.125, 1e-8);
  for (double t : {0.15, 0.3, 0.5}) {
    EXPECT_EQ(at(rb, "A.velocity_m_s", t), 0.0) << t;
    EXPECT_NEAR(at(rb, "f.force_N", t), 1.0, 1e-9) << t;
  }
}

// Claim: chattering is detected and reported with the element, the time and the count, and the
// run ends (SolverError) instead of hanging: a block on a belt whose velocity reverses every
// 0.5 ms switches stick/slip at every reversal; with the detector set to 10 switches in 10 ms it
// trips.
TEST_P(Hybrid, ChatteringIsReported) {
  std::string table = "[";
  for (int i = 0; i <= 400; ++i) table += fmt::format("{}[{}, {}]", i ? ", " : "", i * 0.5e-3, i % 2 ? 0.01 : -0.01);
  table += "]";
  const Model m = model_of(fmt::format(R"(
bodies: {{A: {{type: translational, mass: 1}}}}
contacts: {{belt: {{between: [A, ground], static: 1 N, kinetic: 0.8 N, surface_velocity: {}}}}}
simulation: {{t_end: 0.2, dt_out: 0.01}}
)", table));
  SimulateOptions opt;
  opt.chatter_count = 10;
  opt.chatter_window = 0.01;
  try {
    simulate(with_integrator(m, GetParam()), opt);
    FAIL() << "no chattering reported";
  } catch (const SolverError& e) {
    EXPECT_EQ(e.element(), "belt");
    EXPECT_GT(e.time(), 0.0);
    EXPECT_NE(std::string(e.what()).find("chattering: 10 mode switches"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace machdyn
