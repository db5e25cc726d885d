#pragma once
// Compiler of the section `drives:` (model/model.hpp `Drive`): DC motors and speed-controlled drives,
// torque sources with states of their own. Called from compile.cpp; messages follow its conventions.
//
//   NAME: {type: dc-motor, body, resistance, inductance, motor_constant, voltage (signal),
//          initial_current (0)}
//   NAME: {type: speed-drive, body, reference (signal), gain, integral_time, torque_limit (none),
//          rise_time (0), initial_torque (0)}
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

/// The drive types a `type:` under `drives:` may name.
const std::vector<std::string>& drive_types();

/// Reads `drives:` into m.drives; every problem into `diag`, located.
void compile_drives(const SpecNode* section, Model& m, Diagnostics& diag);

}  // namespace machdyn::detail
