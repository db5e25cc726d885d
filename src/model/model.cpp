#include "machdyn/model/model.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

#include "machdyn/common/expression.hpp"
#include "machdyn/model/element.hpp"
#include "machdyn/model/sheaves.hpp"

namespace machdyn {

namespace {
/// The motor characteristic f(v) for the forward direction, and df/dv if kD.
template <bool kD>
double motor_torque(const Load& l, double v, double* dfdv) {
  switch (l.kind) {
    case LoadKind::motor_linear:
      if constexpr (kD) *dfdv = -l.value / l.omega0;
      return l.value * (1.0 - v / l.omega0);
    case LoadKind::motor_kloss: {
      // M = 2 M_k s s_k/(s² + s_k²); dM/ds = 2 M_k s_k (s_k² − s²)/(s² + s_k²)², ds/dv = −1/ω0
      const double s = (l.omega0 - v) / l.omega0, den = s * s + l.s_k * l.s_k;
      if constexpr (kD) *dfdv = -2.0 * l.value * l.s_k * (l.s_k * l.s_k - s * s) / (den * den) / l.omega0;
      return 2.0 * l.value * s * l.s_k / den;
    }
    default:  // motor_table
      if constexpr (kD) *dfdv = l.signal.slope(v);
      return l.signal.value(v);
  }
}

/// The load law, written once: M(t, q, v) and, if kD, ∂M/∂q and ∂M/∂v (the value alone on the hot
/// path of the right-hand side, the derivatives for the Jacobian).
template <bool kD>
double load_law(const Load& l, double t, double q, double v, double* dMdq, double* dMdv) {
  if constexpr (kD) *dMdq = *dMdv = 0.0;
  switch (l.kind) {
    case LoadKind::constant: return l.value;
    case LoadKind::signal: return l.signal.value(t);
    case LoadKind::expression: {
      const double x[3] = {t, q, v};
      if constexpr (!kD) return l.law->eval_at(x, -1).v;
      *dMdq = l.law->eval_at(x, 1).d;
      const Jet j = l.law->eval_at(x, 2);
      *dMdv = j.d;
      return j.v;
    }
    case LoadKind::speed_table:
    case LoadKind::position_table:
    case LoadKind::drag:
    case LoadKind::eddy_current: {
      // M = s(t) f(q, v): the `scale` s (1 unless switched) times the law of the state.
      const double s = l.switched ? l.on.value(t) : 1.0;
      double f = 0.0;
      if (l.kind == LoadKind::speed_table) {
        if constexpr (kD) *dMdv = l.signal.slope(v);
        f = l.signal.value(v);
      } else if (l.kind == LoadKind::position_table) {
        if constexpr (kD) *dMdq = l.signal.slope(q);
        f = l.signal.value(q);
      } else if (l.kind == LoadKind::drag) {  // f = −k v|v|, df/dv = −2k|v|
        if constexpr (kD) *dMdv = -2.0 * l.value * std::abs(v);
        f = -l.value * v * std::abs(v);
      } else {
        f = eddy_current_law(v, l.value, l.omega0, kD ? dMdv : nullptr);
      }
      if constexpr (kD) *dMdq *= s, *dMdv *= s;
      return s * f;
    }
    case LoadKind::motor_linear:
    case LoadKind::motor_kloss:
    case LoadKind::motor_table: {
      if (!l.switched) return motor_torque<kD>(l, v, dMdv);
      // M = on d f(d v): dM/dv = on d² f'(d v) = on f'(d v)
      const double on = l.on.value(t), d = l.direction.value(t);
      double df = 0.0;
      const double f = motor_torque<kD>(l, d * v, &df);
      if constexpr (kD) *dMdv = on * d * d * df;
      return on * d * f;
    }
  }
  return 0.0;
}
}  // namespace

double Load::own(const double* x) const { return ratio * x[body] + (body2 >= 0 ? ratio2 * x[body2] : 0.0); }

double Load::at(double t, const double* q, const double* v) const {
  return load_law<false>(*this, t, own(q), own(v), nullptr, nullptr);
}

void Load::slopes_at(double t, const double* q, const double* v, double* dMdq, double* dMdv) const {
  (void)load_law<true>(*this, t, own(q), own(v), dMdq, dMdv);
}

void Load::spread(double M, double* f) const {
  f[body] += ratio * M;
  if (body2 >= 0) f[body2] += ratio2 * M;
}

int Load::terms(int* b, double* w) const {
  b[0] = body, w[0] = ratio, b[1] = body2, w[1] = ratio2;
  return body2 >= 0 ? 2 : 1;
}

std::vector<double> Load::breakpoints(double t0, double t1) const {
  std::vector<double> b;
  if (kind == LoadKind::signal) b = signal.breakpoints(t0, t1);
  if (switched) {
    for (const Signal* s : {&on, &direction}) {
      auto x = s->breakpoints(t0, t1);
      b.insert(b.end(), x.begin(), x.end());
    }
  }
  // An expression's switches in t alone (step, comparisons, min, max: common/expression.hpp).
  if (kind == LoadKind::expression && law) {
    auto x = law->switch_points(0, t0, t1);
    b.insert(b.end(), x.begin(), x.end());
  }
  return b;
}

int Drive::states() const { return law->states(); }

double Drive::own(const double* x) const { return ratio * x[body] + (body2 >= 0 ? ratio2 * x[body2] : 0.0); }

void Drive::spread(double M, double* f) const {
  f[body] += ratio * M;
  if (body2 >= 0) f[body2] += ratio2 * M;
}

int Drive::terms(int* b, double* w) const {
  b[0] = body, w[0] = ratio, b[1] = body2, w[1] = ratio2;
  return body2 >= 0 ? 2 : 1;
}

std::string shown_body(const Model& m, int body, const std::string& given) {
  if (!given.empty()) return given;
  return body == kGround ? std::string("ground") : m.bodies[static_cast<size_t>(body)].name;
}

namespace {
/// The one-master slave called `name` (RigidSlave), or null.
const RigidSlave* slave_named(const Model& m, const std::string& name) {
  for (const RigidSlave& s : m.slaves)
    if (s.name == name && s.master2 < 0) return &s;
  return nullptr;
}
}  // namespace

double shown_ratio(const Model& m, const Link& l) {
  // A rope with sheave losses: the drum's ratio is its sheave gear's (model/sheaves.hpp), in the file's bodies.
  if (const int g = sheave_gear(m, l); g >= 0) {
    const LossyGear& x = m.lossy_gears[static_cast<size_t>(g)];
    return x.ratio * x.rho_a / x.rho_b;
  }
  const RigidSlave* s = l.b_weight == 1.0 && l.third == kGround ? slave_named(m, l.given_a) : nullptr;
  return s && s->master == l.a ? l.ratio * s->ratio : l.ratio;
}

double shown_value(const Model& m, const Load& ld) {
  if (ld.kind != LoadKind::constant) return ld.value;
  const RigidSlave* s = ld.body2 < 0 ? slave_named(m, ld.given_body) : nullptr;
  return s && s->master == ld.body ? ld.value / s->ratio : ld.value;
}

std::vector<double> Drive::breakpoints(double t0, double t1) const { return law->breakpoints(t0, t1); }

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
  std::size_t n = 1 + 2 * m.bodies.size() + m.links.size() + 3 * m.contacts.size() + m.drives.size() +
                  2 * m.slaves.size() + 4 * m.lossy_gears.size() + m.merged_gears.size();
  for (const auto& l : m.links) n += (l.has_gap ? 1 : 0) + (is_rope_with_falls(l) ? 2 : 0);
  for (const auto& b : m.bodies) n += b.machine ? 8 : 0;
  for (const auto& c : m.contacts) n += c.thermal ? 1 : 0;  // its temperature
  for (const auto& e : m.eliminated_joints) n += e.members.size();  // its torque on each member
  for (const auto& b : m.bodies) n += b.motion != MotionKind::free ? 1 : 0;  // the motion source's force
  for (const auto& d : m.drives)  // its torque and its own columns
    n += d.law->output_names(m.bodies[static_cast<size_t>(d.body)].kind).size();
  return n + released_bodies(m).size();
}

