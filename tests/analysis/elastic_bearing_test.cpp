// Links on a gear's massless output flange (model/compile_joint.hpp eliminates the flange; the link's
// deflection becomes δ = q_a/i − w_b q_b + w_e q_e over up to three bodies, elements/link.hpp),
// checked against answers computed here without the library's engine: an RK4 of MSL's
// ElasticBearing equations in reduced coordinates, the generalized eigenproblem of the reduced mass
// and stiffness matrices, the quasi-static load of rigid acceleration in closed form, and central
// differences of the drive system's right-hand side for the link's Jacobian terms.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/analysis/linear_analysis.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/elements/linearize.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/jacobian.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::at;
using test::sci;
using test::series;

Model elastic_bearing() { return load_model(std::string(MACHDYN_SOURCE_DIR) + "/examples/msl/elastic-bearing.yaml"); }

// MSL's ElasticBearing in reduced coordinates (φ_s shaft, φ_h housing, φ_l load); the massless
// flange X follows the IdealGear with its support on the housing, φ_X − φ_h = (φ_s − φ_h)/3, i.e.
// φ_X = φ_s/3 + 2 φ_h/3. MSL's component equations: the Spring's torque τ = c (φ_l − φ_X) acts on
// the gear's flange_b (τ_b = τ), the gear gives τ_a = −τ_b/3 on its flange_a and −τ_a − τ_b on its
// support. With F = c (φ_X − φ_l):
//   J_s φ_s'' = τ_src(t) − F/3,   J_h φ_h'' = −2F/3 − c_h φ_h − d_h φ_h',   J_l φ_l'' = F,
// τ_src = 100 N·m · min(t/5 s, 1); everything at rest at 0 (MSL's fixed start values).
struct BearingReference {
  static constexpr double Js = 1.0, Jh = 5.0, Jl = 50.0, c = 1e3, ch = 1e5, dh = 5.0;
  using V6 = Eigen::Matrix<double, 6, 1>;  // (φ_s, φ_h, φ_l, ω_s, ω_h, ω_l)
  static double torque(double t) { return 100.0 * std::min(t / 5.0, 1.0); }
  static double flange(const V6& y) { return y(0) / 3.0 + 2.0 * y(1) / 3.0; }
  static V6 rhs(double t, const V6& y) {
    const double F = c * (flange(y) - y(2));
    V6 d;
    d << y(3), y(4), y(5), (torque(t) - F / 3.0) / Js, (-2.0 * F / 3.0 - ch * y(1) - dh * y(4)) / Jh, F / Jl;
    return d;
  }
};

