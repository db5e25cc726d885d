#pragma once
/// @file
/// The hold rule's allowance of a lock (a freewheel, a backstop, an end stop a body rests on): the
/// one tolerance its stick rule (elements/contact.hpp), the invariant audit (analysis/audit.hpp) and
/// the reference simulator (tests/reference) read.
///
/// A stuck lock holds while lock·λ ≥ −F_d (F_d its drag at rest, 0 for an end stop). Its load λ is
/// formed from the forces of the links on its bodies, c δ + d δ̇ (N or N·m), and the integrator
/// holds every state only to its absolute tolerance atol (m or rad, m/s or rad/s): δ and δ̇ are
/// known to about atol each, so λ is known to about
///
///   ε_h = k · atol,   k = Σ (c + d·1 s⁻¹) over the links on the lock's bodies (N/m or N·m/rad),
///
/// and a load within ε_h of the limit is at it. A smaller allowance decides on the integration's
/// noise: a freewheel carrying nothing beside a backstop that holds the load (its bodies at rest,
/// λ = 0 exactly) reads λ = ±1.5e-9 N from positions known to 1e-12 m through springs of
/// 4e4 N/m, and with the former 1e-9 N it "overran" and re-locked every few ms (campaign
/// `freewheel` seed 1 #103, seed 3 #22; tests/analysis/hold_allowance_test.cpp). The floor 1e-9
/// (N or N·m) keeps the rule's rounding allowance where k·atol is smaller (an unloaded lock at
/// λ = −1e-15 beside a clutch that just broke away starts armed). A real violation is a load
/// beyond the limit by far more (1.01 F_d of a drag of 1 N: 1e-2 N against ε_h ~ 1e-8 N).
///
/// k: stiffness and damping summed, each link on the lock's bodies once (one between its two bodies
/// too), at its b side, else at its a side with 1/i² (its force acts on a as F/i); the damping's d
/// counts per 1 s (a rate known to atol in m/s); `stiffness` ≥ 0, `atol` > 0; returns N or N·m.

#include <algorithm>

namespace machdyn {

[[nodiscard]] inline double hold_allowance(double stiffness, double atol) {
  return std::max(1e-9, stiffness * atol);
}

}  // namespace machdyn
