#include "model/compile_drive.hpp"

#include <cmath>
#include <fmt/format.h>

#include "model/compile_signal.hpp"
#include "model/element_types.hpp"

namespace machdyn::detail {

std::vector<std::string> drive_types() {
  std::vector<std::string> names;
  for (const ElementType* t : element_types())
    if (t->bodies == 1) names.emplace_back(t->name);
  return names;
}

bool is_link_element_type(std::string_view type) {
  const ElementType* t = find_element_type(type);
  return t && t->bodies == 2;
}

void read_link_element(const std::string& name, const SpecNode& spec, Model& m, Diagnostics& diag) {
  FieldReader f(spec, fmt::format("link '{}'", name), diag);
  if (!spec.is_map()) return;  // reported by the reader
  const ElementType* type = find_element_type(*f.text("type"));
  const SpecNode* between = f.node("between");
  int idx[2] = {-1, -1};
  bool ok = between != nullptr;
  if (!between) {
    diag.error(spec.loc, fmt::format("link '{}': missing field 'between' (two body names, e.g. [pinion, wheel])", name));
  } else if (!between->is_seq() || between->items.size() != 2 || !between->items[0].is_scalar() ||
             !between->items[1].is_scalar()) {
    diag.error(between->loc, fmt::format("link '{}': 'between' expected two body names, e.g. [pinion, wheel]", name));
    ok = false;
  } else {
    auto kind_word = [](BodyKind k) { return k == BodyKind::rotational ? "rotational" : "translational"; };
    for (int k = 0; k < 2; ++k) {
      const SpecNode& item = between->items[static_cast<size_t>(k)];
      idx[k] = m.body_index(item.scalar);
      if (idx[k] < 0) {
        diag.error(item.loc, fmt::format("link '{}': unknown body '{}' (a {} joins two bodies with inertia)", name,
                                         item.scalar, type->name));
        ok = false;
      }
    }
    if (ok && m.bodies[static_cast<size_t>(idx[0])].kind != m.bodies[static_cast<size_t>(idx[1])].kind) {
      diag.error(between->loc, fmt::format("link '{}': a {} joins two bodies of one kind; '{}' is {}, '{}' {}", name,
                                           type->name, between->items[0].scalar,
                                           kind_word(m.bodies[static_cast<size_t>(idx[0])].kind),
                                           between->items[1].scalar,
                                           kind_word(m.bodies[static_cast<size_t>(idx[1])].kind)));
      ok = false;
    }
    if (ok && idx[0] == idx[1]) {
      diag.error(between->loc, fmt::format("link '{}': joins '{}' to itself", name, between->items[0].scalar));
      ok = false;
    }
  }
  if (!ok) {  // the fields' dimensions depend on the bodies: no cascade of messages
    for (const auto& [k, v] : spec.fields) f.node(k);
    return;
  }
  Drive d;
  d.name = name;
  d.body = idx[0];
  d.others = {idx[1]};
  d.law = type->compile(f, m.bodies[static_cast<size_t>(idx[0])].kind);
  f.finish();
  if (d.law) m.drives.push_back(std::move(d));
}

bool is_placed_element_type(std::string_view type) {
  const ElementType* t = find_element_type(type);
  return t && t->place;
}

void read_placed_element(const std::string& name, const SpecNode& spec, Model& m, Diagnostics& diag) {
  FieldReader f(spec, fmt::format("link '{}'", name), diag);
  if (!spec.is_map()) return;  // reported by the reader
  const ElementType* type = find_element_type(*f.text("type"));
  std::vector<int> bodies;
  auto law = type->place(f, m, bodies);
  f.finish();
  if (!law || bodies.empty()) return;
  Drive d;
  d.name = name;
  d.body = bodies[0];
  d.others.assign(bodies.begin() + 1, bodies.end());
  d.law = std::move(law);
  m.drives.push_back(std::move(d));
}

std::optional<Signal> signal_field(FieldReader& f, const char* key, const Dim& d) {
  const SpecNode* n = f.node(key);
  if (!n) {
    f.error_at(key, fmt::format("missing field '{}' ({} or a signal of it)", key, describe(d)));
    return std::nullopt;
  }
  return compile_signal(*n, d, fmt::format("{}: field '{}'", f.what(), key), f.diagnostics());
}

void compile_drives(const SpecNode* section, Model& m, Diagnostics& diag) {
  if (!section) return;
  if (!section->is_map()) {
    diag.error(section->loc, "'drives' must be a map of NAME: {fields}");
    return;
  }
  for (const auto& [name, spec] : section->fields) {
    FieldReader f(spec, fmt::format("drive '{}'", name), diag);
    if (!spec.is_map()) continue;  // reported by the reader
    if (const SpecNode* t = spec.find("type");
        t && t->is_scalar() && (is_link_element_type(t->scalar) || is_placed_element_type(t->scalar))) {
      diag.error(t->loc, fmt::format("drive '{}': type '{}' is not a kind of drives; a {} goes under 'links:'", name,
                                     t->scalar, t->scalar));
      continue;
    }
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
    d.law = find_element_type(*type)->compile(f, m.bodies[static_cast<size_t>(i)].kind);
    f.finish();
    if (d.law) m.drives.push_back(std::move(d));
  }
}

}  // namespace machdyn::detail
