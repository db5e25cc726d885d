// Element type `thermal-eddy-current-brake` (elements/eddy_current_brake.hpp): its fields, compiled
// to SI with located errors.
//   NAME: {type: thermal-eddy-current-brake, body, breakdown_torque (signal), breakdown_speed,
//          heat_capacity, reference_temperature (20 degC), temperature_coefficient (0 1/K),
//          initial_temperature (the reference temperature)}
#include <optional>
#include <fmt/format.h>

#include "machdyn/common/units.hpp"
#include "machdyn/elements/eddy_current_brake.hpp"
#include "model/compile_drive.hpp"
#include "model/element_types.hpp"

namespace {

/// An absolute temperature field (`20 degC`, `293.15 K`), or `fallback` when absent.
std::optional<double> temperature(machdyn::FieldReader& f, const char* key, double fallback) {
  using namespace machdyn;
  const SpecNode* v = f.node(key);
  if (!v) return fallback;
  std::string err;
  std::optional<double> T = v->is_scalar() ? parse_temperature(v->scalar, &err) : std::nullopt;
  if (!T)
    f.diagnostics().error(v->loc, fmt::format("{}: field '{}': {}", f.what(), key,
                                              err.empty() ? "expected a temperature, e.g. 20 degC" : err));
  return T;
}

std::shared_ptr<const machdyn::Element> compile_thermal_eddy_current_brake(machdyn::FieldReader& f,
                                                                        machdyn::BodyKind kind) {
  using namespace machdyn;
  const Dim load = kind == BodyKind::rotational ? dim::torque : dim::force;
  const Dim speed = kind == BodyKind::rotational ? dim::angular_velocity : dim::velocity;
  auto b = std::make_shared<EddyCurrentBrake>();
  if (auto M = detail::signal_field(f, "breakdown_torque", load)) {
    b->M_k = *M;
    if (M->kind() == Signal::Kind::constant && M->value(0.0) < 0.0)
      f.error_at("breakdown_torque", fmt::format("field 'breakdown_torque' must not be negative, got {:g}", M->value(0.0)));
  }
  b->omega_ref = f.positive("breakdown_speed", speed).value_or(1.0);
  b->C = f.positive("heat_capacity", dim::heat_capacity).value_or(1.0);
  b->alpha = f.positive("temperature_coefficient", dim::none / dim::temperature, 0.0, true).value_or(0.0);
  const auto T_ref = temperature(f, "reference_temperature", 293.15);
  if (T_ref) b->T_ref = *T_ref;
  const auto T0 = temperature(f, "initial_temperature", b->T_ref);
  if (T0) b->T0 = *T0;
  if (T_ref && T0 && !(1.0 + b->alpha * (b->T0 - b->T_ref) > 0.0))
    f.error_at("initial_temperature",
               fmt::format("field 'initial_temperature' ({:g} K) is so far below the reference temperature that the "
                           "resistance 1 + α (T0 − T_ref) = {:g} is not positive", b->T0,
                           1.0 + b->alpha * (b->T0 - b->T_ref)));
  return b;
}

}  // namespace

MACHDYN_ELEMENT_TYPE(thermal_eddy_current_brake, "thermal-eddy-current-brake", compile_thermal_eddy_current_brake,
                     "breakdown_torque: 30 N*m, breakdown_speed: 20 rad/s, heat_capacity: 500 J/K, temperature_coefficient: 0.004 1/K, initial_temperature: 60 degC")
