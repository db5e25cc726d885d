#include "machdyn/analysis/gear_lock.hpp"

#include <algorithm>
#include <cmath>

#include "machdyn/analysis/drive_system.hpp"

namespace machdyn {

void GearLock::limit_forces(const ContactLaw* c, double t, double* d) const {
  d[0] = d[1] = 0.0;
  for (size_t j = 0; j < contacts.size(); ++j) {
    const ContactLaw& k = c[contacts[j]];
    // Against forward rolling: the load λ = sign(κ) F_s, which puts −w λ on the row's body.
    const double lam = (kappa[j] > 0.0 ? 1.0 : -1.0) * k.static_limit(t);
    for (int p = 0; p < k.row.terms; ++p) d[k.row.body[p] == a ? 0 : 1] -= k.row.w[p] * lam;
  }
}

GearLocks gear_locks(const std::vector<LossyGearLaw>& gears, const std::vector<ContactLaw>& contacts) {
  GearLocks out;
  out.of_gear.assign(gears.size(), -1);
  out.owner.assign(contacts.size(), -1);
  for (size_t g = 0; g < gears.size(); ++g) {
    const LossyGearLaw& k = gears[g];
    GearLock L;
    L.gear = static_cast<int>(g);
    L.a = k.a, L.b = k.b;
    for (size_t c = 0; c < contacts.size(); ++c) {
      const ContactLaw& f = contacts[c];
      if (f.joint || !f.grounded) continue;
      double kappa = 0.0;
      bool on_gear = true;
      for (int p = 0; p < f.row.terms; ++p) {
        const int body = f.row.body[p];
        if (body == k.a) kappa += f.row.w[p];
        else if (body == k.b) kappa += f.row.w[p] / k.i;
        else on_gear = false;
      }
      if (!on_gear || f.row.terms == 0) continue;
      L.contacts.push_back(static_cast<int>(c));
      L.kappa.push_back(kappa);
      if (f.lock != 0) L.blocked = f.lock * (kappa > 0.0 ? 1 : -1);  // a backstop (the only one: compile)
      out.owner[c] = static_cast<int>(g);
    }
    if (L.contacts.empty()) continue;
    out.of_gear[g] = static_cast<int>(out.locks.size());
    out.locks.push_back(std::move(L));
  }
  return out;
}

void lock_events(const LossyGearLaw& g, double Fa, double Fb, const double* d, double* ev) {
  ev[0] = g.start_margin(+1, Fa + d[0], Fb + d[1]);
  ev[1] = g.start_margin(-1, Fa - d[0], Fb - d[1]);
}

int lock_start(const LossyGearLaw& g, double Fa, double Fb, const double* d, double tol) {
  double ev[2];
  lock_events(g, Fa, Fb, d, ev);
  return ev[0] < -tol ? 1 : ev[1] < -tol ? -1 : 0;
}

double lock_share(const LossyGearLaw& g, double Fa, double Fb, const double* d) {
  // θ closest to 0 in [θ+, θ−]: m_{+1} rises and m_{−1} falls along F + θ d (header).
  if (g.start_margin(+1, Fa, Fb) < 0.0) {
    if (g.start_margin(+1, Fa + d[0], Fb + d[1]) <= 0.0) return 1.0;
    return g.margin_root(+1, Fa, Fb, d[0], d[1], 0.0, 1.0);
  }
  if (g.start_margin(-1, Fa, Fb) < 0.0) {
    if (g.start_margin(-1, Fa - d[0], Fb - d[1]) <= 0.0) return -1.0;
    return g.margin_root(-1, Fa, Fb, d[0], d[1], -1.0, 0.0);
  }
  return 0.0;
}

void backstop_events(const GearLock& L, const LossyGearLaw& g, double Fa, double Fb, double* ev) {
  const int s_free = -L.blocked;
  ev[s_free > 0 ? 0 : 1] = g.start_margin(s_free, Fa, Fb);
  ev[s_free > 0 ? 1 : 0] = 1.0;  // never starts against the backstop
}

void backstop_direction(const GearLock& L, const ContactLaw& c, double* e) {
  e[0] = e[1] = 0.0;
  for (int p = 0; p < c.row.terms; ++p) e[c.row.body[p] == L.a ? 0 : 1] -= c.row.w[p];
}

double backstop_load(const GearLock& L, const LossyGearLaw& g, const ContactLaw& c, double Fa, double Fb) {
  if (g.start_margin(L.blocked, Fa, Fb) >= 0.0) return 0.0;  // the gear holds alone
  double e[2];
  backstop_direction(L, c, e);
  // λ has the sign of lock; widen the bracket until the margin holds at its end (it rises along it).
  double end = c.lock * (1.0 + std::abs(Fa) + std::abs(Fb));
  for (int k = 0; k < 60 && g.start_margin(L.blocked, Fa + end * e[0], Fb + end * e[1]) < 0.0; ++k) end *= 2.0;
  return c.lock > 0 ? g.margin_root(L.blocked, Fa, Fb, e[0], e[1], 0.0, end)
                    : g.margin_root(L.blocked, Fa, Fb, e[0], e[1], end, 0.0);
}

GearMode decide_gear_lock(DriveSystem& sys, int g, double t, const double* y, bool strict) {
  const GearLock& L = sys.gear_locks().locks[static_cast<size_t>(sys.gear_locks().of_gear[static_cast<size_t>(g)])];
  const LossyGearLaw& k = sys.lossy_gear(g);
  std::vector<ContactMode> modes = sys.contact_modes();
  for (int c : L.contacts) modes[static_cast<size_t>(c)] = ContactMode::stuck;
  sys.set_contact_modes(modes);
  sys.set_gear_mode(g, GearMode::stuck);
  double Fa = 0.0, Fb = 0.0, d[2];
  sys.gear_loads(g, t, y, &Fa, &Fb);
  L.limit_forces(&sys.contact(0), t, d);
  const double tol = strict ? 0.0 : k.allowance(std::abs(Fa) + std::abs(d[0]), std::abs(Fb) + std::abs(d[1]));
  int s = lock_start(k, Fa, Fb, d, tol);
  if (L.blocked != 0) {  // a backstop: only the free direction can start
    double ev[2];
    backstop_events(L, k, Fa, Fb, ev);
    s = ev[0] < -tol ? 1 : ev[1] < -tol ? -1 : 0;
  }
  if (s == 0) return GearMode::stuck;
  // Start together: the contacts slide with the gear, the driving side from their kinetic forces.
  for (size_t j = 0; j < L.contacts.size(); ++j)
    modes[static_cast<size_t>(L.contacts[j])] = s * L.kappa[j] > 0.0 ? ContactMode::slip_pos : ContactMode::slip_neg;
  sys.set_contact_modes(modes);
  sys.gear_loads(g, t, y, &Fa, &Fb);
  const GearMode md = k.rolling(s, Fa, Fb, sys.inertia(k.a), sys.inertia(k.b), 0.0);
  sys.set_gear_mode(g, md);
  return md;
}

}  // namespace machdyn
