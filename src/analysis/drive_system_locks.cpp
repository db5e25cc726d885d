// The drive system's side of the gear locks (analysis/gear_lock.hpp): a lossy gear stuck together
// with the friction elements to the ground on its bodies. Their dynamics need nothing here (the stuck
// gear holds both bodies at rest, its contacts' rows solve to λ = 0); what is set here is the split of
// the holding torque (outputs, the gear's X and Y) and the joint event functions.
#include <cmath>

#include "machdyn/analysis/drive_system.hpp"

namespace machdyn {

void DriveSystem::gear_loads(int g, double t, const double* y, double* Fa, double* Fb) {
  evaluate(t, y, f_.data(), fc_.data());
  *Fa = gear_fa_[static_cast<size_t>(g)];
  *Fb = gear_fb_[static_cast<size_t>(g)];
}

void DriveSystem::share_locks(double t, double* fc) {
  for (const GearLock& L : locks_.locks) {
    const auto gi = static_cast<size_t>(L.gear);
    if (gear_mode_[gi] != GearMode::stuck) continue;
    const LossyGearLaw& k = gears_[gi];
    const double Ia = 1.0 / inv_mass_[static_cast<size_t>(k.a)], Ib = 1.0 / inv_mass_[static_cast<size_t>(k.b)];
    if (L.blocked != 0) {  // a backstop carries what the gear's locking range leaves
      const auto c = static_cast<size_t>(L.contacts[0]);
      const double lam = backstop_load(L, k, contacts_[c], gear_fa_[gi], gear_fb_[gi]);
      double e[2];
      backstop_direction(L, contacts_[c], e);
      if (mode_[c] == ContactMode::stuck) fc[c] = lam;
      gear_t_[gi] = k.solve(GearMode::stuck, gear_fa_[gi] + lam * e[0], gear_fb_[gi] + lam * e[1], Ia, Ib, 0.0);
      continue;
    }
    double d[2];
    L.limit_forces(contacts_.data(), t, d);
    const double th = lock_share(k, gear_fa_[gi], gear_fb_[gi], d);
    for (size_t j = 0; j < L.contacts.size(); ++j) {
      const auto c = static_cast<size_t>(L.contacts[j]);
      if (mode_[c] == ContactMode::stuck) fc[c] = th * (L.kappa[j] > 0.0 ? 1.0 : -1.0) * contacts_[c].static_limit(t);
    }
    gear_t_[gi] = k.solve(GearMode::stuck, gear_fa_[gi] + th * d[0], gear_fb_[gi] + th * d[1], Ia, Ib, 0.0);
  }
}

void DriveSystem::lock_event_functions(double t, double* g) const {
  for (const GearLock& L : locks_.locks) {
    for (int c : L.contacts) g[2 * nl_ + 2 * c] = g[2 * nl_ + 2 * c + 1] = 1.0;  // the gear's events are theirs
    const auto gi = static_cast<size_t>(L.gear);
    if (gear_mode_[gi] != GearMode::stuck) continue;
    double* ev = g + 2 * (nl_ + nc_ + nd_ + L.gear);
    if (L.blocked != 0) {
      backstop_events(L, gears_[gi], gear_fa_[gi], gear_fb_[gi], ev);
      continue;
    }
    double d[2];
    L.limit_forces(contacts_.data(), t, d);
    lock_events(gears_[gi], gear_fa_[gi], gear_fb_[gi], d, ev);
    if (gear_joint_[gi] != 0) {  // held on its locking range by the split (split_stuck_gears): its limit's allowance
      const double tol = gears_[gi].allowance(std::abs(gear_fa_[gi]) + std::abs(d[0]), std::abs(gear_fb_[gi]) + std::abs(d[1]));
      ev[0] += tol, ev[1] += tol;
    }
  }
}

}  // namespace machdyn
