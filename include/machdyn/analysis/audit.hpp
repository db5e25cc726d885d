#pragma once
/// @file
/// The invariant audit of a run (SimulateOptions::check, `machdyn simulate --check`, Python
/// `check=True`, MACHDYN_CHECK=1): an observer of the one driver that checks the documented laws
/// (docs/hybrid.md, "The invariant audit") on the engine's own per-element values — at every
/// accepted step end in its mode, after every event and breakpoint, and at every output row — and
/// throws AuditError (a SolverError: exit 3) naming the element, the time, the values and the
/// invariant at the first violation. Never a silently wrong number.
///
/// The invariants (each written here from the law, not by calling the function that produced the
/// value; tolerances are roundings of the quantities compared, stated with each):
///   contact.static_limit     stuck friction contact, brake, clutch:  |λ| ≤ F_s(t) + 1e-12 F_s0
///                            (F_s = r(t) F_s0; the stick rule's own allowance, elements/contact.hpp)
///   contact.kinetic_law      sliding:  F = s r(t) F_k0(|u|)  to 1e-9 (r F_k0 + F_s0)
///   contact.sliding_direction sliding in s:  s u ≥ −(1e-12 S + 1e3 (atol + rtol S)), S = |v_a| + |v_b| + |w|
///                            (F then opposes u on body a: a's load is −F; 1e3 (atol + rtol S) the
///                            integrator's resolution of the speeds: its local tolerance, simulation.
///                            atol and rtol, accumulated over the steps — BDF's u on MSL OneWayClutch
///                            is 14 rtol S off its closed form, a tangency u = 0 reads +7.7e-10)
///   contact.kinematic_load   stuck between prescribed motions: λ = 0 (its bodies are held by them)
///   freewheel.hold           stuck freewheel or resting end stop:  lock·λ ≥ −F_d − ε_h (F_d = F_k0(0),
///                            a freewheel's drag at rest, the static limit of its free direction; 0 for
///                            an end stop; ε_h its hold rule's allowance, the resolution of λ,
///                            elements/hold_allowance.hpp); sliding only in its free
///                            direction −lock
///   stop.position            end stop:  −lock (q − q_stop) ≥ −(1e-12 max(1, |q_stop|) + atol + rtol |q|)
///   gap.flank_sign           closed on the positive flank F ≥ 0, on the negative one F ≤ 0, to
///                            1e-12 (|F_e| + |F_v|) + |F_e(e + r) − F_e(e)| + d r (the force of a
///                            deflection and rate within the integrator's resolution of δ,
///                            r = atol + rtol (|q_a/i| + |q_b|)) — a rope (one-sided link) never pushes
///   gap.inside               open:  beyond a flank by more than atol + rtol (|q_a/i| + |q_b|), the law's
///                            pressing force c e + d δ̇ does not press into it (the link passed its
///                            flank without closing), same rounding
///   lossy_gear.loss          loss power (X − Y) v_a ≥ −[1e-12 (|X| + |Y| + |F_a| + |F_b|) |v_a|
///                            + (|X| + |Y|) r_v]  (X, Y solved from the forces F_a, F_b on its bodies;
///                            r_v = atol + rtol |v_a| + 1e-6 × a prescribed side's speed scale: the
///                            integrated speed's error the engine itself takes as the signal,
///                            PrescribedMotionLaw::snapped_velocity)
///   energy.balance           W − (ΔT + ΔV + friction + damping + release + impact + released parts)
///                            ≤ tol · E_max + max(1e-9 J, 1e3 atol), E_max the largest of |W|, T, V and
///                            each loss so far, tol = max(1e-6, 1e3 rtol) (the books are quadrature
///                            states of the same integration; an error of the integrator is O(rtol) per
///                            unit energy, O(atol) J absolute, and accumulates over the steps, a lost
///                            or invented energy is O(1))
///   contact.locked_slide     a friction contact sliding at u = 0 exactly whose row the stuck friction
///                            contacts beside it lock (u ≡ 0): it is stuck (check_locked_slide)
///   events.mode_columns      the mode columns of every output row equal the modes the event list
///                            says (its last `to` before the row), for contacts and gap links
/// A released brake or clutch (application 0) has F_s = 0: it may carry nothing (1e-12 F_s0), and
/// its kept mode is no event (no direction check). In-mode checks (step ends, output rows) take the
/// time-dependent limits at the left limit t⁻ (the mode of the piece that ends there); the check after
/// an event or breakpoint takes them at t (the new modes hold from t on). The end of a piece that a
/// located event truncates is checked after the event's decision, not before (the event function
/// has just crossed 0 there, by the location bracket).

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "machdyn/analysis/hybrid_report.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/elements/contact.hpp"
#include "machdyn/elements/link.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

struct SimulationResult;
class DriveSystem;

/// A violated invariant of the audit: a SolverError (exit 3 from the CLI) whose message names the
/// invariant, the element, the time and the values.
class AuditError : public SolverError {
 public:
  AuditError(std::string element, double t, std::string invariant, const std::string& values);
  [[nodiscard]] const std::string& invariant() const { return invariant_; }
  [[nodiscard]] const std::string& values() const { return values_; }
  /// "invariant NAME violated by 'ELEMENT' at t = T s: VALUES".
  [[nodiscard]] const char* what() const noexcept override { return message_.c_str(); }

 private:
  std::string invariant_, values_, message_;
};

/// Whether the environment asks every run to be audited (MACHDYN_CHECK set and not "0" or empty).
bool audit_requested_by_environment();

