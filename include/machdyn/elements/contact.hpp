#pragma once
/// @file
/// The law of a friction contact or brake (model/model.hpp FrictionContact), stated once and used
/// by the drive system, the mode decision, the outputs and linear models.
///
/// Sliding velocity u = v_a − v_b (v_b = w(t), the prescribed surface velocity, for the ground).
/// The friction load F acts on b with +F and on a with −F (N or N·m):
///   stuck   (u ≡ 0):  F = λ from the equations of motion, holds while |λ| ≤ F_s(t)
///   sliding (u ≠ 0):  F = s r(t) F_k0(|u|), s = ±1 the direction of the mode
/// F_s(t) = r(t) F_s0, r(t) = max(0, g s(t)) the application of a brake or clutch (its normal force
/// or its 0…1 application signal, model/model.hpp), 1 for a contact with constant levels. F_k0(|u|)
/// is a constant, a table over the sliding speed or the Stribeck law (model/model.hpp).
/// Events (≥ 0 while the mode holds): stuck: F_s + ε − λ and F_s + ε + λ; sliding: s u.
/// The stick rule's tolerance: ε = 1e-12 F_s0, a rounding allowance, so a load exactly at the limit
/// holds; the stick rule is exactly "both stuck events ≥ 0" (one limit, holding_limit). A contact
/// whose own limit event just fired (or was left negative by a decision) is judged strictly
/// (|λ| ≤ F_s): it does not hold.
/// A freewheel (lock = ±1) holds while lock·λ ≥ −F_d, has no upper limit, and slides only in its
/// free direction −lock with its drag as kinetic level. F_d = F_k0(0), its drag at zero speed, is the
/// static limit of its free direction: a backstop with drag at rest stays at rest until the push in
/// its free direction exceeds the drag (without it neither stuck nor overrunning would be consistent
/// there). Its stuck event is its hold rule, lock·λ + F_d + ε_h (ε_h the hold allowance, the
/// resolution of its load: elements/hold_allowance.hpp). An end stop (no drag: F_d = 0) is such a
/// lock to the ground that engages by position: while free its event is the distance to the stop.
/// A general row (model/model.hpp VelocityRow: a joint, or a contact on a planetary gear's member
/// without inertia) has u = Σ_j w_j v_j (− w(t) to the ground) and puts −w_j F on body j: the
/// same law with the unit row {a: +1, b: −1} as its special case. A joint (planetary gear, gear on
/// a housing) is a contact that is always stuck with no limit: it holds every λ, never slides and
/// has no events.
/// A kinematic contact (every body of its row has a prescribed motion, elements/prescribed_motion.hpp,
/// or is the ground) has u(t) given by the motions: it changes no acceleration. Sliding, its kinetic
/// force acts as above and the motion sources carry it (their force columns, the heat F u). At u = 0
/// its mode follows the motions (kinematic_mode): stuck while they keep u at 0 (u̇ = 0 within the
/// rounding), else sliding in the direction of u̇ (of u where u̇ vanishes). Stuck, its load is λ = 0:
/// the sources already hold every body of its row, so the contact carries no load of its own (the
/// least-norm share with a constraint of infinite weight, as the weighted split of the drive system
/// gives a joint the larger share). Its stuck events are u and −u: the motions leave rest (u stays
/// exactly 0 while they rest: its bodies' accelerations are the signals' exact 0).

#include <algorithm>
#include <cmath>

#include "machdyn/elements/hold_allowance.hpp"
#include "machdyn/elements/linear_model.hpp"
#include "machdyn/elements/modes.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

struct ContactLaw {
  /// An application r within this of 0 is 0 up to rounding (the band of FrictionContact::released,
  /// where the side is the slope's).
  static constexpr double kApplicationRounding = 1e-12;
  const FrictionContact* spec = nullptr;
  int a = 0, b = kGround;
  bool general = false;  ///< u from `row` (a joint or a rewritten contact), not v_a − v_b
  bool joint = false;    ///< always stuck, no limit (model/model.hpp FrictionContact::joint)
  bool grounded = true;  ///< b is the ground: u subtracts the surface velocity w(t)
  VelocityRow row;       ///< the row of u: `spec->row`, or {a: +1, b: −1}
  bool kinetic_table = false;  ///< F_k0 depends on |u| (a table or the Stribeck law)
  bool moving_surface = false, brake = false;
  bool applied = false;  ///< r(t) from a signal (brakes, clutches), else r ≡ 1
  int lock = 0;  ///< freewheel: +1 or −1, 0 otherwise (model/model.hpp)
  bool stop = false;  ///< a hard end stop: engages by position (model/model.hpp)
  double stop_position = 0.0, restitution = 0.0;
  double kinetic0 = 0.0, surface0 = 0.0;  ///< the constant kinetic level and ground velocity

