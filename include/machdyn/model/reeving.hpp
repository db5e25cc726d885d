#pragma once
/// @file
/// Reeving as drawn on a hoist's drawing (`type: rope` with `falls`, `rope_ends`,
/// `sheave_efficiency`; model/model.hpp Link): n falls (rope parts) carry the hook block, n_e rope
/// ends are wound on the drum (4/2 reeving: n = 4, n_e = 2; each end feeds k = n/n_e parts, the two
/// halves joined over an equalizer sheave that does not turn).
///
/// Kinematics (ideal, rigid parts): winding in Δs of rope at each end shortens each of the k parts of
/// that end by Δs/k, so the hook moves Δs n_e/n: the link's ratio is i = (n/n_e)/R (drum angle per
/// metre of hook travel; the file's `ratio` is the drum's 1/R). The hook stiffness of n parts of free
/// length L_f is c = n E A / L_f (each part stretched by the hook's e): elements/link.hpp.
///
/// Forces: the link's load F is the hook load. With frictionless sheaves every part carries
/// F/n (`NAME.fall_tension_N`). A sheave of efficiency η (the ratio of the rope forces on its two
/// sides, the tight side pulling the rope over it: about 0.98 for steel wire rope over a sheave
/// on rolling bearings) makes the parts of one end differ: number them j = 0 … k − 1 from the drum,
/// part j runs over the j sheaves between it and the drum, so
///   hoisting (the drum winds in, the rope runs towards the drum):  T_j = T_0 η^j
///   lowering (the rope runs away from the drum):                   T_j = T_0 η^(−j)
/// and the hook's balance F = n_e Σ_j T_j (the sheaves' inertia neglected) gives the force in the
/// part at the drum
///   T_0 = F / (n η_r),  η_r = (1/k) Σ_{j<k} η^(±j) = (1 − η^(±k)) / (k (1 − η^(±1)))
/// (+ hoisting: the reeving efficiency of a pulley block, the largest part force and the one a rope
/// is chosen for; − lowering: T_0 = F η^(k−1) / (n η_r+), the least loaded part). At rest the part
/// forces lie anywhere between the two; the hoisting value (the larger) is reported there.
/// The losses act on the dynamics (k > 1, η < 1): compile makes them a lossy gear between the drum and
/// the rope's end at the drum, lumped at the drum side of the rope's spring, with η_mf1 = η_r+ (the
/// drum drives: hoisting) and η_mf2 = 1/η_r− (the load drives: lowering), so the drum carries
/// F/(i η_r+) hoisting, F/(i η_r−) lowering, and holds at rest anything between (model/sheaves.hpp).
/// Valid for n ≥ 1, 1 ≤ n_e ≤ n with n a multiple of n_e, η ∈ (0, 1]. Nothing is thrown.

#include <cmath>

namespace machdyn {

struct Reeving {
  int falls = 1;      ///< n, the parts carrying the hook block
  int ends = 1;       ///< n_e, the rope ends on the drum
  double eta = 1.0;   ///< η, one sheave's efficiency

  /// k = n/n_e, the parts each rope end feeds.
  [[nodiscard]] int parts_per_end() const { return falls / ends; }
  /// η_r for hoisting (`hoisting` true) or lowering: (1/k) Σ_{j<k} η^(±j).
  [[nodiscard]] double efficiency(bool hoisting) const {
    const int k = parts_per_end();
    double sum = 0.0, p = 1.0;
    for (int j = 0; j < k; ++j, p *= hoisting ? eta : 1.0 / eta) sum += p;
    return sum / k;
  }
  /// T_0, the force in the rope part at the drum (N) for the hook load F (N) while the drum's rope
  /// speed is `rope_speed` (> 0 winding in, hoisting; 0: at rest, reported as hoisting).
  [[nodiscard]] double drum_part_force(double F, double rope_speed) const {
    return F / (falls * efficiency(rope_speed >= 0.0));
  }
};

}  // namespace machdyn
