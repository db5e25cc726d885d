#pragma once
/// @file
/// A lossy gear decided together with the friction elements to the ground on its bodies (brakes,
/// ground contacts, MSL's BearingFriction, backstops): the joint law at rest. The gear's law stays in
/// elements/lossy_gear.hpp, the friction's in elements/contact.hpp; this file only joins them.
///
/// Such a contact k (row on one of the gear's bodies, to the fixed ground) slides with
/// u_k = κ_k v_a, κ_k = Σ w_j over a's terms + Σ w_j / i over b's. So while the gear rolls every
/// contact slides (its kinetic force is one of the forces F_a, F_b the gear's law solves with), and
/// at rest the gear and its contacts are stuck together or start together. Stuck together, the gear
/// holds both bodies at rest and the contacts' loads λ_k are not fixed by the dynamics: they are the
/// rows of the bounded split (analysis/gear_split.hpp gear_friction_split) — each λ_k within its
/// stick rule's bounds [lo_k, hi_k] (a brake or ground contact ±F_s(t); a backstop, a freewheel to
/// the ground, lock·λ ≥ −F_d and unbounded in its locking direction), the gear's reactions
/// X = F_a + e_a·λ, Y = −(F_b + e_b·λ)/i within its locking range, and the least Σ (λ_k/w_k)² (the
/// weights of the stuck set's share, docs/hybrid.md): the gear holds what its locking range allows,
/// the friction elements the least weighted norm of the rest. F_a, F_b are the forces on the two
/// bodies from everything else, e_k = (e_a, e_b) the force contact k puts on them per unit λ_k.
/// Events and decision. A start in s is resisted at most by every contact at the bound of its load
/// that opposes it, λ_k = hi_k where s κ_k > 0, else lo_k; d_s = Σ e_k λ_k. Since m_{+1} never
/// increases and m_{−1} never decreases with the forward forces (elements/lossy_gear.hpp), a split
/// exists exactly while
///   m_{+1}(F + d_+) ≥ 0  and  m_{−1}(F + d_−) ≥ 0
/// (from the corner λ of d_+ to that of d_− every load moves forward, m_{+1} falls from ≥ 0, m_{−1}
/// rises to ≥ 0, and they are never both negative: a point between holds), and these are the joint
/// event functions of the stuck pair (the contacts' own limits are no events while their gear is
/// stuck); a margin whose start a contact blocks (an infinite bound: a backstop) is 1. At rest they
/// decide: stuck while both hold (within LossyGearLaw::allowance unless the gear's event fired), else
/// the gear starts in the s whose margin failed, every contact sliding in sign(s κ_k) (consistent:
/// F_k(0) ≤ F_s). The one decision of a gear at rest, with clutches on its bodies too, is
/// analysis/gear_clutch.hpp's decide_gear_at_rest.
/// Supported (compile checks): contacts with a row on exactly one of the gear's bodies and the
/// ground, no moving surface, not a stop or joint.

#include <vector>

#include "machdyn/elements/contact.hpp"
#include "machdyn/elements/lossy_gear.hpp"

namespace machdyn {

/// The friction elements to the ground on one lossy gear's bodies.
struct GearLock {
  int gear = -1;
  int a = 0, b = 0;           ///< the gear's bodies
  std::vector<int> contacts;  ///< contact indices
  std::vector<double> kappa;  ///< κ_k: the contact's sliding velocity per unit v_a of the gear
  std::vector<double> ea, eb; ///< e_k: the force of the contact on a and on b per unit load λ_k

  /// d_s (size 2: on a, on b): the contacts' forces at the bounds that oppose a start in s (header);
  /// false when a contact blocks that start (no finite bound: a backstop). `c`: the model's contact
  /// laws, in order.
  bool resistance(const ContactLaw* c, double t, int s, double* d) const;
  /// The joint event functions of the stuck gear and its contacts at the forces (F_a, F_b) from
  /// everything else (header): ev[0] = m_{+1}(F + d_+), ev[1] = m_{−1}(F + d_−), 1 where blocked.
  void events(const LossyGearLaw& g, const ContactLaw* c, double t, double Fa, double Fb, double* ev) const;
  /// The rounding allowance of those margins (LossyGearLaw::allowance over the forces involved).
  [[nodiscard]] double allowance(const LossyGearLaw& g, const ContactLaw* c, double t, double Fa, double Fb) const;
  /// The direction the gear and its contacts start in at rest: +1, −1, or 0 (they stay stuck); a
  /// margin counts as negative below −`tol` (allowance(), 0 for a fired event).
  [[nodiscard]] int start(const LossyGearLaw& g, const ContactLaw* c, double t, double Fa, double Fb, double tol) const;
};

/// The locks of a model: `locks` one per lossy gear with such contacts, `of_gear[g]` the index of
/// gear g's lock (−1: none), `owner[k]` the gear contact k belongs to (−1: none).
struct GearLocks {
  std::vector<GearLock> locks;
  std::vector<int> of_gear, owner;
  [[nodiscard]] bool empty() const { return locks.empty(); }
};

/// The locks of the gears and contacts (those on a gear's body that compile admitted).
GearLocks gear_locks(const std::vector<LossyGearLaw>& gears, const std::vector<ContactLaw>& contacts);

}  // namespace machdyn
