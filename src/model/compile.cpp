#include "machdyn/model/compile.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string_view>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "machdyn/model/cases.hpp"
#include "machdyn/model/machine.hpp"
#include "machdyn/common/expression.hpp"
#include "compile_hybrid.hpp"
#include "compile_rope.hpp"
#include "model/compile_drive.hpp"
#include "model/compile_signal.hpp"
#include "model/compile_machine.hpp"
#include "model/compile_motion.hpp"
#include "model/compile_point_mass.hpp"
#include "model/compile_crane.hpp"
#include "model/compile_joint.hpp"
#include "model/compile_lossy.hpp"
#include "model/compile_sheaves.hpp"
#include "model/compile_release.hpp"
#include "model/body_dims.hpp"
#include "model/compile_rigid.hpp"
#include "model/element_types.hpp"

namespace machdyn {
namespace {

/// The section an element of this `type` belongs in, or "" (a hint for `type: brake` under loads).
std::string_view section_of_type(std::string_view type) {
  static const std::pair<std::string_view, std::string_view> kTypes[] = {
      {"rotational", "bodies"}, {"translational", "bodies"}, {"spring", "links"},      {"damper", "links"},
      {"spring-damper", "links"}, {"constant", "loads"},     {"step", "loads"},        {"ramp", "loads"},
      {"table", "loads"},       {"motor-linear", "loads"},   {"motor-kloss", "loads"}, {"brake", "brakes"},
      {"sine", "loads"},        {"pulse", "loads"},          {"expression", "loads"},  {"sum", "loads"},
      {"file", "loads"},        {"drag", "loads"},           {"eddy-current-brake", "loads"},
      {"motor-table", "loads"},
      {"contact", "contacts"},  {"friction", "contacts"},    {"clutch", "clutches"},    {"gap", "links"}, {"rope", "links"},
      {"freewheel", "freewheels"}, {"one-way-clutch", "freewheels"}, {"stop", "stops"}, {"end-stop", "stops"},
      {"buffer", "buffers"}, {"ideal-gear", "links"}, {"lossy-gear", "links"}, {"planetary-gear", "links"}};
  for (const auto& [t, sec] : kTypes)
    if (t == type) return sec;
  if (const detail::ElementType* t = detail::find_element_type(type)) return t->section;  // model/element_types.hpp
  return {};
}

/// Reports a `type` that belongs to another section (true: reported; the element is skipped).
bool wrong_section(const SpecNode& spec, std::string_view section, const std::string& what, Diagnostics& diag) {
  const SpecNode* t = spec.is_map() ? spec.find("type") : nullptr;
  if (!t || !t->is_scalar()) return false;
  const std::string_view home = section_of_type(t->scalar);
  if (home.empty() || home == section) return false;
  diag.error(t->loc, fmt::format("{}: type '{}' is not a kind of {}; a {} goes under '{}:'", what, t->scalar,
                                 section, t->scalar, home));
  return true;
}

/// Element names are unique across every section (`--set NAME.FIELD` must find one element) and free
/// of '.' (it separates NAME from FIELD, and BODY.piston names a machine's output point).
void check_names(const SpecNode& root, Model& m, Diagnostics& diag) {
  std::unordered_map<std::string_view, std::pair<std::string_view, const SpecNode*>> seen;
  for (const std::string& section : element_sections()) {
    const SpecNode* sec = root.find(section);
    if (!sec || !sec->is_map()) continue;
    for (const auto& [name, spec] : sec->fields) {
      if (name.find('.') != std::string::npos)
        diag.error(spec.key_loc, fmt::format("{} name '{}' contains '.', which separates NAME.FIELD in --set; "
                                             "expected a name without '.'", section, name));
      // A name is a column of CSV tables, one line each (a sweep's journal is read line by line).
      if (std::any_of(name.begin(), name.end(), [](char ch) { return static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f; }))
        diag.error(spec.key_loc, fmt::format("{} name contains a control character (newline, tab, ...); expected a "
                                             "name on one line", section));
      m.element_where.try_emplace(name, Location(spec.key_loc));
      auto [it, fresh] = seen.try_emplace(name, section, &spec);
      if (!fresh)
        diag.error(spec.key_loc, fmt::format("the name '{}' (under '{}') is already used under '{}' at {}; names must "
                                             "be unique across {}", name, section, it->second.first,
                                             it->second.second->key_loc.str(), fmt::join(element_sections(), ", ")));
    }
  }
}

void compile_bodies(const SpecNode* section, Model& m, Diagnostics& diag) {
  if (!section) return;
  if (!section->is_map()) {
    diag.error(section->loc, "'bodies' must be a map of NAME: {fields}");
    return;
  }
  for (const auto& [name, spec] : section->fields) {
    if (is_machine_type(spec)) {  // variable inertia: model/compile_machine.cpp
      m.bodies.push_back(compile_machine_body(name, spec, diag));
      continue;
    }
    if (detail::is_point_mass(spec)) {  // a load in the plane or in space: model/compile_point_mass.cpp
      detail::compile_point_mass(name, spec, m, diag);
      continue;
    }
    if (wrong_section(spec, "bodies", fmt::format("body '{}'", name), diag)) continue;
    FieldReader f(spec, fmt::format("body '{}'", name), diag);
    if (name == "ground") diag.error(spec.loc, "'ground' is reserved for the fixed frame; name the body otherwise");
    Body b;
    b.name = name;
    auto type = f.word("type", {"rotational", "translational"}, "rotational");
    b.kind = type && *type == "translational" ? BodyKind::translational : BodyKind::rotational;
    // 0 (a massless flange) is checked once the ideal gears are known (model/compile_rigid.cpp).
    auto inertia = b.kind == BodyKind::rotational ? f.positive("inertia", dim::inertia, std::nullopt, true)
                                                   : f.positive("mass", dim::mass, std::nullopt, true);
    b.inertia = inertia.value_or(1.0);
    b.q0 = f.quantity("position", detail::position_dim(b.kind), 0.0).value_or(0.0);
    b.v0 = f.quantity("velocity", detail::velocity_dim(b.kind), 0.0).value_or(0.0);
    if (f.map().find("vertical")) {
      auto up = f.word("vertical", {"up", "down"});
      if (b.kind != BodyKind::translational)
        f.error_at("vertical", fmt::format("body '{}': 'vertical' gives a translational body its weight; a rotational "
                                           "body has none (give its gravity torque as a load)", name));
      else if (up)
        b.vertical = *up == "up" ? 1 : -1;
    }
    detail::read_motion(f, b);
    f.finish();
    m.bodies.push_back(b);
  }
}

/// Fills the given_* names (model.hpp: Link::given_a) from the bodies the elements are on now.
void remember_given_bodies(Model& m) {
  auto name = [&](int b) { return shown_body(m, b, ""); };
  for (Link& l : m.links) {
    if (l.given_a.empty()) l.given_a = name(l.a);  // a rope's drum is set already (model/compile_sheaves.cpp)
    l.given_b = name(l.b);
  }
  for (FrictionContact& c : m.contacts) c.given_a = name(c.a), c.given_b = name(c.b);
  for (Load& ld : m.loads) ld.given_body = name(ld.body);
  for (Drive& d : m.drives) {
    d.given_body = name(d.body);
    d.given_others.clear();
    for (int o : d.others) d.given_others.push_back(name(o));
  }
}

void compile_links(const SpecNode* section, Model& m, std::vector<detail::IdealGear>& gears,
                   std::vector<detail::LossyGearSpec>& lossy, std::vector<detail::JointSpec>& joints,
                   std::vector<std::pair<std::string, const SpecNode*>>& placed, Diagnostics& diag) {
  if (!section) return;
  if (!section->is_map()) {
    diag.error(section->loc, "'links' must be a map of NAME: {fields}");
    return;
  }
  for (const auto& [name, spec] : section->fields) {
    if (wrong_section(spec, "links", fmt::format("link '{}'", name), diag)) continue;
    const SpecNode* type_node = spec.is_map() ? spec.find("type") : nullptr;
    const std::string kind = type_node && type_node->is_scalar() ? type_node->scalar : "";
    if (const SpecNode* h = spec.is_map() ? spec.find("housing") : nullptr;
        kind == "ideal-gear" && h && !(h->is_scalar() && h->scalar == "ground")) {
      detail::read_housed_gear(name, spec, m, joints, diag);  // a joint: model/compile_joint.cpp
      continue;
    }
    if (kind == "ideal-gear") {
      detail::read_ideal_gear(name, spec, m, gears, diag);  // a rigid connection: model/compile_rigid.cpp
      continue;
    }
    if (kind == "planetary-gear") {
      detail::read_planetary_gear(name, spec, m, joints, diag);  // a joint: model/compile_joint.cpp
      continue;
    }
    if (kind == "lossy-gear") {
      detail::read_lossy_gear(name, spec, m, lossy, diag);  // model/compile_lossy.cpp
      continue;
    }
    if (detail::is_placed_element_type(kind)) {  // an element naming its bodies (a spatial rope): after gravity
      placed.emplace_back(name, &spec);
      continue;
    }
    if (detail::is_link_element_type(kind)) {  // a registered element between two bodies (a gear mesh)
      detail::read_link_element(name, spec, m, diag);  // model/compile_drive.cpp
      continue;
    }
    FieldReader f(spec, fmt::format("link '{}'", name), diag);
    Link l;
    l.name = name;
    auto type = f.word("type", {"spring", "damper", "spring-damper", "rope", "ideal-gear", "lossy-gear", "planetary-gear"});
    const SpecNode* between = f.node("between");
    bool ends_ok = false;
    if (!between) {
      diag.error(spec.loc, fmt::format("link '{}': missing field 'between' (two body names, e.g. [I1, I2])", name));
    } else if (!between->is_seq() || between->items.size() != 2 || !between->items[0].is_scalar() ||
               !between->items[1].is_scalar()) {
      diag.error(between->loc, fmt::format("link '{}': 'between' expected two body names, e.g. [I1, I2]", name));
    } else {
      ends_ok = true;
      int idx[2];
      bool point[2];
      for (int k = 0; k < 2; ++k) {
        const auto& item = between->items[static_cast<size_t>(k)];
        std::string why;
        idx[k] = resolve_link_end(m, item.scalar, &point[k], &why);  // "BODY" or "BODY.piston"
        if (idx[k] == -2) {
          diag.error(item.loc, fmt::format("link '{}': {}", name, why));
          ends_ok = false;
        }
      }
      l.a_point = point[0];
      l.b_point = point[1];
      l.a = idx[0];
      l.b = idx[1];
      if (ends_ok && l.a == l.b) {
        diag.error(between->loc, fmt::format("link '{}': joins '{}' to itself", name, between->items[0].scalar));
        ends_ok = false;
      }
    }
    // Dimensions follow the bodies: ratio = [q_a]/[q_b]; stiffness = [load]/[q] of the loaded side.
    BodyKind ka = BodyKind::rotational, kb = BodyKind::rotational;
    if (ends_ok) {
      ka = l.a != kGround ? m.bodies[static_cast<size_t>(l.a)].kind : (l.b != kGround ? m.bodies[static_cast<size_t>(l.b)].kind : ka);
      kb = l.b != kGround ? m.bodies[static_cast<size_t>(l.b)].kind : ka;
      if (l.a_point) ka = BodyKind::translational;  // a machine's output point moves in m
      if (l.b_point || (l.b == kGround && l.a_point)) kb = BodyKind::translational;
    }
    BodyKind side = kb;
    if (ends_ok && (l.a == kGround || l.b == kGround)) {
      if (f.map().find("ratio")) f.error_at("ratio", "a link to the ground has no ratio");
      f.node("ratio");
    } else {
      auto r = f.quantity("ratio", detail::position_dim(ka) / detail::position_dim(kb), 1.0);
      if (r && *r == 0.0) f.error_at("ratio", "field 'ratio' must not be zero");
      l.ratio = r.value_or(1.0);
    }
    const Dim qd = detail::position_dim(side), ld = detail::load_dim(side);
    const bool rope = type && *type == "rope";
    bool needs_c = type && (*type == "spring" || *type == "spring-damper" || rope);
    bool needs_d = type && (*type == "damper" || *type == "spring-damper");
    if (type) l.kind = *type == "spring" ? LinkKind::spring : *type == "damper" ? LinkKind::damper : LinkKind::spring_damper;
    if (rope) {  // tension only: a spring (and damper, if given) on its positive flank at the slack
      l.d = f.positive("damping", ld / qd * dim::time, 0.0, true).value_or(0.0);
      l.tension_only = true;
      l.has_gap = true;
      l.gap = f.positive("slack", qd, 0.0, true).value_or(0.0);
      l.gap_start = 0.0;
    }
    // A rope with a free length (model/model.hpp Link::EA; law: elements/link.hpp): c = n E A / L_f.
    if (rope) needs_c = !detail::compile_rope_length(f, l, ld, qd, side, ends_ok ? m.bodies : std::vector<Body>{});
    else
      for (const char* k : {"EA", "elastic_modulus", "area", "length", "falls", "rope_ends", "sheave_efficiency", "frame"})
        if (type && f.map().is_map() && f.map().find(k)) {
          f.error_at(k, fmt::format("field '{}' belongs to a rope (type: rope)", k));
          f.node(k);
        }
    if (needs_c) l.c = f.positive("stiffness", ld / qd).value_or(0.0);
    else if (type && !rope && f.node("stiffness"))  // a rope with a length reports its own
      f.error_at("stiffness", fmt::format("a {} has no stiffness; use type spring-damper", *type));
    if (needs_d) l.d = f.positive("damping", ld / qd * dim::time, std::nullopt, true).value_or(0.0);
    else if (type && !rope && f.node("damping"))
      f.error_at("damping", fmt::format("a {} has no damping; use type spring-damper", *type));
    if (rope) {
      for (const char* k : {"gap", "gap_start", "flank"})
        if (f.map().find(k)) f.error_at(k, fmt::format("a rope has no '{}'; its 'slack' is the free play", k));
      f.node("gap"), f.node("gap_start"), f.node("flank");
    } else {
      detail::compile_link_gap(f, l, qd);
    }
    // A spring's free length or preload (Link::delta0; law: elements/link.hpp): F = c (δ − δ₀) + d δ̇.
    if (f.map().is_map() && (f.map().find("free_length") || f.map().find("preload"))) {
      const bool fl = f.map().find("free_length") != nullptr;
      const char* key = fl ? "free_length" : "preload";
      if (fl && f.map().find("preload")) f.error_at("preload", "give either 'free_length' or 'preload', not both");
      else if (type && (!needs_c || rope))
        f.error_at(key, fmt::format("field '{}' belongs to a spring or spring-damper ({})", key,
                                    rope ? "a rope's free play is its 'slack'" : "a damper has no spring"));
      else if (l.has_gap)
        f.error_at(key, fmt::format("a link with a 'gap' or a 'flank' carries its load from its flanks; give no '{}'", key));
      else if (l.a_point || l.b_point)
        f.error_at(key, fmt::format("a link to a machine's output point has no '{}'", key));
      else if (fl) {
        if (auto L0 = f.quantity("free_length", qd)) l.delta0 = -*L0;
      } else if (auto P = f.quantity("preload", ld); P && l.c > 0.0) {
        l.delta0 = -*P / l.c;
      }
    }
    f.node("free_length"), f.node("preload");
    // The flank law of a gap or rope: `linear` (F = c e + d δ̇) or `elasto-backlash` (damping capped).
    const bool law_given = f.map().is_map() && f.map().find("flank_law");
    if (auto law = f.word("flank_law", {"linear", "elasto-backlash"}, "linear")) {
      l.damping_capped = *law == "elasto-backlash";
      if (law_given && !l.has_gap)
        f.error_at("flank_law", "field 'flank_law' applies to a link with a 'gap' or a 'flank' or to a rope (it shapes "
                                "the load on a flank)");
    }
    f.finish();
    m.links.push_back(l);
  }
}

/// Types a load may have besides the signal kinds (model/compile_signal.hpp).
const std::vector<std::string>& load_types() {
  static const std::vector<std::string> k = [] {
    std::vector<std::string> v = detail::signal_types();
    for (const char* t : {"drag", "eddy-current-brake", "motor-linear", "motor-kloss", "motor-table"}) v.emplace_back(t);
    return v;
  }();
  return k;
}

/// Whether a motor's `on` is a bare 0 or 1 or a yes/no word (0, 1, 1.0, true, off, ...): such a time
/// needs its unit, since `on: 0` reads as "off" as often as "closes at t = 0" (`on: 0.5` is 0.5 s).
bool bare_switch_word(const std::string& text) {
  static const std::vector<std::string> words = {"true", "false", "yes", "no", "on", "off"};
  std::string low;
  for (char ch : text) low += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  if (std::find(words.begin(), words.end(), low) != words.end()) return true;
  if (low.empty()) return false;
  char* end = nullptr;
  const double x = std::strtod(low.c_str(), &end);
  return end && *end == '\0' && (x == 0.0 || x == 1.0);
}

/// A switching signal of a motor: `on`/`off` times or an `on` signal of 0 and 1; `direction` +1/−1
/// (or `reverse: TIME`). Sets ld.on, ld.direction, ld.switched.
void compile_motor_switching(FieldReader& f, Load& ld) {
  Diagnostics& diag = f.diagnostics();
  const SpecNode* on = f.node("on");
  auto off = f.quantity("off", dim::time, -1.0);
  std::optional<double> t_on;
  bool ok = true;
  if (on && on->is_map()) {  // a 0/1 signal
    auto s = detail::compile_signal(*on, dim::none, f.what() + ": field 'on'", diag);
    const auto lv = s ? s->levels() : std::vector<double>{};
    if (s && (lv.empty() || std::any_of(lv.begin(), lv.end(), [](double x) { return x != 0.0 && x != 1.0; }))) {
      diag.error(on->loc, fmt::format("{}: field 'on' expected a signal that is 0 (open) or 1 (closed): a step, a "
                                      "pulse or a table of flat pieces", f.what()));
      ok = false;
    } else if (s) {
      ld.on = *s;
    }
    if (off && *off >= 0.0) f.error_at("off", "field 'off' is a time; with an 'on' signal, give the opening in it");
  } else if (on && on->is_scalar() && bare_switch_word(on->scalar)) {
    // `on: 0` (or 1, true, off, ...) reads as "off"/"on" as often as "closes at t = 0": refused, with
    // both explicit forms (docs/model-files.md, Signals: `on`).
    diag.error(on->loc, fmt::format("{}: field 'on' is the time the contactor closes, and '{}' without a unit is "
                                    "ambiguous: write 'on: 0 s' for a contactor that closes at t = 0, or 'on: {{type: "
                                    "constant, value: 0}}' for a motor that stays off", f.what(), on->scalar));
    ok = false;
  } else if (on) {
    std::string e;
    t_on = on->is_scalar() ? parse_as(on->scalar, dim::time, &e) : std::nullopt;
    if (!t_on) diag.error(on->loc, fmt::format("{}: field 'on' expected the time the contactor closes or a signal of 0 "
                                               "and 1{}", f.what(), e.empty() ? "" : ": " + e)), ok = false;
  }
  if (ok && !(on && on->is_map()) && (t_on || (off && *off >= 0.0))) {
    const double a = t_on.value_or(0.0);
    if (off && *off >= 0.0 && *off <= a) {
      f.error_at("off", "field 'off' must be later than 'on'");
    } else if (off && *off >= 0.0) {
      ld.on = Signal::table({a, a, *off, *off}, {0.0, 1.0, 1.0, 0.0});
    } else {
      ld.on = Signal::step(0.0, 1.0, a);
    }
  }
  const SpecNode* dir = f.node("direction");
  auto reverse = f.quantity("reverse", dim::time, -1.0);
  if (dir && reverse && *reverse >= 0.0) f.error_at("reverse", "give either 'direction' or 'reverse', not both");
  if (dir) {
    auto s = detail::compile_signal(*dir, dim::none, f.what() + ": field 'direction'", diag);
    const auto lv = s ? s->levels() : std::vector<double>{};
    if (s && (lv.empty() || std::any_of(lv.begin(), lv.end(), [](double x) { return x != 1.0 && x != -1.0; })))
      diag.error(dir->loc, fmt::format("{}: field 'direction' expected +1 (forward) or -1 (reversed), or a signal of "
                                       "those (a step, a pulse or a table of flat pieces)", f.what()));
    else if (s)
      ld.direction = *s;
  } else if (reverse && *reverse >= 0.0) {
    ld.direction = Signal::step(1.0, -1.0, *reverse);
  }
  ld.switched = !(ld.on.kind() == Signal::Kind::constant && ld.on.value(0.0) == 1.0 &&
                  ld.direction.kind() == Signal::Kind::constant && ld.direction.value(0.0) == 1.0);
}

/// `scale`: a signal s(t) that multiplies a law of the state (drag, eddy-current-brake, a table over
/// speed or position): M = s(t) f(q, v), held in ld.on (model/model.hpp Load::on).
void compile_scale(FieldReader& f, Load& ld) {
  const SpecNode* n = f.node("scale");
  if (!n) return;
  auto s = detail::compile_signal(*n, dim::none, f.what() + ": field 'scale'", f.diagnostics());
  if (!s) return;
  ld.on = *s;
  ld.switched = !(s->kind() == Signal::Kind::constant && s->value(0.0) == 1.0);
}

void compile_loads(const SpecNode* section, Model& m, Diagnostics& diag) {
  if (!section) return;
  if (!section->is_map()) {
    diag.error(section->loc, "'loads' must be a map of NAME: {fields}");
    return;
  }
  for (const auto& [name, spec] : section->fields) {
    if (wrong_section(spec, "loads", fmt::format("load '{}'", name), diag)) continue;
    FieldReader f(spec, fmt::format("load '{}'", name), diag);
    Load ld;
    ld.name = name;
    auto type = f.word("type", load_types());
    auto body = f.text("body");
    BodyKind kind = BodyKind::rotational;
    bool body_ok = false;
    if (body) {
      int i = m.body_index(*body);
      if (i < 0) f.error_at("body", fmt::format("unknown body '{}'", *body));
      else {
        ld.body = i;
        kind = m.bodies[static_cast<size_t>(i)].kind;
        body_ok = true;
      }
    }
    const Dim vd = detail::load_dim(kind), wd = detail::velocity_dim(kind), qd = detail::position_dim(kind);
    if (!type || !body_ok) {  // field dimensions depend on both; avoid a cascade of messages
      for (const auto& [k, v] : spec.fields) f.node(k);
      continue;
    }
    const std::string& t = *type;
    const bool rot = kind == BodyKind::rotational;
    if (t == "expression") {  // M(t, q, v): a load law, not only a signal of t
      ld.kind = LoadKind::expression;
      auto text = f.text("expression");
      if (text) {
        try {
          ld.law = std::make_shared<const Expression>(
              *text, std::vector<std::string>{"t", rot ? "phi" : "x", rot ? "omega" : "v"});
          // A jump in the state has no event to stop at: refused; a kink (min, max) is continuous.
          for (int k : {1, 2})
            ld.law->refuse_switches(k, false, "a jump of the load with the state, which no step stops at; write a "
                                              "continuous law (min, max), a table over position or speed, or a "
                                              "friction contact");
        } catch (const ExpressionError& e) {
          f.error_at("expression", fmt::format("field 'expression' '{}': {} (an expression in t [s], {} and {} in SI; "
                                               "the value is {})", text->size() > 60 ? text->substr(0, 57) + "..." : *text,
                                               e.what(), rot ? "phi [rad]" : "x [m]", rot ? "omega [rad/s]" : "v [m/s]",
                                               describe(vd)));
        }
      }
      if (!ld.law) ld.law = std::make_shared<const Expression>("0", "t");
    } else if (t == "table" && f.map().find("over") && f.map().find("over")->is_scalar() &&
               f.map().find("over")->scalar != "time") {
      auto over = f.word("over", {"time", "speed", "position"});
      if (over) {
        const bool speed = *over == "speed";
        ld.kind = speed ? LoadKind::speed_table : LoadKind::position_table;
        // Over the state a jump would need an event of its own: the table must be continuous.
        auto tab = detail::read_table(f, speed ? wd : qd, vd, false, false);
        if (tab) ld.signal = *tab;
        compile_scale(f, ld);
      }
    } else if (detail::is_signal_type(t)) {
      if (t == "table") f.word("over", {"time", "speed", "position"}, "time");
      auto s = detail::read_signal_fields(f, t, vd);
      if (s && s->kind() == Signal::Kind::constant) {
        ld.kind = LoadKind::constant;
        ld.value = s->value(0.0);
      } else if (s) {
        ld.kind = LoadKind::signal;
      }
      if (s) ld.signal = *s;
    } else if (t == "drag") {
      ld.kind = LoadKind::drag;
      // k directly, or from one point of the curve: the load M_n at the speed ω_n, k = M_n/ω_n².
      if (f.map().find("coefficient")) {
        ld.value = f.positive("coefficient", vd / (wd * wd)).value_or(0.0);
      } else {
        auto Mn = f.positive("load", vd);
        auto wn = f.positive("speed", wd);
        if (Mn && wn) ld.value = *Mn / (*wn * *wn);
      }
      compile_scale(f, ld);
    } else if (t == "eddy-current-brake") {
      ld.kind = LoadKind::eddy_current;
      ld.value = f.positive("breakdown_torque", vd).value_or(0.0);
      ld.omega0 = f.positive("breakdown_speed", wd).value_or(1.0);
      compile_scale(f, ld);
    } else if (t == "motor-linear") {
      ld.kind = LoadKind::motor_linear;
      ld.value = f.quantity("stall_torque", vd).value_or(0.0);
      ld.omega0 = f.positive("no_load_speed", wd).value_or(1.0);
      compile_motor_switching(f, ld);
    } else if (t == "motor-kloss") {
      ld.kind = LoadKind::motor_kloss;
      ld.value = f.positive("breakdown_torque", vd).value_or(0.0);
      auto sk = f.positive("breakdown_slip", dim::none);
      if (sk && *sk >= 1.0) f.error_at("breakdown_slip", "field 'breakdown_slip' must be below 1");
      ld.s_k = sk.value_or(0.2);
      ld.omega0 = f.positive("synchronous_speed", wd).value_or(1.0);
      compile_motor_switching(f, ld);
    } else if (t == "motor-table") {
      ld.kind = LoadKind::motor_table;
      auto tab = detail::read_table(f, wd, vd, false, false);
      if (tab) ld.signal = *tab;
      compile_motor_switching(f, ld);
    }
    f.finish();
    m.loads.push_back(ld);
  }
}

/// Gravity: `gravity: g` (m/s², default standard gravity 9.80665 m/s² when a body is vertical) gives
/// each body with `vertical: up|down` the constant load "NAME.weight" = −vertical · m g (N).
void compile_gravity(FieldReader& top, Model& m, Diagnostics& diag) {
  bool any = false;
  for (const auto& b : m.bodies) any = any || b.vertical != 0;
  const std::optional<double> g = top.positive("gravity", dim::acceleration, kStandardGravity);
  if (top.map().find("gravity") && !any)
    diag.error(top.map().find("gravity")->loc, "'gravity' is given but no body is 'vertical: up|down', so no weight "
                                               "would act; give the bodies that hang or rise 'vertical: up' or 'down'");
  if (!any || !g) return;
  m.gravity = *g;
  for (size_t i = 0; i < m.bodies.size(); ++i) {
    const Body& b = m.bodies[i];
    if (b.vertical == 0) continue;
    Load w;
    w.name = b.name + ".weight";
    w.kind = LoadKind::constant;
    w.body = static_cast<int>(i);
    w.value = -b.vertical * b.inertia * m.gravity;
    w.signal = Signal::constant(w.value);
    m.loads.push_back(w);
  }
}

/// The breakpoints of every load within t_end are listed before the run: bound them (a pulse of
/// 1 µs period over an hour would be 7·10^9 stops).
void check_breakpoints(const Model& m, Diagnostics& diag) {
  constexpr double kMaxBreakpoints = 1e7;
  for (const auto& ld : m.loads) {
    double n = ld.kind == LoadKind::signal ? ld.signal.breakpoint_count(0.0, m.simulation.t_end) : 0.0;
    if (ld.switched)
      n += ld.on.breakpoint_count(0.0, m.simulation.t_end) + ld.direction.breakpoint_count(0.0, m.simulation.t_end);
    if (n > kMaxBreakpoints)
      diag.error(m.where(ld.name), fmt::format("load '{}': {:.3g} jumps and kinks before t_end, more than {:.0e}; "
                                               "lengthen the period or give a count", ld.name, n, kMaxBreakpoints));
  }
  for (const auto& c : m.contacts) {
    const double n = c.applied ? c.application.breakpoint_count(0.0, m.simulation.t_end) : 0.0;
    if (n > kMaxBreakpoints)
      diag.error(m.where(c.name), fmt::format("'{}': its application has {:.3g} jumps and kinks before t_end, more "
                                              "than {:.0e}; lengthen the period or give a count", c.name, n,
                                              kMaxBreakpoints));
  }
  for (const auto& d : m.drives) {
    const double n = d.law->breakpoint_count(0.0, m.simulation.t_end);
    if (n > kMaxBreakpoints)
      diag.error(m.where(d.name), fmt::format("drive '{}': {:.3g} jumps and kinks before t_end, more than {:.0e}; "
                                              "lengthen the period or give a count", d.name, n, kMaxBreakpoints));
  }
  for (const auto& b : m.bodies) {
    const double n = b.motion != MotionKind::free ? b.motion_signal.breakpoint_count(0.0, m.simulation.t_end) : 0.0;
    // q'' = d²s/dt² needs s without jumps or kinks (a kink would be a velocity jump, an impulse).
    const double kinks = b.motion != MotionKind::position || n == 0.0 ? 0.0
                         : n > kMaxBreakpoints ? n
                                               : static_cast<double>(b.motion_signal.breakpoints(0.0, m.simulation.t_end).size());
    if (kinks > 0.0)
      diag.error(m.where(b.name), fmt::format("body '{}': its prescribed position has {:.3g} jumps or kinks before t_end; "
                                              "a position must be smooth (a sine, an expression, a constant speed): "
                                              "give 'speed' or 'acceleration' for a motion with kinks", b.name, kinks));
    else if (n > kMaxBreakpoints)
      diag.error(m.where(b.name), fmt::format("body '{}': its motion has {:.3g} jumps and kinks before t_end, more "
                                              "than {:.0e}; lengthen the period or give a count", b.name, n,
                                              kMaxBreakpoints));
  }
}

/// The `simulation:` section; without one, every field has its default (the output grid too).
void compile_simulation(const SpecNode* section, Model& m, Diagnostics& diag) {
  SimulationSettings& s = m.simulation;
  if (!section) {
    s.dt_out = s.t_end / 1000.0;
    return;
  }
  FieldReader f(*section, "simulation", diag);
  s.t_end = f.positive("t_end", dim::time, s.t_end).value_or(s.t_end);
  s.dt_out = f.positive("dt_out", dim::time, 0.0, true).value_or(0.0);
  s.rtol = f.positive("rtol", dim::none, s.rtol).value_or(s.rtol);
  s.atol = f.positive("atol", dim::none, s.atol).value_or(s.atol);
  auto integ = f.word("integrator", {"auto", "dopri5", "bdf"}, "auto");
  if (integ) s.integrator = *integ == "dopri5" ? IntegratorChoice::dopri5
                           : *integ == "bdf"   ? IntegratorChoice::bdf
                                               : IntegratorChoice::automatic;
  s.max_steps = f.integer("max_steps", 1, 2'000'000'000L, s.max_steps).value_or(s.max_steps);
  auto init = f.word("initial", {"given", "equilibrium"}, "given");
  if (init) s.initial = *init == "equilibrium" ? InitialState::equilibrium : InitialState::given;
  if (s.rtol < 1e-14 || s.rtol > 0.1) f.error_at("rtol", "field 'rtol' must lie in [1e-14, 0.1]");
  if (s.dt_out > s.t_end) f.error_at("dt_out", "field 'dt_out' is longer than t_end");
  if (s.dt_out > 0.0 && s.t_end / s.dt_out > 1e8) f.error_at("dt_out", "more than 1e8 output rows; raise 'dt_out'");
  f.finish();
  if (s.dt_out == 0.0) s.dt_out = s.t_end / 1000.0;
}

/// Every load case compiles, whichever case a command runs: a case that overrides a field no element
/// has, or names an element that does not exist, is an error in `simulate` of the base model too.
void check_cases(const SpecNode& root, const std::string& source, Diagnostics& diag) {
  for (const std::string& name : case_names(root)) {
    SpecNode copy = root;
    try {
      apply_case(copy, name);
      (void)compile_model(copy, source);
    } catch (const InputError& e) {
      for (const Diagnostic& d : e.diagnostics())
        diag.error(d.where, d.message.rfind("case '", 0) == 0 ? d.message
                                                               : fmt::format("case '{}': {}", name, d.message));
    }
  }
}

}  // namespace

const std::vector<std::string>& element_sections() {
  static const std::vector<std::string> kSections = {"bodies", "links", "loads", "contacts", "brakes", "clutches", "freewheels", "stops",
                                                     "buffers", "drives", "releases"};
  return kSections;
}

Model compile_model(const SpecNode& root, const std::string& source) {
  Diagnostics diag;
  Model m;
  m.source = source;
  if (!root.is_map()) {
    diag.error(root.loc.line > 0 ? root.loc : Location{source, 1, 1},
               "expected a model: a map with 'bodies', 'links', 'loads', 'simulation'");
    diag.throw_if_any();
  }
  // A gear-synthesis spec (its `law`, no bodies) given where a model is expected: say what it is,
  // not a dozen unknown fields.
  if (const SpecNode* law = root.find("law"); law && !root.find("bodies")) {
    diag.error(law->key_loc, "this is a gear-synthesis spec ('law', no 'bodies'), not a model: run "
                             "`machdyn gears` on it, or name it as a gear-drive's 'gears: FILE' in a model");
    diag.throw_if_any();
  }
  FieldReader top(root, "model", diag);
  m.name = top.text("name", std::filesystem::path(source).stem().string()).value_or("");
  m.description = top.text("description", "").value_or("");
  check_names(root, m, diag);
  const SpecNode* bodies = top.node("bodies");
  compile_bodies(bodies, m, diag);
  m.index_bodies();
  if (m.bodies.empty())
    diag.error(bodies ? bodies->loc : Location{source, 1, 1},
               "the model has no body with mass or inertia: add at least one under 'bodies'");
  std::vector<detail::IdealGear> gears;
  std::vector<detail::LossyGearSpec> lossy;
  std::vector<detail::JointSpec> joints;
  std::vector<std::pair<std::string, const SpecNode*>> placed;
  compile_links(top.node("links"), m, gears, lossy, joints, placed, diag);
  // A rope's sheave losses: a lossy gear at its drum (model/sheaves.hpp), resolved with the others.
  if (diag.empty()) detail::add_sheave_losses(m, lossy, diag);
  compile_loads(top.node("loads"), m, diag);
  compile_gravity(top, m, diag);
  detail::compile_contacts(top.node("contacts"), top.node("brakes"), m, diag);
  detail::compile_clutches(top.node("clutches"), m, diag);
  detail::compile_freewheels(top.node("freewheels"), m, diag);
  detail::compile_stops(top.node("stops"), m, diag);
  detail::compile_buffers(top.node("buffers"), m, diag);
  detail::compile_crane(top.node("crane"), m, diag);
  detail::compile_drives(top.node("drives"), m, diag);
  for (const auto& [name, spec] : placed) detail::read_placed_element(name, *spec, m, diag);  // model/compile_drive.cpp
  detail::check_motion_elements(m, diag);
  // The bodies as the file names them, for display, before the merges below may move an element.
  if (diag.empty()) remember_given_bodies(m);
  // Ideal gears merge their bodies into one degree of freedom: every element is attached by now.
  if (diag.empty()) {
    // Massless bodies a joint eliminates, or one side of a lossy gear (its law needs no 1/I of that
    // side: analysis/gear_clutch.hpp; resolve_lossy checks the other side).
    std::unordered_set<std::string> massless_ok = detail::massless_members(m, joints);
    for (const auto& g : lossy) massless_ok.insert(g.body_a), massless_ok.insert(g.body_b);
    detail::resolve_rigid(m, gears, bodies, massless_ok, diag);
  }
  if (diag.empty()) detail::resolve_lossy(m, lossy, diag);  // on the bodies the merge left
  if (diag.empty()) detail::check_motion_lossy(m, diag);
  if (diag.empty()) detail::resolve_joints(m, joints, bodies, diag);  // after both: contacts rewritten last
  // Releases refer to the bodies as merged (a slaved body's release acts on its master).
  detail::compile_releases(top.node("releases"), m, diag);
  top.node("cases");  // load cases: model/cases.hpp
  compile_simulation(top.node("simulation"), m, diag);
  check_breakpoints(m, diag);
  detail::check_sine_periods(root, m.simulation.t_end, m.simulation.max_steps, diag);
  if (diag.empty()) detail::finish_applications(m);
  top.finish();
  // A velocity jump of a stepwise gear drive does not re-decide stuck contacts or re-check gaps yet
  // (the jump maps one body's speed only), and the energy books do not count its loss: say so
  // instead of simulating such a model wrongly.
  if (diag.empty() && m.is_hybrid() && has_velocity_jumps(m))
    diag.error(bodies ? bodies->loc : Location{source, 1, 1},
               "a body has velocity jumps (stepwise gear ratio), which cannot be combined with gaps, contacts or "
               "brakes yet");
  if (diag.empty() && output_bytes_bound(m) > kMaxOutputBytes) {
    const SpecNode* sim = root.find("simulation");
    const SpecNode* at = sim && sim->is_map() ? (sim->find("dt_out") ? sim->find("dt_out") : sim) : nullptr;
    const double rows = output_bytes_bound(m) / static_cast<double>(output_columns_bound(m) * sizeof(double));
    diag.error(at ? Location(at->loc) : Location{source, 1, 1},
               fmt::format("simulation: the output needs {:.3g} rows x {} columns = {:.3g} GB in memory, more than the "
                           "limit of {:.3g} GB; raise 'dt_out' or shorten 't_end'", rows, output_columns_bound(m),
                           output_bytes_bound(m) / 1e9, kMaxOutputBytes / 1e9));
  }
  if (diag.empty()) check_cases(root, source, diag);
  diag.throw_if_any();
  return m;
}


}  // namespace machdyn
