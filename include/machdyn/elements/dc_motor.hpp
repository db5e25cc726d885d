#pragma once
/// @file
/// The law of a DC motor with its armature circuit (`type: dc-motor` under `drives:`), stated once
/// and used by every consumer: the drive system's right-hand side and Jacobian, outputs, quasi-static
/// loads and the linear model.
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
#include "machdyn/model/model.hpp"

namespace machdyn {

struct DcMotorLaw {
  double R = 0.0, L = 0.0, k = 0.0;
  const Signal* u = nullptr;  ///< armature voltage u(t), V

  static DcMotorLaw of(const Drive& d) { return {d.R, d.L, d.k, &d.voltage}; }

  /// M = k i.
  [[nodiscard]] double torque(double i) const { return k * i; }
  /// di/dt = (u(t) − R i − k ω)/L.
  [[nodiscard]] double current_rate(double t, double omega, double i) const {
    return (u->value(t) - R * i - k * omega) / L;
  }
  /// Jacobian terms: ∂M/∂i = k, ∂(di/dt)/∂ω = −k/L, ∂(di/dt)/∂i = −R/L.
  [[nodiscard]] double dtorque_di() const { return k; }
  [[nodiscard]] double drate_domega() const { return -k / L; }
  [[nodiscard]] double drate_di() const { return -R / L; }
  /// The electrical rate R/L, 1/s (the fastest own motion, for the integrator choice).
  [[nodiscard]] double rate_bound() const { return R / L; }
  /// Linear model: the quasi-static slope (L → 0) dM/dω = −k²/R as a damper to the ground on
  /// `body`. Exact when the electrical time constant L/R is short against the mechanical periods.
  void add_linear(int body, LinearModel& lin) const { lin.D.emplace_back(body, body, k * k / R); }
};

}  // namespace machdyn
