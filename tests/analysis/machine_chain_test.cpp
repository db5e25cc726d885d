// Variable-inertia machines inside elastic chains: motor — shaft — crank-slider, and the 2-DOF
// machine of paper 004 (a load joined to the piston by a spring). Checked by energy balances
// (independent of the equations of motion: a wrong velocity term or a wrong link force breaks
// them), a closed-form linearization, and d'Alembert's balance of paper 004 eq. 5.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/energy.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/model/compile.hpp"
#include "machdyn/model/machine.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::column;

constexpr double kPi = std::numbers::pi;


const std::string kCrank = std::string(test::kCrankSliderBody) +
                           "    piston_force: {against: position, points: [[0, 3000 N], [20 mm, 500 N], [80 mm, 0 N]]}\n";

// Claim: in motor — shaft spring — crank-slider (undamped, constant motor torque M), the energy
// ½ I_m ω_m² + ½ I(φ) ω² + ½ c (q_m − φ)² − M q_m − A_gas(φ) stays at its initial value to 1e-8
// of the largest kinetic energy, with either integrator (BDF uses the finite-difference Jacobian).
// A_gas comes from the 1-DOF crank's energy integral (quadrature, not the ODE).
TEST(MachineChain, MotorShaftCrankConservesEnergy) {
  const std::string chain = std::string("bodies:\n  motor: {inertia: 0.05 kg*m^2, velocity: 100 rad/s}") + kCrank +
                            "    velocity: 100 rad/s\n"
                            "links:\n  shaft: {type: spring, between: [motor, crank], stiffness: 2000 N*m/rad}\n"
                            "loads:\n  M: {type: constant, body: motor, value: 20 N*m}\n"
                            "simulation: {t_end: 0.3 s, dt_out: 0.5 ms, rtol: 1e-11, atol: 1e-12}\n";
  const auto path = test::write_temp("chain.yaml", chain);
  const Model one = load_model(test::write_temp("crank-alone.yaml", std::string("bodies:") + kCrank));
  const EnergyIntegral gas(one);
  for (const char* integ : {"dopri5", "bdf"}) {
    std::vector<std::string> sets = {std::string("simulation.integrator=") + integ};
    if (std::string(integ) == "bdf") sets.insert(sets.end(), {"simulation.rtol=1e-12", "simulation.atol=1e-13"});
    const Model m = load_model(path, sets);
    const SimulationResult r = simulate(m);
    const auto& qm = r.columns[column(r, "motor.position_rad")];
    const auto& wm = r.columns[column(r, "motor.velocity_rad_s")];
    const auto& q = r.columns[column(r, "crank.position_rad")];
    const auto& w = r.columns[column(r, "crank.velocity_rad_s")];
    const auto& I = r.columns[column(r, "crank.inertia_kg_m2")];
    double Tmax = 0, drift = 0;
    auto energy = [&](size_t k) {
      const double d = qm[k] - q[k];
      return 0.5 * 0.05 * wm[k] * wm[k] + 0.5 * I[k] * w[k] * w[k] + 0.5 * 2000 * d * d - 20 * qm[k] - gas.work(q[k]);
    };
    const double E0 = energy(0);
    for (size_t k = 0; k < q.size(); k += 3) {
      Tmax = std::max(Tmax, 0.5 * I[k] * w[k] * w[k] + 0.5 * 0.05 * wm[k] * wm[k]);
      drift = std::max(drift, std::abs(energy(k) - E0));
    }
    EXPECT_LT(drift, 1e-8 * Tmax) << integ;
    EXPECT_GT(*std::max_element(r.columns[column(r, "shaft.load_N_m")].begin(),
                                r.columns[column(r, "shaft.load_N_m")].end()), 1.0);  // the shaft does twist
  }
}

// Claim (paper 004, 2-DOF): a load m joined to the piston by a spring c (δ = s(φ) − x) conserves
// ½ I(φ) ω² + ½ m ẋ² + ½ c δ² − A_gas(φ) to 1e-8 (the force table's kinks limit DOPRI5);
// the link's load is c δ with δ from the piston position.
TEST(MachineChain, LoadOnPistonSpringConservesEnergy) {
  const std::string text = std::string("bodies:") + kCrank +
                           "    velocity: 120 rad/s\n"
                           "  load: {type: translational, mass: 5 kg}\n"
                           "links:\n  rod2: {type: spring, between: [crank.piston, load], stiffness: 2e5 N/m}\n"
                           "simulation: {t_end: 0.2 s, dt_out: 0.2 ms, rtol: 1e-11, atol: 1e-12}\n";
  const Model m = load_model(test::write_temp("two-dof.yaml", text));
  EXPECT_TRUE(m.links[0].a_point);
  const SimulationResult r = simulate(m);
  const auto& q = r.columns[column(r, "crank.position_rad")];
  const auto& w = r.columns[column(r, "crank.velocity_rad_s")];
  const auto& I = r.columns[column(r, "crank.inertia_kg_m2")];
  const auto& s = r.columns[column(r, "crank.piston_m")];
  const auto& x = r.columns[column(r, "load.position_m")];
  const auto& v = r.columns[column(r, "load.velocity_m_s")];
  const auto& F = r.columns[column(r, "rod2.load_N")];
  const Model one = load_model(test::write_temp("crank-alone2.yaml", std::string("bodies:") + kCrank));
  const EnergyIntegral gas(one);
  auto energy = [&](size_t k) {
    const double d = s[k] - x[k];
    return 0.5 * I[k] * w[k] * w[k] + 0.5 * 5 * v[k] * v[k] + 0.5 * 2e5 * d * d - gas.work(q[k]);
  };
  const double E0 = energy(0);
  double drift = 0, Tmax = 0;
  for (size_t k = 0; k < q.size(); k += 2) {
    drift = std::max(drift, std::abs(energy(k) - E0));
    Tmax = std::max(Tmax, 0.5 * I[k] * w[k] * w[k]);
    EXPECT_NEAR(F[k], 2e5 * (s[k] - x[k]), 1e-9 * std::abs(2e5 * 0.08));
  }
  EXPECT_LT(drift, 1e-8 * Tmax);
}

