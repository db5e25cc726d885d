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
///
/// With constraints G (the elements held at an extreme: stuck contacts, stuck lossy gears; rows as
/// elements/linear_model.hpp's G, u = G v) the problem is M q'' + K q + Gᵀ λ = f, G q'' = 0, G q_e = 0:
///   R = basis of ker K ∩ ker G (a body held to the ground by a row is not free; a row between two
///       bodies carries q like a link's ratio, q_b = −(w_a/w_b) q_a);
///   a'' as above with this R, and [K Gᵀ; G 0] [q_e; λ] = [f − M R a''; 0] (pinned as without G).
/// λ is the held elements' reaction: it is part of the solution, never a given force. Entries on
/// bodies with prescribed motion are dropped (they are supports already); rows that repeat others
/// (two brakes on one drum) are left out, as they add no constraint.
///
/// A row whose reaction does not act along it (a rolling lossy gear keeps its ratio, G, but its
/// torques follow its mode's efficiency relation, LossyGearLaw::reaction: forces Hᵀ λ with H ≠ G, and
/// a constant part the caller adds to f) makes the problem M q'' + K q = f + Hᵀ λ, G q'' = 0, G q_e = 0
/// (H = G for the other rows). Then the rigid acceleration depends on λ (Rᵀ Hᵀ ≠ 0: the reaction
/// does work), so a'' is an unknown of the same bordered, unsymmetric solve:
///   [K  −Hᵀ  MR] [q_e]   [f]
///   [G   0   0 ] [λ  ] = [0]        (P: the pins, or (MR)ᵀ when they do not serve)
///   [P   0   0 ] [a''] = [0]
/// whose MR columns (one per rigid motion) are dense: O(n) per rigid motion for a chain.

#include <utility>
#include <vector>
#include <Eigen/Core>

#include "machdyn/model/model.hpp"

namespace machdyn {

/// Constraint rows G: each a list of (body, weight) pairs, u = Σ w_j v_j = 0 (as LinearModel::G).
using ConstraintRows = std::vector<std::vector<std::pair<int, double>>>;

/// Basis of ker K ∩ ker G as columns (n × r), one column per free group of bodies.
Eigen::MatrixXd rigid_motions(const Model& m, const ConstraintRows& G = {});

/// Factors the saddle-point system once; solve() then costs O(n) per load vector.
class ParticularSolver {
 public:
  /// H[k]: the reaction row of G[k] (empty, or k ≥ H.size(): along G[k]).
  explicit ParticularSolver(const Model& m, const ConstraintRows& G = {}, const ConstraintRows& H = {});
  ~ParticularSolver();
  ParticularSolver(const ParticularSolver&) = delete;
  ParticularSolver& operator=(const ParticularSolver&) = delete;
  /// Link loads of the particular solution for constant generalized forces f (size n).
  [[nodiscard]] Eigen::VectorXd solve(const Eigen::VectorXd& f) const;

 private:
  struct Impl;
  Impl* impl_;
  /// Factors the unsymmetric system of rows with their own reactions (header); `pins` empty: (MR)ᵀ.
  void reacting_system(const ConstraintRows& G, const ConstraintRows& H, const std::vector<int>& pins,
                       const std::vector<char>& fixed);
};

/// One-off form of ParticularSolver(m, G, H).solve(f).
Eigen::VectorXd particular_link_loads(const Model& m, const Eigen::VectorXd& f, const ConstraintRows& G = {},
                                      const ConstraintRows& H = {});

}  // namespace machdyn
