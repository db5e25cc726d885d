#pragma once
// Compiler of the elements behind the one interface (model/model.hpp `Drive`, model/element.hpp),
// each of a registered type (model/element_types.hpp) whose own compile function reads its fields:
// on one body under `drives:` (DC motors, speed drives, …), between two under `links:` (a gear
// mesh). Called from compile.cpp; messages follow its conventions.
//
//   drives:  NAME: {type: TYPE, body: BODY, ...the type's fields}
//   links:   NAME: {type: TYPE, between: [A, B], ...the type's fields}
#include <optional>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

/// The types a `type:` under `drives:` may name: every registered element type on one body.
std::vector<std::string> drive_types();

/// Reads `drives:` into m.drives; every problem into `diag`, located.
void compile_drives(const SpecNode* section, Model& m, Diagnostics& diag);

/// Whether `type` is a registered element type between two bodies (written under `links:`).
bool is_link_element_type(std::string_view type);

/// Reads the `links:` entry NAME of a registered two-body type (`between: [A, B]`, its port 0 on A,
/// port 1 on B; both bodies with inertia of their own, or A the ground-free body of an ideal gear's
/// merge) into m.drives; every problem into `diag`, located.
void read_link_element(const std::string& name, const SpecNode& spec, Model& m, Diagnostics& diag);

/// Whether `type` is a registered element type whose own fields name its bodies (ElementType::place:
/// a spatial rope), written under `links:`.
bool is_placed_element_type(std::string_view type);

/// Reads the `links:` entry NAME of such a type into m.drives (its ports on the bodies its place
/// function names); every problem into `diag`, located. Called after `gravity:` is compiled.
void read_placed_element(const std::string& name, const SpecNode& spec, Model& m, Diagnostics& diag);

/// A required signal field of an element: a quantity of dimension d or a map with `type:`; a missing
/// or bad one is reported located (nullopt).
std::optional<Signal> signal_field(FieldReader& f, const char* key, const Dim& d);

}  // namespace machdyn::detail