std::vector<int> released_bodies(const Model& m) {
  std::vector<int> b;
  for (const auto& r : m.releases)
    if (std::find(b.begin(), b.end(), r.body) == b.end()) b.push_back(r.body);
  std::sort(b.begin(), b.end());
  return b;
}

Release body_release(const Model& m, std::string name, int body, double amount, double time) {
  Release r;
  r.name = std::move(name);
  r.body = body;
  r.amount = amount;
  r.time = time;
  const Body& b = m.bodies[static_cast<size_t>(body)];
  const std::string weight = b.name + ".weight";  // compile's gravity load: −vertical · m · g
  for (size_t k = 0; k < m.loads.size(); ++k)
    if (m.loads[k].name == weight && m.loads[k].kind == LoadKind::constant) {
      r.weight_load = static_cast<int>(k);
      r.weight_change = b.vertical * amount * m.gravity;  // −vertical · (m − Δm) · g − (−vertical · m · g)
    }
  return r;
}

Model model_after_releases(const Model& m, std::size_t count) {
  Model out = m;
  count = std::min(count, m.releases.size());
  for (size_t k = 0; k < count; ++k) {
    const Release& r = m.releases[k];
    out.bodies[static_cast<size_t>(r.body)].inertia -= r.amount;
    if (r.weight_load >= 0) {  // a constant load: its value and its signal
      Load& w = out.loads[static_cast<size_t>(r.weight_load)];
      w.value += r.weight_change;
      w.signal = Signal::constant(w.value);
    }
  }
  out.releases.erase(out.releases.begin(), out.releases.begin() + static_cast<long>(count));
  return out;
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
  return applied ? std::max(0.0, application_gain * application.value(t)) : 1.0;
}

