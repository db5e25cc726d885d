#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>

#include <Eigen/Dense>
#include <Eigen/Eigenvalues>

#include "machdyn/analysis/modal.hpp"

namespace machdyn {

namespace {

/// Whether every constraint row is q_a − q_b (or q_a alone): a stuck contact's row.
bool merging_rows(const LinearModel& lin) {
  for (const auto& row : lin.G) {
    if (row.size() == 1 && row[0].second == 1.0) continue;
    if (row.size() == 2 && row[0].second == 1.0 && row[1].second == -1.0) continue;
    return false;
  }
  return true;
}

/// T for merging rows: bodies joined by stuck contacts share one coordinate; those joined to the
/// ground (node n) have none.
Eigen::SparseMatrix<double> merge_basis(const LinearModel& lin) {
  const int n = lin.n;
  std::vector<int> parent(static_cast<size_t>(n + 1));
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int x) {
    while (parent[static_cast<size_t>(x)] != x) x = parent[static_cast<size_t>(x)] = parent[static_cast<size_t>(parent[static_cast<size_t>(x)])];
    return x;
  };
  for (const auto& row : lin.G) {
    const int a = find(row[0].first), b = find(row.size() == 2 ? row[1].first : n);
    if (a != b) parent[static_cast<size_t>(std::min(a, b))] = std::max(a, b);  // the ground (n) stays a root
  }
  const int ground = find(n);
  std::vector<int> column(static_cast<size_t>(n + 1), -1);
  std::vector<Eigen::Triplet<double>> t;
  int r = 0;
  for (int i = 0; i < n; ++i) {
    const int root = find(i);
    if (root == ground) continue;
    if (column[static_cast<size_t>(root)] < 0) column[static_cast<size_t>(root)] = r++;
    t.emplace_back(i, column[static_cast<size_t>(root)], 1.0);
  }
  Eigen::SparseMatrix<double> T(n, r);
  T.setFromTriplets(t.begin(), t.end());
  return T;
}

/// T for general rows: the trailing columns of Q in Gᵀ P = Q R span ker G.
Eigen::SparseMatrix<double> qr_basis(const LinearModel& lin) {
  const Eigen::MatrixXd Gt = Eigen::MatrixXd(lin.constraints()).transpose();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(Gt);
  const Eigen::Index rank = qr.rank();
  const Eigen::MatrixXd Q = qr.householderQ();
  return Q.rightCols(lin.n - rank).sparseView(0.0, 0.0);
}

void normalize_sign(Eigen::MatrixXd& S) {
  for (Eigen::Index k = 0; k < S.cols(); ++k) {
    Eigen::Index imax = 0;
    S.col(k).cwiseAbs().maxCoeff(&imax);
    if (S(imax, k) < 0) S.col(k) *= -1.0;
  }
}

/// Above this size a tridiagonal problem gets its eigenvectors by inverse iteration (O(r) each)
/// instead of accumulating the QR rotations (O(r²) each).
constexpr int kSmallTridiagonal = 200;

/// Eigenvalues closer than this (relative to ‖T‖) form a cluster whose vectors are orthogonalized.
/// Inverse iteration alone leaves vectors of eigenvalues a gap g apart orthogonal to about
/// ε‖T‖/g, so 1e-5 bounds that at 2e-11. (LAPACK's dstein takes 1e-3, which makes a long chain,
/// whose spectrum is spaced about ‖T‖/r apart, one cluster: O(r³).)
constexpr double kClusterGap = 1e-5;

/// Eigenvectors of the symmetric tridiagonal T = tridiag(sub, diag, sub) for its eigenvalues λ
/// (ascending, accurate to ε‖T‖) by inverse iteration, as LAPACK's dstein: (T − λ I) x_{k+1} = x_k
/// with an LU of partial pivoting, three steps from a fixed start; the vectors of a cluster
/// (eigenvalues closer than kClusterGap ‖T‖) are orthogonalized against each other at every step
/// (Gram–Schmidt twice).
/// A zero pivot is replaced by ε‖T‖ (λ is an eigenvalue, so T − λ I is singular to working precision).
Eigen::MatrixXd tridiagonal_eigenvectors(const Eigen::VectorXd& d, const Eigen::VectorXd& e, const Eigen::VectorXd& lambda) {
  const Eigen::Index n = d.size();
  double norm = 0.0;
  for (Eigen::Index i = 0; i < n; ++i)
    norm = std::max(norm, std::abs(d(i)) + (i > 0 ? std::abs(e(i - 1)) : 0.0) + (i + 1 < n ? std::abs(e(i)) : 0.0));
  const double tiny = std::max(norm, 1e-300) * std::numeric_limits<double>::epsilon();
  Eigen::MatrixXd X(n, n);
  // LU of T − λ I with row interchanges: U has diagonal u0 and two superdiagonals u1, u2; L the
  // multipliers m and whether rows i, i+1 were swapped.
  Eigen::VectorXd u0(n), u1(n), u2(n), mult(n), x(n);
  std::vector<char> swapped(static_cast<size_t>(n));
  Eigen::Index cluster_start = 0;
  for (Eigen::Index k = 0; k < n; ++k) {
    if (k > 0 && lambda(k) - lambda(k - 1) > kClusterGap * norm) cluster_start = k;
    const double l = lambda(k);
    // Factor.
    double a = d(0) - l, b = n > 1 ? e(0) : 0.0, c = 0.0;  // the current row: a at i, b at i+1, c at i+2
    for (Eigen::Index i = 0; i < n; ++i) {
      if (i + 1 < n) {
        const double sub = e(i), d1 = d(i + 1) - l, e1 = i + 2 < n ? e(i + 1) : 0.0;
        if (std::abs(a) >= std::abs(sub)) {
          swapped[static_cast<size_t>(i)] = 0;
          const double m = a != 0.0 ? sub / a : 0.0;
          mult(i) = m, u0(i) = a, u1(i) = b, u2(i) = c;
          a = d1 - m * b, b = e1 - m * c, c = 0.0;
        } else {
          swapped[static_cast<size_t>(i)] = 1;
          const double m = a / sub;
          mult(i) = m, u0(i) = sub, u1(i) = d1, u2(i) = e1;
          a = b - m * d1, b = c - m * e1, c = 0.0;
        }
      } else {
        u0(i) = a, u1(i) = u2(i) = 0.0;
      }
      if (std::abs(u0(i)) < tiny) u0(i) = u0(i) < 0 ? -tiny : tiny;
    }
    // A start vector with no special symmetry, then three steps.
    for (Eigen::Index i = 0; i < n; ++i) x(i) = 1.0 + static_cast<double>((i * 7919 + k * 104729) % 1009) / 1009.0;
    for (int step = 0; step < 3; ++step) {
      for (Eigen::Index i = 0; i + 1 < n; ++i) {  // L
        if (swapped[static_cast<size_t>(i)]) std::swap(x(i), x(i + 1));
        x(i + 1) -= mult(i) * x(i);
      }
      for (Eigen::Index i = n - 1; i >= 0; --i) {  // U
        double v = x(i);
        if (i + 1 < n) v -= u1(i) * x(i + 1);
        if (i + 2 < n) v -= u2(i) * x(i + 2);
        x(i) = v / u0(i);
      }
      if (k > cluster_start) {  // classical Gram–Schmidt twice (as stable as modified, but BLAS-2)
        const auto Xc = X.middleCols(cluster_start, k - cluster_start);
        for (int pass = 0; pass < 2; ++pass) x.noalias() -= Xc * (Xc.transpose() * x);
      }
      x /= x.norm();
    }
    X.col(k) = x;
  }
  return X;
}

}  // namespace

