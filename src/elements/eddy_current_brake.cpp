#include "machdyn/elements/eddy_current_brake.hpp"

#include <cmath>
#include <fmt/format.h>

#include "machdyn/elements/linear_model.hpp"

namespace machdyn {

OneBodyJacobian EddyCurrentBrake::jacobian(double t, double omega, const double* x, int) const {
  OneBodyJacobian j;
  double dM_domega = 0.0;
  const double M = torque_at(t, omega, x[0], &dM_domega);
  const double dM_dT = -(omega / breakdown_speed(x[0])) * dM_domega * omega_ref * alpha;
  j.dM_domega = dM_domega;
  j.dM_dx[0] = dM_dT;
  j.dx_domega[0] = -(M + omega * dM_domega) / C;
  j.dx_dx[0][0] = -omega * dM_dT / C;
  return j;
}

void EddyCurrentBrake::add_linear(int body, int, LinearModel& lin) const {
  const double d = 2.0 * M_k.value(0.0) / breakdown_speed(T0);
  if (d != 0.0) lin.D.emplace_back(body, body, d);
}

std::string EddyCurrentBrake::describe(BodyKind body_kind) const {
  auto num = [](double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : std::string("–"); };
  return "M_k: " + M_k.describe(load_unit(body_kind)) + ", ω_k = " + num(omega_ref) + " " + velocity_unit(body_kind) +
         " at T_ref = " + num(T_ref) + " K, α = " + num(alpha) + " 1/K, C = " + num(C) + " J/K, T0 = " + num(T0) + " K";
}

}  // namespace machdyn
