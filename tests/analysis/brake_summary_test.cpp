// The brakes' stops of a run (analysis/brake_summary.hpp; summary.json `brakes`, the `simulate`
// printout): a constant-torque stop against its hand calculation, on both integrators.
#include <cmath>
#include <string>
#include <gtest/gtest.h>

#include "machdyn/analysis/brake_summary.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/results.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

Model model_of(const std::string& yaml) { return compile_model(parse_yaml_string(yaml, "brake.yaml"), "brake.yaml"); }

class BrakeSummary : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, BrakeSummary, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

// Claim: a flywheel I = 2 kg·m² coasting at ω0 = 100 rad/s, and a 1 t cart at v0 = 2 m/s, each stopped
// by a brake of constant braking level (applied as a step at t_a = 0.1005 s, between output rows)
// while a 500 kg load rides on the cart on a stiff spring (it travels with it). By hand, constant
// deceleration α = M/I = 25 rad/s² and a = F/(m_cart + m_load) = 1500 N / 1.5 t = 1 m/s²:
//   stopping time ω0/α = 4 s, v0/a = 2 s; travel ω0²/(2α) = 200 rad, v0²/(2a) = 2 m (the load the same);
//   energy ½ I ω0² = 10 kJ, ½ (m_cart + m_load) v0² = 3 kJ (the spring's share is negligible);
//   peak power at the application M ω0 = 5 kW, F v0 = 3 kW;
//   temperature (adiabatic disc, C = 1 kJ/K from 20 °C): 20 + 10 kJ / C = 30 °C at the stop and the end.
TEST_P(BrakeSummary, ConstantTorqueStopMatchesTheHandCalculation) {
  Model m = model_of(R"(
bodies:
  wheel: {inertia: 2 kg*m^2, velocity: 100 rad/s}
  cart: {type: translational, mass: 1 t, velocity: 2 m/s}
  load: {type: translational, mass: 500 kg, velocity: 2 m/s}
links:
  mount: {type: spring-damper, between: [cart, load], stiffness: 1e9 N/m, damping: 1e5 N*s/m}
brakes:
  disc: {body: wheel, holding: 60 N*m, braking: 50 N*m, time: 0.1005 s,
         thermal: {heat_capacity: 1 kJ/K, conductance: 0 W/K, ambient: 20 degC}}
  shoe: {body: cart, holding: 2000 N, braking: 1500 N, time: 0.1005 s}
  never: {body: cart, holding: 10 N, time: 9 s}
simulation: {t_end: 5 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-13}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const auto stops = brake_stops(m, r);
  ASSERT_EQ(stops.size(), 3u);
  const BrakeStop& d = stops[0];
  EXPECT_EQ(d.brake, "disc");
  ASSERT_TRUE(d.t_applied && d.t_stopped && d.stopping_time);
  EXPECT_NEAR(*d.t_applied, 0.1005, 1e-12);
  EXPECT_NEAR(*d.stopping_time, 4.0, 1e-8);
  ASSERT_EQ(d.travel.size(), 1u);  // the wheel (no translational body is joined to it)
  EXPECT_EQ(d.travel[0].body, "wheel");
  EXPECT_EQ(d.travel[0].unit, "rad");
  EXPECT_NEAR(d.travel[0].value, 200.0, 1e-6);
  EXPECT_NEAR(d.energy_J, 1e4, 1e-6 * 1e4);
  EXPECT_NEAR(d.peak_power_W, 5000.0, 1e-6 * 5000);
  EXPECT_NEAR(d.t_peak_power, 0.1005, 1e-12);
  ASSERT_TRUE(d.thermal);
  EXPECT_NEAR(d.temperature_end_degC, 30.0, 1e-6);
  EXPECT_NEAR(d.temperature_max_degC, 30.0, 1e-6);
  const BrakeStop& s = stops[1];
  ASSERT_TRUE(s.stopping_time);
  EXPECT_NEAR(*s.stopping_time, 2.0, 1e-6);
  ASSERT_EQ(s.travel.size(), 2u);  // the cart, then the load joined to it by the mount
  EXPECT_EQ(s.travel[0].body, "cart");
  EXPECT_EQ(s.travel[1].body, "load");
  EXPECT_NEAR(s.travel[0].value, 2.0, 1e-5);
  EXPECT_NEAR(s.travel[1].value, 2.0, 1e-5);
  EXPECT_NEAR(s.energy_J, 3000.0, 1e-4 * 3000);
  EXPECT_NEAR(s.peak_power_W, 3000.0, 1e-4 * 3000);
  EXPECT_FALSE(s.thermal);
  EXPECT_FALSE(stops[2].t_applied);  // applied after t_end: no stop
  EXPECT_EQ(stops[2].energy_J, 0.0);
  // summary.json carries the same numbers.
  const auto j = simulation_summary(m, r)["brakes"];
  EXPECT_DOUBLE_EQ(j["disc"]["stopping_time_s"].get<double>(), *d.stopping_time);
  EXPECT_DOUBLE_EQ(j["disc"]["travel"]["wheel"]["value"].get<double>(), d.travel[0].value);
  EXPECT_DOUBLE_EQ(j["disc"]["temperature_end_degC"].get<double>(), d.temperature_end_degC);
  EXPECT_TRUE(j["never"]["applied_at_s"].is_null());
  EXPECT_FALSE(j["never"]["stopped"].get<bool>());
}

}  // namespace
}  // namespace machdyn
