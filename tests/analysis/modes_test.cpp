#include "machdyn/analysis/modes.hpp"

#include <cmath>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/three_mass_hoist.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// Claim: `modes` on the hoist equals paper 002 eq. 16 within 1e-10 relative.
TEST(Modes, HoistFrequenciesEqualPaper002Eq16) {
  const Model m = load_model(test::example("hoist-3mass.yaml"));
  const Modes modes = compute_modes(m);
  const paper002::ThreeMassHoist h{m.bodies[0].inertia, m.bodies[1].inertia, m.bodies[2].inertia,
                                   m.links[0].c, m.links[1].c, 0, 0};
  const auto w = paper002::natural_frequencies(h);
  ASSERT_EQ(modes.omega.size(), 2);
  EXPECT_EQ(modes.rigid_body_modes, 1);
  EXPECT_NEAR(modes.omega(0), w[0], 1e-10 * w[0]);
  EXPECT_NEAR(modes.omega(1), w[1], 1e-10 * w[1]);
}

// Claim: shapes are mass-normalized (φᵀ M φ = 1, φ_iᵀ M φ_j = 0) and satisfy K φ = ω² M φ.
TEST(Modes, ShapesAreMassNormalizedEigenvectors) {
  const Model m = load_model(test::example("hoist-3mass.yaml"));
  const Modes modes = compute_modes(m);
  const Eigen::MatrixXd K = stiffness_matrix(m);
  const Eigen::MatrixXd M = mass_diagonal(m).asDiagonal();
  const Eigen::MatrixXd G = modes.shapes.transpose() * M * modes.shapes;
  EXPECT_TRUE(G.isApprox(Eigen::MatrixXd::Identity(G.rows(), G.cols()), 1e-12));
  for (Eigen::Index k = 0; k < modes.omega.size(); ++k) {
    const Eigen::VectorXd r = K * modes.shapes.col(k) - modes.omega(k) * modes.omega(k) * M * modes.shapes.col(k);
    EXPECT_LT(r.norm(), 1e-9 * (K * modes.shapes.col(k)).norm());
  }
}

/// A chain of n bodies: neighbours joined by springs through gear ratios, some bodies grounded.
struct Chain {
  std::vector<double> I, ratio, c, ground;  // ground[i] = 0: no ground spring on body i
  std::string yaml() const {
    std::string s = "bodies:\n";
    for (size_t i = 0; i < I.size(); ++i) s += fmt::format("  b{}: {{inertia: {:.17g} kg*m^2}}\n", i, I[i]);
    s += "links:\n";
    for (size_t i = 0; i + 1 < I.size(); ++i)
      s += fmt::format("  k{}: {{type: spring, between: [b{}, b{}], ratio: {:.17g}, stiffness: {:.17g} N*m/rad}}\n",
                       i, i, i + 1, ratio[i], c[i]);
    for (size_t i = 0; i < I.size(); ++i)
      if (ground[i] > 0)
        s += fmt::format("  g{}: {{type: spring, between: [b{}, ground], stiffness: {:.17g} N*m/rad}}\n", i, i, ground[i]);
    return s;
  }
};

Chain make_chain(int n, bool grounded) {
  Chain ch;
  for (int i = 0; i < n; ++i) {
    ch.I.push_back(0.5 + 0.37 * ((i * 7) % 5));
    ch.ground.push_back(grounded && i % 3 == 0 ? 200.0 + 50 * i : 0.0);
    if (i + 1 < n) ch.ratio.push_back(1.0 + 0.5 * (i % 3)), ch.c.push_back(1e3 * (1 + (i * 3) % 4));
  }
  return ch;
}

