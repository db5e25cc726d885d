#pragma once
/// @file
/// A drive with states of its own (model/model.hpp `Drive`), as the drive system sees it: the body it
/// acts on, its states (appended after [q; v]), and its law — elements/dc_motor.hpp or
/// elements/speed_drive.hpp, each stated once; this file only dispatches to them.
/// A DC motor has no modes (its mode stays `linear`); a speed drive's limiter has three.

#include <string>

#include "machdyn/elements/dc_motor.hpp"
#include "machdyn/elements/linear_model.hpp"
#include "machdyn/elements/speed_drive.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

struct DriveLaw {
  DriveKind kind = DriveKind::dc_motor;
  int body = 0;
  int states = 1;
  DcMotorLaw dc;
  SpeedDriveLaw sd;
  double x0[2] = {0.0, 0.0};  ///< initial states: i0 (DC motor); M0, M0 (speed drive)

  static DriveLaw of(const Drive& d);

  /// The torque M on the body (N·m or N) for velocity ω and states x in mode md.
  [[nodiscard]] double torque(double t, double omega, const double* x, LimitMode md) const {
    return kind == DriveKind::dc_motor ? dc.torque(x[0]) : sd.torque(t, omega, x, md);
  }
  /// The state rates x' (omega_dot: the body's acceleration, read by a speed drive on its limit).
  void rates(double t, double omega, const double* x, LimitMode md, double* dx, double omega_dot) const {
    if (kind == DriveKind::dc_motor) dx[0] = dc.current_rate(t, omega, x[0]);
    else sd.rates(t, omega, x, md, dx, omega_dot);
  }
  [[nodiscard]] DriveJacobian jacobian(LimitMode md) const;
  /// Whether the drive has limiter events (a speed drive with a finite torque limit).
  [[nodiscard]] bool has_events() const { return kind == DriveKind::speed_drive && sd.limited(); }
  /// Two event functions, each ≥ 0 while mode md holds (1 for a drive without events).
  void events(double t, double omega, const double* x, LimitMode md, double* g, double omega_dot) const {
    if (!has_events()) {
      g[0] = g[1] = 1.0;
      return;
    }
    sd.events(sd.command(t, omega, x[0]), sd.ref->value(t) - omega, sd.ref->slope(t) - omega_dot, md, g);
  }
  /// The mode after a switch old → now at the limit (SpeedDriveLaw::settle).
  [[nodiscard]] LimitMode settle(double t, double omega, LimitMode old, LimitMode now, double omega_dot) const {
    if (!has_events()) return now;
    return sd.settle(old, now, sd.ref->value(t) - omega, sd.ref->slope(t) - omega_dot);
  }
  /// The mode the state implies on its own (initial state, time events).
  [[nodiscard]] LimitMode natural_mode(double t, double omega, const double* x, LimitMode current) const {
    return has_events() ? sd.natural_mode(sd.command(t, omega, x[0]), current) : LimitMode::linear;
  }
  /// Its terms of the linear model in mode md (elements/linear_model.hpp).
  void add_linear(LimitMode md, LinearModel& lin) const {
    if (kind == DriveKind::dc_motor) dc.add_linear(body, lin);
    else sd.add_linear(body, md, lin);
  }
  /// The fastest own rate, 1/s (R/L, 1/T_m), for the integrator choice.
  [[nodiscard]] double rate_bound() const { return kind == DriveKind::dc_motor ? dc.rate_bound() : sd.rate_bound(); }
  /// What state j is, for messages: "current", "integral torque", "torque".
  [[nodiscard]] const char* state_name(int j) const;
  /// What a state is measured in, for output columns: "A" or the body's load unit.
  [[nodiscard]] std::string state_unit(int j, BodyKind body_kind) const;
};

}  // namespace machdyn
