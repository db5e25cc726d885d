#pragma once
/// @file
/// The linear(ized) equations of a drive in one topology (every gap, contact and brake in a fixed
/// mode), assembled element by element: each element file adds its own terms (add_linear) — the
/// same law it states for the simulation, differentiated once.
///
///   M q̈ + D q̇ + K q = f,   subject to  G q̇ = 0  (stuck contacts; G q = const on positions)
///
/// q: the bodies' coordinates (rad or m), M = diag(I or m) (kg·m² or kg; a machine's I(q) at the
/// linearization point), K and D symmetric (N·m/rad, N/m; N·m·s/rad, N·s/m) — except a machine's
/// geometric stiffness, which is symmetric too (diagonal). Row k of G is the sliding velocity
/// u_k = v_a − v_b of stuck contact k (a stuck contact to the ground fixes its body). A sliding
/// contact adds its kinetic slope dF_k/du (zero for a constant kinetic level) to D; an open gap or a
/// released brake adds nothing; a closed gap adds its spring and damper.

#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "machdyn/elements/modes.hpp"

namespace machdyn {

/// The mode of every switching element: one entry per link (GapMode; ignored for links without a
/// gap) and per contact or brake (`contacts`), plus whether each contact acts at all (`engaged`: a
/// brake released or a clutch opened contributes nothing).
struct Topology {
  std::vector<GapMode> gaps;          ///< per Model::links
  std::vector<ContactMode> contacts;  ///< per Model::contacts
  std::vector<bool> engaged;          ///< per Model::contacts; empty: all engaged
};

struct LinearModel {
  int n = 0;                                        ///< number of bodies (coordinates)
  Eigen::VectorXd M;                                ///< diagonal of the mass matrix (n)
  std::vector<Eigen::Triplet<double>> K, D;         ///< entries (duplicates are summed)
  std::vector<std::vector<std::pair<int, double>>> G;  ///< constraint rows: (body, weight) pairs
  std::vector<std::string> constraint_names;        ///< the stuck contact of each row of G

  explicit LinearModel(int bodies = 0) : n(bodies), M(Eigen::VectorXd::Zero(bodies)) {}
  /// Adds w · j jᵀ to K (or D) for the gradient j given as (index, value) pairs: the stiffness of a
  /// spring whose deflection is δ = jᵀ q.
  static void add_outer(std::vector<Eigen::Triplet<double>>& to, const int* idx, const double* j, int count, double w);
  [[nodiscard]] Eigen::SparseMatrix<double> stiffness() const;  ///< K (n × n)
  [[nodiscard]] Eigen::SparseMatrix<double> damping() const;    ///< D (n × n)
  [[nodiscard]] Eigen::SparseMatrix<double> constraints() const;  ///< G (rows × n)
};

}  // namespace machdyn
