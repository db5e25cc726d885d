#pragma once
/// @file
/// Modal analysis of one topology's linear model (elements/linear_model.hpp)
///   M q̈ + D q̇ + K q = f,   G q̇ = 0 (stuck contacts),
/// undamped (K φ = ω² M φ) and damped (the state-space eigenproblem, non-proportional damping).
///
/// The constraints are eliminated first: q = T z with G T = 0. A stuck contact's row says
/// q_a = q_b (or q_a = 0 to the ground), so the bodies it joins move as one: T merges them
/// (union–find; T has one 1 per row, so the reduced mass Tᵀ M T stays diagonal, the sum of the
/// joined masses, and a chain stays banded). A general constraint row (none of the elements
/// adds one today) falls back to an orthonormal basis of ker G from a QR of Gᵀ.
///
/// Units: ω in rad/s; shapes in the bodies' coordinates (rad or m). Rigid-body modes (ω² at or
/// below 1e-10 of the largest |ω²|, as analysis/modes.hpp counts them) are counted apart.

#include <complex>
#include <string>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SparseCore>

#include "machdyn/elements/linear_model.hpp"

namespace machdyn {

/// The linear model on the constraint manifold: q = T z (n × r), M_r = Tᵀ M T, K_r = Tᵀ K T,
/// D_r = Tᵀ D T (r × r).
struct ReducedModel {
  int n = 0;                         ///< bodies
  int r = 0;                         ///< independent coordinates
  Eigen::SparseMatrix<double> T;     ///< n × r
  Eigen::SparseMatrix<double> M, K, D;  ///< r × r
  bool diagonal_mass = true;         ///< M_r diagonal (always, unless a general constraint row)
};

/// Eliminates the constraint rows of `lin`. Throws std::invalid_argument when a body's mass is not
/// positive (a body fixed by a stuck contact to the ground drops out first, so it may be anything).
ReducedModel reduce_constraints(const LinearModel& lin);

/// Undamped natural frequencies and mass-normalized shapes (φᵀ M φ = 1, largest entry positive).
struct UndampedModes {
  int constraints = 0;           ///< rows of G (stuck contacts)
  int dof = 0;                   ///< independent coordinates r = n − rank G
  int rigid_body_modes = 0;      ///< ω = 0: motions of the drive as a whole
  Eigen::VectorXd omega;         ///< elastic natural frequencies, rad/s, ascending
  Eigen::MatrixXd shapes;        ///< n × omega.size()
  Eigen::MatrixXd rigid_shapes;  ///< n × rigid_body_modes
};

/// Solves K_r ψ = ω² M_r ψ. With diagonal M_r the symmetric matrix M_r^{-1/2} K_r M_r^{-1/2} is
/// formed; when it is tridiagonal (a chain whose bodies are numbered along it) its eigenproblem
/// is solved directly (O(r²) with vectors), else by a dense symmetric solver. φ = T ψ.
UndampedModes undamped_modes(const LinearModel& lin);

/// One eigenvalue λ of the first-order system ẋ = A x, x = [z; ż]:
///   A = [0, I; −M_r⁻¹K_r, −M_r⁻¹D_r].
/// An oscillatory mode is a pair λ = −ζ ω_n ± i ω_d, ω_d = ω_n √(1 − ζ²); it is listed once
/// (Im λ > 0). An overdamped mode is a real λ < 0 (decay rate −λ; ζ is not defined per root).
struct DampedMode {
  std::complex<double> lambda;      ///< 1/s
  bool oscillatory = true;
  double omega_n = 0.0;             ///< |λ|, rad/s
  double omega_d = 0.0;             ///< Im λ, rad/s (0 for a real root)
  double zeta = 0.0;                ///< −Re λ / |λ| (oscillatory); NaN for a real root
  double decay_rate = 0.0;          ///< −Re λ, 1/s
  Eigen::VectorXcd shape;           ///< n bodies' complex amplitudes, largest entry 1
};

struct DampedModes {
  int zero_eigenvalues = 0;         ///< |λ| ≤ 1e-7 max |λ|: rigid-body motions (a pair each when undamped)
  std::vector<DampedMode> modes;    ///< oscillatory ascending in ω_n, then real roots ascending in decay rate
};

/// The eigenvalues and complex mode shapes of A (Eigen's real nonsymmetric QR algorithm).
DampedModes damped_modes(const LinearModel& lin);

}  // namespace machdyn
