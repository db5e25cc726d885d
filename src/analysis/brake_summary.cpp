#include "machdyn/analysis/brake_summary.hpp"
#include "machdyn/model/sheaves.hpp"

#include <algorithm>
#include <cmath>

namespace machdyn {

namespace {

/// The output columns of one run by name, with values at the rows and, extended from the rows before
/// an instant, at any time inside the grid (analysis/brake_summary.hpp: the motion is smooth up to an
/// event, so a polynomial through the last rows before it, none before the previous event `after`).
struct Grid {
  const SimulationResult& r;
  const std::vector<double>& t;

  const std::vector<double>* column(const std::string& name) const {
    const auto it = std::find(r.column_names.begin(), r.column_names.end(), name);
    return it == r.column_names.end() ? nullptr : &r.columns[static_cast<size_t>(it - r.column_names.begin())];
  }
  /// The rows k with after < t_k < tau, the last `n` of them (first, count).
  std::pair<size_t, size_t> rows_before(double tau, double after, size_t n) const {
    const auto hi = static_cast<size_t>(std::lower_bound(t.begin(), t.end(), tau) - t.begin());
    const auto lo = static_cast<size_t>(std::upper_bound(t.begin(), t.end(), after) - t.begin());
    const size_t count = hi > lo ? std::min(n, hi - lo) : 0;
    return {hi - count, count};
  }
  /// A position at tau from its last row before and the speeds there (q + v h + ½ a h², a from the
  /// two rows before: exact for a uniform acceleration).
  double position_at(const std::vector<double>& q, const std::vector<double>& v, double tau, double after) const {
    const auto [k0, n] = rows_before(tau, after, 2);
    if (n == 0) return value_at(q, tau, -HUGE_VAL);
    const size_t k = k0 + n - 1;
    const double h = tau - t[k], a = n == 2 ? (v[k] - v[k0]) / (t[k] - t[k0]) : 0.0;
    return q[k] + v[k] * h + 0.5 * a * h * h;
  }
  /// A smooth column at tau: the polynomial through its last (up to three) rows before tau after
  /// `after` (exact for a quadratic in t); without such rows, linear between the rows around tau.
  double value_at(const std::vector<double>& y, double tau, double after) const {
    const auto [k0, n] = rows_before(tau, after, 3);
    if (n == 0) {
      const auto k = static_cast<size_t>(std::upper_bound(t.begin(), t.end(), tau) - t.begin());
      if (k == 0) return y.front();
      if (k >= t.size()) return y.back();
      return y[k - 1] + (y[k] - y[k - 1]) * (tau - t[k - 1]) / (t[k] - t[k - 1]);
    }
    double sum = 0.0;  // Lagrange through rows k0 … k0 + n − 1
    for (size_t i = k0; i < k0 + n; ++i) {
      double w = 1.0;
      for (size_t j = k0; j < k0 + n; ++j)
        if (j != i) w *= (tau - t[j]) / (t[i] - t[j]);
      sum += w * y[i];
    }
    return sum;
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

const char* start_name(BrakeStop::Start s) {
  switch (s) {
    case BrakeStop::Start::applied: return "applied";
    case BrakeStop::Start::overcome: return "overcome";
    case BrakeStop::Start::initial: return "initial";
  }
  return "";
}

const char* end_name(BrakeStop::End e) {
  switch (e) {
    case BrakeStop::End::stuck: return "stuck";
    case BrakeStop::End::released: return "released";
    case BrakeStop::End::run_end: return "t_end";
  }
  return "";
}

std::vector<BrakeSummary> brake_summaries(const Model& m, const SimulationResult& r) {
  std::vector<BrakeSummary> out;
  const auto t_it = std::find(r.column_names.begin(), r.column_names.end(), "t_s");
  if (t_it == r.column_names.end() || r.columns.empty()) return out;
  const Grid g{r, r.columns[static_cast<size_t>(t_it - r.column_names.begin())]};
  if (g.t.empty()) return out;
  const double t_end = g.t.back();
  const auto slipping = [](const std::string& md) { return md == "slip+" || md == "slip-"; };
  for (const FrictionContact& c : m.contacts) {
    if (!c.brake) continue;
    const Body& body = m.bodies[static_cast<size_t>(c.a)];
    BrakeSummary s;
    s.brake = c.name;
    s.unit = load_unit(body.kind);
    const auto* F = g.column(c.name + ".force_" + unit_suffix(load_unit(body.kind)));
    const auto* u = g.column(c.name + ".sliding_velocity_" + unit_suffix(velocity_unit(body.kind)));
    const auto* mode = g.column(c.name + ".mode");
    if (!F || !u || !mode) continue;
    std::vector<const ModeEvent*> events;  // the brake's own, in time order
    for (const ModeEvent& e : r.hybrid.events)
      if (e.element == c.name) events.push_back(&e);
    // The stops: from an event into slip± (from released or stuck, or the initial mode) to the next
    // event into stuck or released (or t_end).
    for (const ModeEvent* e : events) {
      const bool open = !s.stops.empty() && s.stops.back().end == BrakeStop::End::run_end;
      if (!open && slipping(e->to)) {
        BrakeStop st;
        st.t_applied = e->t, st.t_end = t_end;
        st.start = e->kind == "initial" ? BrakeStop::Start::initial
                   : e->from == "stuck" ? BrakeStop::Start::overcome
                                        : BrakeStop::Start::applied;
        s.stops.push_back(st);
      } else if (open && (e->to == "stuck" || e->to == "released")) {
        BrakeStop& st = s.stops.back();
        st.t_end = e->t;
        st.end = e->to == "stuck" ? BrakeStop::End::stuck : BrakeStop::End::released;
      }
    }
    // Never sliding, but applied in the run: it holds its body at rest, a stop of 0 s.
    if (s.stops.empty() && c.t_apply < t_end && !c.released(c.t_apply)) {
      BrakeStop st;
      st.t_applied = st.t_end = c.t_apply;
      st.end = BrakeStop::End::stuck;
      s.stops.push_back(st);
    }
    // The previous event of the brake before tau (the rows before it are another smooth piece).
    auto previous_event = [&](double tau) {
      double p = -HUGE_VAL;
      for (const ModeEvent* e : events)
        if (e->t < tau && e->kind != "initial") p = e->t;
      return p;
    };
    // The power P = |F u| on the rows, and on each side of each of the brake's events (the mode of
    // that side: 0 when it is stuck or released; else F of the nearest row on that side).
    std::vector<std::pair<double, double>> pts;  // (t, P), t non-decreasing
    {
      std::vector<double> cuts;
      for (const ModeEvent* e : events)
        if (e->kind != "initial" && e->t > g.t.front() && e->t < t_end) cuts.push_back(e->t);
      auto is_cut = [&](double tk) { return std::find(cuts.begin(), cuts.end(), tk) != cuts.end(); };
      size_t next = 0;
      for (size_t k = 0; k < g.t.size(); ++k) {
        for (; next < events.size(); ++next) {
          const ModeEvent& e = *events[next];
          if (e.kind == "initial" || !(e.t > g.t.front() && e.t < t_end)) continue;
          if (e.t > g.t[k]) break;
          const auto after = static_cast<size_t>(std::upper_bound(g.t.begin(), g.t.end(), e.t) - g.t.begin());
          const auto before = static_cast<size_t>(std::lower_bound(g.t.begin(), g.t.end(), e.t) - g.t.begin());
          const double speed = std::abs(g.value_at(*u, e.t, previous_event(e.t)));
          const double left = slipping(e.from) && before > 0 ? std::abs((*F)[before - 1]) * speed : 0.0;
          const double right = slipping(e.to) && after < g.t.size() ? std::abs((*F)[after]) * speed : 0.0;
          pts.emplace_back(e.t, left);
          pts.emplace_back(e.t, right);
        }
        if (!is_cut(g.t[k])) pts.emplace_back(g.t[k], std::abs((*F)[k] * (*u)[k]));
      }
    }
    // Energy and peak power over [a, b] (the run's and each stop's).
    auto integrate = [&](double a, double b, double& energy, double& peak, double& t_peak) {
      energy = 0.0, peak = 0.0, t_peak = std::isfinite(a) ? a : pts.empty() ? 0.0 : pts.front().first;
      for (size_t k = 0; k < pts.size(); ++k) {
        if (pts[k].first < a || pts[k].first > b) continue;
        if (pts[k].second > peak) peak = pts[k].second, t_peak = pts[k].first;
        if (k > 0 && pts[k - 1].first >= a) energy += 0.5 * (pts[k].second + pts[k - 1].second) * (pts[k].first - pts[k - 1].first);
      }
    };
    integrate(-HUGE_VAL, HUGE_VAL, s.energy_J, s.peak_power_W, s.t_peak_power);
    const auto* T = g.column(c.name + ".temperature_degC");
    const std::vector<int> group = joined(m, c.a);
    for (BrakeStop& st : s.stops) {
      if (st.end == BrakeStop::End::stuck) st.stopping_time = st.t_end - st.t_applied;
      // The travel of the braked body, then of every translational body joined to it (by links,
      // lossy gears or contacts: the load it stops), from t_a to t_e.
      auto add_travel = [&](const Body& b) {
        const auto* q = g.column(b.name + ".position_" + unit_suffix(position_unit(b.kind)));
        const auto* v = g.column(b.name + ".velocity_" + unit_suffix(velocity_unit(b.kind)));
        if (!q || !v) return;
        st.travel.push_back({b.name, position_unit(b.kind),
                             g.position_at(*q, *v, st.t_end, previous_event(st.t_end)) -
                                 g.position_at(*q, *v, st.t_applied, previous_event(st.t_applied))});
      };
      add_travel(body);
      for (size_t i = 0; i < m.bodies.size(); ++i)
        if (group[i] && m.bodies[i].kind == BodyKind::translational && static_cast<int>(i) != c.a &&
            !is_sheave_body(m, static_cast<int>(i)))  // a rope's end at its drum, not a body of the file
          add_travel(m.bodies[i]);
      double peak_any = 0.0;  // its peak below counts only the stop's own side of t_a and t_e
      integrate(st.t_applied, st.t_end, st.energy_J, peak_any, st.t_peak_power);
      st.peak_power_W = 0.0;
      for (size_t k = 0; k < pts.size(); ++k) {
        const bool inside = pts[k].first > st.t_applied && pts[k].first < st.t_end;
        const bool first_right = pts[k].first == st.t_applied && (k + 1 == pts.size() || pts[k + 1].first != st.t_applied);
        const bool last_left = pts[k].first == st.t_end && (k == 0 || pts[k - 1].first != st.t_end);
        if ((inside || first_right || last_left) && pts[k].second > st.peak_power_W)
          st.peak_power_W = pts[k].second, st.t_peak_power = pts[k].first;
      }
      if (T) {
        st.temperature_applied_degC = g.value_at(*T, st.t_applied, previous_event(st.t_applied));
        st.temperature_end_degC = st.t_end >= t_end ? T->back() : g.value_at(*T, st.t_end, previous_event(st.t_end));
      }
    }
    if (T) {
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
