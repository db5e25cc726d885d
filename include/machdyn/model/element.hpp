#pragma once
/// @file
/// An element behind the one interface (model/model.hpp `Drive`, `Model::drives`): a law with,
/// where it needs them, continuous states of its own, acting on one body or between two — a DC
/// motor, a speed-controlled drive, an eddy-current brake with its temperature (section `drives:`,
/// one body), an elastic gear mesh (section `links:`, two bodies). Every consumer reads such an
/// element only through this interface — the drive system's right-hand side, Jacobian and event
/// functions, the run's mode decisions and outputs, quasi-static loads, the energy books, the
/// integrator choice, the linear model, the report and Python — so that a new type adds its own
/// file (its law, stated once, as a subclass), its compile function with its registration
/// (src/model/element_types.hpp), its docs row and its test, and no consumer changes.
///
/// Bodies: the element acts on bodies() = 1 … ElementMotion::kMax bodies (its ports p = 0, 1, …;
/// Drive::at maps them to the model's bodies). It sees each through its position q_p, velocity v_p and, where its law
/// needs it, acceleration a_p (ElementMotion; rad, rad/s, rad/s² or m, m/s, m/s²) and puts the
/// torque or force M_p (N·m or N, positive along +q_p) on it. Its states x (states() of them)
/// follow [q; v] in the drive system's state.
///
/// Power: with P_b = Σ_p M_p v_p the power it puts into its bodies,
///   P_b = P_source − P_stored − P_heat,
/// P_source the power its supply delivers (a motor's electric input net of its inductance's
/// stored energy; 0 for a passive element), P_stored = dV/dt the rate of the mechanical energy V it
/// stores (a mesh's spring: energy()), P_heat ≥ 0 the power it turns into heat (heat_power). The
/// energy books count V with the elastic energy, P_heat as a loss and P_b + P_heat + P_stored as
/// source work; the conformance test (tests/model/element_conformance_test.cpp) checks the balance.
///
/// Modes: an int per element, 0 its smooth default; an element with modes switches between them at
/// its events. Two event functions per element, each ≥ 0 while the mode holds (1, 1 without events).
/// Links and contacts are not elements of this kind: their laws stay concrete on the hot path.
/// The interface is in the model layer (the Model holds the elements, as it holds machines:
/// model/machine.hpp); each type's law is a subclass under elements/. An element on one body may
/// state its law through OneBodyElement (below), in its body's velocity ω alone.

#include <memory>
#include <string>
#include <vector>

#include "machdyn/model/model.hpp"

namespace machdyn {

struct LinearModel;  // elements/linear_model.hpp

/// What an element sees of its bodies: per port p < n its position q[p], velocity v[p] and
/// acceleration a[p] (a: filled only where the element reads_acceleration(mode); else 0).
struct ElementMotion {
  static constexpr int kMax = 8;  ///< a spatial rope: 3 load coordinates and 5 suspension bodies
  int n = 1;
  double q[kMax] = {};
  double v[kMax] = {};
  double a[kMax] = {};
  /// Per port held by the element (held_port(mode)), the force on its body from everything else
  /// (N·m or N): in forces() the free forces, before the stuck set's loads; in events(), settle()
  /// and natural_mode() with them (I a − M_p). 0 on every other port.
  double load[kMax] = {};
};

/// The Jacobian terms of an element with up to kMax states on up to ElementMotion::kMax bodies:
/// its forces M_p and its state rates x' against its bodies' positions q_r, velocities v_r and its
/// states x_k.
struct ElementJacobian {
  static constexpr int kMax = 4;
  static constexpr int kBodies = ElementMotion::kMax;
  double dM_dq[kBodies][kBodies] = {};
  double dM_dv[kBodies][kBodies] = {};
  double dM_dx[kBodies][kMax] = {};
  double dx_dq[kMax][kBodies] = {};
  double dx_dv[kMax][kBodies] = {};
  double dx_dx[kMax][kMax] = {};
};

class Element {
 public:
  virtual ~Element() = default;

  /// Its `type:` (the registered name).
  [[nodiscard]] virtual const char* type() const = 0;
  /// The number of bodies it acts on, 1 … ElementMotion::kMax.
  [[nodiscard]] virtual int bodies() const { return 1; }
  /// The number of its states (≤ ElementJacobian::kMax).
  [[nodiscard]] virtual int states() const = 0;
  /// x at t = 0.
  virtual void initial_states(double* x) const = 0;

