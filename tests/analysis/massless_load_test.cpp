// Loads on a gear's massless member (model.hpp: Load with two bodies): compile eliminates the
// planetary gear's ring without inertia, q_r = c_s q_s + c_c q_c, and a load on the ring acts on the
// sun and the carrier as c_s M and c_c M (virtual work M δq_r), its law reading the ring's own
// q_r and ω_r. Checked against answers computed here without the library's engine: constant
// accelerations in closed form, an RK4 in reduced coordinates for a drag, central differences of
// the right-hand side for the Jacobian.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>
#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/analysis/extra_outputs.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/jacobian.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::at;
using test::series;

// Planetary gear with ratio z = 2.5 (ω_s + z ω_r − (1 + z) ω_c = 0), the ring without inertia:
//   ω_r = c_s ω_s + c_c ω_c,   c_s = −1/z,   c_c = (1 + z)/z.
constexpr double kZ = 2.5, kJs = 0.5, kJc = 4.0;
constexpr double kCs = -1.0 / kZ, kCc = (1.0 + kZ) / kZ;

std::string planetary(const std::string& loads) {
  return "bodies:\n  sun: {inertia: 0.5 kg*m^2, velocity: 2 rad/s}\n  ring: {inertia: 0 kg*m^2}\n"
         "  carrier: {inertia: 4 kg*m^2, velocity: 1 rad/s}\n"
         "links:\n  pg: {type: planetary-gear, sun: sun, ring: ring, carrier: carrier, ratio: 2.5}\n"
         "loads:\n" + loads + "simulation: {t_end: 2 s, dt_out: 0.01 s, rtol: 1e-10, atol: 1e-12}\n";
}

