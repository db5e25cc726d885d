#pragma once
/// @file
/// The lumped thermal model of a friction element (brake disc, clutch plates, a wheel on its rail):
/// one heat capacity C at one temperature T, heated by the element's friction power and cooled to the
/// surroundings at T_a through the conductance G (convection and radiation lumped, G = h A):
///   C dT/dt = P(t) − G (T − T_a)            (C in J/K, G in W/K, T and T_a in K, P in W)
/// P = F u ≥ 0 is the element's heat power (elements/contact.hpp: the friction force times the sliding
/// speed; 0 while stuck). The temperature is an output: it does not act back on the friction.
///
/// Over a piece [t0, t1] of a run, with P given on it, the linear equation integrates exactly to
///   T(t1) = T_a + (T(t0) − T_a) e^{−(t1−t0)/τ} + (1/C) ∫_{t0}^{t1} e^{−(t1−s)/τ} P(s) ds,   τ = C/G
/// (variation of constants; G = 0, adiabatic: T(t1) = T(t0) + (1/C) ∫ P ds). The run evaluates the
/// integral by quadrature on the integrator's dense output (analysis/heat.hpp).
/// Valid for C > 0, G ≥ 0, T_a ≥ 0 (compile checks them). Nothing is thrown.

#include <cmath>

#include "machdyn/model/model.hpp"

namespace machdyn {

struct ThermalLaw {
  double C;   ///< heat capacity, J/K
  double G;   ///< conductance to the surroundings, W/K
  double Ta;  ///< ambient temperature, K

  explicit ThermalLaw(const ThermalMass& p) : C(p.heat_capacity), G(p.conductance), Ta(p.ambient) {}

  /// e^{−G dt / C}: how much of a temperature excess over T_a is left after dt (1 when adiabatic).
  [[nodiscard]] double decay(double dt) const { return G > 0.0 ? std::exp(-G * dt / C) : 1.0; }
  /// The temperature after dt without heating: T_a + (T − T_a) e^{−dt/τ}.
  [[nodiscard]] double relax(double T, double dt) const { return Ta + (T - Ta) * decay(dt); }
  /// The rise at the end of a piece from a heat `weight · P` (J) put in `before_end` seconds earlier:
  /// one quadrature term of (1/C) ∫ e^{−(t1−s)/τ} P(s) ds.
  [[nodiscard]] double rise(double heat, double before_end) const { return heat * decay(before_end) / C; }
  /// dT/dt at temperature T under the heat power P (the law itself; tests and docs).
  [[nodiscard]] double rate(double T, double P) const { return (P - G * (T - Ta)) / C; }
};

}  // namespace machdyn
