#pragma once
// The dimensions of a body's position, velocity and load by its kind, what the model compiler checks
// a field's units against (private to src/): rad, rad/s, N·m for a rotational body; m, m/s, N for a
// translational one. model/model.hpp's position_unit, velocity_unit, load_unit print the same units.
#include "machdyn/common/units.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

inline Dim position_dim(BodyKind k) { return k == BodyKind::rotational ? dim::none : dim::length; }
inline Dim velocity_dim(BodyKind k) { return k == BodyKind::rotational ? dim::angular_velocity : dim::velocity; }
inline Dim load_dim(BodyKind k) { return k == BodyKind::rotational ? dim::torque : dim::force; }

}  // namespace machdyn::detail