ReducedModel reduce_constraints(const LinearModel& lin) {
  ReducedModel red;
  red.n = lin.n;
  const bool merge = merging_rows(lin);
  red.T = lin.G.empty() ? [&] {
    Eigen::SparseMatrix<double> I(lin.n, lin.n);
    I.setIdentity();
    return I;
  }() : merge ? merge_basis(lin) : qr_basis(lin);
  red.r = static_cast<int>(red.T.cols());
  red.diagonal_mass = merge;
  const Eigen::SparseMatrix<double> Tt = red.T.transpose();
  Eigen::SparseMatrix<double> M(lin.n, lin.n);
  for (int i = 0; i < lin.n; ++i) M.insert(i, i) = lin.M(i);
  red.M = Tt * M * red.T;
  red.K = Tt * lin.stiffness() * red.T;
  red.D = Tt * lin.damping() * red.T;
  for (int i = 0; i < red.r; ++i)
    if (!(red.M.coeff(i, i) > 0.0))
      throw std::invalid_argument("modal analysis: a body without positive mass or inertia moves freely");
  return red;
}

UndampedModes undamped_modes(const LinearModel& lin) {
  const ReducedModel red = reduce_constraints(lin);
  UndampedModes out;
  out.constraints = static_cast<int>(lin.G.size());
  out.dof = red.r;
  const int r = red.r;
  Eigen::VectorXd lambda;
  Eigen::MatrixXd Psi;  // eigenvectors in z, M_r-normalized
  if (red.diagonal_mass) {
    const Eigen::VectorXd s = Eigen::VectorXd(red.M.diagonal()).cwiseSqrt().cwiseInverse();
    const Eigen::SparseMatrix<double> A = s.asDiagonal() * red.K * s.asDiagonal();
    bool tridiagonal = true;
    for (int k = 0; k < A.outerSize() && tridiagonal; ++k)
      for (Eigen::SparseMatrix<double>::InnerIterator it(A, k); it; ++it)
        if (std::abs(it.row() - it.col()) > 1 && it.value() != 0.0) tridiagonal = false;
    Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es;
    Eigen::MatrixXd X;
    if (tridiagonal && r > 0) {
      Eigen::VectorXd diag(r), sub(std::max(r - 1, 0));
      for (int i = 0; i < r; ++i) diag(i) = A.coeff(i, i);
      for (int i = 0; i + 1 < r; ++i) sub(i) = A.coeff(i + 1, i);
      if (r <= kSmallTridiagonal) {
        es.computeFromTridiagonal(diag, sub, Eigen::ComputeEigenvectors);
        lambda = es.eigenvalues(), X = es.eigenvectors();
      } else {
        es.computeFromTridiagonal(diag, sub, Eigen::EigenvaluesOnly);
        lambda = es.eigenvalues();
        X = tridiagonal_eigenvectors(diag, sub, lambda);
      }
    } else if (r > 0) {
      es.compute(Eigen::MatrixXd(A));
      lambda = es.eigenvalues(), X = es.eigenvectors();
    }
    if (r > 0) Psi = s.asDiagonal() * X;
  } else if (r > 0) {
    Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(Eigen::MatrixXd(red.K), Eigen::MatrixXd(red.M));
    lambda = es.eigenvalues(), Psi = es.eigenvectors();
  }
  const double lmax = lambda.size() ? lambda.cwiseAbs().maxCoeff() : 0.0;
  int rigid = 0;
  while (rigid < lambda.size() && (lmax == 0.0 || lambda(rigid) <= 1e-10 * lmax)) ++rigid;
  out.rigid_body_modes = rigid;
  const Eigen::Index ne = lambda.size() - rigid;
  out.omega = lambda.tail(ne).cwiseSqrt();
  out.shapes = Eigen::MatrixXd(red.T * Psi.rightCols(ne));
  out.rigid_shapes = Eigen::MatrixXd(red.T * Psi.leftCols(rigid));
  if (r == 0) out.shapes.resize(lin.n, 0), out.rigid_shapes.resize(lin.n, 0);
  normalize_sign(out.shapes);
  normalize_sign(out.rigid_shapes);
  return out;
}

