#pragma once
/// @file
/// The particular (quasi-static) solution of M q'' + K q = f for constant f, without an
/// eigen-decomposition, so it costs O(n) for a chain:
///   R = basis of ker K (rigid-body motions: each spring-connected group of bodies not tied to the
///       ground turns as a whole through its ratios, q_b = q_a / i);
///   a'' = (Rᵀ M R)⁻¹ Rᵀ f         (rigid acceleration),
///   K q_e = f − M R a'',  Rᵀ M q_e = 0  (solved as one sparse saddle-point system),
///   link loads F = C B q_e.
/// It equals the modal form Σ_elastic φ_k φ_kᵀ f / ω_k² (analysis/modes.hpp), which the tests check.

#include <Eigen/Core>

#include "machdyn/model/model.hpp"

namespace machdyn {

/// Basis of ker K as columns (n × r), one column per free group of bodies.
Eigen::MatrixXd rigid_motions(const Model& m);

/// Factors the saddle-point system once; solve() then costs O(n) per load vector.
class ParticularSolver {
 public:
  explicit ParticularSolver(const Model& m);
  ~ParticularSolver();
  ParticularSolver(const ParticularSolver&) = delete;
  ParticularSolver& operator=(const ParticularSolver&) = delete;
  /// Link loads of the particular solution for constant generalized forces f (size n).
  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& f) const;

 private:
  struct Impl;
  Impl* impl_;
};

/// One-off form of ParticularSolver(m).solve(f).
Eigen::VectorXd particular_link_loads(const Model& m, const Eigen::VectorXd& f);

}  // namespace machdyn
