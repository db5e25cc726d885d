#include "machdyn/model/signal_sampling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "machdyn/model/element.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

double sampling_step(const Signal& s, double t0, double t1) {
  constexpr double inf = std::numeric_limits<double>::infinity();
  switch (s.kind()) {
    case Signal::Kind::constant:
    case Signal::Kind::step:
    case Signal::Kind::ramp:
    case Signal::Kind::table:
    case Signal::Kind::pulse: return inf;
    case Signal::Kind::expression: return (t1 - t0) / 4096.0;
    case Signal::Kind::sum: {
      double h = inf;
      for (const Signal& term : s.terms()) h = std::min(h, sampling_step(term, t0, t1));
      return h;
    }
    case Signal::Kind::sine: {
      // From its start t_s on, s = d + A sin(ω (t − t_s) + φ) has s'' = −ω² (s − d), so two times
      // after the start give ω² = −(s''(t_a) − s''(t_b)) / (s(t_a) − s(t_b)) without knowing d.
      // The times: three inside (max(t0, t_s), t1) at irrational fractions, the pair whose values
      // differ most (never two a whole period apart). Not started before t1, or A = 0: constant.
      const std::vector<double> start = s.breakpoints(t0, t1);  // t_s, if inside
      const double from = start.empty() ? t0 : start.back();
      const double len = t1 - from;
      const double t[3] = {from + 0.2113248654 * len, from + 0.5 * len, from + 0.7886751346 * len};
      double best = 0.0, w2 = 0.0;
      for (int i = 0; i < 3; ++i)
        for (int j = i + 1; j < 3; ++j) {
          const double dv = s.value(t[i]) - s.value(t[j]);
          if (std::abs(dv) > best) best = std::abs(dv), w2 = -(s.curvature(t[i]) - s.curvature(t[j])) / dv;
        }
      if (!(w2 > 0.0)) return inf;
      return 2.0 * std::numbers::pi / std::sqrt(w2) / 8.0;
    }
  }
  return inf;
}

double sampling_step(const Model& m, double t_end) {
  const double unknown = t_end / 4096.0;  // a law of t the model cannot see into: as an expression
  double h = std::numeric_limits<double>::infinity();
  for (const Load& ld : m.loads) {
    if (ld.kind == LoadKind::signal) h = std::min(h, sampling_step(ld.signal, 0.0, t_end));
    if (ld.kind == LoadKind::expression) h = std::min(h, unknown);
    if (ld.switched) h = std::min({h, sampling_step(ld.on, 0.0, t_end), sampling_step(ld.direction, 0.0, t_end)});
  }
  for (const Drive& d : m.drives)
    if (d.law->has_events()) h = std::min(h, unknown);
  for (const FrictionContact& c : m.contacts)
    if (c.applied) h = std::min(h, sampling_step(c.application, 0.0, t_end));
  for (const Body& b : m.bodies)
    if (b.motion != MotionKind::free) h = std::min(h, sampling_step(b.motion_signal, 0.0, t_end));
  return h;
}

}  // namespace machdyn
