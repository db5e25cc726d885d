#pragma once
// The heat of every dissipative element over a run: what MSL's HeatLosses examples collect from all
// heat ports at one fixed temperature (heat does not act back on the mechanics). Per element:
//   friction element (contact, brake, clutch, freewheel, stop; not a gear joint): P = F u
//       (elements/contact.hpp; 0 while stuck), plus a stop's impact loss ½ m v⁻² (1 − e²) at its event
//   link with damping (d > 0, or a hydraulic buffer): P = the link law's `dissipation` F_d δ̇
//       (elements/link.hpp, the elasto-backlash cap included), plus the elastic energy its flank
//       releases when it opens at zero force off the flank (the energy books' gap release loss)
//   lossy gear: P = (X − Y) v_a (elements/lossy_gear.hpp `loss_power`)
//   element with states of its own that dissipates (Element::dissipates: a thermal eddy-current brake's
//       −M ω, a DC motor's R i²): P = Element::heat_power
// the heat Q = ∫₀ᵗ P dt + the jumps at events (J), and the total over all elements (W, J): at t_end it
// is what the energy books call dissipated (friction + damping + gap release + impact losses). For a
// friction element with a thermal model also its temperature (elements/thermal.hpp). A piece of the
// run's observer (analysis/run.cpp): each step piece is closed by 3-point Gauss–Legendre quadrature on
// the dense output (exact for P of degree ≤ 5 in t), and output rows inside the open piece add its part.

#include <string>
#include <vector>

#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/elements/thermal.hpp"
#include "machdyn/solve/stepper.hpp"

namespace machdyn::detail {

class Heat {
 public:
  Heat(const Model& m, DriveSystem& sys);
  /// The dissipative elements, in output order: friction elements, links, lossy gears, drives (model order).
  [[nodiscard]] int count() const { return static_cast<int>(names_.size()); }
  [[nodiscard]] const std::string& name(int j) const { return names_[static_cast<size_t>(j)]; }
  /// Whether element j writes NAME.heat_power_W among its own columns already (a thermal eddy-current
  /// brake: Element::output_names), so the heat group adds only its NAME.heat_J.
  [[nodiscard]] bool own_power_column(int j) const { return own_power_[static_cast<size_t>(j)] != 0; }
  /// Whether some element has a thermal model (its temperature is a standard output column).
  [[nodiscard]] bool any_thermal() const { return !thermal_.empty(); }
  /// Adds the piece [ta, tb] of the stepper's last step (tb: the end of the closed part of the run).
  void close_piece(const Stepper& st, double ta, double tb);
  /// The kinetic energy `loss` (J) stop k lost in an impact, and the elastic energy `loss` link l's
  /// flank released when its gap opened (< 0 when it closes off its flank): heat at the event.
  void add_impact(int contact, double loss);
  void add_release(int link, double loss);
  /// Adds the energy element `drive` (Model::drives) released at a switch of its mode (its stored
  /// energy before less after, Element::energy: a gear mesh leaving a flank off it) to its heat.
  void add_drive_release(int drive, double loss);
  /// At t inside the open piece of the current step `st` (nullptr: none open) and state y: per element
  /// P (W) and Q (J) into `power`, `heat` (count() + 1 values each, the last the total; either may be
  /// nullptr), and per element with a thermal model, in the order of the model's contacts, T (K) into
  /// `temperature` (may be nullptr).
  void at(const Stepper* st, double t, const double* y, double* power, double* heat, double* temperature);

 private:
  /// P_j at (t, y) in the current modes (count() values).
  void power(double t, const double* y, double* p);
  /// Advances Q and T over [ta, tb].
  void integrate(const Stepper& st, double ta, double tb, double* heat, double* temperature);

  DriveSystem& sys_;
  int n_;                            // bodies
  std::vector<std::string> names_;
  std::vector<int> contacts_, links_, gears_, drives_;  // the elements' indices in the model, by kind
  std::vector<char> own_power_;      // per element: own_power_column()
  std::vector<int> contact_el_, link_el_;      // per contact / link: its element, −1 if none
  std::vector<int> drive_el_;                  // per Model::drives: its element, −1 if none
  std::vector<int> thermal_;         // elements with a thermal model
  std::vector<ThermalLaw> law_;      // their laws, in that order
  double t_ = 0.0;                   // heat_ and T_ hold the values at t_
  std::vector<double> heat_, T_;     // Q per element, T per thermal element
  std::vector<double> part_heat_, part_T_, p_, acc_, fc_, yq_;
};

}  // namespace machdyn::detail
