#include "model/compile_drive.hpp"

#include <cmath>
#include <fmt/format.h>

#include "model/compile_signal.hpp"

namespace machdyn::detail {

const std::vector<std::string>& drive_types() {
  static const std::vector<std::string> k = {"dc-motor", "speed-drive"};
  return k;
}

namespace {

/// A signal field of a drive (required): a quantity of dimension d or a map with `type:`.
std::optional<Signal> signal_field(FieldReader& f, const char* key, const Dim& d) {
  const SpecNode* n = f.node(key);
  if (!n) {
    f.error_at(key, fmt::format("missing field '{}' ({} or a signal of it)", key, describe(d)));
    return std::nullopt;
  }
  return compile_signal(*n, d, fmt::format("{}: field '{}'", f.what(), key), f.diagnostics());
}

void compile_dc_motor(FieldReader& f, Drive& d, BodyKind kind) {
  const Dim load = kind == BodyKind::rotational ? dim::torque : dim::force;
  d.kind = DriveKind::dc_motor;
  d.R = f.positive("resistance", dim::resistance).value_or(1.0);
  d.L = f.positive("inductance", dim::inductance).value_or(1.0);
  d.k = f.positive("motor_constant", load / dim::current).value_or(1.0);
  d.i0 = f.quantity("initial_current", dim::current, 0.0).value_or(0.0);
  if (auto u = signal_field(f, "voltage", dim::voltage)) d.voltage = *u;
}

void compile_speed_drive(FieldReader& f, Drive& d, BodyKind kind) {
  const Dim load = kind == BodyKind::rotational ? dim::torque : dim::force;
  const Dim speed = kind == BodyKind::rotational ? dim::angular_velocity : dim::velocity;
  d.kind = DriveKind::speed_drive;
  if (auto r = signal_field(f, "reference", speed)) d.reference = *r;
  d.Kp = f.positive("gain", load / speed).value_or(1.0);
  d.Ti = f.positive("integral_time", dim::time).value_or(1.0);
  d.M_max = f.map().find("torque_limit") ? f.positive("torque_limit", load).value_or(HUGE_VAL) : HUGE_VAL;
  d.T_m = f.positive("rise_time", dim::time, 0.0, true).value_or(0.0);
  d.M0 = f.quantity("initial_torque", load, 0.0).value_or(0.0);
  if (std::isfinite(d.M_max) && std::abs(d.M0) > d.M_max)
    f.error_at("initial_torque", fmt::format("field 'initial_torque' ({:g}) exceeds the torque limit {:g}", d.M0,
                                             d.M_max));
}

}  // namespace

void compile_drives(const SpecNode* section, Model& m, Diagnostics& diag) {
  if (!section) return;
  if (!section->is_map()) {
    diag.error(section->loc, "'drives' must be a map of NAME: {fields}");
    return;
  }
  for (const auto& [name, spec] : section->fields) {
    FieldReader f(spec, fmt::format("drive '{}'", name), diag);
    if (!spec.is_map()) continue;  // reported by the reader
    Drive d;
    d.name = name;
    auto type = f.word("type", drive_types());
    auto body = f.text("body");
    int i = -2;
    if (body) {
      i = m.body_index(*body);
      if (i < 0) f.error_at("body", fmt::format("unknown body '{}'", *body));
    }
    if (!type || i < 0) {  // the fields' dimensions depend on both: no cascade of messages
      for (const auto& [k, v] : spec.fields) f.node(k);
      continue;
    }
    d.body = i;
    const BodyKind kind = m.bodies[static_cast<size_t>(i)].kind;
    if (*type == "dc-motor") compile_dc_motor(f, d, kind);
    else compile_speed_drive(f, d, kind);
    f.finish();
    m.drives.push_back(std::move(d));
  }
}

}  // namespace machdyn::detail
