// Drives on a body merged into its master by ideal gears (model.hpp: RigidSlave, Drive::ratio): the
// element sees the slave's own speed ω_s = ρ ω_M and puts ρ M on the master, as a load does; the merged
// gear's torque column counts it. Checked against an RK4 of the reduced system written here, and the
// gear torque against the other side's own equation of motion, on both integrators.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::at;

class SlaveDrive : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, SlaveDrive, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

// Claim: a DC motor (R = 2 Ω, L = 50 mH, k = 0.8 V·s/rad, 100 V) on the motor shaft (J1 = 0.5 kg·m²),
// which an ideal gear φ_m = 4 φ_d ties to the drum (J2 = 8 kg·m², the group's master: it comes first;
// load L = −4 N·m), drives a load J3 = 2 kg·m² through a spring c = 1e4 N·m/rad. Reduced to φ_d
// (I = J2 + 16 J1 = 16 kg·m², the motor's torque k i acts as 4 k i, its speed is 4 ω_d):
//   I ω_d' = L + 4 k i − F,   J3 ω_3' = F,   L_ind i' = u − R i − 4 k ω_d,   F = c (φ_d − φ_3).
// The gear's torque on the drum from the drum's own equation J2 ω_d' = τ_B + L − F: τ_B = J2 ω_d' − L + F
// (the column sums the motor's side: its inertia and the drive's torque). RK4 (h = 1e-5 s) vs the run at
// every 10 ms row over 0.5 s: speeds within 1e-6 (dopri5) or 1e-5 (bdf) of their scale, the current,
// the gear torque; the energy books balance.
TEST_P(SlaveDrive, DcMotorOnASlaveMatchesTheReducedSystem) {
  Model m = test::model_text(R"(bodies:
  drum: {inertia: 8 kg*m^2}
  motor: {inertia: 0.5 kg*m^2}
  load: {inertia: 2 kg*m^2}
links:
  G: {type: ideal-gear, between: [motor, drum], ratio: 4}
  shaft: {type: spring, between: [drum, load], stiffness: 1e4 N*m/rad}
loads:
  L: {type: constant, body: drum, value: -4 N*m}
drives:
  dcm: {type: dc-motor, body: motor, resistance: 2 ohm, inductance: 50 mH, motor_constant: 0.8 V*s/rad, voltage: 100 V}
simulation: {t_end: 0.5 s, dt_out: 10 ms, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  ASSERT_EQ(m.dof(), 2);
  ASSERT_EQ(m.merged_gears.size(), 1u);
  SimulateOptions books;
  books.event_driven = true;
  const SimulationResult r = simulate(m, books);
  const double J2 = 8.0, J3 = 2.0, I = 16.0, c = 1e4, Ld = -4.0, R = 2.0, Lind = 0.05, k = 0.8, u = 100.0;
  using S = std::array<double, 5>;  // (φ_d, ω_d, φ_3, ω_3, i)
  auto f = [&](const S& z) {
    const double F = c * (z[0] - z[2]);
    return S{z[1], (Ld + 4.0 * k * z[4] - F) / I, z[3], F / J3, (u - R * z[4] - 4.0 * k * z[1]) / Lind};
  };
  auto add = [](const S& a, double h, const S& b) {
    S o{};
    for (size_t j = 0; j < a.size(); ++j) o[j] = a[j] + h * b[j];
    return o;
  };
  const double h = 1e-5;
  S z{};
  double e_w = 0.0, e_i = 0.0, e_tau = 0.0, w_scale = 0.0, tau_scale = 0.0;
  int rows = 0;
  for (int n = 0; n < 50000; ++n) {
    const S k1 = f(z), k2 = f(add(z, h / 2, k1)), k3 = f(add(z, h / 2, k2)), k4 = f(add(z, h, k3));
    for (size_t j = 0; j < z.size(); ++j) z[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
    if ((n + 1) % 1000 != 0) continue;
    const double t = (n + 1) * h, F = c * (z[0] - z[2]), tau = J2 * f(z)[1] - Ld + F;
    ++rows;
    w_scale = std::max({w_scale, std::abs(4.0 * z[1]), std::abs(z[3])});
    tau_scale = std::max(tau_scale, std::abs(tau));
    e_w = std::max({e_w, std::abs(at(r, "drum.velocity_rad_s", t) - z[1]),
                    std::abs(at(r, "motor.velocity_rad_s", t) - 4.0 * z[1]), std::abs(at(r, "load.velocity_rad_s", t) - z[3])});
    e_i = std::max(e_i, std::abs(at(r, "dcm.current_A", t) - z[4]));
    e_tau = std::max(e_tau, std::abs(at(r, "G.torque_N_m", t) - tau));
  }
  EXPECT_EQ(rows, 50);
  const double tol = GetParam() == IntegratorChoice::bdf ? 1e-5 : 1e-6;
  EXPECT_GT(std::abs(z[4]), 1.0);  // the motor drives
  EXPECT_LT(e_w, tol * w_scale) << "speeds " << e_w;
  EXPECT_LT(e_i, tol * u / R) << "current " << e_i;
  EXPECT_LT(e_tau, tol * tau_scale) << "gear torque " << e_tau;
  EXPECT_NEAR(r.hybrid.energy.residual(), 0.0, 1e-6 * std::abs(r.hybrid.energy.source_work));
  std::printf("SlaveDrive %s: speeds %.2e of %.3g rad/s, current %.2e A, gear torque %.2e of %.3g N*m\n",
              GetParam() == IntegratorChoice::bdf ? "bdf" : "dopri5", e_w, w_scale, e_i, e_tau, tau_scale);
}

// Claim: a drive on a slave of another kind than its master (a translational body merged into a
// rotational one) is refused, located at the drive, naming the master to put it on.
TEST(SlaveDriveCompile, ADriveOnASlaveOfAnotherKindIsALocatedError) {
  const std::string e = test::compile_errors(R"(bodies:
  wheel: {inertia: 1 kg*m^2}
  cart: {type: translational, mass: 1 kg}
links:
  roll: {type: ideal-gear, between: [wheel, cart], ratio: 1 rad/m}
drives:
  dcm: {type: dc-motor, body: cart, resistance: 2 ohm, inductance: 50 mH, motor_constant: 0.8 V*s/m, voltage: 100 V}
)", "slave.yaml");
  EXPECT_NE(e.find("slave.yaml:7:3"), std::string::npos) << e;
  EXPECT_NE(e.find("a translational body on a rotational one"), std::string::npos) << e;
  EXPECT_NE(e.find("put it on 'wheel'"), std::string::npos) << e;
}

}  // namespace
}  // namespace machdyn
