#pragma once
/// @file
/// A first-order system with modes and events: y' = f_mode(t, y) holds while every event function
/// g_i(t, y) ≥ 0; an event is a sign change of some g_i from ≥ 0 to < 0 on the continuous
/// (dense-output) solution. The system decides its new modes and maps the state across the event
/// (handle_events); the driver (solve/driver.hpp) locates the events, restarts the stepper and
/// never steps across a breakpoint (a time where f jumps or has a kink in t). A system without
/// events has event_count() = 0 and no breakpoints. Integrators still see only the OdeSystem part.

#include <limits>
#include <vector>

#include "machdyn/solve/ode_system.hpp"

namespace machdyn {

class EventSystem : public OdeSystem {
 public:
  /// Number of event functions (constant over a run).
  [[nodiscard]] virtual int event_count() const { return 0; }
  /// g_i(t, y) for i < event_count(), into g; each ≥ 0 while the current mode holds.
  virtual void event_functions(double /*t*/, const double* /*y*/, double* /*g*/) {}
  /// Times in (t0, t_end), increasing, where f jumps or has a kink in t (steps, ramps, tables,
  /// a brake applied). Steps end exactly there and handle_events(t, y, {}) is called.
  [[nodiscard]] virtual std::vector<double> breakpoints(double /*t0*/, double /*t_end*/) const { return {}; }
  /// The longest time over which the event functions may be judged by their values at its ends
  /// alone, s: a function whose explicit dependence on t (a sine load against a constant limit
  /// while the state stands still) can leave ≥ 0 and come back within a step, unseen by the error
  /// control, which follows the state only. The driver checks the functions inside any step longer
  /// than this, at this spacing. +∞ (the default): no such dependence — between breakpoints every
  /// load is linear in t, so a function the stepper's state follows cannot turn around unseen.
  [[nodiscard]] virtual double sampling_step(double /*t0*/, double /*t_end*/) const {
    return std::numeric_limits<double>::infinity();
  }
  /// At an event or breakpoint at t. `y` is the state just before (the left limit, in the old
  /// modes); `fired` lists the functions that crossed zero there, the earliest-located first (empty
  /// at a breakpoint). Decides the new modes and maps y in place to the state just after. Returns
  /// whether anything changed (modes or state); the driver restarts the stepper either way.
  virtual bool handle_events(double /*t*/, double* /*y*/, const std::vector<int>& /*fired*/) { return false; }
};

}  // namespace machdyn
