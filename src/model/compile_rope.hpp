#pragma once
// Compiler part for a rope's reeving and free length (`falls`, `rope_ends`, `sheave_efficiency`, `frame`,
// `length`, `EA` or `elastic_modulus` + `area`).
// Called from compile.cpp for `type: rope`; the law is elements/link.hpp.
#include <vector>

#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

/// Reads a rope's reeving — `falls` (n, default 1), `rope_ends` (n_e on the drum, default 1, n a
/// multiple of it), `sheave_efficiency` (η, default 1; model/reeving.hpp) — its `frame` (a third,
/// translational body the drum hangs from: Link::third with weight 1) and, if given, its free
/// length: `length` (L_f0, one fall, in b's position unit) with `EA` (N) or `elastic_modulus` (Pa)
/// and `area` (m²). The link's ratio becomes (n/n_e) × the file's drum ratio (1/R) and
/// c = n E A / L_f0 (N/m at the hook).
/// Sets l.falls, l.EA, l.length, l.drum_q0 (body a's initial position), l.c. Reports located errors:
/// `length` without EA (or the reverse), both EA and elastic_modulus, `stiffness` beside `length`,
/// a machine's output point as an end, a rotational hook. `bodies` is empty when the ends are invalid.
/// ld, qd: the load and position dimensions of b's side. Returns whether c was set here (the rope
/// then takes no `stiffness`).
bool compile_rope_length(FieldReader& f, Link& l, const Dim& ld, const Dim& qd, BodyKind side,
                         const std::vector<Body>& bodies);

}  // namespace machdyn::detail
