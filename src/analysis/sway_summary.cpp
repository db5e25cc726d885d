#include "machdyn/analysis/sway_summary.hpp"

#include <algorithm>
#include <cmath>

#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/elements/spatial_rope.hpp"

namespace machdyn {

std::vector<std::string> sway_rope_names(const Model& m) {
  std::vector<std::string> out;
  for (const Drive& d : m.drives)
    if (dynamic_cast<const SpatialRope*>(d.law.get())) out.push_back(d.name);
  return out;
}

SwayObserver::SwayObserver(const Model& m) {
  const int n = m.dof();
  size_t outputs = 0;
  for (size_t k = 0; k < m.drives.size(); ++k) {
    const Drive& d = m.drives[k];
    const auto* law = dynamic_cast<const SpatialRope*>(d.law.get());
    if (!law) continue;
    Rope r;
    r.drive = static_cast<int>(k);
    r.law = law;
    r.s.rope = d.name;
    if (law->sway_after >= 0.0) r.s.residual_after = law->sway_after;
    const std::vector<std::string> names = law->output_names(m.bodies[static_cast<size_t>(d.body)].kind);
    outputs = std::max(outputs, names.size());
    for (size_t j = 0; j < names.size(); ++j) {
      if (names[j] == "sway_x_rad" || names[j] == "sway_y_rad" || names[j] == "sway_radial_rad" ||
          names[j] == "sway_tangential_rad")
        r.sway.push_back(static_cast<int>(j));
      if (names[j] == "horizontal_force_N") r.horizontal = static_cast<int>(j);
    }
    // The suspension point's travel: the velocities of its trolley and bridge bodies (with a jib the
    // point also turns, and its acceleration is not theirs: no dynamic factor).
    if (!law->has(SpatialRope::Role::jib))
      for (const SpatialRope::Role role : {SpatialRope::Role::trolley, SpatialRope::Role::bridge}) {
        const int p = law->port_of[static_cast<int>(role)];
        if (p < 0) continue;
        const int b = p == 0 ? d.body : d.others[static_cast<size_t>(p - 1)];
        r.travel.push_back(n + b);
      }
    r.v_prev.assign(r.travel.size(), 0.0);
    ropes_.push_back(std::move(r));
  }
  out_.assign(outputs, 0.0);
}

void SwayObserver::row(const DriveSystem& sys, double t, const double* y) {
  for (Rope& r : ropes_) {
    sys.drive_outputs(r.drive, t, y, out_.data());  // the row's own columns of the rope
    SwaySummary& s = r.s;
    s.max_tension_N = std::max(s.max_tension_N, out_[0]);  // output 0: the tension
    for (const int j : r.sway) {
      const double a = std::abs(out_[static_cast<size_t>(j)]);
      if (a > s.max_sway_rad) s.max_sway_rad = a, s.t_max_sway = t;
      if (s.residual_after && t >= *s.residual_after) s.residual_sway_rad = std::max(s.residual_sway_rad, a);
    }
    const double H = out_[static_cast<size_t>(r.horizontal)];
    if (H > s.max_horizontal_force_N) s.max_horizontal_force_N = H, s.t_max_horizontal_force = t;
    if (r.travel.empty()) continue;
    // |a| of the suspension point between the previous row and this one: |Δv|/Δt over its travel.
    if (r.started && t - r.t_prev > 0.0) {
      const double dt = t - r.t_prev;
      double a2 = 0.0;
      for (size_t k = 0; k < r.travel.size(); ++k)
        a2 += std::pow((y[r.travel[k]] - r.v_prev[k]) / dt, 2);
      r.a_max = std::max(r.a_max, std::sqrt(a2));
    }
    for (size_t k = 0; k < r.travel.size(); ++k) r.v_prev[k] = y[r.travel[k]];
    r.t_prev = t, r.started = true;
  }
}

std::vector<SwaySummary> SwayObserver::summaries() const {
  std::vector<SwaySummary> out;
  out.reserve(ropes_.size());
  for (const Rope& r : ropes_) {
    SwaySummary s = r.s;
    if (r.a_max > 0.0) s.rigid_force_N = r.law->mass * r.a_max, s.dynamic_factor = s.max_horizontal_force_N / *s.rigid_force_N;
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace machdyn