  bool kinematic = false;  ///< every body of its row prescribed (or the ground): see the header
  /// A lock's hold allowance ε_h, N or N·m (elements/hold_allowance.hpp; of(c, m) forms it from the
  /// model's links and atol, the floor 1e-9 without a model).
  double hold_tol = 1e-9;

  static ContactLaw of(const FrictionContact& c);
  /// With `kinematic` from the motions of m's bodies and a lock's `hold_tol` from m's links and atol.
  static ContactLaw of(const FrictionContact& c, const Model& m);
  /// k of the hold allowance: Σ (c + d·1 s⁻¹) of m's links on c's bodies, each once (1/i² on a
  /// link's a side), N/m or N·m/rad (elements/hold_allowance.hpp).
  [[nodiscard]] static double hold_stiffness(const FrictionContact& c, const Model& m);
  /// The mode of a kinematic contact at a decision, from its sliding velocity u and acceleration u̇
  /// (`rounding`: the rounding of u̇): sliding in the direction of u̇ if |u̇| > rounding, else of u if
  /// u ≠ 0, else stuck.
  [[nodiscard]] static ContactMode kinematic_mode(double u, double du, double rounding) {
    if (std::abs(du) > rounding) return du > 0 ? ContactMode::slip_pos : ContactMode::slip_neg;
    if (u != 0.0) return u > 0 ? ContactMode::slip_pos : ContactMode::slip_neg;
    return ContactMode::stuck;
  }

