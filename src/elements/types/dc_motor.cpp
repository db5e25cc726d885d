// Element type `dc-motor` (elements/dc_motor.hpp): its fields, compiled to SI with located errors.
//   NAME: {type: dc-motor, body, resistance, inductance, motor_constant, voltage (signal),
//          initial_current (0)}
#include <fmt/format.h>

#include "machdyn/elements/dc_motor.hpp"
#include "model/compile_drive.hpp"
#include "model/element_types.hpp"

namespace {

std::shared_ptr<const machdyn::Element> compile_dc_motor(machdyn::FieldReader& f, machdyn::BodyKind kind) {
  using namespace machdyn;
  const Dim load = kind == BodyKind::rotational ? dim::torque : dim::force;
  auto d = std::make_shared<DcMotor>();
  d->R = f.positive("resistance", dim::resistance).value_or(1.0);
  d->L = f.positive("inductance", dim::inductance).value_or(1.0);
  d->k = f.positive("motor_constant", load / dim::current).value_or(1.0);
  d->i0 = f.quantity("initial_current", dim::current, 0.0).value_or(0.0);
  if (auto u = detail::signal_field(f, "voltage", dim::voltage)) d->u = *u;
  return d;
}

}  // namespace

MACHDYN_ELEMENT_TYPE(dc_motor, "dc-motor", compile_dc_motor,
                     "resistance: 0.5 ohm, inductance: 20 mH, motor_constant: 0.8 N*m/A, voltage: 50 V, initial_current: 3 A")
