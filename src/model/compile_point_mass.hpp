#pragma once
// A load in the plane or in space (`bodies:` entry of `type: point-mass`): a point mass m with two
// or three Cartesian coordinates, each a translational body of mass m of its own, so that the mass
// matrix stays diagonal and every element sees ordinary 1-D bodies (docs/sway.md):
//
//   NAME: {type: point-mass, mass: M, axes: [x, z] | [y, z] | [x, y, z] (default [x, y, z]),
//          position: [..] (m, one per axis, default 0), velocity: [..] (m/s, default 0)}
//
// creates the bodies NAME.x, NAME.y, NAME.z (the axes given, in that order); z points up and
// NAME.z carries the weight −m g (`vertical: up`: the load NAME.z.weight). A spatial rope
// (elements/spatial_rope.hpp) hangs it from its suspension point.
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

/// Whether a `bodies:` entry is a point-mass load (`type: point-mass`).
bool is_point_mass(const SpecNode& spec);

/// Adds the bodies of the point-mass load NAME to m.bodies; every problem into `diag`, located.
void compile_point_mass(const std::string& name, const SpecNode& spec, Model& m, Diagnostics& diag);

}  // namespace machdyn::detail
