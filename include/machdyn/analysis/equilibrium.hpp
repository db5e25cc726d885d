#pragma once
/// @file
/// The start from static equilibrium (`simulation: {initial: equilibrium}`): the positions and
/// velocities at t = 0 at which nothing elastic moves under the loads acting at t = 0 — a hanging
/// load with its rope stretched by m g / c, a chain preloaded by a constant torque.
///
/// With the generalized forces g(q) = f(0, q, v) + Σ_links (−F j_a on a, +F j_b on b) (the links'
/// own law, elements/link.hpp, in the mode each gap or rope is in) the start solves, with the
/// rigid-body motions R of the transmitting links (analysis/static_loads.hpp: rigid_motions):
///   Rᵀ g(q) = 0                       (every free group is balanced: else no equilibrium exists)
///   g(q) = 0 on the elastic part       (K q = f for linear links)
///   Rᵀ M q = Rᵀ M q_given              (the rigid-body motions keep the given positions)
///   v = R (RᵀMR)⁻¹ RᵀM v_given        (no elastic motion; the rigid motions keep their momentum)
/// Ropes and gaps take the flank they press (slack ropes carry nothing), end stops hold a body that
/// presses into them (a load resting on the ground), a brake to the ground applied at t = 0 holds its
/// body where it is (within its static limit); a clutch (or a brake on a housing body) applied at
/// t = 0 ties its two bodies at their given relative position (a constraint row G Δ = 0, its stuck row
/// of elements/contact.hpp; within its static limit); a lossy gear is at rest (stuck,
/// elements/lossy_gear.hpp) and holds both its sides where they are, if its locking range holds the
/// torques on them (a self-locking worm gear holds a hanging load); one that cannot, in a group a brake
/// or stop holds, is at rest on the verge of the motion it would start (that rolling mode's relation
/// at v = 0: under a hanging load X = η_mf2 Y, the brake holding the rest); each held element's reaction λ
/// solves Hᵀ λ = g − M R a'' over the rows H of everything held; a free group whose loads do not balance moves as a
/// whole until the first open rope, gap flank or stop takes it up: an active-set iteration decides these modes,
/// each step one dense linear solve (O(n³); the modes settle in a few steps).
/// Units: SI of each coordinate (rad or m, rad/s or m/s), forces N or N·m.
///
/// Throws InputError (located at the element) when no equilibrium exists: a free group whose loads
/// do not balance (names its bodies and the net load), given velocities that contradict the ratios
/// of the stiff links (names the body and the speed rigid motion gives), modes that do not settle,
/// a brake or clutch that cannot hold its load (its reaction and limit), a lossy gear whose torques lie
/// beyond its locking range (the torques and by how much), and for elements whose rest force is not
/// decided by the law here (friction contacts, freewheels, gear joints, machines with variable inertia).

#include <vector>

#include "machdyn/model/model.hpp"

namespace machdyn {

/// The equilibrium start of `m`: positions q0 and velocities v0 (one per body, SI).
struct EquilibriumStart {
  std::vector<double> q0, v0;
  int iterations = 0;  ///< active-set steps taken
};

/// Solves for the static equilibrium at t = 0 (see above). Does not look at m.simulation.initial.
EquilibriumStart static_equilibrium(const Model& m);

/// A copy of `m` whose bodies start at static_equilibrium(m), with `initial` set to `given`.
Model with_equilibrium_start(const Model& m);

}  // namespace machdyn
