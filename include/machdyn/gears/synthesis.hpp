#pragma once
/// @file
/// Sector synthesis of paper 003: each pitch curve is split into one-tooth circular-arc sectors of
/// equal arc length, by the paper's successive approximations. Over one big sector of the wheel,
/// φ from φ_1 = T/2 down to −T/2 (T = 2π/N), with n = z_H/N sectors:
///
///  Wheel (eqs. 21–31): φ_{j+1} = φ_j − Δφ_j, r_Hj = r_H(φ_j − Δφ_j/2) from the law, equal arcs
///    r_Hj Δφ_j = r_H1 Δφ_1 (eq. 25–26: each Δφ_j by fixed-point iteration), ΣΔφ_j = T.
///    Start Δφ_1 = T/n (eq. 27), then Δφ_1 ← Δφ_1 + ω (T − ΣΔφ)/n (eqs. 29–30, ω = 0.5 as the paper;
///    halved if the defect grows), until |T − ΣΔφ| ≤ tolerance (eq. 31).
///  Pinion (eqs. 39–51): the arcs of the pinion sectors equal the wheel's and r_Hj + r_j = L, so
///    L Δφ_j Δθ_j/(Δφ_j + Δθ_j) = l for all j, i.e. Δθ_j = C Δφ_j/(Δφ_j − C), C = l/L; ΣΔθ_j = Θ.
///    Start Δθ_1 = Θ/n (eq. 48), update Δθ_1 ← Δθ_1 + ω (Θ − ΣΔθ)/n (eq. 50) until |Θ − ΣΔθ| ≤ tol.
///    Then r_Hj = L Δθ_j/(Δφ_j + Δθ_j) (eq. 41–42), r_j = L − r_Hj (eq. 43–44), θ_1 = θ(T/2),
///    θ_{j+1} = θ_j − Δθ_j (eqs. 45–47).
///  Check (eq. 52): l = r_Hj Δφ_j = r_j Δθ_j for every j. The module of the teeth is m = l/π.
/// For the paper's data (L = 143.5 mm, a, b, c = 60, 100, 360 mm, z = 48, z_H = 96) this is Table 1.
///
/// Throws InputError (at the blamed spec field) when the approximations do not converge or the
/// result is not a gear: a pinion root radius r_j − h_f m ≤ 0, or an installed distance that
/// separates the pitch curves by a module or more.

#include <vector>

#include "machdyn/gears/gear_model.hpp"

namespace machdyn::gears {

/// One row of Table 1 (SI: rad, m).
struct Sector {
  int i = 0;            ///< sector number 1..n
  double phi = 0.0;     ///< φ_i, wheel angle at the sector's start, rad
  double dphi = 0.0;    ///< Δφ_i, rad
  double rH = 0.0;      ///< r_Hi, m
  double theta = 0.0;   ///< θ_i, pinion angle at the sector's start, rad
  double dtheta = 0.0;  ///< Δθ_i, rad
  double r = 0.0;       ///< r_i, m
  double rH_law = 0.0;  ///< r_H(φ_i − Δφ_i/2) of the law, used in the wheel split, m
};

struct GearSynthesis {
  std::vector<Sector> sectors;  ///< one big sector, n rows (the paper's Table 1)
  double arc = 0.0;             ///< l, the common arc length of all sectors (eq. 52), m
  double module = 0.0;          ///< m = l/π, m
  int wheel_cycles = 0;         ///< outer cycles of the wheel split (eqs. 29–31)
  int pinion_cycles = 0;        ///< cycles of the pinion split (eqs. 50–51)
  double wheel_defect = 0.0;    ///< T − ΣΔφ at the end, rad
  double pinion_defect = 0.0;   ///< Θ − ΣΔθ at the end, rad
  double eq52_deviation = 0.0;  ///< max_j |r_Hj Δφ_j − l|, |r_j Δθ_j − l|, divided by l
  double closure = 0.0;         ///< θ(T/2) − θ(−T/2) − Θ, rad (0 when the law closes)
};

GearSynthesis synthesize(const GearModel& m);

/// The stepwise ratio of the synthesized pair at wheel angle φ: i_j = Δθ_j/Δφ_j = r_Hj/r_j of the
/// sector containing φ (periodic).
double stepwise_ratio(const GearModel& m, const GearSynthesis& s, double phi);

/// Travel-speed uniformity at constant pinion speed ω (the kinematic question of the paper's Fig. 2).
/// V(φ) = (dX/dφ)·ω/i(φ) for i the continuous law, the stepwise ratio, or the constant ratio
/// z_H/z of circular gears; V̄ = ω X_T/Θ (time average over a big sector, X_T = ∫ dX/dφ over it);
/// δ = (V_max − V_min)/V̄. Available only for laws derived from a travel law (walking, travel).
struct SpeedUniformity {
  bool available = false;
  double omega = 0.0;   ///< pinion speed, rad/s
  double mean = 0.0;    ///< V̄, travel unit per second (m/s for the walking law)
  double continuous_min = 0.0, continuous_max = 0.0, continuous_delta = 0.0;
  double stepwise_min = 0.0, stepwise_max = 0.0, stepwise_delta = 0.0;
  double circular_delta = 0.0;  ///< with circular gears of the same mean ratio
};
SpeedUniformity speed_uniformity(const GearModel& m, const GearSynthesis& s);

/// Points of the continuous pitch curves, each in its own body frame (x, y in m): the wheel at
/// body angle β = −φ and radius r_H(φ), the pinion at β = π + θ and radius r(θ), for a whole turn.
/// With the pinion centre at (L, 0) both frames are the space frame at φ = θ = 0.
struct PitchCurves {
  std::vector<double> wheel_x, wheel_y, pinion_x, pinion_y;
};
PitchCurves sample_pitch_curves(const GearModel& m, int points_per_big_sector);

}  // namespace machdyn::gears
