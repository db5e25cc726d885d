#pragma once
/// @file
/// The law of an eddy-current brake with its temperature (`type: thermal-eddy-current-brake` under
/// `drives:`; Modelica's Rotational.Sources.EddyCurrentTorque and Translational.Sources.EddyCurrentForce
/// with their heat port on a HeatCapacitor), stated once as an Element (model/element.hpp):
///
///   torque      M = −2 M_k(t) x / (1 + x²),  x = ω / ω_k(T)       (eddy_current_law, model/model.hpp:
///                                                                   the law of the load `eddy-current-brake`)
///   resistance  ω_k(T) = ω_k,ref (1 + α (T − T_ref))                (the disc's resistance R(T) = R_ref (1 +
///                                                                   α (T − T_ref)) shifts the speed of the
///                                                                   largest torque; M_k stays)
///   heat        C dT/dt = P = −M ω ≥ 0                             (adiabatic: all of the braking power)
///
/// M_k(t) ≥ 0 its largest torque (N·m; a signal: MSL's tau_nominal or its input), ω_k,ref > 0 the
/// speed of the largest torque at the reference temperature T_ref (K), α ≥ 0 the resistance's
/// temperature coefficient (1/K), C > 0 the heat capacity (J/K), T the temperature (K), one state.
/// M acts against the motion, so P ≥ 0: T never falls and ω_k(T) ≥ ω_k(T0) > 0 (compile checks
/// 1 + α (T0 − T_ref) > 0). Energy: the kinetic energy the brake takes, ∫ −M ω dt, is C (T − T0).
/// On a translational body the same law holds with force (N) and velocity (m/s). Nothing is thrown.

#include "machdyn/model/element.hpp"

namespace machdyn {

class EddyCurrentBrake final : public OneBodyElement {
 public:
  Signal M_k = Signal::constant(0.0);  ///< largest torque M_k(t), N·m or N, ≥ 0
  double omega_ref = 1.0;  ///< ω_k,ref: speed of the largest torque at T_ref, rad/s or m/s, > 0
  double T_ref = 293.15;   ///< reference temperature, K
  double alpha = 0.0;      ///< temperature coefficient of the resistance α, 1/K, ≥ 0
  double C = 1.0;          ///< heat capacity, J/K, > 0
  double T0 = 293.15;      ///< initial temperature, K

  /// ω_k(T) = ω_k,ref (1 + α (T − T_ref)).
  [[nodiscard]] double breakdown_speed(double T) const { return omega_ref * (1.0 + alpha * (T - T_ref)); }
  /// M at time t, speed ω, temperature T; ∂M/∂ω into *dM_domega when given.
  [[nodiscard]] double torque_at(double t, double omega, double T, double* dM_domega) const {
    return eddy_current_law(omega, M_k.value(t), breakdown_speed(T), dM_domega);
  }

  [[nodiscard]] const char* type() const override { return "thermal-eddy-current-brake"; }
  [[nodiscard]] int states() const override { return 1; }
  void initial_states(double* x) const override { x[0] = T0; }
  [[nodiscard]] double torque(double t, double omega, const double* x, int) const override {
    return torque_at(t, omega, x[0], nullptr);
  }
  /// dT/dt = −M ω / C.
  void rates(double t, double omega, const double* x, int, double* dx, double) const override {
    dx[0] = -torque_at(t, omega, x[0], nullptr) * omega / C;
  }
  /// ∂M/∂ω from the law; ∂M/∂T = −(ω/ω_k) ∂M/∂ω · ω_k,ref α (M depends on ω/ω_k only);
  /// ∂T'/∂ω = −(M + ω ∂M/∂ω)/C, ∂T'/∂T = −ω ∂M/∂T / C.
  [[nodiscard]] OneBodyJacobian jacobian(double t, double omega, const double* x, int) const override;
  [[nodiscard]] bool dissipates() const override { return true; }
  /// All of −M ω becomes heat in the disc.
  [[nodiscard]] double heat_power(double t, double omega, const double* x, int mode) const override {
    return -torque(t, omega, x, mode) * omega;
  }
  /// Passive: no supply.
  [[nodiscard]] double source_power(double, double, const double*, int) const override { return 0.0; }
  /// Linear model: the slope at rest, 2 M_k(0)/ω_k(T0), as a damper to the ground.
  void add_linear(int body, int, LinearModel& lin) const override;
  [[nodiscard]] const char* state_name(int) const override { return "temperature"; }
  [[nodiscard]] std::string state_unit(int, BodyKind) const override { return "K"; }
  /// The temperature in °C (as the `thermal:` model of brakes and clutches) and the heat power P = −M ω.
  [[nodiscard]] std::vector<std::string> output_names(BodyKind) const override {
    return {"temperature_degC", "heat_power_W"};
  }
  void outputs(double t, double omega, const double* x, int mode, double* out) const override {
    out[0] = x[0] - 273.15;
    out[1] = heat_power(t, omega, x, mode);
  }
  [[nodiscard]] std::string describe(BodyKind body_kind) const override;
  [[nodiscard]] std::vector<double> breakpoints(double t0, double t1) const override { return M_k.breakpoints(t0, t1); }
  [[nodiscard]] double breakpoint_count(double t0, double t1) const override { return M_k.breakpoint_count(t0, t1); }
};

}  // namespace machdyn
