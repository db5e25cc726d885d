#include "machdyn/elements/dc_motor.hpp"

#include <cmath>
#include <fmt/format.h>

namespace machdyn {

OneBodyJacobian DcMotor::jacobian(double, double, const double*, int) const {
  OneBodyJacobian j;
  j.dM_dx[0] = k;
  j.dx_domega[0] = -k / L;
  j.dx_dx[0][0] = -R / L;
  return j;
}

std::string DcMotor::describe(BodyKind) const {
  auto num = [](double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : std::string("–"); };
  return "R = " + num(R) + " ohm, L = " + num(L) + " H, k = " + num(k) + ", u(t): " + u.describe("V");
}

}  // namespace machdyn
