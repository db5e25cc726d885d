#pragma once
/// @file
/// Modal analysis of the elastic chain — every link transmitting (a gap taken as closed), no contact
/// or brake acting — at the initial position: K φ = ω² M φ. The matrices are linearize()'s for that
/// topology (elements/linearize.hpp: each element's own law), the eigenproblem is undamped_modes()
/// (analysis/modal.hpp). For the modes of a definite contact state (stuck, sliding, released; gaps
/// open or closed), damping and frequency responses use analysis/linear_analysis.hpp (`machdyn
/// modes`, docs/modes.md); these functions stay for the quasi-static loads of a run and the report.
///
/// Elastic modes have ω > 0; rigid-body modes (ω² at or below 1e-10 of the largest) are counted
/// apart. Shapes are mass-normalized, φᵀ M φ = 1, with the largest-magnitude entry positive.
/// Bodies with variable inertia (model/machine.hpp) are linearized at the initial position:
/// M = diag(I(q0)), a link to a machine's output point has entries p′(q0) and adds the geometric
/// stiffness c δ0 p″(q0). The machines' own forces Q(q) and the velocity terms ½ I′ q'² are not
/// included (they vanish at rest in an equilibrium).

#include <Eigen/Core>

#include "machdyn/model/model.hpp"

namespace machdyn {

/// M as a vector of the diagonal (kg·m² or kg).
Eigen::VectorXd mass_diagonal(const Model& m);
/// K = Bᵀ C B (n × n, symmetric positive semi-definite).
Eigen::MatrixXd stiffness_matrix(const Model& m);
/// D = Bᵀ diag(d) B.
Eigen::MatrixXd damping_matrix(const Model& m);
/// B: row l gives δ_l = B.row(l) · q.
Eigen::MatrixXd deflection_matrix(const Model& m);

struct Modes {
  int rigid_body_modes = 0;     ///< dim ker K
  Eigen::VectorXd omega;        ///< elastic natural frequencies, rad/s, ascending
  Eigen::MatrixXd shapes;       ///< n × omega.size(), column k mass-normalized
  Eigen::MatrixXd rigid_shapes; ///< n × rigid_body_modes, mass-normalized
};

/// Solves K φ = ω² M φ (undamped_modes of the chain topology). An eigenvalue at or below
/// 1e-10 · max|λ| (or exactly zero stiffness) counts as a rigid-body mode.
Modes compute_modes(const Model& m);

/// Link loads of the particular (quasi-static) solution for constant generalized forces f:
/// the deflections of q_e = Σ_elastic φ_k φ_kᵀ f / ω_k², the motion without elastic vibration
/// (rigid-body modes accelerate and do not load links). For the three-mass hoist this is
/// eq. 22 of paper 002: M12*, M23*.
Eigen::VectorXd static_link_loads(const Model& m, const Modes& modes, const Eigen::VectorXd& f);

}  // namespace machdyn