// Claim: modes linearize at the initial position. At φ0 = π/2 the piston's p′ = r (ψ′ = 0 there)
// and with δ0 = 0 the 2-DOF machine has K = c [r², −r; −r, 1], M = diag(I(π/2), m): one rigid-body
// mode and ω² = c (r²/I(π/2) + 1/m).
TEST(MachineChain, ModesLinearizeAtInitialPosition) {
  const CrankSlider c(CrankSlider::Params{0.04, 0.16, 1.2, 0.08, 0.00256, 1.6, 0.08, false});
  double s0, ds, dds, I0, dI;
  c.point(kPi / 2, &s0, &ds, &dds);
  c.inertia(kPi / 2, &I0, &dI);
  const std::string text = std::string("bodies:") + kCrank + "    position: 90 deg\n" +
                           fmt::format("  load: {{type: translational, mass: 5 kg, position: {:.17g} m}}\n", s0) +
                           "links:\n  rod2: {type: spring, between: [crank.piston, load], stiffness: 2e5 N/m}\n";
  const Model m = load_model(test::write_temp("modes2.yaml", text));
  const Modes md = compute_modes(m);
  EXPECT_EQ(md.rigid_body_modes, 1);
  ASSERT_EQ(md.omega.size(), 1);
  EXPECT_NEAR(ds, 0.04, 1e-15);
  EXPECT_NEAR(md.omega(0), std::sqrt(2e5 * (0.04 * 0.04 / I0 + 1.0 / 5)), 1e-9 * md.omega(0));
}

// Claim (paper 004 eq. 5, d'Alembert): the inertia moments of the parts, M_k = −I_k ε − ½ I_k′ ω²,
// balance the applied moments at every output point: Σ M_k + Q_gas(φ) + M_drive = 0.
TEST(MachineOutputs, InertiaMomentsBalanceAppliedMoments) {
  const Model m = load_model(test::example("crank-slider.yaml"));
  const SimulationResult r = simulate(m);
  const auto& q = r.columns[column(r, "crank.position_rad")];
  const auto& Mc = r.columns[column(r, "crank.M_crank_N_m")];
  const auto& Mr = r.columns[column(r, "crank.M_rod_N_m")];
  const auto& Mp = r.columns[column(r, "crank.M_piston_N_m")];
  double worst = 0, scale = 0;
  for (size_t k = 0; k < q.size(); ++k) {
    const double Q = m.bodies[0].machine->force(q[k]) + m.loads[0].value;
    worst = std::max(worst, std::abs(Mc[k] + Mr[k] + Mp[k] + Q));
    scale = std::max(scale, std::abs(Mp[k]));
  }
  EXPECT_LT(worst, 1e-9 * scale);
  EXPECT_GT(scale, 10.0);  // the piston's inertia moment matters in this machine
}

// Claim: the crank's "approximate" switch changes only I(q), and for this λ = 0.25 machine the
// speed histories of the two models differ by less than λ³ relative (they agree to O(λ³)).
TEST(MachineOutputs, ApproximateModelStaysCloseToExact) {
  const SimulationResult a = simulate(load_model(test::example("crank-slider.yaml"), {"simulation.t_end=0.1"}));
  const SimulationResult b = simulate(load_model(test::example("crank-slider.yaml"),
                                                 {"simulation.t_end=0.1", "crank.inertia_model=approximate"}));
  const auto& va = a.columns[column(a, "crank.velocity_rad_s")];
  const auto& vb = b.columns[column(b, "crank.velocity_rad_s")];
  double worst = 0;
  for (size_t k = 0; k < va.size(); ++k) worst = std::max(worst, std::abs(va[k] - vb[k]) / va[k]);
  EXPECT_GT(worst, 0.0);
  EXPECT_LT(worst, 0.25 * 0.25 * 0.25);
}

}  // namespace
}  // namespace machdyn
