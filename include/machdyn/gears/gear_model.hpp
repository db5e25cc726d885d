#pragma once
/// @file
/// A non-circular gear pair, compiled from a spec file (the paper 003 data or any ratio law) into a
/// validated, immutable model. Symbols follow the paper: φ driven wheel (carrier, index H) angle,
/// θ pinion angle, i(φ) = dθ/dφ = r_H/r, L the centre distance, z pinion teeth, z_H wheel teeth.
/// All quantities are SI (m, rad, rad/s).
///
/// Spec fields (top level of the YAML file):
///   law          walking | travel | expression | table            (default walking)
///   a, b, c      lengths, law walking: hub-to-crank distance, crank, shoe strut
///   travel       expression of phi, law travel: the travel per carrier angle dX/dφ (any unit)
///   ratio        expression of phi, law expression: i(φ) or its shape
///   ratio_table  [[φ, i], ...], law table: one big sector, φ with an angle unit
///   normalize    true | false (default false): scale an expression/table law so that it closes
///   L            calculation centre distance (length, > 0)
///   L_installed (or clearance = L_installed − L)  installation centre distance (length, default L, L ≤ L_installed < L + m)
///   z, zH        teeth of the pinion and of the wheel
///   sectors      number N of big sectors of the wheel (default 4); z_H/N teeth per big sector
///   tolerance    angle, the successive approximations stop below it (default 1e-6 rad, as the paper)
///   max_iterations  cap of the successive approximations (default 10000)
///   pinion_speed angular velocity of the pinion for the speed report (default 1 rad/s)
///   profile      map: basis (stepwise | continuous, default stepwise), pressure_angle (20 deg),
///                addendum (coefficient h_a*, 1), dedendum (coefficient h_f*, 1.25), points (per flank, 12)
///
/// compile_gears() reports every problem at once as InputError with file:line:col: missing/unknown
/// fields, wrong units, tooth counts that do not divide into big sectors, a ratio law that is not
/// positive, does not repeat across the big sector, or does not close (∫ i dφ over a big sector must
/// equal Θ = 2π z_H/(z N), the pinion turn per big sector).

#include <string>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/spec.hpp"
#include "machdyn/gears/ratio_law.hpp"

namespace machdyn::gears {

/// How tooth flanks are generated.
enum class ProfileBasis {
  Stepwise,    ///< the paper's construction: each tooth on its own circular arc (radius r_Hj or r_j)
  Continuous,  ///< the rack rolls on the smooth pitch curve of the ratio law (needs a convex, C¹ curve)
};

struct ProfileSettings {
  ProfileBasis basis = ProfileBasis::Stepwise;
  double pressure_angle = 0.0;  ///< α, rad
  double addendum = 1.0;        ///< h_a*, in modules
  double dedendum = 1.25;       ///< h_f*, in modules
  int points = 12;              ///< points per flank
};

/// Where the values that later checks may blame came from (for file:line:col in messages).
struct GearPlaces {
  Location root, law, L, L_installed, z, zH, basis;
};

struct GearModel {
  RatioLaw law;             ///< i(φ), periodic with T = 2π/N
  double L = 0.0;           ///< calculation centre distance, m
  double L_installed = 0.0; ///< installation centre distance, m
  int z = 0;                ///< pinion teeth
  int zH = 0;               ///< wheel teeth
  int N = 4;                ///< big sectors of the wheel
  int n = 0;                ///< teeth (sectors) per big sector = z_H/N (the paper's i = 24)
  double tolerance = 1e-6;  ///< rad
  int max_iterations = 10000;
  double pinion_speed = 1.0;  ///< rad/s
  ProfileSettings profile;
  GearPlaces where;

  [[nodiscard]] double T() const { return law.period(); }           ///< 2π/N
  [[nodiscard]] double Theta() const { return law.sector_turn(); }  ///< 2π z_H/(z N)
  [[nodiscard]] double rH(double phi) const;  ///< wheel pitch radius L i/(1 + i), m
  [[nodiscard]] double r(double phi) const;   ///< pinion pitch radius L/(1 + i), m (at θ(φ))
};

/// Compiles a parsed spec. Throws InputError with every problem found.
GearModel compile_gears(const SpecNode& root);

}  // namespace machdyn::gears
