#include "compile_hybrid.hpp"
#include "machdyn/model/describe.hpp"

#include <cmath>
#include <fmt/format.h>

#include "model/body_dims.hpp"
#include "model/compile_signal.hpp"

namespace machdyn::detail {
namespace {

/// A list of [x, y] pairs with x strictly increasing (and >= x_min). False if reported bad.
bool read_pairs(const SpecNode& n, const std::string& what, const std::string& key, const Dim& dx, const Dim& dy,
                double x_min, std::vector<double>& xs, std::vector<double>& ys, Diagnostics& diag) {
  if (!n.is_seq() || n.items.empty()) {
    diag.error(n.loc, fmt::format("{}: '{}' expected a number or a list of [x, y] pairs", what, key));
    return false;
  }
  bool ok = true;
  for (const auto& p : n.items) {
    if (!p.is_seq() || p.items.size() != 2 || !p.items[0].is_scalar() || !p.items[1].is_scalar()) {
      diag.error(p.loc, fmt::format("{}: '{}' expected a pair [x, y]", what, key));
      ok = false;
      continue;
    }
    std::string e1, e2;
    auto x = parse_as(p.items[0].scalar, dx, &e1);
    auto y = parse_as(p.items[1].scalar, dy, &e2);
    if (!x) diag.error(p.items[0].loc, fmt::format("{}: '{}': {}", what, key, e1));
    if (!y) diag.error(p.items[1].loc, fmt::format("{}: '{}': {}", what, key, e2));
    if (!x || !y) {
      ok = false;
      continue;
    }
    if ((!xs.empty() && *x <= xs.back()) || *x < x_min) {
      diag.error(p.items[0].loc, fmt::format("{}: '{}': the first entries must increase{}", what, key,
                                             x_min == 0.0 ? " from 0" : ""));
      ok = false;
    }
    xs.push_back(*x);
    ys.push_back(*y);
  }
  return ok;
}

/// A scalar quantity or a table against sliding speed.
void read_level(FieldReader& f, const std::string& key, const Dim& dy, const Dim& dspeed, FrictionContact& c,
                double factor) {
  const SpecNode* n = f.node(key);
  if (!n) return;
  if (n->is_scalar()) {
    auto v = f.positive(key, dy, std::nullopt, true);
    c.kinetic = {v.value_or(0.0) * factor};
    c.speeds.clear();
    return;
  }
  std::vector<double> xs, ys;
  if (read_pairs(*n, f.what(), key, dspeed, dy, 0.0, xs, ys, f.diagnostics())) {
    for (size_t i = 0; i < ys.size(); ++i)
      if (ys[i] < 0) f.error_at(key, fmt::format("field '{}': levels must not be negative", key));
    for (auto& y : ys) y *= factor;
    c.speeds = xs;
    c.kinetic = ys;
  }
}

int resolve_body(FieldReader& f, const SpecNode& item, const Model& m, bool allow_ground) {
  int i = m.body_index(item.scalar);
  if (i == -2 || (i == kGround && !allow_ground)) {
    f.diagnostics().error(item.loc, fmt::format("{}: unknown body '{}'", f.what(), item.scalar));
    return -2;
  }
  return i;
}

/// The body named by field `body` of an element acting on one body, or −2 (reported; the other
/// fields are then marked as seen, so they draw no "unknown field" errors).
int field_body(FieldReader& f, const SpecNode& spec, const Model& m) {
  auto body = f.text("body");
  int i = -2;
  if (body) {
    i = m.body_index(*body);
    if (i < 0) f.error_at("body", fmt::format("unknown body '{}'", *body));
  }
  if (i < 0) {
    for (const auto& [k, v] : spec.fields) f.node(k);
    return -2;
  }
  return i;
}

/// The two ends of `between` of element `name` (a `what`: contact, freewheel): c.a is a body, c.b a
/// body or the ground (the ground given first is moved to b: *swapped). False if reported bad.
bool resolve_between(FieldReader& f, const SpecNode& spec, const std::string& name, const char* what, const Model& m,
                     FrictionContact& c, bool& swapped) {
  Diagnostics& diag = f.diagnostics();
  const SpecNode* between = f.node("between");
  if (!between) {
    diag.error(spec.loc, fmt::format("{} '{}': missing field 'between' (a body and a body or 'ground')", what, name));
    return false;
  }
  if (!between->is_seq() || between->items.size() != 2 || !between->items[0].is_scalar() ||
      !between->items[1].is_scalar()) {
    diag.error(between->loc, fmt::format("{} '{}': 'between' expected two names, e.g. [mk, m2]", what, name));
    return false;
  }
  const int a = resolve_body(f, between->items[0], m, true), b = resolve_body(f, between->items[1], m, true);
  if (a == -2 || b == -2) return false;
  if (a == kGround && b == kGround) {
    diag.error(between->loc, fmt::format("{} '{}': needs at least one body", what, name));
    return false;
  }
  if (a == b) {
    diag.error(between->loc, fmt::format("{} '{}': joins '{}' to itself", what, name, between->items[0].scalar));
    return false;
  }
  if (a != kGround && b != kGround && m.bodies[static_cast<size_t>(a)].kind != m.bodies[static_cast<size_t>(b)].kind) {
    diag.error(between->loc, fmt::format("{} '{}': joins a rotational and a translational body", what, name));
    return false;
  }
  // Keep the ground on side b: u = v_a − w.
  swapped = a == kGround;
  c.a = swapped ? b : a;
  c.b = swapped ? kGround : b;
  return true;
}


/// `stribeck_speed` w_s and `stribeck_exponent` δ (model/model.hpp): the kinetic level falls from
/// the static limit at rest to the constant level F_c. Needs a constant kinetic level.
/// `peak` (MSL's peak, ≥ 1) with a Stribeck law: the static limit is peak times the law's level at
/// rest (the given static level or N μ_s), F_s0 = peak · F_k0(0) (model/model.hpp FrictionContact::peak).
void read_stribeck(FieldReader& f, const SpecNode& spec, const Dim& vd, const char* level_key, FrictionContact& c) {
  if (!spec.find("stribeck_speed")) {
    if (spec.find("stribeck_exponent")) f.error_at("stribeck_exponent", "field 'stribeck_exponent' needs 'stribeck_speed'");
    if (spec.find("peak"))
      f.error_at("peak", "field 'peak' needs 'stribeck_speed': without a Stribeck law the static level is given "
                         "apart from the kinetic one (static = peak · kinetic at rest)");
    f.node("stribeck_exponent"), f.node("peak");
    return;
  }
  if (spec.find("peak")) {
    auto p = f.quantity("peak", dim::none);
    if (p && !(*p >= 1.0 && *p <= 1e3))
      f.error_at("peak", fmt::format("field 'peak' must lie in [1, 1000] (the static limit over the kinetic level at "
                                     "rest), got {}", *p));
    else if (p)
      c.peak = *p, c.static_limit *= *p;
  }
  auto ws = f.positive("stribeck_speed", vd);
  auto d = f.quantity("stribeck_exponent", dim::none, 1.0);
  if (d && !(*d >= 1.0))
    f.error_at("stribeck_exponent", fmt::format("field 'stribeck_exponent' must be at least 1, got {}", *d));
  if (c.speeds.size() > 1)
    f.error_at(level_key, fmt::format("field '{}': a table and 'stribeck_speed' exclude each other; give the "
                                      "Coulomb level as one number", level_key));
  if (ws && d && *d >= 1.0) c.stribeck_speed = *ws, c.stribeck_exponent = *d;
}

/// The levels from coefficients, per newton of normal force: F_s0 = z r μ_s, F_k0 = z r μ_k(s)
/// (`radius` r on a rotational body only, `surfaces` z ≥ 1).
void read_coefficients(FieldReader& f, const SpecNode& spec, const std::string& name, BodyKind kind, FrictionContact& c) {
  double radius = 1.0;
  if (kind == BodyKind::rotational) radius = f.positive("radius", dim::length).value_or(1.0);
  else if (spec.find("radius")) f.error_at("radius", "a translational element has no radius");
  const double z = static_cast<double>(f.integer("surfaces", 1, 1000, 1).value_or(1));
  const double scale = z * radius;
  c.static_limit = f.positive("mu_s", dim::none).value_or(1.0) * scale;
  if (!spec.find("mu_k")) f.diagnostics().error(spec.loc, fmt::format("{}: missing field 'mu_k'", f.what()));
  read_level(f, "mu_k", dim::none, velocity_dim(kind), c, scale);
  (void)name;
}

/// `normal_force`: a force f_N in N, or a signal of it (model/signal.hpp). A positive constant is
/// folded into the levels; a signal becomes the application r(t) = max(0, f_N(t)) / f_N,ref, scaled
/// once t_end is known (finish_applications).
void read_normal_force(FieldReader& f, const SpecNode& spec, FrictionContact& c) {
  const SpecNode* n = f.node("normal_force");
  if (!n) {
    f.diagnostics().error(spec.loc, fmt::format("{}: missing field 'normal_force' (a force in N or a signal of it)", f.what()));
    return;
  }
  auto sig = compile_signal(*n, dim::force, f.what() + ": field 'normal_force'", f.diagnostics());
  if (!sig) return;
  if (sig->kind() == Signal::Kind::constant) {
    const double N = sig->value(0.0);
    if (!(N > 0.0)) {
      f.error_at("normal_force", fmt::format("field 'normal_force' must be positive, got {}", N));
      return;
    }
    c.static_limit *= N;
    for (auto& y : c.kinetic) y *= N;
    return;
  }
  c.applied = true;
  c.by_normal_force = true;
  c.application = *sig;
}

/// F_k0(0) ≤ F_s0 (before a Stribeck law is set: its F_c), reported at `key`.
void check_levels(FieldReader& f, const char* key, FrictionContact& c) {
  if (!c.kinetic.empty() && c.kinetic_level(0.0) > c.static_limit)
    f.error_at(key, fmt::format("the kinetic level at zero sliding speed ({}) exceeds the static limit ({})",
                                c.kinetic_level(0.0), c.static_limit));
  if (c.kinetic.empty()) c.kinetic = {0.0};
}

/// A brake's or clutch's `housing` (brakes) or second body: the body named, or the ground.
int read_housing(FieldReader& f, const Model& m, int body) {
  auto h = f.text("housing", "ground");
  if (!h) return kGround;
  const int i = m.body_index(*h);
  if (i == -2) {
    f.error_at("housing", fmt::format("unknown body '{}' (a body or 'ground')", *h));
    return kGround;
  }
  if (i == body) {
    f.error_at("housing", fmt::format("the brake joins '{}' to itself", *h));
    return kGround;
  }
  if (i >= 0 && m.bodies[static_cast<size_t>(i)].kind != m.bodies[static_cast<size_t>(body)].kind) {
    f.error_at("housing", "joins a rotational and a translational body");
    return kGround;
  }
  return i;
}
}  // namespace

/// `thermal: {heat_capacity, conductance, ambient, initial}` of a friction element (elements/thermal.hpp).
void read_thermal(FieldReader& f, FrictionContact& c) {
  const SpecNode* node = f.node("thermal");
  if (!node) return;
  Diagnostics& diag = f.diagnostics();
  if (!node->is_map()) {
    diag.error(node->loc, fmt::format("{}: 'thermal' expected a map {{heat_capacity: 4 kJ/K, conductance: 10 W/K, "
                                      "ambient: 20 degC}}", f.what()));
    return;
  }
  FieldReader t(*node, f.what() + ": thermal", diag);
  ThermalMass th;
  auto temperature = [&](const char* key, double fallback) {
    const SpecNode* v = t.node(key);
    if (!v) return fallback;
    std::string err;
    std::optional<double> T = v->is_scalar() ? parse_temperature(v->scalar, &err) : std::nullopt;
    if (!T) {
      diag.error(v->loc, fmt::format("{}: thermal: '{}' {}", f.what(), key,
                                     err.empty() ? "expected a temperature, e.g. 20 degC" : err));
      return fallback;
    }
    return *T;
  };
  const auto C = t.positive("heat_capacity", dim::heat_capacity);
  const auto G = t.positive("conductance", dim::thermal_conductance, 0.0, true);
  th.ambient = temperature("ambient", th.ambient);
  th.initial = temperature("initial", th.ambient);
  t.finish();
  if (!C || !G) return;
  th.heat_capacity = *C;
  th.conductance = *G;
  c.thermal = th;
}

void compile_link_gap(FieldReader& f, Link& l, const Dim& qd) {
  // A one-sided link (MSL's ElastoGap): its only flank δ₊ = `flank`, on either side of δ = 0; the
  // same representation as a rope's slack, so the one law of elements/link.hpp serves it.
  if (f.map().is_map() && f.map().find("flank")) {
    auto flank = f.quantity("flank", qd);
    if (f.map().find("gap"))
      f.error_at("flank", "a link has either a 'gap' (two flanks) or a 'flank' (one), not both");
    if (l.kind == LinkKind::damper) f.error_at("flank", "a damper cannot have a flank; use type spring-damper");
    f.node("gap"), f.node("gap_start");
    if (!flank) return;
    l.has_gap = true;
    l.tension_only = true;
    l.gap = *flank;
    l.gap_start = 0.0;
    return;
  }
  f.node("flank");
  if (!f.map().is_map() || !f.map().find("gap")) {
    if (f.map().is_map() && f.map().find("gap_start")) f.error_at("gap_start", "field 'gap_start' needs a 'gap'");
    f.node("gap_start");
    f.node("gap");
    return;
  }
  auto gap = f.positive("gap", qd, std::nullopt, true);
  auto start = f.quantity("gap_start", qd, 0.0);
  if (l.kind == LinkKind::damper) f.error_at("gap", "a damper cannot have a gap; use type spring-damper");
  if (!gap) return;
  l.has_gap = true;
  l.gap = *gap;
  l.gap_start = start.value_or(0.0);
  if (start && (*start < 0.0 || *start > *gap))
    f.error_at("gap_start", fmt::format("field 'gap_start' must lie in [0, gap] = [0, {}], got {}", *gap, *start));
}

void compile_contacts(const SpecNode* contacts, const SpecNode* brakes, Model& m, Diagnostics& diag) {
  if (contacts && !contacts->is_map()) diag.error(contacts->loc, "'contacts' must be a map of NAME: {fields}");
  if (brakes && !brakes->is_map()) diag.error(brakes->loc, "'brakes' must be a map of NAME: {fields}");
  if (contacts && contacts->is_map()) {
    for (const auto& [name, spec] : contacts->fields) {
      FieldReader f(spec, fmt::format("contact '{}'", name), diag);
      FrictionContact c;
      c.name = name;
      bool swapped = false;
      if (!resolve_between(f, spec, name, "contact", m, c, swapped)) {
        for (const auto& [k, v] : spec.fields) f.node(k);
        continue;
      }
      if (swapped)
        diag.error(spec.find("between")->items[0].loc, fmt::format("contact '{}': write the body first: [{}, ground]",
                                                                  name, spec.find("between")->items[1].scalar));
      const BodyKind kind = m.bodies[static_cast<size_t>(c.a)].kind;
      const Dim ld = load_dim(kind), vd = velocity_dim(kind);
      const bool by_mu = spec.find("normal_force") != nullptr;
      if (by_mu) {
        read_coefficients(f, spec, name, kind, c);
        read_normal_force(f, spec, c);
        for (const char* k : {"static", "kinetic"})
          if (spec.find(k)) f.error_at(k, fmt::format("give either 'normal_force' with mu_s, mu_k or '{}', not both", k));
      } else {
        c.static_limit = f.positive("static", ld).value_or(1.0);
        if (!spec.find("kinetic")) diag.error(spec.loc, fmt::format("contact '{}': missing field 'kinetic'", name));
        read_level(f, "kinetic", ld, vd, c, 1.0);
        for (const char* k : {"mu_s", "mu_k", "radius", "surfaces"}) {
          if (spec.find(k)) f.error_at(k, fmt::format("field '{}' needs 'normal_force'", k));
          f.node(k);
        }
      }
      if (const SpecNode* w = f.node("surface_velocity")) {
        if (c.b != kGround) {
          f.error_at("surface_velocity", "only a contact with the ground has a surface velocity");
        } else if (w->is_scalar()) {
          c.surface_velocities = {f.quantity("surface_velocity", vd).value_or(0.0)};
        } else {
          read_pairs(*w, f.what(), "surface_velocity", dim::time, vd, -1e300, c.surface_times, c.surface_velocities, diag);
        }
      }
      check_levels(f, by_mu ? "mu_k" : "kinetic", c);
      read_stribeck(f, spec, vd, by_mu ? "mu_k" : "kinetic", c);
      read_thermal(f, c);
      f.finish();
      m.contacts.push_back(c);
    }
  }
  if (brakes && brakes->is_map()) {
    for (const auto& [name, spec] : brakes->fields) {
      FieldReader f(spec, fmt::format("brake '{}'", name), diag);
      FrictionContact c;
      c.name = name;
      c.brake = true;
      const int i = field_body(f, spec, m);
      if (i < 0) continue;
      c.a = i;
      c.b = read_housing(f, m, i);
      const BodyKind kind = m.bodies[static_cast<size_t>(i)].kind;
      const Dim ld = load_dim(kind), vd = velocity_dim(kind);
      const bool by_mu = spec.find("normal_force") != nullptr;
      if (by_mu) {
        read_coefficients(f, spec, name, kind, c);
        read_normal_force(f, spec, c);
        for (const char* k : {"holding", "braking", "time", "ramp", "application"})
          if (spec.find(k))
            f.error_at(k, fmt::format("field '{}' and 'normal_force' exclude each other (the normal force is the "
                                      "application)", k));
        check_levels(f, "mu_k", c);
      } else {
        c.static_limit = f.positive("holding", ld).value_or(1.0);
        c.kinetic = {f.positive("braking", ld, c.static_limit).value_or(c.static_limit)};
        if (c.kinetic[0] > c.static_limit)
          f.error_at("braking", fmt::format("the braking level ({}) exceeds the holding level ({})", c.kinetic[0],
                                            c.static_limit));
        for (const char* k : {"mu_s", "mu_k", "radius", "surfaces"}) {
          if (spec.find(k)) f.error_at(k, fmt::format("field '{}' needs 'normal_force'", k));
          f.node(k);
        }
        if (const SpecNode* app = f.node("application")) {
          // r(t) directly: 0 released, 1 the full holding level.
          for (const char* k : {"time", "ramp"})
            if (spec.find(k)) f.error_at(k, fmt::format("give either 'application' or '{}', not both", k));
          if (auto sig = compile_signal(*app, dim::none, f.what() + ": field 'application'", diag)) {
            c.applied = true;
            c.application = *sig;
          }
        } else {
          // The application time and ramp of old files: r(t) = 0 before t_a, linear to 1 over t_r.
          const double ta = f.positive("time", dim::time, 0.0, true).value_or(0.0);
          const double tr = f.positive("ramp", dim::time, 0.0, true).value_or(0.0);
          if (tr > 0.0) c.application = Signal::ramp(0.0, 1.0, ta, ta + tr), c.applied = true;
          else if (ta > 0.0) c.application = Signal::step(0.0, 1.0, ta), c.applied = true;
        }
      }
      read_stribeck(f, spec, vd, by_mu ? "mu_k" : "braking", c);
      read_thermal(f, c);
      f.finish();
      m.contacts.push_back(c);
    }
  }
}

void compile_clutches(const SpecNode* clutches, Model& m, Diagnostics& diag) {
  if (!clutches) return;
  if (!clutches->is_map()) {
    diag.error(clutches->loc, "'clutches' must be a map of NAME: {fields}");
    return;
  }
  for (const auto& [name, spec] : clutches->fields) {
    FieldReader f(spec, fmt::format("clutch '{}'", name), diag);
    FrictionContact c;
    c.name = name;
    c.clutch = true;
    bool swapped = false;
    if (!resolve_between(f, spec, name, "clutch", m, c, swapped)) {
      for (const auto& [k, v] : spec.fields) f.node(k);
      continue;
    }
    if (c.b == kGround) {
      diag.error(spec.find("between")->loc, fmt::format("clutch '{}': a clutch joins two bodies; friction against "
                                                        "the ground is a brake (section 'brakes', 'housing')", name));
      for (const auto& [k, v] : spec.fields) f.node(k);
      continue;
    }
    const BodyKind kind = m.bodies[static_cast<size_t>(c.a)].kind;
    read_coefficients(f, spec, name, kind, c);
    read_normal_force(f, spec, c);
    check_levels(f, "mu_k", c);
    read_stribeck(f, spec, velocity_dim(kind), "mu_k", c);
    read_thermal(f, c);
    f.finish();
    m.contacts.push_back(c);
  }
}

void finish_applications(Model& m) {
  const double t_end = m.simulation.t_end;
  for (FrictionContact& c : m.contacts) {
    if (!c.applied) continue;
    if (c.by_normal_force) {
      // f_N,ref = the largest |f_N|: F_s0 and F_k0 become the levels at that force, r ≤ 1.
      const double ref = c.application.magnitude_bound(0.0, t_end);
      if (ref > 0.0 && std::isfinite(ref)) {
        c.static_limit *= ref;
        for (auto& y : c.kinetic) y *= ref;
        c.application_gain = 1.0 / ref;
      }
    }
    c.t_apply = t_end;
    if (!c.released(0.0)) {
      c.t_apply = 0.0;
      continue;
    }
    for (double t : c.application_times(t_end))
      if (!c.released(t)) {
        c.t_apply = t;
        break;
      }
  }
}

void compile_freewheels(const SpecNode* freewheels, Model& m, Diagnostics& diag) {
  if (!freewheels) return;
  if (!freewheels->is_map()) {
    diag.error(freewheels->loc, "'freewheels' must be a map of NAME: {fields}");
    return;
  }
  for (const auto& [name, spec] : freewheels->fields) {
    FieldReader f(spec, fmt::format("freewheel '{}'", name), diag);
    FrictionContact c;
    c.name = name;
    bool swapped = false;
    if (!resolve_between(f, spec, name, "freewheel", m, c, swapped)) {
      for (const auto& [k, v] : spec.fields) f.node(k);
      continue;
    }
    // [A, B]: A drives B forward (locked while λ ≥ 0), B may overrun. [ground, A]: a backstop, A
    // moves forward only; kept as (A, ground) with the lock reversed.
    c.lock = swapped ? -1 : +1;
    const BodyKind kind = m.bodies[static_cast<size_t>(c.a)].kind;
    c.static_limit = 1.0;  // unused by a freewheel's law (no upper limit)
    if (spec.find("drag")) read_level(f, "drag", load_dim(kind), velocity_dim(kind), c, 1.0);
    if (c.kinetic.empty()) c.kinetic = {0.0};
    read_thermal(f, c);
    f.finish();
    // The initial relative speed must not turn the freewheel in its locked direction (that would be
    // an impact the model does not describe).
    const double va = m.bodies[static_cast<size_t>(c.a)].v0, vb = c.b >= 0 ? m.bodies[static_cast<size_t>(c.b)].v0 : 0.0;
    if (c.lock * (va - vb) > 0.0) {
      const SpecNode& ends = *spec.find("between");  // as written: the driving side first
      diag.error(ends.loc, fmt::format("freewheel '{}': the initial speeds turn it in its locked direction ('{}' "
                                       "faster than '{}'); give equal speeds or let the driven side run ahead",
                                       name, ends.items[0].scalar, ends.items[1].scalar));
    }
    m.contacts.push_back(c);
  }
}

void compile_stops(const SpecNode* stops, Model& m, Diagnostics& diag) {
  if (!stops) return;
  if (!stops->is_map()) {
    diag.error(stops->loc, "'stops' must be a map of NAME: {fields}");
    return;
  }
  for (const auto& [name, spec] : stops->fields) {
    FieldReader f(spec, fmt::format("stop '{}'", name), diag);
    FrictionContact c;
    c.name = name;
    c.stop = true;
    c.b = kGround;
    const int i = field_body(f, spec, m);
    if (i < 0) continue;
    c.a = i;
    const Body& b = m.bodies[static_cast<size_t>(i)];
    const Dim qd = b.kind == BodyKind::rotational ? dim::none : dim::length;  // rad or m
    const bool has_min = spec.find("min") != nullptr, has_max = spec.find("max") != nullptr;
    if (has_min == has_max) {
      diag.error(spec.loc, fmt::format("stop '{}': give one of 'min' (a lower stop) or 'max' (an upper stop)", name));
      for (const auto& [k, v] : spec.fields) f.node(k);
      continue;
    }
    const char* key = has_min ? "min" : "max";
    c.lock = has_min ? -1 : +1;  // a lower stop pushes up: holds while λ ≤ 0 (model/model.hpp)
    c.stop_position = f.quantity(key, qd).value_or(0.0);
    c.restitution = f.quantity("restitution", dim::none, 0.0).value_or(0.0);
    if (c.restitution < 0.0 || c.restitution > 1.0)
      f.error_at("restitution", fmt::format("field 'restitution' must lie in [0, 1], got {}", c.restitution));
    c.static_limit = 1.0;  // unused (a stop has no upper limit)
    c.kinetic = {0.0};
    f.finish();
    const double gap = -c.lock * (b.q0 - c.stop_position);
    if (gap < 0.0)
      f.error_at(key, fmt::format("the initial position of '{}' ({}) lies beyond the stop", b.name, b.q0));
    else if (gap == 0.0 && c.lock * b.v0 > 0.0)
      f.error_at(key, fmt::format("'{}' starts on the stop moving into it (velocity {})", b.name, b.v0));
    m.contacts.push_back(c);
  }
}


// A gap as the file wrote it (compile_link_gap): backlash with its start, or a single flank.
std::string describe_gap(const Model& m, const Link& l) {
  const int body = l.b != kGround ? l.b : l.a;
  const std::string qu = position_unit(body == kGround ? BodyKind::rotational : m.bodies[static_cast<size_t>(body)].kind);
  if (l.tension_only) return fmt::format("one flank at δ = {} {} (no load below it)", describe_number(l.gap), qu);
  return fmt::format("backlash Δ = {} {}, starting {} {} from the negative flank", describe_number(l.gap), qu,
                     describe_number(l.gap_start), qu);
}

namespace {
// The thermal model of a friction element (`thermal:`), temperatures in °C as most files give them.
std::string thermal_text(const ThermalMass& th) {
  constexpr double kKelvin = 273.15;
  return fmt::format("thermal: C = {} J/K, G = {} W/K{}, ambient {} °C, T(0) = {} °C", describe_number(th.heat_capacity),
                     describe_number(th.conductance), th.conductance == 0.0 ? " (adiabatic)" : "",
                     describe_number(th.ambient - kKelvin), describe_number(th.initial - kKelvin));
}
}  // namespace

// A friction element as the file wrote it: an end stop, a freewheel, a brake, a clutch or a contact.
ElementText describe_friction_element(const Model& m, const FrictionContact& c) {
  const BodyKind k = m.bodies[static_cast<size_t>(c.a)].kind;
  const std::string lu = load_unit(k), qu = position_unit(k), vu = velocity_unit(k);
  const std::string a = shown_body(m, c.a, c.given_a), b = shown_body(m, c.b, c.given_b);
  ElementText e{c.name, "", ""};
  auto levels = [&] {
    std::string kinetic = c.kinetic.size() == 1
                              ? describe_number(c.kinetic[0]) + " " + lu
                              : fmt::format("a table over {} sliding speeds, {} … {} {}", c.kinetic.size(),
                                            describe_number(c.kinetic.front()), describe_number(c.kinetic.back()), lu);
    std::string t = fmt::format("static limit F_s = {} {}, kinetic F_k = {}", describe_number(c.static_limit), lu, kinetic);
    if (c.stribeck_speed > 0.0)
      t += fmt::format(" (Stribeck: w_s = {} {}, δ = {}{})", describe_number(c.stribeck_speed), vu,
                       describe_number(c.stribeck_exponent),
                       c.peak != 1.0 ? fmt::format(", from {} {} at rest, peak {}", describe_number(c.static_limit / c.peak),
                                                   lu, describe_number(c.peak))
                                     : std::string());
    return t;
  };
  if (c.joint) {
    e.type = "gear joint";
    e.definition = "a rigid velocity constraint (always locked)";
  } else if (c.stop) {
    e.type = "end stop";
    e.definition = fmt::format("{} stop of '{}' at {} {}, restitution e = {}", c.lock < 0 ? "lower" : "upper", a,
                               describe_number(c.stop_position), qu, describe_number(c.restitution));
  } else if (c.lock != 0) {
    e.type = "freewheel";
    e.definition = c.b == kGround ? fmt::format("backstop: '{}' moves {} only", a, c.lock < 0 ? "forward" : "backward")
                                  : fmt::format("'{}' drives '{}' forward, '{}' may overrun", a, b, b);
    if (!c.kinetic.empty() && c.kinetic[0] > 0.0)
      e.definition += fmt::format("; drag {} {} while free", describe_number(c.kinetic[0]), lu);
  } else {
    e.type = c.brake ? "brake" : c.clutch ? "clutch" : "friction";
    e.definition = (c.brake ? fmt::format("holding F_s = {} {}, braking F_k = {}", describe_number(c.static_limit), lu,
                                          c.kinetic.size() == 1 ? describe_number(c.kinetic[0]) + " " + lu
                                                                : std::string("a table over the sliding speed"))
                            : levels());
    if (c.applied)
      e.definition += c.by_normal_force ? "; normal force f_N(t): " + c.application.describe("N") + " (levels at its largest)"
                                        : "; application (0 released … 1 full): " + c.application.describe("");
    if (!c.surface_velocities.empty() && c.b == kGround)
      e.definition += c.surface_times.empty()
                          ? fmt::format("; ground surface moves at {} {}", describe_number(c.surface_velocities[0]), vu)
                          : std::string("; ground surface velocity: a table in t");
  }
  if (c.thermal) e.definition += "; " + thermal_text(*c.thermal);
  return e;
}

}  // namespace machdyn::detail
