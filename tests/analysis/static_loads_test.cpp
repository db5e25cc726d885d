#include "machdyn/analysis/static_loads.hpp"

#include <gtest/gtest.h>

#include "machdyn/analysis/modes.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

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

// Claim: with held elements (constraint rows G) rigid_motions spans ker K ∩ ker G: K R = 0, G R = 0,
// and its size drops by one per independent row that joins or holds a free group. Here a row ties
// the free groups {A,B,C} and {D,E} (v_B = v_D) and a second holds H: one free group is left, and a
// repeated row changes nothing.
TEST(StaticLoads, RigidMotionsWithHeldElementsSpanKerKAndKerG) {
  const Model m = load_model(test::write_temp("mixed3.yaml", kMixed));
  const ConstraintRows G = {{{1, 1.0}, {3, -1.0}}, {{7, 1.0}}, {{7, 2.0}}};
  const Eigen::MatrixXd R = rigid_motions(m, G);
  ASSERT_EQ(R.cols(), 1);
  EXPECT_LT((stiffness_matrix(m) * R).norm(), 1e-9 * stiffness_matrix(m).norm() * R.norm());
  for (const auto& g : G) {
    double u = 0.0;
    for (const auto& [j, w] : g) u += w * R(j, 0);
    EXPECT_NEAR(u, 0.0, 1e-12 * R.norm());
  }
}

// Two free chains A–B and C–D (geared springs); a row v_B − v_C = 0 ties B and C.
const char* kTwoChains = R"(bodies:
  A: {inertia: 1.3}
  B: {inertia: 0.4}
  C: {inertia: 0.9}
  D: {type: translational, mass: 50}
links:
  ab: {type: spring, between: [A, B], ratio: 3.5, stiffness: 2e4}
  cd: {type: spring, between: [C, D], ratio: 12 rad/m, stiffness: 3e6 N/m}
)";
// The same with B and C merged into one body BC (I_B + I_C).
const char* kTied = R"(bodies:
  A: {inertia: 1.3}
  BC: {inertia: 1.3}
  D: {type: translational, mass: 50}
links:
  ab: {type: spring, between: [A, BC], ratio: 3.5, stiffness: 2e4}
  cd: {type: spring, between: [BC, D], ratio: 12 rad/m, stiffness: 3e6 N/m}
)";

// Claim: a row tying two bodies (a stuck clutch) gives the link loads of the model where the two are
// one body carrying both bodies' forces (an independent model through the unconstrained solver), for
// arbitrary loads; a repeated row (two clutches on the same pair) changes nothing.
TEST(StaticLoads, TiedBodiesEqualTheMergedModel) {
  const Model two = load_model(test::write_temp("two.yaml", kTwoChains));
  const Model one = load_model(test::write_temp("tied.yaml", kTied));
  Eigen::VectorXd f(4), f1(3);
  f << 120, -35, 900, 14;
  f1 << 120, -35 + 900, 14;
  const Eigen::VectorXd a = particular_link_loads(two, f, {{{1, 1.0}, {2, -1.0}}});
  const Eigen::VectorXd a2 = particular_link_loads(two, f, {{{1, 1.0}, {2, -1.0}}, {{2, -3.0}, {1, 3.0}}});
  const Eigen::VectorXd b = particular_link_loads(one, f1);
  for (Eigen::Index k = 0; k < b.size(); ++k) {
    EXPECT_NEAR(a(k), b(k), 1e-9 * b.cwiseAbs().maxCoeff()) << k;
    EXPECT_NEAR(a2(k), b(k), 1e-9 * b.cwiseAbs().maxCoeff()) << k;
  }
}

// Claim: rows on one body each (stuck brakes to the ground on B and C) make them supports: K q = f
// by hand. Link ab (δ = q_A/i − q_B) puts −F/i on A: with B held, A's balance f_A − F/i = 0 gives
// F = i f_A. Link cd puts +F on D: with C held, F = −f_D. No rigid motion is left.
TEST(StaticLoads, HeldBodyIsASupport) {
  const Model two = load_model(test::write_temp("two2.yaml", kTwoChains));
  Eigen::VectorXd f(4);
  f << 120, -35, 900, 14;
  const Eigen::VectorXd a = particular_link_loads(two, f, {{{1, 1.0}}, {{2, 1.0}}});
  EXPECT_NEAR(a(0), 3.5 * 120, 1e-9 * 420);
  EXPECT_NEAR(a(1), -14.0, 1e-9 * 14);
}

}  // namespace
}  // namespace machdyn
