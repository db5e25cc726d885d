// Run-time failures name their cause (issue 28): a load whose law is not finite, the state that holds
// the steps short at the step limit (a stiff DC motor's current), a brake whose temperature
// overflows, a rope wound in to its end (two-blocking). Each on both integrators.
#include <cmath>
#include <limits>
#include <string>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

class FailureNames : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, FailureNames,
                         ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf), test::IntegratorName{});

/// The SolverError of simulating `yaml` with the test's integrator ("" element if it ran through).
SolverError failure_of(const std::string& yaml, IntegratorChoice ic) {
  Model m = test::model_text(yaml);
  m.simulation.integrator = ic;
  try {
    (void)simulate(m);
  } catch (const SolverError& e) {
    return e;
  }
  ADD_FAILURE() << "expected a SolverError";
  return SolverError("", std::numeric_limits<double>::quiet_NaN(), "");
}

// Claim: an expression load that divides by zero (1/(t - t) is NaN at every t) is named as the
// cause ("load 'L'"), not the velocity of the body it acts on; at t = 0, its first evaluation.
TEST_P(FailureNames, ALoadWhoseLawIsNotFiniteIsNamed) {
  const SolverError e = failure_of(
      "bodies:\n  I1: {type: rotational, inertia: 1 kg*m^2}\n"
      "links:\n  c1: {type: spring, between: [I1, ground], stiffness: 100 N*m/rad}\n"
      "loads:\n  K: {type: constant, body: I1, value: 1 N*m}\n"
      "  L: {type: expression, body: I1, expression: '1/(t-t)'}\n"
      "simulation: {t_end: 0.1 s}\n", GetParam());
  EXPECT_EQ(e.element(), "load 'L'") << e.what();
  EXPECT_EQ(e.time(), 0.0);
}

// Claim: at the step limit the state that holds the steps short is named: a DC motor with an
// electrical time constant L/R = 1e-9 H / 2 Ω = 5e-10 s holds an explicit method to steps of that
// order (its current's error dominates), so 2000 steps end at t ≈ 1e-6 s naming "drive 'dcm'";
// on bdf the same limit of 5 steps ends inside the current's transient, naming the current too.
TEST_P(FailureNames, TheStepLimitNamesWhatHoldsTheStepsShort) {
  const bool bdf = GetParam() == IntegratorChoice::bdf;
  const SolverError e = failure_of(
      "bodies:\n  motor: {type: rotational, inertia: 0.1 kg*m^2}\n"
      "links:\n  c1: {type: spring, between: [motor, ground], stiffness: 100 N*m/rad}\n"
      "drives:\n  dcm: {type: dc-motor, body: motor, resistance: 2 ohm, inductance: 1e-9 H, "
      "motor_constant: 0.8 V*s/rad, voltage: 100 V}\n"
      "simulation: {t_end: 1 s, max_steps: " + std::string(bdf ? "5" : "2000") + "}\n", GetParam());
  EXPECT_EQ(e.element().rfind("drive 'dcm'", 0), 0u) << e.what();
  EXPECT_NE(std::string(e.what()).find("maximum number of steps"), std::string::npos) << e.what();
  EXPECT_LT(e.time(), 1e-3);
}

// Claim: a brake whose temperature leaves the doubles stops the run naming the brake, not after the
// overflow time. A 1 kg·m² body at 10 rad/s braked by 10 N·m from t = 0: ω = 10 − 10 t, heat
// Q(t) = ∫ M ω dt = 100 t − 50 t² J; adiabatic with C = 1e-307 J/K, T = T0 + Q/C passes DBL_MAX at
// Q* = DBL_MAX · 1e-307 J (17.98 J), t* = 1 − √(1 − Q*/50) = 0.1997 s, long before the stop at 1 s.
TEST_P(FailureNames, ATemperatureBeyondTheDoublesNamesTheBrake) {
  const SolverError e = failure_of(
      "bodies:\n  I1: {type: rotational, inertia: 1 kg*m^2, velocity: 10 rad/s}\n"
      "brakes:\n  B: {body: I1, holding: 10 N*m, braking: 10 N*m, time: 0 s, "
      "thermal: {heat_capacity: 1e-307 J/K, ambient: 20 degC}}\n"
      "simulation: {t_end: 2 s}\n", GetParam());
  EXPECT_EQ(e.element(), "B") << e.what();
  EXPECT_NE(std::string(e.what()).find("temperature overflows"), std::string::npos) << e.what();
  const double q_star = std::numeric_limits<double>::max() * 1e-307;
  const double t_star = 1.0 - std::sqrt(1.0 - q_star / 50.0);
  EXPECT_GE(e.time(), t_star * (1 - 1e-12));
  EXPECT_LT(e.time(), 1.0);
}

// Claim: a rope wound in to its end stops the run at that time, naming the rope. A drum (10 kg·m²)
// with a rope of 1 m (10 rad/m, R = 0.1 m, EA 1e7 N) to a 100 kg hook under gravity, driven by
// 200 N·m: rigidly, α = (M − m g R)/(I + m R²) = (200 − 98.1)/11 rad/s², and one fall reaches
// L_min = 1e-3 L at θ = 0.999 L / R = 9.99 rad, t* = √(2 θ / α) = 1.4687 s. The rope's stretch
// (m g / (EA/L) ≈ 1e-4 m) shifts it by far less than the 1e-3 allowed.
TEST_P(FailureNames, ARopeWoundInToItsEndStopsTheRun) {
  const SolverError e = failure_of(
      "gravity: 9.81 m/s^2\n"
      "bodies:\n  drum: {type: rotational, inertia: 10 kg*m^2}\n"
      "  hook: {type: translational, mass: 100 kg, vertical: up}\n"
      "links:\n  rope: {type: rope, between: [drum, hook], ratio: 10 rad/m, EA: 1e7 N, length: 1 m}\n"
      "loads:\n  M: {type: constant, body: drum, value: 200 N*m}\n"
      "simulation: {t_end: 3 s}\n", GetParam());
  EXPECT_EQ(e.element(), "rope") << e.what();
  EXPECT_NE(std::string(e.what()).find("wound in to its end"), std::string::npos) << e.what();
  const double alpha = (200.0 - 100.0 * 9.81 * 0.1) / (10.0 + 100.0 * 0.01);
  const double t_star = std::sqrt(2.0 * 9.99 / alpha);
  EXPECT_NEAR(e.time(), t_star, 1e-3 * t_star) << test::sci(e.time() - t_star);
}

}  // namespace
}  // namespace machdyn
