#pragma once
// Compiler part for `releases:`, bodies losing part of their mass at an instant (model/model.hpp:
// Release). Called from compile.cpp once the ideal gears are resolved.
#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

/// Reads the `releases:` section (may be null) into m.releases, sorted by time (file order at equal
/// times): NAME: {body, mass (translational) | inertia (rotational), time}. A release on a body an
/// ideal gear slaves acts on its master through the ratio ρ (ΔI = ρ² Δm, weight change ρ·Δm·g).
/// Located errors: unknown body, ΔI ≤ 0 or the releases of a body reaching its own inertia, a
/// negative time, the other kind's amount field, a body with variable inertia.
void compile_releases(const SpecNode* section, Model& m, Diagnostics& diag);

}  // namespace machdyn::detail
