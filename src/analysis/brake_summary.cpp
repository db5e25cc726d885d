#include "machdyn/analysis/brake_summary.hpp"

#include <algorithm>
#include <cmath>

namespace machdyn {

namespace {

/// The output columns of one run by name, with values at the rows and, extended from the rows before
/// an instant, at any time inside the grid (analysis/brake_summary.hpp: the motion is smooth up to an
/// event, so q + v τ + ½ a τ² from the last row before it, a from the two rows before).
struct Grid {
  const SimulationResult& r;
  const std::vector<double>& t;

  const std::vector<double>* column(const std::string& name) const {
    const auto it = std::find(r.column_names.begin(), r.column_names.end(), name);
    return it == r.column_names.end() ? nullptr : &r.columns[static_cast<size_t>(it - r.column_names.begin())];
  }
  /// The last row k with t_k ≤ tau (0 before the first).
  size_t row_before(double tau) const {
    const auto it = std::upper_bound(t.begin(), t.end(), tau);
    return it == t.begin() ? 0 : static_cast<size_t>(it - t.begin()) - 1;
  }
  /// A position at tau from its row before and the speeds there (exact for a uniform acceleration).
  double position_at(const std::vector<double>& q, const std::vector<double>& v, double tau) const {
    const size_t k = row_before(tau);
    const double h = tau - t[k], a = k > 0 ? (v[k] - v[k - 1]) / (t[k] - t[k - 1]) : 0.0;
    return q[k] + v[k] * h + 0.5 * a * h * h;
  }
  /// A speed at tau from its row before (exact for a uniform acceleration).
  double speed_at(const std::vector<double>& v, double tau) const {
    const size_t k = row_before(tau);
    const double a = k > 0 ? (v[k] - v[k - 1]) / (t[k] - t[k - 1]) : 0.0;
    return v[k] + a * (tau - t[k]);
  }
};

/// Which bodies are joined to `body` by links (both ends and a rope's frame), lossy gears and
/// friction contacts between two bodies: 1 for each of them (the body itself included).
std::vector<int> joined(const Model& m, int body) {
  std::vector<int> parent(m.bodies.size());
  for (size_t i = 0; i < parent.size(); ++i) parent[i] = static_cast<int>(i);
  auto find = [&](int x) {
    while (parent[static_cast<size_t>(x)] != x) x = parent[static_cast<size_t>(x)] = parent[static_cast<size_t>(parent[static_cast<size_t>(x)])];
    return x;
  };
  auto join = [&](int a, int b) {
    if (a >= 0 && b >= 0) parent[static_cast<size_t>(find(a))] = find(b);
  };
  for (const Link& l : m.links) join(l.a, l.b), join(l.a, l.third), join(l.b, l.third);
  for (const LossyGear& g : m.lossy_gears) join(g.a, g.b);
  for (const FrictionContact& c : m.contacts) join(c.a, c.b);
  std::vector<int> out(m.bodies.size(), 0);
  for (size_t i = 0; i < out.size(); ++i) out[i] = find(static_cast<int>(i)) == find(body);
  return out;
}

}  // namespace

std::vector<BrakeStop> brake_stops(const Model& m, const SimulationResult& r) {
  std::vector<BrakeStop> out;
  const auto t_it = std::find(r.column_names.begin(), r.column_names.end(), "t_s");
  if (t_it == r.column_names.end() || r.columns.empty()) return out;
  const Grid g{r, r.columns[static_cast<size_t>(t_it - r.column_names.begin())]};
  if (g.t.empty()) return out;
  const double t_end = g.t.back();
  for (const FrictionContact& c : m.contacts) {
    if (!c.brake) continue;
    const Body& body = m.bodies[static_cast<size_t>(c.a)];
    BrakeStop s;
    s.brake = c.name;
    s.unit = load_unit(body.kind);
    const auto* F = g.column(c.name + ".force_" + unit_suffix(load_unit(body.kind)));
    const auto* u = g.column(c.name + ".sliding_velocity_" + unit_suffix(velocity_unit(body.kind)));
    const auto* mode = g.column(c.name + ".mode");
    if (!F || !u || !mode) continue;
    // The stop: the first application that meets its body moving (the brake's event out of
    // `released` into slip±, or its initial mode slip± when applied from t = 0) to its next event into
    // `stuck`. Without one, an application that met its body at rest (it holds it) is a stop of 0 s.
    const auto slipping = [](const std::string& md) { return md == "slip+" || md == "slip-"; };
    for (size_t k = 0; k < r.hybrid.events.size() && !s.t_applied; ++k) {
      const ModeEvent& e = r.hybrid.events[k];
      if (e.element != c.name || !slipping(e.to) || !(e.from == "released" || e.kind == "initial")) continue;
      s.t_applied = e.t;
      for (size_t j = k + 1; j < r.hybrid.events.size(); ++j)
        if (r.hybrid.events[j].element == c.name && r.hybrid.events[j].to == "stuck") {
          s.t_stopped = r.hybrid.events[j].t;
          break;
        }
    }
    if (!s.t_applied && c.t_apply < t_end) s.t_applied = s.t_stopped = c.t_apply;
    if (s.t_applied) {
      if (s.t_stopped) s.stopping_time = *s.t_stopped - *s.t_applied;
      // The travel of the braked body, then of every translational body joined to it (by links,
      // lossy gears or contacts: the load it stops), from t_a to t_s.
      const double t_to = s.t_stopped.value_or(t_end);
      auto add_travel = [&](const Body& b) {
        const auto* q = g.column(b.name + ".position_" + unit_suffix(position_unit(b.kind)));
        const auto* v = g.column(b.name + ".velocity_" + unit_suffix(velocity_unit(b.kind)));
        if (!q || !v) return;
        s.travel.push_back({b.name, position_unit(b.kind),
                            g.position_at(*q, *v, t_to) - g.position_at(*q, *v, *s.t_applied)});
      };
      add_travel(body);
      const std::vector<int> group = joined(m, c.a);
      for (size_t i = 0; i < m.bodies.size(); ++i)
        if (group[i] && m.bodies[i].kind == BodyKind::translational && static_cast<int>(i) != c.a) add_travel(m.bodies[i]);
    }
    // Energy and peak power of P = |F u| on the rows, cut at t_a (where P jumps from the released
    // brake's 0 to |F(t_a⁺)| |u(t_a)|) and at t_s (P = 0).
    std::vector<std::pair<double, double>> pts;  // (t, P), t increasing
    const double ta = s.t_applied.value_or(HUGE_VAL), ts = s.t_stopped.value_or(HUGE_VAL);
    for (size_t k = 0; k < g.t.size(); ++k) {
      const double tk = g.t[k], tn = k + 1 < g.t.size() ? g.t[k + 1] : HUGE_VAL;
      pts.emplace_back(tk, std::abs((*F)[k] * (*u)[k]));
      if (ta >= tk && ta < tn && tn < HUGE_VAL) {
        if (ta == tk) pts.back().second = 0.0;  // the row at t_a shows the released brake's 0 or the jump
        pts.emplace_back(ta, 0.0);
        pts.emplace_back(ta, std::abs((*F)[k + 1]) * std::abs(g.speed_at(*u, ta)));
      }
      if (ts > tk && ts < tn && ts != ta) pts.emplace_back(ts, 0.0);
    }
    for (size_t k = 0; k < pts.size(); ++k) {
      if (pts[k].second > s.peak_power_W) s.peak_power_W = pts[k].second, s.t_peak_power = pts[k].first;
      if (k > 0) s.energy_J += 0.5 * (pts[k].second + pts[k - 1].second) * (pts[k].first - pts[k - 1].first);
    }
    if (const auto* T = g.column(c.name + ".temperature_degC")) {
      s.thermal = true;
      const auto it = std::max_element(T->begin(), T->end());
      s.temperature_max_degC = *it;
      s.t_temperature_max = g.t[static_cast<size_t>(it - T->begin())];
      s.temperature_end_degC = T->back();
    }
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace machdyn
