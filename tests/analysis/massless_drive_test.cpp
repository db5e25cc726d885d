// Drives on a gear's massless member (model.hpp: Drive with two bodies): compile eliminates the
// planetary gear's ring without inertia, q_r = c_s q_s + c_c q_c, and an element with states of its
// own on the ring sees ω_r and acts on the sun and the carrier as c_s M and c_c M (virtual work
// M δq_r), as a load does. Checked against answers computed here without the library's engine: an
// RK4 of the reduced equations, central differences of the right-hand side for the Jacobian, the
// linear terms spread by hand.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>
#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/analysis/extra_outputs.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/elements/linearize.hpp"
#include "support/jacobian.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::at;

// Planetary gear z = 2.5 (ω_s + z ω_r − (1 + z) ω_c = 0), the ring without inertia:
//   ω_r = c_s ω_s + c_c ω_c,   c_s = −1/z,   c_c = (1 + z)/z.
constexpr double kZ = 2.5, kJs = 0.5, kJc = 4.0;
constexpr double kCs = -1.0 / kZ, kCc = (1.0 + kZ) / kZ;

std::string planetary(const std::string& drives) {
  return "bodies:\n  sun: {inertia: 0.5 kg*m^2, velocity: 2 rad/s}\n  ring: {inertia: 0 kg*m^2}\n"
         "  carrier: {inertia: 4 kg*m^2, velocity: 1 rad/s}\n"
         "links:\n  pg: {type: planetary-gear, sun: sun, ring: ring, carrier: carrier, ratio: 2.5}\n"
         "loads:\n  Ms: {type: constant, body: sun, value: 5 N*m}\n"
         "drives:\n" + drives + "simulation: {t_end: 1 s, dt_out: 0.01 s, rtol: 1e-10, atol: 1e-12}\n";
}

const char* kMotor = "  motor: {type: dc-motor, body: ring, resistance: 2 ohm, inductance: 50 mH, motor_constant: "
                     "0.8 V*s/rad, voltage: 100 V}\n";

class MasslessDrive : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, MasslessDrive, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

