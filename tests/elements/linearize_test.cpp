// linearize(): the linear model of one topology, assembled from the elements' own laws, against
// the closed-form natural frequencies of paper 001's travel drive in each of its topologies.
#include <cmath>
#include <Eigen/Dense>
#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "machdyn/elements/linearize.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

/// Elastic frequencies of M q̈ + K q = 0 on G q = 0: with q = N z (N a basis of ker G), the reduced
/// pair (Nᵀ K N, Nᵀ M N). Eigenvalues below 1e-9 of the largest are rigid-body modes, dropped.
std::vector<double> frequencies(const LinearModel& lin) {
  const Eigen::MatrixXd K(lin.stiffness()), M = lin.M.asDiagonal();
  Eigen::MatrixXd N = Eigen::MatrixXd::Identity(lin.n, lin.n);
  if (!lin.G.empty()) N = Eigen::FullPivLU<Eigen::MatrixXd>(Eigen::MatrixXd(lin.constraints())).kernel();
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(N.transpose() * K * N, N.transpose() * M * N);
  std::vector<double> w;
  const double top = es.eigenvalues().cwiseAbs().maxCoeff();
  for (double l : es.eigenvalues())
    if (l > 1e-9 * top) w.push_back(std::sqrt(l));
  return w;
}

// Claim: with the gap closed, the wheels (mk) stuck to the crane (m2) and the crane stuck to the
// ground, only m1 moves on the spring: ω2 = √(c/m1). Rolling without slip (adhesion stuck, W
// sliding, constant kinetic level: no damping): m1 against mk + m2, ω3 = √(c/m1 + c/(mk + m2)).
// Slipping (both sliding): m1 against mk alone, ω4 = √(c/m1 + c/mk). Paper 001; the constraint rows
// come from the stuck contacts and the spring from the closed gap.
TEST(Linearize, TravelDriveTopologiesGivePaperFrequencies) {
  const Model m = load_model(test::example("travel-start.yaml"));
  const double c = 2.0e6, m1 = 3000, mk = 300, m2 = 10000;
  Topology topo;
  topo.gaps = {GapMode::closed_pos};
  topo.contacts = {ContactMode::stuck, ContactMode::stuck};
  auto w = frequencies(linearize(m, topo));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NEAR(w[0], std::sqrt(c / m1), 1e-10 * w[0]);

  topo.contacts = {ContactMode::stuck, ContactMode::slip_pos};
  w = frequencies(linearize(m, topo));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NEAR(w[0], std::sqrt(c / m1 + c / (mk + m2)), 1e-10 * w[0]);

  topo.contacts = {ContactMode::slip_pos, ContactMode::slip_pos};
  w = frequencies(linearize(m, topo));
  ASSERT_EQ(w.size(), 1u);
  EXPECT_NEAR(w[0], std::sqrt(c / m1 + c / mk), 1e-10 * w[0]);

  // An open gap: no spring at all, so no elastic frequency.
  topo.gaps = {GapMode::open};
  EXPECT_TRUE(frequencies(linearize(m, topo)).empty());
}

// Claim: at rest with δ = 0 and gap_start 0 the link sits on its negative flank without pressing,
// so it is open; both contacts are at zero sliding speed, hence stuck, and engaged.
TEST(Linearize, InitialTopologyOfTravelDriveAtRest) {
  const Model m = load_model(test::example("travel-start.yaml"));
  const Topology t = initial_topology(m);
  ASSERT_EQ(t.gaps.size(), 1u);
  EXPECT_EQ(t.gaps[0], GapMode::open);
  EXPECT_EQ(t.contacts, (std::vector<ContactMode>{ContactMode::stuck, ContactMode::stuck}));
  EXPECT_EQ(t.engaged, (std::vector<bool>{true, true}));
}

// Claim: a topology whose sizes do not match the model is refused, not read out of bounds.
TEST(Linearize, MismatchedTopologyThrows) {
  const Model m = load_model(test::example("travel-start.yaml"));
  Topology topo;
  EXPECT_THROW(linearize(m, topo), std::invalid_argument);
}

}  // namespace
}  // namespace machdyn
