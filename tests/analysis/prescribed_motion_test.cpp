// Prescribed motion (`motion:` of a body; law in elements/prescribed_motion.hpp): a body whose
// acceleration or speed follows a signal drives the rest of the model, every link and load on it still
// acts, and the source's force closes its equation of motion. Each claim is checked against a closed
// form derived in its comment or an RK4 written here, on both integrators where it runs.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/analysis/linear_analysis.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/elements/linearize.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::max_error;
using test::series;

class PrescribedMotion : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, PrescribedMotion,
                         ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf), test::IntegratorName{});



// Claim: a driver (m_d = 2 kg) whose speed is prescribed as v_d = V sin Ωt (V = 0.5 m/s, Ω = 3 rad/s)
// drives a mass m = 1 kg through a spring c = 400 N/m (ω² = c/m = 400 s⁻²); a constant force
// F = 5 N acts on the driver. The driver moves as x_d = A (1 − cos Ωt), A = V/Ω, whatever the loads.
// The mass, from rest at 0: x'' + ω² x = ω² x_d(t). Particular solution x_p = A − A ω²/(ω² − Ω²) cos Ωt;
// with x(0) = 0, x'(0) = 0 the homogeneous part is A Ω²/(ω² − Ω²) cos ωt (its sine term is 0), so
//   x(t) = A − A ω²/(ω² − Ω²) cos Ωt + A Ω²/(ω² − Ω²) cos ωt.
// The source's force closes the driver's equation m_d a_d = F − c (x_d − x) + R (the spring [driver,
// mass] pulls the driver back by its load c (x_d − x)):  R = m_d V Ω cos Ωt − F + c (x_d − x).
// Within 1e-8 m, 1e-7 m/s and 1e-5 N at every 1 ms row (amplitudes 0.17 m, 0.5 m/s, ~50 N).
TEST_P(PrescribedMotion, PrescribedSpeedDrivesASpringMassAsTheClosedForm) {
  Model m = test::model_text(R"(
bodies:
  driver: {type: translational, mass: 2 kg, motion: {speed: {type: sine, amplitude: 0.5 m/s, frequency: 3 rad/s}}}
  mass: {type: translational, mass: 1 kg}
links:
  spring: {type: spring, between: [driver, mass], stiffness: 400 N/m}
loads:
  push: {type: constant, body: driver, value: 5 N}
simulation: {t_end: 2 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const double V = 0.5, W = 3.0, A = V / W, w2 = 400.0, w = 20.0, md = 2.0, c = 400.0, F = 5.0;
  auto xd = [&](double t) { return A * (1 - std::cos(W * t)); };
  auto x = [&](double t) { return A - A * w2 / (w2 - W * W) * std::cos(W * t) + A * W * W / (w2 - W * W) * std::cos(w * t); };
  auto v = [&](double t) { return A * w2 * W / (w2 - W * W) * std::sin(W * t) - A * W * W * w / (w2 - W * W) * std::sin(w * t); };
  auto R = [&](double t) { return md * V * W * std::cos(W * t) - F + c * (xd(t) - x(t)); };
  const double tx = GetParam() == IntegratorChoice::bdf ? 1e-7 : 1e-8;
  EXPECT_LT(max_error(r, "driver.position_m", xd), tx);
  EXPECT_LT(max_error(r, "driver.velocity_m_s", [&](double t) { return V * std::sin(W * t); }), 1e-7);
  EXPECT_LT(max_error(r, "mass.position_m", x), tx);
  EXPECT_LT(max_error(r, "mass.velocity_m_s", v), 1e-6);
  EXPECT_LT(max_error(r, "driver.motion_force_N", R), 1e-4);
  EXPECT_GT(max_error(r, "driver.motion_force_N", [](double) { return 0.0; }), 10.0);  // a real load
}

// Claim: the motion source's work is source work of the energy books: with a spring-damper between
// the driver (speed V sin Ωt) and the mass, W = ΔT + ΔV + damping loss (residual within 1e-7 of W),
// and W equals ∫ (R + F) v_d dt of the output columns (R the source's force, F = 5 N the constant
// load on the driver; trapezoid rule on the 0.1 ms grid, within 1e-4 relative).
TEST_P(PrescribedMotion, TheSourcesWorkIsSourceWork) {
  Model m = test::model_text(R"(
bodies:
  driver: {type: translational, mass: 2 kg, motion: {speed: {type: sine, amplitude: 0.5 m/s, frequency: 3 rad/s}}}
  mass: {type: translational, mass: 1 kg}
links:
  sd: {type: spring-damper, between: [driver, mass], stiffness: 400 N/m, damping: 4 N*s/m}
loads:
  push: {type: constant, body: driver, value: 5 N}
simulation: {t_end: 1 s, dt_out: 0.1 ms, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  SimulateOptions opt;
  opt.event_driven = true;
  const SimulationResult r = simulate(m, opt);
  const EnergyBalance& e = r.hybrid.energy;
  EXPECT_GT(e.source_work, 1e-3);  // not a trivial balance: 0.0135 J of work, 0.0032 J damped
  EXPECT_GT(e.damping_loss, 1e-3);
  EXPECT_LT(std::abs(e.residual()), 1e-7 * std::abs(e.source_work) + 1e-9);
  const auto& ts = series(r, "t_s");
  const auto& R = series(r, "driver.motion_force_N");
  const auto& vd = series(r, "driver.velocity_m_s");
  double W = 0.0;
  for (size_t i = 1; i < ts.size(); ++i)
    W += 0.5 * (ts[i] - ts[i - 1]) * ((R[i] + 5.0) * vd[i] + (R[i - 1] + 5.0) * vd[i - 1]);
  EXPECT_NEAR(W, e.source_work, 1e-4 * std::abs(e.source_work));
}

// Claim: a prescribed position x_d = A sin Ωt (A = 0.05 m, Ω = 3 rad/s) drives the mass m = 1 kg
// through the spring c = 400 N/m (ω = 20 rad/s); the driver starts at x_d(0) = 0 with v_d(0) = A Ω.
// The mass from rest: x'' + ω² x = ω² A sin Ωt; particular ω² A/(ω² − Ω²) sin Ωt, and x'(0) = 0 gives
// the homogeneous part −ω A Ω/(ω² − Ω²) sin ωt:  x = A ω (ω sin Ωt − Ω sin ωt)/(ω² − Ω²).
// The source's force on the driver (m_d = 2 kg, no other load): R = −m_d A Ω² sin Ωt + c (x_d − x).
// Within 1e-8 m (1e-7 bdf), 1e-6 m/s and 1e-4 N at every 1 ms row.
TEST_P(PrescribedMotion, PrescribedPositionDrivesASpringMassAsTheClosedForm) {
  Model m = test::model_text(R"(
bodies:
  driver: {type: translational, mass: 2 kg, motion: {position: {type: sine, amplitude: 0.05 m, frequency: 3 rad/s}}}
  mass: {type: translational, mass: 1 kg}
links:
  spring: {type: spring, between: [driver, mass], stiffness: 400 N/m}
simulation: {t_end: 2 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  EXPECT_NEAR(m.bodies[0].v0, 0.15, 1e-15);
  const SimulationResult r = simulate(m);
  const double A = 0.05, W = 3.0, w = 20.0, c = 400.0, md = 2.0, den = w * w - W * W;
  auto xd = [&](double t) { return A * std::sin(W * t); };
  auto x = [&](double t) { return A * w * (w * std::sin(W * t) - W * std::sin(w * t)) / den; };
  auto v = [&](double t) { return A * w * W * w * (std::cos(W * t) - std::cos(w * t)) / den; };
  auto R = [&](double t) { return -md * A * W * W * std::sin(W * t) + c * (xd(t) - x(t)); };
  const double tx = GetParam() == IntegratorChoice::bdf ? 1e-7 : 1e-8;
  EXPECT_LT(max_error(r, "driver.position_m", xd), tx);
  EXPECT_LT(max_error(r, "driver.velocity_m_s", [&](double t) { return A * W * std::cos(W * t); }), 1e-7);
  EXPECT_LT(max_error(r, "mass.position_m", x), tx);
  EXPECT_LT(max_error(r, "mass.velocity_m_s", v), 1e-6);
  EXPECT_LT(max_error(r, "driver.motion_force_N", R), 1e-4);
}

// Claim: a rotational position given as an expression, φ = 0.2 t³ + 0.5 t rad, starts at ω(0) = 0.5
// rad/s and turns as ω = 0.6 t² + 0.5; with I = 2 kg·m² and nothing else on it the source's torque
// is I φ'' = 2 · 1.2 t (the expression's exact second derivative). Within 1e-9 at every row (the
// torque; the motion 1e-9 on dopri5, 1e-7 on bdf, default tolerances).
TEST_P(PrescribedMotion, PositionExpressionUsesItsExactSecondDerivative) {
  Model m = test::model_text(
      "bodies:\n  b: {inertia: 2, motion: {position: {type: expression, expression: '0.2*t^3 + 0.5*t'}}}\n"
      "simulation: {t_end: 1 s}\n");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const double tol = GetParam() == IntegratorChoice::bdf ? 1e-7 : 1e-9;
  EXPECT_LT(max_error(r, "b.position_rad", [](double t) { return 0.2 * t * t * t + 0.5 * t; }), tol);
  EXPECT_LT(max_error(r, "b.velocity_rad_s", [](double t) { return 0.6 * t * t + 0.5; }), tol);
  EXPECT_LT(max_error(r, "b.motion_torque_N_m", [](double t) { return 2.4 * t; }), 1e-9);
}

// Claim: a prescribed acceleration with jumps (a table: 0, then 2 m/s² on [0.2, 0.5) s, then −1 m/s²
// on [0.5, 0.9) s, then 0; the speed is a ramp-like broken line) drives a mass through a spring-damper
// (c = 900 N/m, d = 6 N·s/m, m = 1.5 kg). Reference: an RK4 (h = 1e-5 s, the jumps on its grid)
// of m x'' = c (x_d − x) + d (v_d − x') with the driver's x_d, v_d integrated exactly (piecewise
// quadratic) in the test. The jumps are breakpoints, so the run matches within 1e-8 m (1e-7 bdf) and
// the source's force R = m_d a_d + c (x_d − x) + d (v_d − x') (m_d = 3 kg) jumps by m_d Δa at 0.2 s.
TEST_P(PrescribedMotion, AccelerationWithJumpsMatchesAnRk4) {
  Model m = test::model_text(R"(
bodies:
  driver: {type: translational, mass: 3 kg, motion: {acceleration: {type: table, unit: m/s^2, points: [[0, 0], [0.2, 0], [0.2, 2], [0.5, 2], [0.5, -1], [0.9, -1], [0.9, 0]]}}}
  mass: {type: translational, mass: 1.5 kg}
links:
  sd: {type: spring-damper, between: [driver, mass], stiffness: 900 N/m, damping: 6 N*s/m}
simulation: {t_end: 1.5 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  // The driver in closed form: a piecewise constant ⇒ v, x piecewise linear and quadratic.
  const std::vector<double> tb = {0.0, 0.2, 0.5, 0.9}, ab = {0.0, 2.0, -1.0, 0.0};
  auto driver = [&](double t, double& xd, double& vd, double& ad) {
    xd = vd = 0.0;
    ad = 0.0;
    for (size_t k = 0; k < tb.size(); ++k) {
      if (t < tb[k]) break;
      const double t1 = k + 1 < tb.size() ? std::min(t, tb[k + 1]) : t, h = t1 - tb[k];
      xd += vd * h + 0.5 * ab[k] * h * h;
      vd += ab[k] * h;
      ad = ab[k];
    }
  };
  const double c = 900, d = 6, mm = 1.5, md = 3.0;
  auto accel = [&](double t, double x, double v) {
    double xd, vd, ad;
    driver(t, xd, vd, ad);
    return (c * (xd - x) + d * (vd - v)) / mm;
  };
  // RK4 over the output grid (1e-5 s steps: 100 per row; 0.2, 0.5, 0.9 s are step boundaries). A
  // stage at a step's end takes the left limit: the step's own piece.
  double x = 0, v = 0, t = 0, ex = 0, ev = 0, eR = 0;
  const double h = 1e-5;
  const auto& ts = series(r, "t_s");
  const auto& X = series(r, "mass.position_m");
  const auto& Vv = series(r, "mass.velocity_m_s");
  const auto& RR = series(r, "driver.motion_force_N");
  for (size_t i = 0; i < ts.size(); ++i) {
    while (t < ts[i] - 1e-12) {
      const double te = t + h - 1e-13;  // left limit at the step's end
      const double k1x = v, k1v = accel(t, x, v);
      const double k2x = v + 0.5 * h * k1v, k2v = accel(t + 0.5 * h, x + 0.5 * h * k1x, v + 0.5 * h * k1v);
      const double k3x = v + 0.5 * h * k2v, k3v = accel(t + 0.5 * h, x + 0.5 * h * k2x, v + 0.5 * h * k2v);
      const double k4x = v + h * k3v, k4v = accel(te, x + h * k3x, v + h * k3v);
      x += h / 6 * (k1x + 2 * k2x + 2 * k3x + k4x);
      v += h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
      t = std::round((t + h) / h) * h;
    }
    double xd, vd, ad;
    driver(ts[i], xd, vd, ad);
    ex = std::max(ex, std::abs(X[i] - x));
    ev = std::max(ev, std::abs(Vv[i] - v));
    eR = std::max(eR, std::abs(RR[i] - (md * ad + c * (xd - x) + d * (vd - v))));
    EXPECT_NEAR(series(r, "driver.velocity_m_s")[i], vd, 1e-8) << ts[i];
  }
  const bool bdf = GetParam() == IntegratorChoice::bdf;
  EXPECT_LT(ex, bdf ? 1e-7 : 1e-8) << (GetParam() == IntegratorChoice::bdf ? "bdf" : "dopri5");
  EXPECT_LT(ev, bdf ? 1e-5 : 1e-6);
  EXPECT_LT(eR, bdf ? 1e-3 : 1e-4);
  // The jump of the source's force at 0.2 s: m_d · 2 m/s² (the spring's load is continuous).
  EXPECT_NEAR(test::at(r, "driver.motion_force_N", 0.201) - test::at(r, "driver.motion_force_N", 0.199), md * 2.0, 0.5);
}

// Claim: a friction contact between a prescribed body and a free one acts as between two free bodies,
// the prescribed one infinitely heavy. Driver (I_d = 1 kg·m²) at the prescribed speed 10 rad/s, ramped
// to 20 rad/s over [6, 8] s (a_d = 5 rad/s²); flywheel I = 0.5 kg·m² from rest under a load −1 N·m;
// contact [driver, fly], static 3 N·m, kinetic 2 N·m (the force F on fly, −F on the driver). Phases:
//   [0, 5)   sliding, u > 0: I ω' = 2 − 1 ⇒ ω = 2 t, reaches 10 at 5 s; R = I_d a_d + F = 2
//   [5, 6)   stuck: F = λ = 1 ≤ 3 (the load held); R = 1
//   [6, 11)  holding would need λ = I a_d + 1 = 3.5 > 3: slips at 6 s, ω = 10 + 2 (t − 6) (the driver
//            runs ahead); R = 5 + 2 = 7 on [6, 8), 2 on [8, 11); ω reaches 20 at 11 s
//   [11, 12] stuck again, R = 1.
// Within 1e-7 rad/s (1e-5 bdf) at every 1 ms row; R within 1e-6 N·m at rows inside each phase.
TEST_P(PrescribedMotion, AContactWithAPrescribedBodyActsOnBoth) {
  Model m = test::model_text(R"(
bodies:
  driver: {inertia: 1, motion: {speed: {type: table, unit: rad/s, points: [[0, 10], [6, 10], [8, 20]]}}}
  fly: {inertia: 0.5}
contacts:
  c: {between: [driver, fly], static: 3 N*m, kinetic: 2 N*m}
loads:
  drag: {type: constant, body: fly, value: -1 N*m}
simulation: {t_end: 12 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  auto w = [](double t) { return t < 5 ? 2 * t : t < 6 ? 10.0 : t < 11 ? 10 + 2 * (t - 6) : 20.0; };
  EXPECT_LT(max_error(r, "fly.velocity_rad_s", w), GetParam() == IntegratorChoice::bdf ? 1e-5 : 1e-7);
  for (const auto& [t, R] : std::vector<std::pair<double, double>>{{3, 2}, {5.5, 1}, {7, 7}, {9, 2}, {11.5, 1}})
    EXPECT_NEAR(test::at(r, "driver.motion_torque_N_m", t), R, 1e-6) << t;
  EXPECT_NEAR(test::at(r, "c.force_N_m", 5.5), 1.0, 1e-6);
  EXPECT_NEAR(test::at(r, "driver.velocity_rad_s", 7.0), 15.0, 1e-8);
}

// Claim: in modes a prescribed body is a fixed support: driver – spring c – mass m has the one elastic
// frequency √(c/m) = 20 rad/s and no rigid-body mode, as the mass on a spring to the ground.
TEST(PrescribedMotionModes, APrescribedBodyIsAFixedSupport) {
  const Model m = test::model_text(R"(
bodies:
  driver: {type: translational, mass: 2 kg, motion: {speed: 1 m/s}}
  mass: {type: translational, mass: 1 kg}
links:
  spring: {type: spring, between: [driver, mass], stiffness: 400 N/m}
)");
  const TopologyModes tm = analyse_topology(m, initial_topology(m));
  EXPECT_EQ(tm.modes.rigid_body_modes, 0);
  ASSERT_EQ(tm.modes.omega.size(), 1);
  EXPECT_NEAR(tm.modes.omega(0), 20.0, 1e-9);
  EXPECT_EQ(tm.modes.constraints, 1);
}

// Claim: the quasi-static load of a link treats a prescribed body as a support: a constant force of
// 3 N on the mass hanging on the driver is held by the spring, F_spring = −3 N (the spring [driver,
// mass] acts on the mass with +F). And the driver starts at the speed signal's v(0) = 1 m/s.
TEST(PrescribedMotionStatic, APrescribedBodyIsASupportOfTheQuasiStaticLoads) {
  Model m = test::model_text(R"(
bodies:
  driver: {type: translational, mass: 2 kg, motion: {speed: 1 m/s}}
  mass: {type: translational, mass: 1 kg}
links:
  spring: {type: spring, between: [driver, mass], stiffness: 400 N/m}
loads:
  F: {type: constant, body: mass, value: 3 N}
simulation: {t_end: 0.5 s}
)");
  EXPECT_EQ(m.bodies[0].v0, 1.0);
  const SimulationResult r = simulate(m);
  ASSERT_EQ(r.links.size(), 1u);
  EXPECT_NEAR(r.links[0].static_at_max, -3.0, 1e-12);
  EXPECT_NEAR(r.links[0].static_at_min, -3.0, 1e-12);
  EXPECT_NEAR(series(r, "driver.position_m").back(), 0.5, 1e-9);
}

// Claim: `initial: equilibrium` refuses a prescribed body with a located error naming it.
TEST(PrescribedMotionStatic, EquilibriumStartIsALocatedError) {
  Model m = test::model_text(R"(
bodies:
  driver: {type: translational, mass: 2 kg, motion: {speed: 1 m/s}}
  mass: {type: translational, mass: 1 kg}
links:
  spring: {type: spring, between: [driver, mass], stiffness: 400 N/m}
simulation: {t_end: 0.5 s, initial: equilibrium}
)");
  try {
    (void)simulate(m);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    const std::string s = e.what();
    EXPECT_NE(s.find("test.yaml:3:"), std::string::npos) << s;
    EXPECT_NE(s.find("'driver'"), std::string::npos) << s;
  }
}

// Claim: every bad `motion:` is a located error (file:line:col), all listed at once.
TEST(PrescribedMotionCompile, BadFieldsAreLocatedErrors) {
  struct Case {
    const char* yaml;
    const char* expect;
  };
  const std::vector<Case> cases = {
      {"bodies:\n  b: {type: translational, mass: 1, motion: 2 m/s}\n", "test.yaml:2:"},
      {"bodies:\n  b: {type: translational, mass: 1, motion: {speed: 1 m/s, acceleration: 1 m/s^2}}\n", "exactly one"},
      {"bodies:\n  b: {type: translational, mass: 1, motion: {}}\n", "exactly one"},
      {"bodies:\n  b: {type: translational, mass: 1, motion: {jerk: 1}}\n", "jerk"},
      {"bodies:\n  b: {type: translational, mass: 1, position: 2 m, motion: {position: 1 m}}\n", "contradicts"},
      {"bodies:\n  b: {type: translational, mass: 1, velocity: 2 m/s, motion: {position: 1 m}}\n", "contradicts"},
      {"bodies:\n  b: {inertia: 1, motion: {position: 1 m}}\n", "test.yaml:2:"},
      {"bodies:\n  b: {type: translational, mass: 1, motion: {position: {type: table, unit: m, points: [[0, 0], "
       "[0.5, 1], [1, 1]]}}}\nsimulation: {t_end: 2 s}\n", "must be smooth"},
      {"bodies:\n  b: {type: translational, mass: 1, motion: {acceleration: 1 m/s}}\n", "test.yaml:2:"},
      {"bodies:\n  b: {inertia: 1, motion: {speed: 2 m/s}}\n", "test.yaml:2:"},
      {"bodies:\n  b: {type: translational, mass: 1, velocity: 3 m/s, motion: {speed: 2 m/s}}\n", "contradicts"},
      {"bodies:\n  b: {type: translational, mass: 1, motion: {acceleration: {type: pulse, high: 1 m/s^2, period: 1 ns, "
       "width: 0.5 ns}}}\nsimulation: {t_end: 1 s}\n", "more than 1e+07"},
      {"bodies:\n  a: {type: translational, mass: 1, motion: {speed: 1 m/s}}\n  b: {type: translational, mass: 1, "
       "motion: {speed: 2 m/s}}\nstops:\n  s: {body: a, max: 12 m}\n", "end stop"},
  };
  for (const Case& c : cases) {
    const std::string e = test::compile_errors(c.yaml);
    EXPECT_NE(e.find(c.expect), std::string::npos) << c.yaml << "\n→ " << e;
    EXPECT_NE(e.find("test.yaml:"), std::string::npos) << e;
  }
  // A rotational body takes rad/s² and rad/s; its source's output is a torque.
  const Model m = test::model_text("bodies:\n  b: {inertia: 2, motion: {acceleration: 3 rad/s^2}}\n");
  EXPECT_EQ(m.bodies[0].motion, MotionKind::acceleration);
  EXPECT_EQ(m.bodies[0].motion_signal.value(0.7), 3.0);
  // A position starts the body at s(0) and ds/dt(0); a constant speed given as a table that ends
  // after t_end is smooth before it.
  const Model p = test::model_text("bodies:\n  b: {type: translational, mass: 1, motion: {position: {type: table, "
                                   "unit: m, points: [[0, 1], [10, 6]]}}}\nsimulation: {t_end: 2 s}\n");
  EXPECT_EQ(p.bodies[0].q0, 1.0);
  EXPECT_EQ(p.bodies[0].v0, 0.5);
}

// Claim: the command line refuses a bad `motion:` with exit code 2 and the error located, writing
// nothing; a good one writes the source's force column to timeseries.csv.
TEST(PrescribedMotionCompile, CliExitsTwoOnABadMotionAndWritesTheForceColumn) {
  const auto bad = test::write_temp("bad-motion.yaml", "bodies:\n  b: {type: translational, mass: 1,\n"
                                                       "      motion: {speed: 1 m/s^2}}\n");
  const auto out = test::temp_dir() / "bad-motion-out";
  const auto r = test::run_cli("simulate '" + bad + "' -o '" + out.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad-motion.yaml:3:"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out / "timeseries.csv"));
  const auto good_out = test::temp_dir() / "accelerate-out";
  const auto g = test::run_cli("simulate '" + test::example("msl/accelerate.yaml") + "' -o '" + good_out.string() + "'");
  EXPECT_EQ(g.exit_code, 0) << g.err;
  const std::string csv = test::slurp(good_out / "timeseries.csv");
  EXPECT_NE(csv.find("mass.motion_force_N"), std::string::npos);
}

// Claim: a rotational body with prescribed acceleration α = 3 rad/s² and inertia 2 kg·m² needs the
// torque I α = 6 N·m (column b.motion_torque_N_m) and turns as φ = α t²/2.
TEST_P(PrescribedMotion, RotationalTorqueIsInertiaTimesAcceleration) {
  Model m = test::model_text("bodies:\n  b: {inertia: 2, motion: {acceleration: 3 rad/s^2}}\nsimulation: {t_end: 1 s}\n");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  EXPECT_LT(max_error(r, "b.motion_torque_N_m", [](double) { return 6.0; }), 1e-12);
  EXPECT_LT(max_error(r, "b.position_rad", [](double t) { return 1.5 * t * t; }), 1e-9);
}

}  // namespace
}  // namespace machdyn
