#include "machdyn/analysis/gear_clutch.hpp"

#include <algorithm>
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

/// The gears at rest tied to gear g by clutches at zero sliding speed (stuck, or u = 0), g first: a
/// stuck clutch between two gears' bodies makes them one degree of freedom, so their starts are
/// decided together (decide_gear_at_rest).
std::vector<int> gears_tied_at_rest(DriveSystem& sys, int g, double t, const double* y) {
  std::vector<int> group{g};
  const int n = sys.dof(), ng = static_cast<int>(sys.model().lossy_gears.size());
  auto gear_of = [&](int body) {
    for (int h = 0; h < ng; ++h)
      if (sys.lossy_gear(h).a == body || sys.lossy_gear(h).b == body) return h;
    return -1;
  };
  for (size_t q = 0; q < group.size(); ++q) {
    const LossyGearLaw& k = sys.lossy_gear(group[q]);
    for (int c = 0; c < static_cast<int>(sys.model().contacts.size()); ++c) {
      const ContactLaw& law = sys.contact(c);
      if (law.joint || law.kinematic || law.general || law.b < 0 || sys.gear_locks().owner[static_cast<size_t>(c)] >= 0)
        continue;
      if (sys.contact_mode(c) != ContactMode::stuck && sys.sliding_velocity(c, t, y) != 0.0) continue;
      const bool on_a = law.a == k.a || law.a == k.b, on_b = law.b == k.a || law.b == k.b;
      if (on_a == on_b) continue;
      const int h = gear_of(on_a ? law.b : law.a);
      if (h < 0 || y[n + sys.lossy_gear(h).a] != 0.0 || std::find(group.begin(), group.end(), h) != group.end()) continue;
      group.push_back(h);
    }
  }
  return group;
}

/// Gears tied at rest (gears_tied_at_rest, two or more): their start directions enumerated together,
/// as a two-stage train's (analysis/gear_train.hpp): each gear stuck or starting in ±1, the fewest
/// starts first; for each the contacts at zero sliding speed Z decided with them and the rolling
/// gears' sides settled; the first consistent combination kept (every stuck gear within its margins,
/// with its ground friction's; every starting gear accelerating in its direction, s a > 0). Leaves
/// `sys` in it and returns gear `group[0]`'s mode.
GearMode decide_tied_gears_at_rest(DriveSystem& sys, const std::vector<int>& group, const std::vector<int>& Z, double t,
                                   const double* y, bool strict, const std::vector<int>& strict_contacts) {
  const auto ng = static_cast<int>(group.size());
  std::vector<int> dir(static_cast<size_t>(ng), 0);
  auto set_lock = [&](int g, int s) {  // the gear's ground friction stuck (s = 0) or sliding with it
    const int li = sys.gear_locks().of_gear[static_cast<size_t>(g)];
    if (li < 0) return;
    const GearLock& L = sys.gear_locks().locks[static_cast<size_t>(li)];
    std::vector<ContactMode> modes = sys.contact_modes();
    for (size_t j = 0; j < L.contacts.size(); ++j)
      modes[static_cast<size_t>(L.contacts[j])] = s == 0 ? ContactMode::stuck
                                                  : s * L.kappa[j] > 0.0 ? ContactMode::slip_pos
                                                                         : ContactMode::slip_neg;
    sys.set_contact_modes(modes);
  };
  auto consistent = [&]() {
    for (int q = 0; q < ng; ++q) {
      const int g = group[static_cast<size_t>(q)];
      sys.set_gear_mode(g, dir[static_cast<size_t>(q)] == 0 ? GearMode::stuck
                           : dir[static_cast<size_t>(q)] > 0 ? GearMode::forward
                                                             : GearMode::backward);
      set_lock(g, dir[static_cast<size_t>(q)]);
    }
    if (!Z.empty()) (void)decide_contacts(sys, t, y, Z, strict_contacts);
    for (int pass = 0; pass < 2; ++pass)  // the tied gears' sides depend on each other's
      for (int q = 0; q < ng; ++q)
        if (dir[static_cast<size_t>(q)] != 0)
          (void)settle_rolling_side(sys, group[static_cast<size_t>(q)], dir[static_cast<size_t>(q)], t, y);
    for (int q = 0; q < ng; ++q) {
      const int g = group[static_cast<size_t>(q)], s = dir[static_cast<size_t>(q)];
      const LossyGearLaw& k = sys.lossy_gear(g);
      if (s != 0) {
        if (s * sys.gear_torques(g, t, y).acc <= 0.0) return false;
        continue;
      }
      double Fa = 0.0, Fb = 0.0;
      sys.gear_loads(g, t, y, &Fa, &Fb);
      if (const int li = sys.gear_locks().of_gear[static_cast<size_t>(g)]; li >= 0) {
        const GearLock& L = sys.gear_locks().locks[static_cast<size_t>(li)];
        if (L.start(k, &sys.contact(0), t, Fa, Fb, strict ? 0.0 : L.allowance(k, &sys.contact(0), t, Fa, Fb)) != 0)
          return false;
      } else {
        const double tol = strict ? 0.0 : k.allowance(std::abs(Fa), std::abs(Fb));
        if (k.start_margin(+1, Fa, Fb) < -tol || k.start_margin(-1, Fa, Fb) < -tol) return false;
      }
    }
    return true;
  };
  // The combinations by the number of starting gears, then in order (3^n of them: n is 2 or 3).
  int total = 1;
  for (int q = 0; q < ng; ++q) total *= 3;
  for (int starts = 0; starts <= ng; ++starts)
    for (int code = 0; code < total; ++code) {
      int c = code, m = 0;
      for (int q = 0; q < ng; ++q, c /= 3) {
        dir[static_cast<size_t>(q)] = c % 3 == 0 ? 0 : c % 3 == 1 ? 1 : -1;
        m += dir[static_cast<size_t>(q)] != 0;
      }
      if (m == starts && consistent()) return sys.gear_mode(group[0]);
    }
  throw SolverError(sys.lossy_gear(group[0]).spec->name, t,
                    "no consistent modes of the lossy gears a stuck clutch ties at rest (analysis/gear_clutch.hpp)");
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
  // Gears a stuck clutch ties to it at rest: one degree of freedom, their starts decided together.
  if (!Z.empty())
    if (const std::vector<int> tied = gears_tied_at_rest(sys, g, t, y); tied.size() > 1)
      return decide_tied_gears_at_rest(sys, tied, Z, t, y, strict, strict_contacts);
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
