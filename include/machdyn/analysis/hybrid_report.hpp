#pragma once
/// @file
/// What a hybrid (event-driven) simulation reports besides the time series: the mode events, the
/// slip phases with the peak link loads inside each, and the energy balance. Plain data, filled by
/// simulate() (analysis/simulate.hpp) and written by io/results.hpp.

#include <string>
#include <vector>

namespace machdyn {

/// One change of mode of one element at time t (located to ~1e-13 s on the dense output).
struct ModeEvent {
  double t = 0.0;        ///< s
  std::string kind;      ///< gap_closed, gap_opened, stick, slip, reversal, initial
  std::string element;   ///< link, contact or brake name
  std::string from, to;  ///< open / closed+ / closed-; stuck / slip+ / slip-
};

/// An interval during which a friction contact slides in one direction, with the extremes of every
/// link load inside it (Model::links order).
struct SlipPhase {
  std::string contact;
  int direction = 0;                 ///< +1: u = v_a − v_b > 0
  double t_start = 0.0, t_end = 0.0; ///< s
  std::vector<double> link_max, link_t_max, link_min;
  /// Link loads at t_start: the load at which the contact broke away (exact, at the located event).
  std::vector<double> link_start;
};

/// Energy balance over the run, J: work of the sources (loads and moving surfaces) equals the change
/// of kinetic and elastic energy plus the losses in friction and dampers (and the elastic energy a
/// damped gap releases when it opens at zero force off its flank). The work and the losses are
/// integrated as extra states with the motion, so the balance measures the integration error.
struct EnergyBalance {
  double source_work = 0.0;
  double kinetic_start = 0.0, kinetic_end = 0.0;
  double elastic_start = 0.0, elastic_end = 0.0;
  double friction_loss = 0.0, damping_loss = 0.0, release_loss = 0.0;
  double impact_loss = 0.0;  ///< kinetic energy lost in end-stop impacts, ½ m v⁻² (1 − e²) each, J
  /// Kinetic energy the parts released by `releases:` carried away, ½ ΔI v(t_r)² each, J. (Their
  /// weight's work is not a stored energy here: a weight is a load, its work is source work, and the
  /// released part's weight stops working on the body at t_r.)
  double released_kinetic = 0.0;
  /// W − (ΔT + ΔV + losses + the released parts' kinetic energy).
  [[nodiscard]] double residual() const {
    return source_work - (kinetic_end - kinetic_start + elastic_end - elastic_start + friction_loss + damping_loss +
                          release_loss + impact_loss + released_kinetic);
  }
};

struct HybridReport {
  bool active = false;                ///< false for a smooth model (no gap, contact or brake)
  std::vector<ModeEvent> events;      ///< in time order; `initial` entries give the modes at t = 0
  std::vector<SlipPhase> slip_phases; ///< in order of start
  EnergyBalance energy;
  std::vector<double> breakpoints;    ///< times where a load, brake or surface table has a kink, s
  /// What the run decided on its own and the user should know (an end stop's bounces that
  /// accumulate and end at rest), one sentence each, in time order.
  std::vector<std::string> warnings;
};

}  // namespace machdyn
