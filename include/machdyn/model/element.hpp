#pragma once
/// @file
/// An element with continuous states of its own acting on one body (section `drives:`; model/model.hpp
/// `Drive`): a DC motor, a speed-controlled drive, an eddy-current brake with its temperature. The one
/// interface through which every consumer reads such an element — the drive system's right-hand
/// side, Jacobian and event functions, the run's mode decisions and outputs, quasi-static loads, the
/// integrator choice and the linear model — so that a new type adds its own file (its law, stated
/// once, as a subclass), its compile function with its registration (src/model/element_types.hpp), its
/// docs row and its test, and no consumer changes.
///
/// The element sees its body through ω (its velocity, rad/s or m/s) and, where its law needs it, ω'
/// (its acceleration); its states x (states() of them) follow [q; v] in the drive system's state.
/// M is the torque (N·m) or force (N) it puts on the body, positive along +q.
///
/// Modes: an int per element, 0 its smooth default; an element with modes switches between them at
/// its events. Two event functions per element, each ≥ 0 while the mode holds (1, 1 without events).
/// Links and contacts are not elements of this kind: their laws stay concrete on the hot path.
/// The interface is in the model layer (the Model holds the elements, as it holds machines:
/// model/machine.hpp); each type's law is a subclass under elements/.

#include <memory>
#include <string>
#include <vector>

#include "machdyn/model/model.hpp"

namespace machdyn {

struct LinearModel;  // elements/linear_model.hpp

/// The Jacobian terms of an element with up to kMax states: its torque M and its state rates x'
/// against the body's velocity ω and the states.
struct ElementJacobian {
  static constexpr int kMax = 4;
  double dM_domega = 0.0;
  double dM_dx[kMax] = {};
  double dx_domega[kMax] = {};
  double dx_dx[kMax][kMax] = {};
};

class Element {
 public:
  virtual ~Element() = default;

  /// Its `type:` under `drives:` (the registered name).
  [[nodiscard]] virtual const char* type() const = 0;
  /// The number of its states (≤ ElementJacobian::kMax).
  [[nodiscard]] virtual int states() const = 0;
  /// x at t = 0.
  virtual void initial_states(double* x) const = 0;

  // ---- the law ----
  /// M on the body at time t, velocity ω, states x, in `mode`.
  [[nodiscard]] virtual double torque(double t, double omega, const double* x, int mode) const = 0;
  /// The state rates x' into dx. omega_dot: the body's acceleration ω' (read only where
  /// reads_acceleration(mode); else 0).
  virtual void rates(double t, double omega, const double* x, int mode, double* dx, double omega_dot) const = 0;
  /// ∂M/∂(ω, x) and ∂x'/∂(ω, x) at (t, ω, x) in `mode`.
  [[nodiscard]] virtual ElementJacobian jacobian(double t, double omega, const double* x, int mode) const = 0;
  /// Whether it turns energy into heat (then it is one of the `heat` outputs' elements with its heat
  /// NAME.heat_J, and its heat_power is in the model's total heat: analysis/heat.hpp).
  [[nodiscard]] virtual bool dissipates() const { return false; }
  /// The heat power inside the element, W (≥ 0): the part of −M ω it turns into heat (a brake), or
  /// the loss of its own circuit (a DC motor's R i²); 0 for an ideal source. The energy books count it
  /// as a loss and its source work as M ω + heat_power (the work its supply delivers into the
  /// mechanics and the heat), so their dissipated energy is the total of the heat outputs.
  [[nodiscard]] virtual double heat_power(double /*t*/, double /*omega*/, const double* /*x*/, int /*mode*/) const {
    return 0.0;
  }