class ElasticBearing : public ::testing::TestWithParam<IntegratorChoice> {
 protected:
  double tol(double dopri5, double bdf) const { return GetParam() == IntegratorChoice::bdf ? bdf : dopri5; }
};
INSTANTIATE_TEST_SUITE_P(Integrators, ElasticBearing, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

// ---------------------------------------------------------------------------------------------
// Claim: examples/msl/elastic-bearing.yaml (MSL Rotational.Examples.ElasticBearing) follows the
// reduced equations above: angles and speeds of shaft, housing, load and the massless flange, and
// the spring's load, at every 10 ms row over MSL's 10 s. RK4 with h = 5e-5 s (the ramp's kink at
// 5 s on the grid).
TEST_P(ElasticBearing, MslExampleMatchesReducedCoordinates) {
  Model m = elastic_bearing();
  m.simulation.integrator = GetParam();
  ASSERT_EQ(m.dof(), 3);  // the flange is no degree of freedom
  const SimulationResult r = simulate(m);
  using R = BearingReference;
  R::V6 y = R::V6::Zero();
  const double h = 5e-5;
  double e_angle = 0.0, e_speed = 0.0, e_load = 0.0;
  int rows = 0;
  for (int k = 0; k < 200000; ++k) {
    const double t = k * h;
    const R::V6 k1 = R::rhs(t, y), k2 = R::rhs(t + h / 2, y + h / 2 * k1), k3 = R::rhs(t + h / 2, y + h / 2 * k2),
                k4 = R::rhs(t + h, y + h * k3);
    y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    if ((k + 1) % 200 != 0) continue;  // every output row (10 ms)
    const double tn = (k + 1) * h;
    ++rows;
    const double wX = y(3) / 3.0 + 2.0 * y(4) / 3.0;
    e_angle = std::max({e_angle, std::abs(at(r, "shaft.position_rad", tn) - y(0)),
                        std::abs(at(r, "housing.position_rad", tn) - y(1)), std::abs(at(r, "load.position_rad", tn) - y(2)),
                        std::abs(at(r, "flange.position_rad", tn) - R::flange(y))});
    e_speed = std::max({e_speed, std::abs(at(r, "shaft.velocity_rad_s", tn) - y(3)),
                        std::abs(at(r, "housing.velocity_rad_s", tn) - y(4)),
                        std::abs(at(r, "load.velocity_rad_s", tn) - y(5)), std::abs(at(r, "flange.velocity_rad_s", tn) - wX)});
    e_load = std::max(e_load, std::abs(at(r, "spring.load_N_m", tn) - R::c * (R::flange(y) - y(2))));
  }
  EXPECT_EQ(rows, 1000);
  EXPECT_EQ(series(r, "t_s").size(), 1001u);
  EXPECT_LT(e_angle, tol(1e-8, 1e-6)) << "angles: " << e_angle << " rad";
  EXPECT_LT(e_speed, tol(1e-8, 1e-6)) << "speeds: " << e_speed << " rad/s";
  EXPECT_LT(e_load, tol(1e-5, 1e-3)) << "spring load: " << e_load << " N*m";
  RecordProperty("angle_error", sci(e_angle));
  RecordProperty("speed_error", sci(e_speed));
  RecordProperty("load_error", sci(e_load));
  std::printf("ElasticBearing %s: angles %s rad, speeds %s rad/s, spring load %s N*m; load speed at 10 s %.6f rad/s\n",
              GetParam() == IntegratorChoice::bdf ? "bdf" : "dopri5", sci(e_angle).c_str(), sci(e_speed).c_str(),
              sci(e_load).c_str(), y(5));
  // The energy books balance: the source's work = kinetic + elastic energy + the damper's heat.
  EXPECT_NEAR(r.hybrid.energy.residual(), 0.0, 1e-6 * r.hybrid.energy.source_work);
}

// ---------------------------------------------------------------------------------------------
// Claim: a gap on the flange's link (backlash ±5 mrad, gap_start in the middle) follows the same
// reduced equations with the spring's dead-zone law F = c (δ − 0.005) above, c (δ + 0.005) below,
// 0 between (no damper: F is continuous in δ, so the fixed-step RK4, h = 5e-5 s, needs no event
// location); the run's gap events are located on the dense output. Over 3 s.
TEST_P(ElasticBearing, GapOnTheFlangeMatchesReducedCoordinates) {
  Model m = elastic_bearing();
  m.simulation.integrator = GetParam();
  m.simulation.t_end = 3.0;
  Link& l = m.links[0];
  ASSERT_EQ(l.name, "spring");
  l.has_gap = true, l.gap = 0.01, l.gap_start = 0.005;
  const SimulationResult r = simulate(m);
  using R = BearingReference;
  auto rhs = [](double t, const R::V6& y) {
    const double delta = R::flange(y) - y(2);
    const double F = delta > 0.005 ? R::c * (delta - 0.005) : delta < -0.005 ? R::c * (delta + 0.005) : 0.0;
    R::V6 d;
    d << y(3), y(4), y(5), (R::torque(t) - F / 3.0) / R::Js, (-2.0 * F / 3.0 - R::ch * y(1) - R::dh * y(4)) / R::Jh,
        F / R::Jl;
    return d;
  };
  R::V6 y = R::V6::Zero();
  const double h = 5e-5;
  double e_speed = 0.0;
  for (int k = 0; k < 60000; ++k) {
    const double t = k * h;
    const R::V6 k1 = rhs(t, y), k2 = rhs(t + h / 2, y + h / 2 * k1), k3 = rhs(t + h / 2, y + h / 2 * k2),
                k4 = rhs(t + h, y + h * k3);
    y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    if ((k + 1) % 200 != 0) continue;
    const double tn = (k + 1) * h;
    e_speed = std::max({e_speed, std::abs(at(r, "shaft.velocity_rad_s", tn) - y(3)),
                        std::abs(at(r, "housing.velocity_rad_s", tn) - y(4)),
                        std::abs(at(r, "load.velocity_rad_s", tn) - y(5))});
  }
  EXPECT_LT(e_speed, tol(1e-6, 1e-5)) << "speeds: " << e_speed << " rad/s";
  const auto closed = std::count_if(r.hybrid.events.begin(), r.hybrid.events.end(),
                                    [](const ModeEvent& ev) { return ev.kind == "gap_closed" && ev.element == "spring"; });
  EXPECT_GE(closed, 1);  // the gap closes on the dense output (a located event)
  RecordProperty("speed_error", sci(e_speed));
  std::printf("ElasticBearing with a gap %s: speeds %s rad/s, %ld gap closings\n",
              GetParam() == IntegratorChoice::bdf ? "bdf" : "dopri5", sci(e_speed).c_str(), static_cast<long>(closed));
}

// ---------------------------------------------------------------------------------------------
// Claim: the natural frequencies of ElasticBearing are those of the reduced coordinates
// (φ_s, φ_h, φ_l): M = diag(J_s, J_h, J_l), K = c j jᵀ + c_h e_h e_hᵀ with j = (1/3, 2/3, −1) (the
// spring's ∂δ/∂q), one rigid-body mode (shaft and load turning 3 : 1 with the housing at rest).
TEST(ElasticBearingModes, FrequenciesEqualReducedCoordinates) {
  const Model m = elastic_bearing();
  using R = BearingReference;
  const Eigen::Vector3d j(1.0 / 3.0, 2.0 / 3.0, -1.0);
  Eigen::Matrix3d K = R::c * j * j.transpose();
  K(1, 1) += R::ch;
  const Eigen::Matrix3d M = Eigen::Vector3d(R::Js, R::Jh, R::Jl).asDiagonal();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix3d> es(K, M);
  const TopologyModes tm = analyse_topology(m, initial_topology(m));
  EXPECT_EQ(tm.modes.rigid_body_modes, 1);
  ASSERT_EQ(tm.modes.omega.size(), 2);
  EXPECT_LT(std::abs(es.eigenvalues()(0)), 1e-9 * es.eigenvalues()(2));  // the rigid-body mode
  for (int k = 0; k < 2; ++k) {
    const double w = std::sqrt(es.eigenvalues()(k + 1));
    EXPECT_NEAR(tm.modes.omega(k), w, 1e-9 * w);
    std::printf("ElasticBearing mode %d: %.9f rad/s (reduced coordinates %.9f)\n", k + 1, tm.modes.omega(k), w);
  }
}

// ---------------------------------------------------------------------------------------------
// Claim: the quasi-static load of the spring is the load of rigid acceleration. The rigid motion
// (ker K) is φ_h = 0, φ_l = φ_s/3; under the shaft's torque M the drive accelerates as
// α_s = M / (J_s + J_l/9), and the spring alone accelerates the load: F = J_l α_s/3 = 150 M/59
// (J_s = 1, J_l = 50). Checked at both extremes of the run, M = τ_src(t) there.
TEST(ElasticBearingStatic, QuasiStaticLoadIsRigidAcceleration) {
  const SimulationResult r = simulate(elastic_bearing());
  ASSERT_EQ(r.links.size(), 2u);
  const LinkSummary& s = r.links[0];  // spring (the gear became a joint, not a link)
  EXPECT_NEAR(s.static_at_max, 150.0 / 59.0 * BearingReference::torque(s.t_max), 1e-9 * s.static_at_max);
  EXPECT_NEAR(s.static_at_min, 150.0 / 59.0 * BearingReference::torque(s.t_min), 1e-9 * std::max(1.0, s.static_at_max));
  EXPECT_GT(s.max, 0.0);
}

// ---------------------------------------------------------------------------------------------
// Claim: the Jacobian terms of a three-body link (elements/link.hpp: c j jᵀ, d j jᵀ with
// j = (1/i, −w_b, w_e)) equal central differences of the drive system's right-hand side, which
// applies the link's load through its kinematics (−F/i, +F w_b, −F w_e). A spring-damper on the
// flange of a planetary gear's massless ring, at a generic state.
TEST(ThreeBodyLink, JacobianMatchesCentralDifferences) {
  const Model m = test::model_text(R"(
bodies:
  sun: {inertia: 0.5 kg*m^2}
  ring: {inertia: 0 kg*m^2}
  carrier: {inertia: 4 kg*m^2}
  out: {inertia: 2 kg*m^2}
links:
  pg: {type: planetary-gear, sun: sun, ring: ring, carrier: carrier, ratio: 2.5}
  k: {type: spring-damper, between: [out, ring], ratio: 1.7, stiffness: 3e4 N*m/rad, damping: 20 N*m*s/rad}
  m: {type: spring, between: [carrier, ground], stiffness: 5e3 N*m/rad}
)");
  ASSERT_EQ(m.dof(), 3);
  const Link& l = m.links[0];
  EXPECT_GE(l.third, 0);  // the ring's two masters and `out`: three bodies
  DriveSystem sys(m, false);
  const int N = sys.size();
  std::vector<double> y(static_cast<size_t>(N));
  for (int i = 0; i < N; ++i) y[static_cast<size_t>(i)] = 0.3 * std::sin(1.7 * i + 0.4) + 0.1 * i;
  Eigen::SparseMatrix<double> S;
  sys.sparse_jacobian(0.2, y.data(), S);
  const Eigen::MatrixXd J(S), D = test::central_difference_jacobian(sys, 0.2, y);
  const double scale = J.cwiseAbs().maxCoeff();
  EXPECT_LT((J - D).cwiseAbs().maxCoeff(), 1e-7 * scale) << "J\n" << J << "\nD\n" << D;
  // Closed form of the link's rows: δ = q_out/1.7 − q_ring, q_ring = ((1 + z) q_c − q_s)/z.
  const double z = 2.5, i = 1.7;
  const int s = m.body_index("sun"), c = m.body_index("carrier"), o = m.body_index("out");
  Eigen::VectorXd jv = Eigen::VectorXd::Zero(3);
  jv(o) = 1.0 / i, jv(s) = 1.0 / z, jv(c) = -(1.0 + z) / z;
  for (int r = 0; r < 3; ++r)
    for (int col = 0; col < 3; ++col) {
      const double Ir = m.bodies[static_cast<size_t>(r)].inertia;
      const double spring = -3e4 * jv(r) * jv(col) / Ir - (r == c && col == c ? 5e3 / Ir : 0.0);
      EXPECT_NEAR(J(3 + r, col), spring, 1e-9 * scale);
      EXPECT_NEAR(J(3 + r, 3 + col), -20.0 * jv(r) * jv(col) / Ir, 1e-9 * scale);
    }
}

// ---------------------------------------------------------------------------------------------
// Bad input: what stays unsupported on a massless member is located, nothing simulated.
TEST(MasslessMemberErrors, AreLocated) {
  const std::string head =
      "bodies:\n  s: {inertia: 1 kg*m^2}\n  x: {inertia: 0 kg*m^2}\n  h: {inertia: 1 kg*m^2}\n"
      "  u: {inertia: 1 kg*m^2}\n  y: {inertia: 0 kg*m^2}\n  r: {inertia: 1 kg*m^2}\n"
      "links:\n  g: {type: ideal-gear, between: [s, x], ratio: 3, housing: h}\n";
  // (Loads and drives on the flange are supported: massless_load_test.cpp, massless_drive_test.cpp.)
  // A link between two flanges of two gears: four bodies.
  const std::string four = test::compile_errors(
      head + "  g2: {type: ideal-gear, between: [u, y], ratio: 2, housing: r}\n"
             "  k: {type: spring, between: [x, y], stiffness: 1 N*m/rad}\n",
      "bearing.yaml");
  EXPECT_NE(four.find("bearing.yaml:11:3: error: link 'k'"), std::string::npos) << four;
  EXPECT_NE(four.find("would join 4 bodies"), std::string::npos) << four;
  // A link whose ends the gear makes move together (ratio 1: the flange turns with the shaft).
  const std::string zero = test::compile_errors(
      "bodies:\n  s: {inertia: 1 kg*m^2}\n  x: {inertia: 0 kg*m^2}\n  h: {inertia: 1 kg*m^2}\n"
      "links:\n  g: {type: ideal-gear, between: [s, x], ratio: 1, housing: h}\n"
      "  k: {type: spring, between: [x, s], stiffness: 1 N*m/rad}\n",
      "bearing.yaml");
  EXPECT_NE(zero.find("bearing.yaml:7:3: error: link 'k'"), std::string::npos) << zero;
  EXPECT_NE(zero.find("always 0"), std::string::npos) << zero;
  // A rope wound on the flange as a drum.
  const std::string rope = test::compile_errors(
      "bodies:\n  s: {inertia: 1 kg*m^2}\n  x: {inertia: 0 kg*m^2}\n  h: {inertia: 1 kg*m^2}\n"
      "  hook: {type: translational, mass: 100 kg}\n"
      "links:\n  g: {type: ideal-gear, between: [s, x], ratio: 3, housing: h}\n"
      "  k: {type: rope, between: [x, hook], ratio: 2 rad/m, EA: 1e7 N, length: 10 m}\n",
      "bearing.yaml");
  EXPECT_NE(rope.find("bearing.yaml:8:3: error: link 'k'"), std::string::npos) << rope;
  EXPECT_NE(rope.find("a rope wound on a drum on it is not supported"), std::string::npos) << rope;
  // A machine's output point at the link's other end.
  const std::string point = test::compile_errors(
      std::string("bodies:\n") + test::kCrankSliderBody +
          "  s: {inertia: 1 kg*m^2}\n  x: {inertia: 0 kg*m^2}\n  h: {inertia: 1 kg*m^2}\n"
          "links:\n  g: {type: ideal-gear, between: [s, x], ratio: 3, housing: h}\n"
          "  k: {type: spring, between: [crank.piston, x], ratio: 0.1 m/rad, stiffness: 1e3 N*m/rad}\n",
      "bearing.yaml");
  EXPECT_NE(point.find("bearing.yaml:"), std::string::npos) << point;
  EXPECT_NE(point.find("error: link 'k'"), std::string::npos) << point;
  EXPECT_NE(point.find("a machine's output point on it is not supported"), std::string::npos) << point;
}

}  // namespace
}  // namespace machdyn
