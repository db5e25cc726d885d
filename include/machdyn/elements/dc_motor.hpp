#pragma once
/// @file
/// The law of a DC motor with its armature circuit (`type: dc-motor` under `drives:`), stated once
/// as an Element (model/element.hpp), through which every consumer reads it: the drive system's
/// right-hand side and Jacobian, outputs, quasi-static loads and the linear model.
///
///   armature:  L di/dt = u(t) − R i − k ω        (V; i in A, ω the body's velocity in rad/s)
///   torque:    M = k i                            (N·m, acts on the body along +q)
///
/// k = k_t = k_e: in SI the torque constant (N·m/A) equals the back-emf constant (V·s/rad), by the
/// power balance u i = R i² + L i di/dt + M ω. On a translational body (a linear motor) k is in N/A
/// = V·s/m and M is a force. One state: the current i.
/// Steady state (di/dt = 0): i = (u − k ω)/R, so M = k (u − k ω)/R — stall torque k u/R, no-load
/// speed u/k, slope −k²/R. Valid for R > 0, L > 0, k > 0 (compile checks); nothing is thrown.

#include "machdyn/elements/linear_model.hpp"
#include "machdyn/model/element.hpp"

namespace machdyn {

class DcMotor final : public OneBodyElement {
 public:
  double R = 0.0;   ///< armature resistance, Ω, > 0
  double L = 0.0;   ///< armature inductance, H, > 0
  double k = 0.0;   ///< motor constant k = k_t = k_e, N·m/A = V·s/rad (N/A on a translational body), > 0
  double i0 = 0.0;  ///< initial current, A
  Signal u = Signal::constant(0.0);  ///< armature voltage u(t), V

  /// M = k i.
  [[nodiscard]] double torque_of(double i) const { return k * i; }
  /// di/dt = (u(t) − R i − k ω)/L.
  [[nodiscard]] double current_rate(double t, double omega, double i) const {
    return (u.value(t) - R * i - k * omega) / L;
  }

  [[nodiscard]] const char* type() const override { return "dc-motor"; }
  [[nodiscard]] int states() const override { return 1; }
  void initial_states(double* x) const override { x[0] = i0; }
  [[nodiscard]] double torque(double, double, const double* x, int) const override { return torque_of(x[0]); }
  void rates(double t, double omega, const double* x, int, double* dx, double) const override {
    dx[0] = current_rate(t, omega, x[0]);
  }
  /// The armature's copper loss R i² is heat (MSL's DC machines put it on their heat port): by
  /// u i = R i² + L i di/dt + M ω the supply delivers M ω into the mechanics plus this heat (the
  /// inductance's ½ L i² is stored, not counted).
  [[nodiscard]] bool dissipates() const override { return true; }
  [[nodiscard]] double heat_power(double, double, const double* x, int) const override { return R * x[0] * x[0]; }
  /// The supply's power into the mechanics and the heat, u i − L i di/dt (the inductance's share
  /// of u i is stored in ½ L i², not counted): P_source = M ω + R i² by the armature equation.
  [[nodiscard]] double source_power(double t, double omega, const double* x, int) const override {
    return u.value(t) * x[0] - L * x[0] * current_rate(t, omega, x[0]);
  }
  /// ∂M/∂i = k, ∂(di/dt)/∂ω = −k/L, ∂(di/dt)/∂i = −R/L.
  [[nodiscard]] OneBodyJacobian jacobian(double, double, const double*, int) const override;
  /// Linear model: the quasi-static slope (L → 0) dM/dω = −k²/R as a damper to the ground on
  /// `body`. Exact when the electrical time constant L/R is short against the mechanical periods.
  void add_linear(int body, int, LinearModel& lin) const override { lin.D.emplace_back(body, body, k * k / R); }
  /// The electrical rate R/L, 1/s (the fastest own motion, for the integrator choice).
  [[nodiscard]] double rate_bound() const override { return R / L; }

  [[nodiscard]] const char* state_name(int) const override { return "current"; }
  [[nodiscard]] std::string state_unit(int, BodyKind) const override { return "A"; }
  /// The current and the mode (always 0: a DC motor has no modes).
  [[nodiscard]] std::vector<std::string> output_names(BodyKind) const override { return {"current_A", "mode"}; }
  void outputs(double, double, const double* x, int mode, double* out) const override {
    out[0] = x[0];
    out[1] = static_cast<double>(mode);
  }
  [[nodiscard]] std::string describe(BodyKind) const override;
  [[nodiscard]] std::vector<double> breakpoints(double t0, double t1) const override { return u.breakpoints(t0, t1); }
  [[nodiscard]] double breakpoint_count(double t0, double t1) const override { return u.breakpoint_count(t0, t1); }
};

}  // namespace machdyn
