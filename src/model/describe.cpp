// The model's elements in words (model/describe.hpp): the entry points; each kind's text is
// defined beside its compile code.
#include "machdyn/model/describe.hpp"
#include "machdyn/model/sheaves.hpp"

#include <cmath>

#include <fmt/format.h>

namespace machdyn {

namespace detail {
std::string describe_number(double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : std::string("–"); }
}  // namespace detail

ElementText describe_link(const Model& m, const Link& l) {
  using detail::describe_number;
  if (l.buffer) return {l.name, "buffer", detail::describe_buffer(m, l)};
  // A rope: falls or a free length; or tension only from a drum (rotational) to a hook
  // (translational) — a `flank` link (MSL's ElastoGap) joins bodies of one kind.
  const bool drum_to_hook = l.a != kGround && l.b != kGround &&
                            m.bodies[static_cast<size_t>(l.a)].kind == BodyKind::rotational &&
                            m.bodies[static_cast<size_t>(l.b)].kind == BodyKind::translational;
  if (is_rope_with_falls(l) || (l.tension_only && drum_to_hook)) return {l.name, "rope", detail::describe_rope(m, l)};
  // A spring, a damper or both, with a ratio and perhaps backlash.
  const int body = l.b != kGround ? l.b : l.a;
  const BodyKind k = body == kGround ? BodyKind::rotational : m.bodies[static_cast<size_t>(body)].kind;
  const std::string lu = load_unit(k), qu = position_unit(k);
  std::string def;
  if (l.kind != LinkKind::damper) def = fmt::format("c = {} {}/{}", describe_number(l.c), lu, qu);
  if (l.kind != LinkKind::spring)
    def += fmt::format("{}d = {} {}·s/{}", def.empty() ? "" : ", ", describe_number(l.d), lu, qu);
  if (l.has_gap) def += "; " + detail::describe_gap(m, l);
  if (l.delta0 != 0.0)
    def += fmt::format("; free length {} {} (load {} {} at δ = 0)", describe_number(-l.delta0), qu,
                       describe_number(-l.c * l.delta0), lu);
  const char* type = l.kind == LinkKind::damper ? "damper" : l.kind == LinkKind::spring ? "spring" : "spring-damper";
  return {l.name,
          l.tension_only ? std::string("one-sided ") + type : l.has_gap ? std::string(type) + " with backlash" : std::string(type),
          def};
}

ElementText describe_contact(const Model& m, const FrictionContact& c) { return detail::describe_friction_element(m, c); }

std::vector<ElementText> describe_gears(const Model& m) {
  std::vector<ElementText> out = detail::describe_ideal_gears(m);
  for (const LossyGear& g : m.lossy_gears)  // a rope's sheave losses are the rope's (model/sheaves.hpp)
    if (!is_sheave_gear(m, g)) out.push_back(detail::describe_lossy_gear(m, g));
  return out;
}

}  // namespace machdyn
