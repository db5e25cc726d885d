#include "model/compile_crane.hpp"

#include <fmt/format.h>

namespace machdyn::detail {
namespace {

int link_index(const Model& m, const std::string& name) {
  for (size_t k = 0; k < m.links.size(); ++k)
    if (m.links[k].name == name) return static_cast<int>(k);
  return -1;
}

/// A list of link names (one name or a sequence); every name must be a link (of the kind `buffer`
/// when `buffers`).
std::vector<int> link_list(FieldReader& f, const char* key, const Model& m, bool buffers) {
  std::vector<int> out;
  const SpecNode* n = f.node(key);
  if (!n) return out;
  std::vector<const SpecNode*> items;
  if (n->is_scalar()) items.push_back(n);
  else if (n->is_seq())
    for (const auto& it : n->items) items.push_back(&it);
  for (const SpecNode* it : items) {
    if (!it->is_scalar()) {
      f.diagnostics().error(it->loc, fmt::format("crane: '{}' expected link names", key));
      continue;
    }
    const int k = link_index(m, it->scalar);
    if (k < 0 || (buffers && !m.links[static_cast<size_t>(k)].buffer))
      f.diagnostics().error(it->loc, fmt::format("crane: '{}': '{}' is not {}", key, it->scalar,
                                                 buffers ? "a buffer (under 'buffers:')" : "a link"));
    else
      out.push_back(k);
  }
  if (items.empty()) f.diagnostics().error(n->loc, fmt::format("crane: '{}' expected a link name or a list of them", key));
  return out;
}

}  // namespace

void compile_buffers(const SpecNode* buffers, Model& m, Diagnostics& diag) {
  if (!buffers) return;
  if (!buffers->is_map()) {
    diag.error(buffers->loc, "'buffers' must be a map of NAME: {fields}");
    return;
  }
  for (const auto& [name, spec] : buffers->fields) {
    FieldReader f(spec, fmt::format("buffer '{}'", name), diag);
    auto body = f.text("body");
    const int i = body ? m.body_index(*body) : -2;
    if (body && i < 0) f.error_at("body", fmt::format("unknown body '{}'", *body));
    if (i < 0) {
      for (const auto& [k, v] : spec.fields) f.node(k);
      continue;
    }
    const Body& b = m.bodies[static_cast<size_t>(i)];
    const bool rot = b.kind == BodyKind::rotational;
    const Dim qd = rot ? dim::none : dim::length, ld = rot ? dim::torque : dim::force;
    const bool has_min = spec.find("min") != nullptr, has_max = spec.find("max") != nullptr;
    if (has_min == has_max) {
      diag.error(spec.loc, fmt::format("buffer '{}': give one of 'min' (a buffer below the body: it pushes up) or "
                                       "'max' (above the body: it pushes down)", name));
      for (const auto& [k, v] : spec.fields) f.node(k);
      continue;
    }
    const bool upper = has_max;
    const double xb = f.quantity(upper ? "max" : "min", qd).value_or(0.0);
    Link l;
    l.name = name;
    l.buffer = true;
    l.tension_only = true;  // the one flank δ₊ (model/model.hpp)
    l.has_gap = true;
    l.c = f.positive("stiffness", ld / qd).value_or(0.0);
    l.d = f.positive("damping", ld / qd * dim::time, 0.0, true).value_or(0.0);
    l.kind = l.d > 0.0 ? LinkKind::spring_damper : LinkKind::spring;
    l.a = upper ? i : kGround;
    l.b = upper ? kGround : i;
    l.gap = upper ? xb : -xb;
    l.gap_start = 0.0;
    f.finish();
    if (upper ? b.q0 > xb : b.q0 < xb)
      f.error_at(upper ? "max" : "min", fmt::format("the initial position of '{}' ({}) lies beyond the buffer ({})",
                                                    b.name, b.q0, xb));
    m.links.push_back(l);
  }
}

void compile_crane(const SpecNode* crane, Model& m, Diagnostics& diag) {
  if (!crane) return;
  if (!crane->is_map()) {
    diag.error(crane->loc, "'crane' must be a map of fields (docs/crane-factors.md)");
    return;
  }
  FieldReader f(*crane, "crane", diag);
  CraneSpec& c = m.crane;
  c.given = true;
  auto hc = f.word("hoisting_class", {"HC1", "HC2", "HC3", "HC4"}, "HC2");
  if (hc) c.hoisting_class = (*hc)[2] - '0';
  auto hd = f.word("drive_class", {"HD1", "HD2", "HD3", "HD4", "HD5"}, "HD1");
  if (hd) c.drive_class = (*hd)[2] - '0';
  c.hoist_speed = f.positive("hoist_speed", dim::velocity, 0.0, true).value_or(0.0);
  c.creep_speed = f.positive("creep_speed", dim::velocity, 0.0, true).value_or(0.0);
  if ((c.drive_class == 2 || c.drive_class == 3) && !crane->find("creep_speed"))
    f.error_at("drive_class", fmt::format("crane: drive class HD{} hoists at the creep speed: give 'creep_speed'",
                                          c.drive_class));
  if (auto load = f.text("load", "")) {
    if (!load->empty()) {
      c.load = m.body_index(*load);
      if (c.load < 0) f.error_at("load", fmt::format("crane: unknown body '{}'", *load));
      else if (m.bodies[static_cast<size_t>(c.load)].vertical == 0)
        f.error_at("load", fmt::format("crane: the hook load '{}' needs its weight: give it 'vertical: up'", *load));
    }
  }
  if (auto rope = f.text("rope", "")) {
    if (!rope->empty()) {
      c.rope = link_index(m, *rope);
      if (c.rope < 0) f.error_at("rope", fmt::format("crane: unknown link '{}'", *rope));
      else if (c.load >= 0 && m.links[static_cast<size_t>(c.rope)].b != c.load)
        f.error_at("rope", fmt::format("crane: the rope '{}' must end at the load: between: [DRUM_OR_HOOK, {}]", *rope,
                                       m.bodies[static_cast<size_t>(c.load)].name));
    }
  }
  if ((c.load < 0) != (c.rope < 0) && diag.empty())
    f.error_at(c.load < 0 ? "load" : "rope", "crane: give both 'load' and 'rope' (the hoisting cases need both)");
  if (const SpecNode* rel = f.node("release")) {
    FieldReader r(*rel, "crane: release", diag);
    c.release_mass = r.positive("mass", dim::mass).value_or(-1.0);
    auto kind = r.word("kind", {"rapid", "slow"}, "rapid");
    c.rapid_release = !kind || *kind == "rapid";
    r.finish();
    if (c.load < 0) diag.error(rel->loc, "crane: a 'release' needs the hook 'load' and its 'rope'");
    else if (c.release_mass > m.bodies[static_cast<size_t>(c.load)].inertia)
      r.error_at("mass", fmt::format("crane: the released mass {} kg exceeds the load's mass {} kg", c.release_mass,
                                     m.bodies[static_cast<size_t>(c.load)].inertia));
  }
  if (const SpecNode* drive = f.node("drive")) {
    FieldReader d(*drive, "crane: drive", diag);
    c.drive_links = link_list(d, "links", m, false);
    if (!drive->find("links")) d.error_at("links", "crane: drive: missing field 'links' (the drive links of the φ5 case)");
    auto change = d.word("force_change", {"centrifugal", "smooth", "sudden", "backlash"}, "smooth");
    if (change)
      c.force_change = *change == "centrifugal" ? 0 : *change == "smooth" ? 1 : *change == "sudden" ? 2 : 3;
    d.finish();
  }
  c.buffers = link_list(f, "buffers", m, true);
  f.finish();
}

}  // namespace machdyn::detail
