#pragma once
/// @file
/// Prescribed motion (`motion:` of a body; Modelica's Sources.Accelerate and Sources.Speed): the
/// body's acceleration follows a signal instead of its equation of motion,
///   acceleration:  q'' = a(t)
///   speed:         q'' = dv/dt (t),  v(0) = v(t = 0)         (a signal's slope on the right of a kink)
///   position:      q'' = d²s/dt² (t),  q(0) = s(0), v(0) = ds/dt(0)   (s without jumps or kinks)
/// in rad/s² or m/s². Every link, load and drive on the body still acts; the force that keeps it on
/// its motion (the motion source's force, N·m or N, positive along +q) closes its equation of motion:
///   R = I q'' − f,      f: the sum of all other forces on the body (links, loads, drives).
/// The body is infinitely heavy for everything mass-weighted: its inverse inertia is 0 in the drive
/// system, and in modes (linearize) it is a fixed support (the constraint row q̇_i = 0).
/// A friction contact between the body and a free one acts on both; while stuck its force λ is
/// carried by the source too (R includes it). A friction element to the ground or to another
/// prescribed body is kinematic (elements/contact.hpp): sliding, its force is part of f (the source
/// delivers it); stuck, it carries no load. Ideal gears that tie the body to free ones make their
/// group prescribed (model/compile_rigid.hpp: the body is the group's master, I the reduced inertia,
/// R the force at its coordinate). A release lowers I at its instant (`inertia`, kept by the drive
/// system), so R jumps by −ΔI q''. A lossy gear on the body ties its other side to the motion; the gear's
/// torque X (or −i Y) is part of f (elements/lossy_gear.hpp "Prescribed side"). Valid on a body with a
/// constant inertia (compile refuses, located, a freewheel or end stop that would lock it, and a lossy
/// gear prescribed on both sides).

#include <cmath>
#include <string>

#include "machdyn/elements/linear_model.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

struct PrescribedMotionLaw {
  int body = 0;
  MotionKind kind = MotionKind::acceleration;
  const Signal* signal = nullptr;  ///< the body's motion_signal (the Model outlives the law)
  double inertia = 0.0;            ///< I or m of the body, kg·m² or kg (the current one, after releases)
  double speed_scale = 0.0;        ///< a prescribed speed: max |v(t)| over [0, t_end] (the rounding's scale)

  /// The law of body `i` of `m` (whose motion is not free).
  static PrescribedMotionLaw of(const Model& m, int i);

  /// q''(t), rad/s² or m/s².
  [[nodiscard]] double acceleration(double t) const {
    return kind == MotionKind::acceleration ? signal->value(t)
           : kind == MotionKind::speed      ? signal->slope(t)
                                            : signal->curvature(t);
  }
  /// A prescribed speed's velocity state put back onto the signal, v(t), where it is within 1e-6 of
  /// the signal's scale: the integration error of its slope (a step ending on a kink takes its last
  /// stage's slope from the right, ~1e-9 of the speed), never a jump of the signal (which the
  /// integrated slope does not carry). The speed is then exactly the signal's: a rest at v = 0 is
  /// exactly at rest. Any other v (another kind of motion) is returned unchanged.
  [[nodiscard]] double snapped_velocity(double t, double v) const {
    if (kind != MotionKind::speed) return v;
    const double s = signal->value(t);
    return std::abs(v - s) <= 1e-6 * speed_scale ? s : v;
  }
  /// R = I q''(t) − f: the force of the motion source for the other forces f on the body.
  [[nodiscard]] double force(double t, double f) const { return inertia * acceleration(t) - f; }
  /// Adds the fixed support q̇_i = 0 of modes (a constraint row named after the body).
  void add_linear(const std::string& name, LinearModel& lin) const;
};

}  // namespace machdyn
