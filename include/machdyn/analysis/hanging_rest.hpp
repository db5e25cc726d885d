#pragma once
/// @file
/// The state a topology's linear model is taken about (docs/modes.md, docs/sway.md "Pendulum
/// modes"): the model's initial positions and velocities — except for a load that starts on the
/// floor. A point-mass load on one spatial rope whose z starts on a lower end stop (its position at
/// the stop: resting there, its rope slack or carrying part of the weight) is, in a topology where
/// that stop does not hold it (open, released or sliding off), taken at its hanging rest under the
/// suspension point (SpatialRope::hang: x, y under the point, z = h − (L(φ) + m g/c(φ)), at rest),
/// the drive line at its given positions; so the hanging topology shows the pendulum modes of the
/// hanging load. In the topology with the stop holding the load stays where it starts. A rigid load
/// on the floor, and a load on more than one rope, stay at the start too.

#include <vector>

#include "machdyn/analysis/topology.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// The state y = [q; v] (2n values) to linearize `topo` about, or empty where it is the initial
/// state (every model whose loads start hanging).
std::vector<double> linearization_state(const Model& m, const Topology& topo);

}  // namespace machdyn
