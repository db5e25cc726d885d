#pragma once
// The velocity jump of an end stop's impact on the bodies tied to its body (analysis/run.cpp calls it
// at the stop's event; the stop's own law — v⁺ = −e v⁻, rest, accumulation — is elements/contact.hpp).
//
// An impact is an impulse Λ_s at the stop. The constraints that can carry an impulse pass it on: a
// joint (any impulse), a stuck freewheel or an end stop a body rests on (an impulse pressing into
// its lock, lock·Λ ≥ 0, with no upper limit). A friction contact, a brake or a clutch has a finite
// limit and carries no impulse: a stuck one slides after the impact if the jump gives it a sliding
// velocity; a link's force is finite, so links carry none either. With G the rows of the stop and the
// active ties, M⁻¹ the inverse inertias (0 for a prescribed motion),
//   v⁺ = v⁻ − M⁻¹ Gᵀ Λ,   G v⁺ = u*   (u* = −e u⁻ or 0 for the stop, 0 for every tie: plastic),
// i.e. (G M⁻¹ Gᵀ) Λ = G v⁻ − u* (least-norm Λ where ties are redundant). A one-sided tie whose Λ
// would pull against its lock lets go (it overruns: the partner of a stopped freewheel runs on),
// and a freewheel overrunning before whose relative velocity the jump would turn into its locked
// direction engages (joins the ties); both are repeated until the set is consistent. The energy the
// jump takes is the impact loss (analysis/run.cpp books it).

#include "machdyn/analysis/drive_system.hpp"

namespace machdyn::detail {

/// Puts the velocities of y (state of `sys` at t, the stop's body on the stop) after the impact of
/// end stop k that leaves the stop with sliding velocity `u_out` (−e u⁻, or 0 at rest); `tie(j)`:
/// whether contact j may carry an impulse as a tie (not the run's gear-owned contacts). A stop whose
/// body no tie touches gets v⁺ = u_out exactly.
void impact_jump(const DriveSystem& sys, int k, double u_out, double t, double* y, const std::vector<char>& tie);

}  // namespace machdyn::detail
