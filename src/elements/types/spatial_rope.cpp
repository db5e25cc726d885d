// Element type `spatial-rope` (elements/spatial_rope.hpp) under `links:`: a point-mass load
// (model/compile_point_mass.hpp) on a rope from a suspension point that moves with the model's bodies;
// its fields compiled to SI with located errors.
//   NAME: {type: spatial-rope, load: LOAD (a point-mass), length (L0, m), EA (N) or elastic_modulus + area,
//          falls (1), damping (0 N·s/m, the hook's), height (m; default L0 + m g/c: the load at z = 0
//          hangs at rest),
//          trolley: BODY (translational, x), bridge: BODY (translational, y),
//          jib: BODY (rotational, θ) with radius: BODY (translational) or a length,
//          drum: BODY (rotational, φ) with drum_radius (m), sway_after (s: the summary's residual sway),
//          attach: [a_h, a_z] (m: the rope's point on a rigid load, its frame), offset (m: a planar
//          load's suspension point along its horizontal axis)}
#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "machdyn/common/units.hpp"
#include "machdyn/elements/spatial_rope.hpp"
#include "model/element_types.hpp"

namespace machdyn::detail {

namespace {

const char* spatial_rope_kind_text(BodyKind k) { return k == BodyKind::rotational ? "rotational" : "translational"; }

std::shared_ptr<const Element> place_spatial_rope(FieldReader& f, const Model& m, std::vector<int>& bodies) {
  using Role = SpatialRope::Role;
  auto rope = std::make_shared<SpatialRope>();
  bool ok = true;
  int port_body[SpatialRope::kRoles] = {-1, -1, -1, -1, -1, -1, -1, -1, -1};  // by Role
  // The load: its coordinates NAME.x, NAME.y, NAME.z.
  const std::optional<std::string> load = f.text("load");
  if (load) {
    const int z = m.body_index(*load + ".z");
    if (z < 0) {
      f.error_at("load", m.body_index(*load) >= 0
                             ? fmt::format("'{}' is a body of its own; the load of a spatial rope is a body of "
                                           "'type: point-mass' or 'type: rigid-load'", *load)
                             : fmt::format("unknown load '{}' (a body of 'type: point-mass' or 'type: rigid-load')", *load));
      ok = false;
    } else {
      port_body[static_cast<int>(Role::load_z)] = z;
      port_body[static_cast<int>(Role::load_x)] = std::max(m.body_index(*load + ".x"), -1);
      port_body[static_cast<int>(Role::load_y)] = std::max(m.body_index(*load + ".y"), -1);
      port_body[static_cast<int>(Role::load_psi)] = std::max(m.body_index(*load + ".psi"), -1);
      rope->mass = m.bodies[static_cast<size_t>(z)].inertia;
    }
  } else {
    ok = false;
  }
  // The suspension point's bodies.
  struct Suspension {
    const char* key;
    Role role;
    BodyKind kind;
    const char* what;
  };
  const Suspension kSuspension[] = {{"trolley", Role::trolley, BodyKind::translational, "its travel x"},
                                    {"bridge", Role::bridge, BodyKind::translational, "its travel y"},
                                    {"jib", Role::jib, BodyKind::rotational, "its slewing angle"},
                                    {"drum", Role::drum, BodyKind::rotational, "its angle"}};
  for (const Suspension& s : kSuspension) {
    const SpecNode* n = f.node(s.key);
    if (!n) continue;
    const int i = n->is_scalar() ? m.body_index(n->scalar) : -2;
    if (i < 0) {
      f.error_at(s.key, i == kGround ? fmt::format("'{}' expected a body ({}), not the ground; leave it out", s.key, s.what)
                                     : fmt::format("'{}': unknown body '{}' (a {} body: {})", s.key,
                                                   n->is_scalar() ? n->scalar : "", spatial_rope_kind_text(s.kind), s.what));
      ok = false;
      continue;
    }
    if (m.bodies[static_cast<size_t>(i)].kind != s.kind) {
      f.error_at(s.key, fmt::format("'{}': body '{}' is {}; the {} of a spatial rope is a {} body ({})", s.key,
                                    n->scalar, spatial_rope_kind_text(m.bodies[static_cast<size_t>(i)].kind), s.key,
                                    spatial_rope_kind_text(s.kind), s.what));
      ok = false;
      continue;
    }
    port_body[static_cast<int>(s.role)] = i;
  }
  // The jib's radius: a translational body (the trolley on the jib) or a constant.
  if (const SpecNode* n = f.node("radius")) {
    if (port_body[static_cast<int>(Role::jib)] < 0 && !f.map().find("jib")) {
      f.error_at("radius", "a slewing 'radius' needs the 'jib' it is measured on (a rotational body)");
      ok = false;
    } else if (n->is_scalar() && m.body_index(n->scalar) >= 0) {
      const int i = m.body_index(n->scalar);
      if (m.bodies[static_cast<size_t>(i)].kind != BodyKind::translational) {
        f.error_at("radius", fmt::format("'radius': body '{}' is rotational; the radius on the jib is a translational "
                                         "body (the trolley on it) or a length", n->scalar));
        ok = false;
      }
      port_body[static_cast<int>(Role::radius)] = i;
    } else {
      std::string err;
      const std::optional<double> r = n->is_scalar() ? parse_as(n->scalar, dim::length, &err) : std::nullopt;
      if (!r || *r <= 0.0) {
        f.error_at("radius", r ? fmt::format("'radius' must be > 0, got {:g} m", *r)
                               : fmt::format("'radius' expected a body on the jib or a length (m){}",
                                             err.empty() ? "" : ": " + err));
        ok = false;
      } else {
        rope->r0 = *r;
      }
    }
  } else if (f.map().find("jib")) {
    f.error_at("jib", "a slewing 'jib' needs the load's 'radius' on it (a translational body or a length)");
    ok = false;
  }
  // A planar load swings in its plane only.
  if (port_body[static_cast<int>(Role::load_z)] >= 0) {
    const bool lx = port_body[static_cast<int>(Role::load_x)] >= 0, ly = port_body[static_cast<int>(Role::load_y)] >= 0;
    auto refuse = [&](const char* key, const char* why) {
      f.error_at(key, fmt::format("the load '{}' moves in the {} plane; {}", *load, lx ? "xz" : "yz", why));
      ok = false;
    };
    if (!ly && f.map().find("bridge")) refuse("bridge", "a bridge moves its suspension point along y: give the load axes [x, y, z]");
    if (!lx && f.map().find("trolley")) refuse("trolley", "a trolley moves its suspension point along x: give the load axes [x, y, z]");
    if ((!lx || !ly) && f.map().find("jib")) refuse("jib", "a slewing jib moves its suspension point in space: give the load axes [x, y, z]");
  }
  // A rigid load's attach point (its frame) and a planar load's suspension offset.
  if (const SpecNode* n = f.node("attach")) {
    std::vector<double> a;
    if (n->is_seq() && n->items.size() == 2)
      for (const SpecNode& item : n->items) {
        std::string err;
        const std::optional<double> v = item.is_scalar() ? parse_as(item.scalar, dim::length, &err) : std::nullopt;
        if (v) a.push_back(*v);
      }
    if (port_body[static_cast<int>(Role::load_psi)] < 0 && port_body[static_cast<int>(Role::load_z)] >= 0) {
      f.error_at("attach", fmt::format("'attach' is a point on a rigid load; '{}' is a point mass", *load));
      ok = false;
    } else if (a.size() != 2) {
      f.error_at("attach", "'attach' expected the rope's point on the load in its frame, two lengths "
                           "[along its horizontal axis, up], e.g. [2 m, 0.5 m]");
      ok = false;
    } else {
      rope->attach[0] = a[0], rope->attach[1] = a[1];
    }
  }
  if (f.map().find("offset")) {
    rope->offset = f.quantity("offset", dim::length).value_or(0.0);
    const bool lx = port_body[static_cast<int>(Role::load_x)] >= 0, ly = port_body[static_cast<int>(Role::load_y)] >= 0;
    if (lx && ly) {
      f.error_at("offset", "an 'offset' of the suspension point is along a planar load's horizontal axis; the load "
                           "moves in space");
      ok = false;
    }
  }
  // The rope: its length, EA, falls, damping; the drum's radius.
  const std::optional<double> L0 = f.positive("length", dim::length);
  std::optional<double> EA;
  const bool has_ea = f.map().find("EA") != nullptr, has_e = f.map().find("elastic_modulus") || f.map().find("area");
  if (has_ea && has_e) {
    f.error_at("EA", "give either 'EA' or 'elastic_modulus' and 'area', not both");
    f.node("EA"), f.node("elastic_modulus"), f.node("area");
  } else if (has_e) {
    auto E = f.positive("elastic_modulus", dim::force / (dim::length * dim::length));
    auto A = f.positive("area", dim::length * dim::length);
    if (E && A) EA = *E * *A;
  } else {
    EA = f.positive("EA", dim::force);
  }
  const int falls = static_cast<int>(f.integer("falls", 1, 1000, 1).value_or(1));
  const double d = f.positive("damping", dim::damping_lin, 0.0, true).value_or(0.0);
  std::optional<double> R;
  if (port_body[static_cast<int>(Role::drum)] >= 0 || f.map().find("drum")) {
    R = f.positive("drum_radius", dim::length);
  } else if (f.map().find("drum_radius")) {
    f.error_at("drum_radius", "a 'drum_radius' needs the 'drum' (a rotational body) the rope is wound on");
    f.node("drum_radius");
    ok = false;
  }
  const std::optional<double> height = f.map().find("height") ? f.quantity("height", dim::length) : std::nullopt;
  if (f.map().find("sway_after")) rope->sway_after = f.positive("sway_after", dim::time, 0.0, true).value_or(-1.0);
  if (!ok || !L0 || !EA || (port_body[static_cast<int>(Role::drum)] >= 0 && !R)) return nullptr;

  // The ports in their order, each body once.
  const Role kOrder[] = {Role::load_z, Role::load_x, Role::load_y, Role::load_psi, Role::trolley,
                         Role::bridge, Role::jib,    Role::radius, Role::drum};
  for (Role r : kOrder) {
    const int i = port_body[static_cast<int>(r)];
    if (i < 0) continue;
    for (int b : bodies)
      if (b == i) {
        f.error_at("load", fmt::format("the body '{}' is named twice; each of the rope's bodies is a body of its own",
                                       m.bodies[static_cast<size_t>(i)].name));
        return nullptr;
      }
    rope->role[rope->n_ports] = r;
    rope->port_of[static_cast<int>(r)] = rope->n_ports++;
    bodies.push_back(i);
  }
  LinkLaw& law = rope->law;
  law.gap = true, law.lo = -HUGE_VAL, law.hi = 0.0;  // one positive flank at e = 0 (elements/link.hpp)
  law.K = falls * *EA, law.L0 = *L0, law.falls = falls, law.d = d;
  law.c = law.K / *L0;
  if (rope->has(Role::drum)) {
    law.winding = true;
    law.inv_ratio = *R / falls;
    law.u0 = m.bodies[static_cast<size_t>(port_body[static_cast<int>(Role::drum)])].q0;
  } else {
    law.inv_ratio = 0.0;
  }
  // The suspension height: given, or where the load at z = 0 hangs at rest below it, L0 + m g/c
  // (a rigid load's centre at z = 0: its rope point at (R(ψ0) a)_z).
  double ra_z = 0.0;
  if (rope->has(Role::load_psi)) {
    const double psi0 = m.bodies[static_cast<size_t>(port_body[static_cast<int>(Role::load_psi)])].q0;
    ra_z = rope->attach[0] * std::sin(psi0) + rope->attach[1] * std::cos(psi0);
  }
  rope->h = height ? *height : ra_z + *L0 + rope->mass * m.gravity / law.c;
  return rope;
}

}  // namespace

}  // namespace machdyn::detail

MACHDYN_PLACED_ELEMENT_TYPE(spatial_rope, "spatial-rope", machdyn::detail::place_spatial_rope,
                            "load: L, trolley: T, jib: J, radius: R, drum: D, drum_radius: 0.2 m, falls: 2, length: 1.5 m, "
                            "EA: 3e4 N, damping: 50 N*s/m",
                            "L: {type: point-mass, mass: 100 kg, position: [1.8 m, 0.1 m, -0.3 m], velocity: [0.2 m/s, -0.1 m/s, 0]}, "
                            "T: {type: translational, mass: 50 kg}, J: {inertia: 20 kg*m^2}, "
                            "R: {type: translational, mass: 10 kg, position: 2 m}, D: {inertia: 1 kg*m^2}")
