#include "machdyn/solve/driver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/solve/roots.hpp"

namespace machdyn {
namespace {

StepperStats minus(StepperStats a, const StepperStats& b) {
  a.steps -= b.steps, a.rejected -= b.rejected, a.rhs_evals -= b.rhs_evals, a.jac_evals -= b.jac_evals;
  return a;
}

/// Rounds of re-decision at one instant before the driver gives up: each round hands back the
/// functions the last decision left negative, and every element changes its mode at most a few
/// times at one instant (a contact stuck → sliding, a flank open ↔ closed).
constexpr int kMaxRedecisions = 16;

/// The earliest dip of an event function below 0 between three check points t0 < t1 < t2 (values
/// g0, g1, g2, each ≥ off: no crossing seen) that the parabola through them predicts: its vertex t*
/// inside (max(t0, ta), t2) with the predicted minimum p* below every check and below a quarter of
/// the function's variation over them above p* (max g − p*: the parabola's error through a sine's
/// extremum at checks T/8 apart is under 1 % of it). NaN if none; only armed functions (off = 0).
/// Near 0, not only below it: p* is a prediction, the function at t* decides.
double dip(double t0, const double* g0, double t1, const double* g1, double t2, const double* g2, const double* off,
           size_t ne, double ta) {
  double best = std::numeric_limits<double>::quiet_NaN();
  if (!(t0 < t1 && t1 < t2)) return best;
  // At a step's first check the vertex lies in (t1, t2) (t0 < ta = t1): then p'(t1) < 0, and as p
  // is convex its chord before t1 falls (y1 < y0) and p* ≥ y1 + p'(t1)(t2 − t1) ≥ y1 − (y0 − y1) ρ,
  // ρ = (t2 − t1)/(t1 − t0). A function failing either has no dip: two operations, no division.
  const bool right = std::max(t0, ta) >= t1;
  const double rho = (t2 - t1) / (t1 - t0);
  for (size_t k = 0; k < ne; ++k) {
    const double y0 = g0[k], y1 = g1[k], y2 = g2[k];
    if (right && !(y1 < y0 && y1 - (y0 - y1) * rho < 0.25 * std::max(y0, y2))) continue;
    if (off[k] != 0.0) continue;
    const double lo = std::min({y0, y1, y2}), hi = std::max({y0, y1, y2});
    if (lo > 4.0 * (hi - lo)) continue;  // far from 0 for its variation (and a constant): no division
    const double d01 = (y1 - y0) / (t1 - t0), d12 = (y2 - y1) / (t2 - t1), c = (d12 - d01) / (t2 - t0);
    if (!(c > 0.0)) continue;  // p(t) = y0 + d01 (t − t0) + c (t − t0)(t − t1), convex
    const double ts = 0.5 * (t0 + t1) - d01 / (2.0 * c);
    if (!(ts > std::max(t0, ta) && ts < t2)) continue;
    const double ps = y0 + d01 * (ts - t0) + c * (ts - t0) * (ts - t1);
    if (ps < lo && ps < 0.25 * (hi - ps) && !(ts >= best)) best = ts;
  }
  return best;
}

/// One check's scan over the event functions g at s against the check before, gp at a, and the one
/// before that, gpp at t_pp (h1 = a − t_pp, h2 = s − a): whether some function crosses from ≥ off to
/// < off, and whether some armed one passes dip()'s pre-test at a step's first check (it falls into
/// the step, y1 < y0, and its convex lower bound y1 − (y0 − y1) h2/h1 comes within a quarter of its
/// largest check of 0; times h1: no division). The pre-test only gates the call of dip(), which
/// tests again. Two functions per SSE2 operation (every check of every step runs this scan: one
/// function at a time it was some 40 % of the driver's own instructions in the travel start-up, six
/// functions); the same comparisons and roundings as the scalar loop after it.
struct Scan {
  bool cross = false, may_dip = false;
};
inline Scan scan_checks(const double* gpp, const double* gp, const double* g, const double* off, size_t ne,
                        double h1, double h2) {
  Scan r;
  size_t k = 0;
  const double q = 0.25 * h1;
#if defined(__SSE2__)
  __m128d c = _mm_setzero_pd(), d = _mm_setzero_pd();
  const __m128d H1 = _mm_set1_pd(h1), H2 = _mm_set1_pd(h2), Q = _mm_set1_pd(q), Z = _mm_setzero_pd();
  for (; k + 2 <= ne; k += 2) {
    const __m128d v0 = _mm_loadu_pd(gpp + k), v1 = _mm_loadu_pd(gp + k), v2 = _mm_loadu_pd(g + k),
                  o = _mm_loadu_pd(off + k);
    c = _mm_or_pd(c, _mm_and_pd(_mm_cmpge_pd(v1, o), _mm_cmplt_pd(v2, o)));
    // max(v2, v0) as std::max(v0, v2): v2 where v0 < v2, else v0
    const __m128d lhs = _mm_sub_pd(_mm_mul_pd(v1, H1), _mm_mul_pd(_mm_sub_pd(v0, v1), H2));
    const __m128d rhs = _mm_mul_pd(Q, _mm_max_pd(v2, v0));
    d = _mm_or_pd(d, _mm_and_pd(_mm_and_pd(_mm_cmpeq_pd(o, Z), _mm_cmplt_pd(v1, v0)), _mm_cmplt_pd(lhs, rhs)));
  }
  r.cross = _mm_movemask_pd(c) != 0, r.may_dip = _mm_movemask_pd(d) != 0;
#endif
  for (; k < ne; ++k) {
    const double v0 = gpp[k], v1 = gp[k];
    r.cross |= (v1 >= off[k]) & (g[k] < off[k]);
    r.may_dip |= (off[k] == 0.0) & (v1 < v0) & (v1 * h1 - (v0 - v1) * h2 < q * std::max(v0, g[k]));
  }
  return r;
}

}  // namespace

RunStats integrate(Stepper& st, EventSystem& sys, double t0, const double* y0, double t_end,
                   const DriveOptions& opt, StepObserver& obs) {
  const auto start = std::chrono::steady_clock::now();
  const StepperStats before = st.stats();  // a stepper reused for a second run
  const auto n = static_cast<size_t>(st.size());
  const auto ne = static_cast<size_t>(sys.event_count());
  std::vector<double> y(y0, y0 + n), ytmp(n);
  std::vector<double> g_prev(ne), g_new(ne), g_tmp(ne), g_mid(ne), g_a(ne), g_dip(ne);
  // The check point before the last one (time, functions), for the dips between checks (dip()):
  // −∞ after a restart (the stepper's dense output starts there); last_*: the check before t1.
  std::vector<double> g_pp(ne);
  std::vector<double>* last_g = &g_prev;
  double t_pp = -std::numeric_limits<double>::infinity(), last_t = t_pp;
  // Per function the value it fires below: 0, or −∞ while the system's own decision keeps it below
  // 0 (settle below) until it is ≥ 0 at a step end.
  std::vector<double> off(ne, 0.0);
  bool any_off = false;
  const std::vector<double> bps = sys.breakpoints(t0, t_end);
  const long n_out = std::max(1L, std::lround(std::ceil((t_end - t0) / opt.dt_out - 1e-9)));
  // Local copies: no call in the loop below can change them, so they stay in registers.
  const double dt_out = opt.dt_out;
  const bool outputs = opt.outputs;
  // The spacing of the event functions' checks inside long steps (EventSystem::sampling_step), at
  // most 2^20 checks over the run (a sine of 1e9 rad/s on a body that stands still for seconds).
  const double h_s = ne ? std::max(sys.sampling_step(t0, t_end), (t_end - t0) / 1048576.0)
                        : std::numeric_limits<double>::infinity();
  auto out_time = [&](long k) { return k >= n_out ? t_end : t0 + static_cast<double>(k) * dt_out; };
  long k_out = 1;
  // The time of output row k_out (∞ after the last or without outputs): formed once per row.
  double t_out = outputs ? out_time(k_out) : std::numeric_limits<double>::infinity();
  // The solution on [ta, tb] of the current step ending at ts = st.t(): outputs inside it, then the
  // observers' piece.
  auto segment = [&](double ta, double tb, double ts) {
    if (t_out <= tb) {
      do {  // a row at the step's end from the stepper's own state (exact there)
        if (t_out == ts) {
          obs.on_output(t_out, st.y());
        } else {
          st.interpolate(t_out, ytmp.data());
          obs.on_output(t_out, ytmp.data());
        }
        ++k_out;
        t_out = k_out <= n_out ? out_time(k_out) : std::numeric_limits<double>::infinity();
      } while (t_out <= tb);
    }
    obs.on_segment(st, ta, tb);
  };
  RunStats stats;
  std::vector<int> fired;
  // The modes the system decided at t (the start, an event, a breakpoint) must have every event
  // function ≥ 0 at the state there: a function that is negative at a restart could never cross
  // from ≥ 0 to < 0 again and would stay disarmed for good. Such a function is a decision the event
  // functions contradict (one quantity formed by two computations that differ in their last bits,
  // a flank the state has already passed): it is handed back to the system as fired at t and
  // decided again, until every function is ≥ 0 or the system's decision no longer changes.
  // Leaves g_prev at t.
  auto settle = [&](double t, double* ys) {
    for (int round = 0;; ++round) {
      sys.event_functions(t, ys, g_prev.data());
      fired.clear();
      for (size_t k = 0; k < ne; ++k)
        if (!(g_prev[k] >= 0.0)) fired.push_back(static_cast<int>(k));
      std::fill(off.begin(), off.end(), 0.0);
      if (fired.empty()) return;
      if (round == kMaxRedecisions)
        throw SolverError("event function " + std::to_string(fired.front()), t,
                          "no consistent mode: the function stays negative after " + std::to_string(kMaxRedecisions) +
                              " decisions at this instant");
      const bool changed = sys.handle_events(t, ys, fired);
      obs.on_event(t, ys, fired);
      if (!changed) {
        // The system keeps its decision (it reports nothing changed): its last word. Such a
        // function is armed again only once it is ≥ 0 at a step end (the rule of old; the hybrid
        // run keeps it for lossy gears and stepwise gears alone, docs/hybrid.md "The restart rule").
        sys.event_functions(t, ys, g_prev.data());
        for (size_t k = 0; k < ne; ++k)
          if (!(g_prev[k] >= 0.0)) off[k] = -std::numeric_limits<double>::infinity(), any_off = true;
        return;
      }
    }
  };
  if (ne) settle(t0, y.data());
  st.reset(t0, y.data());
  if (opt.outputs) obs.on_output(t0, y.data());
  double t = t0;
  size_t next_bp = 0;
  while (t < t_end) {
    while (next_bp < bps.size() && bps[next_bp] <= t) ++next_bp;
    const bool to_bp = next_bp < bps.size() && bps[next_bp] < t_end;
    const double t_limit = to_bp ? bps[next_bp] : t_end;
    st.step(t_limit);
    obs.on_step(st);
    const double ta = st.t_prev(), t1 = st.t();
    const bool at_bp = to_bp && t1 == t_limit;
    // The earliest sign change from ≥ 0 to < 0 in the step. At a breakpoint the functions are taken
    // at its left limit: the loads there have already jumped. So at t_end, which may be one (the
    // breakpoints list only those before it): a normal force stepping up at t_end put a contact
    // stuck beyond its limit since 0.4 s back within it at the run's last step end, and the
    // breakaway inside that step was never seen.
    int first = -1;
    double te = std::numeric_limits<double>::infinity();
    if (ne) {
      sys.event_functions(at_bp || t1 >= t_end ? std::nextafter(t1, -std::numeric_limits<double>::infinity()) : t1,
                          st.y(), g_new.data());
      // A function may leave ≥ 0 and come back within one step, unseen by the error control (a
      // stuck body's state is constant while a sine load rises past the limit and falls back): in a
      // step longer than the system's sampling step h_s (its signals' time scale, whatever dt_out
      // is) the functions are checked every h_s inside it too, so no excursion longer than h_s is
      // missed. The crossing is then looked for in [a, b], the first stretch between checks that
      // has one.
      double a = ta, b = t1;
      const double *gp = g_prev.data(), *gn = g_new.data();
      // A check point (s, g) after (a, gp): a crossing between them; else a dip below 0 between
      // checks that the parabola through the last three check points finds (a function with an
      // excursion shorter than the checks' spacing: a sine load peaking 4 % beyond a stuck
      // contact's limit for 0.016 s, with checks T/8 = 0.027 s apart). The dip's point is checked
      // itself: [left check, dip] then brackets the crossing.
      bool crossed = false;
      auto check = [&](double s, const double* g) {
        // Most checks cross nothing, and at a step's first check (the dip's vertex in (a, s)) most
        // functions fail dip()'s pre-test on these same values (scan_checks).
        const bool right = std::max(t_pp, ta) >= a;
        const Scan sc = scan_checks(g_pp.data(), gp, g, off.data(), ne, a - t_pp, s - a);
        // One function crossing at s does not end the check: another's dip before it comes first
        // (a gap's relative motion, a free-flight parabola in one dopri5 step, touching one flank
        // and reaching the other at s: the first flank's closing was lost).
        if (sc.cross) crossed = true, b = s, gn = g;
        if (!(sc.may_dip || !right) || !(t_pp > -std::numeric_limits<double>::infinity())) return crossed;
        // The rare rest: a dip between the last three checks, (t_pp, g_pp), (a, gp), (s, g) (dip()),
        // checked at its point — out of line, its closure formed only here, so that the scan above is
        // all a check costs.
        auto at_dip = [&]() __attribute__((noinline)) {
          const double td = dip(t_pp, g_pp.data(), a, gp, s, g, off.data(), ne, ta);
          if (!(td > ta && td < s)) return crossed;
          const bool crossed_at_s = crossed;
          crossed = false;
          st.interpolate(td, ytmp.data());
          sys.event_functions(td, ytmp.data(), g_dip.data());
          // A dip shallower than 1e-4 of the function's variation over the checks is a tangency
          // within the integration's resolution (BDF's freewheel speed touching 0 at −8e-10 rad/s in
          // MSL's OneWayClutch, 3e-6 of its variation), not an excursion (a stuck contact's load beyond
          // its limit for 16 ms between step ends, 2e-3; a sine's peak beyond it, 0.1): no crossing.
          for (size_t k = 0; k < ne; ++k) {
            const double hi = std::max({g_pp[k], gp[k], g[k]});
            if (g_dip[k] < off[k] && !(g_dip[k] < -1e-4 * (hi - g_dip[k]))) g_dip[k] = off[k];
          }
          // A vertex after the last check: the crossing is from it, (a, gp). One between the two checks
          // before is from (t_pp, g_pp) only: judged from (a, gp) it made a reversed bracket [a, td]
          // whose Illinois root was the function's way back up (campaign `mixed` seed 7 #283: a
          // stuck contact's load beyond its sine limit from 0.3599 s to 0.3924 s in one 0.37 s
          // dopri5 step, its breakaway located at 0.3924 s, the end of the excursion).
          if (td > a)
            for (size_t k = 0; k < ne; ++k) crossed = crossed || (gp[k] >= off[k] && g_dip[k] < off[k]);
          if (!crossed && td < a) {  // between the two checks before: the crossing is from (t_pp, g_pp)
            for (size_t k = 0; k < ne; ++k) crossed = crossed || (g_pp[k] >= off[k] && g_dip[k] < off[k]);
            if (crossed) gp = g_pp.data(), a = t_pp;
          }
          if (crossed) b = td, gn = g_dip.data();
          crossed = crossed || crossed_at_s;
          return crossed;
        };
        return at_dip();
      };
      for (double j = 1.0; t1 - ta > h_s; ++j) {
        const double s = ta + j * h_s;
        if (!(s < t1)) break;
        st.interpolate(s, ytmp.data());
        sys.event_functions(s, ytmp.data(), g_mid.data());
        if (check(s, g_mid.data())) break;
        g_pp.assign(gp, gp + ne), t_pp = a;
        g_a = g_mid, gp = g_a.data(), a = s;
      }
      if (!crossed) check(t1, g_new.data());
      last_t = -std::numeric_limits<double>::infinity();
      // The check before t1 becomes the next step's first (t_pp, g_pp): swapped in below, not copied.
      if (!crossed) last_t = a, last_g = gp == g_prev.data() ? &g_prev : &g_a;
      for (size_t k = 0; k < (crossed ? ne : 0); ++k) {
        if (!(gp[k] >= off[k] && gn[k] < off[k])) continue;
        const Bracket br = illinois(
            [&](double tm) {
              st.interpolate(tm, ytmp.data());
              sys.event_functions(tm, ytmp.data(), g_tmp.data());
              return g_tmp[k] - off[k];
            },
            // 400 iterates: on a kink (a taut rope or gap without a damper: −c (δ − δ₊) beyond the
            // flank) the Illinois halvings do not outlast the bisection of every 8th iterate, so the
            // bracket halves once per 8 — some 45 bisections from a step of 0.1 s down to 1e-13 s.
            a, gp[k] - off[k], b, gn[k] - off[k], opt.event_tol * std::max(1.0, std::abs(b)), 400);
        if (br.hi < te) te = br.hi, first = static_cast<int>(k);
      }
    }
    if (first < 0) {
      segment(ta, t1, t1);
      t_pp = last_t, g_pp.swap(*last_g);  // the check before t1: the next step's first triple
      g_prev.swap(g_new);
      if (any_off) {  // a function armed below 0 that is ≥ 0 again is armed from 0
        any_off = false;
        for (size_t k = 0; k < ne; ++k) {
          if (g_prev[k] >= 0.0) off[k] = 0.0;
          any_off = any_off || off[k] != 0.0;
        }
      }
      t = t1;
      if (at_bp) {  // loads may jump here: the system looks at its modes, the stepper restarts
        std::copy(st.y(), st.y() + n, y.begin());
        fired.clear();
        sys.handle_events(t1, y.data(), fired);
        obs.on_event(t1, y.data(), fired);
        if (ne) settle(t1, y.data());
        st.reset(t1, y.data());
        t_pp = -std::numeric_limits<double>::infinity();
      }
      continue;
    }
    // An event at te (the right end of the final bracket: the crossing has happened there). The
    // solution up to te belongs to the old modes.
    segment(ta, te, t1);
    st.interpolate(te, y.data());
    sys.event_functions(te, y.data(), g_tmp.data());
    fired.assign(1, first);
    for (size_t k = 0; k < ne; ++k)
      if (static_cast<int>(k) != first && g_prev[k] >= off[k] && g_tmp[k] < off[k]) fired.push_back(static_cast<int>(k));
    ++stats.events;
    sys.handle_events(te, y.data(), fired);
    obs.on_event(te, y.data(), fired);
    settle(te, y.data());
    st.reset(te, y.data());
    t_pp = -std::numeric_limits<double>::infinity();
    t = te;
  }
  stats.stepper = minus(st.stats(), before);
  stats.method = st.name();
  stats.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return stats;
}

}  // namespace machdyn
