#pragma once
/// @file
/// The law of a speed-controlled drive (`type: speed-drive` under `drives:`): an inverter with a PI
/// speed controller, a torque limit and an optional torque rise time, its torque acting on the motor
/// body. Stated once and used by every consumer: the drive system's right-hand side, Jacobian and
/// event functions, the run's mode decisions, outputs, quasi-static loads and the linear model.
///
///   speed error     e = ω_ref(t) − ω                         (rad/s; ω the body's velocity)
///   PI controller   M_c = K_p e + x_I                         (N·m; x_I the integral part, a state)
///                   x_I' = (K_p/T_i) e   while not limited,   x_I' = 0 while limited
///   torque limit    M_s = M_c (mode `linear`), +M_max (`limited+`), −M_max (`limited-`)
///   torque lag      M = M_s (T_m = 0), or T_m M' = M_s − M (T_m > 0; M a second state)
/// Anti-windup by clamping (conditional integration): while the torque is limited the integral is
/// held, so the drive leaves the limit as soon as K_p e + x_I falls back inside it, without the
/// overshoot a wound-up integrator would cause.
/// On the limit (M_c = ±M_max) the two laws can point against each other: held, M_c' = K_p ė < 0
/// pulls the command inside; integrating, M_c' = K_p ė + (K_p/T_i) e > 0 pushes it out again (a
/// speed that overtakes its reference while the error is still large, typically with a torque lag).
/// Switching would chatter; the exact (Filippov) motion is the mode `on-limit±`: the command stays
/// on the limit, M_s = ±M_max, and the integral integrates just enough for it,
///   x_I' = −K_p ė = K_p (ω' − ω_ref'(t))            (ω' the body's acceleration)
/// The limit is exact, not smoothed: each mode is a smooth law and the switches are events
/// (each event function ≥ 0 while its mode holds; s = +1 for the upper limit, −1 for the lower):
///   linear:     g₀ = M_max − M_c,  g₁ = M_max + M_c     (g₀ < 0: limited+, g₁ < 0: limited-)
///   limited+:   g₀ = M_c − M_max                          (< 0: back to linear)
///   limited-:   g₁ = −M_max − M_c                         (< 0: back to linear)
///   on-limit±:  g₀ = s (K_p ė + (K_p/T_i) e)  (< 0: linear pulls inside: linear)
///               g₁ = −s K_p ė                  (< 0: held pushes outside: limited±)
/// A switch between linear and limited± lands on on-limit± when, at the limit, held points inside
/// and integrating points outside (settle()).
/// A model without a limit (M_max = ∞) has no such events. On a translational body the same law
/// holds with velocity (m/s) and force (N), K_p in N·s/m. Valid for K_p > 0, T_i > 0, M_max > 0,
/// T_m ≥ 0 (compile checks); nothing is thrown.

#include <cmath>

#include "machdyn/elements/linear_model.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// The mode of a speed drive's torque limiter.
enum class LimitMode : int { on_limit_neg = -2, limited_neg = -1, linear = 0, limited_pos = 1, on_limit_pos = 2 };
/// +1 for limited+ and on-limit+, −1 for the lower ones, 0 for linear.
inline int limit_side(LimitMode m) { return static_cast<int>(m) > 0 ? 1 : static_cast<int>(m) < 0 ? -1 : 0; }
inline bool on_limit(LimitMode m) { return m == LimitMode::on_limit_pos || m == LimitMode::on_limit_neg; }
const char* to_string(LimitMode m);

/// The Jacobian terms of a drive with up to two states x: its torque M and the state rates x'
/// against the body's velocity ω and the states.
struct DriveJacobian {
  double dM_domega = 0.0, dM_dx[2] = {0.0, 0.0}, dx_domega[2] = {0.0, 0.0}, dx_dx[2][2] = {{0.0, 0.0}, {0.0, 0.0}};
};

struct SpeedDriveLaw {
  double Kp = 0.0, Ti = 0.0, M_max = HUGE_VAL, T_m = 0.0;
  const Signal* ref = nullptr;  ///< ω_ref(t)

  static SpeedDriveLaw of(const Drive& d) { return {d.Kp, d.Ti, d.M_max, d.T_m, &d.reference}; }