  // ---- the law ----
  /// M_p on each of its bodies into M[0 .. bodies()) at time t, motion b, states x, in `mode`.
  virtual void forces(double t, const ElementMotion& b, const double* x, int mode, double* M) const = 0;
  /// The state rates x' into dx (b.a read only where reads_acceleration(mode)).
  virtual void rates(double t, const ElementMotion& b, const double* x, int mode, double* dx) const = 0;
  /// ∂M/∂(q, v, x) and ∂x'/∂(q, v, x) at (t, b, x) in `mode`.
  [[nodiscard]] virtual ElementJacobian jacobian(double t, const ElementMotion& b, const double* x, int mode) const = 0;
  /// Whether its law reads its bodies' positions q (then the Jacobian's pattern has its q terms).
  [[nodiscard]] virtual bool reads_positions() const { return false; }

  // ---- power (the balance in the file comment) ----
  /// Whether it turns energy into heat (then it is one of the `heat` outputs' elements with its heat
  /// NAME.heat_J, and its heat_power is in the model's total heat: analysis/heat.hpp).
  [[nodiscard]] virtual bool dissipates() const { return false; }
  /// P_heat, W (≥ 0): the power it turns into heat (a brake's −M ω, a motor's R i², a mesh's damping
  /// and efficiency loss).
  [[nodiscard]] virtual double heat_power(double /*t*/, const ElementMotion& /*b*/, const double* /*x*/,
                                          int /*mode*/) const {
    return 0.0;
  }
  /// P_source, W: the power its supply delivers into the bodies, the heat and its stored energy.
  [[nodiscard]] virtual double source_power(double t, const ElementMotion& b, const double* x, int mode) const = 0;
  /// Whether it stores mechanical energy V (energy(), stored_power()).
  [[nodiscard]] virtual bool has_energy() const { return false; }
  /// V, J, the energy it stores in mode `mode` (a spring's ½ c δ²); 0 without.
  [[nodiscard]] virtual double energy(const ElementMotion& /*b*/, const double* /*x*/, int /*mode*/) const {
    return 0.0;
  }
  /// P_stored = dV/dt, W, along the motion b (and the state rates).
  [[nodiscard]] virtual double stored_power(double /*t*/, const ElementMotion& /*b*/, const double* /*x*/,
                                            int /*mode*/) const {
    return 0.0;
  }

  // ---- modes and events ----
  /// Whether it has event functions at all (then the run decides its mode).
  [[nodiscard]] virtual bool has_events() const { return false; }
  /// Its two event functions in `mode` into g[0], g[1] (b.a read only where reads_acceleration).
  virtual void events(double /*t*/, const ElementMotion& /*b*/, const double* /*x*/, int /*mode*/, double* g) const {
    g[0] = g[1] = 1.0;
  }
  /// Whether its law or event functions in `mode` read its bodies' accelerations.
  [[nodiscard]] virtual bool reads_acceleration(int /*mode*/) const { return false; }
  /// The mode after event function `slot` (0 or 1) of `mode` crossed zero.
  [[nodiscard]] virtual int mode_after(int mode, int /*slot*/) const { return mode; }
  /// Whether a switch old → now must be settled by settle() (it reads the accelerations).
  [[nodiscard]] virtual bool settles(int /*old*/, int /*now*/) const { return false; }
  /// The mode a switch old → now lands in (settles() only).
  [[nodiscard]] virtual int settle(double /*t*/, const ElementMotion& /*b*/, const double* /*x*/, int /*old*/,
                                   int now) const {
    return now;
  }
  /// After a switch old → now made on its switching surface (`located`: one of its own event functions
  /// crossed 0; else a switch its natural_mode() found): puts its states x exactly on that surface, on
  /// the side of mode `now`, so that the new mode's event functions start ≥ 0 — there the function is 0
  /// only up to an error (rounding, or the drift of an invariant the mode integrates), and a function
  /// negative at a restart would be decided again (docs/hybrid.md, "The restart rule"). A switch off
  /// the surface (a jump of a signal at a breakpoint) changes nothing. Default: nothing to put.
  virtual void on_switch(double /*t*/, const ElementMotion& /*b*/, double* /*x*/, int /*old*/, int /*now*/,
                         bool /*located*/) const {}
  /// The mode its state implies on its own (initial state, after a time event); `current` its mode.
  [[nodiscard]] virtual int natural_mode(double /*t*/, const ElementMotion& /*b*/, const double* /*x*/,
                                         int current) const {
    return current;
  }
  /// The port whose body the element holds at rest in `mode`, or −1 (a gear mesh's body at rest on
  /// a lossy flank, elements/gear_mesh.hpp). Its force M_p there is its law's function of the body's
  /// other forces, ElementMotion::load (the drive system supplies them after every other force and
  /// before the stuck set's loads, which carry what the element does not); the run puts that body's
  /// velocity at exactly 0 when the element switches into such a mode. Only a port on one body.
  [[nodiscard]] virtual int held_port(int /*mode*/) const { return -1; }
  /// The name of a mode (event records, JSON).
  [[nodiscard]] virtual const char* mode_name(int /*mode*/) const { return "linear"; }
  /// The kind of a switch to `now` in the event records ("limited", "unlimited", …).
  [[nodiscard]] virtual const char* switch_kind(int /*now*/) const { return "switch"; }

