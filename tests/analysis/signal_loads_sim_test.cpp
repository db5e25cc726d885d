// Signals and state-dependent loads through simulate(), against closed-form motions, on both
// integrators and on both paths (the plain chain and the event-driven one every load case can take).
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <tuple>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/solve/stepper.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

constexpr double kPi = std::numbers::pi;

/// (integrator, event-driven path)
class SignalSim : public ::testing::TestWithParam<std::tuple<Method, bool>> {
 protected:
  /// Compiles `yaml` (without a `simulation:` section) with the parameter's integrator and tight tolerances.
  Model model(const std::string& yaml, double t_end, double dt_out) const {
    const char* integ = std::get<0>(GetParam()) == Method::dopri5 ? "dopri5" : "bdf";
    const std::string text = yaml + "simulation: {t_end: " + std::to_string(t_end) + ", dt_out: " + std::to_string(dt_out) +
                             ", rtol: 1e-10, atol: 1e-12, integrator: " + integ + "}\n";
    return compile_model_case(parse_yaml(text), "signals.yaml", {}, "");
  }
  SimulationResult run(const Model& m) const {
    SimulateOptions o;
    o.event_driven = std::get<1>(GetParam());
    return simulate(m, o);
  }
  static SpecNode parse_yaml(const std::string& text) { return parse_yaml_string(text, "signals.yaml"); }
};

INSTANTIATE_TEST_SUITE_P(BothIntegratorsBothPaths, SignalSim,
                         ::testing::Combine(::testing::Values(Method::dopri5, Method::bdf), ::testing::Bool()));

// Claim: a sine force started at t_s on an undamped spring–mass gives the closed-form forced response.
// m x'' + k x = A sin(Ω τ), τ = t − t_s ≥ 0, x = x' = 0 at τ = 0 (at rest before). With ω_n² = k/m,
// r = Ω/ω_n: the particular solution is x_p = A/(k − mΩ²) sin Ωτ = A/(k(1 − r²)) sin Ωτ; adding
// C sin ω_n τ + D cos ω_n τ, x(0) = 0 gives D = 0 and x'(0) = 0 gives C ω_n = −A Ω/(k(1 − r²)), so
//   x(τ) = A/(k(1 − r²)) (sin Ωτ − r sin ω_n τ).
TEST_P(SignalSim, SineForceOnSpringMassMatchesForcedResponse) {
  const Model m = model(R"(bodies:
  M: {type: translational, mass: 2 kg}
links:
  k: {type: spring, between: [M, ground], stiffness: 800 N/m}
loads:
  F: {type: sine, body: M, amplitude: 5 N, frequency: 1.5 Hz, start: 0.1 s}
)", 2.0, 1e-3);
  const SimulationResult r = run(m);
  const double A = 5, k = 800, wn = 20, W = 2 * kPi * 1.5, rr = W / wn, ts = 0.1;
  const auto& t = r.columns[0];
  const auto& x = r.columns[test::column(r, "M.position_m")];
  ASSERT_EQ(t.size(), 2001u);
  double worst = 0;
  for (size_t i = 0; i < t.size(); ++i) {
    const double tau = t[i] - ts;
    const double ref = tau <= 0 ? 0.0 : A / (k * (1 - rr * rr)) * (std::sin(W * tau) - rr * std::sin(wn * tau));
    worst = std::max(worst, std::abs(x[i] - ref));
  }
  // The response's amplitude is about A/k = 6e-3 m; tolerances 1e-10 keep the error some 1e-9 of it.
  EXPECT_LT(worst, 1e-9);
}

// Claim: a force step at t0 = 0.3 s (not on the output grid) lands exactly: t0 is a breakpoint of the
// run (the driver ends a step there), and the motion is x = F/k (1 − cos ω_n (t − t0)) after it, 0 before.
TEST_P(SignalSim, StepLandsExactlyAtItsTime) {
  const Model m = model(R"(bodies:
  M: {type: translational, mass: 2 kg}
links:
  k: {type: spring, between: [M, ground], stiffness: 800 N/m}
loads:
  F: {type: step, body: M, value: 40 N, time: 0.3 s}
)", 1.0, 7e-3);
  ASSERT_EQ(m.breakpoints(1.0), (std::vector<double>{0.3}));
  const SimulationResult r = run(m);
  // The run's breakpoints are the model's: the driver ends a step exactly at each (driver_test.cpp).
  EXPECT_EQ(r.hybrid.breakpoints, (std::vector<double>{0.3}));
  const auto& t = r.columns[0];
  const auto& x = r.columns[test::column(r, "M.position_m")];
  for (size_t i = 0; i < t.size(); ++i) {
    const double ref = t[i] < 0.3 ? 0.0 : 40.0 / 800.0 * (1 - std::cos(20.0 * (t[i] - 0.3)));
    ASSERT_NEAR(x[i], ref, 1e-9) << t[i];
  }
}

