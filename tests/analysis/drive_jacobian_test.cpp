// The analytic Jacobian of the drive system (analysis/drive_system.hpp, used by CVODE BDF) against
// central finite differences of its own right-hand side.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>
#include <Eigen/Core>
#include <gtest/gtest.h>

#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/model/compile.hpp"
#include "support/jacobian.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// ∂f_i/∂y_j ≈ (f_i(y + h e_j) − f_i(y − h e_j)) / 2h with h = 1e-6 (1 + |y_j|): error O(h²) for a
// smooth f, exact up to rounding for the linear chain; compared to 1e-6 of the largest entry.
void expect_jacobian_matches_differences(const Model& m) {
  DriveSystem sys(m, /*energy_books=*/false);
  const int N = sys.size();
  ASSERT_TRUE(sys.has_jacobian());
  std::vector<double> y(static_cast<size_t>(N));
  for (int i = 0; i < N; ++i) y[static_cast<size_t>(i)] = 0.3 * std::sin(1.7 * i + 0.4) + 0.1 * i;  // a generic state
  const double t = 0.37;
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(N, N);
  sys.jacobian(t, y.data(), J);
  const Eigen::MatrixXd D = test::central_difference_jacobian(sys, t, y);
  const double scale = std::max(1.0, J.cwiseAbs().maxCoeff());
  EXPECT_LT((J - D).cwiseAbs().maxCoeff(), 1e-6 * scale) << "J\n" << J << "\nD\n" << D;
  // The sparse form (KLU for large systems) has the same entries, to rounding.
  ASSERT_TRUE(sys.has_sparse_jacobian());
  Eigen::SparseMatrix<double> S;
  sys.sparse_jacobian(t, y.data(), S);
  EXPECT_LT((Eigen::MatrixXd(S) - J).cwiseAbs().maxCoeff(), 1e-14 * scale);
  EXPECT_LE(S.nonZeros(), 3 * N + 8 * static_cast<long>(m.links.size()) + static_cast<long>(m.loads.size()));
}

// Claim: CVODE BDF with the sparse Jacobian (KLU; a chain of 150 masses, 300 states ≥ the sparse
// threshold) gives the link peaks of dopri5 on the same model to 1e-6 of the largest.
TEST(DriveJacobian, SparseBdfMatchesDopri5OnALongChain) {
  std::string yaml = "bodies:\n";
  const int n = 150;
  for (int i = 1; i <= n; ++i) yaml += "  m" + std::to_string(i) + ": {type: translational, mass: 1 kg}\n";
  yaml += "links:\n";
  for (int i = 1; i < n; ++i)
    yaml += "  c" + std::to_string(i) + ": {type: spring-damper, between: [m" + std::to_string(i) + ", m" +
            std::to_string(i + 1) + "], stiffness: 1e4 N/m, damping: 5 N*s/m}\n";
  yaml += "loads:\n  P: {type: constant, body: m1, value: 100 N}\n";
  yaml += "simulation: {t_end: 0.5 s, dt_out: 0.05 s, rtol: 1e-9, atol: 1e-12, integrator: INTEG}\n";
  auto model = [&](const std::string& integ) {
    std::string y2 = yaml;
    y2.replace(y2.find("INTEG"), 5, integ);
    return compile_model(parse_yaml_string(y2, "chain.yaml"), "chain.yaml");
  };
  const SimulationResult a = simulate(model("dopri5")), b = simulate(model("bdf"));
  ASSERT_EQ(b.stats.method, "cvode-bdf");
  double scale = 0, worst = 0;
  for (size_t l = 0; l < a.links.size(); ++l) scale = std::max(scale, std::abs(a.links[l].max));
  for (size_t l = 0; l < a.links.size(); ++l)
    worst = std::max({worst, std::abs(a.links[l].max - b.links[l].max), std::abs(a.links[l].min - b.links[l].min)});
  EXPECT_LT(worst, 1e-6 * scale);
}

// Claim: the Jacobian of the shipped three-mass hoist and the 20-mass chain equals the finite
// difference of f (links with ratios, dampers, constant loads).
TEST(DriveJacobian, ExamplesMatchFiniteDifferences) {
  expect_jacobian_matches_differences(load_model(test::example("hoist-3mass.yaml")));
  expect_jacobian_matches_differences(load_model(test::example("chain-20.yaml")));
}

// Claim: the same with speed-dependent loads (a linear motor characteristic, ∂M/∂ω = −M_s/ω_0), a
// gear ratio, a rope ratio to a translational body and a link to the ground.
TEST(DriveJacobian, SpeedDependentLoadsAndRatiosMatchFiniteDifferences) {
  const Model m = compile_model(parse_yaml_string(R"(
bodies:
  motor: {inertia: 0.5}
  drum: {inertia: 3}
  load: {type: translational, mass: 200}
links:
  gear: {type: spring-damper, between: [motor, drum], ratio: 12, stiffness: 4e4, damping: 30}
  rope: {type: spring-damper, between: [drum, load], ratio: 2.5 rad/m, stiffness: 1e6 N/m, damping: 500 N*s/m}
  hold: {type: spring-damper, between: [load, ground], stiffness: 1e3 N/m, damping: 10 N*s/m}
loads:
  M: {type: motor-linear, body: motor, stall_torque: 300 N*m, no_load_speed: 150 rad/s}
  G: {type: constant, body: load, value: -1962 N}
)", "jac.yaml"), "jac.yaml");
  expect_jacobian_matches_differences(m);
}

}  // namespace
}  // namespace machdyn
