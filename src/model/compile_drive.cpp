#include "model/compile_drive.hpp"

#include <cmath>
#include <fmt/format.h>

#include "model/compile_signal.hpp"
#include "model/element_types.hpp"

namespace machdyn::detail {

std::vector<std::string> drive_types() {
  std::vector<std::string> names;
  for (const ElementType* t : element_types()) names.emplace_back(t->name);
  return names;
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
