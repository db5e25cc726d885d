#include "model/compile_point_mass.hpp"

#include <fmt/format.h>

#include "machdyn/common/units.hpp"

namespace machdyn::detail {

bool is_point_mass(const SpecNode& spec) {
  const SpecNode* t = spec.is_map() ? spec.find("type") : nullptr;
  return t && t->is_scalar() && (t->scalar == "point-mass" || t->scalar == "rigid-load");
}

namespace {

/// A list of one quantity of dimension `d` per axis (`key` absent: zeros); problems located.
std::vector<double> point_mass_per_axis(FieldReader& f, const char* key, const Dim& d, size_t axes, Diagnostics& diag) {
  std::vector<double> out(axes, 0.0);
  const SpecNode* n = f.node(key);
  if (!n) return out;
  if (!n->is_seq() || n->items.size() != axes) {
    diag.error(n->loc, fmt::format("{}: '{}' expected {} values, one per axis ({}), e.g. [{}]", f.what(), key, axes,
                                   describe(d), axes == 2 ? "0 m, -1 m" : "0 m, 0 m, -1 m"));
    return out;
  }
  for (size_t k = 0; k < axes; ++k) {
    const SpecNode& item = n->items[k];
    std::string err;
    const std::optional<double> v = item.is_scalar() ? parse_as(item.scalar, d, &err) : std::nullopt;
    if (!v) {
      diag.error(item.loc, fmt::format("{}: '{}' item {}: {}", f.what(), key, k + 1,
                                       err.empty() ? "expected " + describe(d) : err));
      continue;
    }
    out[k] = *v;
  }
  return out;
}

}  // namespace

void compile_point_mass(const std::string& name, const SpecNode& spec, Model& m, Diagnostics& diag) {
  FieldReader f(spec, fmt::format("body '{}'", name), diag);
  const bool rigid = f.text("type").value_or("") == "rigid-load";
  const std::optional<double> mass = f.positive("mass", dim::mass);
  // A rigid load: its moment of inertia J about its centre and its angle ψ in its vertical plane.
  const std::optional<double> J = rigid ? f.positive("inertia", dim::inertia) : std::nullopt;
  std::vector<std::string> axes = rigid ? std::vector<std::string>{"x", "z"} : std::vector<std::string>{"x", "y", "z"};
  if (const SpecNode* a = f.node("axes")) {
    std::vector<std::string> given;
    if (a->is_seq())
      for (const SpecNode& item : a->items) given.push_back(item.is_scalar() ? item.scalar : "?");
    if (given == std::vector<std::string>{"x", "z"} || given == std::vector<std::string>{"y", "z"} ||
        (!rigid && given == std::vector<std::string>{"x", "y", "z"}))
      axes = given;
    else if (rigid)
      diag.error(a->loc, fmt::format("body '{}': a rigid load moves in a vertical plane: 'axes' expected [x, z] or "
                                     "[y, z]; z points up", name));
    else
      diag.error(a->loc, fmt::format("body '{}': 'axes' expected [x, z] or [y, z] (a load in a vertical plane) or "
                                     "[x, y, z] (in space); z points up", name));
  }
  const std::vector<double> q0 = point_mass_per_axis(f, "position", dim::length, axes.size(), diag);
  const std::vector<double> v0 = point_mass_per_axis(f, "velocity", dim::velocity, axes.size(), diag);
  const double psi0 = rigid ? f.quantity("angle", dim::none, 0.0).value_or(0.0) : 0.0;
  const double omega0 = rigid ? f.quantity("angular_velocity", dim::angular_velocity, 0.0).value_or(0.0) : 0.0;
  f.finish();
  for (size_t k = 0; k < axes.size(); ++k) {
    Body b;
    b.name = name + "." + axes[k];
    b.kind = BodyKind::translational;
    b.inertia = mass.value_or(1.0);
    b.q0 = q0[k], b.v0 = v0[k];
    if (axes[k] == "z") b.vertical = 1;  // z up: its weight −m g
    m.bodies.push_back(std::move(b));
  }
  if (rigid) {  // ψ: a rotational body of inertia J (the mass matrix stays diagonal in x, z, ψ)
    Body b;
    b.name = name + ".psi";
    b.kind = BodyKind::rotational;
    b.inertia = J.value_or(1.0);
    b.q0 = psi0, b.v0 = omega0;
    m.bodies.push_back(std::move(b));
  }
}

}  // namespace machdyn::detail
