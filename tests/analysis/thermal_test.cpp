// The lumped thermal model of friction elements (elements/thermal.hpp, `thermal:` of brakes, clutches,
// contacts and freewheels) against closed forms of C dT/dt = P(t) − G (T − T_a), on both integrators,
// and its input errors.
#include "machdyn/elements/thermal.hpp"

#include <cmath>
#include <string>
#include <gtest/gtest.h>

#include "machdyn/analysis/extra_outputs.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/units.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::series;

Model model_of(const std::string& yaml) { return test::model_text(yaml, "th.yaml"); }

std::string compile_error(const std::string& yaml) { return test::compile_errors(yaml, "th.yaml"); }

class ThermalIntegrators : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, ThermalIntegrators,
                         ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

// A brake of constant braking torque M_b = 8 N·m stops a flywheel (I = 2 kg·m², ω0 = 10 rad/s) at
// t_s = I ω0 / M_b = 2.5 s: while it slides P(s) = M_b (ω0 − α s), α = M_b / I = 4 rad/s², then P = 0.
// Its disc (C = 50 J/K, G = 2 W/K, τ = C/G = 25 s) starts at T0 = 30 °C in air at T_a = 20 °C.
// Variation of constants, E(t) = 1 − e^{−t/τ}:
//   ∫₀ᵗ e^{−(t−s)/τ} ds = τ E,   ∫₀ᵗ s e^{−(t−s)/τ} ds = τ t − τ² E   (substitute u = t − s)
//   T(t) = T_a + (T0 − T_a) e^{−t/τ} + (M_b/C) [ω0 τ E − α (τ t − τ² E)]        (t ≤ t_s)
//   T(t) = T_a + (T(t_s) − T_a) e^{−(t − t_s)/τ}                                 (t ≥ t_s)
TEST_P(ThermalIntegrators, BrakeDiscTemperatureFollowsTheClosedForm) {
  Model m = model_of(R"(
bodies: {w: {inertia: 2, velocity: 10 rad/s}}
brakes:
  B:
    body: w
    holding: 10 N*m
    braking: 8 N*m
    thermal: {heat_capacity: 50 J/K, conductance: 2 W/K, ambient: 20 degC, initial: 303.15 K}
simulation: {t_end: 6 s, dt_out: 0.01 s, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const auto &t = series(r, "t_s"), &T = series(r, "B.temperature_degC");
  ASSERT_EQ(t.size(), 601u);
  const double Mb = 8.0, C = 50.0, tau = 25.0, w0 = 10.0, alpha = 4.0, Ta = 20.0, T0 = 30.0, ts = 2.5;
  auto sliding = [&](double s) {
    const double E = 1.0 - std::exp(-s / tau);
    return Ta + (T0 - Ta) * std::exp(-s / tau) + Mb / C * (w0 * tau * E - alpha * (tau * s - tau * tau * E));
  };
  double worst = 0.0;
  for (size_t k = 0; k < t.size(); ++k) {
    const double expected = t[k] <= ts ? sliding(t[k]) : Ta + (sliding(ts) - Ta) * std::exp(-(t[k] - ts) / tau);
    worst = std::max(worst, std::abs(T[k] - expected));
  }
  EXPECT_LT(worst, 1e-8) << "largest deviation from the closed form, K";
  EXPECT_NEAR(T.front(), 30.0, 1e-12);
  // Cooling after the stop: the excess decays with τ (the column keeps falling towards T_a).
  EXPECT_LT(T.back(), sliding(ts));
  EXPECT_GT(T.back(), Ta);
}

// Adiabatic (no `conductance`): the disc keeps all the heat, T(t_end) = T0 + ½ I ω0² / C, here with a
// clutch: two flywheels (I = 1 kg·m² each, 20 and 0 rad/s) end at the common speed 10 rad/s and the
// clutch turns ½·1·20² − 2·½·1·10² = 100 J into heat; C = 25 J/K: +4 K. The heat column agrees.
TEST_P(ThermalIntegrators, AdiabaticClutchKeepsTheDissipatedEnergy) {
  Model m = model_of(R"(
bodies: {a: {inertia: 1, velocity: 20 rad/s}, b: {inertia: 1}}
clutches:
  K:
    between: [a, b]
    normal_force: 1000 N
    mu_s: 0.3
    mu_k: 0.25
    radius: 0.02 m
    thermal: {heat_capacity: 25 J/K, ambient: 15 degC}
simulation: {t_end: 3 s, dt_out: 0.01 s, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m, SimulateOptions{}, output_selection({"heat"}));
  EXPECT_NEAR(series(r, "K.temperature_degC").back(), 15.0 + 4.0, 1e-8);
  EXPECT_NEAR(series(r, "K.heat_J").back(), 100.0, 1e-7);
  EXPECT_NEAR(series(r, "a.velocity_rad_s").back(), 10.0, 1e-8);
}

// The law's rate is the equation it integrates: dT/dt = (P − G (T − T_a)) / C, and relax/rise are
// its exact solution pieces (a constant P over h: T_a + P/G + (T − T_a − P/G) e^{−h/τ}, checked
// against relax + the exact integral of the rise term).
// examples/brake-heating.yaml: the brake's heat is the energy books' friction loss (kinetic energy
// of the drive plus the potential energy of the sinking load, a second computation: the books are
// integrated as states of the run), the drive ends at rest, and the disc (C = 5.5 kJ/K, τ = C/G =
// 367 s) ends between T_a + Q e^{−t_end/τ}/C (all heat at t = 0, cooled the longest) and T_a + Q/C.
TEST(ThermalExample, BrakeHeatingDiscWarmsByTheDissipatedEnergy) {
  const Model m = load_model(test::example("brake-heating.yaml"));
  const SimulationResult r = simulate(m, SimulateOptions{}, output_selection({"heat"}));
  const double Q = series(r, "brake.heat_J").back();
  EXPECT_NEAR(Q, r.hybrid.energy.friction_loss, 1e-6 * Q);
  EXPECT_NEAR(series(r, "motor.velocity_rad_s").back(), 0.0, 1e-9);
  const double C = 5500.0, G = 15.0, Ta = 25.0, t_end = 2.0;
  const double rise = series(r, "brake.temperature_degC").back() - Ta;
  EXPECT_GT(rise, Q / C * std::exp(-G * t_end / C));
  EXPECT_LT(rise, Q / C);
  // More than the drive's kinetic energy ½ I_red ω0², I_red = 0.9 + 120/37² + 12000/(16·37)² kg·m²,
  // ω0 = 177.6 rad/s (16.1 kJ): the load sinks on while the brake stops it.
  const double I_red = 0.9 + 120.0 / (37.0 * 37.0) + 12000.0 / (16.0 * 37.0 * 16.0 * 37.0);
  EXPECT_GT(Q, 0.5 * I_red * 177.6 * 177.6);
}

TEST(ThermalLaw, PiecesAreTheExactSolution) {
  const ThermalLaw law(ThermalMass{400.0, 8.0, 290.0, 300.0});
  EXPECT_DOUBLE_EQ(law.rate(300.0, 100.0), (100.0 - 8.0 * 10.0) / 400.0);
  const double h = 7.0, P = 100.0, tau = 50.0;
  const double exact = 290.0 + P / 8.0 + (300.0 - 290.0 - P / 8.0) * std::exp(-h / tau);
  // ∫₀ʰ e^{−(h−s)/τ} P ds / C = P τ (1 − e^{−h/τ}) / C, = rise(P τ (e^{h/τ} − 1), h)
  const double by_pieces = law.relax(300.0, h) + law.rise(P * tau * (std::exp(h / tau) - 1.0), h);
  EXPECT_NEAR(by_pieces, exact, 1e-12);
  const ThermalLaw adiabatic(ThermalMass{400.0, 0.0, 290.0, 300.0});
  EXPECT_DOUBLE_EQ(adiabatic.relax(310.0, 1e6), 310.0);
}

TEST(ThermalUnits, TemperaturesNeedTheirUnit) {
  std::string err;
  EXPECT_NEAR(*parse_temperature("20 degC", &err), 293.15, 1e-12);
  EXPECT_NEAR(*parse_temperature("-5 °C", &err), 268.15, 1e-12);
  EXPECT_NEAR(*parse_temperature("300 K", &err), 300.0, 0.0);
  EXPECT_FALSE(parse_temperature("20", &err));
  EXPECT_NE(err.find("with its unit"), std::string::npos) << err;
  EXPECT_FALSE(parse_temperature("20 N", &err));
  EXPECT_FALSE(parse_temperature("-300 degC", &err));
  EXPECT_NE(err.find("absolute zero"), std::string::npos) << err;
  EXPECT_NEAR(*parse_as("4 kJ/K", dim::heat_capacity, &err), 4000.0, 1e-9);
  EXPECT_FALSE(parse_as("4 kJ", dim::heat_capacity, &err));
  EXPECT_NE(err.find("heat capacity (J/K)"), std::string::npos) << err;
}

TEST(ThermalErrors, LocatedMessages) {
  const std::string head = "bodies: {w: {inertia: 2}}\nbrakes:\n  B: {body: w, holding: 10 N*m, thermal: ";
  std::string e = compile_error(head + "{conductance: 2 W/K}}\n");
  EXPECT_NE(e.find("th.yaml:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("heat_capacity"), std::string::npos) << e;
  e = compile_error(head + "{heat_capacity: 50 J/K, ambient: 20}}\n");
  EXPECT_NE(e.find("th.yaml:3:"), std::string::npos) << e;
  EXPECT_NE(e.find("'ambient'"), std::string::npos) << e;
  EXPECT_NE(e.find("20 degC"), std::string::npos) << e;
  e = compile_error(head + "{heat_capacity: 50 J, conductance: -1 W/K}}\n");
  EXPECT_NE(e.find("heat capacity (J/K)"), std::string::npos) << e;
  EXPECT_NE(e.find("conductance"), std::string::npos) << e;
  e = compile_error(head + "{heat_capacity: 50 J/K, colour: red}}\n");
  EXPECT_NE(e.find("colour"), std::string::npos) << e;
  e = compile_error(head + "40 J/K}\n");
  EXPECT_NE(e.find("expected a map"), std::string::npos) << e;
  // A stop has no friction heat of its own to warm a part: `thermal` is not one of its fields.
  e = compile_error("bodies: {x: {mass: 1}}\nstops: {S: {body: x, min: 0 m, thermal: {heat_capacity: 1 J/K}}}\n");
  EXPECT_NE(e.find("thermal"), std::string::npos) << e;
}

}  // namespace
}  // namespace machdyn
