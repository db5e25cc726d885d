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
//
// A rigid load in a vertical plane (a long load, a spreader: `type: rigid-load`) is the same with
// its moment of inertia J about its centre and its angle ψ (rad; ψ turns the load's frame from its
// horizontal axis towards z):
//
//   NAME: {type: rigid-load, mass: M, inertia: J, axes: [x, z] (default) | [y, z], position, velocity,
//          angle: ψ0 (0), angular_velocity: ψ0' (0)}
//
// adds the rotational body NAME.psi (inertia J, no weight): the mass matrix stays diagonal in
// (x, z, ψ). A rope's `attach` point on it (in the load's frame) makes ψ swing.
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

/// Whether a `bodies:` entry is a point-mass or rigid load (`type: point-mass`, `type: rigid-load`).
bool is_point_mass(const SpecNode& spec);

/// Adds the bodies of the point-mass or rigid load NAME to m.bodies; every problem into `diag`, located.
void compile_point_mass(const std::string& name, const SpecNode& spec, Model& m, Diagnostics& diag);

}  // namespace machdyn::detail