bool FrictionContact::released(double t) const {
  if (!applied) return false;
  // At a zero crossing (a breakpoint) s is 0 up to rounding: within 1e-12 of 0 (r ≤ 1 near full
  // application) the side is the slope's.
  constexpr double eps = 1e-12;
  const double s = application_gain * application.value(t);
  return s < -eps || (s <= eps && !(application_gain * application.slope(t) > 0.0));
}

double FrictionContact::kinetic_level(double speed) const {
  if (stribeck_speed > 0.0) {
    // From F_s0 / peak at rest (the static limit itself without a peak: peak = 1 divides exactly).
    const double Fc = kinetic.empty() ? 0.0 : kinetic.front();
    return Fc + (static_limit / peak - Fc) * std::exp(-std::pow(std::abs(speed) / stribeck_speed, stribeck_exponent));
  }
  return table_value(speeds, kinetic, speed);
}

double FrictionContact::kinetic_level_slope(double speed) const {
  const double s = std::abs(speed);
  if (stribeck_speed > 0.0) {
    // d/ds [F_c + (F_s0 − F_c) e^{−x^δ}], x = s/w_s: −(F_s0 − F_c) δ x^{δ−1} e^{−x^δ} / w_s (δ ≥ 1: finite at 0).
    const double Fc = kinetic.empty() ? 0.0 : kinetic.front(), x = s / stribeck_speed, d = stribeck_exponent;
    return -(static_limit / peak - Fc) * d * std::pow(x, d - 1.0) * std::exp(-std::pow(x, d)) / stribeck_speed;
  }
  const auto& x = speeds;
  const auto& y = kinetic;
  if (x.size() < 2 || s < x.front() || s >= x.back()) return 0.0;  // held constant outside
  const auto k = static_cast<size_t>(std::upper_bound(x.begin(), x.end(), s) - x.begin());
  return (y[k] - y[k - 1]) / (x[k] - x[k - 1]);
}

std::vector<double> FrictionContact::application_times(double t_end) const {
  if (!applied) return {};
  std::vector<double> t = application.breakpoints(0.0, t_end);
  const auto z = application.crossings(0.0, 0.0, t_end);  // max(0, s): a kink where s crosses 0
  t.insert(t.end(), z.begin(), z.end());
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  return t;
}

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

std::vector<double> Model::breakpoints(double t_end) const {
  std::vector<double> t;
  for (const auto& ld : loads) {
    auto b = ld.breakpoints(0.0, t_end);
    t.insert(t.end(), b.begin(), b.end());
  }
  for (const auto& d : drives) {
    auto b = d.breakpoints(0.0, t_end);
    t.insert(t.end(), b.begin(), b.end());
  }
  for (const auto& c : contacts) {
    auto r = c.application_times(t_end);
    t.insert(t.end(), r.begin(), r.end());
    t.insert(t.end(), c.surface_times.begin(), c.surface_times.end());
  }
  for (const auto& r : releases) t.push_back(r.time);  // the mass matrix changes there
  for (const auto& b : bodies)
    if (b.motion != MotionKind::free) {
      auto s = b.motion_signal.breakpoints(0.0, t_end);
      t.insert(t.end(), s.begin(), s.end());
    }
  std::sort(t.begin(), t.end());
  t.erase(std::unique(t.begin(), t.end()), t.end());
  std::erase_if(t, [&](double x) { return !(x > 0.0 && x < t_end); });
  // Breakpoints closer than s = 1e-12 t_end are one, the last of them: a step of a few ulps is none
  // an integrator can take (CVODE refuses it: `t > 20` beside a table's jump at 20 gives 20 and the
  // double after), and the switches inside act over at most s. One closer than s to 0 moves to s
  // (the first step must not start on the old value and carry the switch), one closer to t_end goes.
  const double s = 1e-12 * t_end;
  std::vector<double> kept;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (k + 1 == t.size() || t[k + 1] - t[k] >= s) kept.push_back(std::max(t[k], s));
  std::erase_if(kept, [&](double x) { return !(x < t_end - s); });
  kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
  return kept;
}

bool Model::is_hybrid() const {
  if (!contacts.empty() || !lossy_gears.empty()) return true;
  for (const auto& l : links)
    if (l.has_gap) return true;
  return false;
}

}  // namespace machdyn
