// The brakes' stops of a run (analysis/brake_summary.hpp; summary.json `brakes`, the `simulate`
// printout): a constant-torque stop and a run of two stops against their hand calculations, on both
// integrators.
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
  const auto brakes = brake_summaries(m, r);
  ASSERT_EQ(brakes.size(), 3u);
  EXPECT_EQ(brakes[0].brake, "disc");
  ASSERT_EQ(brakes[0].stops.size(), 1u);
  ASSERT_EQ(brakes[1].stops.size(), 1u);
  const BrakeStop& d = brakes[0].stops[0];
  ASSERT_TRUE(d.stopping_time);
  EXPECT_EQ(d.end, BrakeStop::End::stuck);
  EXPECT_NEAR(d.t_applied, 0.1005, 1e-12);
  EXPECT_NEAR(*d.stopping_time, 4.0, 1e-8);
  ASSERT_EQ(d.travel.size(), 1u);  // the wheel (no translational body is joined to it)
  EXPECT_EQ(d.travel[0].body, "wheel");
  EXPECT_EQ(d.travel[0].unit, "rad");
  EXPECT_NEAR(d.travel[0].value, 200.0, 1e-6);
  EXPECT_NEAR(d.energy_J, 1e4, 1e-6 * 1e4);
  EXPECT_NEAR(d.peak_power_W, 5000.0, 1e-6 * 5000);
  EXPECT_NEAR(d.t_peak_power, 0.1005, 1e-12);
  EXPECT_NEAR(brakes[0].energy_J, d.energy_J, 1e-9 * d.energy_J);  // the run's: this one stop
  ASSERT_TRUE(brakes[0].thermal);
  EXPECT_NEAR(brakes[0].temperature_end_degC, 30.0, 1e-6);
  EXPECT_NEAR(brakes[0].temperature_max_degC, 30.0, 1e-6);
  EXPECT_NEAR(d.temperature_applied_degC, 20.0, 1e-9);
  EXPECT_NEAR(d.temperature_end_degC, 30.0, 1e-6);
  const BrakeStop& s = brakes[1].stops[0];
  ASSERT_TRUE(s.stopping_time);
  EXPECT_NEAR(*s.stopping_time, 2.0, 1e-6);
  ASSERT_EQ(s.travel.size(), 2u);  // the cart, then the load joined to it by the mount
  EXPECT_EQ(s.travel[0].body, "cart");
  EXPECT_EQ(s.travel[1].body, "load");
  EXPECT_NEAR(s.travel[0].value, 2.0, 1e-5);
  EXPECT_NEAR(s.travel[1].value, 2.0, 1e-5);
  EXPECT_NEAR(s.energy_J, 3000.0, 1e-4 * 3000);
  EXPECT_NEAR(s.peak_power_W, 3000.0, 1e-4 * 3000);
  EXPECT_FALSE(brakes[1].thermal);
  EXPECT_TRUE(brakes[2].stops.empty());  // applied after t_end: no stop
  EXPECT_EQ(brakes[2].energy_J, 0.0);
  // summary.json carries the same numbers.
  const auto j = simulation_summary(m, r)["brakes"];
  EXPECT_DOUBLE_EQ(j["disc"]["stops"][0]["stopping_time_s"].get<double>(), *d.stopping_time);
  EXPECT_DOUBLE_EQ(j["disc"]["stops"][0]["travel"]["wheel"]["value"].get<double>(), d.travel[0].value);
  EXPECT_DOUBLE_EQ(j["disc"]["temperature_end_degC"].get<double>(), brakes[0].temperature_end_degC);
  EXPECT_EQ(j["disc"]["stops"][0]["end"], "stuck");
  EXPECT_TRUE(j["never"]["stops"].empty());
}

