#pragma once
// Compiler hooks for bodies with variable inertia (model/machine.hpp), used by model/compile.cpp.
//   bodies:
//     crank: {type: crank-slider, crank_radius, rod_length, rod_mass, rod_com, rod_inertia,
//             piston_mass, crank_inertia, inertia_model: exact|approximate,
//             piston_force: {against: angle|position, points: [[x, F], ...], period}, position, velocity}
//     wheel: {type: rolling-wheel, scheme: 1|2|3, R1, r1, r2, H, m1, m2, rho, F, beta0, omega0}
//     cam:   {type: inertia-table, points: [[q, I], ...], periodic: true|false, torque, position, velocity}
//     rot:   {type: inertia-expression, inertia: "expr in q", torque: "expr in q", period, position, velocity}
//     drive: {type: gear-drive, gears: FILE | {gear spec fields}, ratio: continuous|stepwise,
//             pinion_inertia, wheel_inertia, mass, resistance, position, velocity}   (model/gear_drive.hpp)
// Links may attach to a machine's output point: `between: [crank.piston, load]`.

#include <string>

#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// Whether the body's `type` names a machine (crank-slider, rolling-wheel, inertia-table, inertia-expression, gear-drive).
bool is_machine_type(const SpecNode& spec);

/// Compiles one machine body; problems go to `diag` with their place.
Body compile_machine_body(const std::string& name, const SpecNode& spec, Diagnostics& diag);

/// Resolves a link end: "BODY" (→ index, *point = false), "BODY.POINT" for a machine's output point
/// (→ index, *point = true), "ground" (kGround). Returns -2 and sets *error if not found.
int resolve_link_end(const Model& m, const std::string& text, bool* point, std::string* error);

}  // namespace machdyn