/// Independent eigen-solution, assembled by hand from the chain's data (not from the library):
/// link i (δ = q_i/r − q_{i+1}) adds c/r² to K_ii, c to K_{i+1,i+1}, −c/r to K_{i,i+1}.
/// A = M^{-1/2} K M^{-1/2} is symmetric tridiagonal; the number of its eigenvalues below x is the
/// number of negative pivots of A − x I (Sturm sequence), so bisection finds each eigenvalue.
std::vector<double> sturm_eigenvalues(const Chain& ch) {
  const size_t n = ch.I.size();
  std::vector<double> Kd(n, 0.0), Ko(n, 0.0), d(n), e(n, 0.0);
  for (size_t i = 0; i < n; ++i) Kd[i] += ch.ground[i];
  for (size_t i = 0; i + 1 < n; ++i) {
    Kd[i] += ch.c[i] / (ch.ratio[i] * ch.ratio[i]);
    Kd[i + 1] += ch.c[i];
    Ko[i] = -ch.c[i] / ch.ratio[i];
  }
  for (size_t i = 0; i < n; ++i) {
    d[i] = Kd[i] / ch.I[i];
    if (i + 1 < n) e[i] = Ko[i] / std::sqrt(ch.I[i] * ch.I[i + 1]);
  }
  auto count_below = [&](double x) {
    int neg = 0;
    double p = 1.0;
    for (size_t i = 0; i < n; ++i) {
      p = d[i] - x - (i ? e[i - 1] * e[i - 1] / p : 0.0);
      if (p == 0.0) p = -1e-300;
      if (p < 0) ++neg;
    }
    return neg;
  };
  double hi = 0;
  for (size_t i = 0; i < n; ++i) hi = std::max(hi, d[i] + std::abs(e[i]) + (i ? std::abs(e[i - 1]) : 0.0));
  std::vector<double> lambda;
  for (size_t k = 0; k < n; ++k) {
    double a = -1e-9 * hi, b = hi * 1.01;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (a + b);
      if (count_below(mid) > static_cast<int>(k)) b = mid;
      else a = mid;
    }
    lambda.push_back(0.5 * (a + b));
  }
  return lambda;
}

class ChainModes : public ::testing::TestWithParam<std::tuple<int, bool>> {};

// Claim: `modes` on chains of 5 and 20 masses, with gear ratios and ground springs, equals an
// independent Sturm-bisection eigen-solution; a free chain has exactly one rigid-body mode.
TEST_P(ChainModes, MatchIndependentSturmBisection) {
  const auto [n, grounded] = GetParam();
  const Chain ch = make_chain(n, grounded);
  const Model m = load_model(test::write_temp(fmt::format("chain{}{}.yaml", n, grounded), ch.yaml()));
  const Modes modes = compute_modes(m);
  const auto lambda = sturm_eigenvalues(ch);
  EXPECT_EQ(modes.rigid_body_modes, grounded ? 0 : 1);
  ASSERT_EQ(modes.omega.size() + modes.rigid_body_modes, n);
  for (Eigen::Index k = 0; k < modes.omega.size(); ++k) {
    const double expected = std::sqrt(lambda[static_cast<size_t>(k + modes.rigid_body_modes)]);
    EXPECT_NEAR(modes.omega(k), expected, 1e-10 * expected) << "mode " << k + 1;
  }
}

INSTANTIATE_TEST_SUITE_P(FiveAndTwenty, ChainModes,
                         ::testing::Combine(::testing::Values(5, 20), ::testing::Bool()));

// Claim: the particular solution of static_link_loads is eq. 22 of paper 002 (M12*, M23*).
TEST(Modes, StaticLinkLoadsEqualPaper002Eq22) {
  const Model m = load_model(test::example("hoist-3mass.yaml"));
  const Modes modes = compute_modes(m);
  Eigen::VectorXd f(3);
  f << 450.0, -270.0, 0.0;
  const Eigen::VectorXd F = static_link_loads(m, modes, f);
  const auto Ms = paper002::particular_loads({0.8, 0.45, 0.25, 2.4e4, 9e3, 450.0, 270.0});
  EXPECT_NEAR(F(0), Ms[0], 1e-10 * Ms[0]);
  EXPECT_NEAR(F(1), Ms[1], 1e-10 * Ms[0]);
}

}  // namespace
}  // namespace machdyn