namespace audit {

/// One contact's values as the engine has them at time t: its mode, its load F (λ while stuck),
/// its sliding velocity u and the speeds it is formed of (their magnitudes scale u's rounding).
struct ContactValues {
  ContactMode mode = ContactMode::stuck;
  double F = 0.0, u = 0.0;
  double speed_scale = 0.0;  ///< |v_a| + |v_b| + |w|
  double q = 0.0;            ///< the position of body a (end stops)
  /// The integrator's resolution of u and of q (its error control: atol + rtol |state|, SI): a
  /// direction or a side within it is within the solution's own accuracy.
  double resolution = 0.0, position_resolution = 0.0;
  /// A lock's hold allowance ε_h (elements/hold_allowance.hpp: the resolution of its λ), N or N·m.
  double hold_allowance = 1e-9;
};
/// Checks contact `law` named `name` at t (limits at t: the caller passes t⁻ in a mode).
void check_contact(const ContactLaw& law, const std::string& name, double t, const ContactValues& x);

/// contact.locked_slide: a friction contact labelled sliding (mode) with its sliding velocity u
/// exactly 0, whose velocity row `row` (over the bodies, size n) lies in the span of the rows
/// `stuck_rows` of the stuck friction contacts beside it (not freewheels, stops or joints): they hold
/// u ≡ 0, so it cannot slide — it is stuck, and the load it would carry stays locked up to the sum of
/// its and their limits (a contact released by a wrong share slid at u ≡ 0 with its kinetic force, and
/// its set broke away at F_s1 + F_k2 instead of F_s1 + F_s2). Exact (a rank test to 1e-9).
void check_locked_slide(const std::string& name, double t, ContactMode mode, double u,
                        const std::vector<std::vector<double>>& stuck_rows, const std::vector<double>& row);

/// One link's values: its mode, deflection δ, rate δ̇, load F and the drum position q_a (ropes).
struct LinkValues {
  GapMode mode = GapMode::open;
  double delta = 0.0, rate = 0.0, F = 0.0, qa = 0.0;
  double resolution = 0.0;  ///< of δ (and δ̇): atol + rtol (|q_a/i| + |q_b|)
};
/// Checks link `law` (with a gap or one-sided) named `name` at t.
void check_link(const LinkLaw& law, const std::string& name, double t, const LinkValues& x);

/// Checks a lossy gear's torques X, Y at body a's speed v_a: its loss power is never negative, to
/// 1e-12 (|X| + |Y| + |F_a| + |F_b|) |v_a| + (|X| + |Y|) atol — X and Y are solved from the forces
/// F_a, F_b on its two bodies (their rounding), and a speed within the integrator's resolution
/// `resolution` (atol) is rest.
void check_gear_loss(const std::string& name, double t, double X, double Y, double va, double force_scale = 0.0,
                     double resolution = 0.0);

/// The energy books at t: the source work and what it went into.
struct EnergyValues {
  double work = 0.0;                        ///< W
  double kinetic = 0.0, kinetic_start = 0.0;  ///< T(t), T(0)
  double elastic = 0.0, elastic_start = 0.0;  ///< V(t), V(0)
  double friction = 0.0, damping = 0.0;     ///< quadrature states
  double discrete = 0.0;                    ///< release, impact and released parts' kinetic, so far
  [[nodiscard]] double residual() const {
    return work - (kinetic - kinetic_start + elastic - elastic_start + friction + damping + discrete);
  }
};
/// Checks the balance at t to tol · E_max + abs_tol; `E_max` is the largest energy so far (updated).
void check_energy(double t, const EnergyValues& e, double tol, double& E_max, double abs_tol = 1e-9);

/// Checks that the mode columns of `r` (contacts `NAME.mode`, gap links `NAME.gap_mode`) agree with
/// its event list at every output row (a row at an event's time shows the modes before it).
void check_event_list(const Model& m, const SimulationResult& r);

}  // namespace audit

/// The audit of one run over its drive system (the observer DriveRun calls when SimulateOptions::
/// check is on; nothing exists when it is off). The driver's calls, in its order: `row` at each
/// output row, `piece_end` at the end of each piece in one mode, `after_event` after each event or
/// breakpoint, `settle` after each step and at the end. A check in a mode that fails at the instant
/// a located event then truncates the piece at is no violation (the event function has just crossed
/// 0 there, by the location bracket, and the event decides it): such a failure waits for the next
/// call and is thrown unless a located event follows within the location bracket after it
/// (2e-13 max(1, t) s: the driver's bracket is 1e-13 max(1, t)).
class Audit {
 public:
  /// `E` the run's energy books (their start values and the discrete losses as the run adds them),
  /// `release_loss` the gap-release loss so far.
  Audit(const Model& m, DriveSystem& sys, const EnergyBalance& E, const double& release_loss);
  /// An output row at t in the current modes (limits at t⁻).
  void row(double t, const double* y);
  /// The end tb of a piece in the current modes; `step_end`: tb is the step's end (y its state).
  void piece_end(double tb, bool step_end, const double* y);
  /// After the modes at t were decided (`located`: an event; else a breakpoint or the start).
  void after_event(double t, const double* y, bool located);
  /// Throws a waiting failure (after a step, and at the end of the run).
  void settle();

 private:
  void in_mode(double t, const double* y);
  void check(double t_law, double t, const double* y);
  void check_at(double t, const double* y);
  const Model& m_;
  DriveSystem& sys_;
  const EnergyBalance& E_;
  const double& release_loss_;
  std::vector<double> fc_;
  std::vector<double> hold_;  // each contact's hold allowance (locks), from the model's links and atol
  double tol_E_ = 0.0, abs_E_ = 1e-9, E_max_ = 0.0;
  std::unique_ptr<AuditError> pending_;  // the earliest failure in a mode, until it is settled
};

}  // namespace machdyn
