#include "machdyn/analysis/static_loads.hpp"

#include <gtest/gtest.h>

#include "machdyn/analysis/modes.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace {

// A free geared chain, a second free group, a grounded group and a damper-only body.
const char* kMixed = R"(bodies:
  A: {inertia: 1.3}
  B: {inertia: 0.4}
  C: {type: translational, mass: 500}
  D: {inertia: 2}
  E: {inertia: 0.7}
  F: {inertia: 0.9}
  G: {inertia: 1.1}
  H: {inertia: 0.5}
links:
  ab: {type: spring, between: [A, B], ratio: 3.5, stiffness: 2e4}
  bc: {type: spring-damper, between: [B, C], ratio: 12 rad/m, stiffness: 3e6 N/m, damping: 10 N*s/m}
  de: {type: spring, between: [D, E], ratio: -2, stiffness: 5e3}
  fg: {type: spring, between: [F, G], stiffness: 7e3}
  g0: {type: spring, between: [G, ground], stiffness: 1e3}
  hd: {type: damper, between: [H, ground], damping: 3}
)";

// Claim: rigid_motions spans ker K exactly: K R = 0 and its size is the modal count of rigid modes.
TEST(StaticLoads, RigidMotionsSpanTheNullSpaceOfK) {
  const Model m = load_model(test::write_temp("mixed.yaml", kMixed));
  const Eigen::MatrixXd R = rigid_motions(m);
  const Modes modes = compute_modes(m);
  EXPECT_EQ(R.cols(), modes.rigid_body_modes);  // groups {A,B,C}, {D,E}, {H}
  EXPECT_EQ(R.cols(), 3);
  EXPECT_LT((stiffness_matrix(m) * R).norm(), 1e-9 * stiffness_matrix(m).norm());
}

// Claim: the O(n) saddle-point particular solution equals the modal one Σ φφᵀ f / ω² (a second
// algorithm) for arbitrary loads.
TEST(StaticLoads, SparseSolutionEqualsModalSolution) {
  const Model m = load_model(test::write_temp("mixed2.yaml", kMixed));
  const Modes modes = compute_modes(m);
  Eigen::VectorXd f(8);
  f << 120, -35, 900, 14, -3, 60, 25, 7;
  const Eigen::VectorXd a = particular_link_loads(m, f);
  const Eigen::VectorXd b = static_link_loads(m, modes, f);
  for (Eigen::Index k = 0; k < a.size(); ++k) EXPECT_NEAR(a(k), b(k), 1e-9 * b.cwiseAbs().maxCoeff()) << k;
}

}  // namespace
}  // namespace machdyn
