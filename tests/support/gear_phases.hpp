#pragma once
/// @file
/// The phase walk of the tests' reference solutions for a lossy gear driven from its input (MSL's
/// LossyGearDemo1 and LossyGearDemo2, whose tests state each phase's closed form). At rest, the
/// first instant either start test turns positive starts a phase in that direction; a rolling phase
/// ends where its speed returns to 0 (then stuck, or an immediate start: one switch) or where its
/// quadrant changes. Instants by scanning and bisection (test::first_positive).

#include <algorithm>
#include <functional>
#include <vector>

#include "support/support.hpp"

namespace machdyn::test {

/// One phase: from t0 at speed w0, direction s (0 stuck), quadrant factor k (η_mf1 or 1/η_mf2).
struct GearPhase {
  double t0 = 0.0, w0 = 0.0;
  int s = 0;
  double k = 1.0;
};

struct GearPhases {
  using StartTest = std::function<double(double)>;                // > 0: at rest, it starts at t
  using Quadrant = std::function<double(int, double, double)>;    // k in direction s at (t, w)
  using Speed = std::function<double(const GearPhase&, double)>;  // the phase's speed at t

  std::vector<GearPhase> segs;
  std::vector<double> switches;  // every change of direction or quadrant
  Speed w;

  GearPhases(double t_end, const StartTest& start_fwd, const StartTest& start_bwd, const Quadrant& quadrant,
             Speed speed)
      : w(std::move(speed)) {
    GearPhase g;
    double t = 0.0;
    while (t < t_end) {
      if (g.s == 0) {
        const double tf = start_fwd(t) > 0 ? t : first_positive(start_fwd, t, t_end);
        const double tb = start_bwd(t) > 0 ? t : first_positive(start_bwd, t, t_end);
        t = std::min(tf, tb);
        if (t >= t_end) break;
        if (t > 0) switches.push_back(t);
        g = {t, 0.0, tf <= tb ? 1 : -1, 0.0};
        g.k = quadrant(g.s, t, 0.0);
        segs.push_back(g);
        continue;
      }
      const GearPhase cur = g;
      const auto stops = [&](double x) { return -cur.s * w(cur, x); };
      const auto flips = [&](double x) { return quadrant(cur.s, x, w(cur, x)) != cur.k ? 1.0 : -1.0; };
      const double t_stop = first_positive(stops, t, t_end), t_flip = first_positive(flips, t, t_end);
      t = std::min(t_stop, t_flip);
      if (t >= t_end) break;
      switches.push_back(t);
      if (t_flip < t_stop) {
        g = {t, w(cur, t), cur.s, quadrant(cur.s, t, w(cur, t))};
      } else {  // at rest: stuck, or an immediate start in either direction (one switch)
        g = {t, 0.0, start_fwd(t) > 0 ? 1 : start_bwd(t) > 0 ? -1 : 0, 1.0};
        if (g.s != 0) g.k = quadrant(g.s, t, 0.0);
      }
      segs.push_back(g);
    }
    if (segs.empty() || segs.front().t0 > 0) segs.insert(segs.begin(), GearPhase{});
  }
  /// The phase at time t.
  [[nodiscard]] const GearPhase& at(double t) const {
    const GearPhase* g = &segs.front();
    for (const auto& s : segs)
      if (s.t0 <= t) g = &s;
    return *g;
  }
  /// The reference speed at time t.
  [[nodiscard]] double speed(double t) const {
    const GearPhase& g = at(t);
    return g.s == 0 ? 0.0 : w(g, t);
  }
};

}  // namespace machdyn::test
