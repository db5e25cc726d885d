#pragma once
// The heat of the friction elements over a run (contacts, brakes, clutches, freewheels, stops): per
// element the heat power P = F u (W, the friction force times the sliding speed, 0 while stuck —
// elements/contact.hpp, as the energy books' friction loss), the heat Q = ∫₀ᵗ P dt (J) and, for an
// element with a thermal model, its temperature (elements/thermal.hpp). A piece of the run's observer
// (analysis/run.cpp): each step piece is closed by 3-point Gauss–Legendre quadrature on the dense
// output (exact for P of degree ≤ 5 in t), and output rows inside the open piece add its part.

#include <optional>
#include <vector>

#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/elements/thermal.hpp"
#include "machdyn/solve/stepper.hpp"

namespace machdyn::detail {

class FrictionHeat {
 public:
  FrictionHeat(const Model& m, DriveSystem& sys);
  /// Whether some element has a thermal model (its temperature is a standard output column).
  [[nodiscard]] bool any_thermal() const { return !thermal_.empty(); }
  /// Adds the piece [ta, tb] of the stepper's last step (tb: the end of the closed part of the run).
  void close_piece(const Stepper& st, double ta, double tb);
  /// At t inside the open piece of the current step `st` (nullptr: none open) and state y: per element
  /// P (W) and Q (J) into `power`, `heat` (either may be nullptr), and per element with a thermal model,
  /// in the order of the model's contacts, T (K) into `temperature` (may be nullptr).
  void at(const Stepper* st, double t, const double* y, double* power, double* heat, double* temperature);

 private:
  /// P_k at (t, y) in the current modes.
  void power(double t, const double* y, double* p);
  /// Advances Q and T over [ta, tb].
  void integrate(const Stepper& st, double ta, double tb, double* heat, double* temperature);

  DriveSystem& sys_;
  int nc_;
  std::vector<int> thermal_;         // contacts with a thermal model
  std::vector<ThermalLaw> law_;      // their laws, in that order
  double t_ = 0.0;                   // heat_ and T_ hold the values at t_
  std::vector<double> heat_, T_;     // Q per contact, T per thermal element
  std::vector<double> part_heat_, part_T_, p_, acc_, fc_, yq_;
};

}  // namespace machdyn::detail
