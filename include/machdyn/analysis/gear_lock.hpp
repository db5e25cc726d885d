#pragma once
/// @file
/// A lossy gear decided together with the friction elements to the ground on its bodies (brakes,
/// ground contacts, MSL's BearingFriction): the joint law at rest. The gear's law stays in
/// elements/lossy_gear.hpp, the friction's in elements/contact.hpp; this file only joins them.
///
/// Such a contact k (row on one of the gear's bodies, to the fixed ground) slides with
/// u_k = κ_k v_a, κ_k = Σ w_j over a's terms + Σ w_j / i over b's. So while the gear rolls every
/// contact slides (its kinetic force is one of the forces F_a, F_b the gear's law solves with), and
/// at rest the gear and its contacts are stuck together or start together. Stuck together, any loads
/// λ_k give a = 0: the split of the holding torque between the gear and the friction is not unique
/// (MSL's LossyGearDemo2 notes it). Let F_a, F_b be the forces on the two bodies from everything
/// else and d = (d_a, d_b) the forces of the contacts at their static limits against forward rolling,
///   d_j = −Σ_k w_kj sign(κ_k) F_s,k(t)    (contact k puts −w_kj λ_k on body j).
/// Since m_{+1} never increases and m_{−1} never decreases with the forward forces
/// (elements/lossy_gear.hpp), the pair holds
///   against a forward start   ⇔  m_{+1}(F + d) ≥ 0   (every contact at its limit against it),
///   against a backward start  ⇔  m_{−1}(F − d) ≥ 0,
/// and these are the joint event functions of the stuck pair (the contacts' own limits are not
/// events while their gear is stuck: m_{+1}(F + θ d), m_{−1}(F + θ d) cannot both be negative, so
/// both conditions give a split within every limit). The split (outputs, the held torques):
///   λ_k = θ sign(κ_k) F_s,k(t),  θ ∈ [−1, 1] the value closest to 0 with m_{±1}(F + θ d) ≥ 0,
/// i.e. the gear holds what its locking range allows and the friction elements carry only the rest,
/// shared in proportion to their static limits (as stuck contacts share a locked load,
/// docs/hybrid.md). θ is continuous in the forces; it reaches ±1 exactly where a joint event fires.
/// A start in s sets the gear rolling in s (driving side by its law with the contacts' kinetic
/// forces) and every contact sliding in sign(s κ_k): consistent, as F_k(0) ≤ F_s.
/// Backstop: a freewheel to the ground ([ground, A], free direction −lock in u) on one of the gear's
/// bodies blocks the gear's rolling direction s_b = lock·sign(κ) and lets it roll in −s_b, sliding
/// freely with it. It has no upper limit, so stuck with it the gear never starts in s_b (that event
/// is 1) and starts in −s_b where its own margin m_{−s_b}(F) < 0 (the backstop carries nothing against
/// it). The split: the gear holds what its locking range allows, the backstop the rest: λ = 0 while
/// m_{s_b}(F) ≥ 0, else the λ (lock·λ > 0) with m_{s_b}(F + λ e) = 0, e its force on (a, b) per unit λ.
/// Supported (compile checks): contacts with a row on exactly one of the gear's bodies and the
/// ground, no moving surface, not a stop or joint; a backstop only as the one friction element on the
/// gear's bodies (no brake or clutch beside it). With a clutch on the same gear the
/// decision at rest is analysis/gear_clutch.hpp's, which takes these events and this split.

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
  int blocked = 0;            ///< a backstop's blocked rolling direction s_b (header), 0: none

  /// d (size 2: on a, on b): the contacts' forces at their static limits F_s(t) against forward
  /// rolling (header); `c` the model's contact laws, in order.
  void limit_forces(const ContactLaw* c, double t, double* d) const;
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

/// The joint event functions of a stuck gear with its contacts stuck (header), ≥ 0 while they hold.
void lock_events(const LossyGearLaw& g, double Fa, double Fb, const double* d, double* ev);
/// The direction the gear and its contacts start in at rest: +1, −1, or 0 (they stay stuck); a
/// margin counts as negative below −`tol` (LossyGearLaw::allowance, 0 for a fired event).
[[nodiscard]] int lock_start(const LossyGearLaw& g, double Fa, double Fb, const double* d, double tol);
/// θ of the split (header) for a pair that holds; clamped to [−1, 1] otherwise.
[[nodiscard]] double lock_share(const LossyGearLaw& g, double Fa, double Fb, const double* d);

/// A backstop lock (L.blocked ≠ 0; header): its joint events at the forces F on the gear's bodies.
void backstop_events(const GearLock& L, const LossyGearLaw& g, double Fa, double Fb, double* ev);
/// A backstop lock's load λ of the split (header) at F; its contact's row in `c`.
[[nodiscard]] double backstop_load(const GearLock& L, const LossyGearLaw& g, const ContactLaw& c, double Fa, double Fb);
/// The force (e_a, e_b) a backstop's load puts on the gear's bodies per unit λ.
void backstop_direction(const GearLock& L, const ContactLaw& c, double* e);

class DriveSystem;
/// The joint decision at rest of gear g and its contacts at (t, y): sets their modes in `sys` (the gear
/// stuck or rolling, the contacts stuck or sliding with it) and returns the gear's; `strict`: the
/// gear's event fired (no rounding allowance). The gear's bodies must be at rest.
GearMode decide_gear_lock(DriveSystem& sys, int g, double t, const double* y, bool strict);

}  // namespace machdyn
