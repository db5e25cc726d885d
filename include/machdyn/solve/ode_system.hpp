#pragma once
/// @file
/// The narrow interface between physics and integrators: a first-order system y' = f(t, y).
/// Integrators see only this; they never see bodies or links.

#include <string>

#include <Eigen/Core>
#include <Eigen/SparseCore>

namespace machdyn {

class OdeSystem {
 public:
  virtual ~OdeSystem() = default;
  /// Number of states n = dim(y).
  [[nodiscard]] virtual int size() const = 0;
  /// dydt = f(t, y); both arrays have size().
  virtual void rhs(double t, const double* y, double* dydt) = 0;
  /// Whether jacobian() is available (analytic ∂f/∂y).
  [[nodiscard]] virtual bool has_jacobian() const { return false; }
  /// J = ∂f/∂y (n × n), when has_jacobian().
  virtual void jacobian(double /*t*/, const double* /*y*/, Eigen::Ref<Eigen::MatrixXd> /*J*/) {}
  /// Whether sparse_jacobian() is available: then a stiff solver for a large system factors J
  /// sparsely (KLU) instead of as a dense n × n matrix.
  [[nodiscard]] virtual bool has_sparse_jacobian() const { return false; }
  /// J = ∂f/∂y in compressed columns; the same nonzero pattern (explicit zeros kept) at every call.
  virtual void sparse_jacobian(double /*t*/, const double* /*y*/, Eigen::SparseMatrix<double>& /*J*/) {}
  /// What state i means, for error messages: e.g. "body 'I2' (velocity)".
  [[nodiscard]] virtual std::string state_name(int i) const { return "state " + std::to_string(i); }
};

}  // namespace machdyn
