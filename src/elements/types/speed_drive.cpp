// Element type `speed-drive` (elements/speed_drive.hpp): its fields, compiled to SI with located errors.
//   NAME: {type: speed-drive, body, reference (signal), gain, integral_time, torque_limit (none),
//          rise_time (0), initial_torque (0)}
#include <cmath>
#include <fmt/format.h>

#include "machdyn/elements/speed_drive.hpp"
#include "model/compile_drive.hpp"
#include "model/element_types.hpp"

namespace {

std::shared_ptr<const machdyn::Element> compile_speed_drive(machdyn::FieldReader& f, machdyn::BodyKind kind) {
  using namespace machdyn;
  const Dim load = kind == BodyKind::rotational ? dim::torque : dim::force;
  const Dim speed = kind == BodyKind::rotational ? dim::angular_velocity : dim::velocity;
  auto d = std::make_shared<SpeedDrive>();
  if (auto r = detail::signal_field(f, "reference", speed)) d->ref = *r;
  d->Kp = f.positive("gain", load / speed).value_or(1.0);
  d->Ti = f.positive("integral_time", dim::time).value_or(1.0);
  d->M_max = f.map().find("torque_limit") ? f.positive("torque_limit", load).value_or(HUGE_VAL) : HUGE_VAL;
  d->T_m = f.positive("rise_time", dim::time, 0.0, true).value_or(0.0);
  d->M0 = f.quantity("initial_torque", load, 0.0).value_or(0.0);
  if (std::isfinite(d->M_max) && std::abs(d->M0) > d->M_max)
    f.error_at("initial_torque", fmt::format("field 'initial_torque' ({:g}) exceeds the torque limit {:g}", d->M0,
                                             d->M_max));
  return d;
}

}  // namespace

MACHDYN_ELEMENT_TYPE(speed_drive, "speed-drive", compile_speed_drive,
                     "reference: 100 rad/s, gain: 2 N*m*s/rad, integral_time: 0.2 s, torque_limit: 40 N*m, rise_time: 20 ms, initial_torque: 5 N*m")
