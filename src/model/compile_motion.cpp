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
  if (!node->is_map()) {
    diag.error(node->loc, what + " expected {acceleration: SIGNAL} or {speed: SIGNAL}");
    return;
  }
  const bool rot = b.kind == BodyKind::rotational;
  const Dim acc = rot ? Dim{0, 0, -2} : dim::acceleration;
  const Dim vel = rot ? dim::angular_velocity : dim::velocity;
  FieldReader g(*node, what, diag);
  const SpecNode* a = g.node("acceleration");
  const SpecNode* v = g.node("speed");
  g.finish();
  if ((a == nullptr) == (v == nullptr)) {
    diag.error(node->loc, what + " expects exactly one of 'acceleration' (a signal in " + (rot ? "rad/s^2" : "m/s^2") +
                              ") or 'speed' (a signal in " + (rot ? "rad/s" : "m/s") + ")");
    return;
  }
  auto s = a ? compile_signal(*a, acc, what + " 'acceleration'", diag)
             : compile_signal(*v, vel, what + " 'speed'", diag);
  if (!s) return;
  b.motion = a ? MotionKind::acceleration : MotionKind::speed;
  b.motion_signal = *s;
  if (b.motion != MotionKind::speed) return;
  // The speed signal fixes the initial velocity; a `velocity` that says otherwise is a contradiction.
  const double v0 = s->value(0.0);
  if (const SpecNode* given = f.map().find("velocity"); given && std::abs(b.v0 - v0) > 1e-9 * std::max(1.0, std::abs(v0)))
    diag.error(given->loc, fmt::format("body '{}': 'velocity' {:.6g} {} contradicts its prescribed speed at t = 0, {:.6g} {} "
                                       "(leave 'velocity' out)", b.name, b.v0, velocity_unit(b.kind), v0,
                                       velocity_unit(b.kind)));
  b.v0 = v0;
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
