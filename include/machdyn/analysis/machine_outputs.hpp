#pragma once
/// @file
/// Output series of bodies with variable inertia (model/machine.hpp), appended to a simulation's
/// columns after the run, for each machine body NAME:
///   NAME.inertia_kg_m2          I(q)
///   NAME.acceleration_rad_s2    ε = q''
///   NAME.M_PART_N_m             inertia moment of each part, M_k = −I_k ε − ½ I_k′ ω² (paper 004 eq. 5)
///   NAME.POINT_m                the output point: piston displacement from TDC, wheel centre travel x
///   NAME.POINT_speed_m_s        the point's speed p′(q) q' (gear drive: the travel speed)
///   NAME.beta_rad               the rolling wheel's thread angle β
///   NAME.phi_rad, NAME.ratio    the gear drive's carrier angle φ and ratio i = dθ/dφ

#include <functional>

#include "machdyn/analysis/simulate.hpp"

namespace machdyn {

/// Whether the model has a body with variable inertia or a link to a machine's output point.
bool has_machines(const Model& m);

/// Appends the series above to `r` (which holds the standard columns): `accel(row, y, acc)` gives
/// the n accelerations at output row `row` (y = [q; v] there).
void append_machine_outputs(const Model& m, SimulationResult& r,
                            const std::function<void(size_t row, const double* y, double* acc)>& accel);

}  // namespace machdyn
