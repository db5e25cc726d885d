#include "machdyn/model/model.hpp"

#include <algorithm>

namespace machdyn {

double Load::evaluate(double t, double v) const {
  switch (kind) {
    case LoadKind::constant:
      return value;
    case LoadKind::step:
      return t < t0 ? before : value;
    case LoadKind::ramp:
      if (t <= t0) return before;
      if (t >= t1) return value;
      return before + (value - before) * (t - t0) / (t1 - t0);
    case LoadKind::table: {
      if (t <= times.front()) return values.front();
      if (t >= times.back()) return values.back();
      auto it = std::upper_bound(times.begin(), times.end(), t);
      size_t k = static_cast<size_t>(it - times.begin());
      double w = (t - times[k - 1]) / (times[k] - times[k - 1]);
      return values[k - 1] + w * (values[k] - values[k - 1]);
    }
    case LoadKind::motor_linear:
      return value * (1.0 - v / omega0);
    case LoadKind::motor_kloss: {
      double s = (omega0 - v) / omega0;
      return 2.0 * value * s * s_k / (s * s + s_k * s_k);
    }
  }
  return 0.0;
}

double Load::slope(double /*t*/, double v) const {
  switch (kind) {
    case LoadKind::motor_linear:
      return -value / omega0;
    case LoadKind::motor_kloss: {
      // dM/ds = 2 M_k s_k (s_k² − s²)/(s² + s_k²)², ds/dv = −1/ω0
      double s = (omega0 - v) / omega0, den = s * s + s_k * s_k;
      return -2.0 * value * s_k * (s_k * s_k - s * s) / (den * den) / omega0;
    }
    default:
      return 0.0;
  }
}

Location Model::where(const std::string& element) const {
  auto it = element_where.find(element);
  return it == element_where.end() ? Location{source, 0, 0} : it->second;
}

void Model::index_bodies() {
  body_lookup.clear();
  body_lookup.reserve(bodies.size());
  for (size_t i = 0; i < bodies.size(); ++i) body_lookup.try_emplace(bodies[i].name, static_cast<int>(i));
}

int Model::body_index(const std::string& n) const {
  if (n == "ground") return kGround;
  if (body_lookup.size() == bodies.size() && !bodies.empty()) {  // the index is current
    auto it = body_lookup.find(n);
    return it == body_lookup.end() ? -2 : it->second;
  }
  for (size_t i = 0; i < bodies.size(); ++i)
    if (bodies[i].name == n) return static_cast<int>(i);
  return -2;
}

const char* position_unit(BodyKind k) { return k == BodyKind::rotational ? "rad" : "m"; }
const char* velocity_unit(BodyKind k) { return k == BodyKind::rotational ? "rad/s" : "m/s"; }
const char* load_unit(BodyKind k) { return k == BodyKind::rotational ? "N*m" : "N"; }

std::string unit_suffix(const char* unit) {
  std::string s(unit);
  for (auto& ch : s)
    if (ch == '*' || ch == '/') ch = '_';
  return s;
}

std::vector<std::string> chain_column_names(const Model& m) {
  std::vector<std::string> names{"t_s"};
  for (const auto& b : m.bodies) {
    names.push_back(b.name + ".position_" + unit_suffix(position_unit(b.kind)));
    names.push_back(b.name + ".velocity_" + unit_suffix(velocity_unit(b.kind)));
  }
  for (const auto& l : m.links) names.push_back(l.name + ".load_" + unit_suffix(link_load_unit(m, l)));
  return names;
}

std::size_t output_columns_bound(const Model& m) {
  std::size_t n = 1 + 2 * m.bodies.size() + m.links.size() + 3 * m.contacts.size();
  for (const auto& l : m.links) n += l.has_gap ? 1 : 0;
  for (const auto& b : m.bodies) n += b.machine ? 8 : 0;
  return n;
}

double output_bytes_bound(const Model& m) {
  const double rows = m.simulation.dt_out > 0.0 ? m.simulation.t_end / m.simulation.dt_out + 2.0 : 1002.0;
  return rows * static_cast<double>(output_columns_bound(m)) * static_cast<double>(sizeof(double));
}

const char* link_load_unit(const Model& m, const Link& l) {
  int side = l.b != kGround ? l.b : l.a;
  if (l.b != kGround ? l.b_point : l.a_point) return "N";  // a machine's output point (piston) moves in m
  return load_unit(m.bodies[static_cast<size_t>(side)].kind);
}

}  // namespace machdyn

namespace machdyn {

namespace {
/// Piecewise-linear interpolation through (x, y), held constant outside.
double table_value(const std::vector<double>& x, const std::vector<double>& y, double at) {
  if (y.empty()) return 0.0;
  if (x.size() < 2 || at <= x.front()) return y.front();
  if (at >= x.back()) return y.back();
  auto it = std::upper_bound(x.begin(), x.end(), at);
  size_t k = static_cast<size_t>(it - x.begin());
  return y[k - 1] + (y[k] - y[k - 1]) * (at - x[k - 1]) / (x[k] - x[k - 1]);
}
}  // namespace

double FrictionContact::scale(double t) const {
  if (!brake) return 1.0;
  if (t < t_apply) return 0.0;
  if (t_ramp <= 0.0 || t >= t_apply + t_ramp) return 1.0;
  return (t - t_apply) / t_ramp;
}

double FrictionContact::kinetic_level(double speed) const { return table_value(speeds, kinetic, speed); }

double FrictionContact::surface_velocity(double t) const {
  return table_value(surface_times, surface_velocities, t);
}

double FrictionContact::surface_acceleration(double t) const {
  const auto& x = surface_times;
  const auto& y = surface_velocities;
  if (x.size() < 2 || t < x.front() || t >= x.back()) return 0.0;
  auto it = std::upper_bound(x.begin(), x.end(), t);
  size_t k = static_cast<size_t>(it - x.begin());
  return (y[k] - y[k - 1]) / (x[k] - x[k - 1]);
}

bool Model::is_hybrid() const {
  if (!contacts.empty()) return true;
  for (const auto& l : links)
    if (l.has_gap) return true;
  return false;
}

}  // namespace machdyn
