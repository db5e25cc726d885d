#pragma once
/// @file
/// Root bracketing on a continuous (dense-output) solution: events, extrema of link loads, turning
/// points of the energy integral all locate a sign change of a scalar function.

#include <algorithm>
#include <cmath>

namespace machdyn {

/// The final bracket: f(lo) on the side of f(a), f(hi) on the other side.
struct Bracket {
  double lo, hi;
};

/// Illinois false position (Dowell & Jarratt 1971) on [a, b], where f(a) and f(b) have opposite
/// signs: superlinear on smooth f, never leaves the bracket. With `bisect_every` = k > 0 every k-th
/// iterate is a bisection, so the bracket still shrinks when f has a kink or jump inside (event
/// functions); 0 for a smooth f (load rates). A point where f = 0 counts as on a's side (an element
/// keeps its mode while its event function is ≥ 0). Stops when |hi − lo| ≤ tol or after max_iter.
template <class F>
Bracket illinois(F&& f, double a, double fa, double b, double fb, double tol, int max_iter = 200,
                 int bisect_every = 8) {
  const bool a_nonnegative = fa >= 0.0;
  int side = 0;
  for (int it = 0; it < max_iter && std::abs(b - a) > tol; ++it) {
    double t = fb != fa ? (a * fb - b * fa) / (fb - fa) : 0.5 * (a + b);
    if (!(t > std::min(a, b) && t < std::max(a, b)) || (bisect_every > 0 && it % bisect_every == bisect_every - 1))
      t = 0.5 * (a + b);
    const double ft = f(t);
    if (a_nonnegative ? ft >= 0.0 : ft <= 0.0) {
      a = t, fa = ft;
      if (side == -1) fb *= 0.5;  // the same end moved twice: halve the other's weight
      side = -1;
    } else {
      b = t, fb = ft;
      if (side == 1) fa *= 0.5;
      side = 1;
    }
  }
  return {a, b};
}

}  // namespace machdyn
