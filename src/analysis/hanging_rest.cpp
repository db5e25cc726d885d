// The state a topology's linear model is taken about: a load that starts on the floor hangs
// (analysis/hanging_rest.hpp, docs/sway.md "Pendulum modes").
#include "machdyn/analysis/hanging_rest.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "machdyn/elements/spatial_rope.hpp"

namespace machdyn {

namespace hanging_rest_detail {

/// Whether body `z` starts on a lower end stop (its position at or below the stop's), and whether
/// one of those stops holds it in `topo` (engaged and stuck).
struct Floor {
  bool starts_on = false, holds = false;
};
Floor floor_under(const Model& m, const Topology& topo, int z) {
  Floor f;
  const double q0 = m.bodies[static_cast<size_t>(z)].q0;
  for (size_t k = 0; k < m.contacts.size(); ++k) {
    const FrictionContact& c = m.contacts[k];
    if (!c.stop || c.lock != -1 || c.a != z) continue;  // a lower stop (q ≥ q_stop) under z
    if (!(q0 - c.stop_position <= 1e-9 * std::max(1.0, std::fabs(c.stop_position)))) continue;
    f.starts_on = true;
    const bool engaged = topo.engaged.empty() || topo.engaged[k];
    f.holds = f.holds || (engaged && topo.contacts[k] == ContactMode::stuck);
  }
  return f;
}

}  // namespace hanging_rest_detail

std::vector<double> linearization_state(const Model& m, const Topology& topo) {
  const int n = m.dof();
  std::map<int, int> ropes;  // per load (its z body): the spatial ropes it hangs on
  for (const Drive& d : m.drives)
    if (dynamic_cast<const SpatialRope*>(d.law.get())) ++ropes[d.body];  // port 0: the load's z
  std::vector<double> y;
  for (const Drive& d : m.drives) {
    const auto* rope = dynamic_cast<const SpatialRope*>(d.law.get());
    if (!rope || ropes[d.body] != 1) continue;
    const hanging_rest_detail::Floor f = hanging_rest_detail::floor_under(m, topo, d.body);
    if (!f.starts_on || f.holds) continue;
    if (y.empty()) {
      y.resize(static_cast<size_t>(2 * n));
      for (int i = 0; i < n; ++i)
        y[static_cast<size_t>(i)] = m.bodies[static_cast<size_t>(i)].q0, y[static_cast<size_t>(n + i)] = m.bodies[static_cast<size_t>(i)].v0;
    }
    ElementMotion b;
    b.n = d.ports();
    auto body_of = [&](int p) { return static_cast<size_t>(p == 0 ? d.body : d.others[static_cast<size_t>(p - 1)]); };
    for (int p = 0; p < b.n; ++p) b.q[p] = y[body_of(p)];
    if (!rope->hang(b, m.gravity)) continue;
    for (int p = 0; p < b.n; ++p)
      if (rope->role[p] == SpatialRope::Role::load_x || rope->role[p] == SpatialRope::Role::load_y ||
          rope->role[p] == SpatialRope::Role::load_z)
        y[body_of(p)] = b.q[p], y[static_cast<size_t>(n) + body_of(p)] = 0.0;  // at rest
  }
  return y;
}

}  // namespace machdyn