DampedModes damped_modes(const LinearModel& lin) {
  const ReducedModel red = reduce_constraints(lin);
  const int r = red.r;
  DampedModes out;
  if (r == 0) return out;
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(2 * r, 2 * r);
  A.topRightCorner(r, r).setIdentity();
  const Eigen::MatrixXd Minv = Eigen::MatrixXd(red.M).inverse();
  A.bottomLeftCorner(r, r) = -Minv * Eigen::MatrixXd(red.K);
  A.bottomRightCorner(r, r) = -Minv * Eigen::MatrixXd(red.D);
  const Eigen::EigenSolver<Eigen::MatrixXd> es(A, true);
  const Eigen::VectorXcd lam = es.eigenvalues();
  const Eigen::MatrixXcd V = es.eigenvectors();
  const double lmax = lam.cwiseAbs().maxCoeff();
  const Eigen::MatrixXcd T = Eigen::MatrixXd(red.T).cast<std::complex<double>>();
  std::vector<DampedMode> osc, real;
  for (Eigen::Index k = 0; k < lam.size(); ++k) {
    const std::complex<double> l = lam(k);
    if (std::abs(l) <= 1e-7 * lmax) {
      ++out.zero_eigenvalues;
      continue;
    }
    // A real root's imaginary part is exactly 0 from the real Schur form; a pair's is not.
    const bool oscillatory = l.imag() != 0.0;
    if (oscillatory && l.imag() < 0) continue;
    DampedMode d;
    d.lambda = l;
    d.oscillatory = oscillatory;
    d.omega_n = std::abs(l);
    d.omega_d = oscillatory ? l.imag() : 0.0;
    d.zeta = oscillatory ? -l.real() / d.omega_n : std::numeric_limits<double>::quiet_NaN();
    d.decay_rate = -l.real();
    d.shape = T * V.col(k).head(r);
    Eigen::Index imax = 0;
    d.shape.cwiseAbs().maxCoeff(&imax);
    if (std::abs(d.shape(imax)) > 0) d.shape /= d.shape(imax);
    (oscillatory ? osc : real).push_back(std::move(d));
  }
  std::sort(osc.begin(), osc.end(), [](const DampedMode& a, const DampedMode& b) { return a.omega_n < b.omega_n; });
  std::sort(real.begin(), real.end(),
            [](const DampedMode& a, const DampedMode& b) { return a.decay_rate < b.decay_rate; });
  out.modes = std::move(osc);
  out.modes.insert(out.modes.end(), real.begin(), real.end());
  return out;
}

}  // namespace machdyn
