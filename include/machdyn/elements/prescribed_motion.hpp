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
/// carried by the source too (R includes it). Valid on a body with a constant inertia, tied to no
/// ideal or lossy gear, with no release and no friction element to the ground or to another
/// prescribed body (compile refuses those, located).

#include <string>

#include "machdyn/elements/linear_model.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

struct PrescribedMotionLaw {
  int body = 0;
  MotionKind kind = MotionKind::acceleration;
  const Signal* signal = nullptr;  ///< the body's motion_signal (the Model outlives the law)
  double inertia = 0.0;            ///< I or m of the body, kg·m² or kg

  /// The law of body `i` of `m` (whose motion is not free).
  static PrescribedMotionLaw of(const Model& m, int i);

  /// q''(t), rad/s² or m/s².
  [[nodiscard]] double acceleration(double t) const {
    return kind == MotionKind::acceleration ? signal->value(t)
           : kind == MotionKind::speed      ? signal->slope(t)
                                            : signal->curvature(t);
  }
  /// R = I q''(t) − f: the force of the motion source for the other forces f on the body.
  [[nodiscard]] double force(double t, double f) const { return inertia * acceleration(t) - f; }
  /// Adds the fixed support q̇_i = 0 of modes (a constraint row named after the body).
  void add_linear(const std::string& name, LinearModel& lin) const;
};

}  // namespace machdyn
