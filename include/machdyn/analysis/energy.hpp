#pragma once
/// @file
/// The first integral of a 1-DOF machine (paper 000 eq. 25). For I(q) q'' + ½ I′ q'² = Q(q),
///   d/dt(½ I q'²) = (I q'' + ½ I′ q'²) q' = Q q',  so  ½ I(q) ω² − ½ I(q0) ω0² = A(q) = ∫_{q0}^{q} Q dq
///   ω(q) = √[(I(q0) ω0² + 2 A(q)) / I(q)]
/// A(q) by adaptive Gauss–Kronrod (7–15) quadrature. Q is the machine's own force plus constant
/// loads on the body; anything depending on time or speed (motors, steps, tables in t) has no such
/// integral and is rejected.
///
/// The scan runs in the machine's sweep coordinate s (the thread angle β for the rolling wheel,
/// q otherwise), from the start in the direction of motion (sign of ω0, or of Q(q0) at rest), up
/// to the first turning point (ω = 0: the motion reverses there), the end of the range (β → π),
/// or `s_to` (default: one period, or 2π rad).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "machdyn/model/model.hpp"

namespace machdyn {

/// ∫_a^b f by adaptive Gauss–Kronrod 7–15, to |error| <= max(abs_tol, rel_tol·|∫|) per panel.
double integrate_gk15(const std::function<double(double)>& f, double a, double b, double rel_tol = 1e-13,
                      double abs_tol = 1e-300);

/// The energy integral of a model with one body and no links.
class EnergyIntegral {
 public:
  /// Throws InputError if the model is not 1-DOF or has a load that is not constant.
  /// `added_inertia` (a flywheel, kg·m²) and `extra_torque` (N·m) modify the machine.
  explicit EnergyIntegral(const Model& m, double added_inertia = 0.0, double extra_torque = 0.0);

  [[nodiscard]] double q0() const { return q0_; }
  [[nodiscard]] double s0() const { return s0_; }
  [[nodiscard]] double omega0() const { return omega0_; }
  /// q(s) and s(q).
  [[nodiscard]] double q_of_s(double s) const;
  [[nodiscard]] double s_of_q(double q) const;
  /// Total generalized force Q(s) (machine force + constant loads + extra torque), N·m.
  [[nodiscard]] double force_s(double s) const;
  [[nodiscard]] double inertia_s(double s) const;
  /// ∫ Q dq between s_a and s_b.
  [[nodiscard]] double work_s(double s_a, double s_b) const;
  /// A(q) = ∫_{q0}^{q} Q dq.
  [[nodiscard]] double work(double q) const;
  /// ω²(q) = (I(q0) ω0² + 2A(q))/I(q) for the start speed ω_start (default ω0); negative: unreachable.
  [[nodiscard]] double omega_squared(double q) const;
  /// |ω(q)|, NaN where the position is not reached.
  [[nodiscard]] double omega(double q) const;
  [[nodiscard]] const Body& body() const { return *body_; }
  [[nodiscard]] double added_inertia() const { return added_; }

 private:
  const Body* body_;
  double q0_, s0_, omega0_, added_, constant_torque_;
};

struct EnergyOptions {
  std::optional<double> s_to;  ///< end of the scan in the sweep coordinate
  int points = 201;            ///< rows of the table
};

struct EnergyRow {
  double s, q, omega, inertia, work;
};

struct EnergyResult {
  std::string body, machine, s_name, point_name;
  double q0 = 0, omega0 = 0, direction = 1;
  std::vector<double> turning_points;  ///< q where ω = 0 and the motion reverses
  double omega_max = 0, q_at_omega_max = 0, omega_min = 0, q_at_omega_min = 0;
  std::optional<double> omega_limit;   ///< as s reaches its end; null when unbounded or not reached
  std::string limit_kind;              ///< "finite", "unbounded", "turning point", "none"
  /// With an unbounded limit: the angular acceleration q'' the motion tends to, rad/s², = Q/I at the
  /// end of the range (the term ½ I′ ω² vanishes there); paper 000 eq. 30 for the rolling wheel,
  /// ε = F (R1 − r1) / [m1 (ρ² + r1²) + (m2/2)(R1 − r1)²]. Null otherwise.
  std::optional<double> epsilon_limit;
  std::optional<double> work_per_period;  ///< A over one period, for periodic machines
  std::vector<EnergyRow> table;
};

/// The analysis described in the file comment. Throws InputError on unsuitable models.
EnergyResult energy_analysis(const Model& m, const EnergyOptions& opt = {});

/// The energy integral of a 1-DOF machine without links, gaps or contacts (what a report draws as
/// ω against distance or angle), or nothing when the model has no such integral (e.g. a load that
/// depends on time: energy_analysis rejects it).
std::optional<EnergyResult> machine_energy(const Model& m);

/// Steady running of a periodic machine (a crank): with the constant torque that balances the work
/// per period, the periodic speed whose mean (ωmax + ωmin)/2 is `omega_mean`, its coefficient of
/// speed fluctuation δ = (ωmax − ωmin)/ωmean, and the flywheel inertia J (added to I(q)) that brings
/// δ to `delta_target` (J = 0 if δ is already below it).
struct SteadyResult {
  double omega_mean = 0, balancing_torque = 0, work_per_period = 0;
  double delta = 0, omega_max = 0, omega_min = 0;           ///< without flywheel
  double delta_target = 0, flywheel_inertia = 0;            ///< kg·m²
  double delta_with_flywheel = 0, omega_max_fw = 0, omega_min_fw = 0;
  double omega_start_fw = 0;  ///< speed at q0 on the periodic solution with the flywheel
  double mean_inertia = 0;                                  ///< mean of I(q) over the period
  double flywheel_estimate = 0;  ///< classic estimate ΔA_max/(δ ω_m²) − mean I (constant-inertia theory)
};
SteadyResult steady_running(const Model& m, double omega_mean, double delta_target);

}  // namespace machdyn
