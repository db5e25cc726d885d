#include "support/three_mass_hoist.hpp"

#include <cmath>

namespace machdyn::paper002 {

std::array<double, 2> natural_frequencies(const ThreeMassHoist& h) {
  const double s = h.c1 / h.I1 + h.c1 / h.I2 + h.c2 / h.I2 + h.c2 / h.I3;
  const double P = h.c1 * h.c2 * (h.I1 + h.I2 + h.I3) / (h.I1 * h.I2 * h.I3);
  const double root = std::sqrt(s * s - 4.0 * P);
  const double w2_high = 0.5 * (s + root);
  const double w2_low = 2.0 * P / (s + root);  // = ½ (s − root), without cancellation
  return {std::sqrt(w2_low), std::sqrt(w2_high)};
}

std::array<double, 2> particular_loads(const ThreeMassHoist& h) {
  const double I = h.I1 + h.I2 + h.I3;
  return {h.M_B + (h.I2 + h.I3) * (h.M_sp - h.M_B) / I, h.I3 * (h.M_sp - h.M_B) / I};
}

ThreeMassSolution::ThreeMassSolution(const ThreeMassHoist& h, double x1_0, double x2_0, double x1dot_0,
                                     double x2dot_0)
    : h_(h), w_(natural_frequencies(h)) {
  const double a11 = h.c1 * (1 / h.I1 + 1 / h.I2), a12 = h.c2 / h.I2, a21 = h.c1 / h.I2,
               a22 = h.c2 * (1 / h.I2 + 1 / h.I3);
  const double b1 = h.M_sp / h.I1 + h.M_B / h.I2, b2 = -h.M_B / h.I2;
  // x* solves A x* + b = 0 with A = [[−a11, a12], [a21, −a22]].
  const double detA = a11 * a22 - a12 * a21;
  xs_ = {(a22 * b1 + a12 * b2) / detA, (a21 * b1 + a11 * b2) / detA};
  for (int k = 0; k < 2; ++k) u_[k] = {a12, a11 - w_[k] * w_[k]};
  // U C = x(0) − x*, U diag(ω) S = x'(0), U = [u_0 u_1] (columns).
  const double det = u_[0][0] * u_[1][1] - u_[1][0] * u_[0][1];
  auto solve = [&](double r0, double r1) {
    return std::array<double, 2>{(r0 * u_[1][1] - u_[1][0] * r1) / det, (u_[0][0] * r1 - r0 * u_[0][1]) / det};
  };
  C_ = solve(x1_0 - xs_[0], x2_0 - xs_[1]);
  const auto v = solve(x1dot_0, x2dot_0);
  S_ = {v[0] / w_[0], v[1] / w_[1]};
}

std::array<double, 2> ThreeMassSolution::x(double t) const {
  std::array<double, 2> r = xs_;
  for (int k = 0; k < 2; ++k) {
    const double a = C_[k] * std::cos(w_[k] * t) + S_[k] * std::sin(w_[k] * t);
    r[0] += u_[k][0] * a;
    r[1] += u_[k][1] * a;
  }
  return r;
}

double ThreeMassSolution::M12(double t) const { return h_.c1 * x(t)[0]; }
double ThreeMassSolution::M23(double t) const { return h_.c2 * x(t)[1]; }

}  // namespace machdyn::paper002
