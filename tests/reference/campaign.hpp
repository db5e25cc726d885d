#pragma once
/// @file
/// The engine against the reference simulator on one model, shrinking a failure, and the campaign
/// over many random models (issue 27). Used by the `machdyn_campaign` executable (make test, make
/// verify) and by tests/reference/reference_test.cpp.
///
/// Stated tolerances of a comparison (the reference's own error, measured against closed forms and
/// against itself at half the step, is below a tenth of them):
///   states: every body's position and velocity at every output row within δq, δv =
///           kStateTol·(the largest |value| of that column in the reference run) + 1e-9;
///   events: the same (element, kind) in the same order, each within the largest of
///           kEventTol·max(1, t_end) s, δg/|ġ| and the reference event's resolution window:
///           - δg/|ġ|: an event is a zero of a switching function g, and states within δx move
///             that zero by δg/|ġ| (RefEvent: dt_dq δq + dt_dv δv of its body). A comparison that
///             accepts the states must accept the event times they imply: a damped flank's opening
///             (g = c e + d δ̇) by (c δq + d δv)/|ġ|, a gear mesh reaching a flank by
///             (δq_a + i δq_b)/|Δ'|; the n-th bounce of a Zeno
///             series under e < 1 meets its stop at |ġ| = |v⁻| ∝ eⁿ, its instant conditioned like
///             1/eⁿ; the rest at the accumulation instant t∞ is known to
///             √(δq/(2a)) (1 + e)/(1 − e) + 2 e δv/(a (1 − e)) (bounces whose apex height is below
///             δq are rest at that tolerance), and an impact within that of the rest is not compared,
///             nor a reversal of a friction contact on the bouncing body there (each bounce's);
///           - the window (RefEvent::window): an event function known to δ (a load's:
///             kLoadResolution × the model's force scale) fixes a simple root to δ/|g'|, a root of
///             multiplicity k (g ≈ c (t − t₀)^k, a load growing from 0 through a chain of k/2
///             springs) only to (δ/c)^(1/k): the time over which g stays within δ of its value at the
///             root, so a steep root keeps kEventTol and a real shift of 1e-3 s is caught
///             (tests/reference/event_window_test.cpp);
///           - a slide's `stick` or `reversal` (u = v_a − v_b reaching 0): (δv_a + δv_b)/|u̇|;
///           kinds gap_closed, gap_opened, stick, slip, reversal, impact, applied, and a gear
///           mesh's `mesh` and `free play`;
///   not compared (on either side; the states are): a phase shorter than kEventTol·max(1, t_end)
///           (slip or applied → stick, stick → slip, slip → released, a gap opened → closed and
///           back): the instants are resolved only to that; such a phase of the reference shorter
///           than both its events' tolerances; an event within it of t = 0 (the
///           start's decision: the engine's initial modes, the reference's located a step later),
///           and a reference event whose tolerance reaches back to t = 0 with the engine's events
///           of that element up to its instant plus tolerance (a start from rest whose margin grows
///           from 0 within the loads' resolution: `gear` seed 2 #5);
///           a `reversal` of a brake's or clutch's slide whose tolerance reaches back to its
///           `applied` (u's sign at the application is fixed only to δv: applied the other way
///           without a reversal is the same motion within the states' tolerance), and the
///           engine's reversals of that element up to its instant plus tolerance; a `stick` and
///           the `slip` that ends it of a freewheel without drag whose load stays within
///           kLoadResolution × the largest stuck load at every row between them, in both runs (stuck with
///           λ = 0 and overrunning at u = 0 it exerts the same force, none, on the same velocities:
///           one motion, the mode a label that rounding picks — BDF's 1e-20 m/s off rest on a body
///           stuck contacts tie to the ground fired a backstop's overrun function, `mixed` seed 1
///           #52). Each such rule still catches an event moved by 1e-3 s
///           (tests/analysis/campaign_defects_e_test.cpp, campaign_defects_h_test.cpp);
/// A state mismatch is decided again with both tolerances tightened (`tightened`: the engine at
/// rtol 1e-12, atol 1e-14, the reference at a quarter of its step): a model whose trajectory
/// amplifies a perturbation — a rattle through backlash, where each contact multiplies a phase
/// error — carries the engine's error at rtol 1e-10 (bdf's ~50 times dopri5's) past kStateTol
/// while both runs follow the law. Such a difference shrinks with both tolerances (it is the two
/// runs' errors, amplified), a missed, extra or shifted event or a wrong law does not (the model
/// is another motion): the run agrees only if the tightened pair passes every rule above
/// (tests/analysis/campaign_defects_f_test.cpp: gap seed 4 #63 on bdf converges from 1.6 times
/// the state tolerance to 0.02; a load's step 1e-3 s late is still a mismatch).
/// A mismatch that persists tightened where the reference itself at h and at h/4 differs by more
/// than the state tolerance is beyond the reference's resolution (`unless_unresolved`, below).
/// Only the part of the run before the reference's `ambiguous_from` is compared. The states are
/// compared even where the events differ: a state mismatch is a wrong motion, an event mismatch with
/// every state agreeing ("states agree") a wrong event list.

#include <cstdint>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "reference/reference.hpp"

#include "machdyn/analysis/simulate.hpp"

