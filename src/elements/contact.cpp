#include "machdyn/elements/contact.hpp"

#include <algorithm>

namespace machdyn {

ContactLaw ContactLaw::of(const FrictionContact& c) {
  ContactLaw k;
  k.spec = &c;
  k.a = c.a, k.b = c.b;
  k.joint = c.joint;
  k.general = c.row.terms > 0;
  k.grounded = c.b < 0 && !c.joint;
  if (k.general) {
    k.row = c.row;
  } else {
    k.row.terms = c.b >= 0 ? 2 : 1;
    k.row.body[0] = c.a, k.row.w[0] = 1.0;
    k.row.body[1] = c.b, k.row.w[1] = -1.0;
  }
  k.kinetic_table = c.kinetic.size() > 1 || c.stribeck_speed > 0.0;
  k.applied = c.applied;
  k.moving_surface = c.surface_times.size() > 1;
  k.brake = c.brake;
  k.lock = c.lock;
  k.stop = c.stop;
  k.stop_position = c.stop_position;
  k.restitution = c.restitution;
  k.kinetic0 = c.kinetic.empty() ? 0.0 : c.kinetic.front();
  k.surface0 = c.surface_velocities.empty() ? 0.0 : c.surface_velocities.front();
  return k;
}

ContactLaw ContactLaw::of(const FrictionContact& c, const Model& m) {
  ContactLaw k = of(c);
  k.kinematic = !c.joint;
  for (int j = 0; j < k.row.terms; ++j)
    k.kinematic = k.kinematic && k.row.body[j] >= 0 &&
                  m.bodies[static_cast<size_t>(k.row.body[j])].motion != MotionKind::free;
  if (k.lock != 0) k.hold_tol = hold_allowance(hold_stiffness(c, m), m.simulation.atol);
  return k;
}

double ContactLaw::hold_stiffness(const FrictionContact& c, const Model& m) {
  // The lock's bodies: its row's (a, b; a general row's terms).
  int body[VelocityRow::kMaxTerms + 2] = {};
  int n = 0;
  if (c.row.terms > 0) {
    for (int j = 0; j < c.row.terms; ++j) body[n++] = c.row.body[j];
  } else {
    body[n++] = c.a, body[n++] = c.b;
  }
  auto on = [&](int x) {
    if (x < 0) return false;
    for (int j = 0; j < n; ++j)
      if (body[j] == x) return true;
    return false;
  };
  double k = 0.0;
  for (const Link& l : m.links) {
    // A rope of EA: its stiffness n EA/L_f0 at its free length; d per 1 s (a rate known to atol in m/s).
    const double c_l = l.EA > 0.0 && l.length > 0.0 ? l.falls * l.EA / l.length : l.c;
    const double cd = c_l + l.d;
    // Each link once: one between the lock's two bodies enters λ once (its force on both cancels in
    // their relative motion but for one share), at b, else at a divided by i (its force acts on a as F/i).
    if (on(l.b)) k += cd;
    else if (on(l.a)) k += cd / (l.ratio * l.ratio);
  }
  return k;
}

double ContactLaw::kinetic_slope(double t, double u) const {
  if (!kinetic_table) return 0.0;
  // F = ±r F_k0(|u|): dF/du = r F_k0′(|u|) in either direction.
  return scale(t) * spec->kinetic_level_slope(u);
}

double ContactLaw::steepest_kinetic_slope() const {
  double slope = 0.0;
  if (spec->stribeck_speed > 0.0) return slope;  // falls from F_s0 ≥ F_c
  const auto& x = spec->speeds;
  const auto& y = spec->kinetic;
  for (size_t i = 0; i + 1 < x.size() && i + 1 < y.size(); ++i)
    slope = std::max(slope, (y[i + 1] - y[i]) / (x[i + 1] - x[i]));
  return slope;
}

void ContactLaw::add_linear(ContactMode md, bool engaged, double t, double u, LinearModel& lin) const {
  if (joint) md = ContactMode::stuck;  // in every topology
  else if (!engaged || kinematic) return;
  if (md == ContactMode::stuck) {
    std::vector<std::pair<int, double>> g;
    for (int j = 0; j < row.terms; ++j) g.emplace_back(row.body[j], row.w[j]);
    lin.G.push_back(std::move(g));
    lin.constraint_names.push_back(spec->name);
    return;
  }
  LinearModel::add_outer(lin.D, row.body, row.w, row.terms, kinetic_slope(t, u));
}

}  // namespace machdyn