// Claim: a DC motor (R = 2 Ω, L = 50 mH, k = 0.8, 100 V) on the ring drives the reduced system
//   J_s ω_s' = M_s + c_s k i,   J_c ω_c' = c_c k i,   L i' = u − R i − k ω_r,   ω_r = c_s ω_s + c_c ω_c
// (M_s = 5 N·m on the sun). RK4 of these equations (h = 1e-5 s) vs the run at every 10 ms row: the
// speeds, the current, the ring's speed, the motor's power M ω_r, the joint's torque on the ring −M
// (the ring's torque balance: the gear holds what the motor puts on it), and the motor's heat
// ∫ R i² dt (within 1e-6 relative on dopri5, 1e-5 on bdf); the energy books balance.
TEST_P(MasslessDrive, DcMotorOnRingMatchesReducedCoordinates) {
  Model m = test::model_text(planetary(kMotor));
  m.simulation.integrator = GetParam();
  ASSERT_EQ(m.dof(), 2);
  SimulateOptions books;
  books.event_driven = true;
  const SimulationResult r = simulate(m, books, output_selection({"power", "heat"}));
  const double R = 2.0, L = 0.05, k = 0.8, u = 100.0, Ms = 5.0, h = 1e-5;
  using S = std::array<double, 4>;  // (ω_s, ω_c, i, Q)
  auto f = [&](const S& z) {
    const double wr = kCs * z[0] + kCc * z[1], M = k * z[2];
    return S{(Ms + kCs * M) / kJs, kCc * M / kJc, (u - R * z[2] - k * wr) / L, R * z[2] * z[2]};
  };
  auto add = [](const S& a, double c, const S& b) {
    S o{};
    for (size_t j = 0; j < 4; ++j) o[j] = a[j] + c * b[j];
    return o;
  };
  S z{2.0, 1.0, 0.0, 0.0};
  double e_w = 0.0, e_i = 0.0, e_p = 0.0, e_tau = 0.0, e_q = 0.0, scale_p = 0.0;
  int rows = 0;
  for (int n = 0; n < 100000; ++n) {
    const S k1 = f(z), k2 = f(add(z, h / 2, k1)), k3 = f(add(z, h / 2, k2)), k4 = f(add(z, h, k3));
    for (size_t j = 0; j < 4; ++j) z[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
    if ((n + 1) % 1000 != 0) continue;
    const double t = (n + 1) * h, wr = kCs * z[0] + kCc * z[1], M = k * z[2];
    ++rows;
    e_w = std::max({e_w, std::abs(at(r, "sun.velocity_rad_s", t) - z[0]), std::abs(at(r, "carrier.velocity_rad_s", t) - z[1]),
                    std::abs(at(r, "ring.velocity_rad_s", t) - wr)});
    e_i = std::max(e_i, std::abs(at(r, "motor.current_A", t) - z[2]));
    e_p = std::max(e_p, std::abs(at(r, "motor.power_W", t) - M * wr));
    scale_p = std::max(scale_p, std::abs(M * wr));
    e_tau = std::max(e_tau, std::abs(at(r, "pg.torque_ring_N_m", t) + M));
    e_q = std::max(e_q, std::abs(at(r, "motor.heat_J", t) - z[3]));
  }
  EXPECT_EQ(rows, 100);
  const double tol = GetParam() == IntegratorChoice::bdf ? 1e-5 : 1e-6;
  EXPECT_GT(std::abs(z[2]), 1.0);  // the motor drives
  EXPECT_LT(e_w, tol * std::abs(z[0])) << "speeds " << e_w;
  EXPECT_LT(e_i, tol * 50.0) << "current " << e_i;  // of the stall current u/R
  EXPECT_LT(e_p, tol * scale_p) << "power " << e_p;
  EXPECT_LT(e_tau, tol * 0.8 * 50.0) << "ring torque " << e_tau;
  EXPECT_LT(e_q, tol * z[3]) << "heat " << e_q;
  const EnergyBalance& E = r.hybrid.energy;
  EXPECT_NEAR(E.residual(), 0.0, 1e-6 * std::abs(E.source_work));
  std::printf("MasslessDrive %s: speeds %.2e rad/s, current %.2e A, ring torque %.2e N*m, heat %.2e J\n",
              GetParam() == IntegratorChoice::bdf ? "bdf" : "dopri5", e_w, e_i, e_tau, e_q);
}

// Claim: the Jacobian of a drive on the ring (f_i = c_i M(ω_r, x), x' = g(ω_r, x)) is
// ∂f_i/∂v_j = c_i c_j ∂M/∂ω, ∂f_i/∂x = c_i ∂M/∂x, ∂x'/∂v_j = c_j ∂g/∂ω: equal to central differences
// of the drive system's right-hand side at a generic state, for a DC motor and a speed drive.
TEST(MasslessDriveJacobian, MatchesCentralDifferences) {
  for (const char* d : {kMotor, "  sd: {type: speed-drive, body: ring, reference: 3 rad/s, gain: 20 N*m*s/rad, "
                                "integral_time: 0.5 s, torque_limit: 1000 N*m, rise_time: 20 ms}\n"}) {
    const Model m = test::model_text(planetary(d));
    DriveSystem sys(m, false);
    const int N = sys.size();
    std::vector<double> y(static_cast<size_t>(N));
    for (int i = 0; i < N; ++i) y[static_cast<size_t>(i)] = 0.3 * std::sin(1.7 * i + 0.4) + 0.1 * i;
    Eigen::SparseMatrix<double> S;
    sys.sparse_jacobian(0.2, y.data(), S);
    const Eigen::MatrixXd J(S), D = test::central_difference_jacobian(sys, 0.2, y);
    const double scale = J.cwiseAbs().maxCoeff();
    EXPECT_LT((J - D).cwiseAbs().maxCoeff(), 1e-7 * scale) << d << "J\n" << J << "\nD\n" << D;
    // The motor's entry ∂v_s'/∂v_c = c_s c_c ∂M/∂ω / J_s is 0 for a DC motor (M = k i); ∂v_s'/∂i = c_s k / J_s.
    if (N == 5) {
      EXPECT_NEAR(J(2 + m.body_index("sun"), 4), kCs * 0.8 / kJs, 1e-12);
    }
  }
}

// Claim: the linear model of a DC motor on the ring is its quasi-static damper k²/R at the ring,
// spread as c_i c_j k²/R over the sun and the carrier (the entries computed here by hand).
TEST(MasslessDriveLinear, DamperIsSpreadByTheWeights) {
  const Model m = test::model_text(planetary(kMotor));
  const Eigen::MatrixXd D(linearize(m, initial_topology(m)).damping());
  const double d = 0.8 * 0.8 / 2.0;
  const int s = m.body_index("sun"), c = m.body_index("carrier");
  const double w[2] = {s == 0 ? kCs : kCc, s == 0 ? kCc : kCs};
  ASSERT_EQ(c, 1 - s);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) EXPECT_NEAR(D(i, j), w[i] * w[j] * d, 1e-14) << i << j;
}

}  // namespace
}  // namespace machdyn
