#pragma once
/// @file
/// A lossy gear decided together with the clutches on its bodies (a friction contact between one of
/// the gear's bodies and another body: MSL's LossyGear – Clutch, a motor – clutch – worm gear): the
/// joint law. The gear's law stays in elements/lossy_gear.hpp, the clutch's in elements/contact.hpp;
/// this file only joins them (as analysis/gear_lock.hpp does for friction to the ground).
///
/// Compliance. In a mode md the gear's law gives body a's acceleration affine in the forces on its
/// two bodies, a = k_a F_a + k_b F_b + k_0 (a_b = a / i; stuck: a = 0), e.g. while a drives
/// k_a = η_mf1 / (η_mf1 I_a + J_b), k_b = 1 / (i (η_mf1 I_a + J_b)), k_0 = −s τ_bf1 / (η_mf1 I_a + J_b),
/// with J_b = I_b / i². So the accelerations of all bodies are acc = C f + c_0 with C = diag(1/I_j)
/// except each gear's block [[k_a, k_b], [k_a/i, k_b/i]] on (a, b); C needs no 1/I_b, so one side of
/// the gear may have no inertia (MSL's massless flange) while the other has. k_a, k_b, k_0 are read
/// off the law itself (LossyGearLaw::solve at F = 0 and the unit forces), not written again.
///
/// Stuck contacts. A stuck contact j puts −w_jp λ_j on the bodies of its row and keeps
/// G_j acc = ẇ_j, so
///   (G C Gᵀ) λ = G (C f + c_0) − ẇ,
/// the stick equations of docs/hybrid.md with the gear's law inside: a stuck clutch makes the body
/// beyond it part of the gear's side. G C Gᵀ is not symmetric (the mesh passes power with η) and is
/// singular where stuck contacts lock one motion; λ is then the weighted least-norm solution of
/// docs/hybrid.md, λ = D (G C Gᵀ D)⁺ r with D = diag(√F_s0), with the one-sided rule for
/// freewheels. With λ's loads in F_a, F_b the gear's law gives X, Y and a exactly (outputs, heat,
/// events), and a_b = a / i, the bodies stuck to a gear's body take its acceleration exactly.
///
/// Driving side while rolling. The bodies stuck to the gear's sides move with them; with their
/// inertias and forces lumped into the sides, elements/lossy_gear.hpp's argument holds: both modes
/// give X̃ the sign of D of the lumped sides. So for given contact modes exactly one side is
/// consistent (both at the switch): a drives while the a-drives mode's event s X̃ ≥ 0, else b drives
/// (the larger of the two modes' side events decides, so a located switch lands on the new side).
/// The contact decision (analysis/contact_decision.hpp) settles the side at every trial, so a clutch
/// sticks or slips with the side it implies: the small linear system per driving side of the gear's
/// mode equation and the clutch's holding torque, the combination consistent with both kept.
///
/// At rest (v_a = 0) the gear, its friction to the ground (analysis/gear_lock.hpp: brakes, bearing
/// friction, backstops on its bodies) and the contacts at zero sliding speed Z (clutches on its bodies;
/// none without them) are decided together, one decision for every gear at rest:
///   1. the gear and its ground friction stuck, Z by the stick rule (the stuck set's bounded split,
///      with the gear as bounded rows where the weighted share leaves it beyond its locking range or a
///      contact beyond its limit, analysis/gear_split.hpp); kept when the pair's events of
///      analysis/gear_lock.hpp hold, m_{+1}(F + d_+) ≥ −tol and m_{−1}(F + d_−) ≥ −tol (d = 0 without
///      ground friction: the gear's own margins), with the stuck clutches' loads in F = (F_a, F_b);
///      the ground friction's loads are the bounded split of gear_lock.hpp at these F;
///   2. else the gear starts in the direction s whose margin failed, its ground friction sliding
///      with it, Z decided again with the gear rolling (its side settled as above); kept when s a ≥ 0
///      within rounding; with ground friction and a = 0 exactly the stuck contacts hold the gear's
///      other side (a chain stuck to a brake): the start moves nothing, the modes of 1. are kept
///      (else its rest event s v_a would fire again at once, every 1e-13 s);
///   3. else no consistent combination: SolverError naming the gear.
/// Gears a stuck clutch ties at rest (a clutch between two gears' bodies: motor – gear – clutch – gear
/// – drum) are one degree of freedom: they are decided together, each stuck or starting in ±1, the
/// fewest starts first, Z decided and the rolling gears' sides settled per combination, the first in
/// which every stuck gear holds (its margins, with its ground friction's) and every starting gear has
/// s a > 0 kept (none: SolverError) — a train's enumeration of its directions (analysis/gear_train.hpp);
/// a gear coming to rest stops the gears its stuck clutch ties to it (DriveSystem::stop_gear).
/// Events: those of the gear (elements/lossy_gear.hpp) and of the contacts (elements/contact.hpp),
/// each from the joint solution above.
/// Supported (compile checks): a two-body friction contact or freewheel (a one-sided clutch: the
/// one-sided rule above, its lock·λ ≥ 0 its stick rule) with one body on the gear and the other on
/// no lossy gear, or a two-sided clutch to another gear's body (friction to the ground on the same
/// gear is decided in the same decision, above);
/// no variable inertia among the gear's bodies; no prescribed motion in the
/// model (a stuck chain could tie it to a stuck gear: two kinematic ends, which this solve does not take).

#include <vector>

#include "machdyn/analysis/drive_system.hpp"

namespace machdyn {

/// Gear g rolling in s = ±1 on the driving side consistent with the current contact modes (header);
/// leaves `sys` in that mode.
GearMode settle_rolling_side(DriveSystem& sys, int g, int s, double t, const double* y);

/// The one decision of gear g at rest (v_a = 0; header, "At rest") at (t, y): the gear, its friction
/// to the ground (analysis/gear_lock.hpp) and, with clutches on its bodies, the contacts at zero
/// sliding speed, together; sets their modes in `sys` and returns the gear's. `strict`: the gear's
/// event fired; `strict_contacts`: contacts whose breakaway event fired (judged without the rounding
/// allowance).
GearMode decide_gear_at_rest(DriveSystem& sys, int g, double t, const double* y, bool strict,
                             const std::vector<int>& strict_contacts);

}  // namespace machdyn