class MasslessLoad : public ::testing::TestWithParam<IntegratorChoice> {
 protected:
  double tol(double dopri5, double bdf) const { return GetParam() == IntegratorChoice::bdf ? bdf : dopri5; }
};
INSTANTIATE_TEST_SUITE_P(Integrators, MasslessLoad, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

// ---------------------------------------------------------------------------------------------
// Claim: constant torques M_r = 30 N·m on the ring and M_s = 5 N·m on the sun give constant
// accelerations. Virtual work M_r δq_r = c_s M_r δq_s + c_c M_r δq_c:
//   J_s α_s = M_s + c_s M_r,   J_c α_c = c_c M_r,   α_r = c_s α_s + c_c α_c,
// so ω = ω0 + α t and q = ω0 t + α t²/2 (q0 = 0; the ring starts at c_s·2 + c_c·1 rad/s). The
// ring's power column is M_r ω_r, and the books' source work is M_s q_s + M_r q_r.
TEST_P(MasslessLoad, ConstantTorqueOnRingGivesClosedFormAccelerations) {
  Model m = test::model_text(planetary("  Mr: {type: constant, body: ring, value: 30 N*m}\n"
                                       "  Ms: {type: constant, body: sun, value: 5 N*m}\n"));
  m.simulation.integrator = GetParam();
  ASSERT_EQ(m.dof(), 2);  // the ring is no degree of freedom
  SimulateOptions books;
  books.event_driven = true;
  const SimulationResult r = simulate(m, books, output_selection({"power"}));
  const double Ms = 5.0, Mr = 30.0;
  const double as = (Ms + kCs * Mr) / kJs, ac = kCc * Mr / kJc, ar = kCs * as + kCc * ac;
  const double ws0 = 2.0, wc0 = 1.0, wr0 = kCs * ws0 + kCc * wc0;
  double e_q = 0.0, e_w = 0.0, e_p = 0.0;
  for (double t : series(r, "t_s")) {
    e_q = std::max({e_q, std::abs(at(r, "sun.position_rad", t) - (ws0 * t + as * t * t / 2)),
                    std::abs(at(r, "carrier.position_rad", t) - (wc0 * t + ac * t * t / 2)),
                    std::abs(at(r, "ring.position_rad", t) - (wr0 * t + ar * t * t / 2))});
    e_w = std::max({e_w, std::abs(at(r, "sun.velocity_rad_s", t) - (ws0 + as * t)),
                    std::abs(at(r, "carrier.velocity_rad_s", t) - (wc0 + ac * t)),
                    std::abs(at(r, "ring.velocity_rad_s", t) - (wr0 + ar * t))});
    e_p = std::max(e_p, std::abs(at(r, "Mr.power_W", t) - Mr * (wr0 + ar * t)));
  }
  EXPECT_LT(e_q, tol(1e-8, 1e-6)) << "angles " << e_q;
  EXPECT_LT(e_w, tol(1e-8, 1e-6)) << "speeds " << e_w;
  EXPECT_LT(e_p, tol(1e-6, 1e-4)) << "ring power " << e_p;
  // The joint's torques on its members (model.hpp: EliminatedJoint) from each member's equation of
  // motion: on the sun J_s α_s − M_s, on the carrier J_c α_c, on the massless ring −M_r.
  for (double t : {0.0, 1.0, 2.0}) {
    EXPECT_NEAR(at(r, "pg.torque_sun_N_m", t), kJs * as - Ms, 1e-9 * Mr);
    EXPECT_NEAR(at(r, "pg.torque_carrier_N_m", t), kJc * ac, 1e-9 * Mr);
    EXPECT_NEAR(at(r, "pg.torque_ring_N_m", t), -Mr, 1e-9 * Mr);
  }
  const double T = 2.0, work = Ms * (ws0 * T + as * T * T / 2) + Mr * (wr0 * T + ar * T * T / 2);
  EXPECT_NEAR(r.hybrid.energy.source_work, work, 1e-6 * std::abs(work));
  EXPECT_NEAR(r.hybrid.energy.residual(), 0.0, 1e-7 * std::abs(work));
  std::printf("MasslessLoad constant %s: angles %.2e rad, speeds %.2e rad/s, power %.2e W, work %.9g J (closed form "
              "%.9g J), residual %.2e J\n", GetParam() == IntegratorChoice::bdf ? "bdf" : "dopri5", e_q, e_w, e_p,
              r.hybrid.energy.source_work, work, r.hybrid.energy.residual());
}

// ---------------------------------------------------------------------------------------------
// Claim: a drag M = −k ω_r|ω_r| (k = 0.4 N·m·s²/rad²) on the ring reads the ring's own speed and
// acts on sun and carrier by the weights, with M_s = 5 N·m on the sun:
//   J_s ω_s' = M_s + c_s M(ω_r),   J_c ω_c' = c_c M(ω_r),   ω_r = c_s ω_s + c_c ω_c.
// RK4 of these equations (h = 1e-4 s) vs the run at every 10 ms row: speeds, the ring's speed and
// the drag's power M ω_r; the books balance (no elastic energy, no losses but the drag's work).
TEST_P(MasslessLoad, DragOnRingMatchesReducedCoordinates) {
  Model m = test::model_text(planetary("  D: {type: drag, body: ring, coefficient: 0.4 N*m*s^2/rad^2}\n"
                                       "  Ms: {type: constant, body: sun, value: 5 N*m}\n"));
  m.simulation.integrator = GetParam();
  SimulateOptions books;
  books.event_driven = true;
  const SimulationResult r = simulate(m, books, output_selection({"power"}));
  const double k = 0.4, Ms = 5.0;
  auto drag = [k](double w) { return -k * w * std::abs(w); };
  auto rhs = [&](const Eigen::Vector2d& w) {
    const double M = drag(kCs * w(0) + kCc * w(1));
    return Eigen::Vector2d((Ms + kCs * M) / kJs, kCc * M / kJc);
  };
  Eigen::Vector2d w(2.0, 1.0);
  const double h = 1e-4;
  double e_w = 0.0, e_p = 0.0;
  int rows = 0;
  for (int n = 0; n < 20000; ++n) {
    const Eigen::Vector2d k1 = rhs(w), k2 = rhs(w + h / 2 * k1), k3 = rhs(w + h / 2 * k2), k4 = rhs(w + h * k3);
    w += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    if ((n + 1) % 100 != 0) continue;
    const double t = (n + 1) * h, wr = kCs * w(0) + kCc * w(1);
    ++rows;
    e_w = std::max({e_w, std::abs(at(r, "sun.velocity_rad_s", t) - w(0)), std::abs(at(r, "carrier.velocity_rad_s", t) - w(1)),
                    std::abs(at(r, "ring.velocity_rad_s", t) - wr)});
    e_p = std::max(e_p, std::abs(at(r, "D.power_W", t) - drag(wr) * wr));
  }
  EXPECT_EQ(rows, 200);
  EXPECT_GT(std::abs(drag(kCs * w(0) + kCc * w(1))), 1.0);  // the drag matters at the end
  EXPECT_LT(e_w, tol(1e-8, 1e-6)) << "speeds " << e_w;
  EXPECT_LT(e_p, tol(1e-7, 1e-5)) << "drag power " << e_p;
  const double dT = 0.5 * kJs * (w(0) * w(0) - 4.0) + 0.5 * kJc * (w(1) * w(1) - 1.0);
  EXPECT_NEAR(r.hybrid.energy.kinetic_end - r.hybrid.energy.kinetic_start, dT, tol(1e-7, 1e-5) * std::abs(dT));
  EXPECT_NEAR(r.hybrid.energy.residual(), 0.0, 1e-6 * std::abs(r.hybrid.energy.source_work));
  std::printf("MasslessLoad drag %s: speeds %.2e rad/s, drag power %.2e W, residual %.2e J\n",
              GetParam() == IntegratorChoice::bdf ? "bdf" : "dopri5", e_w, e_p, r.hybrid.energy.residual());
}

// ---------------------------------------------------------------------------------------------
// Claim: the Jacobian of a load on the ring, f_i = c_i M(q_r, ω_r), is ∂f_i/∂x_j = c_i c_j ∂M/∂x_r
// (model.hpp: Load): equal to central differences of the drive system's right-hand side, for an
// expression in the ring's angle and speed, at a generic state.
TEST(MasslessLoadJacobian, MatchesCentralDifferences) {
  const Model m = test::model_text(planetary("  E: {type: expression, body: ring, expression: '3*sin(phi) - 0.7*omega*abs(omega)'}\n"));
  DriveSystem sys(m, false);
  const int N = sys.size();
  ASSERT_EQ(N, 4);
  std::vector<double> y(static_cast<size_t>(N));
  for (int i = 0; i < N; ++i) y[static_cast<size_t>(i)] = 0.3 * std::sin(1.7 * i + 0.4) + 0.1 * i;
  Eigen::SparseMatrix<double> S;
  sys.sparse_jacobian(0.2, y.data(), S);
  const Eigen::MatrixXd J(S), D = test::central_difference_jacobian(sys, 0.2, y);
  const double scale = J.cwiseAbs().maxCoeff();
  EXPECT_LT((J - D).cwiseAbs().maxCoeff(), 1e-7 * scale) << "J\n" << J << "\nD\n" << D;
  // Closed form: ∂M/∂φ_r = 3 cos φ_r, ∂M/∂ω_r = −1.4 |ω_r|.
  const int s = m.body_index("sun"), c = m.body_index("carrier");
  double cw[2];
  cw[s] = kCs, cw[c] = kCc;
  const double qr = kCs * y[static_cast<size_t>(s)] + kCc * y[static_cast<size_t>(c)];
  const double wr = kCs * y[static_cast<size_t>(2 + s)] + kCc * y[static_cast<size_t>(2 + c)];
  const double I[2] = {m.bodies[0].inertia, m.bodies[1].inertia};
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) {
      EXPECT_NEAR(J(2 + i, j), cw[i] * cw[j] * 3.0 * std::cos(qr) / I[i], 1e-12 * scale);
      EXPECT_NEAR(J(2 + i, 2 + j), cw[i] * cw[j] * -1.4 * std::abs(wr) / I[i], 1e-12 * scale);
    }
}

