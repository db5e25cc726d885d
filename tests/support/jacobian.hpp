#pragma once
// The finite-difference Jacobian the analytic Jacobians of the drive system are checked against.
#include <cmath>
#include <cstddef>
#include <vector>
#include <Eigen/Core>

#include "machdyn/analysis/drive_system.hpp"

namespace machdyn::test {

/// ∂f/∂y of the drive system's right-hand side at (t, y) by central differences, step
/// 1e-6 (1 + |y_j|) per state (truncation error O(h²) of the third derivative).
inline Eigen::MatrixXd central_difference_jacobian(DriveSystem& sys, double t, const std::vector<double>& y) {
  const int N = sys.size();
  Eigen::MatrixXd D(N, N);
  std::vector<double> yp, ym, fp(static_cast<std::size_t>(N)), fm(fp);
  for (int j = 0; j < N; ++j) {
    const double h = 1e-6 * (1.0 + std::abs(y[static_cast<std::size_t>(j)]));
    yp = y, ym = y;
    yp[static_cast<std::size_t>(j)] += h;
    ym[static_cast<std::size_t>(j)] -= h;
    sys.rhs(t, yp.data(), fp.data());
    sys.rhs(t, ym.data(), fm.data());
    for (int i = 0; i < N; ++i) D(i, j) = (fp[static_cast<std::size_t>(i)] - fm[static_cast<std::size_t>(i)]) / (2 * h);
  }
  return D;
}

}  // namespace machdyn::test
