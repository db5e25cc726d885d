#pragma once
/// @file
/// Quantities with units, as users write them in model files: `2.5 kg*m^2`, `143.5 mm`, `30 deg`,
/// `1.2 kN*m`, `1500 rpm`, `3e4 N*m/rad`. A plain number is SI.
///
/// Dimensions are exponents of kilogram, metre and second. The radian is dimensionless (as in SI),
/// so `N*m/rad` is a torque per unit angle and `rpm` is 2π/60 s⁻¹. Grammar:
///   quantity := number [unit-expr];  unit-expr := factor (('*' | '/' | '·' | '.' | ' ') factor)*
///   factor := unit ['^' integer] | '1' | '(' unit-expr ')' ['^' integer]
/// `a/b*c` is `(a/b)*c`; a space multiplies (`1.2 kg m^2`); `1/m` is a reciprocal unit. Units: m g t
/// s min h N J W Pa Hz rad deg rev rpm rps % A V ohm (or Ω) H K, SI prefixes (n u µ m c d k M G) on m g
/// s N J W Pa Hz rad A V ohm Ω H, and `Nm`, `kNm` for N*m. K (kelvin) is a temperature difference in
/// unit expressions (`kJ/K`, `W/K`); an absolute temperature is read by parse_temperature(). `rps` is revolutions per second (2π rad/s).
/// Limits: exponents after '^' from -12 to 12, at most 16 nested parentheses, and the value in SI
/// must be finite and, unless zero, not underflow to zero (`1e308 kN` is an error, not infinity).
/// An angular speed in Hz is rejected (cycles or radians per second?) with a hint: rpm, rps, rad/s.

#include <array>
#include <optional>
#include <string>
#include <string_view>

namespace machdyn {

/// Exponents of (kg, m, s, A, K). The ampere is there for the electrical fields of a DC motor
/// (armature voltage V, resistance Ω, inductance H, motor constant N·m/A = V·s/rad), the kelvin for
/// the thermal model of brakes and clutches (heat capacity J/K, conductance W/K).
struct Dim {
  int kg = 0, m = 0, s = 0, A = 0, K = 0;
  friend constexpr bool operator==(const Dim&, const Dim&) = default;
  constexpr Dim operator*(const Dim& o) const { return {kg + o.kg, m + o.m, s + o.s, A + o.A, K + o.K}; }
  constexpr Dim operator/(const Dim& o) const { return {kg - o.kg, m - o.m, s - o.s, A - o.A, K - o.K}; }
  constexpr Dim pow(int p) const { return {kg * p, m * p, s * p, A * p, K * p}; }
};

namespace dim {
inline constexpr Dim none{0, 0, 0};            ///< ratio, angle (rad)
inline constexpr Dim mass{1, 0, 0};            ///< kg
inline constexpr Dim length{0, 1, 0};          ///< m
inline constexpr Dim time{0, 0, 1};            ///< s
inline constexpr Dim inertia{1, 2, 0};         ///< kg*m^2
inline constexpr Dim force{1, 1, -2};          ///< N
inline constexpr Dim torque{1, 2, -2};         ///< N*m (also N*m/rad, J)
inline constexpr Dim velocity{0, 1, -1};       ///< m/s
inline constexpr Dim angular_velocity{0, 0, -1};  ///< rad/s
inline constexpr Dim stiffness_lin{1, 0, -2};  ///< N/m
inline constexpr Dim damping_lin{1, 0, -1};    ///< N*s/m
inline constexpr Dim damping_rot{1, 2, -1};    ///< N*m*s/rad
inline constexpr Dim inv_length{0, -1, 0};     ///< 1/m (rad/m)
inline constexpr Dim acceleration{0, 1, -2};   ///< m/s^2
inline constexpr Dim current{0, 0, 0, 1};      ///< A
inline constexpr Dim voltage{1, 2, -3, -1};    ///< V = W/A
inline constexpr Dim resistance{1, 2, -3, -2}; ///< Ω = V/A
inline constexpr Dim inductance{1, 2, -2, -2}; ///< H = V·s/A
inline constexpr Dim temperature{0, 0, 0, 0, 1};       ///< K
inline constexpr Dim heat_capacity{1, 2, -2, 0, -1};   ///< J/K
inline constexpr Dim thermal_conductance{1, 2, -3, 0, -1};  ///< W/K
}  // namespace dim

/// A name and an SI unit for a dimension, for messages: "a torque (N*m)". Unknown: the exponents.
std::string describe(const Dim& d);

/// A parsed quantity in SI.
struct Quantity {
  double value = 0.0;
  Dim dim;
  bool has_unit = false;  ///< false for a plain number, which is SI in whatever dimension is expected
  bool hertz = false;     ///< the unit contains Hz (ambiguous as an angular speed: parse_as rejects it there)
};

/// Parses `text`. Returns nullopt and sets `error` (what was expected at which character) on failure.
/// Non-finite numbers (nan, inf) are rejected.
std::optional<Quantity> parse_quantity(std::string_view text, std::string* error);

/// Parses and checks the dimension (a plain number is taken as SI of `expected`); on mismatch sets `error` to e.g.
/// "expected a torque (N*m), got a force (N) in '12 N'".
std::optional<double> parse_as(std::string_view text, const Dim& expected, std::string* error);

inline constexpr double kZeroCelsius = 273.15;  ///< 0 °C in K

/// An absolute temperature in K from `20 degC` (also `20 °C`, `-5 degC`) or `293.15 K` (also mK, kK).
/// A plain number is refused (20 K or 20 °C?), as is a temperature below absolute zero; on failure
/// returns nullopt and sets `error`.
std::optional<double> parse_temperature(std::string_view text, std::string* error);

}  // namespace machdyn
