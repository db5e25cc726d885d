#pragma once
// Compiler parts for the hybrid elements: link gaps, friction contacts, brakes, freewheels.
// Called from compile.cpp; the checks and messages follow its conventions.
#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

/// Reads the optional `gap` and `gap_start` fields of a link (qd: the dimension of b's position).
void compile_link_gap(FieldReader& f, Link& l, const Dim& qd);

/// Reads the `contacts:` and `brakes:` sections (either may be null) into m.contacts.
void compile_contacts(const SpecNode* contacts, const SpecNode* brakes, Model& m, Diagnostics& diag);
/// Reads the `freewheels:` section (may be null) into m.contacts (FrictionContact::lock ≠ 0).
/// Checks the initial speeds: a freewheel cannot start turning in its locked direction.
void compile_freewheels(const SpecNode* freewheels, Model& m, Diagnostics& diag);

}  // namespace machdyn::detail
