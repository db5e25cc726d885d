// Element type `gear-mesh` (elements/gear_mesh.hpp) under `links:`, between a pinion and a wheel: its
// fields, compiled to SI at the pinion with located errors.
//   NAME: {type: gear-mesh, between: [PINION, WHEEL],
//          ratio (i = r_w/r_p), stiffness (N·m/rad at the pinion), damping (0), backlash (0 rad)
//       or pinion_radius, wheel_radius (base radii), stiffness (N/m along the line of action),
//          damping (0 N·s/m), backlash (0 m along the line of action);
//          efficiency (1)}
#include <fmt/format.h>

#include "machdyn/common/units.hpp"
#include "machdyn/elements/gear_mesh.hpp"
#include "model/element_types.hpp"

namespace {

std::shared_ptr<const machdyn::Element> compile_gear_mesh(machdyn::FieldReader& f, machdyn::BodyKind kind) {
  using namespace machdyn;
  if (kind != BodyKind::rotational) {
    f.error_at("between", "a gear mesh joins two rotational bodies (a pinion and a wheel)");
    for (const auto& [k, v] : f.map().fields) f.node(k);
    return nullptr;
  }
  auto g = std::make_shared<GearMesh>();
  const bool radii = f.map().find("pinion_radius") || f.map().find("wheel_radius");
  if (radii) {  // along the line of action: c = c_lin r_p², d = d_lin r_p², b = b_lin / r_p
    if (f.node("ratio")) f.error_at("ratio", "give either 'ratio' or the base radii 'pinion_radius' and 'wheel_radius'");
    const double rp = f.positive("pinion_radius", dim::length).value_or(1.0);
    const double rw = f.positive("wheel_radius", dim::length).value_or(1.0);
    g->r_p = rp;
    g->i = rw / rp;
    g->c = f.positive("stiffness", dim::stiffness_lin).value_or(1.0) * rp * rp;
    g->d = f.positive("damping", dim::damping_lin, 0.0, true).value_or(0.0) * rp * rp;
    g->b = f.positive("backlash", dim::length, 0.0, true).value_or(0.0) / rp;
  } else {
    g->i = f.positive("ratio", dim::none).value_or(1.0);
    g->c = f.positive("stiffness", dim::torque).value_or(1.0);
    g->d = f.positive("damping", dim::damping_rot, 0.0, true).value_or(0.0);
    g->b = f.positive("backlash", dim::none, 0.0, true).value_or(0.0);
  }
  const auto eta = f.positive("efficiency", dim::none, 1.0);
  if (eta && *eta > 1.0)
    f.error_at("efficiency", fmt::format("field 'efficiency' must be in (0, 1], got {:g}", *eta));
  g->eta = eta.value_or(1.0);
  return g;
}

}  // namespace

MACHDYN_LINK_ELEMENT_TYPE(gear_mesh, "gear-mesh", compile_gear_mesh,
                          "ratio: 3, stiffness: 2e4 N*m/rad, damping: 2 N*m*s/rad, backlash: 0.01 rad, efficiency: 0.95")
