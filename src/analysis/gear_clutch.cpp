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

GearMode decide_gear_clutch(DriveSystem& sys, int g, double t, const double* y, bool strict,
                            const std::vector<int>& strict_contacts) {
  const LossyGearLaw& k = sys.lossy_gear(g);
  std::vector<int> Z;  // the contacts at zero sliding speed, decided with the gear
  for (int c = 0; c < static_cast<int>(sys.model().contacts.size()); ++c) {
    const ContactLaw& law = sys.contact(c);
    if (law.joint || law.kinematic || sys.gear_locks().owner[static_cast<size_t>(c)] >= 0) continue;
    if (sys.contact_mode(c) == ContactMode::stuck || sys.sliding_velocity(c, t, y) == 0.0) Z.push_back(c);
  }
  // 1. The gear holds, with the stuck clutches' loads in F_a, F_b.
  sys.set_gear_mode(g, GearMode::stuck);
  if (!Z.empty()) (void)decide_contacts(sys, t, y, Z, strict_contacts);
  double Fa = 0.0, Fb = 0.0;
  sys.gear_loads(g, t, y, &Fa, &Fb);
  const double tol = strict ? 0.0 : k.allowance(Fa, Fb);
  const double mp = k.start_margin(+1, Fa, Fb), mm = k.start_margin(-1, Fa, Fb);
  if (mp >= -tol && mm >= -tol) return GearMode::stuck;
  // 2. It starts where its margin failed, the contacts decided again with it rolling.
  const int s = mp < -tol ? 1 : -1;
  sys.set_gear_mode(g, s > 0 ? GearMode::forward : GearMode::backward);
  if (!Z.empty()) (void)decide_contacts(sys, t, y, Z, strict_contacts);
  const GearMode md = settle_rolling_side(sys, g, s, t, y);
  const double a = sys.gear_torques(g, t, y).acc;
  if (s * a >= -1e-12 * std::abs(a)) return md;
  throw SolverError(k.spec->name, t,
                    "no consistent modes of the lossy gear and the clutches on its bodies at rest (analysis/gear_clutch.hpp)");
}

}  // namespace machdyn