  // ---- linear model and integrator choice ----
  /// Its terms of the linear model in `mode`, its port p at coordinate body[p] of `lin`
  /// (elements/linear_model.hpp).
  virtual void add_linear(const int* /*body*/, int /*mode*/, LinearModel& /*lin*/) const {}
  /// The same about the configuration b (positions; velocities and accelerations 0) and states x,
  /// for an element whose linear terms depend on where it is (a spatial rope's geometric stiffness):
  /// by default add_linear() above.
  virtual void add_linear_at(const int* body, const ElementMotion& /*b*/, const double* /*x*/, int mode,
                             LinearModel& lin) const {
    add_linear(body, mode, lin);
  }
  /// The fastest rate of its own states, 1/s (for the integrator choice).
  [[nodiscard]] virtual double rate_bound() const { return 0.0; }

  // ---- names, outputs, description ----
  /// What state j is, for messages: "current", "temperature".
  [[nodiscard]] virtual const char* state_name(int j) const = 0;
  /// What state j is measured in: "A", "K", or the body's load unit.
  [[nodiscard]] virtual std::string state_unit(int j, BodyKind body_kind) const = 0;
  /// Its columns in the time series after NAME.torque_UNIT (M_0, on its first body), as suffixes
  /// ("current_A", "mode"); body_kind: its first body's.
  [[nodiscard]] virtual std::vector<std::string> output_names(BodyKind body_kind) const = 0;
  /// Their values at (t, b, x) in `mode`, in that order.
  virtual void outputs(double t, const ElementMotion& b, const double* x, int mode, double* out) const = 0;
  /// Its parameters in words, for the model report ("R = 0.5 ohm, …").
  [[nodiscard]] virtual std::string describe(BodyKind body_kind) const = 0;
  /// Times in (t0, t1) where a signal it reads jumps or has a kink, and how many (without listing).
  [[nodiscard]] virtual std::vector<double> breakpoints(double /*t0*/, double /*t1*/) const { return {}; }
  [[nodiscard]] virtual double breakpoint_count(double /*t0*/, double /*t1*/) const { return 0.0; }

  // ---- the invariant audit (analysis/audit.hpp) ----
  /// Checks the invariants of its law at (t, b, x) in `mode` against the forces M and the heat power
  /// the engine has from it, written from its parameters (a force that must vanish in a region, a
  /// loss that is never negative); `resolution` is that of its bodies' positions and velocities (the
  /// integrator's). Returns "" or "INVARIANT|VALUES" (reported as an AuditError).
  [[nodiscard]] virtual std::string violated(double /*t*/, const ElementMotion& /*b*/, const double* /*x*/,
                                             int /*mode*/, const double* /*M*/, double /*heat*/,
                                             double /*resolution*/) const {
    return {};
  }

