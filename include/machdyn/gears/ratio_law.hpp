#pragma once
/// @file
/// The gear-ratio law of a non-circular gear pair: i(φ) = dθ/dφ = r_H/r, where φ is the angle of the
/// driven wheel (the carrier, index H) and θ the angle of the driving pinion. The law is periodic with
/// the big-sector period T = 2π/N (N big sectors on the wheel) and is written i(φ) = u·f(φ):
///
///  - walking (paper 003, eq. 2): travel per carrier angle dX/dφ = a − b + c + 3b·cos 2φ; constant
///    travel speed at constant pinion speed needs i ∝ dX/dφ, so f = 1 + k·cos 2φ, k = 3b/(a − b + c);
///  - travel: f = a user expression of dX/dφ (any mechanism's speed law), normalised by closure;
///  - expression: f = a user expression of φ (normalised by closure only when asked);
///  - table: f = periodic cubic spline through (φ_k, i_k) (C², so the pitch curves have curvature).
///
/// f is evaluated with φ wrapped into the big sector [−T/2, T/2] (the formula holds there, the law
/// repeats in every big sector). Closure: over one big sector the pinion must turn
/// Θ = 2π z_H/(z N), so u = Θ / ∫_{−T/2}^{T/2} f dφ; for the walking law with T = π/2 this is the
/// paper's u = (π/2)/(π/4 + k/2) (eq. 10), and in general u = Θ/(T + k sin T).
/// θ(φ) = ∫_0^φ i dφ (θ(0) = 0, the paper's constant C = 0): closed form u(φ + (k/2) sin 2φ) in the
/// principal sector for the walking law, Gauss–Legendre quadrature otherwise.

#include <memory>
#include <string>
#include <vector>

#include "machdyn/common/expression.hpp"

namespace machdyn::gears {

/// Periodic cubic spline y(x) with period `period` through strictly increasing knots spanning less
/// than one period. Second derivatives continuous everywhere, including across the period.
class PeriodicSpline {
 public:
  PeriodicSpline() = default;
  /// Throws std::invalid_argument for fewer than 3 knots or knots not increasing within one period.
  PeriodicSpline(std::vector<double> x, std::vector<double> y, double period);
  [[nodiscard]] Jet eval(double x) const;
  [[nodiscard]] const std::vector<double>& knots() const { return x_; }

 private:
  std::vector<double> x_, y_, m_;  ///< knots, values, second derivatives
  double period_ = 0.0;
};

class RatioLaw {
 public:
  enum class Kind { Walking, Travel, Expression, Table };

  /// The paper's law for a propulsor with hub-to-crank distance a, crank b, shoe strut c (any common
  /// length unit), big-sector period T (rad) and pinion turn per big sector Theta (rad).
  static RatioLaw walking(double a, double b, double c, double T, double Theta);
  /// i = u·travel(φ)/1 with u from closure; `travel` is dX/dφ in any unit.
  static RatioLaw travel(Expression travel, double T, double Theta);
  /// i = u·f(φ); u from closure if `normalize`, else u = 1 (and closure is the caller's check).
  static RatioLaw expression(Expression f, double T, double Theta, bool normalize);
  /// i = u·spline(φ); u as for expression().
  static RatioLaw table(PeriodicSpline f, double T, double Theta, bool normalize);

  [[nodiscard]] Kind kind() const { return kind_; }
  [[nodiscard]] double period() const { return T_; }       ///< T = 2π/N, rad
  [[nodiscard]] double sector_turn() const { return Theta_; }  ///< Θ, rad
  [[nodiscard]] double u() const { return u_; }            ///< scale factor u
  [[nodiscard]] double k() const { return k_; }            ///< walking: k = 3b/(a − b + c); else 0

  /// φ wrapped into [−T/2, T/2] (left as is when already inside, so ±T/2 give the one-sided limits).
  [[nodiscard]] double wrap(double phi) const;
  /// i(φ) with its first and second derivatives in φ.
  [[nodiscard]] Jet ratio(double phi) const;
  /// θ(φ) = ∫_0^φ i dφ, rad.
  [[nodiscard]] double theta(double phi) const;
  /// The inverse of theta() (i > 0 makes θ increasing). Newton's method, |error| < 1e-13 rad.
  [[nodiscard]] double phi_of_theta(double theta) const;
  /// ∫ i dφ over one big sector (Θ when the law closes).
  [[nodiscard]] double sector_integral() const;
  /// The travel law dX/dφ (the same length unit as given) when the law comes from one
  /// (walking: metres per radian; travel: the user's unit); has_travel() says whether there is one.
  [[nodiscard]] bool has_travel() const { return kind_ == Kind::Walking || kind_ == Kind::Travel; }
  [[nodiscard]] double travel(double phi) const;

 private:
  [[nodiscard]] Jet shape(double phi_wrapped) const;
  [[nodiscard]] double integral_wrapped(double from, double to) const;
  Kind kind_ = Kind::Walking;
  double T_ = 0.0, Theta_ = 0.0, u_ = 1.0, k_ = 0.0;
  double a_ = 0.0, b_ = 0.0, c_ = 0.0;
  std::shared_ptr<const Expression> expr_;
  PeriodicSpline spline_;
};

}  // namespace machdyn::gears
