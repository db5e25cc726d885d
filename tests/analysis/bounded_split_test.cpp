// The bounded split of a redundantly locked load (analysis/bounded_split.hpp) against an independent
// answer: brute-force enumeration of every active set (each constraint free, at its lower or at its
// upper bound) on random small problems.
#include "machdyn/analysis/bounded_split.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <optional>
#include <random>

namespace machdyn {
namespace {

// The optimum over every face of the box: on a face (a set C clamped at its bounds b_C) the weighted
// least-norm split of the rest, λ_F = W_F (A_F W_F)⁺ (r − A_C b_C), is a candidate when it meets
// A λ = r as well as the unbounded split does and lies within the bounds. The convex problem's optimum
// is the least Σ (λ_i/w_i)² over the candidates (its own face's candidate is it; every candidate is
// feasible); none: no split within the bounds.
std::optional<Eigen::VectorXd> enumerate(const Eigen::MatrixXd& A, const Eigen::VectorXd& r, const Eigen::VectorXd& w,
                                         const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  const Eigen::Index n = A.cols();
  const double res0 = (A * (w.asDiagonal() * (A * w.asDiagonal()).completeOrthogonalDecomposition().solve(r)) - r).norm();
  std::optional<Eigen::VectorXd> best;
  double best_cost = HUGE_VAL;
  int faces = 1;
  for (Eigen::Index i = 0; i < n; ++i) faces *= 3;
  for (int code = 0; code < faces; ++code) {
    Eigen::VectorXd lam = Eigen::VectorXd::Zero(n), wf = w;
    bool ok = true;
    for (Eigen::Index i = 0, c = code; i < n; ++i, c /= 3) {
      const int side = static_cast<int>(c % 3);  // 0 free, 1 at lo, 2 at hi
      if (side == 1) ok = ok && std::isfinite(lo(i)), lam(i) = lo(i), wf(i) = 0.0;
      if (side == 2) ok = ok && std::isfinite(hi(i)), lam(i) = hi(i), wf(i) = 0.0;
    }
    if (!ok) continue;
    const Eigen::VectorXd rr = r - A * lam;
    lam += wf.asDiagonal() * (A * wf.asDiagonal()).completeOrthogonalDecomposition().solve(rr);
    if ((A * lam - r).norm() > res0 + 1e-9 * (1.0 + r.norm())) continue;
    bool inside = true;
    for (Eigen::Index i = 0; i < n; ++i) inside = inside && lam(i) >= lo(i) - 1e-9 && lam(i) <= hi(i) + 1e-9;
    if (!inside) continue;
    const double cost = (lam.array() / w.array()).square().sum();
    if (cost < best_cost) best_cost = cost, best = lam;
  }
  return best;
}

// Claim: on random redundant sets (n = 2…6 stuck constraints on fewer bodies: A = G M⁻¹ Gᵀ of rank
// < n, r = A λ* for a random λ*), with friction bounds ±F, one-sided locks [−F_d, ∞) or (−∞, F_d] and
// unbounded joints, the bounded split is the enumerated optimum within 1e-7 of the load scale, and it
// finds no split exactly when the enumeration finds none.
TEST(BoundedSplit, EqualsTheOptimumOverEveryActiveSet) {
  std::mt19937 gen(27);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int feasible = 0, infeasible = 0, moved = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 2 + trial % 5, bodies = 1 + static_cast<int>(U(gen) * (n - 1));
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n, bodies);
    for (int i = 0; i < n; ++i) {  // a contact between two bodies or from one body to the ground
      const int a = static_cast<int>(U(gen) * bodies), b = static_cast<int>(U(gen) * (bodies + 1)) - 1;
      G(i, a) += 1.0;
      if (b >= 0 && b != a) G(i, b) -= 1.0;
    }
    Eigen::VectorXd im(bodies);
    for (int j = 0; j < bodies; ++j) im(j) = 0.2 + 5.0 * U(gen);
    const Eigen::MatrixXd A = G * im.asDiagonal() * G.transpose();
    Eigen::VectorXd lam_true(n), w(n), lo(n), hi(n);
    for (int i = 0; i < n; ++i) {
      lam_true(i) = 20.0 * (U(gen) - 0.5);
      const double kind = U(gen), F = 0.5 + 10.0 * U(gen);
      if (kind < 0.6) lo(i) = -F, hi(i) = F, w(i) = std::sqrt(F);                    // friction
      else if (kind < 0.75) lo(i) = -0.1 * F, hi(i) = HUGE_VAL, w(i) = 1.0;         // a lock, +
      else if (kind < 0.9) lo(i) = -HUGE_VAL, hi(i) = 0.1 * F, w(i) = 1.0;          // a lock, −
      else lo(i) = -HUGE_VAL, hi(i) = HUGE_VAL, w(i) = 1e3;                          // a joint
    }
    const Eigen::VectorXd r = A * lam_true;
    const auto got = bounded_split(A, r, w, lo, hi);
    const auto want = enumerate(A, r, w, lo, hi);
    ASSERT_EQ(got.has_value(), want.has_value()) << "trial " << trial;
    if (!want) {
      ++infeasible;
      continue;
    }
    ++feasible;
    const Eigen::VectorXd plain = w.asDiagonal() * (A * w.asDiagonal()).completeOrthogonalDecomposition().solve(r);
    if ((plain - *want).cwiseAbs().maxCoeff() > 1e-6) ++moved;
    const double scale = 1.0 + want->cwiseAbs().maxCoeff();
    for (int i = 0; i < n; ++i) {
      EXPECT_NEAR((*got)(i), (*want)(i), 1e-7 * scale) << "trial " << trial << " i " << i;
      EXPECT_GE((*got)(i), lo(i)) << "trial " << trial;
      EXPECT_LE((*got)(i), hi(i)) << "trial " << trial;
    }
    EXPECT_LE((A * *got - r).norm(), 1e-9 * (1.0 + r.norm())) << "trial " << trial;
  }
  // The draw exercises every case: splits moved onto bounds, and sets no split holds.
  EXPECT_GT(moved, 30);
  EXPECT_GT(infeasible, 10);
  EXPECT_GT(feasible, 100);
}

