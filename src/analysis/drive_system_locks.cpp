// The drive system's side of the gear locks (analysis/gear_lock.hpp): a lossy gear stuck together
// with the friction elements to the ground on its bodies. Their dynamics need nothing here (the stuck
// gear holds both bodies at rest, its contacts' rows solve to λ = 0); what is set here is the split of
// the holding torque (outputs, the gear's X and Y) and the joint event functions. Neither is a mode
// decision: the split is the bounded split of the stuck set's rule (analysis/gear_split.hpp
// gear_friction_split), the events are its admissible set's boundary.
#include <cmath>

#include <Eigen/Core>

#include "analysis/bounded_share.hpp"
#include "analysis/gear_split.hpp"
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
    const auto nk = static_cast<Eigen::Index>(L.contacts.size());
    Eigen::VectorXd ea(nk), eb(nk), w(nk), lo(nk), hi(nk);
    for (Eigen::Index j = 0; j < nk; ++j) {
      const int c = L.contacts[static_cast<size_t>(j)];
      ea(j) = L.ea[static_cast<size_t>(j)], eb(j) = L.eb[static_cast<size_t>(j)];
      w(j) = share_weight(c, t);
      detail::stuck_bounds(contacts_[static_cast<size_t>(c)], t, &lo(j), &hi(j));
    }
    Eigen::VectorXd lam = Eigen::VectorXd::Zero(nk);
    if (const auto split = detail::gear_friction_split(k, gear_fa_[gi], gear_fb_[gi], ea, eb, w, lo, hi)) {
      lam = *split;
    } else if (const int s = L.start(k, contacts_.data(), t, gear_fa_[gi], gear_fb_[gi], 0.0); s != 0) {
      // Beyond the locking range by rounding (the decision's allowance): every contact at the bound
      // that opposes the start.
      for (Eigen::Index j = 0; j < nk; ++j) lam(j) = s * L.kappa[static_cast<size_t>(j)] > 0.0 ? hi(j) : lo(j);
    }
    double Fa = gear_fa_[gi], Fb = gear_fb_[gi];
    for (Eigen::Index j = 0; j < nk; ++j) {
      const auto c = static_cast<size_t>(L.contacts[static_cast<size_t>(j)]);
      if (mode_[c] == ContactMode::stuck) fc[c] = lam(j);
      Fa += ea(j) * lam(j), Fb += eb(j) * lam(j);
    }
    gear_t_[gi] = k.solve(GearMode::stuck, Fa, Fb, 1.0 / inv_mass_[static_cast<size_t>(k.a)],
                          1.0 / inv_mass_[static_cast<size_t>(k.b)], 0.0);
  }
}

void DriveSystem::lock_event_functions(double t, double* g) const {
  for (const GearLock& L : locks_.locks) {
    for (int c : L.contacts) g[2 * nl_ + 2 * c] = g[2 * nl_ + 2 * c + 1] = 1.0;  // the gear's events are theirs
    const auto gi = static_cast<size_t>(L.gear);
    if (gear_mode_[gi] != GearMode::stuck) continue;
    double* ev = g + 2 * (nl_ + nc_ + nd_ + L.gear);
    L.events(gears_[gi], contacts_.data(), t, gear_fa_[gi], gear_fb_[gi], ev);
    if (gear_joint_[gi] != 0) {  // held on its locking range by the split (split_stuck_gears): its limit's allowance
      const double tol = L.allowance(gears_[gi], contacts_.data(), t, gear_fa_[gi], gear_fb_[gi]);
      ev[0] += tol, ev[1] += tol;
    }
  }
}

}  // namespace machdyn