// Claim: a linear motor switched on at 0.2 s and off at 0.5 s spins a free rotor up as
// I ω' = M_s (1 − ω/ω0): ω = ω0 (1 − exp(−(t − 0.2)/τ)), τ = I ω0 / M_s, and the rotor coasts at
// constant speed after 0.5 s; reversed (direction −1) the same in the negative sense.
TEST_P(SignalSim, ContactorAndReversingOfAMotor) {
  for (const char* dir : {"", ", direction: -1"}) {
    const Model m = model(std::string(R"(bodies:
  R: {inertia: 0.5 kg*m^2}
loads:
  M: {type: motor-linear, body: R, stall_torque: 100 N*m, no_load_speed: 150 rad/s, on: 0.2 s, off: 0.5 s)") +
                              dir + "}\n", 1.0, 1e-3);
    const double sgn = *dir ? -1.0 : 1.0, tau = 0.5 * 150 / 100.0;
    auto w = [&](double t) {
      const double te = std::min(std::max(t - 0.2, 0.0), 0.3);
      return sgn * 150 * (1 - std::exp(-te / tau));
    };
    const SimulationResult r = run(m);
    const auto& t = r.columns[0];
    const auto& v = r.columns[test::column(r, "R.velocity_rad_s")];
    for (size_t i = 0; i < t.size(); ++i) ASSERT_NEAR(v[i], w(t[i]), 2e-6) << dir << " t = " << t[i];
  }
}

// Claim: a drag force −k v|v| slows a sliding mass as v = v0/(1 + k v0 t/m) (m v' = −k v², v > 0),
// and a speed table of a straight line M = −c v over the range of speeds acts as a viscous damper:
// v = v0 exp(−c t/m).
TEST_P(SignalSim, DragAndSpeedTableDecelerateAsClosedForms) {
  const Model m = model(R"(bodies:
  A: {type: translational, mass: 4 kg, velocity: 3 m/s}
  B: {type: translational, mass: 4 kg, velocity: 3 m/s}
loads:
  drag: {type: drag, body: A, coefficient: 0.5 N*s^2/m^2}
  visc: {type: table, over: speed, body: B, points: [[-10 m/s, 20 N], [10 m/s, -20 N]]}
)", 2.0, 1e-3);
  const SimulationResult r = run(m);
  const auto& t = r.columns[0];
  const auto& va = r.columns[test::column(r, "A.velocity_m_s")];
  const auto& vb = r.columns[test::column(r, "B.velocity_m_s")];
  for (size_t i = 0; i < t.size(); ++i) {
    ASSERT_NEAR(va[i], 3.0 / (1 + 0.5 * 3.0 * t[i] / 4.0), 1e-8) << t[i];
    ASSERT_NEAR(vb[i], 3.0 * std::exp(-2.0 * t[i] / 4.0), 1e-8) << t[i];
  }
}

// Claim: an eddy-current brake M = −2 M_k x/(1 + x²), x = ω/ω_k, on a free rotor keeps
// ln x + x²/2 + 2 M_k t/(I ω_k) constant: I ω_k x' = −2 M_k x/(1 + x²) separates into
// (1 + x²)/x dx = −2 M_k/(I ω_k) dt.
TEST_P(SignalSim, EddyCurrentBrakeKeepsItsFirstIntegral) {
  const Model m = model(R"(bodies:
  R: {inertia: 0.2 kg*m^2, velocity: 300 rad/s}
loads:
  B: {type: eddy-current-brake, body: R, breakdown_torque: 40 N*m, breakdown_speed: 100 rad/s}
)", 1.5, 1e-3);
  const SimulationResult r = run(m);
  const auto& t = r.columns[0];
  const auto& w = r.columns[test::column(r, "R.velocity_rad_s")];
  auto invariant = [&](size_t i) {
    const double x = w[i] / 100.0;
    return std::log(x) + 0.5 * x * x + 2 * 40.0 * t[i] / (0.2 * 100.0);
  };
  for (size_t i = 0; i < t.size(); ++i) ASSERT_NEAR(invariant(i), invariant(0), 1e-7) << t[i];
  EXPECT_LT(w.back(), 100.0);  // it did brake: ln x + x²/2 = ln 3 + 4.5 − 6 at 1.5 s gives x ≈ 0.57
}

// Claim: an expression load in the body's position, F = −k x, is a spring: x = x0 cos(ω_n t).
TEST_P(SignalSim, PositionExpressionIsASpring) {
  const Model m = model(R"(bodies:
  M: {type: translational, mass: 2 kg, position: 0.01 m}
loads:
  F: {type: expression, body: M, expression: "-800*x + 0*v*t"}
)", 1.0, 1e-3);
  const SimulationResult r = run(m);
  const auto& t = r.columns[0];
  const auto& x = r.columns[test::column(r, "M.position_m")];
  for (size_t i = 0; i < t.size(); ++i) ASSERT_NEAR(x[i], 0.01 * std::cos(20.0 * t[i]), 1e-9) << t[i];
}

}  // namespace
}  // namespace machdyn