  // ---- load cases ----
  /// A copy for a run that starts in steady motion at speed v (the crane's φ2 case starts the hoist
  /// at its hoisting speed): a speed drive then holds v as its reference. Null: unchanged.
  [[nodiscard]] virtual std::shared_ptr<const Element> at_steady_speed(double /*v*/) const { return nullptr; }
};

/// The Jacobian terms of an element on one body: its torque M and its state rates x' against the
/// body's velocity ω and the states.
struct OneBodyJacobian {
  static constexpr int kMax = ElementJacobian::kMax;
  double dM_domega = 0.0;
  double dM_dx[kMax] = {};
  double dx_domega[kMax] = {};
  double dx_dx[kMax][kMax] = {};
};

/// An element on one body whose law reads only the body's velocity ω (and its acceleration ω'
/// where reads_acceleration): it states the law in (ω, ω'), and the interface above is that law
/// with ω = b.v[0], ω' = b.a[0], M_0 = torque(), no stored mechanical energy.
class OneBodyElement : public Element {
 public:
  /// M on the body at time t, velocity ω, states x, in `mode`.
  [[nodiscard]] virtual double torque(double t, double omega, const double* x, int mode) const = 0;
  /// The state rates x' into dx; omega_dot the body's acceleration (where reads_acceleration(mode)).
  virtual void rates(double t, double omega, const double* x, int mode, double* dx, double omega_dot) const = 0;
  /// ∂M/∂(ω, x) and ∂x'/∂(ω, x).
  [[nodiscard]] virtual OneBodyJacobian jacobian(double t, double omega, const double* x, int mode) const = 0;
  /// P_heat at (t, ω, x).
  [[nodiscard]] virtual double heat_power(double /*t*/, double /*omega*/, const double* /*x*/, int /*mode*/) const {
    return 0.0;
  }
  /// P_source at (t, ω, x) (its own statement: the balance P_b = P_source − P_heat is checked).
  [[nodiscard]] virtual double source_power(double t, double omega, const double* x, int mode) const = 0;
  virtual void events(double /*t*/, double /*omega*/, const double* /*x*/, int /*mode*/, double /*omega_dot*/,
                      double* g) const {
    g[0] = g[1] = 1.0;
  }
  [[nodiscard]] virtual int settle(double /*t*/, double /*omega*/, int /*old*/, int now, double /*omega_dot*/) const {
    return now;
  }
  virtual void on_switch(double /*t*/, double /*omega*/, double* /*x*/, int /*old*/, int /*now*/, bool /*located*/) const {}
  [[nodiscard]] virtual int natural_mode(double /*t*/, double /*omega*/, const double* /*x*/, int current,
                                         double /*omega_dot*/) const {
    return current;
  }
  /// Its terms of the linear model on coordinate `body`.
  virtual void add_linear(int /*body*/, int /*mode*/, LinearModel& /*lin*/) const {}
  virtual void outputs(double t, double omega, const double* x, int mode, double* out) const = 0;

  // ---- the interface, in terms of the law above ----
  void forces(double t, const ElementMotion& b, const double* x, int mode, double* M) const final {
    M[0] = torque(t, b.v[0], x, mode);
  }
  void rates(double t, const ElementMotion& b, const double* x, int mode, double* dx) const final {
    rates(t, b.v[0], x, mode, dx, b.a[0]);
  }
  [[nodiscard]] ElementJacobian jacobian(double t, const ElementMotion& b, const double* x, int mode) const final {
    const OneBodyJacobian o = jacobian(t, b.v[0], x, mode);
    ElementJacobian j;
    j.dM_dv[0][0] = o.dM_domega;
    for (int k = 0; k < ElementJacobian::kMax; ++k) {
      j.dM_dx[0][k] = o.dM_dx[k];
      j.dx_dv[k][0] = o.dx_domega[k];
      for (int l = 0; l < ElementJacobian::kMax; ++l) j.dx_dx[k][l] = o.dx_dx[k][l];
    }
    return j;
  }
  [[nodiscard]] double heat_power(double t, const ElementMotion& b, const double* x, int mode) const final {
    return heat_power(t, b.v[0], x, mode);
  }
  [[nodiscard]] double source_power(double t, const ElementMotion& b, const double* x, int mode) const final {
    return source_power(t, b.v[0], x, mode);
  }
  void events(double t, const ElementMotion& b, const double* x, int mode, double* g) const final {
    events(t, b.v[0], x, mode, b.a[0], g);
  }
  [[nodiscard]] int settle(double t, const ElementMotion& b, const double*, int old, int now) const final {
    return settle(t, b.v[0], old, now, b.a[0]);
  }
  void on_switch(double t, const ElementMotion& b, double* x, int old, int now, bool located) const final {
    on_switch(t, b.v[0], x, old, now, located);
  }
  [[nodiscard]] int natural_mode(double t, const ElementMotion& b, const double* x, int current) const final {
    return natural_mode(t, b.v[0], x, current, b.a[0]);
  }
  void add_linear(const int* body, int mode, LinearModel& lin) const final { add_linear(body[0], mode, lin); }
  void outputs(double t, const ElementMotion& b, const double* x, int mode, double* out) const final {
    outputs(t, b.v[0], x, mode, out);
  }
};

}  // namespace machdyn
