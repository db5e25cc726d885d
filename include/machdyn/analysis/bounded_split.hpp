#pragma once
/// @file
/// The bounded split of a redundantly locked load (docs/hybrid.md "Redundant locks"): the loads λ of
/// n stuck constraints that hold m motion equations A λ = r, each within its own bounds
/// lo_i ≤ λ_i ≤ hi_i (a friction contact or brake ±F_s(t), a freewheel or backstop one-sided
/// [−F_d, ∞) or (−∞, F_d] — unbounded in its locking direction, a joint (−∞, ∞)), shared by weights
/// w_i > 0 (N^½ or (N·m)^½):
///
///   minimize Σ_i (λ_i / w_i)²  subject to  A λ = r  (least squares where r is outside A's range)
///                                           and  lo ≤ λ ≤ hi.
///
/// Without bounds this is the weighted least-norm split λ = D (A D)⁺ r, D = diag(w), of the drive
/// system; where that split is within the bounds it is returned unchanged. Otherwise the split is
/// moved along the null space of A D (the redundancy: the splits that hold the same motion): with
/// λ = D (z₀ + N s), z₀ = (A D)⁺ r and N an orthonormal basis of the null space, Σ (λ_i/w_i)² =
/// ‖z₀‖² + ‖s‖², so the problem is the least-distance problem min ‖s‖ over the polytope the bounds
/// cut in s-space. It is solved by the active-set method of nonnegative least squares (Lawson and
/// Hanson's least-distance programming): a constraint at its bound is clamped there, the rest are
/// solved again, and a clamped one is released when its multiplier turns negative — finite, and the
/// answer is the unique optimum. A weight w_i = 0 fixes λ_i = 0.
///
/// Returns nothing when no split within the bounds exists: only then is a constraint overloaded (it
/// slides or overruns; the mode decision releases it).
#include <optional>

#include <Eigen/Dense>

namespace machdyn {

/// λ of the bounded weighted least-norm split above. A: m × n, r: m, w, lo, hi: n (lo_i ≤ hi_i;
/// ±HUGE_VAL for an unbounded side). Rank decisions are relative to 1e-12 of the largest singular
/// value of A D; a bound is met within 1e-12 of the problem's load scale (then clamped onto it).
[[nodiscard]] std::optional<Eigen::VectorXd> bounded_split(const Eigen::MatrixXd& A, const Eigen::VectorXd& r,
                                                           const Eigen::VectorXd& w, const Eigen::VectorXd& lo,
                                                           const Eigen::VectorXd& hi);

/// The same split with general rows besides the bounds: also D λ ≥ e (D: p × n, e: p), each row met
/// within 1e-12 of the problem's load scale. A stuck lossy gear's locking range is such a set of rows
/// on its two reactions (analysis/gear_split.hpp): it is not a box. Rows are taken in the least-distance
/// problem exactly as the bounds (s-space rows D W N s ≥ e − D λ₀).
[[nodiscard]] std::optional<Eigen::VectorXd> bounded_split(const Eigen::MatrixXd& A, const Eigen::VectorXd& r,
                                                           const Eigen::VectorXd& w, const Eigen::VectorXd& lo,
                                                           const Eigen::VectorXd& hi, const Eigen::MatrixXd& D,
                                                           const Eigen::VectorXd& e);

/// min ‖E u − f‖ subject to u ≥ 0 (nonnegative least squares, Lawson–Hanson active set); tol: the
/// gradient level below which a constraint stays clamped. Used by bounded_split; exposed for tests.
[[nodiscard]] Eigen::VectorXd nonnegative_least_squares(const Eigen::MatrixXd& E, const Eigen::VectorXd& f, double tol);

}  // namespace machdyn
