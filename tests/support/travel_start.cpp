#include "support/travel_start.hpp"

#include <cmath>
#include <limits>
#include <numbers>

namespace machdyn::paper001 {

double stage2_force(const TravelDrive& d, double tau) {
  const double w2 = std::sqrt(d.c / d.m1);
  return d.P - d.P * std::cos(w2 * tau) + std::sqrt(2 * d.c * d.Delta * d.P) * std::sin(w2 * tau);
}

ExactStages exact_stages(const TravelDrive& d) {
  ExactStages e;
  e.t1 = std::sqrt(2 * d.m1 * d.Delta / d.P);
  e.v1_stage1 = std::sqrt(2 * d.P * d.Delta / d.m1);
  e.omega2 = std::sqrt(d.c / d.m1);
  e.t2 = (std::atan(std::sqrt(d.P / (2 * d.c * d.Delta))) - std::asin((d.P - d.W) / std::sqrt(d.P * (2 * d.c * d.Delta + d.P)))) /
         e.omega2;
  e.v1_stage2 = std::sqrt((2 * d.P * (d.Delta * d.c + d.W) - d.W * d.W) / (d.c * d.m1));
  const double M = d.m1 + d.mk + d.m2;
  e.omega3 = std::sqrt(d.c / d.m1 + d.c / (d.mk + d.m2));
  e.D3 = (d.P * (d.mk + d.m2) + d.W * d.m1) / M;
  e.A3 = d.W - e.D3;
  e.B3 = d.c * e.v1_stage2 / e.omega3;
  e.F_slip = (d.F_sc * (d.mk + d.m2) - d.mk * d.W) / d.m2;
  // First τ > 0 with A3 cos ω3τ + B3 sin ω3τ + D3 = F_slip: R cos(ω3τ − φ) = F_slip − D3.
  const double R = std::hypot(e.A3, e.B3), phi = std::atan2(e.B3, e.A3);
  const double x = (e.F_slip - e.D3) / R;
  if (std::abs(x) > 1) {
    e.t3 = std::numeric_limits<double>::quiet_NaN();
  } else {
    // ω3τ − φ = −acos(x) (rising through the level), taken into [0, 2π).
    double th = phi - std::acos(x);
    while (th < 0) th += 2 * std::numbers::pi;
    e.t3 = th / e.omega3;
  }
  return e;
}

ApproxStages approximate_stage4(const TravelDrive& d, const ExactStages& e) {
  ApproxStages a;
  a.omega4 = std::sqrt(d.c / d.m1 + d.c / d.mk);
  a.D4 = (d.P * d.mk + d.F_d * d.m1) / (d.m1 + d.mk);
  a.A4 = d.F_sc - a.D4;
  const double rate = e.omega3 * (-e.A3 * std::sin(e.omega3 * e.t3) + e.B3 * std::cos(e.omega3 * e.t3));
  a.B4 = rate / a.omega4;
  const double R = std::hypot(a.A4, a.B4);
  a.F4_max = R + a.D4;
  if (a.D4 > R) {
    a.t4 = std::numeric_limits<double>::quiet_NaN();
  } else {
    // R cos(ω4τ − φ) = −D4, first root after the maximum at ω4τ = φ.
    const double phi = std::atan2(a.B4, a.A4);
    double th = phi + std::acos(-a.D4 / R);
    while (th < 0) th += 2 * std::numbers::pi;
    a.t4 = th / a.omega4;
  }
  return a;
}

double approximate_t5(const TravelDrive& d, double vk_minus_v2) {
  return d.m2 * d.mk * vk_minus_v2 / (d.F_d * (d.m2 + d.mk));
}

}  // namespace machdyn::paper001