// Claim: a run of two stops is reported as two. The flywheel I = 2 kg·m² at ω0 = 100 rad/s and the
// 1 t cart (a 500 kg load on it) at v0 = 2 m/s: each brake (constant braking level M = 50 N·m,
// F = 1500 N) is applied at t1 = 0.1005 s, lifted at t2 (before its body stops) and applied again at
// t3, when it stops its body. By hand, with α = M/I = 25 rad/s² and a = F/1.5 t = 1 m/s²:
//   disc, t2 = 1.1005 s: stop 1 lasts 1 s, ω 100 → 75 rad/s, turns 100·1 − 25/2 = 87.5 rad, takes
//     M·87.5 = 4375 J, peak M ω0 = 5000 W at t1, warms its adiabatic disc (C = 1 kJ/K) by 4.375 K;
//     it coasts at 75 rad/s to t3 = 2.1005 s; stop 2 lasts 75/25 = 3 s, turns 75²/50 = 112.5 rad,
//     takes 5625 J (5.625 K), peak M·75 = 3750 W at t3; the run's energy 10 kJ = ½ I ω0².
//   shoe, t2 = 0.6005 s: stop 1 lasts 0.5 s, v 2 → 1.5 m/s, 2·0.5 − 0.125 = 0.875 m (the load the
//     same), 1312.5 J, peak F v0 = 3000 W; t3 = 1.0005 s: stop 2 lasts 1.5 s, 1.5²/2 = 1.125 m,
//     1687.5 J, peak F·1.5 = 2250 W.
TEST_P(BrakeSummary, TwoStopsOfOneRunEachByHand) {
  Model m = model_of(R"(
bodies:
  wheel: {inertia: 2 kg*m^2, velocity: 100 rad/s}
  cart: {type: translational, mass: 1 t, velocity: 2 m/s}
  load: {type: translational, mass: 500 kg, velocity: 2 m/s}
links:
  mount: {type: spring-damper, between: [cart, load], stiffness: 1e9 N/m, damping: 1e5 N*s/m}
brakes:
  disc: {body: wheel, holding: 60 N*m, braking: 50 N*m,
         application: {type: table, points: [[0 s, 0], [0.1005 s, 0], [0.1005 s, 1], [1.1005 s, 1], [1.1005 s, 0],
                                             [2.1005 s, 0], [2.1005 s, 1]]},
         thermal: {heat_capacity: 1 kJ/K, conductance: 0 W/K, ambient: 20 degC}}
  shoe: {body: cart, holding: 2000 N, braking: 1500 N,
         application: {type: table, points: [[0 s, 0], [0.1005 s, 0], [0.1005 s, 1], [0.6005 s, 1], [0.6005 s, 0],
                                             [1.0005 s, 0], [1.0005 s, 1]]}}
simulation: {t_end: 5.5 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-13}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const auto brakes = brake_summaries(m, r);
  ASSERT_EQ(brakes.size(), 2u);
  struct ByHand {
    double t_a, duration, travel, energy, peak;
    BrakeStop::End end;
  };
  const std::vector<std::vector<ByHand>> by_hand = {
      {{0.1005, 1.0, 87.5, 4375.0, 5000.0, BrakeStop::End::released}, {2.1005, 3.0, 112.5, 5625.0, 3750.0, BrakeStop::End::stuck}},
      {{0.1005, 0.5, 0.875, 1312.5, 3000.0, BrakeStop::End::released}, {1.0005, 1.5, 1.125, 1687.5, 2250.0, BrakeStop::End::stuck}}};
  for (size_t b = 0; b < 2; ++b) {
    ASSERT_EQ(brakes[b].stops.size(), 2u) << brakes[b].brake;
    for (size_t k = 0; k < 2; ++k) {
      const BrakeStop& st = brakes[b].stops[k];
      const ByHand& h = by_hand[b][k];
      const std::string what = brakes[b].brake + " stop " + std::to_string(k + 1);
      EXPECT_EQ(st.start, BrakeStop::Start::applied) << what;  // applied to its body moving
      EXPECT_EQ(st.end, h.end) << what;
      EXPECT_NEAR(st.t_applied, h.t_a, 1e-9) << what;
      EXPECT_NEAR(st.t_end - st.t_applied, h.duration, 1e-6) << what;
      EXPECT_EQ(st.stopping_time.has_value(), h.end == BrakeStop::End::stuck) << what;
      ASSERT_FALSE(st.travel.empty()) << what;
      for (const auto& x : st.travel) EXPECT_NEAR(x.value, h.travel, 1e-5 * h.travel) << what << " " << x.body;
      EXPECT_NEAR(st.energy_J, h.energy, 1e-4 * h.energy) << what;
      EXPECT_NEAR(st.peak_power_W, h.peak, 1e-4 * h.peak) << what;
      EXPECT_NEAR(st.t_peak_power, h.t_a, 1e-9) << what;
    }
    EXPECT_NEAR(brakes[b].energy_J, brakes[b].stops[0].energy_J + brakes[b].stops[1].energy_J, 1e-6 * brakes[b].energy_J);
  }
  // The disc's temperature rises: 4.375 K and 5.625 K (adiabatic, C = 1 kJ/K), 30 °C at the end.
  ASSERT_TRUE(brakes[0].thermal);
  EXPECT_NEAR(brakes[0].stops[0].temperature_applied_degC, 20.0, 1e-9);
  EXPECT_NEAR(brakes[0].stops[0].temperature_end_degC - brakes[0].stops[0].temperature_applied_degC, 4.375, 1e-5);
  EXPECT_NEAR(brakes[0].stops[1].temperature_end_degC - brakes[0].stops[1].temperature_applied_degC, 5.625, 1e-5);
  EXPECT_NEAR(brakes[0].temperature_end_degC, 30.0, 1e-6);
  // summary.json and the printout carry each stop.
  const auto j = simulation_summary(m, r)["brakes"];
  ASSERT_EQ(j["disc"]["stops"].size(), 2u);
  EXPECT_EQ(j["disc"]["stops"][0]["end"], "released");
  EXPECT_TRUE(j["disc"]["stops"][0]["stopping_time_s"].is_null());
  EXPECT_DOUBLE_EQ(j["disc"]["stops"][1]["stopping_time_s"].get<double>(), *brakes[0].stops[1].stopping_time);
  EXPECT_NEAR(j["disc"]["stops"][1]["temperature_rise_K"].get<double>(), 5.625, 1e-5);
  const std::string text = brake_stops_text(brakes);
  EXPECT_NE(text.find("brake disc: 2 stops"), std::string::npos) << text;
  EXPECT_NE(text.find("  stop 1: applied at 0.1005 s, released after 1 s"), std::string::npos) << text;
  EXPECT_NE(text.find("  stop 2: applied at 2.1005 s, stopped after 3 s"), std::string::npos) << text;
}

}  // namespace
}  // namespace machdyn
