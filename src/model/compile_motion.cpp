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

void check_motion_elements(const Model& m, Diagnostics& diag) {
  // A friction element between prescribed motions (or to the ground) is kinematic (elements/contact.hpp);
  // a freewheel or end stop there would lock a motion that is given: its lock could not hold.
  for (const auto& c : m.contacts)
    if (c.lock != 0 && prescribed(m, c.a) && (c.b < 0 || prescribed(m, c.b)))
      diag.error(m.where(c.name), fmt::format("'{}': body '{}' has a prescribed motion ('motion'); a freewheel or end "
                                              "stop between it and {} is not supported (its lock would contradict the "
                                              "given motion)", c.name, m.bodies[static_cast<size_t>(c.a)].name,
                                              c.b < 0 ? "the ground" : "another prescribed body"));
}

void check_motion_lossy(const Model& m, Diagnostics& diag) {
  // A lossy gear with one prescribed side (elements/lossy_gear.hpp "Prescribed side"): its torques follow
  // from the given motion. Refused: both sides given (two motions for one degree of freedom), a given b
  // with a self-locking reverse efficiency (b could not drive), friction elements on its bodies (their
  // decision with the gear at rest is another law).
  for (const auto& g : m.lossy_gears) {
    const bool pa = prescribed(m, g.a), pb = prescribed(m, g.b);
    const std::string& A = m.bodies[static_cast<size_t>(g.a)].name;
    const std::string& B = m.bodies[static_cast<size_t>(g.b)].name;
    if (pa && pb) {
      diag.error(m.where(g.name), fmt::format("lossy gear '{}': both '{}' and '{}' have a prescribed motion ('motion', "
                                              "their own or through ideal gears); the gear ties them, give one only",
                                              g.name, A, B));
      continue;
    }
    if (!pa && !pb) continue;
    if (pb && std::find(g.eta_reverse.begin(), g.eta_reverse.end(), 0.0) != g.eta_reverse.end())
      diag.error(m.where(g.name), fmt::format("lossy gear '{}': '{}' has a prescribed motion and the gear is "
                                              "self-locking (efficiency_reverse 0): it cannot drive '{}' backwards; "
                                              "prescribe the motion of '{}' instead", g.name, B, A, A));
    for (const auto& c : m.contacts)
      if (c.a == g.a || c.a == g.b || c.b == g.a || c.b == g.b) {
        diag.error(m.where(g.name), fmt::format("lossy gear '{}': '{}' has a prescribed motion and the friction "
                                                "element '{}' acts on the gear's bodies; not supported yet", g.name,
                                                pa ? A : B, c.name));
        break;
      }
  }
}

}  // namespace machdyn::detail
