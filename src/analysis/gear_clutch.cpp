#include "machdyn/analysis/gear_clutch.hpp"

#include <cmath>

#include "machdyn/analysis/contact_decision.hpp"
#include "machdyn/common/diagnostics.hpp"

namespace machdyn {
namespace {

/// The side event of gear g (≥ 0 while its driving side holds) in mode md at (t, y).
double side_event(DriveSystem& sys, int g, GearMode md, double t, const double* y) {
  sys.set_gear_mode(g, md);
  double Fa = 0.0, Fb = 0.0, ev[2];
  sys.gear_loads(g, t, y, &Fa, &Fb);
  const LossyGearLaw& k = sys.lossy_gear(g);
  k.events(md, Fa, Fb, sys.inertia(k.a), sys.inertia(k.b), y[sys.dof() + k.a], sys.gear_torques(g, t, y), ev);
  return ev[1];
}

}  // namespace

GearMode settle_rolling_side(DriveSystem& sys, int g, int s, double t, const double* y) {
  const GearMode a_drives = s > 0 ? GearMode::forward : GearMode::backward;
  const GearMode b_side = s > 0 ? GearMode::forward_b : GearMode::backward_b;
  const double ea = side_event(sys, g, a_drives, t, y);
  if (ea >= 0.0) return a_drives;
  const double eb = side_event(sys, g, b_side, t, y);
  const GearMode md = eb >= ea ? b_side : a_drives;
  sys.set_gear_mode(g, md);
  return md;
}

void DriveSystem::settle_gear_sides(double t, const double* y) {
  for (int g = 0; g < ng_; ++g) {
    const int s = direction(gear_mode_[static_cast<size_t>(g)]);
    if (coupled_gear(g) && s != 0) (void)settle_rolling_side(*this, g, s, t, y);
  }
}

GearMode decide_gear_at_rest(DriveSystem& sys, int g, double t, const double* y, bool strict,
                             const std::vector<int>& strict_contacts) {
  const LossyGearLaw& k = sys.lossy_gear(g);
  std::vector<int> Z;  // the contacts at zero sliding speed, decided with the gear (with clutches on it)
  if (sys.coupled_gear(g))
    for (int c = 0; c < static_cast<int>(sys.model().contacts.size()); ++c) {
      const ContactLaw& law = sys.contact(c);
      if (law.joint || law.kinematic || sys.gear_locks().owner[static_cast<size_t>(c)] >= 0) continue;
      if (sys.contact_mode(c) == ContactMode::stuck || sys.sliding_velocity(c, t, y) == 0.0) Z.push_back(c);
    }
  // The gear's friction to the ground (analysis/gear_lock.hpp), if any: stuck with it.
  const int li = sys.gear_locks().of_gear[static_cast<size_t>(g)];
  const GearLock* L = li >= 0 ? &sys.gear_locks().locks[static_cast<size_t>(li)] : nullptr;
  auto set_lock = [&](int s) {  // s = 0: stuck; else sliding with the gear rolling in s
    if (!L) return;
    std::vector<ContactMode> modes = sys.contact_modes();
    for (size_t j = 0; j < L->contacts.size(); ++j)
      modes[static_cast<size_t>(L->contacts[j])] = s == 0 ? ContactMode::stuck
                                                   : s * L->kappa[j] > 0.0 ? ContactMode::slip_pos
                                                                           : ContactMode::slip_neg;
    sys.set_contact_modes(modes);
  };
  // 1. The gear holds (with its ground friction), with the stuck clutches' loads in F_a, F_b.
  sys.set_gear_mode(g, GearMode::stuck);
  set_lock(0);
  if (!Z.empty()) (void)decide_contacts(sys, t, y, Z, strict_contacts);
  double Fa = 0.0, Fb = 0.0;
  sys.gear_loads(g, t, y, &Fa, &Fb);
  int s = 0;
  if (L) {
    const double tol = strict ? 0.0 : L->allowance(k, &sys.contact(0), t, Fa, Fb);
    s = L->start(k, &sys.contact(0), t, Fa, Fb, tol);
  } else {
    const double tol = strict ? 0.0 : k.allowance(std::abs(Fa), std::abs(Fb));
    s = k.start_margin(+1, Fa, Fb) < -tol ? 1 : k.start_margin(-1, Fa, Fb) < -tol ? -1 : 0;
  }
  if (s == 0) return GearMode::stuck;
  // 2. It starts where its margin failed (its ground friction sliding with it), the contacts decided
  //    again with it rolling.
  sys.set_gear_mode(g, s > 0 ? GearMode::forward : GearMode::backward);
  set_lock(s);
  if (!Z.empty()) (void)decide_contacts(sys, t, y, Z, strict_contacts);
  if (!sys.coupled_gear(g)) {  // its driving side by its law, at the contacts' kinetic forces
    sys.gear_loads(g, t, y, &Fa, &Fb);
    const GearMode md = k.rolling(s, Fa, Fb, sys.inertia(k.a), sys.inertia(k.b), 0.0);
    sys.set_gear_mode(g, md);
    return md;
  }
  const GearMode md = settle_rolling_side(sys, g, s, t, y);
  const double a = sys.gear_torques(g, t, y).acc;
  if (L && a == 0.0) {
    // The contacts hold the gear's other side (a chain stuck to a brake): the start moves nothing, and
    // its ground friction would slide at rest. The gear holds with them (step 1's modes).
    sys.set_gear_mode(g, GearMode::stuck);
    set_lock(0);
    if (!Z.empty()) (void)decide_contacts(sys, t, y, Z, strict_contacts);
    return GearMode::stuck;
  }
  if (s * a >= -1e-12 * std::abs(a)) return md;
  throw SolverError(k.spec->name, t,
                    "no consistent modes of the lossy gear and the clutches on its bodies at rest (analysis/gear_clutch.hpp)");
}

}  // namespace machdyn
