#include "machdyn/elements/drive.hpp"

namespace machdyn {

DriveLaw DriveLaw::of(const Drive& d) {
  DriveLaw k;
  k.kind = d.kind;
  k.body = d.body;
  k.states = d.states();
  if (d.kind == DriveKind::dc_motor) {
    k.dc = DcMotorLaw::of(d);
    k.x0[0] = d.i0;
  } else {
    k.sd = SpeedDriveLaw::of(d);
    k.x0[0] = k.x0[1] = d.M0;  // the integral holds the initial torque; the lag starts there too
  }
  return k;
}

DriveJacobian DriveLaw::jacobian(LimitMode md) const {
  if (kind == DriveKind::speed_drive) return sd.jacobian(md);
  DriveJacobian j;
  j.dM_dx[0] = dc.dtorque_di();
  j.dx_domega[0] = dc.drate_domega();
  j.dx_dx[0][0] = dc.drate_di();
  return j;
}

const char* DriveLaw::state_name(int j) const {
  if (kind == DriveKind::dc_motor) return "current";
  return j == 0 ? "integral torque" : "torque";
}

std::string DriveLaw::state_unit(int, BodyKind body_kind) const {
  if (kind == DriveKind::dc_motor) return "A";
  return load_unit(body_kind);
}

}  // namespace machdyn