// ---------------------------------------------------------------------------------------------
// Claim: the torque columns of MSL's ElasticBearing's IdealGear (support on the housing, ratio 3,
// massless flange X): the spring's load F = c (φ_X − φ_l) acts on X as −F, so the gear puts +F on
// X and, by MSL's IdealGear (τ_a = −τ_b/3, support −τ_a − τ_b), −F/3 on the shaft and −2F/3 on the
// housing. F from the reduced-coordinate RK4 of elastic_bearing_test.cpp's equations (h = 5e-5 s,
// the ramp's kink on the grid) over the first 2 s; and the three torques do no work together.
TEST(MasslessJointTorques, ElasticBearingGearFollowsTheSpring) {
  Model m = load_model(std::string(MACHDYN_SOURCE_DIR) + "/examples/msl/elastic-bearing.yaml");
  m.simulation.t_end = 2.0;
  const SimulationResult r = simulate(m);
  constexpr double Js = 1.0, Jh = 5.0, Jl = 50.0, c = 1e3, ch = 1e5, dh = 5.0;
  using V6 = Eigen::Matrix<double, 6, 1>;  // (φ_s, φ_h, φ_l, ω_s, ω_h, ω_l)
  auto flange = [](const V6& y) { return y(0) / 3.0 + 2.0 * y(1) / 3.0; };
  auto rhs = [&](double t, const V6& y) {
    const double F = c * (flange(y) - y(2));
    V6 d;
    d << y(3), y(4), y(5), (100.0 * std::min(t / 5.0, 1.0) - F / 3.0) / Js, (-2.0 * F / 3.0 - ch * y(1) - dh * y(4)) / Jh,
        F / Jl;
    return d;
  };
  V6 y = V6::Zero();
  const double h = 5e-5;
  double e = 0.0, peak = 0.0, work = 0.0;
  for (int k = 0; k < 40000; ++k) {
    const double t = k * h;
    const V6 k1 = rhs(t, y), k2 = rhs(t + h / 2, y + h / 2 * k1), k3 = rhs(t + h / 2, y + h / 2 * k2), k4 = rhs(t + h, y + h * k3);
    y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    if ((k + 1) % 200 != 0) continue;
    const double tn = (k + 1) * h, F = c * (flange(y) - y(2));
    const double ts = at(r, "idealGear.torque_shaft_N_m", tn), tx = at(r, "idealGear.torque_flange_N_m", tn),
                 th = at(r, "idealGear.torque_housing_N_m", tn);
    e = std::max({e, std::abs(ts + F / 3.0), std::abs(tx - F), std::abs(th + 2.0 * F / 3.0)});
    peak = std::max(peak, std::abs(F));
    const double wx = at(r, "flange.velocity_rad_s", tn);
    work = std::max(work, std::abs(ts * at(r, "shaft.velocity_rad_s", tn) + tx * wx + th * at(r, "housing.velocity_rad_s", tn)));
  }
  EXPECT_GT(peak, 1.0);
  EXPECT_LT(e, 1e-5 * peak) << "torques " << e << " N*m, peak spring load " << peak;
  EXPECT_LT(work, 1e-9 * peak) << "power of the gear's torques " << work;
  std::printf("MasslessJointTorques ElasticBearing: torque error %.2e N*m (spring peak %.6g N*m), gear power %.2e W\n", e,
              peak, work);
}

