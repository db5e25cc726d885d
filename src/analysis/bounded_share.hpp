#pragma once
/// @file
/// The share rule of a redundant stuck set over the drive system's contacts (docs/hybrid.md
/// "Redundant locks"): the contacts' bounds and the bounded split (analysis/bounded_split.hpp) that
/// replaces a weighted share leaving one beyond what it holds. Internal to the drive system's
/// evaluation (the plain stuck solve; the gear-coupled one, analysis/gear_clutch.hpp, does not use it
/// yet).
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "machdyn/analysis/bounded_split.hpp"
#include "machdyn/elements/contact.hpp"

namespace machdyn::detail {

/// The bounds of stuck contact c's load at t, as its stick rule (elements/contact.hpp holds(),
/// strict) states them: a friction contact or brake ±F_s(t); a freewheel or end stop lock·λ ≥ −F_d,
/// unbounded in its locking direction; a joint unbounded.
inline void stuck_bounds(const ContactLaw& c, double t, double* lo, double* hi) {
  *lo = -HUGE_VAL, *hi = HUGE_VAL;
  if (c.joint) return;
  if (c.lock > 0) *lo = -c.free_limit();
  else if (c.lock < 0) *hi = c.free_limit();
  else *hi = c.static_limit(t), *lo = -*hi;
}

/// The share rule of a redundant stuck set (docs/hybrid.md "Redundant locks"): when the weighted
/// least-norm share lam (with the one-sided rule) leaves a contact beyond what it holds (strictly,
/// without the rounding allowance: the decision judges a contact whose event fired so), the bounded
/// split (analysis/bounded_split.hpp) with the same weights replaces it if a split within every
/// contact's bounds exists; else lam stays and the mode decision releases the overloaded one. A
/// share within the bounds is not touched.
template <class Matrix, class Weight>
void bound_share(const std::vector<int>& stuck, const std::vector<ContactLaw>& contacts, double t, Eigen::VectorXd& lam,
                 const Eigen::VectorXd& r, Matrix matrix, Weight weight) {
  const auto ns = static_cast<Eigen::Index>(stuck.size());
  bool holds = true;
  for (Eigen::Index j = 0; j < ns && holds; ++j) holds = contacts[static_cast<size_t>(stuck[static_cast<size_t>(j)])].holds(lam(j), t, true);
  if (holds) return;
  Eigen::VectorXd w(ns), lo(ns), hi(ns);
  for (Eigen::Index j = 0; j < ns; ++j) {
    const int k = stuck[static_cast<size_t>(j)];
    w(j) = weight(k);
    stuck_bounds(contacts[static_cast<size_t>(k)], t, &lo(j), &hi(j));
  }
  if (const auto split = bounded_split(matrix(), r, w, lo, hi)) lam = *split;
}

}  // namespace machdyn::detail
