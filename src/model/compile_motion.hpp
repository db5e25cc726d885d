#pragma once
// Compiler part for a body's `motion:` (prescribed motion; model/model.hpp MotionKind, law in
// elements/prescribed_motion.hpp). Called from compile.cpp; messages follow its conventions.
//
//   motion: {acceleration: SIGNAL}   q'' = a(t), rad/s² or m/s²
//   motion: {speed: SIGNAL}          q' = v(t), rad/s or m/s; the body starts at v(0)
//   motion: {position: SIGNAL}       q = s(t), rad or m (smooth before t_end); starts at s(0), ds/dt(0)
#include <vector>

#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"
#include "model/compile_lossy.hpp"
#include "model/compile_rigid.hpp"

namespace machdyn::detail {

/// Reads `motion` of body b from its fields `f` (if given). A prescribed speed sets b.v0 = v(0), a
/// position b.q0 = s(0) and b.v0 = ds/dt(0); a `position` or `velocity` in the file that contradicts
/// them (beyond 1e-9 relative) is a located error. (Smoothness of a position: compile's breakpoint check.)
void read_motion(FieldReader& f, Body& b);

/// The elements a prescribed body cannot carry yet, each a located error: friction elements (contacts,
/// brakes, clutches, freewheels, stops), ideal and lossy gears (with the file's body indices, before
/// the merge).
void check_motion_elements(const Model& m, const std::vector<IdealGear>& gears, const std::vector<LossyGearSpec>& lossy,
                           Diagnostics& diag);
/// Releases on a prescribed body (after compile_releases), a located error.
void check_motion_releases(const Model& m, Diagnostics& diag);

}  // namespace machdyn::detail
