#include "model/compile_crane.hpp"
#include "machdyn/model/describe.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "machdyn/common/units.hpp"

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
  // An empty list `[]` names none (a load case may switch a case off this way).
  if (items.empty() && !n->is_seq())
    f.diagnostics().error(n->loc, fmt::format("crane: '{}' expected a link name or a list of them", key));
  return out;
}

/// The buffer's characteristic (model/model.hpp, law in elements/link.hpp) into l: `linear`
/// (stiffness), `progressive` (exponent, force at stroke), `hydraulic` (hydraulic_damping, an
/// optional return-spring stiffness) or `table` ([[stroke, force], ...] from [0, 0], strokes
/// increasing, forces ≥ 0); `damping` (linear, N·s/m) may join each. Problems are located.
void read_characteristic(FieldReader& f, const Dim& qd, const Dim& ld, Link& l) {
  using C = Link::Characteristic;
  const auto ch = f.word("characteristic", {"linear", "progressive", "hydraulic", "table"}, "linear");
  l.d = f.positive("damping", ld / qd * dim::time, 0.0, true).value_or(0.0);
  if (!ch || *ch == "linear") {
    l.c = f.positive("stiffness", ld / qd).value_or(0.0);
    return;
  }
  if (*ch == "progressive") {
    l.characteristic = C::progressive;
    const auto n = f.quantity("exponent", dim::none);
    const auto F = f.positive("force", ld);
    const auto s = f.positive("stroke", qd);
    if (n && !(*n > 1.0)) f.error_at("exponent", fmt::format("the exponent of a progressive buffer must be > 1 "
                                                         "(1 is 'characteristic: linear'), got {}", *n));
    if (!n || !F || !s || !(*n > 1.0)) return;
    l.exponent = *n;
    l.coefficient = *F / std::pow(*s, *n);  // F = c sⁿ through (s_ref, F_ref)
    l.c = *n * *F / *s;                     // the slope there (a representative stiffness)
    return;
  }
  if (*ch == "hydraulic") {
    l.characteristic = C::hydraulic;
    const Dim wd = qd / dim::time;
    l.hydraulic_k = f.positive("hydraulic_damping", ld / (wd * wd)).value_or(0.0);
    l.c = f.positive("stiffness", ld / qd, 0.0, true).value_or(0.0);  // the return spring
    return;
  }
  l.characteristic = C::table;
  const SpecNode* t = f.node("table");
  if (!t) {
    f.error_at("table", "missing field 'table' ([[stroke, force], ...] from [0, 0])");
    return;
  }
  Diagnostics& diag = f.diagnostics();
  if (!t->is_seq() || t->items.size() < 2) {
    diag.error(t->loc, fmt::format("{}: 'table' expected two or more [stroke, force] pairs", f.what()));
    return;
  }
  bool ok = true;
  for (const auto& p : t->items) {
    if (!p.is_seq() || p.items.size() != 2 || !p.items[0].is_scalar() || !p.items[1].is_scalar()) {
      diag.error(p.loc, fmt::format("{}: expected a pair [stroke, force]", f.what()));
      ok = false;
      continue;
    }
    std::string e[2];
    const auto s = parse_as(p.items[0].scalar, qd, &e[0]);
    const auto F = parse_as(p.items[1].scalar, ld, &e[1]);
    for (int k = 0; k < 2; ++k)
      if (!e[k].empty() || !(k == 0 ? s : F)) {
        diag.error(p.items[static_cast<size_t>(k)].loc, fmt::format("{}: {}", f.what(), e[k]));
        ok = false;
      }
    if (!s || !F) continue;
    const bool first = l.table_stroke.empty();
    if (first && (*s != 0.0 || *F != 0.0)) {
      diag.error(p.loc, fmt::format("{}: the table starts at [0, 0] (contact begins at the buffer's position "
                                    "without force), got [{}, {}]", f.what(), *s, *F));
      ok = false;
    } else if (!first && !(*s > l.table_stroke.back())) {
      diag.error(p.items[0].loc, fmt::format("{}: the strokes must increase, got {} after {}", f.what(), *s,
                                             l.table_stroke.back()));
      ok = false;
    } else if (*F < 0.0) {
      diag.error(p.items[1].loc, fmt::format("{}: a buffer force must be >= 0, got {}", f.what(), *F));
      ok = false;
    }
    l.table_stroke.push_back(*s);
    l.table_force.push_back(*F);
  }
  if (ok && l.table_force.back() <= 0.0) {
    diag.error(t->loc, fmt::format("{}: the table carries no force", f.what()));
    ok = false;
  }
  if (!ok) return;
  for (size_t k = 1; k < l.table_stroke.size(); ++k)  // the steepest slope (a representative stiffness)
    l.c = std::max(l.c, (l.table_force[k] - l.table_force[k - 1]) / (l.table_stroke[k] - l.table_stroke[k - 1]));
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
    read_characteristic(f, qd, ld, l);
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
  if (c.creep_speed > 0.0 && c.hoist_speed > 0.0 && c.creep_speed > c.hoist_speed)
    f.error_at("creep_speed", fmt::format("the creep speed {:.6g} m/s exceeds the hoisting speed 'hoist_speed' "
                                          "{:.6g} m/s; the creep speed is the slow speed the load is taken up with",
                                          c.creep_speed, c.hoist_speed));
  if ((c.drive_class == 2 || c.drive_class == 3) && !crane->find("creep_speed"))
    f.error_at("drive_class", fmt::format("drive class HD{} hoists at the creep speed: give 'creep_speed'",
                                          c.drive_class));
  if (auto load = f.text("load", "")) {
    if (!load->empty()) {
      c.load = m.body_index(*load);
      if (c.load < 0) f.error_at("load", fmt::format("unknown body '{}'", *load));
      else if (m.bodies[static_cast<size_t>(c.load)].vertical == 0)
        f.error_at("load", fmt::format("the hook load '{}' needs its weight: give it 'vertical: up'", *load));
    }
  }
  if (auto rope = f.text("rope", "")) {
    if (!rope->empty()) {
      c.rope = link_index(m, *rope);
      if (c.rope < 0) f.error_at("rope", fmt::format("unknown link '{}'", *rope));
      else if (c.load >= 0 && m.links[static_cast<size_t>(c.rope)].b != c.load)
        f.error_at("rope", fmt::format("the rope '{}' must end at the load: between: [DRUM_OR_HOOK, {}]", *rope,
                                       m.bodies[static_cast<size_t>(c.load)].name));
    }
  }
  if ((c.load < 0) != (c.rope < 0) && diag.empty())
    f.error_at(c.load < 0 ? "load" : "rope", "give both 'load' and 'rope' (the hoisting cases need both)");
  if (const SpecNode* rel = f.node("release")) {
    FieldReader r(*rel, "crane: release", diag);
    c.release_mass = r.positive("mass", dim::mass).value_or(-1.0);
    auto kind = r.word("kind", {"rapid", "slow"}, "rapid");
    c.rapid_release = !kind || *kind == "rapid";
    // Released during a run (a Release at t_r): hanging at rest with the drum held, or hoisting.
    if (rel->is_map() && rel->find("time")) c.release_time = r.positive("time", dim::time, std::nullopt, true).value_or(-1.0);
    auto during = r.word("while", {"hanging", "hoisting"}, "hanging");
    c.release_hoisting = during && *during == "hoisting";
    if (rel->is_map() && rel->find("while") && !rel->find("time"))
      r.error_at("while", "'while' needs the release 'time' (without it the load is released at once "
                          "from the hanging equilibrium)");
    if (c.release_hoisting && !(c.hoist_speed > 0.0))
      r.error_at("while", "'while: hoisting' hoists at 'hoist_speed': give it in the crane section");
    r.finish();
    if (c.load < 0) diag.error(rel->loc, "crane: a 'release' needs the hook 'load' and its 'rope'");
    else if (c.release_mass > m.bodies[static_cast<size_t>(c.load)].inertia)
      r.error_at("mass", fmt::format("the released mass {} kg exceeds the load's mass {} kg", c.release_mass,
                                     m.bodies[static_cast<size_t>(c.load)].inertia));
  }
  if (const SpecNode* drive = f.node("drive")) {
    FieldReader d(*drive, "crane: drive", diag);
    c.drive_links = link_list(d, "links", m, false);
    if (!drive->find("links")) d.error_at("links", "missing field 'links' (the drive links of the φ5 case)");
    auto change = d.word("force_change", {"centrifugal", "smooth", "sudden", "backlash"}, "smooth");
    if (change)
      c.force_change = *change == "centrifugal" ? 0 : *change == "smooth" ? 1 : *change == "sudden" ? 2 : 3;
    d.finish();
  }
  c.buffers = link_list(f, "buffers", m, true);
  f.finish();
}


