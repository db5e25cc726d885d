#pragma once
// Compiler parts for the crane elements: buffers (one-sided springs to the ground) and the `crane:`
// section of the crane analysis. Called from compile.cpp; the checks and messages follow its
// conventions.
#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

/// Reads the `buffers:` section (may be null) into m.links (Link::buffer, law in model/model.hpp and
/// elements/link.hpp). A body may not start beyond its buffer's position.
void compile_buffers(const SpecNode* buffers, Model& m, Diagnostics& diag);
/// Reads the `crane:` section (may be null) into m.crane; names are checked against m's bodies and
/// links (call after links, loads and buffers).
void compile_crane(const SpecNode* crane, Model& m, Diagnostics& diag);

}  // namespace machdyn::detail
