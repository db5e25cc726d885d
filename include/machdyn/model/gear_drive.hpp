#pragma once
/// @file
/// The drive of the wheel-walking propulsor (paper 003) as a machine with variable reduced inertia:
/// a pinion (angle θ, the body's coordinate) drives the carrier (angle φ) through a non-circular
/// gear pair, and the carrier moves the hub by the walking mechanism's travel X(φ).
///
/// Kinematics. The gear pair gives φ(θ):
///  - continuous ratio: φ = φ(θ) the inverse of θ(φ) = ∫ i dφ, dφ/dθ = 1/i(φ) (gears/ratio_law.hpp);
///  - stepwise ratio (one circular arc per tooth, the synthesized sectors of gears/synthesis.hpp):
///    in sector j the two sector circles r_Hj, r_j roll on each other, so φ is linear in θ with
///    dφ/dθ = 1/i_j, i_j = Δθ_j/Δφ_j; φ(θ) is continuous and passes through every (θ_j, φ_j).
///    The last sector of a big sector is closed onto the next big sector's first boundary
///    (θ_1 − Θ, φ_1 − T), which changes its ratio by the synthesis defect (≤ tolerance/Δθ).
/// The hub travel (paper eq. 2, walking law, lengths a, b, c): with A = a − b + c, B = 3b,
///   X′(φ) = dX/dφ = A + B cos 2φ,  X(φ) = A φ + (B/2) sin 2φ   for φ in the big sector [−T/2, T/2],
/// repeated with the increment X_T = A T + B sin T per big sector (X(0) = 0 at θ = 0).
///
/// Reduced inertia about θ, with g = dφ/dθ and X_θ = dX/dθ = X′ g:
///   I(θ) = I_p + I_H g² + m X_θ²                          (parts pinion, wheel, vehicle)
///   I′(θ) = 2 I_H g g′ + 2 m X_θ X_θθ,   X_θθ = X″ g² + X′ g′
/// g′ = −i′/i³ (continuous), 0 inside a sector (stepwise). The resistance to travel F_r (N, acting
/// against +X: rolling resistance while the vehicle moves forward, or a slope) gives
/// Q(θ) = −F_r X_θ. The output point `travel` is X (m).
///
/// With the continuous ratio of the walking law X_θ = A/u is constant (the synthesis' purpose), so
/// I varies only through I_H/i²; at constant pinion speed the travel speed is exactly constant.
///
/// Ratio jumps (stepwise). At a sector boundary the contact passes to the next pair of circles and
/// the velocity ratio jumps from i− to i+ (the sides seen in the direction of motion). The new pair
/// of teeth meets with an impulse Λ at its contact, normal to the new rolling constraint
/// r+ θ' = r_H+ φ' (rigid teeth, no rebound: the constraint holds afterwards). With J_H(φ) =
/// I_H + m X′(φ)² the carrier-side inertia about φ (the vehicle moves with the carrier, finite forces
/// such as the motor torque, loads and elastic links give no impulse):
///   I_p (θ'+ − θ'−) = −Λ r+,   J_H (φ'+ − φ'−) = +Λ r_H+,   θ'+ = i+ φ'+,   φ'− = θ'−/i−
/// Eliminating Λ (r+/r_H+ = 1/i+):
///   (I_p + J_H/i+²) θ'+ = (I_p + J_H/(i− i+)) θ'−
/// — the momentum of the pre-impact motion along the new constraint is kept (a perfectly plastic
/// impact, Carnot): the kinetic energy lost is ½ I_p (Δθ')² + ½ J_H (Δφ')² ≥ 0, and vanishes only for
/// i+ = i−. This is the idealisation of rigid, backlash-free teeth; real teeth spread it over the
/// mesh stiffness.

#include <vector>

#include "machdyn/gears/gear_model.hpp"
#include "machdyn/gears/synthesis.hpp"
#include "machdyn/model/machine.hpp"

namespace machdyn {

class GearDrive final : public Machine {
 public:
  enum class Ratio { continuous, stepwise };
  struct Params {
    double I_p = 0.0;  ///< pinion and everything rigid with its shaft (motor rotor, flywheel), kg·m², > 0
    double I_H = 0.0;  ///< driven wheel (carrier) about its axis, kg·m², ≥ 0
    double m = 0.0;    ///< mass moved with the hub travel X (the vehicle's share), kg, ≥ 0
    double F_r = 0.0;  ///< resistance to travel, N, acting against +X
    Ratio ratio = Ratio::continuous;
  };

  /// `gear_model` must have the walking law (law.kind() == Walking); `synthesis` its sector table.
  GearDrive(Params p, gears::GearModel gear_model, const gears::GearSynthesis& synthesis);

  [[nodiscard]] std::string type() const override { return "gear-drive"; }
  [[nodiscard]] int parts() const override { return 3; }
  [[nodiscard]] std::string part_name(int k) const override;
  void part_inertia(int k, double q, double* I, double* dI) const override;
  [[nodiscard]] double force(double q) const override;
  [[nodiscard]] std::string point_name() const override { return "travel"; }
  void point(double q, double* p, double* dp, double* ddp) const override;
  [[nodiscard]] std::vector<std::string> extra_names() const override { return {"phi_rad", "ratio"}; }
  void extras(double q, double* out) const override;
  [[nodiscard]] double period() const override { return Theta_; }
  [[nodiscard]] bool reports_point_speed() const override { return true; }
  [[nodiscard]] bool has_jumps() const override { return p_.ratio == Ratio::stepwise; }
  [[nodiscard]] double next_jump(double q, int dir) const override;
  [[nodiscard]] double velocity_after_jump(double qj, int dir, double w, double* loss) const override;

  /// The kinematics at θ: φ, g = dφ/dθ, g′ = d²φ/dθ². Stepwise: the sector containing θ, sectors
  /// closed on the left (at a boundary, the sector above it).
  struct Kinematics {
    double phi, g, dg;
  };
  [[nodiscard]] Kinematics kinematics(double theta) const;
  /// X(φ), X′(φ), X″(φ) of the walking mechanism, m, m/rad, m/rad².
  void travel(double phi, double* X, double* dX, double* ddX) const;
  /// The ratio on the side `dir` (±1) of the jump position qj (a sector boundary).
  [[nodiscard]] double ratio_beside(double qj, int dir) const;
  [[nodiscard]] const Params& params() const { return p_; }
  [[nodiscard]] const gears::GearModel& gear_model() const { return gears_; }

 private:
  /// θ reduced to the big sector: θ = k Θ + θw with θw in [B_0, B_0 + Θ).
  [[nodiscard]] double reduce(double theta, double* k) const;
  /// Index m of the stepwise segment [B_m, B_{m+1}) containing θw.
  [[nodiscard]] size_t segment(double theta_w) const;

  Params p_;
  gears::GearModel gears_;
  double T_, Theta_;      ///< big sector of the wheel and the pinion turn over it, rad
  double A_, B_;          ///< X′ = A + B cos 2φ, m/rad
  double XT_;             ///< travel per big sector, m
  // Stepwise segments over one big sector in increasing θ: [B_m, B_{m+1}] ↔ [P_m, P_{m+1}], ratio i_m.
  std::vector<double> Bth_, Pphi_, iseg_;
};

}  // namespace machdyn