  [[nodiscard]] bool lagged() const { return T_m > 0.0; }
  [[nodiscard]] bool limited() const { return std::isfinite(M_max); }
  /// The controller output M_c = K_p (ω_ref(t) − ω) + x_I.
  [[nodiscard]] double command(double t, double omega, double xI) const { return Kp * (ref->value(t) - omega) + xI; }
  /// M_s: the command through the limiter in mode md.
  [[nodiscard]] double limited_command(double Mc, LimitMode md) const {
    return md == LimitMode::linear ? Mc : limit_side(md) * M_max;
  }
  /// The torque on the body: M_s, or the lagged torque x[1].
  [[nodiscard]] double torque(double t, double omega, const double* x, LimitMode md) const {
    return lagged() ? x[1] : limited_command(command(t, omega, x[0]), md);
  }
  /// The state rates: x_I' and (lagged) M'. omega_dot: the body's acceleration ω' (read on the limit).
  void rates(double t, double omega, const double* x, LimitMode md, double* dx, double omega_dot) const {
    const double e = ref->value(t) - omega;
    dx[0] = md == LimitMode::linear ? Kp / Ti * e : on_limit(md) ? -Kp * (ref->slope(t) - omega_dot) : 0.0;
    if (lagged()) dx[1] = (limited_command(Kp * e + x[0], md) - x[1]) / T_m;
  }
  /// Jacobian terms in mode md (the limited and on-limit modes hold M_s constant; on the limit the
  /// coupling of x_I' to the acceleration ω' is left out: the Newton iteration of an implicit method
  /// converges with it missing, the solution does not depend on it):
  ///   T_m = 0:  ∂M/∂ω = −K_p, ∂M/∂x_I = 1 (linear; 0 limited);  ∂x_I'/∂ω = −K_p/T_i (linear)
  ///   T_m > 0:  ∂M/∂x₁ = 1;  ∂x₁'/∂ω = −K_p/T_m, ∂x₁'/∂x_I = 1/T_m (linear), ∂x₁'/∂x₁ = −1/T_m
  [[nodiscard]] DriveJacobian jacobian(LimitMode md) const {
    DriveJacobian j;
    const bool lin = md == LimitMode::linear;
    if (lin) j.dx_domega[0] = -Kp / Ti;
    if (!lagged()) {
      if (lin) j.dM_domega = -Kp, j.dM_dx[0] = 1.0;
      return j;
    }
    j.dM_dx[1] = 1.0;
    if (lin) j.dx_domega[1] = -Kp / T_m, j.dx_dx[1][0] = 1.0 / T_m;
    j.dx_dx[1][1] = -1.0 / T_m;
    return j;
  }
  /// The two event functions of mode md (see above), from the command M_c, the error e and its
  /// rate ė = ω_ref'(t) − ω' (read on the limit only).
  void events(double Mc, double e, double e_dot, LimitMode md, double* g) const {
    if (!limited()) {
      g[0] = g[1] = 1.0;
      return;
    }
    if (on_limit(md)) {
      const double s = limit_side(md);
      g[0] = s * (Kp * e_dot + Kp / Ti * e);
      g[1] = -s * Kp * e_dot;
      return;
    }
    g[0] = md == LimitMode::linear ? M_max - Mc : md == LimitMode::limited_pos ? Mc - M_max : 1.0;
    g[1] = md == LimitMode::linear ? M_max + Mc : md == LimitMode::limited_neg ? -M_max - Mc : 1.0;
  }
  /// The mode after event function `slot` (0 or 1) of mode md crossed zero.
  static LimitMode mode_after(LimitMode md, int slot) {
    if (on_limit(md)) return slot == 0 ? LimitMode::linear : limit_side(md) > 0 ? LimitMode::limited_pos : LimitMode::limited_neg;
    if (md != LimitMode::linear) return LimitMode::linear;
    return slot == 0 ? LimitMode::limited_pos : LimitMode::limited_neg;
  }
  /// A switch old → now between linear and limited± happens with the command on the limit: it
  /// stays there (on-limit±) when held points inside (s K_p ė < 0) and integrating points outside
  /// (s (K_p ė + (K_p/T_i) e) > 0); otherwise `now` holds.
  [[nodiscard]] LimitMode settle(LimitMode old, LimitMode now, double e, double e_dot) const {
    if (on_limit(old) || on_limit(now)) return now;
    const int s = limit_side(old) != 0 ? limit_side(old) : limit_side(now);
    if (s == 0) return now;
    if (s * Kp * e_dot < 0.0 && s * (Kp * e_dot + Kp / Ti * e) > 0.0)
      return s > 0 ? LimitMode::on_limit_pos : LimitMode::on_limit_neg;
    return now;
  }
  /// The mode a command implies on its own (the initial state, a jump of ω_ref at a breakpoint):
  /// limited beyond the limit, else linear; exactly at the limit the current mode holds.
  [[nodiscard]] LimitMode natural_mode(double Mc, LimitMode current) const {
    if (Mc > M_max) return LimitMode::limited_pos;
    if (Mc < -M_max) return LimitMode::limited_neg;
    if (std::abs(Mc) == M_max) return current;
    return LimitMode::linear;
  }
  /// The fastest own rate, 1/s: 1/T_m (the PI loop's own speed depends on the inertia; the links and
  /// the inertia bound it in the integrator choice through K_p).
  [[nodiscard]] double rate_bound() const { return lagged() ? 1.0 / T_m : 0.0; }
  /// Linear model in the linear mode: about the reference motion the PI law is
  /// M = −K_p δω − (K_p/T_i) δq, a damper K_p and a spring K_p/T_i from the body to the ground
  /// (exact for T_m = 0; with a lag, its phase is neglected). Limited: a constant torque, nothing.
  void add_linear(int body, LimitMode md, LinearModel& lin) const {
    if (md != LimitMode::linear) return;
    lin.D.emplace_back(body, body, Kp);
    lin.K.emplace_back(body, body, Kp / Ti);
  }
};

}  // namespace machdyn
