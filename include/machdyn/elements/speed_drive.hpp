#pragma once
/// @file
/// The law of a speed-controlled drive (`type: speed-drive` under `drives:`): an inverter with a PI
/// speed controller, a torque limit and an optional torque rise time, its torque acting on the motor
/// body. Stated once as an Element (model/element.hpp), through which every consumer reads it: the
/// drive system's right-hand side, Jacobian and event functions, the run's mode decisions, outputs,
/// quasi-static loads and the linear model.
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
#include "machdyn/model/element.hpp"

namespace machdyn {

/// The mode of a speed drive's torque limiter (its Element mode is the int of this).
enum class LimitMode : int { on_limit_neg = -2, limited_neg = -1, linear = 0, limited_pos = 1, on_limit_pos = 2 };
/// +1 for limited+ and on-limit+, −1 for the lower ones, 0 for linear.
inline int limit_side(LimitMode m) { return static_cast<int>(m) > 0 ? 1 : static_cast<int>(m) < 0 ? -1 : 0; }
inline bool on_limit(LimitMode m) { return m == LimitMode::on_limit_pos || m == LimitMode::on_limit_neg; }
const char* to_string(LimitMode m);

class SpeedDrive final : public OneBodyElement {
 public:
  double Kp = 0.0;        ///< proportional gain K_p, N·m·s/rad or N·s/m, > 0
  double Ti = 0.0;        ///< integral time T_i, s, > 0
  double M_max = HUGE_VAL;  ///< torque limit, N·m or N, > 0 (infinite: no limit)
  double T_m = 0.0;       ///< torque rise time, s, ≥ 0 (0: no lag)
  double M0 = 0.0;        ///< initial torque (integral state and lagged torque at t = 0), N·m or N
  Signal ref = Signal::constant(0.0);  ///< ω_ref(t), rad/s or m/s

