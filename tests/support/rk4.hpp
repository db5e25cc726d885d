#pragma once
/// @file
/// One classical Runge–Kutta step for the tests' independent reference solutions (fixed step, written
/// apart from the library's integrators).

#include <cstddef>

namespace machdyn::test {

/// y(t + h) of y' = f(t, y) by one RK4 step; Y a fixed-size state such as std::array<double, N>
/// (indexable, size()). The sums are formed as y + h/6 (k1 + 2 k2 + 2 k3 + k4).
template <class Y, class F>
Y rk4_step(const F& f, double t, const Y& y, double h) {
  auto add = [](const Y& a, const Y& k, double s) {
    Y r = a;
    for (std::size_t i = 0; i < a.size(); ++i) r[i] = a[i] + s * k[i];
    return r;
  };
  const Y k1 = f(t, y), k2 = f(t + h / 2, add(y, k1, h / 2));
  const Y k3 = f(t + h / 2, add(y, k2, h / 2)), k4 = f(t + h, add(y, k3, h));
  Y r = y;
  for (std::size_t i = 0; i < y.size(); ++i) r[i] = y[i] + h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
  return r;
}

}  // namespace machdyn::test