// ---------------------------------------------------------------------------------------------
// Claim: the quasi-static load of a spring on the ring, under a ramp torque T(t) on the ring, is the
// load of rigid acceleration. Over (s, c, o) the spring's δ = q_o/i − q_r has j = ∂δ/∂q =
// (−c_s, −c_c, 1/i); the ring's torque gives f = T (c_s, c_c, 0). Rigid acceleration, jᵀ q̈ = 0 with
// M q̈ = f − j F, gives F = jᵀM⁻¹f / (jᵀM⁻¹j) = −T A / (A + 1/(i² J_o)), A = c_s²/J_s + c_c²/J_c.
// Checked at both extremes of the run, T = T(t) there.
TEST(MasslessLoadStatic, QuasiStaticLoadIsRigidAcceleration) {
  const Model m = test::model_text(R"(
bodies:
  sun: {inertia: 0.5 kg*m^2}
  ring: {inertia: 0 kg*m^2}
  carrier: {inertia: 4 kg*m^2}
  out: {inertia: 2 kg*m^2}
links:
  pg: {type: planetary-gear, sun: sun, ring: ring, carrier: carrier, ratio: 2.5}
  k: {type: spring, between: [out, ring], ratio: 1.7, stiffness: 3e4 N*m/rad}
loads:
  T: {type: ramp, body: ring, value: 40 N*m, end: 0.5 s}
simulation: {t_end: 1 s, dt_out: 1 ms}
)");
  ASSERT_EQ(m.dof(), 3);
  const SimulationResult r = simulate(m);
  ASSERT_EQ(r.links.size(), 1u);
  const LinkSummary& s = r.links[0];
  const double A = kCs * kCs / kJs + kCc * kCc / kJc, factor = -A / (A + 1.0 / (1.7 * 1.7 * 2.0));
  auto T = [](double t) { return 40.0 * std::min(t / 0.5, 1.0); };
  EXPECT_LT(s.min, 0.0);
  EXPECT_NEAR(s.static_at_min, factor * T(s.t_min), 1e-9 * 40.0);
  EXPECT_NEAR(s.static_at_max, factor * T(s.t_max), 1e-9 * 40.0);
  std::printf("MasslessLoadStatic: static at min %.9g N*m (closed form %.9g), at max %.9g (closed form %.9g)\n",
              s.static_at_min, factor * T(s.t_min), s.static_at_max, factor * T(s.t_max));
}

}  // namespace
}  // namespace machdyn