// A buffer as the file wrote it: its side, position and characteristic (Link::Characteristic).
std::string describe_buffer(const Model& m, const Link& l) {
  const bool lower = l.a == kGround;  // [ground, body]: δ = −q, δ₊ = −x_b
  const int body = lower ? l.b : l.a;
  const BodyKind k = m.bodies[static_cast<size_t>(body)].kind;
  const std::string qu = position_unit(k), lu = load_unit(k);
  std::string t = fmt::format("{} buffer of '{}' at {} {}: ", lower ? "lower" : "upper", m.bodies[static_cast<size_t>(body)].name,
                              describe_number(lower ? -l.gap : l.gap), qu);
  switch (l.characteristic) {
    case Link::Characteristic::linear: t += fmt::format("linear, c = {} {}/{}", describe_number(l.c), lu, qu); break;
    case Link::Characteristic::progressive:
      t += fmt::format("progressive F = c·sⁿ, c = {} {}/{}ⁿ, n = {}", describe_number(l.coefficient), lu, qu,
                       describe_number(l.exponent));
      break;
    case Link::Characteristic::hydraulic:
      t += fmt::format("hydraulic F = c s + d v + k v|v|, c = {} {}/{}, k = {} {}·s²/{}²", describe_number(l.c), lu, qu,
                       describe_number(l.hydraulic_k), lu, qu);
      break;
    case Link::Characteristic::table:
      t += fmt::format("force–stroke table of {} points up to s = {} {}, F = {} {}", l.table_stroke.size(),
                       describe_number(l.table_stroke.empty() ? 0.0 : l.table_stroke.back()), qu,
                       describe_number(l.table_force.empty() ? 0.0 : l.table_force.back()), lu);
      break;
  }
  if (l.d > 0.0) t += fmt::format(", d = {} {}·s/{}", describe_number(l.d), lu, qu);
  return t + "; compression only";
}

}  // namespace machdyn::detail
