#pragma once
/// @file
/// The optional output columns a drive engineer puts in a report, beyond the positions, velocities
/// and link loads every run writes. Off by default (the default files stay small and the output
/// rows of the plain run stay a copy of the state); `machdyn simulate --outputs LIST` turns groups on.
/// Each value comes from the one statement of its element's law, in the modes in force at the row:
///   deflection:   per link  NAME.deflection_rad|m = δ and NAME.deflection_rate_rad_s|m_s = δ̇
///                 (elements/link.hpp: δ = p_a(q_a)/i − p_b(q_b), in b's coordinate)
///   acceleration: per body  NAME.acceleration_rad_s2|m_s2 = the right-hand side M⁻¹ f at the row
///                 (with stuck contacts their constraint forces; not a finite difference)
///   power:        per load and per drive  NAME.power_W = M v (W; > 0: it drives the body), and per
///                 link with damping  NAME.damping_power_W = F_d δ̇ (the link law's dissipation, a
///                 winding rope's with the stiffness of its current free length)
///   heat:         per dissipative element  NAME.heat_power_W = P (W, ≥ 0) and NAME.heat_J = ∫₀ᵗ P dt
///                 plus its losses at events (J), and the model's total  heat_power_W, heat_J: friction
///                 elements (contact, brake, clutch, freewheel, stop) P = F u (0 while stuck; a stop's
///                 impact loss), links with damping P = F_d δ̇ (the gap release loss of a flank that
///                 opens off the flank), lossy gears P = (X − Y) v_a, drives that dissipate P =
///                 Element::heat_power (a thermal eddy-current brake's −M ω, whose NAME.heat_power_W is
///                 already its own column; a DC motor's R i²) (analysis/heat.hpp); integrated by
///                 3-point Gauss–Legendre quadrature on the dense output of every step piece (exact for
///                 loads and speeds of degree ≤ 5 in t; otherwise to the integrator's tolerance, as the
///                 energy books' losses, whose sum the total heat_J equals at t_end).

#include <string>
#include <vector>

#include "machdyn/analysis/simulate.hpp"

namespace machdyn {

/// Which groups of extra columns a run writes (all off: the plain run).
struct OutputSelection {
  bool deflection = false;
  bool acceleration = false;
  bool power = false;
  bool heat = false;
  [[nodiscard]] bool any() const { return deflection || acceleration || power || heat; }
};

/// The group names accepted by `--outputs` (and "all").
inline const std::vector<std::string>& output_group_names() {
  static const std::vector<std::string> names{"deflection", "acceleration", "power", "heat", "all"};
  return names;
}

/// The selection from group names ("deflection", "acceleration", "power", "heat", "all").
/// Throws InputError (located at `--outputs`) for an unknown name.
OutputSelection output_selection(const std::vector<std::string>& groups);

/// The number of extra columns `s` adds to a run of `m`, at most.
std::size_t extra_columns_bound(const Model& m, const OutputSelection& s);

/// simulate(m, options) with the extra columns of `extra` appended after the standard ones (the
/// same run: the standard columns, peaks, events and energies are the same numbers). Throws
/// InputError (at `--outputs`) when the widened output grid would exceed kMaxOutputBytes in memory.
SimulationResult simulate(const Model& m, const SimulateOptions& options, const OutputSelection& extra);

}  // namespace machdyn
