#pragma once
/// @file
/// The dynamic factors of the crane standards as pure functions and tables, for comparison with
/// simulated factors (docs/crane-factors.md). Source of every value: /work/shared/docs/crane-standards.md
/// (collected from public sources; the standards' own texts were not available — verify before
/// relying on a value). The tests check every value against that page.
///
/// EN 13001-2 (and ISO 8686-1):
///   φ2 = φ2,min + β2 vh                  hoisting an unrestrained grounded load; vh in m/s, β2 in s/m
///     β2 by hoisting class HC1…HC4: 0.17, 0.34, 0.51, 0.68 s/m
///     φ2,min: HD1, HD2, HD4: 1.05, 1.10, 1.15, 1.20 by HC1…HC4; HD3, HD5: 1.05 in every class
///     characteristic vh by hoist drive class: HD1 vh,max; HD2, HD3 creep speed vh,CS; HD4 0.5 vh,max;
///     HD5 0 (stepless drive starting from zero)
///   φ3 = 1 − (Δm/m)(1 + β3)              sudden release of Δm of the hoist load m; β3 = 0.5 for grabs
///                                       or slow release, 1.0 for rapid release
///   φ5 ranges by how the drive force changes: centrifugal 1.0; smooth 1.0–1.5; sudden 1.5–2.0;
///                                       considerable backlash 3.0 (one source)
///   φ6,dyn = 0.5 (1 + φ2)                dynamic test load
///   φ7 = 1.25                  for 0 ≤ ξb ≤ 0.5,
///   φ7 = 1.25 + 0.7 (ξb − 0.5) for 0.5 < ξb ≤ 1      buffer forces; ξb the buffer's energy-absorption
///                                       ratio ∫F dx / (F_max · stroke)
/// FEM 1.001 (1998): ψ = max(1.15, 1 + ξ vL), ξ = 0.6 overhead and gantry cranes, 0.3 jib cranes; for
///   vL above 1 m/s the value at 1 m/s (the page says "capped"; the cap taken as ψ(1 m/s), verify).
/// DIN 15018 (one source): ψ = k + l v, v in m/min, H1…H4: 1.1 + 0.0022 v, 1.2 + 0.0044 v,
///   1.3 + 0.0066 v, 1.4 + 0.0088 v.
///
/// Every function throws std::invalid_argument for an argument outside its range (named in the
/// message): negative speeds or masses, Δm > m, ξb outside [0, 1], a class out of its enum.

#include <string>
#include <vector>

namespace machdyn::crane {

enum class HoistingClass { HC1 = 1, HC2, HC3, HC4 };
enum class HoistDriveClass { HD1 = 1, HD2, HD3, HD4, HD5 };

/// "HC1" … "HC4" / "HD1" … "HD5"; parse_* throws std::invalid_argument for another word.
std::string to_string(HoistingClass hc);
std::string to_string(HoistDriveClass hd);
HoistingClass parse_hoisting_class(const std::string& s);
HoistDriveClass parse_hoist_drive_class(const std::string& s);

/// β2 of a hoisting class, s/m.
double beta2(HoistingClass hc);
/// φ2,min of a hoisting class and hoist drive class.
double phi2_min(HoistingClass hc, HoistDriveClass hd);
/// The characteristic hoisting speed vh of a drive class, m/s, from the drive's steady hoisting
/// speed vh,max and its creep speed vh,CS (m/s, ≥ 0; the creep speed is read for HD2 and HD3 only).
double characteristic_hoisting_speed(HoistDriveClass hd, double vh_max, double vh_creep);
/// φ2 = φ2,min + β2 vh (vh ≥ 0, m/s).
double phi2(HoistingClass hc, HoistDriveClass hd, double vh);

enum class ReleaseKind { slow, rapid };  ///< grabs or slow release: β3 = 0.5; rapid: β3 = 1.0
double beta3(ReleaseKind k);
/// φ3 = 1 − (Δm/m)(1 + β3), 0 ≤ Δm ≤ m, m > 0 (kg).
double phi3(double released_mass, double hoist_mass, ReleaseKind k);

/// How a drive force changes (φ5's ranges).
enum class DriveForceChange { centrifugal, smooth, sudden, backlash };
struct Range {
  double lo, hi;  ///< lo = hi for a single value
};
Range phi5_range(DriveForceChange c);
std::string to_string(DriveForceChange c);  ///< "centrifugal", "smooth", "sudden", "backlash"

/// φ6,dyn = 0.5 (1 + φ2).
double phi6_dynamic(double phi2_value);

/// φ7 from the buffer's energy-absorption ratio ξb in [0, 1].
double phi7(double xi_b);
/// ξb = ∫F dx / (F_max · x_max) of a buffer characteristic given as a table of strokes x (m,
/// increasing from 0) and forces F (N, ≥ 0, one per stroke), taken as piecewise linear (the
/// trapezoids are exact for it). Throws for fewer than two points, a stroke that does not increase
/// or start at 0, a negative force or an all-zero characteristic.
double buffer_energy_ratio(const std::vector<double>& stroke, const std::vector<double>& force);

enum class CraneType { overhead_or_gantry, jib };
/// FEM 1.001 ψ(vL), vL ≥ 0 in m/s.
double fem_psi(CraneType t, double vL);
/// DIN 15018 ψ for hoisting class H1…H4 (1…4) and speed v in m/s (the formula's v is in m/min).
double din_psi(int hoisting_class, double v);

}  // namespace machdyn::crane