  // ---- modes and events ----
  /// Whether it has event functions at all (then the run decides its mode).
  [[nodiscard]] virtual bool has_events() const { return false; }
  /// Its two event functions in `mode` into g[0], g[1].
  virtual void events(double /*t*/, double /*omega*/, const double* /*x*/, int /*mode*/, double /*omega_dot*/,
                      double* g) const {
    g[0] = g[1] = 1.0;
  }
  /// Whether its law or event functions in `mode` read the body's acceleration ω'.
  [[nodiscard]] virtual bool reads_acceleration(int /*mode*/) const { return false; }
  /// The mode after event function `slot` (0 or 1) of `mode` crossed zero.
  [[nodiscard]] virtual int mode_after(int mode, int /*slot*/) const { return mode; }
  /// Whether a switch old → now must be settled by settle() (it reads ω').
  [[nodiscard]] virtual bool settles(int /*old*/, int /*now*/) const { return false; }
  /// The mode a switch old → now lands in (settles() only).
  [[nodiscard]] virtual int settle(double /*t*/, double /*omega*/, int /*old*/, int now, double /*omega_dot*/) const {
    return now;
  }
  /// After a switch old → now made on its switching surface (`located`: one of its own event functions
  /// crossed 0; else a switch its natural_mode() found): puts its states x exactly on that surface, on
  /// the side of mode `now`, so that the new mode's event functions start ≥ 0 — there the function is 0
  /// only up to an error (rounding, or the drift of an invariant the mode integrates), and a function
  /// negative at a restart would be decided again (docs/hybrid.md, "The restart rule"). A switch off
  /// the surface (a jump of a signal at a breakpoint) changes nothing. Default: nothing to put.
  virtual void on_switch(double /*t*/, double /*omega*/, double* /*x*/, int /*old*/, int /*now*/,
                         bool /*located*/) const {}
  /// The mode its state implies on its own (initial state, after a time event); `current` its mode.
  [[nodiscard]] virtual int natural_mode(double /*t*/, double /*omega*/, const double* /*x*/, int current,
                                         double /*omega_dot*/) const {
    return current;
  }
  /// The name of a mode (event records, JSON).
  [[nodiscard]] virtual const char* mode_name(int /*mode*/) const { return "linear"; }
  /// The kind of a switch to `now` in the event records ("limited", "unlimited", …).
  [[nodiscard]] virtual const char* switch_kind(int /*now*/) const { return "switch"; }

  // ---- linear model and integrator choice ----
  /// Its terms of the linear model in `mode` on body `body` (elements/linear_model.hpp).
  virtual void add_linear(int /*body*/, int /*mode*/, LinearModel& /*lin*/) const {}
  /// The fastest rate of its own states, 1/s (for the integrator choice).
  [[nodiscard]] virtual double rate_bound() const { return 0.0; }

  // ---- names, outputs, description ----
  /// What state j is, for messages: "current", "temperature".
  [[nodiscard]] virtual const char* state_name(int j) const = 0;
  /// What state j is measured in: "A", "K", or the body's load unit.
  [[nodiscard]] virtual std::string state_unit(int j, BodyKind body_kind) const = 0;
  /// Its columns in the time series after NAME.torque_UNIT, as suffixes ("current_A", "mode").
  [[nodiscard]] virtual std::vector<std::string> output_names(BodyKind body_kind) const = 0;
  /// Their values at (t, ω, x) in `mode`, in that order.
  virtual void outputs(double t, double omega, const double* x, int mode, double* out) const = 0;
  /// Its parameters in words, for the model report ("R = 0.5 ohm, …").
  [[nodiscard]] virtual std::string describe(BodyKind body_kind) const = 0;
  /// Times in (t0, t1) where a signal it reads jumps or has a kink, and how many (without listing).
  [[nodiscard]] virtual std::vector<double> breakpoints(double /*t0*/, double /*t1*/) const { return {}; }
  [[nodiscard]] virtual double breakpoint_count(double /*t0*/, double /*t1*/) const { return 0.0; }

  // ---- load cases ----
  /// A copy for a run that starts in steady motion at speed v (the crane's φ2 case starts the hoist
  /// at its hoisting speed): a speed drive then holds v as its reference. Null: unchanged.
  [[nodiscard]] virtual std::shared_ptr<const Element> at_steady_speed(double /*v*/) const { return nullptr; }
};

}  // namespace machdyn
