#pragma once
/// @file
/// A stuck lossy gear in the bounded split of the stuck set (docs/hybrid.md "Modes, events,
/// complementarity"): the gear decided together with the contacts, brakes and clutches around it,
/// as one more bounded constraint. Internal to the drive system's coupled solve
/// (analysis/drive_system_coupled.cpp).
///
/// Rows and reactions. Stuck, the gear holds both its bodies at rest: two rows, v_a = 0 (e_a) and
/// i v_b = 0 (i e_b), with the reactions λ_X = X and λ_ρ = −Y, so that the gear's forces on its
/// bodies are those of elements/lossy_gear.hpp (−X on a, +i Y on b), as any stuck row puts −w λ on its
/// bodies. With these two rows the gear's bodies keep their own inertias in G M⁻¹ Gᵀ, and a chain of
/// stuck clutches to the ground beside the gear is a redundancy the split resolves, not a load the
/// gear must take.
///
/// Admissible set (the locking range, elements/lossy_gear.hpp "Stuck mode"). Stuck with X = F_a and
/// Y = −F_b/i, the gear holds while both start margins are ≥ 0. The margin of direction s on the
/// driving side σ ∈ {a, b} is −s N, N = p X − q Y − c the numerator of that rolling mode's equation
/// (LossyGearLaw::relation(md, 0): a drives p = η_mf1, q = 1, c = s τ_bf1; b drives p = 1, q = η_mf2,
/// c = s η_mf2 τ_bf2). Solved for X each is a line X_s,σ(Y) = (q Y + c)/p, increasing in Y; the side
/// that drives at a given X is the one whose line is further out: X_+(Y) = max over σ of X_+,σ(Y) and
/// X_−(Y) = min over σ of X_−,σ(Y) (the two lines of one s meet at the kink X = s τ_bf,a, where the
/// driving side changes; beyond it the other line is the inner one). So the gear holds exactly while
///   X_−(Y) ≤ X ≤ X_+(Y),
/// with no bearing friction η_mf1 X ≤ Y ≤ X/η_mf2 for X > 0 (and mirrored for X < 0): a bow tie, not a
/// box and not convex. It is the union of the four convex pieces (σ₊, σ₋) ∈ {a, b}²,
///   s (p X − q Y − c) ≤ 0  for (s, σ) = (+1, σ₊) and (−1, σ₋),
/// i.e. the rows −s p λ_X − s q λ_ρ ≥ −s c on the gear's reactions. The split is solved on every
/// piece (analysis/bounded_split.hpp with these rows) and the least Σ (λ/w)² kept: the optimum over
/// the union. Weights: the gear's reactions 1e3 (a joint's): the gear holds what its locking range
/// allows, the friction elements carry the rest in proportion to their limits.
#include <optional>
#include <vector>

#include <Eigen/Dense>

#include "machdyn/elements/lossy_gear.hpp"

namespace machdyn::detail {

/// The weight of a stuck gear's reactions in the split (a joint's).
inline constexpr double kGearSplitWeight = 1e3;

/// The bounded split over stuck rows of which the last 2 × gears.size() are the stuck gears' pairs
/// (λ_X, λ_ρ) (header), the others bounded by lo, hi (the gears' entries there unbounded): the least
/// Σ (λ/w)² over the pieces of the gears' locking ranges; nothing when no piece admits a split.
/// A: the rows' G C Gᵀ, r their right-hand side, w their weights.
[[nodiscard]] std::optional<Eigen::VectorXd> gear_bounded_split(const Eigen::MatrixXd& A, const Eigen::VectorXd& r,
                                                                const Eigen::VectorXd& w, const Eigen::VectorXd& lo,
                                                                const Eigen::VectorXd& hi,
                                                                const std::vector<const LossyGearLaw*>& gears);

/// The loads λ_k of the friction elements to the ground on a stuck gear's bodies (analysis/gear_lock.hpp):
/// the bounded split with no row of the dynamics (the gear holds both bodies at rest whatever λ is),
/// each λ_k within [lo_k, hi_k], the gear's reactions X = F_a + e_a·λ, Y = −(F_b + e_b·λ)/i within its
/// locking range (the pieces above as rows on λ), the least Σ (λ_k/w_k)²: λ = 0 where the gear holds
/// alone. Nothing when no piece admits a split (the gear's joint events are then negative).
/// ea, eb: each contact's force on a and on b per unit λ_k.
[[nodiscard]] std::optional<Eigen::VectorXd> gear_friction_split(const LossyGearLaw& g, double Fa, double Fb,
                                                                 const Eigen::VectorXd& ea, const Eigen::VectorXd& eb,
                                                                 const Eigen::VectorXd& w, const Eigen::VectorXd& lo,
                                                                 const Eigen::VectorXd& hi);

/// Whether the gear holds the reactions (X, Y) (both start margins ≥ −tol), by the pieces of the
/// header; the same set as LossyGearLaw::start_margin at F_a = X, F_b = −i Y (tested against it).
[[nodiscard]] bool gear_holds(const LossyGearLaw& g, double X, double Y, double tol);

}  // namespace machdyn::detail
