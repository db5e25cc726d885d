#include "machdyn/analysis/sway_summary.hpp"

#include <algorithm>
#include <cmath>

#include "machdyn/elements/spatial_rope.hpp"

namespace machdyn {

namespace {

/// The column called `name` of r, or null.
const std::vector<double>* sway_column(const SimulationResult& r, const std::string& name) {
  for (size_t k = 0; k < r.column_names.size(); ++k)
    if (r.column_names[k] == name) return &r.columns[k];
  return nullptr;
}

}  // namespace

std::vector<std::string> sway_rope_names(const Model& m) {
  std::vector<std::string> out;
  for (const Drive& d : m.drives)
    if (dynamic_cast<const SpatialRope*>(d.law.get())) out.push_back(d.name);
  return out;
}

std::vector<SwaySummary> sway_summaries(const Model& m, const SimulationResult& r) {
  std::vector<SwaySummary> out;
  const std::vector<double>* t = sway_column(r, "t_s");
  if (!t) return out;
  for (const Drive& d : m.drives) {
    const auto* rope = dynamic_cast<const SpatialRope*>(d.law.get());
    if (!rope) continue;
    SwaySummary s;
    s.rope = d.name;
    if (rope->sway_after >= 0.0) s.residual_after = rope->sway_after;
    for (const char* col : {"sway_x_rad", "sway_y_rad", "sway_radial_rad", "sway_tangential_rad"}) {
      const std::vector<double>* th = sway_column(r, d.name + "." + col);
      if (!th) continue;
      for (size_t k = 0; k < th->size() && k < t->size(); ++k) {
        const double a = std::abs((*th)[k]);
        if (a > s.max_sway_rad) s.max_sway_rad = a, s.t_max_sway = (*t)[k];
        if (s.residual_after && (*t)[k] >= *s.residual_after) s.residual_sway_rad = std::max(s.residual_sway_rad, a);
      }
    }
    if (const std::vector<double>* H = sway_column(r, d.name + ".horizontal_force_N"))
      for (size_t k = 0; k < H->size() && k < t->size(); ++k)
        if ((*H)[k] > s.max_horizontal_force_N) s.max_horizontal_force_N = (*H)[k], s.t_max_horizontal_force = (*t)[k];
    if (const std::vector<double>* F = sway_column(r, d.name + ".tension_N"))
      for (double f : *F) s.max_tension_N = std::max(s.max_tension_N, f);
    // The suspension point's largest horizontal acceleration from its travel bodies' speeds.
    const std::vector<double>* v[2] = {nullptr, nullptr};
    const SpatialRope::Role travel[2] = {SpatialRope::Role::trolley, SpatialRope::Role::bridge};
    for (int k = 0; k < 2; ++k) {
      const int p = rope->port_of[static_cast<int>(travel[k])];
      if (p < 0) continue;
      const int b = p == 0 ? d.body : d.others[static_cast<size_t>(p - 1)];
      v[k] = sway_column(r, m.bodies[static_cast<size_t>(b)].name + ".velocity_m_s");
    }
    if ((v[0] || v[1]) && !rope->has(SpatialRope::Role::jib)) {
      double a_max = 0.0;
      for (size_t k = 1; k < t->size(); ++k) {
        const double dt = (*t)[k] - (*t)[k - 1];
        if (dt <= 0.0) continue;
        double a2 = 0.0;
        for (const auto* vk : v)
          if (vk && k < vk->size()) a2 += std::pow(((*vk)[k] - (*vk)[k - 1]) / dt, 2);
        a_max = std::max(a_max, std::sqrt(a2));
      }
      if (a_max > 0.0) s.rigid_force_N = rope->mass * a_max, s.dynamic_factor = s.max_horizontal_force_N / *s.rigid_force_N;
    }
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace machdyn
