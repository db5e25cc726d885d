#pragma once
/// @file
/// The contact-mode decision at an event (the complementarity problem of stick and slip), over the
/// drive system (analysis/drive_system.hpp), with the contact law's stick rule (elements/contact.hpp).
///
/// The contacts in Z have zero sliding velocity at (t, y); all are decided together: they start
/// stuck; while some stuck contact needs more than its static limit, the one with the largest
/// |λ|/F_s is released in the direction of its λ. The result is consistent when every stuck contact
/// of Z holds and every sliding one accelerates in its own direction (s u̇ ≥ 0 within the rounding
/// of u̇ = a_a − a_b, 1e-12 (|a_a| + |a_b|): with μ_s = μ_k a breakaway starts at u̇ = 0); if the release
/// sequence does not end consistent, every combination is tried, fewest sliding contacts first, then
/// in index order. Kinematic contacts in Z (between prescribed motions, elements/contact.hpp) change
/// no acceleration: they are decided first, apart, by ContactLaw::kinematic_mode. Deterministic; no
/// smoothing, no velocity threshold.

#include <vector>

#include "machdyn/analysis/drive_system.hpp"

namespace machdyn {

/// The new modes of all contacts (those outside Z keep theirs). `strict` lists the stuck contacts
/// whose limit event just fired (judged without the rounding allowance). Leaves `sys` in the
/// returned modes. Throws SolverError naming the contacts when no consistent combination exists
/// (or more than 10 contacts are at rest at once and the release sequence failed).
std::vector<ContactMode> decide_contacts(DriveSystem& sys, double t, const double* y, const std::vector<int>& Z,
                                         const std::vector<int>& strict);
/// The same decision into `modes` (overwritten; its capacity reused: no allocation per event).
void decide_contacts(DriveSystem& sys, double t, const double* y, const std::vector<int>& Z,
                     const std::vector<int>& strict, std::vector<ContactMode>& modes);

}  // namespace machdyn
