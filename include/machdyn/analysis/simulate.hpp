#pragma once
/// @file
/// Time simulation of a drive chain: the time series on the output grid, the peaks of every link
/// load located on the continuous solution, the quasi-static loads and dynamic factors.

#include <functional>
#include <string>
#include <vector>

#include "machdyn/analysis/hybrid_report.hpp"
#include "machdyn/analysis/sway_summary.hpp"
#include "machdyn/model/model.hpp"
#include "machdyn/solve/driver.hpp"
#include "machdyn/solve/stepper.hpp"

namespace machdyn {

/// Extremes of one link load over the run and its dynamic factor — the one definition used by the
/// CLI, the load-case table, the report, sweeps and JSON. `t_max`/`t_min` are located to ~1e-12
/// relative on the dense output (the load rate changes sign there), not only on output points.
/// Each extreme has its own quasi-static load: the particular solution (static_loads.hpp) for the
/// loads acting at its instant — the load of rigid acceleration; the elements held at that instant
/// (stuck brakes, clutches, stops, joints, lossy gears at rest) are its constraints, not forces
/// (docs/design.md). The peak is the extreme of larger
/// magnitude (the maximum on a tie), and
///   dynamic_factor = peak / static_load,  static_load = the quasi-static load at t_peak,
/// NaN when |static_load| ≤ 1e-9 |peak| (no quasi-static load to compare with) and for a buffer (its
/// reference is the rigid-body peak of φ7). An extreme below 1e-12 of the link's largest magnitude is 0.
struct LinkSummary {
  double max = 0.0, min = 0.0;      ///< N·m or N
  double t_max = 0.0, t_min = 0.0;  ///< s
  double static_at_max = 0.0, static_at_min = 0.0;  ///< quasi-static loads at t_max and t_min
  double peak = 0.0, t_peak = 0.0;  ///< the extreme of larger magnitude and its time
  double static_load = 0.0;         ///< quasi-static load at t_peak
  double dynamic_factor = 0.0;      ///< peak / static_load (NaN, see above)
};

/// Fills peak, t_peak, static_load and dynamic_factor of `s` from its extremes and their
/// quasi-static loads (the definition above).
void set_peak(LinkSummary& s);

/// For a machine body whose output point advances with q (the gear drive's travel X, model/
/// gear_drive.hpp): the uniformity of the point's speed V = p′(q) q' and of q' over the last whole
/// period P of q in the run (steady running once the run is long enough: compare `delta_previous`,
/// the same over the period before), and the velocity jumps of the run (stepwise gears).
///   V̄ = (p(q_end) − p(q_end − P))/(t_end − t_from), q(t_from) = q_end − P (sign of the motion)
///   δ = (V_max − V_min)/V̄ over [t_from, t_end], extremes over the dense solution (a few points per
///   step, and both sides of every jump, where the stepwise extremes are).
struct MachineRunReport {
  std::string body;
  std::string point;            ///< the output point's name ("travel"); empty: no point-speed report
  double period = 0.0;          ///< P, rad
  double periods_run = 0.0;     ///< (q_end − q_0)/P
  bool window = false;          ///< at least one whole period was run (the values below are set)
  double t_from = 0.0, t_to = 0.0;  ///< the window, s
  double v_mean = 0.0, v_max = 0.0, v_min = 0.0, delta = 0.0;  ///< point speed, m/s
  double delta_previous = -1.0;  ///< δ over the period before the window (−1 if fewer than 2 periods)
  double omega_mean = 0.0, omega_max = 0.0, omega_min = 0.0, omega_delta = 0.0;  ///< q', rad/s
  long jumps = 0;               ///< velocity jumps over the run
  double jump_loss = 0.0;       ///< kinetic energy lost in them, J
  long jumps_window = 0;        ///< jumps inside the window
  double jump_loss_window = 0.0;  ///< J, inside the window
};

struct SimulationResult {
  std::vector<std::string> column_names;      ///< "t_s", "I1.position_rad", ..., "c1.load_N_m"
  std::vector<std::vector<double>> columns;   ///< one series per name, on the output grid
  std::vector<LinkSummary> links;             ///< in Model::links order
  RunStats stats;
  std::string method_reason;                  ///< why this integrator (for `integrator: auto`)
  HybridReport hybrid;                        ///< events, slip phases, energy (models with gaps or friction)
  std::vector<MachineRunReport> machines;     ///< machines with velocity jumps or a point-speed report
  std::vector<SwaySummary> sway;              ///< per spatial rope, taken on the output grid during the run
};

/// The integrator `auto` picks, from O(n) Gershgorin bounds ρ_D ≥ |Re λ| of M⁻¹D and ω_K ≥ ω_max:
/// CVODE BDF when the fastest motion is damping-dominated (ρ_D ≥ ω_K) and ρ_D · t_end > 2e4 (an
/// explicit method would spend > 2e4 steps on stability alone), else dopri5. `reason` says which.
/// A rising kinetic friction table counts as a damper of its steepest slope dF_k/du.
Method choose_method(const Model& m, std::string* reason);

/// Where a running simulation is, for a progress display (the CLI draws a bar; the library only
/// reports). Wall time counts from the start of the integration.
struct SimulationProgress {
  double t = 0.0;        ///< simulated time reached, s
  double t_end = 0.0;    ///< s
  long steps = 0;        ///< accepted steps so far
  long events = 0;       ///< events located so far (gaps closing, stops, ...)
  double wall_s = 0.0;   ///< wall time since the start, s
  bool finished = false; ///< the last call, at t_end
};
using ProgressCallback = std::function<void(const SimulationProgress&)>;

/// Options of a run beyond the model's simulation settings.
struct SimulateOptions {
  /// Progress observer; called at most every `progress_interval_s` of wall time (checked every few
  /// steps, so it costs nothing measurable) and once at the end.
  ProgressCallback progress;
  double progress_interval_s = 0.1;
  /// Keep the energy books and the event report (HybridReport) for a model without gaps, contacts
  /// or brakes too, as every load case of a file runs (`--all-cases`, case sweeps, the report): the
  /// cases are then computed alike, with zero events. Models with them always keep the books.
  bool event_driven = false;
  /// false: no time series on the output grid (SimulationResult::columns stay empty, the names are
  /// set); the peaks, events, slip phases and energies are the same bytes. For callers that need
  /// only the summaries (sweeps).
  bool record_series = true;
  /// The link extremes (LinkSummary: max, min, their quasi-static loads, the peak) and the slip
  /// phases' link extremes over [extremes_from, t_end] only, s (0: the whole run). The crane's φ3
  /// case released during a hoisting run asks for the rope's minimum after the release.
  double extremes_from = 0.0;
  /// The invariant audit (analysis/audit.hpp, docs/hybrid.md): every step end, event and output row
  /// is checked against the documented laws (static limits, kinetic laws, freewheels, gaps, ropes,
  /// end stops, lossy gears' losses, the energy books, the event list against the mode columns);
  /// the first violation throws AuditError (a SolverError naming the element, the time, the values
  /// and the invariant). Also on when the environment has MACHDYN_CHECK=1 (the test suite sets it).
  /// Off, no observer exists: the run is the same instructions as without the audit.
  bool check = false;
  long max_events = 1'000'000;  ///< SolverError when exceeded
  int chatter_count = 50;       ///< switches of one element ...
  double chatter_window = 1e-6; ///< ... within this fraction of t_end (or of 1 s) mean chattering
};

/// Runs the model's simulation settings: the one entry point of the CLI, the Python module, the
/// report and sweeps. Every model runs through the one DriveSystem (analysis/drive_system.hpp) and
/// the one driver (solve/driver.hpp); a model without gaps, contacts, brakes or stepwise gears simply
/// has no event functions. Throws SolverError on numerical failure (naming the element and the
/// time), on chattering (the element, the time and the number of switches) and when no consistent
/// contact mode exists.
SimulationResult simulate(const Model& m);
SimulationResult simulate(const Model& m, const SimulateOptions& options);

}  // namespace machdyn