namespace machdyn::reference {

constexpr double kEventTol = 1e-6;
constexpr double kStateTol = 1e-5;
constexpr double kTightStep = 4.0;  ///< the tightened reference's step: h / kTightStep

struct Outcome {
  enum class Kind { pass, engine_error, event_mismatch, state_mismatch, reference_error } kind = Kind::pass;
  std::string detail;  ///< what differs first (or the error)
  double t = 0.0;      ///< where, s
  [[nodiscard]] bool failed() const { return kind == Kind::engine_error || kind == Kind::event_mismatch || kind == Kind::state_mismatch; }
};
const char* to_string(Outcome::Kind k);

/// Runs the engine on to_yaml(m, integrator) and compares it with the reference result `ref`.
Outcome compare(const RefModel& m, const std::string& integrator, const RefResult& ref);

/// Compares an engine result `r` of m with the reference result `ref` (compare() after the run).
Outcome compare_results(const RefModel& m, const RefResult& ref, const SimulationResult& r);

/// δq, δv per body: kStateTol times the largest |value| of the column in `ref`, + 1e-9.
struct StateTolerances {
  std::vector<double> q, v;
};
StateTolerances state_tolerances(const RefModel& m, const RefResult& ref);

/// The time tolerance of reference event e: max(tol_t, dt_dq δq + dt_dsqrtq √δq + dt_dv δv of its body).
double event_tolerance(const RefEvent& e, const StateTolerances& s, double tol_t);

/// The engine on engine_model at rtol 1e-12 (atol 1e-14) against the reference of ref_model at a
/// step h/kTightStep, compared by the same rules (a state mismatch decided again; the campaign passes
/// ref_model = engine_model, a test a shifted engine_model).
Outcome tightened(const RefModel& ref_model, const RefModel& engine_model, const std::string& integrator);
/// The states' allowance for a time shift: the events are matched within their tolerances, and an
/// engine whose matched events lie up to δt from the reference's runs the same motion shifted by up
/// to δt — at row k a column then differs by its rate times δt, with δt the largest offset of the
/// events matched up to t_k (0 before the first, and in a run without events: there the states
/// alone decide), each offset taken up to the sharp events' tolerance 1e-6·max(1, t_end) s only (an
/// event accepted further off — a grazing closure, a resolution window — is an ill-conditioned
/// instant, not a shifted motion). That offset is what the integration's error does to a motion between repeated
/// events (an undamped load bouncing on its rope: its period depends on its amplitude, so the phase
/// error of the steps accumulates bounce by bounce; BDF at rtol 1e-10 3e-8 s after 0.45 s, L.z's
/// velocity 1.4 × kStateTol off — converging with the tolerances, 50× less at 1e-12); a real shift
/// (1e-3 s) is an event mismatch. Rate: the reference's velocity for a position, the largest
/// difference quotient of its velocity over the neighbouring rows for a velocity. (body: column
/// index, w: 0 position, 1 velocity; shifts: (reference time, |offset|) per matched event.)
double shift_allowance(const RefResult& ref, const std::vector<std::pair<double, double>>& shifts, std::size_t body, int w, std::size_t k);

/// The reference's own resolution of m's states: the largest difference of the reference at its
/// step h (`ref`) and at h/kTightStep (`ref4`) over every body's position and velocity at every output
/// row, in units of the state tolerance (1 = the campaign's limit). RK4's error falls 4⁴ = 256 times
/// from h to h/4, so this is the reference's own error at h to within 0.4 %.
double reference_spread(const RefModel& m, const RefResult& ref, const RefResult& ref4);

/// A state mismatch that persists tightened (`tight`, of m on one integrator), judged by what the
/// reference resolves: the comparison rests on the reference's own error being below a tenth of the
/// tolerances (above), and where the reference at h and at h/4 already differ by more than the state
/// tolerance (reference_spread > 1) neither run fixes the states to that tolerance — a model that
/// amplifies every perturbation (a series of impacts, each multiplying a phase error: `stop` seed 1
/// #75, its reference at h and h/4 1.8e4 tolerances apart) cannot be compared there, whatever the
/// engine does. Then the outcome is `reference_error` ("unresolved", not an agreement), else `tight`
/// unchanged: a model the reference resolves keeps every rule, and a motion shifted by 1e-3 s is
/// still a mismatch (CampaignDefectsH).
Outcome unless_unresolved(const RefModel& m, const RefResult& ref, const Outcome& tight);

/// Runs both on m (the reference once) and compares on `integrator`.
Outcome check(const RefModel& m, const std::string& integrator, const RefOptions& o = {});

/// Shrinks a failing model while it still fails on `integrator` with the same outcome kind: drops
/// elements and bodies, rounds numbers to 1–2 digits, shortens the run. At most `budget` trials.
RefModel shrink(const RefModel& m, const std::string& integrator, Outcome::Kind kind, int budget = 40);

struct CampaignOptions {
  long models = 300;
  std::uint64_t seed = 1;
  std::vector<std::string> families;  ///< empty: all_families()
  std::string out_dir;                ///< non-empty: write each failure (shrunk) there
  bool shrink = true;
  bool verbose = false;
  long shard = 0, shards = 1;         ///< run the models i with i % shards == shard (parallel ctest jobs)
};

/// Prints model `index` of `family` (campaign seed `seed`): its file, the reference's events and
/// each integrator's events and outcome (machdyn_campaign --show FAMILY:INDEX).
void show(const std::string& family, std::uint64_t seed, std::uint64_t index);

/// Checks whether a state mismatch of model `index` is an amplified difference of the two runs'
/// errors (machdyn_campaign --converge FAMILY:INDEX): prints the largest state differences, in units
/// of the state tolerance, of the reference at h against h/4, of the engine at rtol 1e-10 against the
/// reference at h and at rtol 1e-12 against h/4, and the comparison of the tight pair. An amplified
/// error shrinks with both tolerances; a missed or extra event does not.
void converge(const std::string& family, std::uint64_t seed, std::uint64_t index);

/// Runs the campaign (models spread round-robin over the families, both integrators), prints a
/// table per family and returns the number of failing (model, integrator) runs.
long run_campaign(const CampaignOptions& o);

}  // namespace machdyn::reference
