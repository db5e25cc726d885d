// Freewheels (one-way clutches, elements/contact.hpp with lock ≠ 0): overrunning and re-locking at
// the closed-form instants, a backstop holding a body at rest, and located input errors. Every
// event-driven claim on both integrators.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>
#include <gtest/gtest.h>

#include "support/support.hpp"

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn {
namespace {

Model model_of(const std::string& yaml) { return compile_model(parse_yaml_string(yaml, "fw.yaml"), "fw.yaml"); }

class Freewheel : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, Freewheel, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

double column_at_end(const SimulationResult& r, const std::string& name) {
  for (size_t c = 0; c < r.column_names.size(); ++c)
    if (r.column_names[c] == name) return r.columns[c].back();
  ADD_FAILURE() << "no column " << name;
  return NAN;
}

// Claim: a motor a (I_a = 0.5 kg·m²) drives a load b (I_b = 1.5) through a freewheel with drag
// D = 1 N·m while overrunning. The torque on a is 10 N·m, −10 from t = 0.5 s, +20 from t = 1 s.
//   0 … 0.5 s locked: ε = 10/(I_a + I_b) = 5, the freewheel carries λ = I_b ε = 7.5 ≥ 0, v(0.5) = 2.5.
//   At 0.5 s locked would need λ = I_b (−10)/2 = −7.5 < 0: b overruns at once (u̇ < 0), slip at 0.5.
//   Overrunning: b decelerates by the drag, v_b = 2.5 − (D/I_b)(t − 0.5); a gets −10 + D (the drag
//   pulls it along): v_a(1) = 2.5 + 0.5 (−10 + D)/I_a; after 1 s v_a = v_a(1) + (20 + D)/I_a (t − 1).
//   It locks again when v_a = v_b: t_r = 1 + (v_b(1) − v_a(1)) / ((20 + D)/I_a + D/I_b) = 1.20312…
//   Locked again (λ = I_b · 20/2 = 15 ≥ 0): v(1.5) = v_b(t_r) + 10 (1.5 − t_r).
TEST_P(Freewheel, OverrunsAndRelocksAtTheClosedFormInstants) {
  Model m = model_of(R"(
bodies: {a: {inertia: 0.5}, b: {inertia: 1.5}}
freewheels: {fw: {between: [a, b], drag: 1 N*m}}
loads:
  M: {type: constant, body: a, value: 10 N*m}
  off: {type: step, body: a, time: 0.5 s, value: -20 N*m}
  on: {type: step, body: a, time: 1.0 s, value: 30 N*m}
simulation: {t_end: 1.5 s, dt_out: 0.01 s, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const double Ia = 0.5, Ib = 1.5, D = 1.0;
  const double vb1 = 2.5 - D / Ib * 0.5, va1 = 2.5 + 0.5 * (-10 + D) / Ia;
  const double t_r = 1.0 + (vb1 - va1) / ((20 + D) / Ia + D / Ib);
  const double v_end = (2.5 - D / Ib * (t_r - 0.5)) + 10.0 * (1.5 - t_r);
  const SimulationResult r = simulate(m);
  std::vector<ModeEvent> ev;
  for (const auto& e : r.hybrid.events)
    if (e.element == "fw" && e.kind != "initial") ev.push_back(e);
  ASSERT_EQ(ev.size(), 2u);
  EXPECT_EQ(ev[0].kind, "slip");
  EXPECT_EQ(ev[0].to, "slip-");
  EXPECT_DOUBLE_EQ(ev[0].t, 0.5);  // at the load step itself (a breakpoint)
  EXPECT_EQ(ev[1].kind, "stick");
  EXPECT_NEAR(ev[1].t, t_r, 1e-9 * t_r);
  const double tol = GetParam() == IntegratorChoice::dopri5 ? 1e-8 : 1e-6;
  EXPECT_NEAR(column_at_end(r, "a.velocity_rad_s"), v_end, tol * v_end);
  EXPECT_EQ(column_at_end(r, "a.velocity_rad_s"), column_at_end(r, "b.velocity_rad_s"));  // locked exactly
  // The energy books close: work of the torques = ΔT + the drag's loss.
  EXPECT_LT(std::abs(r.hybrid.energy.residual()), 1e-7 * r.hybrid.energy.source_work);
  EXPECT_GT(r.hybrid.energy.friction_loss, 0.0);
}

// A freewheel fw [X, Y] (X drives Y forward) and a friction contact K (3 N·m, μ_s = μ_k) in parallel
// between X (I_X = 1) and Y (I_Y = 2), both at rest; a torque τ = 10 − 20 t on X only. Together the
// pair accelerates at a = τ/3, and Y needs the load λ = I_Y a = 2τ/3 from X.
//   0 … t_b: both stuck (u ≡ 0), sharing λ by the bounded split (docs/hybrid.md "Redundant locks"):
//     the weighted share (w² = 3 for K, 1 for fw) K 3λ/4, fw λ/4 while 3λ/4 ≤ 3 (λ ≤ 4); beyond, K at
//     its limit 3 and fw the rest λ − 3 (0 … t = 0.2 s); λ < 0 K alone, fw unloaded (the one-sided
//     rule): it is not labelled as overrunning while the contact holds the pair.
//   At t_b = 0.725 s, λ = −3 (τ = −4.5): K breaks away backwards and fw overruns at once (Y ahead):
//     I_X a_X = τ + 3, I_Y a_Y = −3 after it, v(t_b) = (10 t_b − 10 t_b²)/3 before.
// (Before the bounded split K was labelled sliding at zero speed while λ > 3, t < t_a = 0.275 s, and
// stuck at t_a; before an earlier fix fw overran at t_a, K sliding forwards beside it.)
// Claim: fw's only switch is the overrun at t_b and K's the breakaway at t_b (each within 1e-8 s),
// K stuck before with the load above; X's and Y's speeds follow the closed form at every row within
// 1e-8 rad/s (1e-6 on BDF); fw carries no negative load beyond its 1e-9 N·m allowance.
TEST_P(Freewheel, ParallelClutchHoldsAndTheFreewheelOverrunsWhenItBreaksAway) {
  Model m = model_of(R"(
bodies: {X: {inertia: 1}, Y: {inertia: 2}}
freewheels: {fw: {between: [X, Y]}}
contacts: {K: {between: [X, Y], static: 3 N*m, kinetic: 3 N*m}}
loads: {tau: {type: table, body: X, points: [[0, 10], [2, -30]]}}
simulation: {t_end: 1.5 s, dt_out: 0.01 s, rtol: 1e-11, atol: 1e-13}
)");
  m.simulation.integrator = GetParam();
  const double tb = 0.725, vb = (10.0 * tb - 10.0 * tb * tb) / 3.0;
  const SimulationResult r = simulate(m);
  std::vector<ModeEvent> fw, K;
  for (const auto& e : r.hybrid.events)
    if (e.kind != "initial") (e.element == "fw" ? fw : K).push_back(e);
  ASSERT_EQ(fw.size(), 1u);
  EXPECT_EQ(fw[0].to, "slip-");
  EXPECT_NEAR(fw[0].t, tb, 1e-8);
  ASSERT_EQ(K.size(), 1u);
  EXPECT_EQ(K[0].to, "slip-");
  EXPECT_NEAR(K[0].t, tb, 1e-8);
  const double tol = GetParam() == IntegratorChoice::dopri5 ? 1e-8 : 1e-6;
  const auto& t = test::series(r, "t_s");
  const auto& vx = test::series(r, "X.velocity_rad_s");
  const auto& vy = test::series(r, "Y.velocity_rad_s");
  const auto& F = test::series(r, "fw.force_N_m");
  const auto& FK = test::series(r, "K.force_N_m");
  const auto& mK = test::series(r, "K.mode");
  for (size_t j = 0; j < t.size(); ++j) {
    if (t[j] < tb - 1e-6) {
      const double lam = 2.0 * (10.0 - 20.0 * t[j]) / 3.0, k = lam < 0.0 ? lam : std::min(0.75 * lam, 3.0);
      EXPECT_EQ(mK[j], 0.0) << t[j];
      EXPECT_NEAR(FK[j], k, 1e-7) << t[j];
      EXPECT_NEAR(F[j], lam - k, 1e-7) << t[j];
    }
    const double s = t[j] - tb;
    const double x = t[j] <= tb ? (10.0 * t[j] - 10.0 * t[j] * t[j]) / 3.0 : vb + 13.0 * s - 10.0 * (t[j] * t[j] - tb * tb);
    const double y = t[j] <= tb ? x : vb - 1.5 * s;
    EXPECT_NEAR(vx[j], x, tol) << t[j];
    EXPECT_NEAR(vy[j], y, tol) << t[j];
    EXPECT_GE(F[j], -1e-9) << t[j];
  }
}

// Claim: a backstop ([ground, A]) lets A turn forward only. A at 2 rad/s forward under −5 N·m
// (I = 0.5) decelerates at 10 rad/s² and stops at t = 0.2 s; there the backstop locks and holds
// the torque: A stays at rest exactly, and the backstop carries the 5 N·m.
TEST_P(Freewheel, BackstopHoldsABodyAtRest) {
  Model m = model_of(R"(
bodies: {A: {inertia: 0.5, velocity: 2 rad/s}}
freewheels: {stop: {between: [ground, A]}}
loads: {M: {type: constant, body: A, value: -5 N*m}}
simulation: {t_end: 0.5 s, dt_out: 0.01 s, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  std::vector<ModeEvent> ev;
  for (const auto& e : r.hybrid.events)
    if (e.element == "stop" && e.kind != "initial") ev.push_back(e);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_EQ(ev[0].kind, "stick");
  EXPECT_NEAR(ev[0].t, 0.2, 1e-9);
  EXPECT_EQ(column_at_end(r, "A.velocity_rad_s"), 0.0);
  EXPECT_NEAR(std::abs(column_at_end(r, "stop.force_N_m")), 5.0, 1e-9);
}

// Claim: the same backstop under a forward torque never locks: A accelerates freely (no drag).
TEST_P(Freewheel, BackstopLetsTheForwardMotionFree) {
  Model m = model_of(R"(
bodies: {A: {inertia: 0.5}}
freewheels: {stop: {between: [ground, A]}}
loads: {M: {type: constant, body: A, value: 5 N*m}}
simulation: {t_end: 0.5 s, dt_out: 0.01 s, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  EXPECT_NEAR(column_at_end(r, "A.velocity_rad_s"), 10.0 * 0.5, 1e-9);
}

// Claim: bad freewheels are located input errors, all listed at once: one joining a body to itself,
// an unknown body, and initial speeds that turn one in its locked direction.
TEST(FreewheelInput, ErrorsAreLocatedAndListedTogether) {
  try {
    model_of(R"(
bodies: {a: {inertia: 1, velocity: 3 rad/s}, b: {inertia: 1}}
freewheels:
  self: {between: [a, a]}
  lost: {between: [a, nowhere]}
  ahead: {between: [a, b]}
)");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string s = e.what();
    EXPECT_NE(s.find("fw.yaml:4:"), std::string::npos) << s;
    EXPECT_NE(s.find("joins 'a' to itself"), std::string::npos) << s;
    EXPECT_NE(s.find("unknown body 'nowhere'"), std::string::npos) << s;
    EXPECT_NE(s.find("fw.yaml:6:"), std::string::npos) << s;
    EXPECT_NE(s.find("locked direction"), std::string::npos) << s;
  }
}

}  // namespace
}  // namespace machdyn
