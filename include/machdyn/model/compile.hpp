#pragma once
/// @file
/// Spec → Model: validates a model file's tree, converts units to SI, resolves names and reports
/// every problem at once (InputError, with file:line:col for each).
///
/// File layout (YAML):
///   name: text                       description: text
///   bodies:  NAME: {type: rotational|translational, inertia | mass, position, velocity}
///   links:   NAME: {type: spring|damper|spring-damper, between: [A, B], stiffness, damping, ratio}
///   loads:   NAME: {type: constant|step|ramp|table|motor-linear|motor-kloss, body, ...}
///   simulation: {t_end, dt_out, rtol, atol, integrator: auto|dopri5|bdf, max_steps}
/// See docs/model-files.md for every field.

#include <string>
#include <vector>

#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// The sections whose entries are named elements: bodies, links, loads, contacts, brakes. A name is
/// unique across all of them and contains no '.'.
const std::vector<std::string>& element_sections();

/// Compiles a spec tree. Throws InputError listing every problem found, including those of every
/// load case under `cases:` (each compiled on a copy), so a broken case fails every command.
Model compile_model(const SpecNode& root, const std::string& source);

// Reading a model file (and its overrides, cases, gear includes): io/model_file.hpp.

}  // namespace machdyn
