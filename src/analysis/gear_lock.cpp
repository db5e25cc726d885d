#include "machdyn/analysis/gear_lock.hpp"

#include <algorithm>
#include <cmath>

namespace machdyn {

bool GearLock::resistance(const ContactLaw* c, double t, int s, double* d) const {
  d[0] = d[1] = 0.0;
  for (size_t j = 0; j < contacts.size(); ++j) {
    const ContactLaw& k = c[contacts[j]];
    // The bound of its stuck load that opposes the start (elements/contact.hpp's stick rule).
    double lo = -HUGE_VAL, hi = HUGE_VAL;
    if (k.lock > 0) lo = -k.free_limit();
    else if (k.lock < 0) hi = k.free_limit();
    else hi = k.static_limit(t), lo = -hi;
    const double lam = s * kappa[j] > 0.0 ? hi : lo;
    if (!std::isfinite(lam)) return false;
    d[0] += ea[j] * lam, d[1] += eb[j] * lam;
  }
  return true;
}

void GearLock::events(const LossyGearLaw& g, const ContactLaw* c, double t, double Fa, double Fb, double* ev) const {
  for (int s : {+1, -1}) {
    double d[2];
    ev[s > 0 ? 0 : 1] = resistance(c, t, s, d) ? g.start_margin(s, Fa + d[0], Fb + d[1]) : 1.0;
  }
}

double GearLock::allowance(const LossyGearLaw& g, const ContactLaw* c, double t, double Fa, double Fb) const {
  double Da = 0.0, Db = 0.0;
  for (int s : {+1, -1}) {
    double d[2];
    if (resistance(c, t, s, d)) Da = std::max(Da, std::abs(d[0])), Db = std::max(Db, std::abs(d[1]));
  }
  return g.allowance(std::abs(Fa) + Da, std::abs(Fb) + Db);
}

int GearLock::start(const LossyGearLaw& g, const ContactLaw* c, double t, double Fa, double Fb, double tol) const {
  double ev[2];
  events(g, c, t, Fa, Fb, ev);
  return ev[0] < -tol ? 1 : ev[1] < -tol ? -1 : 0;
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
      double kappa = 0.0, ea = 0.0, eb = 0.0;
      bool on_gear = true;
      for (int p = 0; p < f.row.terms; ++p) {
        const int body = f.row.body[p];
        // The contact puts −w λ on the row's body.
        if (body == k.a) kappa += f.row.w[p], ea -= f.row.w[p];
        else if (body == k.b) kappa += f.row.w[p] / k.i, eb -= f.row.w[p];
        else on_gear = false;
      }
      if (!on_gear || f.row.terms == 0) continue;
      L.contacts.push_back(static_cast<int>(c));
      L.kappa.push_back(kappa);
      L.ea.push_back(ea), L.eb.push_back(eb);
      out.owner[c] = static_cast<int>(g);
    }
    if (L.contacts.empty()) continue;
    out.of_gear[g] = static_cast<int>(out.locks.size());
    out.locks.push_back(std::move(L));
  }
  return out;
}

}  // namespace machdyn
