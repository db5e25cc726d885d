// `releases:` (model/compile_release.hpp): a body loses ΔI of its inertia at t_r. The weight the
// released part had leaves with it: the body's "NAME.weight" load −vertical·m·g becomes
// −vertical·(m − Δm)·g, i.e. it changes by +vertical·Δm·g (model/model.hpp: Release).
#include "model/compile_release.hpp"

#include <algorithm>
#include <fmt/format.h>

namespace machdyn::detail {

void compile_releases(const SpecNode* section, Model& m, Diagnostics& diag) {
  if (!section) return;
  if (!section->is_map()) {
    diag.error(section->loc, "'releases' must be a map of NAME: {body, mass, time}");
    return;
  }
  std::vector<double> released(m.bodies.size(), 0.0);  // Σ ΔI per body so far (in its own coordinate)
  std::vector<double> released_slave(m.slaves.size(), 0.0);
  for (const auto& [name, spec] : section->fields) {
    FieldReader f(spec, fmt::format("release '{}'", name), diag);
    Release r;
    const std::optional<std::string> body = f.text("body");
    // The body: an ordinary one, or one slaved by ideal gears (acting on its master through ρ).
    int idx = -2, slave = -1;
    if (body) {
      for (size_t s = 0; s < m.slaves.size(); ++s)
        if (m.slaves[s].name == *body) slave = static_cast<int>(s);
      idx = slave >= 0 ? m.slaves[static_cast<size_t>(slave)].master : m.body_index(*body);
      if (slave >= 0 && m.slaves[static_cast<size_t>(slave)].master2 >= 0) {  // a joint's member without inertia
        f.error_at("body", fmt::format("release '{}': body '{}' has no inertia (a gear joint moves it), so it has no "
                                       "mass to release", name, *body));
        idx = -2;
      } else if (idx < 0) f.error_at("body", fmt::format("release '{}': unknown body '{}'", name, *body));
      else if (m.bodies[static_cast<size_t>(idx)].machine)
        f.error_at("body", fmt::format("release '{}': body '{}' has a variable inertia I(q); a release on a machine body "
                                       "is not supported (give the released mass as a body of its own)", name, *body));
    }
    const bool ok = idx >= 0 && !m.bodies[static_cast<size_t>(idx)].machine;
    // A merged gear's torque sums the inertias of its side at t = 0: none for a side that releases mass.
    if (body)
      std::erase_if(m.merged_gears, [&](const MergedGear& g) { return std::find(g.side.begin(), g.side.end(), *body) != g.side.end(); });
    const BodyKind kind = slave >= 0 ? m.slaves[static_cast<size_t>(slave)].kind
                          : ok       ? m.bodies[static_cast<size_t>(idx)].kind
                                     : BodyKind::translational;
    const bool rot = kind == BodyKind::rotational;
    const char* key = rot ? "inertia" : "mass";
    const char* other = rot ? "mass" : "inertia";
    if (ok && spec.is_map() && spec.find(other)) {
      f.error_at(other, fmt::format("release '{}': a {} body releases '{}', not '{}'", name,
                                    rot ? "rotational" : "translational", key, other));
      f.node(other);
    }
    double dI = 0.0, t_r = 0.0;  // ΔI and t_r as given (a value only where the fields are valid)
    bool valid = ok;
    if (ok) {
      const std::optional<double> a = f.positive(key, rot ? dim::inertia : dim::mass);
      valid = valid && a.has_value();
      dI = a.value_or(0.0);
    } else {  // no body to give the amount a dimension: only mark the fields read
      f.node("mass");
      f.node("inertia");
    }
    const std::optional<double> time = f.positive("time", dim::time, std::nullopt, true);
    valid = valid && time.has_value();
    t_r = time.value_or(0.0);
    f.finish();
    if (!valid) continue;
    // What the body may lose: its own inertia (a master's without its slaves' share, a slave's own).
    double own = m.bodies[static_cast<size_t>(idx)].inertia, rho = 1.0;
    double* sum = &released[static_cast<size_t>(idx)];
    if (slave >= 0) {
      own = m.slaves[static_cast<size_t>(slave)].inertia;
      rho = m.slaves[static_cast<size_t>(slave)].ratio;
      sum = &released_slave[static_cast<size_t>(slave)];
    } else {
      for (const RigidSlave& s : m.slaves)
        if (s.master == idx) own -= s.ratio * s.ratio * s.inertia;
    }
    *sum += dI;
    if (*sum >= own) {
      f.error_at(key, fmt::format("release '{}': '{}' would lose {:.6g} {} of its {} {:.6g} {}{}; a release must "
                                  "leave part of the body", name, *body, *sum, rot ? "kg*m^2" : "kg", key, own,
                                  rot ? "kg*m^2" : "kg", *sum > dI ? " (with its earlier releases)" : ""));
      continue;
    }
    if (slave < 0) {
      r = body_release(m, name, idx, dI, t_r);
    } else {
      // On a slave: ΔI = ρ² Δm on the master; its weight load is ρ·(−vertical·m_s·g) (model/
      // compile_rigid.cpp), of which the released fraction Δm/m_s leaves.
      r.name = name;
      r.body = idx;
      r.amount = rho * rho * dI;
      r.time = t_r;
      const std::string weight = *body + ".weight";
      for (size_t k = 0; k < m.loads.size(); ++k)
        if (m.loads[k].name == weight && m.loads[k].kind == LoadKind::constant) {
          r.weight_load = static_cast<int>(k);
          r.weight_change = -m.loads[k].value * (dI / own);
        }
    }
    m.releases.push_back(r);
  }
  std::stable_sort(m.releases.begin(), m.releases.end(),
                   [](const Release& a, const Release& b) { return a.time < b.time; });
}

}  // namespace machdyn::detail
