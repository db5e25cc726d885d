#include "machdyn/elements/speed_drive.hpp"

#include <fmt/format.h>

namespace machdyn {

const char* to_string(LimitMode m) {
  switch (m) {
    case LimitMode::linear: return "linear";
    case LimitMode::limited_pos: return "limited+";
    case LimitMode::limited_neg: return "limited-";
    case LimitMode::on_limit_pos: return "on-limit+";
    case LimitMode::on_limit_neg: return "on-limit-";
  }
  return "?";
}

OneBodyJacobian SpeedDrive::jacobian(double, double, const double*, int mode) const {
  OneBodyJacobian j;
  const bool lin = LimitMode(mode) == LimitMode::linear;
  if (lin) j.dx_domega[0] = -Kp / Ti;
  if (!lagged()) {
    if (lin) j.dM_domega = -Kp, j.dM_dx[0] = 1.0;
    return j;
  }
  j.dM_dx[1] = 1.0;
  if (lin) j.dx_domega[1] = -Kp / T_m, j.dx_dx[1][0] = 1.0 / T_m;
  j.dx_dx[1][1] = -1.0 / T_m;
  return j;
}

int SpeedDrive::natural_mode(double t, double omega, const double* x, int current, double omega_dot) const {
  const LimitMode cur = LimitMode(current);
  if (!limited()) return static_cast<int>(LimitMode::linear);
  if (!on_limit(cur)) return static_cast<int>(command_mode(command(t, omega, x[0]), cur));
  double g[2];
  events(t, omega, x, current, omega_dot, g);
  return g[0] < 0.0 ? static_cast<int>(LimitMode::linear) : g[1] < 0.0 ? static_cast<int>(limit_mode_after(cur, 1)) : current;
}

std::vector<std::string> SpeedDrive::output_names(BodyKind body_kind) const {
  return {"reference_" + unit_suffix(velocity_unit(body_kind)), "mode"};
}

std::string SpeedDrive::describe(BodyKind body_kind) const {
  auto num = [](double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : std::string("–"); };
  return "K_p = " + num(Kp) + ", T_i = " + num(Ti) + " s" +
         (limited() ? ", M_max = " + num(M_max) + " " + load_unit(body_kind) : std::string()) +
         (lagged() ? ", T_m = " + num(T_m) + " s" : std::string()) + ", reference: " +
         ref.describe(velocity_unit(body_kind));
}

std::shared_ptr<const Element> SpeedDrive::at_steady_speed(double v) const {
  auto held = std::make_shared<SpeedDrive>(*this);
  held->ref = Signal::constant(v);
  return held;
}

}  // namespace machdyn
