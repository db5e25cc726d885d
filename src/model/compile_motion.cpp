#include "model/compile_motion.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <fmt/format.h>

#include "model/compile_signal.hpp"

namespace machdyn::detail {

void read_motion(FieldReader& f, Body& b) {
  const SpecNode* node = f.node("motion");
  if (!node) return;
  Diagnostics& diag = f.diagnostics();
  const std::string what = fmt::format("body '{}': field 'motion'", b.name);
  const bool rot = b.kind == BodyKind::rotational;
  const std::string expects = fmt::format(" expects exactly one of 'acceleration' (a signal in {}), 'speed' ({}) or "
                                          "'position' ({})", rot ? "rad/s^2" : "m/s^2", rot ? "rad/s" : "m/s",
                                          rot ? "rad" : "m");
  if (!node->is_map()) {
    diag.error(node->loc, what + expects);
    return;
  }
  FieldReader g(*node, what, diag);
  const SpecNode* a = g.node("acceleration");
  const SpecNode* v = g.node("speed");
  const SpecNode* p = g.node("position");
  g.finish();
  if ((a != nullptr) + (v != nullptr) + (p != nullptr) != 1) {
    diag.error(node->loc, what + expects);
    return;
  }
  const Dim d = a ? (rot ? Dim{0, 0, -2} : dim::acceleration)
                  : v ? (rot ? dim::angular_velocity : dim::velocity)
                      : (rot ? dim::none : dim::length);
  const MotionKind kind = a ? MotionKind::acceleration : v ? MotionKind::speed : MotionKind::position;
  const char* field = a ? "acceleration" : v ? "speed" : "position";
  auto s = compile_signal(a ? *a : v ? *v : *p, d, fmt::format("{} '{}'", what, field), diag);
  if (!s) return;
  b.motion = kind;
  b.motion_signal = *s;
  // A prescribed speed fixes the initial velocity, a prescribed position the initial position and
  // velocity; a `position` or `velocity` in the file that says otherwise is a contradiction.
  auto fix = [&](const char* key, double& given_value, double value, const char* unit) {
    const SpecNode* given = f.map().find(key);
    if (given && std::abs(given_value - value) > 1e-9 * std::max(1.0, std::abs(value)))
      diag.error(given->loc, fmt::format("body '{}': '{}' {:.6g} {} contradicts its prescribed {} at t = 0, {:.6g} {} "
                                         "(leave '{}' out)", b.name, key, given_value, unit, field, value, unit, key));
    given_value = value;
  };
  if (kind == MotionKind::speed) fix("velocity", b.v0, s->value(0.0), velocity_unit(b.kind));
  if (kind == MotionKind::position) {
    fix("position", b.q0, s->value(0.0), position_unit(b.kind));
    fix("velocity", b.v0, s->slope(0.0), velocity_unit(b.kind));
  }
}

namespace {
bool prescribed(const Model& m, int i) { return i >= 0 && m.bodies[static_cast<size_t>(i)].motion != MotionKind::free; }
}  // namespace

void check_motion_elements(const Model& m, const std::vector<IdealGear>& gears, const std::vector<LossyGearSpec>& lossy,
                           Diagnostics& diag) {
  // A friction element between a prescribed body and a free one acts (its stuck force is carried by the
  // source); to the ground or between two prescribed bodies its stuck mode would contradict the motion.
  for (const auto& c : m.contacts)
    if (prescribed(m, c.a) && (c.b < 0 || prescribed(m, c.b)))
      diag.error(m.where(c.name), fmt::format("'{}': body '{}' has a prescribed motion ('motion'); a friction element "
                                              "between it and {} is not supported (it could not stick)", c.name,
                                              m.bodies[static_cast<size_t>(c.a)].name,
                                              c.b < 0 ? "the ground" : "another prescribed body"));
  for (const auto& g : gears)
    for (const int i : {g.a, g.b})
      if (prescribed(m, i))
        diag.error(g.where, fmt::format("ideal gear '{}': body '{}' has a prescribed motion ('motion'); a gear on such "
                                        "a body is not supported yet (prescribe the motion of a body it drives through "
                                        "a link instead)", g.name, m.bodies[static_cast<size_t>(i)].name));
  for (const auto& g : lossy)
    for (const int i : {g.gear.a, g.gear.b})
      if (prescribed(m, i))
        diag.error(g.where, fmt::format("lossy gear '{}': body '{}' has a prescribed motion ('motion'), not supported "
                                        "yet", g.gear.name, m.bodies[static_cast<size_t>(i)].name));
}

void check_motion_releases(const Model& m, Diagnostics& diag) {
  for (const auto& r : m.releases)
    if (prescribed(m, r.body))
      diag.error(m.where(r.name), fmt::format("release '{}': body '{}' has a prescribed motion ('motion'), its mass does "
                                              "not act on its motion; a release there is not supported",
                                              r.name, m.bodies[static_cast<size_t>(r.body)].name));
}

}  // namespace machdyn::detail