  /// w(t): the velocity of b's side when b is the ground.
  [[nodiscard]] double surface_velocity(double t) const {
    return moving_surface ? spec->surface_velocity(t) : surface0;
  }
  [[nodiscard]] double surface_acceleration(double t) const {
    return moving_surface ? spec->surface_acceleration(t) : 0.0;
  }
  /// u = v_a − v_b.
  [[nodiscard]] double sliding_velocity(double t, const double* v) const {
    if (general) [[unlikely]] return dot(v) - (grounded ? surface_velocity(t) : 0.0);
    return v[a] - (b >= 0 ? v[b] : surface_velocity(t));
  }
  /// Σ_j w_j x_j over the row's bodies.
  [[nodiscard]] double dot(const double* x) const {
    double s = 0.0;
    for (int j = 0; j < row.terms; ++j) s += row.w[j] * x[row.body[j]];
    return s;
  }
  /// The sliding acceleration u̇ from the accelerations.
  [[nodiscard]] double sliding_acceleration(double t, const double* acc) const {
    if (general) [[unlikely]] return dot(acc) - (grounded ? surface_acceleration(t) : 0.0);
    return acc[a] - (b >= 0 ? acc[b] : surface_acceleration(t));
  }
  /// r(t): the application (1 for a contact with constant levels).
  [[nodiscard]] double scale(double t) const { return applied ? spec->scale(t) : 1.0; }
  /// F_s(t) = r(t) F_s0.
  [[nodiscard]] double static_limit(double t) const { return scale(t) * spec->static_limit; }
  /// The kinetic force s r(t) F_k0(s u) of sliding mode md (s = ±1): F_k0(|u|) where the mode holds
  /// (s u ≥ 0). Beyond it (an integrator's trial stage past the stop, s u < 0) the level is F_k0(0),
  /// not F_k0(|u|): read at |u| a table held beyond its last speed gave a stage overshooting through
  /// zero speed the level of the overshoot's mirror, the same as at its start, so BDF's corrector agreed
  /// with its predictor and stepped over the whole table (MslGaps.HeldKineticTableSlidesOnIntoTheTable).
  [[nodiscard]] double kinetic_force(ContactMode md, double t, double u) const {
    const double s = static_cast<double>(static_cast<int>(md));
    const double level = kinetic_table ? spec->kinetic_level(std::max(0.0, s * u)) : kinetic0;
    return s * scale(t) * level;
  }
  /// dF/du of sliding mode md: r(t) F_k0′(|u|), the slope of the table or Stribeck law (0 for a
  /// constant level).
  [[nodiscard]] double kinetic_slope(double t, double u) const;
  /// The steepest rising slope of the kinetic table, max dF_k0/d|u| ≥ 0 (a damper while sliding; 0
  /// for the Stribeck law, which falls from F_s0 to F_c).
  [[nodiscard]] double steepest_kinetic_slope() const;
  /// The stuck load a friction contact holds at t: F_s(t) with the rounding allowance 1e-12 F_s0, so
  /// a load exactly at the limit holds. The stick rule and the stuck events both read this one value.
  [[nodiscard]] double holding_limit(double t) const { return static_limit(t) + 1e-12 * spec->static_limit; }
  /// The stick rule: whether λ is within the static limit at t (strict: without the allowance).
  /// A freewheel holds while lock·λ ≥ −F_d (allowance ε_h = hold_tol, the resolution of λ).
  /// Not strict, it is exactly "both stuck events are ≥ 0" (events()): a contact the decision keeps
  /// stuck starts armed.
  [[nodiscard]] bool holds(double lambda, double t, bool strict) const {
    if (joint) return true;
    if (lock != 0) return strict ? lock * lambda >= -free_limit() : lock * lambda + free_limit() + hold_tol >= 0.0;
    const double F = std::abs(lambda);
    return strict ? F <= static_limit(t) : F <= holding_limit(t);
  }
  /// A freewheel's static limit in its free direction: its drag at zero speed F_k0(0), N or N·m (0
  /// without drag, and for an end stop).
  [[nodiscard]] double free_limit() const {
    if (stop) return 0.0;
    return kinetic_table ? spec->kinetic_level(0.0) : kinetic0;
  }
  /// Whether sliding mode md can exist at all (a freewheel slides in its free direction only).
  [[nodiscard]] bool can_slide(ContactMode md) const {
    if (joint) return false;
    return lock == 0 || static_cast<int>(md) == -lock;
  }
  /// How far the stuck load λ is beyond what holds, as a ratio (> 1: beyond; ∞ for a freewheel
  /// loaded against its lock): the mode decision releases the largest first.
  [[nodiscard]] double overload(double lambda, double t) const {
    if (joint) return 0.0;
    if (lock != 0) {
      const double Fd = free_limit();
      return lock * lambda >= -Fd ? 0.0 : Fd > 0.0 ? -lock * lambda / Fd : HUGE_VAL;
    }
    const double Fs = static_limit(t);
    return Fs > 0 ? std::abs(lambda) / Fs : HUGE_VAL;
  }
  /// The weight of this contact in the least-norm share of a redundantly locked load (√F_s0; 1 for
  /// a freewheel, which has no limit to share by; 1e3 for a joint, which carries any load: it takes
  /// the larger share of a load it locks together with contacts).
  [[nodiscard]] double share_weight() const {
    return joint ? 1e3 : lock != 0 ? 1.0 : std::sqrt(spec->static_limit);
  }
  /// An end stop's impact law: the velocity just after an impact at velocity v⁻, v⁺ = −e v⁻.
  [[nodiscard]] double rebound(double v_in) const { return -restitution * v_in; }
  /// How an impact ends: the body rebounds, rests (v⁺ = 0: e = 0), or its bounces accumulate.
  enum class Landing { rebound, rest, accumulation };
  /// The end of an impact with v⁺ under an acceleration `back` towards the stop (> 0: it comes
  /// back). Under a constant `back` the flights 2|v⁺|/back shrink by e each, so the bounces
  /// accumulate at t + 2|v⁺|/(back (1 − e)) (Zeno): they are taken as over (the body rests on the
  /// stop from this impact, `accumulation`) once that remaining time is below 1e-10·max(1, t) s, or
  /// the flight's apex height v⁺²/(2 back) below 1e-12 of the stop's position |x_s| — there the
  /// position, hence the stop's distance, no longer resolves the flight (a stop at 0.01 m: heights
  /// below its last bits of ~2e-18 m; the impacts then came 1e-9 s apart with no end).
  [[nodiscard]] Landing landing(double v_out, double back, double t) const {
    if (v_out == 0.0) return Landing::rest;
    if (!(back > 0.0)) return Landing::rebound;
    const double flight = 2.0 * std::abs(v_out) / back;
    const double remaining = restitution < 1.0 ? flight / (1.0 - restitution) : flight;
    const bool over = remaining <= 1e-10 * std::max(1.0, t) || 0.25 * std::abs(v_out) * flight <= 1e-12 * std::abs(stop_position);
    return over ? Landing::accumulation : Landing::rebound;
  }
  /// The time the bounces starting with v⁺ under `back` accumulate at, from the impact at t
  /// (constant `back`: t + 2|v⁺|/(back (1 − e))), s.
  [[nodiscard]] double accumulation_time(double v_out, double back, double t) const {
    return back > 0.0 && restitution < 1.0 ? t + 2.0 * std::abs(v_out) / (back * (1.0 - restitution)) : t;
  }
  /// The distance of an end stop's body from the stop, ≥ 0 while off it (q: the body's position).
  [[nodiscard]] double stop_distance(double q) const { return -lock * (q - stop_position); }
  /// The two event functions of mode md; λ is the stuck contact's load, u the sliding velocity (read
  /// while stuck by a kinematic contact only), q
  /// the position of body a (read by end stops only).
  void events(ContactMode md, double t, double lambda, double u, double q, double* ev) const {
    if (joint) {
      ev[0] = ev[1] = 1.0;
    } else if (stop && md != ContactMode::stuck) {
      ev[0] = stop_distance(q);  // reaches the stop
      ev[1] = 1.0;
    } else if (md == ContactMode::stuck && kinematic) {
      ev[0] = u;  // the motions leave rest (u: the sliding velocity, also while stuck)
      ev[1] = -u;
    } else if (md == ContactMode::stuck && lock != 0) {
      // The load turns against the lock: it overruns (a stop: the body leaves it). The event is the
      // hold rule, allowance included (the resolution of λ), so one held unloaded at λ = −1e-15
      // (beside a clutch that just broke away) starts armed and λ's noise never fires it.
      ev[0] = lock * lambda + free_limit() + hold_tol;
      ev[1] = 1.0;
    } else if (md == ContactMode::stuck) {
      const double Fs = holding_limit(t);  // the stick rule's own limit (holds)
      ev[0] = Fs - lambda;
      ev[1] = Fs + lambda;
    } else if (applied && (released(t) || scale(t) <= kApplicationRounding) && !closing(t)) {
      // Transmits nothing whatever u does: its mode is a label (released()). So also while r is 0 up
      // to rounding, where released() judges by the slope: just before a rising zero of r, the label
      // kept while released is relabelled by the application's breakpoint, not fired as a slide
      // against u (a sine normal force rising through 0: a `reversal` 1e-13 s before its zero, the
      // bodies' speeds jumped to u = 0, the energy books short by the jump).
      ev[0] = ev[1] = 1.0;
    } else {
      ev[0] = static_cast<double>(static_cast<int>(md)) * u;
      ev[1] = 1.0;
    }
  }
  /// A slide whose application r still acts (r > 0) but falls into its zero, 0 up to rounding: its
  /// release is the zero's breakpoint, and until then the slide's function s u holds (a step ending
  /// there reads it at the left limit, r ~ 1e-17: read as released, it hid a reversal 34 ms before
  /// in the same step — campaign `mixed` seed 7 #17, dopri5, a brake sliding against u).
  [[nodiscard]] bool closing(double t) const {
    return spec->scale(t) > 0.0 && spec->application_gain * spec->application.slope(t) < 0.0;
  }
  /// A brake or clutch whose application is 0 at t and does not rise just after is released (open):
  /// it acts with no force and has no slip phases. It is never stuck (no row of the stuck set: a
  /// limit of 0 holds no load, and stuck it took a share of the load its body's neighbours carry):
  /// its mode is the direction of its sliding velocity, a label with no events while it is released
  /// (decided again from u when it is applied).
  [[nodiscard]] bool released(double t) const { return applied && spec->released(t); }
  /// Adds the generalized forces of load F to f: −F on a, +F on b (a general row: −w_j F on body j).
  void apply(double F, double* f) const {
    if (general) [[unlikely]] {
      for (int j = 0; j < row.terms; ++j) f[row.body[j]] -= row.w[j] * F;
      return;
    }
    f[a] -= F;
    if (b >= 0) f[b] += F;
  }
  /// Linear terms in mode md at sliding velocity u: a stuck contact is a constraint row of G
  /// (u = 0), a sliding one adds its kinetic slope to D; `engaged` false adds nothing. A joint is a
  /// constraint row in every mode. A kinematic contact adds nothing (its bodies are fixed supports).
  void add_linear(ContactMode md, bool engaged, double t, double u, LinearModel& lin) const;
};

}  // namespace machdyn
