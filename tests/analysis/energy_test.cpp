// The energy integral (analysis/energy.hpp) against the published numbers of paper 000, closed
// forms, and time integration; steady running and flywheel sizing.
#include "machdyn/analysis/energy.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/model/compile.hpp"
#include "machdyn/model/machine.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::column;

constexpr double kPi = std::numbers::pi;


// Claim (paper 000, eq. 28): in scheme 1 the speed tends, as β → π, to
// ω1max = √(4 F H (1 + cos β0) / (3 m1 R1² sin β0)) = 8.92 rad/s. Derivation of the closed form:
// A(π) = F H ∫ (1 + cos β)/sin²β dβ = F H cot(β0/2), I(π) = (3/2) m1 R1² (solid disk, the block's
// share (m2/2)R1²(1 + cos β)² vanishes), ω² = 2A/I.
TEST(EnergyPaper000, SchemeOneLimitSpeedIs892) {
  const Model m = load_model(test::example("rolling-wheel-1.yaml"));
  const EnergyResult r = energy_analysis(m);
  ASSERT_TRUE(r.omega_limit.has_value());
  EXPECT_EQ(r.limit_kind, "finite");
  const double F = 200, H = 1, b0 = kPi / 6, m1 = 50, R1 = 0.5;
  const double eq28 = std::sqrt(4 * F * H * (1 + std::cos(b0)) / (3 * m1 * R1 * R1 * std::sin(b0)));
  EXPECT_NEAR(*r.omega_limit, eq28, 1e-9 * eq28);
  EXPECT_NEAR(*r.omega_limit, 8.92, 0.005);  // the published value
  EXPECT_TRUE(r.turning_points.size() == 1 && r.turning_points[0] == 0.0);  // starts at rest, never turns
}

// Claim (paper 000, scheme 2): the wheel turns back at β = π − arctan(3√3/13) = 2.76 rad, after
// x = H (cot β0 − cot β) = 3.079 m (published ≈ 3.1 m); its speed peaks where Q = F(r1 + R1 cos β)
// = 0, β = 2π/3, x = 2/√3 = 1.155 m (published ≈ 1.2 m), independent of ρ; with ρ = 0 the peak is 3.58 rad/s.
// Closed forms: Rt = r2, so x(β) = H(cot β0 − cot β) and A = F H [½ cot β0 + 1/sin β0 − ½ cot β − 1/sin β];
// A = 0 gives the turning angle.
TEST(EnergyPaper000, SchemeTwoTurnsAt276AfterThreeMetres) {
  for (const char* rho : {"0.42", "0", "0.6"}) {
    const Model m = load_model(test::example("rolling-wheel-2.yaml"), {std::string("wheel.rho=") + rho});
    const EnergyResult r = energy_analysis(m);
    const auto& w = dynamic_cast<const RollingWheel&>(*m.bodies[0].machine);
    ASSERT_EQ(r.turning_points.size(), 2u);
    const double beta_t = w.beta(r.turning_points[1]);
    EXPECT_NEAR(beta_t, kPi - std::atan(3 * std::sqrt(3.0) / 13), 1e-10);
    EXPECT_NEAR(beta_t, 2.76, 0.005);
    const double x_t = w.Rr() * r.turning_points[1];
    EXPECT_NEAR(x_t, 1 / std::tan(kPi / 3) - 1 / std::tan(beta_t), 1e-10);
    EXPECT_NEAR(x_t, 3.079, 5e-4);
    EXPECT_NEAR(w.beta(r.q_at_omega_max), 2 * kPi / 3, 1e-7);
    EXPECT_NEAR(w.Rr() * r.q_at_omega_max, 2 / std::sqrt(3.0), 1e-7);
    if (std::string(rho) == "0") {
      EXPECT_NEAR(r.omega_max, 3.58, 0.005);
    }
    // A(β) against the closed form at a few points.
    const EnergyIntegral E(m);
    for (double b : {1.3, 2.0, 2.5}) {
      auto A = [](double x) { return 0.5 / std::tan(x) + 1 / std::sin(x); };
      EXPECT_NEAR(E.work(w.x_of_beta(b) / w.Rr()), 200.0 * (A(kPi / 3) - A(b)), 1e-10 * 200);
    }
  }
}

// Claim (paper 000, scheme 3): the speed grows monotonically without bound and the angular
// acceleration tends to ε = F (R1 − r1)/[m1 (ρ² + r1²) + (m2/2)(R1 − r1)²] (eq. 30), approached
// monotonically in the second half of the run; the energy analysis reports that limit beside
// `unbounded` (to 1e-12 of eq. 30, since at β = π it is exactly Q/I = F g(π)/I(π)).
TEST(EnergyPaper000, SchemeThreeAccelerationTendsToEquation30) {
  const Model m = load_model(test::example("rolling-wheel-3.yaml"));
  const double eq30 = 200 * (0.6 - 0.3) / (50 * (0.42 * 0.42 + 0.3 * 0.3) + 5 * 0.3 * 0.3);
  const EnergyResult e = energy_analysis(m);
  EXPECT_EQ(e.limit_kind, "unbounded");
  ASSERT_TRUE(e.epsilon_limit.has_value());
  EXPECT_NEAR(*e.epsilon_limit, eq30, 1e-12 * eq30);
  // The bounded schemes have no limiting acceleration.
  EXPECT_FALSE(energy_analysis(load_model(test::example("rolling-wheel-1.yaml"))).epsilon_limit.has_value());
  const SimulationResult r = simulate(m);
  const auto& v = r.columns[column(r, "wheel.velocity_rad_s")];
  const auto& eps = r.columns[column(r, "wheel.acceleration_rad_s2")];
  for (size_t k = 1; k < v.size(); ++k) EXPECT_GT(v[k], v[k - 1]);
  for (size_t k = v.size() / 2; k + 1 < v.size(); ++k)
    EXPECT_LT(std::abs(eps[k + 1] - eq30), std::abs(eps[k] - eq30) + 1e-12);
  EXPECT_LT(std::abs(eps.back() - eq30), 2e-3 * eq30);
}