  [[nodiscard]] bool lagged() const { return T_m > 0.0; }
  [[nodiscard]] bool limited() const { return std::isfinite(M_max); }
  /// The controller output M_c = K_p (ω_ref(t) − ω) + x_I.
  [[nodiscard]] double command(double t, double omega, double xI) const { return Kp * (ref.value(t) - omega) + xI; }
  /// M_s: the command through the limiter in mode md.
  [[nodiscard]] double limited_command(double Mc, LimitMode md) const {
    return md == LimitMode::linear ? Mc : limit_side(md) * M_max;
  }
  /// The two event functions of mode md (see above), from the command M_c, the error e and its
  /// rate ė = ω_ref'(t) − ω' (read on the limit only).
  void limit_events(double Mc, double e, double e_dot, LimitMode md, double* g) const {
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
  static LimitMode limit_mode_after(LimitMode md, int slot) {
    if (on_limit(md)) return slot == 0 ? LimitMode::linear : limit_side(md) > 0 ? LimitMode::limited_pos : LimitMode::limited_neg;
    if (md != LimitMode::linear) return LimitMode::linear;
    return slot == 0 ? LimitMode::limited_pos : LimitMode::limited_neg;
  }
  /// A switch old → now between linear and limited± happens with the command on the limit: it
  /// stays there (on-limit±) when held points inside (s K_p ė < 0) and integrating points outside
  /// (s (K_p ė + (K_p/T_i) e) > 0); otherwise `now` holds.
  [[nodiscard]] LimitMode settle_limit(LimitMode old, LimitMode now, double e, double e_dot) const {
    if (on_limit(old) || on_limit(now)) return now;
    const int s = limit_side(old) != 0 ? limit_side(old) : limit_side(now);
    if (s == 0) return now;
    if (s * Kp * e_dot < 0.0 && s * (Kp * e_dot + Kp / Ti * e) > 0.0)
      return s > 0 ? LimitMode::on_limit_pos : LimitMode::on_limit_neg;
    return now;
  }
  /// The mode a command implies on its own (the initial state, a jump of ω_ref at a breakpoint):
  /// limited beyond the limit, else linear; exactly at the limit the current mode holds.
  [[nodiscard]] LimitMode command_mode(double Mc, LimitMode current) const {
    if (Mc > M_max) return LimitMode::limited_pos;
    if (Mc < -M_max) return LimitMode::limited_neg;
    if (std::abs(Mc) == M_max) return current;
    return LimitMode::linear;
  }

  // ---- Element ----
  [[nodiscard]] const char* type() const override { return "speed-drive"; }
  /// x_I, and the lagged torque M when T_m > 0.
  [[nodiscard]] int states() const override { return lagged() ? 2 : 1; }
  /// The integral holds the initial torque; the lag starts there too.
  void initial_states(double* x) const override {
    x[0] = M0;
    if (lagged()) x[1] = M0;
  }
  /// The torque on the body: M_s, or the lagged torque x[1].
  [[nodiscard]] double torque(double t, double omega, const double* x, int mode) const override {
    return lagged() ? x[1] : limited_command(command(t, omega, x[0]), LimitMode(mode));
  }
  /// The state rates: x_I' and (lagged) M'. omega_dot: the body's acceleration ω' (read on the limit).
  void rates(double t, double omega, const double* x, int mode, double* dx, double omega_dot) const override {
    const LimitMode md = LimitMode(mode);
    const double e = ref.value(t) - omega;
    dx[0] = md == LimitMode::linear ? Kp / Ti * e : on_limit(md) ? -Kp * (ref.slope(t) - omega_dot) : 0.0;
    if (lagged()) dx[1] = (limited_command(Kp * e + x[0], md) - x[1]) / T_m;
  }
  /// Jacobian terms in mode md (the limited and on-limit modes hold M_s constant; on the limit the
  /// coupling of x_I' to the acceleration ω' is left out: the Newton iteration of an implicit method
  /// converges with it missing, the solution does not depend on it):
  ///   T_m = 0:  ∂M/∂ω = −K_p, ∂M/∂x_I = 1 (linear; 0 limited);  ∂x_I'/∂ω = −K_p/T_i (linear)
  ///   T_m > 0:  ∂M/∂x₁ = 1;  ∂x₁'/∂ω = −K_p/T_m, ∂x₁'/∂x_I = 1/T_m (linear), ∂x₁'/∂x₁ = −1/T_m
  [[nodiscard]] OneBodyJacobian jacobian(double t, double omega, const double* x, int mode) const override;
  /// An ideal controlled source (the converter's losses are not modelled): it delivers M ω.
  [[nodiscard]] double source_power(double t, double omega, const double* x, int mode) const override {
    return torque(t, omega, x, mode) * omega;
  }
  [[nodiscard]] bool has_events() const override { return limited(); }
  void events(double t, double omega, const double* x, int mode, double omega_dot, double* g) const override {
    limit_events(command(t, omega, x[0]), ref.value(t) - omega, ref.slope(t) - omega_dot, LimitMode(mode), g);
  }
  [[nodiscard]] bool reads_acceleration(int mode) const override { return on_limit(LimitMode(mode)); }
  [[nodiscard]] int mode_after(int mode, int slot) const override {
    return static_cast<int>(limit_mode_after(LimitMode(mode), slot));
  }
  /// At the limit ω' is the same in both modes (the torque is ±M_max either way, or a lagged state).
  [[nodiscard]] bool settles(int old, int now) const override {
    return limited() && !on_limit(LimitMode(old)) && !on_limit(LimitMode(now));
  }
  [[nodiscard]] int settle(double t, double omega, int old, int now, double omega_dot) const override {
    return static_cast<int>(settle_limit(LimitMode(old), LimitMode(now), ref.value(t) - omega, ref.slope(t) - omega_dot));
  }
  /// A switch to or from the limit happens with the command on it, M_c = s M_max: located by its own
  /// event (g₀ or g₁ just crossed 0), or leaving an on-limit mode (which keeps M_c = s M_max through
  /// x_I' = −K_p ė, an integrated invariant that drifts: on bdf DriveOnLimit left the limit with
  /// M_max − M_c = −3.8e-10 N·m). x_I is put on K_p e + x_I = s M_max, then the few ulps to the side of
  /// `now` its events read: |M_c| ≤ M_max linear, s (M_c − s M_max) ≥ 0 limited± (on-limit: on it).
  void on_switch(double t, double omega, double* x, int old, int now, bool located) const override {
    const LimitMode o = LimitMode(old), n = LimitMode(now);
    if (!limited() || (!located && !on_limit(o))) return;
    const int s = limit_side(o) != 0 ? limit_side(o) : limit_side(n);
    if (s == 0) return;
    const double Kpe = Kp * (ref.value(t) - omega);  // as command() forms it
    auto holds = [&](double xI) {
      const double Mc = Kpe + xI;
      return n == LimitMode::linear ? std::abs(Mc) <= M_max : on_limit(n) || s * (Mc - s * M_max) >= 0.0;
    };
    double xI = s * M_max - Kpe;
    const double toward = n == LimitMode::linear ? -s : s;  // inside for linear, outside for limited±
    for (int i = 0; i < 8 && !holds(xI); ++i) xI = std::nextafter(xI, toward * HUGE_VAL);
    x[0] = xI;
  }
  /// Off the limit: the command's mode; on it, a jump of ω_ref' (a ramp's end) may end the on-limit
  /// motion: its event functions decide.
  [[nodiscard]] int natural_mode(double t, double omega, const double* x, int current, double omega_dot) const override;
  [[nodiscard]] const char* mode_name(int mode) const override { return to_string(LimitMode(mode)); }
  [[nodiscard]] const char* switch_kind(int now) const override {
    return now == 0 ? "unlimited" : on_limit(LimitMode(now)) ? "on limit" : "limited";
  }
  /// Linear model in the linear mode: about the reference motion the PI law is
  /// M = −K_p δω − (K_p/T_i) δq, a damper K_p and a spring K_p/T_i from the body to the ground
  /// (exact for T_m = 0; with a lag, its phase is neglected). Limited: a constant torque, nothing.
  void add_linear(int body, int mode, LinearModel& lin) const override {
    if (LimitMode(mode) != LimitMode::linear) return;
    lin.D.emplace_back(body, body, Kp);
    lin.K.emplace_back(body, body, Kp / Ti);
  }
  /// The fastest own rate, 1/s: 1/T_m (the PI loop's own speed depends on the inertia; the links and
  /// the inertia bound it in the integrator choice through K_p).
  [[nodiscard]] double rate_bound() const override { return lagged() ? 1.0 / T_m : 0.0; }
  [[nodiscard]] const char* state_name(int j) const override { return j == 0 ? "integral torque" : "torque"; }
  [[nodiscard]] std::string state_unit(int, BodyKind body_kind) const override { return load_unit(body_kind); }
  /// The reference speed and the limiter mode (0 linear, ±1 limited±, ±2 on the limit).
  [[nodiscard]] std::vector<std::string> output_names(BodyKind body_kind) const override;
  void outputs(double t, double, const double*, int mode, double* out) const override {
    out[0] = ref.value(t);
    out[1] = static_cast<double>(mode);
  }
  [[nodiscard]] std::string describe(BodyKind body_kind) const override;
  [[nodiscard]] std::vector<double> breakpoints(double t0, double t1) const override { return ref.breakpoints(t0, t1); }
  [[nodiscard]] double breakpoint_count(double t0, double t1) const override { return ref.breakpoint_count(t0, t1); }
  /// The drive holds the steady speed v as its reference (instead of its own ramp from rest).
  [[nodiscard]] std::shared_ptr<const Element> at_steady_speed(double v) const override;
};

}  // namespace machdyn
