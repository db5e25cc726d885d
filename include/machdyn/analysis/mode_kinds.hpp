#pragma once
/// @file
/// What a natural mode of a model with a swinging load is (docs/sway.md, "Pendulum modes"): a
/// pendulum (sway) mode, the rope's stretch mode, or a mode of the drive line, decided from the
/// mass-normalized shape φ (φᵀ M φ = 1): the kinetic energy share of body i in the mode is
/// M_ii φ_i² (the shares sum to 1), grouped as
///   sway     the loads' horizontal coordinates (LOAD.x, LOAD.y) and the part of a rigid load's
///            rotation J φ_ψ² that moves its rope points across (the horizontal share of
///            |∂(R(ψ) a)/∂ψ|², summed over its ropes: a body on one rope above its centre swings,
///            a wide spreader on two ropes rolls by stretching them);
///   stretch  the loads' vertical coordinates (LOAD.z) and the rest of the rotation;
///   drive    every other body (trolleys, bridges, jibs, drums, the drive lines).
/// The rule: a mode in which the loads carry less than kLoadShare of the kinetic energy is the
/// drive line's (the load stands practically still: a drive-line mode with the rope as a spring to
/// a quiet mass); otherwise a pendulum mode if sway ≥ stretch, else a rope-stretch mode. A model
/// without a spatial rope has drive-line modes only.

#include <string>
#include <vector>

#include <Eigen/Core>

#include "machdyn/model/model.hpp"

namespace machdyn {

enum class ModeKind { drive_line, pendulum, rope_stretch };

/// "drive line", "pendulum", "rope stretch".
const char* to_string(ModeKind k);

/// A mode's kinetic energy shares (sway + stretch + drive = 1).
struct ModeShares {
  double sway = 0.0, stretch = 0.0, drive = 1.0;
};

/// Below this share of the loads a mode is the drive line's.
inline constexpr double kLoadShare = 0.01;

/// True when the model has a spatial rope (a load whose modes are told apart).
bool has_swinging_load(const Model& m);

/// The shares of each column of `shapes` (n × k, n = the model's bodies), the masses `mass`
/// (M's diagonal, n).
std::vector<ModeShares> mode_shares(const Model& m, const Eigen::VectorXd& mass, const Eigen::MatrixXd& shapes);

/// The rule above applied to shares.
ModeKind mode_kind(const ModeShares& s);

/// The kind of each column of `shapes` (mass_diagonal(m) as M); all drive_line without a rope.
std::vector<ModeKind> mode_kinds(const Model& m, const Eigen::MatrixXd& shapes);

}  // namespace machdyn