// Claim: time integration (DOPRI5 on I q'' + ½ I′ q'² = Q) and the energy integral (quadrature of
// A(q), eq. 25) are two independent answers; on every example the kinetic energy ½ I(q) q'² of the
// run equals ½ I(q0) ω0² + A(q) to 1e-8 of its largest value at every output point, and away from
// turning points ω itself agrees to 1e-8 relative.
TEST(EnergyIntegral, AgreesWithTimeIntegrationOnEveryExample) {
  for (const char* ex : {"rolling-wheel-1.yaml", "rolling-wheel-2.yaml", "rolling-wheel-3.yaml", "crank-slider.yaml"}) {
    const Model m = load_model(test::example(ex));
    const std::string name = m.bodies[0].name;
    const SimulationResult r = simulate(m);
    const EnergyIntegral E(m);
    const auto& q = r.columns[column(r, name + ".position_rad")];
    const auto& v = r.columns[column(r, name + ".velocity_rad_s")];
    const auto& I = r.columns[column(r, name + ".inertia_kg_m2")];
    double Tmax = 0;
    for (size_t k = 0; k < q.size(); ++k) Tmax = std::max(Tmax, 0.5 * I[k] * v[k] * v[k]);
    const double T0 = 0.5 * m.bodies[0].inertia * m.bodies[0].v0 * m.bodies[0].v0;
    double worst_T = 0, worst_w = 0;
    for (size_t k = 0; k < q.size(); k += 5) {
      const double T_energy = T0 + E.work(q[k]);
      worst_T = std::max(worst_T, std::abs(0.5 * I[k] * v[k] * v[k] - T_energy) / Tmax);
      if (T_energy > 0.05 * Tmax)
        worst_w = std::max(worst_w, std::abs(std::abs(v[k]) - std::sqrt(2 * T_energy / I[k])) / std::abs(v[k]));
    }
    EXPECT_LT(worst_T, 1e-8) << ex;
    EXPECT_LT(worst_w, 1e-8) << ex;
  }
}

// Claim: for a constant inertia I and Q = M0 sin q the steady-running analysis is exact in closed
// form: ωmax² − ωmin² = 2ΔA/I with ΔA = 2 M0, so with ωmean = (ωmax + ωmin)/2,
// δ = (ωmax − ωmin)/ωmean = ΔA/(I ωmean²), and the flywheel for a target δ* is ΔA/(δ* ωmean²) − I.
TEST(SteadyRunning, FlywheelMatchesClosedFormForConstantInertia) {
  const auto path = test::write_temp("flywheel.yaml", R"Y(bodies:
  rotor: {type: inertia-expression, inertia: "0.5", torque: "40*sin(q)", period: 360 deg, velocity: 100 rad/s}
)Y");
  const Model m = load_model(path);
  const SteadyResult s = steady_running(m, 100.0, 0.01);
  EXPECT_NEAR(s.balancing_torque, 0.0, 1e-10);
  EXPECT_NEAR(s.delta, 80.0 / (0.5 * 1e4), 1e-9);
  EXPECT_NEAR(s.flywheel_inertia, 80.0 / (0.01 * 1e4) - 0.5, 1e-8);
  EXPECT_NEAR(s.delta_with_flywheel, 0.01, 1e-10);
  EXPECT_NEAR(0.5 * (s.omega_max_fw + s.omega_min_fw), 100.0, 1e-9);
  EXPECT_NEAR(s.flywheel_estimate, s.flywheel_inertia, 1e-8);  // the classic estimate is exact here
}

// Claim: for the crank-slider the flywheel found brings the speed fluctuation of a time
// simulation to the target (second algorithm: DOPRI5 started on the periodic solution, with the
// flywheel added to the crank's inertia and the balancing torque added to the drive): the run's
// (ωmax − ωmin)/((ωmax + ωmin)/2) is the target within 1e-3 relative (sampling of the output grid).
TEST(SteadyRunning, CrankFlywheelGivesTargetFluctuationInSimulation) {
  const Model m0 = load_model(test::example("crank-slider.yaml"));
  const SteadyResult s = steady_running(m0, 150.0, 0.02);
  EXPECT_GT(s.delta, 0.02);
  EXPECT_GT(s.flywheel_inertia, 0.0);
  const std::vector<std::string> sets = {
      fmt::format("crank.crank_inertia={:.17g}", 0.08 + s.flywheel_inertia),
      fmt::format("drive.value={:.17g}", 24.66 + s.balancing_torque),
      fmt::format("crank.velocity={:.17g}", s.omega_start_fw), "simulation.t_end=0.2", "simulation.dt_out=2e-5"};
  const SimulationResult r = simulate(load_model(test::example("crank-slider.yaml"), sets));
  const auto& v = r.columns[column(r, "crank.velocity_rad_s")];
  const double wmax = *std::max_element(v.begin(), v.end()), wmin = *std::min_element(v.begin(), v.end());
  EXPECT_NEAR((wmax - wmin) / (0.5 * (wmax + wmin)), 0.02, 2e-5);
  EXPECT_NEAR(0.5 * (wmax + wmin), 150.0, 150.0 * 1e-5);
}

}  // namespace
}  // namespace machdyn
