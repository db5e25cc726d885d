#include "machdyn/analysis/bounded_split.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

namespace machdyn {

Eigen::VectorXd nonnegative_least_squares(const Eigen::MatrixXd& E, const Eigen::VectorXd& f, double tol) {
  const Eigen::Index p = E.cols();
  Eigen::VectorXd u = Eigen::VectorXd::Zero(p);
  std::vector<char> passive(static_cast<size_t>(p), 0);
  // The unconstrained least squares over the passive set (the others held at 0).
  auto solve_passive = [&]() {
    std::vector<Eigen::Index> idx;
    for (Eigen::Index j = 0; j < p; ++j)
      if (passive[static_cast<size_t>(j)]) idx.push_back(j);
    Eigen::MatrixXd Ep(E.rows(), static_cast<Eigen::Index>(idx.size()));
    for (size_t c = 0; c < idx.size(); ++c) Ep.col(static_cast<Eigen::Index>(c)) = E.col(idx[c]);
    const Eigen::VectorXd zp = Ep.completeOrthogonalDecomposition().solve(f);
    Eigen::VectorXd z = Eigen::VectorXd::Zero(p);
    for (size_t c = 0; c < idx.size(); ++c) z(idx[c]) = zp(static_cast<Eigen::Index>(c));
    return z;
  };
  // Each outer round frees one clamped constraint; the inner rounds clamp again those that cross 0.
  // Finite in exact arithmetic; the cap guards against cycling on rounding.
  for (Eigen::Index outer = 0; outer < 3 * p + 3; ++outer) {
    const Eigen::VectorXd g = E.transpose() * (f - E * u);  // −gradient: the clamped ones' multipliers
    Eigen::Index jmax = -1;
    for (Eigen::Index j = 0; j < p; ++j)
      if (!passive[static_cast<size_t>(j)] && g(j) > tol && (jmax < 0 || g(j) > g(jmax))) jmax = j;
    if (jmax < 0) break;
    passive[static_cast<size_t>(jmax)] = 1;
    for (Eigen::Index inner = 0; inner <= p; ++inner) {
      const Eigen::VectorXd z = solve_passive();
      bool positive = true;
      for (Eigen::Index j = 0; j < p; ++j)
        if (passive[static_cast<size_t>(j)] && z(j) <= 0.0) positive = false;
      if (positive) {
        u = z;
        break;
      }
      // Step from u towards z as far as every passive one stays ≥ 0, and clamp those that reach 0.
      double alpha = 1.0;
      for (Eigen::Index j = 0; j < p; ++j)
        if (passive[static_cast<size_t>(j)] && z(j) <= 0.0) alpha = std::min(alpha, u(j) / (u(j) - z(j)));
      u += alpha * (z - u);
      for (Eigen::Index j = 0; j < p; ++j)
        if (passive[static_cast<size_t>(j)] && u(j) <= tol) passive[static_cast<size_t>(j)] = 0, u(j) = 0.0;
    }
  }
  return u;
}

std::optional<Eigen::VectorXd> bounded_split(const Eigen::MatrixXd& A, const Eigen::VectorXd& r, const Eigen::VectorXd& w,
                                             const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  return bounded_split(A, r, w, lo, hi, Eigen::MatrixXd(0, A.cols()), Eigen::VectorXd(0));
}

std::optional<Eigen::VectorXd> bounded_split(const Eigen::MatrixXd& A, const Eigen::VectorXd& r, const Eigen::VectorXd& w,
                                             const Eigen::VectorXd& lo, const Eigen::VectorXd& hi, const Eigen::MatrixXd& D,
                                             const Eigen::VectorXd& e) {
  const Eigen::Index n = A.cols(), nd = D.rows();
  // The weighted least-norm split λ₀ = D z₀ and the null space N of A D (its redundancy).
  const Eigen::MatrixXd B = A * w.asDiagonal();
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(B, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::VectorXd& sv = svd.singularValues();
  const double smax = sv.size() > 0 ? sv(0) : 0.0;
  Eigen::Index rank = 0;
  while (rank < sv.size() && sv(rank) > 1e-12 * smax) ++rank;
  Eigen::VectorXd z0 = Eigen::VectorXd::Zero(n);
  for (Eigen::Index i = 0; i < rank; ++i) z0 += svd.matrixV().col(i) * (svd.matrixU().col(i).dot(r) / sv(i));
  const Eigen::VectorXd lam0 = w.cwiseProduct(z0);
  // The load scale: the bounds are met within 1e-12 of it.
  double scale = lam0.cwiseAbs().maxCoeff();
  for (Eigen::Index i = 0; i < n; ++i) {
    if (std::isfinite(lo(i))) scale = std::max(scale, std::abs(lo(i)));
    if (std::isfinite(hi(i))) scale = std::max(scale, std::abs(hi(i)));
  }
  for (Eigen::Index m = 0; m < nd; ++m) scale = std::max(scale, std::abs(e(m)));
  const double slack = 1e-12 * scale;
  auto within = [&](const Eigen::VectorXd& lam) {
    for (Eigen::Index i = 0; i < n; ++i)
      if (lam(i) < lo(i) - slack || lam(i) > hi(i) + slack) return false;
    for (Eigen::Index m = 0; m < nd; ++m)
      if (D.row(m).dot(lam) < e(m) - slack * std::max(1.0, D.row(m).cwiseAbs().sum())) return false;
    return true;
  };
  bool inside = true;  // exactly: a share in the rounding band beyond a bound is moved onto it
  for (Eigen::Index i = 0; i < n; ++i) inside = inside && lam0(i) >= lo(i) && lam0(i) <= hi(i);
  for (Eigen::Index m = 0; m < nd; ++m) inside = inside && D.row(m).dot(lam0) >= e(m);
  if (inside) return lam0;
  const Eigen::Index k = n - rank;
  if (k == 0) return std::nullopt;  // one split only, and it is beyond a bound
  const Eigen::MatrixXd N = svd.matrixV().rightCols(k);
  // The bounds as rows G s ≥ h of the least-distance problem, in z units (λ_i = w_i (z₀ + N s)_i),
  // each row scaled to unit length; a row without s is met by λ₀ or by no split.
  // s in units of zs: h stays O(1) (without a least-norm share, z₀ = 0: the bounds' scale in z units)
  const double wmax = w.cwiseAbs().maxCoeff();
  const double zs = z0.norm() > slack ? z0.norm() : std::max(wmax > 0.0 ? scale / wmax : 0.0, slack);
  std::vector<Eigen::VectorXd> G;
  std::vector<double> h;
  auto add = [&](const Eigen::VectorXd& g, double rhs) {
    const double gn = g.norm();
    if (gn <= 1e-12) return rhs <= 1e-12;
    G.push_back(g / gn);
    h.push_back(rhs / gn);
    return true;
  };
  for (Eigen::Index i = 0; i < n; ++i) {
    if (w(i) == 0.0) continue;  // λ_i ≡ 0
    const Eigen::VectorXd row = N.row(i).transpose();
    // lo ≤ w (z₀ + N s) ⇔ N_i s ≥ lo/w − z₀;  w (z₀ + N s) ≤ hi ⇔ −N_i s ≥ z₀ − hi/w
    if (std::isfinite(lo(i)) && !add(row, (lo(i) / w(i) - z0(i)) / zs)) return std::nullopt;
    if (std::isfinite(hi(i)) && !add(-row, (z0(i) - hi(i) / w(i)) / zs)) return std::nullopt;
  }
  // D λ ≥ e ⇔ (D W N) s ≥ e − D λ₀.
  for (Eigen::Index m = 0; m < nd; ++m) {
    const double dn = (D.row(m) * w.asDiagonal()).norm();  // the row in z units, scaled to length 1
    const double rhs = e(m) - D.row(m).dot(lam0);
    if (dn == 0.0) {
      if (rhs > slack) return std::nullopt;
      continue;
    }
    const Eigen::VectorXd row = (D.row(m) * w.asDiagonal() * N).transpose() / dn;
    if (!add(row, rhs / (dn * zs))) return std::nullopt;
  }
  // min ‖s‖ subject to G s ≥ h: with u ≥ 0 minimizing ‖E u − e‖, E = [Gᵀ; hᵀ], e = (0, …, 0, 1), and
  // ρ = E u − e, s = −ρ₁…ₖ / ρₖ₊₁; ρ = 0 (ρₖ₊₁ = 0) when the bounds admit no s (Lawson–Hanson).
  const auto p = static_cast<Eigen::Index>(G.size());
  Eigen::MatrixXd E(k + 1, p);
  for (Eigen::Index j = 0; j < p; ++j) {
    E.col(j).head(k) = G[static_cast<size_t>(j)];
    E(k, j) = h[static_cast<size_t>(j)];
  }
  Eigen::VectorXd last = Eigen::VectorXd::Zero(k + 1);
  last(k) = 1.0;
  const Eigen::VectorXd u = nonnegative_least_squares(E, last, 1e-14 * std::max(1.0, E.cwiseAbs().maxCoeff()));
  const Eigen::VectorXd rho = E * u - last;
  if (-rho(k) <= 1e-12) return std::nullopt;
  Eigen::VectorXd s = -rho.head(k) / rho(k) * zs;
  // A general row met only up to the rounding of s (weights 1e3 beside 1 scale it up in λ): moved onto
  // it along the null space, the least step (a bound is clamped below; a row cannot be).
  for (int pass = 0; pass < 3; ++pass)
    for (Eigen::Index m = 0; m < nd; ++m) {
      const Eigen::VectorXd lam_m = w.cwiseProduct(z0 + N * s);
      const double short_by = e(m) - D.row(m).dot(lam_m);
      const Eigen::VectorXd g = (D.row(m) * w.asDiagonal() * N).transpose();
      if (short_by > 0.0 && g.squaredNorm() > 0.0) s += g * (short_by / g.squaredNorm());
    }
  Eigen::VectorXd lam = w.cwiseProduct(z0 + N * s);
  if (!within(lam)) return std::nullopt;
  for (Eigen::Index i = 0; i < n; ++i) lam(i) = std::clamp(lam(i), lo(i), hi(i));  // onto a bound met within slack
  return lam;
}

}  // namespace machdyn
