#pragma once
// Compiler of the section `drives:` (model/model.hpp `Drive`): elements with states of their own
// acting on one body, each of a registered type (model/element_types.hpp: DC motors, speed drives,
// …), whose own compile function reads its fields. Called from compile.cpp; messages follow its
// conventions.
//
//   NAME: {type: TYPE, body: BODY, ...the type's fields}
#include <optional>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

/// The types a `type:` under `drives:` may name: every registered element type.
std::vector<std::string> drive_types();

/// Reads `drives:` into m.drives; every problem into `diag`, located.
void compile_drives(const SpecNode* section, Model& m, Diagnostics& diag);

/// A required signal field of an element: a quantity of dimension d or a map with `type:`; a missing
/// or bad one is reported located (nullopt).
std::optional<Signal> signal_field(FieldReader& f, const char* key, const Dim& d);

}  // namespace machdyn::detail
