// The engine against the reference simulator (campaign.hpp).
#include "reference/campaign.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <set>

#include "reference/generator.hpp"

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn::reference {

const char* to_string(Outcome::Kind k) {
  switch (k) {
    case Outcome::Kind::pass: return "pass";
    case Outcome::Kind::engine_error: return "engine error";
    case Outcome::Kind::event_mismatch: return "event mismatch";
    case Outcome::Kind::state_mismatch: return "state mismatch";
    case Outcome::Kind::reference_error: return "reference error";
  }
  return "?";
}

namespace {

/// The invariant audit of the run (SimulateOptions::check, issue 27 item 2) where the engine has it.
template <class O>
void audit_on(O& o) {
  if constexpr (requires { o.check = true; }) o.check = true;
}

const std::set<std::string>& compared_kinds() {
  static const std::set<std::string> k = {"gap_closed", "gap_opened", "stick", "slip", "reversal", "impact", "applied",
                                          "mesh", "free play", "taut", "slack", "driving_side"};
  return k;
}

/// The events of `list` that open and close a phase of one element shorter than tol (s): a `slip`
/// (or an `applied` into a slide) and the `stick` that ends it, a `stick` and the `slip` that ends
/// it, a `slip` and the `released` that ends it (a clutch breaking away as its normal force falls to
/// 0 and opening at that zero: whether it broke away first is below the resolution), a `gap_opened` and the
/// `gap_closed` that ends it (and the reverse), within tol of each other. The comparison resolves
/// instants to tol only, so it cannot see such a phase — nor compare it; the states are compared
/// whatever the events (a phase with an effect shows there). Both sides make them: the engine a
/// slide of a pair of parallel contacts 1e-13 s long at an impact, the reference a stick between
/// two located crossings 7e-14 s apart.
///
/// `tols` (the reference's list): each event's own tolerance (its window, δg/|ġ|); a phase shorter
/// than both of its events' is below their resolution too (a rope going slack at a grazing zero of
/// its force, its instants known to ±0.04 s: 0.45 ms slack in the reference, 1e-15 s in the engine —
/// `one-sided` seed 7 #495).
template <class List, class Get>
std::vector<char> brief_phases(const List& list, double tol, Get get, const std::vector<double>* tols = nullptr) {
  auto undoes = [](const std::string& a, const std::string& b) {
    return ((a == "slip" || a == "applied") && b == "stick") || (a == "stick" && b == "slip") || (a == "slip" && b == "released") ||
           (a == "gap_opened" && b == "gap_closed") || (a == "gap_closed" && b == "gap_opened") || (a == "taut" && b == "slack") ||
           (a == "slack" && b == "taut");
  };
  std::vector<char> brief(list.size(), 0);
  auto own = [&](size_t i) { return tols != nullptr && i < tols->size() ? std::max(tol, (*tols)[i]) : tol; };
  for (size_t i = 0; i < list.size(); ++i) {
    if (brief[i]) continue;
    for (size_t j = i + 1; j < list.size() && get(list[j]).t <= get(list[i]).t + own(i); ++j) {
      if (brief[j] || get(list[j]).element != get(list[i]).element) continue;
      if (undoes(get(list[i]).kind, get(list[j]).kind) && get(list[j]).t <= get(list[i]).t + std::min(own(i), own(j)))
        brief[i] = brief[j] = 1;
      break;  // the element's next event: it ends the phase, or the phase is not brief
    }
  }
  return brief;
}

/// The events of `list` that open and close an unloaded stuck phase of a freewheel without drag: its
/// `stick` and the `slip` that ends it, where its load stays within δ of 0 at every output row of the
/// phase, and it has one (`load(element, t0, t1)`: the largest |λ| of both runs over those rows, ∞
/// without one). Stuck with λ = 0 and overrunning
/// at u = 0 it exerts the same force (none: no drag) on the same velocities (u = 0 either way), so the
/// two modes are one motion and the mode a label — which one a run shows is its rounding: BDF's
/// Newton corrections leave a body tied to the ground by stuck contacts 1e-20 m/s off rest, and the
/// overrun function of a backstop on it fired there and was decided stuck (campaign `mixed` seed 1
/// #52: 5 ms stuck with λ = 0 exactly, then a `slip` with the contact that held the body; the
/// reference's body stays at 0 exactly and never fires it). Not compared on that side; a stuck phase
/// that carries a load is (CampaignDefectsH).
template <class List, class Get, class Load>
std::vector<char> label_phases(const List& list, const RefModel& m, double t_cmp, double delta, Get get, Load load) {
  std::vector<char> label(list.size(), 0);
  for (size_t i = 0; i < list.size(); ++i) {
    const auto& e = get(list[i]);
    if (e.kind != "stick") continue;
    const Friction* f = nullptr;
    for (const Friction& x : m.frictions)
      if (x.name == e.element) f = &x;
    if (f == nullptr || f->kind != Friction::Kind::freewheel || f->drag != 0.0) continue;
    size_t j = i + 1;
    while (j < list.size() && get(list[j]).element != e.element) ++j;
    // A phase to the end, or whose slip is not compared (at the reference's ambiguity, on both sides
    // alike): compared.
    if (j == list.size() || get(list[j]).kind != "slip" || get(list[j]).t >= t_cmp) continue;
    if (load(e.element, e.t, get(list[j]).t) <= delta) label[i] = label[j] = 1;
  }
  return label;
}

std::string fmt(double x) {
  char b[32];
  std::snprintf(b, sizeof b, "%.12g", x);
  return b;
}

}  // namespace

Outcome compare(const RefModel& m, const std::string& integrator, const RefResult& ref) {
  if (!ref.error.empty()) return {Outcome::Kind::reference_error, ref.error, 0.0};
  SimulationResult r;
  try {
    Model model = compile_model(parse_yaml_string(to_yaml(m, integrator), "random.yaml"), "random.yaml");
    SimulateOptions so;
    so.max_events = 200'000;  // a runaway run is a failure, not a hang (and max_steps in the file)
    audit_on(so);
    r = simulate(model, so);
  } catch (const std::exception& e) {
    return {Outcome::Kind::engine_error, e.what(), 0.0};
  }
  return compare_results(m, ref, r);
}

StateTolerances state_tolerances(const RefModel& m, const RefResult& ref) {
  StateTolerances s;
  s.q.assign(m.bodies.size(), 1e-9), s.v.assign(m.bodies.size(), 1e-9);
  for (size_t i = 0; i < m.bodies.size(); ++i) {
    double sq = 0.0, sv = 0.0;
    for (size_t k = 0; k < ref.t.size(); ++k) sq = std::max(sq, std::abs(ref.q[k][i])), sv = std::max(sv, std::abs(ref.v[k][i]));
    s.q[i] = kStateTol * sq + 1e-9, s.v[i] = kStateTol * sv + 1e-9;
  }
  return s;
}

double event_tolerance(const RefEvent& e, const StateTolerances& s, double tol_t) {
  if (e.body < 0 || static_cast<size_t>(e.body) >= s.q.size()) return tol_t;
  const auto b = static_cast<size_t>(e.body);
  double dq = s.q[b], dv = s.v[b];
  if (e.body2 >= 0 && static_cast<size_t>(e.body2) < s.q.size()) dq += e.w2 * s.q[static_cast<size_t>(e.body2)], dv += e.w2 * s.v[static_cast<size_t>(e.body2)];
  return std::max(tol_t, e.dt_dq * dq + e.dt_dsqrtq * std::sqrt(dq) + e.dt_dv * dv);
}

double shift_allowance(const RefResult& ref, const std::vector<std::pair<double, double>>& shifts, size_t body, int w, size_t k) {
  double dt = 0.0;  // the largest time offset of the events matched up to row k
  for (const auto& [t, d] : shifts)
    if (t <= ref.t[k]) dt = std::max(dt, d);
  if (dt == 0.0) return 0.0;
  // The column's rate at row k: the velocity for a position, the largest difference quotient of the
  // velocity over the neighbouring rows for a velocity.
  double rate = 0.0;
  if (w == 0) {
    rate = std::abs(ref.v[k][body]);
  } else {
    if (k > 0) rate = std::abs(ref.v[k][body] - ref.v[k - 1][body]) / (ref.t[k] - ref.t[k - 1]);
    if (k + 1 < ref.t.size()) rate = std::max(rate, std::abs(ref.v[k + 1][body] - ref.v[k][body]) / (ref.t[k + 1] - ref.t[k]));
  }
  return rate * dt;
}

Outcome compare_results(const RefModel& m, const RefResult& ref, const SimulationResult& r) {
  Outcome o;
  if (!ref.error.empty()) return {Outcome::Kind::reference_error, ref.error, 0.0};
  const double t_cmp = ref.ambiguous_from;
  const double tol_t = kEventTol * std::max(1.0, m.t_end);
  const StateTolerances stol = state_tolerances(m, ref);
  // Events: every reference event before t_cmp matched in order by (element, kind) within its
  // tolerance (tol_t, or what the state tolerance moves it by: event_tolerance).
  // The bounces of a stop with restitution end in a Zeno tail; the engine stops it at flights of
  // 1e-12 s, the reference at 1e-9 s: an impact followed within tol_t by another impact or the rest
  // of the same stop is not compared (on both sides).
  auto zeno_tail = [&](const auto& list, size_t i, auto get) {
    if (get(list[i]).kind != "impact") return false;
    for (size_t j = i + 1; j < list.size() && get(list[j]).t <= get(list[i]).t + tol_t; ++j)
      if (get(list[j]).element == get(list[i]).element && (get(list[j]).kind == "impact" || get(list[j]).kind == "stick")) return true;
    return false;
  };
  // A gear mesh's `mesh` event within tol_t of the start or of another event (the same mesh's, or
  // another element's that is no mesh's: a slip, a release) is that instant's decision: the signs of speeds at 0 there (a
  // body at rest when the contact begins, every body at rest at the start, a body held by a stuck
  // contact that slips at that instant) are read one way or the other within rounding — at ω = 0
  // that side passes no power, so either reading is the law's — and the other way is a reversal
  // ~1e-13 s later. Not compared (on both sides); a wrong power direction over any finite time
  // still changes the torques by (1 − η) τ and the states.
  auto mesh_tie = [&](const auto& list, size_t i, auto get) {
    if (get(list[i]).kind != "mesh") return false;
    const double ti = get(list[i]).t;
    if (ti <= tol_t) return true;
    auto ties = [&](size_t j) {  // the same mesh's event, or another element's that is no mesh's
      const auto& e = get(list[j]);
      if (e.kind == "initial") return false;
      return e.element == get(list[i]).element || (e.kind != "mesh" && e.kind != "free play");
    };
    for (size_t j = i; j-- > 0 && get(list[j]).t >= ti - tol_t;)
      if (ties(j)) return true;
    for (size_t j = i + 1; j < list.size() && get(list[j]).t <= ti + tol_t; ++j)
      if (get(list[j]).element != get(list[i]).element && ties(j)) return true;
    return false;
  };
  const auto eng_brief = brief_phases(r.hybrid.events, tol_t, [](const ModeEvent& x) -> const ModeEvent& { return x; });
  std::vector<double> ref_tols(ref.events.size());
  for (size_t i = 0; i < ref.events.size(); ++i)
    ref_tols[i] = std::max(event_tolerance(ref.events[i], stol, tol_t), ref.events[i].window);
  const auto ref_brief = brief_phases(ref.events, tol_t, [](const RefEvent& x) -> const RefEvent& { return x; }, &ref_tols);
  // Unloaded stuck phases of freewheels without drag (label_phases), λ within δ = kLoadResolution ×
  // the largest stuck load of the reference run (≥ 1 N).
  double lam_scale = 1.0;
  for (const auto& row : ref.lam)
    for (double x : row) lam_scale = std::max(lam_scale, std::abs(x));
  const double lam_delta = kLoadResolution * lam_scale;
  // The largest |λ| over the rows inside (t0, t1); a phase without a row is not seen unloaded (∞).
  auto ref_load = [&](const std::string& name, double t0, double t1) {
    double worst = HUGE_VAL;
    for (size_t j = 0; j < m.frictions.size(); ++j)
      if (m.frictions[j].name == name)
        for (size_t k = 0; k < ref.t.size(); ++k)
          if (ref.t[k] > t0 && ref.t[k] < t1 && j < ref.lam[k].size())
            worst = std::isinf(worst) ? std::abs(ref.lam[k][j]) : std::max(worst, std::abs(ref.lam[k][j]));
    return worst;
  };
  auto eng_load = [&](const std::string& name, double t0, double t1) {
    const std::vector<double>* F = nullptr;
    const std::vector<double>* ts = nullptr;
    for (size_t c = 0; c < r.column_names.size(); ++c) {
      if (r.column_names[c] == name + ".force_N" || r.column_names[c] == name + ".force_N_m") F = &r.columns[c];
      if (r.column_names[c] == "t_s") ts = &r.columns[c];
    }
    double worst = HUGE_VAL;  // no column, or no row inside: not seen unloaded
    if (F == nullptr || ts == nullptr) return worst;
    for (size_t k = 0; k < ts->size() && k < F->size(); ++k)
      if ((*ts)[k] > t0 && (*ts)[k] < t1) worst = std::isinf(worst) ? std::abs((*F)[k]) : std::max(worst, std::abs((*F)[k]));
    return worst;
  };
  // Unloaded in both runs (one side's label phase is the other's unloaded stuck or overrun phase:
  // a side whose freewheel carries a load there is compared on both).
  auto both_load = [&](const std::string& name, double t0, double t1) { return std::max(eng_load(name, t0, t1), ref_load(name, t0, t1)); };
  const auto eng_label = label_phases(r.hybrid.events, m, t_cmp - tol_t, lam_delta, [](const ModeEvent& x) -> const ModeEvent& { return x; }, both_load);
  const auto ref_label = label_phases(ref.events, m, t_cmp - tol_t, lam_delta, [](const RefEvent& x) -> const RefEvent& { return x; }, both_load);
  // The rest that ends a series of bounces is its accumulation instant t∞, known to its tolerance
  // only: an impact of the same stop within that tolerance of it belongs to the series' tail (either
  // side may resolve fewer or more of those bounces) and is not compared either.
  // Each bounce reverses the friction on the bouncing body: a `reversal` of a contact on it within
  // that tolerance of the rest belongs to the tail too.
  struct Rest {
    const std::string* element;
    double t, tol;
    int body;
  };
  auto friction = [&](const std::string& name) -> const Friction* {
    for (const Friction& f : m.frictions)
      if (f.name == name) return &f;
    return nullptr;
  };
  std::vector<Rest> rests;
  for (const RefEvent& e : ref.events) {
    const Friction* f = friction(e.element);
    if (e.kind == "stick" && e.body >= 0 && f != nullptr && f->kind == Friction::Kind::stop)
      rests.push_back({&e.element, e.t, event_tolerance(e, stol, tol_t), e.body});
  }
  auto near_rest = [&](const std::string& element, const std::string& kind, double t) {
    if (kind != "impact" && kind != "reversal") return false;
    const Friction* f = kind == "reversal" ? friction(element) : nullptr;
    for (const Rest& x : rests) {
      if (std::abs(t - x.t) > x.tol) continue;
      if (kind == "impact" ? *x.element == element : f != nullptr && (f->a == x.body || f->b == x.body)) return true;
    }
    return false;
  };
  // A brake or clutch applied while its bodies move slides the way u points; the sign of u there is
  // fixed only to the state tolerance δv_a + δv_b. A reversal of that slide whose instant is known
  // to less than its time since the application (its tolerance δv/|u̇| reaches back to it) may lie
  // before it: applied the other way, without a reversal, is the same motion within the states'
  // tolerance. Such a reversal is not compared, nor one of the engine's of that element up to it.
  struct Undecided {
    const std::string* element;
    double from, to;
  };
  std::vector<Undecided> undecided;
  std::vector<char> ref_undecided(ref.events.size(), 0);
  for (size_t i = 0; i < ref.events.size(); ++i) {
    const RefEvent& e = ref.events[i];
    if (e.kind != "reversal" || ref_brief[i]) continue;
    for (size_t j = i; j-- > 0;) {
      if (ref.events[j].element != e.element) continue;
      const double tol_e = std::max(event_tolerance(e, stol, tol_t), e.window);
      if (ref.events[j].kind == "applied" && e.t - tol_e <= ref.events[j].t)
        ref_undecided[i] = 1, undecided.push_back({&e.element, ref.events[j].t, e.t + tol_e});
      break;
    }
  }
  auto undecided_reversal = [&](const ModeEvent& e) {
    if (e.kind != "reversal") return false;
    for (const Undecided& x : undecided)
      if (*x.element == e.element && e.t >= x.from && e.t <= x.to) return true;
    return false;
  };
  // An event whose instant is known only to a tolerance that reaches back to the start (its window
  // covers [0, t]: a function growing from 0 at rest, within the resolution of its loads all the
  // way) is that instant's decision as much as one within tol_t of it: not compared, nor the
  // engine's events of that element up to its instant plus tolerance (short of the element's next
  // reference event that is compared, less its tolerance). A train that starts at 3e-6 s in the
  // reference and at 6e-9 s in the engine (`gear` seed 2 #5), a freewheel overrunning from 2e-8 s
  // to 1.4e-4 s in one run and stuck in the other (`freewheel` seed 7 #28: its stick ±0.07 s).
  struct AtStart {
    const std::string* element;
    double to;
  };
  // Only the element's first compared event (a later one with a wide tolerance — the tail of a
  // Zeno series — is no start).
  std::vector<AtStart> at_start;
  std::vector<char> ref_at_start(ref.events.size(), 0);
  std::set<std::string> seen;
  for (size_t i = 0; i < ref.events.size(); ++i) {
    const RefEvent& e = ref.events[i];
    if (ref_brief[i] || ref_label[i] || ref_undecided[i] || compared_kinds().count(e.kind) == 0 || e.t <= tol_t || e.t >= t_cmp - tol_t) continue;
    if (!seen.insert(e.element).second) continue;
    const double tol_e = std::max(event_tolerance(e, stol, tol_t), e.window);
    if (e.t - tol_e > tol_t) continue;
    ref_at_start[i] = 1;
    double to = e.t + tol_e;
    for (size_t j = i + 1; j < ref.events.size(); ++j)
      if (ref.events[j].element == e.element && compared_kinds().count(ref.events[j].kind) != 0 && !ref_brief[j] && !ref_label[j]) {
        const double tol_j = std::max(event_tolerance(ref.events[j], stol, tol_t), ref.events[j].window);
        if (ref.events[j].t - tol_j > tol_t) to = std::min(to, ref.events[j].t - tol_j);
        if (ref.events[j].t - tol_j > tol_t) break;
      }
    at_start.push_back({&e.element, to});
  }
  auto start_decision = [&](const ModeEvent& e) {
    for (const AtStart& x : at_start)
      if (*x.element == e.element && e.t <= x.to) return true;
    return false;
  };
  // The engine's counterpart of a reference phase below its events' tolerances (brief_phases): its
  // events of those kinds within the pair's tolerances are not compared either.
  struct Unresolved {
    const RefEvent *a, *b;
    double lo, hi;
  };
  std::vector<Unresolved> unresolved_phases;
  for (size_t i = 0; i < ref.events.size(); ++i) {
    if (!ref_brief[i]) continue;
    for (size_t j = i + 1; j < ref.events.size(); ++j)
      if (ref.events[j].element == ref.events[i].element) {
        if (ref_brief[j] && ref.events[j].t - ref.events[i].t > tol_t)
          unresolved_phases.push_back({&ref.events[i], &ref.events[j], ref.events[i].t - ref_tols[i], ref.events[j].t + ref_tols[j]});
        if (ref_brief[j]) i = j;
        break;
      }
  }
  // The engine's pair: its first event of the opening kind within the tolerances and the element's
  // next event, of the closing kind, within them too.
  std::vector<char> eng_unresolved(r.hybrid.events.size(), 0);
  for (const Unresolved& x : unresolved_phases)
    for (size_t i = 0; i < r.hybrid.events.size(); ++i) {
      const ModeEvent& e = r.hybrid.events[i];
      if (eng_unresolved[i] || e.element != x.a->element || e.kind != x.a->kind || e.t < x.lo || e.t > x.hi) continue;
      size_t j = i + 1;
      while (j < r.hybrid.events.size() && r.hybrid.events[j].element != e.element) ++j;
      if (j < r.hybrid.events.size() && r.hybrid.events[j].kind == x.b->kind && r.hybrid.events[j].t <= x.hi)
        eng_unresolved[i] = eng_unresolved[j] = 1;
      break;
    }
  std::vector<const ModeEvent*> eng;
  for (size_t i = 0; i < r.hybrid.events.size(); ++i) {
    const auto& e = r.hybrid.events[i];
    if (eng_brief[i] || eng_label[i] || undecided_reversal(e) || start_decision(e) || eng_unresolved[i]) continue;  // a phase shorter than the instants' resolution
    auto same = [](const ModeEvent& x) -> const ModeEvent& { return x; };
    if (compared_kinds().count(e.kind) != 0 && e.t < t_cmp - tol_t && e.t > tol_t && !near_rest(e.element, e.kind, e.t) &&
        !zeno_tail(r.hybrid.events, i, same) && !mesh_tie(r.hybrid.events, i, same))
      eng.push_back(&e);
  }
  std::vector<bool> used(eng.size(), false);
  std::vector<std::pair<double, double>> shifts;  // (reference time, |engine − reference|) of the matched events
  size_t first_free = 0;
  Outcome ev;  // the first event difference (pass if none)
  for (size_t ir = 0; ir < ref.events.size(); ++ir) {
    const RefEvent& re = ref.events[ir];
    if (ref_brief[ir] || ref_label[ir] || ref_undecided[ir] || ref_at_start[ir]) continue;
    // An event within tol_t of the start is that instant's decision, which the engine makes at t = 0
    // (its `initial` modes, not events) and the reference may locate an ulp-sized step later (a
    // brake whose application and load both start from 0): not compared on either side (the states
    // are). A shift beyond tol_t is compared.
    if (compared_kinds().count(re.kind) == 0 || re.t >= t_cmp - tol_t || re.t <= tol_t) continue;
    auto same_ref = [](const RefEvent& x) -> const RefEvent& { return x; };
    if (near_rest(re.element, re.kind, re.t) || zeno_tail(ref.events, ir, same_ref) || mesh_tie(ref.events, ir, same_ref))
      continue;
    // The instant as well as the state tolerance (event_tolerance) and the model (its resolution
    // window) fix it.
    const double tol_e = std::max(event_tolerance(re, stol, tol_t), re.window);
    bool hit = false;
    for (size_t j = first_free; j < eng.size(); ++j) {
      if (used[j]) continue;
      if (eng[j]->t > re.t + tol_e) break;
      if (eng[j]->element == re.element && eng[j]->kind == re.kind && std::abs(eng[j]->t - re.t) <= tol_e) {
        used[j] = hit = true;
        shifts.push_back({re.t, std::min(std::abs(eng[j]->t - re.t), tol_t)});  // a wider tolerance is the instant's, not the motion's
        break;
      }
    }
    while (first_free < used.size() && used[first_free]) ++first_free;
    if (!hit) {
      // The first unmatched engine event before this one says what the engine did instead.
      std::string instead = "nothing";
      for (size_t j = 0; j < eng.size(); ++j)
        if (!used[j] && eng[j]->t <= re.t + tol_e) {
          instead = eng[j]->kind + " " + eng[j]->element + " at " + fmt(eng[j]->t);
          break;
        }
      ev = {Outcome::Kind::event_mismatch,
            "reference " + re.kind + " " + re.element + " at " + fmt(re.t) + " (±" + fmt(tol_e) + "), engine: " + instead, re.t};
      break;
    }
  }
  if (ev.kind == Outcome::Kind::pass)
    for (size_t j = 0; j < eng.size(); ++j)
      if (!used[j]) {
        ev = {Outcome::Kind::event_mismatch, "engine " + eng[j]->kind + " " + eng[j]->element + " at " + fmt(eng[j]->t) + ", not in the reference",
              eng[j]->t};
        break;
      }
  // States at the output rows.
  auto col = [&](const std::string& name) -> const std::vector<double>* {
    for (size_t c = 0; c < r.column_names.size(); ++c)
      if (r.column_names[c] == name) return &r.columns[c];
    return nullptr;
  };
  const auto* ts = col("t_s");
  if (ts == nullptr || ts->size() != ref.t.size())
    return {Outcome::Kind::state_mismatch, "output rows: engine " + std::to_string(ts ? ts->size() : 0) + ", reference " + std::to_string(ref.t.size()), 0.0};
  for (size_t i = 0; i < m.bodies.size(); ++i)
    for (int w = 0; w < 2; ++w) {
      const bool rot = (m.rotational && !m.bodies[i].linear) || m.bodies[i].angular;
      const std::string name = m.bodies[i].name + (w == 0 ? (rot ? ".position_rad" : ".position_m") : (rot ? ".velocity_rad_s" : ".velocity_m_s"));
      const auto* c = col(name);
      if (c == nullptr) return {Outcome::Kind::state_mismatch, "no column " + name, 0.0};
      const double tol0 = w == 0 ? stol.q[i] : stol.v[i];
      for (size_t k = 0; k < ref.t.size() && ref.t[k] < t_cmp; ++k) {
        const double rv = w == 0 ? ref.q[k][i] : ref.v[k][i];
        const double tol = tol0 + shift_allowance(ref, shifts, i, w, k);
        if (!(std::abs((*c)[k] - rv) <= tol))
          return {Outcome::Kind::state_mismatch,
                  name + " at t = " + fmt(ref.t[k]) + ": engine " + fmt((*c)[k]) + ", reference " + fmt(rv) + " (tolerance " + fmt(tol) + ")" +
                      (ev.kind == Outcome::Kind::pass ? std::string() : "; first event difference: " + ev.detail),
                  ref.t[k]};
      }
    }
  // The events differ but every state agrees: the event list is wrong, not the motion.
  if (ev.kind != Outcome::Kind::pass) ev.detail += " (states agree)";
  return ev.kind != Outcome::Kind::pass ? ev : o;
}

Outcome tightened(const RefModel& ref_model, const RefModel& engine_model, const std::string& integrator) {
  RefOptions fine;
  fine.omega_h /= kTightStep;
  const RefResult ref = simulate_reference(ref_model, fine);
  if (!ref.error.empty()) return {Outcome::Kind::reference_error, ref.error, 0.0};
  SimulationResult r;
  try {
    std::string y = to_yaml(engine_model, integrator);
    const std::string loose = "rtol: 1e-10, atol: 1e-12";
    const size_t at = y.find(loose);
    if (at != std::string::npos) y.replace(at, loose.size(), "rtol: 1e-12, atol: 1e-14");
    SimulateOptions so;
    so.max_events = 200'000;
    audit_on(so);
    r = simulate(compile_model(parse_yaml_string(y, "random.yaml"), "random.yaml"), so);
  } catch (const std::exception& e) {
    return {Outcome::Kind::engine_error, e.what(), 0.0};
  }
  return compare_results(ref_model, ref, r);
}

double reference_spread(const RefModel& m, const RefResult& ref, const RefResult& ref4) {
  const StateTolerances s = state_tolerances(m, ref);
  double worst = 0.0;
  for (size_t k = 0; k < ref.t.size() && k < ref4.t.size(); ++k)
    for (size_t i = 0; i < m.bodies.size(); ++i) {
      const double dq = std::abs(ref.q[k][i] - ref4.q[k][i]) / s.q[i], dv = std::abs(ref.v[k][i] - ref4.v[k][i]) / s.v[i];
      worst = std::isnan(dq + dv) ? HUGE_VAL : std::max({worst, dq, dv});
    }
  return worst;
}

Outcome unless_unresolved(const RefModel& m, const RefResult& ref, const Outcome& tight) {
  if (tight.kind != Outcome::Kind::state_mismatch || !ref.error.empty()) return tight;
  RefOptions fine;
  fine.omega_h /= kTightStep;
  const RefResult ref4 = simulate_reference(m, fine);
  if (!ref4.error.empty()) return tight;
  const double spread = reference_spread(m, ref, ref4);
  if (!(spread > 1.0)) return tight;
  return {Outcome::Kind::reference_error,
          "unresolved: the reference at h and at h/" + fmt(kTightStep) + " differ by " + fmt(spread) +
              " state tolerances (" + tight.detail + ")",
          tight.t};
}

Outcome check(const RefModel& m, const std::string& integrator, const RefOptions& o) {
  return compare(m, integrator, simulate_reference(m, o));
}

namespace {

/// m without body i (and every element on it).
RefModel without_body(const RefModel& m, int i) {
  RefModel s = m;
  auto map = [&](int b) { return b < 0 ? b : b > i ? b - 1 : b; };
  s.bodies.erase(s.bodies.begin() + i);
  s.links.clear(), s.loads.clear(), s.frictions.clear();
  for (auto L : m.links)
    if (L.a != i && L.b != i && !(L.a < 0 && L.b < 0)) L.a = map(L.a), L.b = map(L.b), s.links.push_back(L);
  for (auto l : m.loads)
    if (l.body != i) l.body = map(l.body), s.loads.push_back(l);
  for (auto f : m.frictions)
    if (f.a != i && f.b != i) f.a = map(f.a), f.b = map(f.b), s.frictions.push_back(f);
  s.motors.clear();
  for (auto M : m.motors)
    if (M.body != i) M.body = map(M.body), s.motors.push_back(M);
  s.releases.clear();
  for (auto x : m.releases)
    if (x.body != i) x.body = map(x.body), s.releases.push_back(x);
  s.meshes.clear();
  for (auto G : m.meshes)
    if (G.a != i && G.b != i) G.a = map(G.a), G.b = map(G.b), s.meshes.push_back(G);
  s.sway.clear();
  for (auto R : m.sway) {
    if (R.x == i || R.y == i || R.z == i || R.psi == i || R.trolley == i || R.bridge == i || R.drum == i) continue;
    R.x = map(R.x), R.y = map(R.y), R.z = map(R.z), R.psi = map(R.psi), R.trolley = map(R.trolley), R.bridge = map(R.bridge),
    R.drum = map(R.drum);
    s.sway.push_back(R);
  }
  s.gears.clear();
  for (auto g : m.gears)
    if (g.a != i && g.b != i && g.c != i) g.a = map(g.a), g.b = map(g.b), g.c = map(g.c), s.gears.push_back(g);
  s.trains.clear();
  for (auto T : m.trains)
    if (T.a != i && T.m != i && T.c != i) T.a = map(T.a), T.m = map(T.m), T.c = map(T.c), s.trains.push_back(T);
  return s;
}

double round_to(double x, int digits) {
  if (x == 0.0 || !std::isfinite(x)) return x;
  const double e = std::pow(10.0, digits - 1 - static_cast<int>(std::floor(std::log10(std::abs(x)))));
  return std::round(x * e) / e;
}

}  // namespace

RefModel shrink(const RefModel& m0, const std::string& integrator, Outcome::Kind kind, int budget) {
  RefModel best = m0;
  int trials = 0;
  auto still_fails = [&](const RefModel& c) {
    if (trials >= budget) return false;
    ++trials;
    const Outcome o = check(c, integrator);
    return o.kind == kind;
  };
  bool changed = true;
  while (changed && trials < budget) {
    changed = false;
    // Shorter run: just past the first difference.
    {
      const Outcome o = check(best, integrator);
      ++trials;
      if (o.t > 0 && o.t < 0.8 * best.t_end) {
        RefModel c = best;
        c.t_end = round_to(std::min(best.t_end, o.t * 1.25 + 0.01), 2);
        c.dt_out = c.t_end / 200;
        if (c.t_end < best.t_end && still_fails(c)) best = c, changed = true;
      }
    }
    for (size_t k = best.frictions.size(); k-- > 0;) {
      RefModel c = best;
      c.frictions.erase(c.frictions.begin() + static_cast<long>(k));
      if (still_fails(c)) best = c, changed = true;
    }
    for (size_t k = best.releases.size(); k-- > 0;) {
      RefModel c = best;
      c.releases.erase(c.releases.begin() + static_cast<long>(k));
      if (still_fails(c)) best = c, changed = true;
    }
    for (size_t k = best.loads.size(); k-- > 0;) {
      RefModel c = best;
      c.loads.erase(c.loads.begin() + static_cast<long>(k));
      if (still_fails(c)) best = c, changed = true;
    }
    for (size_t k = best.links.size(); k-- > 0;) {
      RefModel c = best;
      c.links.erase(c.links.begin() + static_cast<long>(k));
      if (still_fails(c)) best = c, changed = true;
    }
    for (size_t k = best.meshes.size(); k-- > 0;) {
      RefModel c = best;
      c.meshes.erase(c.meshes.begin() + static_cast<long>(k));
      if (still_fails(c)) best = c, changed = true;
    }
    for (int i = static_cast<int>(best.bodies.size()); i-- > 0 && best.bodies.size() > 1;) {
      RefModel c = without_body(best, i);
      if (still_fails(c)) best = c, changed = true;
    }
    // Round numbers, one element at a time, to 2 then 1 digits.
    for (int d = 2; d >= 1; --d) {
      for (size_t k = 0; k < best.bodies.size(); ++k) {
        RefModel c = best;
        auto& b = c.bodies[k];
        b.m = round_to(b.m, d), b.v0 = round_to(b.v0, d);
        if (b.m != best.bodies[k].m || b.v0 != best.bodies[k].v0)
          if (still_fails(c)) best = c, changed = true;
      }
      for (size_t k = 0; k < best.links.size(); ++k) {
        RefModel c = best;
        auto& L = c.links[k];
        L.c = round_to(L.c, d), L.d = round_to(L.d, d), L.gap = round_to(L.gap, d), L.gap_start = round_to(L.gap_start, d);
        L.flank = round_to(L.flank, d);
        if (L.gap_start > L.gap) L.gap_start = L.gap;
        if (still_fails(c)) best = c, changed = true;
      }
      for (size_t k = 0; k < best.loads.size(); ++k) {
        RefModel c = best;
        auto& s = c.loads[k].s;
        s.value = round_to(s.value, d), s.before = round_to(s.before, d), s.amplitude = round_to(s.amplitude, d);
        s.offset = round_to(s.offset, d);
        if (still_fails(c)) best = c, changed = true;
      }
      for (size_t k = 0; k < best.frictions.size(); ++k) {
        RefModel c = best;
        auto& f = c.frictions[k];
        f.Fs = round_to(f.Fs, d), f.Fk = std::min(f.Fs, round_to(f.Fk, d)), f.drag = round_to(f.drag, d);
        if (still_fails(c)) best = c, changed = true;
      }
    }
  }
  return best;
}

namespace {

/// A run's position (w = 0) or velocity (w = 1) of body i at output row k: the reference's, or an
/// engine run's column (NaN where it has none).
double state_of(const RefResult& r, size_t k, size_t i, int w) { return w == 0 ? r.q[k][i] : r.v[k][i]; }
double state_of(const RefModel& m, const SimulationResult& r, size_t k, size_t i, int w) {
  const bool rot = (m.rotational && !m.bodies[i].linear) || m.bodies[i].angular;
  const std::string name = m.bodies[i].name + (w == 0 ? (rot ? ".position_rad" : ".position_m") : (rot ? ".velocity_rad_s" : ".velocity_m_s"));
  for (size_t c = 0; c < r.column_names.size(); ++c)
    if (r.column_names[c] == name) return k < r.columns[c].size() ? r.columns[c][k] : std::nan("");
  return std::nan("");
}

/// The largest state difference of two runs of m over the rows, in units of the state tolerance.
template <class A, class B>
double largest_gap(const RefModel& m, const RefResult& ref, const A& a, const B& b) {
  const StateTolerances s = state_tolerances(m, ref);
  double worst = 0.0;
  for (size_t k = 0; k < ref.t.size(); ++k)
    for (size_t i = 0; i < m.bodies.size(); ++i)
      for (int w = 0; w < 2; ++w) {
        const double d = std::abs(a(k, i, w) - b(k, i, w)) / (w == 0 ? s.q[i] : s.v[i]);
        worst = std::isnan(d) ? HUGE_VAL : std::max(worst, d);
      }
  return worst;
}

}  // namespace

void converge(const std::string& family, std::uint64_t seed, std::uint64_t index) {
  const RefModel m = random_model(family, seed, index);
  RefOptions fine;
  fine.omega_h /= kTightStep;
  const RefResult ref = simulate_reference(m), ref4 = simulate_reference(m, fine);
  if (!ref.error.empty() || !ref4.error.empty()) {
    std::printf("reference error: %s %s\n", ref.error.c_str(), ref4.error.c_str());
    return;
  }
  auto R = [&](const RefResult& x) { return [&x](size_t k, size_t i, int w) { return state_of(x, k, i, w); }; };
  std::printf("largest state differences in units of the state tolerance (1 = the campaign's limit):\n");
  std::printf("  reference h against h/4: %.3g\n", largest_gap(m, ref, R(ref), R(ref4)));
  for (const char* w : {"dopri5", "bdf"}) {
    try {
      std::string y = to_yaml(m, w);
      const std::string loose = "rtol: 1e-10, atol: 1e-12", tight = "rtol: 1e-12, atol: 1e-14";
      const SimulationResult r = simulate(compile_model(parse_yaml_string(y, "random.yaml"), "random.yaml"));
      y.replace(y.find(loose), loose.size(), tight);
      const SimulationResult r2 = simulate(compile_model(parse_yaml_string(y, "random.yaml"), "random.yaml"));
      auto E = [&](const SimulationResult& x) { return [&x, &m](size_t k, size_t i, int c) { return state_of(m, x, k, i, c); }; };
      std::printf("  %s: rtol 1e-10 against the reference at h: %.3g; rtol 1e-12 against h/4: %.3g; rtol 1e-10 against 1e-12: %.3g\n", w,
                  largest_gap(m, ref, E(r), R(ref)), largest_gap(m, ref, E(r2), R(ref4)), largest_gap(m, ref, E(r), E(r2)));
      const Outcome o = compare_results(m, ref4, r2);
      std::printf("    rtol 1e-12 against h/4: %s %s\n", to_string(o.kind), o.detail.c_str());
    } catch (const std::exception& e) {
      std::printf("  %s: error: %s\n", w, e.what());
    }
  }
}

void show(const std::string& family, std::uint64_t seed, std::uint64_t index) {
  const RefModel m = random_model(family, seed, index);
  std::printf("%s", to_yaml(m, "dopri5").c_str());
  const RefResult ref = simulate_reference(m);
  std::printf("reference (%ld steps)%s%s:\n", ref.steps, ref.error.empty() ? "" : ", error: ", ref.error.c_str());
  const StateTolerances stol = state_tolerances(m, ref);
  const double tol_t = kEventTol * std::max(1.0, m.t_end);
  for (const auto& e : ref.events)
    std::printf("  %.15g %s %s (±%.3g)\n", e.t, e.kind.c_str(), e.element.c_str(), std::max(event_tolerance(e, stol, tol_t), e.window));
  if (std::isfinite(ref.ambiguous_from)) std::printf("  ambiguous from %.15g\n", ref.ambiguous_from);
  for (const char* w : {"dopri5", "bdf"}) {
    std::printf("%s:\n", w);
    try {
      Model model = compile_model(parse_yaml_string(to_yaml(m, w), "random.yaml"), "random.yaml");
      const SimulationResult r = simulate(model);
      for (const auto& e : r.hybrid.events) std::printf("  %.15g %s %s %s -> %s\n", e.t, e.kind.c_str(), e.element.c_str(), e.from.c_str(), e.to.c_str());
    } catch (const std::exception& e) {
      std::printf("  error: %s\n", e.what());
    }
    const Outcome o = compare(m, w, ref);
    std::printf("  outcome: %s %s\n", to_string(o.kind), o.detail.c_str());
    if (o.kind == Outcome::Kind::state_mismatch) {
      const Outcome t = unless_unresolved(m, ref, tightened(m, m, w));
      std::printf("  tightened (rtol 1e-12, the reference's step / %g): %s %s\n", kTightStep, to_string(t.kind), t.detail.c_str());
    }
  }
}

long run_campaign(const CampaignOptions& o) {
  const auto families = o.families.empty() ? all_families() : o.families;
  const std::vector<std::string> integrators = {"dopri5", "bdf"};
  struct Count {
    long models = 0, pass[2] = {0, 0}, fail[2] = {0, 0}, ref_error = 0, ambiguous = 0;
    long tight[2] = {0, 0};  // of the passes: after tightening both (a state mismatch that converged)
    long unresolved[2] = {0, 0};  // neither a pass nor a failure: beyond the reference's resolution
    std::map<std::string, long> kinds;
  };
  std::map<std::string, Count> counts;
  long failures = 0;
  const auto t0 = std::chrono::steady_clock::now();
  if (!o.out_dir.empty()) std::filesystem::create_directories(o.out_dir);
  for (long i = 0; i < o.models; ++i) {
    if (static_cast<long>(static_cast<size_t>(i) / families.size()) % o.shards != o.shard) continue;  // every family in every shard
    const std::string& fam = families[static_cast<size_t>(i) % families.size()];
    const auto index = static_cast<std::uint64_t>(i) / families.size();
    const RefModel m = random_model(fam, o.seed, index);
    if (o.verbose) std::printf("%s #%llu\n", fam.c_str(), static_cast<unsigned long long>(index)), std::fflush(stdout);
    const RefResult ref = simulate_reference(m);
    Count& c = counts[fam];
    ++c.models;
    if (!ref.error.empty()) {
      ++c.ref_error;
      if (o.verbose) std::printf("%s seed %llu #%llu: reference error: %s\n", fam.c_str(), static_cast<unsigned long long>(o.seed),
                                 static_cast<unsigned long long>(index), ref.error.c_str());
      continue;
    }
    if (std::isfinite(ref.ambiguous_from)) ++c.ambiguous;
    for (size_t w = 0; w < integrators.size(); ++w) {
      Outcome out = compare(m, integrators[w], ref);
      if (out.kind == Outcome::Kind::state_mismatch) {  // amplified, or wrong: tighten both (campaign.hpp)
        const Outcome tight = unless_unresolved(m, ref, tightened(m, m, integrators[w]));
        if (tight.kind == Outcome::Kind::reference_error) {  // beyond the reference's own resolution: not compared
          ++c.unresolved[w];
          std::printf("UNRESOLVED %s seed %llu #%llu %s: %s\n", fam.c_str(), static_cast<unsigned long long>(o.seed),
                      static_cast<unsigned long long>(index), integrators[w].c_str(), tight.detail.c_str());
          continue;
        }
        if (!tight.failed()) {
          ++c.pass[w], ++c.tight[w];
          if (o.verbose) std::printf("%s seed %llu #%llu %s: agrees tightened (%s)\n", fam.c_str(), static_cast<unsigned long long>(o.seed),
                                     static_cast<unsigned long long>(index), integrators[w].c_str(), out.detail.c_str());
          continue;
        }
        out.detail += "; tightened: " + std::string(to_string(tight.kind)) + " " + tight.detail;
      }
      if (!out.failed()) {
        ++c.pass[w];
        continue;
      }
      ++c.fail[w], ++failures;
      ++c.kinds[std::string(to_string(out.kind))];
      std::printf("FAIL %s seed %llu #%llu %s: %s: %s\n", fam.c_str(), static_cast<unsigned long long>(o.seed),
                  static_cast<unsigned long long>(index), integrators[w].c_str(), to_string(out.kind), out.detail.c_str());
      std::fflush(stdout);
      if (!o.out_dir.empty()) {
        const RefModel s = o.shrink ? shrink(m, integrators[w], out.kind) : m;
        const Outcome so = check(s, integrators[w]);
        char name[160];
        std::snprintf(name, sizeof name, "%s-seed%llu-%llu-%s.yaml", fam.c_str(), static_cast<unsigned long long>(o.seed),
                      static_cast<unsigned long long>(index), integrators[w].c_str());
        std::string header = "# " + std::string(to_string(so.kind)) + " on " + integrators[w] + ": " + so.detail + "\n";
        header += "# family " + fam + ", campaign seed " + std::to_string(o.seed) + ", model " + std::to_string(index) +
                  " (shrunk from " + std::to_string(m.bodies.size()) + " bodies, " + std::to_string(m.links.size() + m.frictions.size()) +
                  " elements); reproduce: machdyn simulate FILE, compare with the reference (tests/reference)\n";
        std::ofstream(std::filesystem::path(o.out_dir) / name) << to_yaml(s, integrators[w], header);
      }
    }
  }
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("\n%-16s %7s %10s %10s %10s %10s %9s %9s %11s %11s\n", "family", "models", "dopri5 ok", "dopri5 bad", "bdf ok", "bdf bad",
              "ambiguous", "ref error", "ok tightened", "unresolved");
  Count total;
  for (const auto& f : families) {
    const Count& c = counts[f];
    std::printf("%-16s %7ld %10ld %10ld %10ld %10ld %9ld %9ld %5ld / %-5ld %5ld / %-5ld\n", f.c_str(), c.models, c.pass[0], c.fail[0], c.pass[1],
                c.fail[1], c.ambiguous, c.ref_error, c.tight[0], c.tight[1], c.unresolved[0], c.unresolved[1]);
    total.models += c.models, total.pass[0] += c.pass[0], total.pass[1] += c.pass[1], total.fail[0] += c.fail[0];
    total.fail[1] += c.fail[1], total.ambiguous += c.ambiguous, total.ref_error += c.ref_error;
    total.tight[0] += c.tight[0], total.tight[1] += c.tight[1];
    total.unresolved[0] += c.unresolved[0], total.unresolved[1] += c.unresolved[1];
  }
  std::printf("%-16s %7ld %10ld %10ld %10ld %10ld %9ld %9ld %5ld / %-5ld %5ld / %-5ld\n", "total", total.models, total.pass[0], total.fail[0],
              total.pass[1], total.fail[1], total.ambiguous, total.ref_error, total.tight[0], total.tight[1], total.unresolved[0],
              total.unresolved[1]);
  std::printf("seed %llu, shard %ld/%ld, %.1f s\n", static_cast<unsigned long long>(o.seed), o.shard, o.shards, wall);
  return failures;
}

}  // namespace machdyn::reference
