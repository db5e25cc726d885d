#pragma once
// Compiler part for a body's `motion:` (prescribed motion; model/model.hpp MotionKind, law in
// elements/prescribed_motion.hpp). Called from compile.cpp; messages follow its conventions.
//
//   motion: {acceleration: SIGNAL}   q'' = a(t), rad/s² or m/s²
//   motion: {speed: SIGNAL}          q' = v(t), rad/s or m/s; the body starts at v(0)
//   motion: {position: SIGNAL}       q = s(t), rad or m (smooth before t_end); starts at s(0), ds/dt(0)
#include <vector>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

/// Reads `motion` of body b from its fields `f` (if given). A prescribed speed sets b.v0 = v(0), a
/// position b.q0 = s(0) and b.v0 = ds/dt(0); a `position` or `velocity` in the file that contradicts
/// them (beyond 1e-9 relative) is a located error. (Smoothness of a position: compile's breakpoint check.)
void read_motion(FieldReader& f, Body& b);

/// The friction elements a prescribed body cannot carry, each a located error: a freewheel or end stop
/// between it and the ground or another prescribed body (a lock against a given motion).
void check_motion_elements(const Model& m, Diagnostics& diag);
/// Lossy gears on a prescribed body (after the ideal-gear merge, which may make a group prescribed),
/// a located error.
void check_motion_lossy(const Model& m, Diagnostics& diag);

}  // namespace machdyn::detail
