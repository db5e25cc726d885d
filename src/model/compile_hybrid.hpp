#pragma once
// Compiler parts for the hybrid elements: link gaps, friction contacts, brakes, freewheels.
// Called from compile.cpp; the checks and messages follow its conventions.
#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

/// Reads the optional `gap` and `gap_start` fields of a link, or its `flank` (a one-sided link, any
/// sign; model/model.hpp Link::tension_only) (qd: the dimension of b's position).
void compile_link_gap(FieldReader& f, Link& l, const Dim& qd);

/// Reads the `contacts:` and `brakes:` sections (either may be null) into m.contacts.
void compile_contacts(const SpecNode* contacts, const SpecNode* brakes, Model& m, Diagnostics& diag);
/// Reads the `clutches:` section (may be null) into m.contacts (FrictionContact::clutch): friction
/// between two bodies by a normal force f_N(t), μ_s, μ_k, radius and number of surfaces.
void compile_clutches(const SpecNode* clutches, Model& m, Diagnostics& diag);
/// After the simulation settings: scales the levels of contacts applied by a normal-force signal to
/// its largest magnitude over [0, t_end] and sets FrictionContact::t_apply (the first time r > 0).
void finish_applications(Model& m);
/// Reads the `freewheels:` section (may be null) into m.contacts (FrictionContact::lock ≠ 0).
/// Checks the initial speeds: a freewheel cannot start turning in its locked direction.
void compile_freewheels(const SpecNode* freewheels, Model& m, Diagnostics& diag);
/// Reads the `stops:` section (may be null) into m.contacts (FrictionContact::stop). Checks that
/// the initial state is on the allowed side and not moving into the stop.
void compile_stops(const SpecNode* stops, Model& m, Diagnostics& diag);

}  // namespace machdyn::detail