// Claim: a split already within the bounds is the weighted least-norm split itself, bit for bit.
TEST(BoundedSplit, ASplitWithinTheBoundsIsTheWeightedLeastNormSplit) {
  // Two brakes (limits 4 and 9) on one body: A = [1 1; 1 1] (unit inertia), r = 6.5.
  // λ = D (A D)⁺ r with D = diag(2, 3): λ_i ∝ w_i² = F_i, λ = 6.5 (4, 9)/13 = (2, 4.5).
  Eigen::MatrixXd A(2, 2);
  A << 1, 1, 1, 1;
  const Eigen::VectorXd r = Eigen::VectorXd::Constant(2, 6.5), w = Eigen::Vector2d(2.0, 3.0);
  const auto lam = bounded_split(A, r, w, -Eigen::Vector2d(4, 9), Eigen::Vector2d(4, 9));
  ASSERT_TRUE(lam);
  EXPECT_NEAR((*lam)(0), 2.0, 1e-14);
  EXPECT_NEAR((*lam)(1), 4.5, 1e-14);
}

// Claim: a brake (limit 3, weight √3) beside a backstop (weight 1, [0, ∞)) on one body under a load
// of 10: the weighted split 10 (3, 1)/4 = (7.5, 2.5) overloads the brake; the bounded split clamps
// it at 3 and the backstop carries 7; under −2 (against the backstop) the brake carries all of it.
TEST(BoundedSplit, ABrakeBesideABackstopIsClampedAtItsLimit) {
  Eigen::MatrixXd A(2, 2);
  A << 1, 1, 1, 1;
  const Eigen::Vector2d w(std::sqrt(3.0), 1.0), lo(-3.0, 0.0), hi(3.0, HUGE_VAL);
  auto lam = bounded_split(A, Eigen::Vector2d(10, 10), w, lo, hi);
  ASSERT_TRUE(lam);
  EXPECT_NEAR((*lam)(0), 3.0, 1e-12);
  EXPECT_NEAR((*lam)(1), 7.0, 1e-12);
  lam = bounded_split(A, Eigen::Vector2d(-2, -2), w, lo, hi);
  ASSERT_TRUE(lam);
  EXPECT_NEAR((*lam)(0), -2.0, 1e-12);
  EXPECT_NEAR((*lam)(1), 0.0, 1e-12);
  EXPECT_FALSE(bounded_split(A, Eigen::Vector2d(-4, -4), w, lo, hi));  // beyond the brake, against the lock
}

}  // namespace
}  // namespace machdyn
