#include "model/compile_machine.hpp"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <fmt/format.h>
#include "common/constants.hpp"

#include "machdyn/gears/gear_model.hpp"
#include "machdyn/gears/synthesis.hpp"
#include "machdyn/model/gear_drive.hpp"
#include "machdyn/model/machine.hpp"

namespace machdyn {
namespace {


/// Reads `key: [[x, y], ...]` with dimensions dx, dy; x must increase. Empty on error (reported).
bool read_pairs(FieldReader& f, std::string_view key, const Dim& dx, const Dim& dy, std::vector<double>* xs,
                std::vector<double>* ys, size_t min_points) {
  Diagnostics& diag = f.diagnostics();
  const SpecNode* pts = f.node(key);
  if (!pts) {
    diag.error(f.map().loc, fmt::format("{}: missing field '{}' ([[{}, {}], ...])", f.what(), key,
                                        describe(dx), describe(dy)));
    return false;
  }
  if (!pts->is_seq() || pts->items.size() < min_points) {
    diag.error(pts->loc, fmt::format("{}: '{}' expected a list of at least {} pairs [x, y]", f.what(), key, min_points));
    return false;
  }
  bool ok = true;
  for (const auto& p : pts->items) {
    if (!p.is_seq() || p.items.size() != 2 || !p.items[0].is_scalar() || !p.items[1].is_scalar()) {
      diag.error(p.loc, fmt::format("{}: expected a pair [x, y] in '{}'", f.what(), key));
      ok = false;
      continue;
    }
    std::string e1, e2;
    auto xv = parse_as(p.items[0].scalar, dx, &e1);
    auto yv = parse_as(p.items[1].scalar, dy, &e2);
    if (!xv) diag.error(p.items[0].loc, fmt::format("{}: {}", f.what(), e1));
    if (!yv) diag.error(p.items[1].loc, fmt::format("{}: {}", f.what(), e2));
    if (!xv || !yv) {
      ok = false;
      continue;
    }
    if (!xs->empty() && *xv <= xs->back()) {
      diag.error(p.items[0].loc, fmt::format("{}: the first values in '{}' must increase", f.what(), key));
      ok = false;
    }
    xs->push_back(*xv);
    ys->push_back(*yv);
  }
  return ok;
}

/// Parses an expression field in q; reports a parse error at the value.
std::optional<Expression> read_expression(FieldReader& f, std::string_view key, bool required) {
  auto text = f.text(key, required ? std::nullopt : std::optional<std::string>(""));
  if (!text || text->empty()) return std::nullopt;
  try {
    Expression e(*text, "q");
    e.refuse_switches(0, true, "the law needs its derivatives everywhere (a smooth function of q)");
    return e;
  } catch (const std::invalid_argument& e) {
    const std::string shown = text->size() > 80 ? text->substr(0, 77) + "..." : *text;
    f.error_at(key, fmt::format("field '{}': expression '{}': {}", key, shown, e.what()));
    return std::nullopt;
  }
}

void check_positive_inertia(FieldReader& f, const Machine& mach, double q_lo, double q_hi, const std::string& key) {
  // I(q) must stay positive: sample densely over the range that matters.
  const int n = 2000;
  for (int j = 0; j <= n; ++j) {
    const double q = q_lo + (q_hi - q_lo) * j / n;
    double I, dI;
    mach.inertia(q, &I, &dI);
    if (!(I > 0.0) || !std::isfinite(dI)) {
      f.error_at(key, fmt::format("the reduced inertia must be positive and finite, but I({:.6g}) = {:.6g}", q, I));
      return;
    }
  }
}

std::shared_ptr<const Machine> crank_slider(FieldReader& f, Body& b) {
  CrankSlider::Params p;
  auto r = f.positive("crank_radius", dim::length);
  auto l = f.positive("rod_length", dim::length);
  p.r = r.value_or(0.05);
  p.l = l.value_or(std::max(0.2, 2 * p.r));
  if (r && l && *l <= *r) {
    f.error_at("rod_length", fmt::format("field 'rod_length' ({} m) must exceed 'crank_radius' ({} m)", *l, *r));
    p.l = 2 * p.r;
  }
  p.m_rod = f.positive("rod_mass", dim::mass, 0.0, true).value_or(0.0);
  // Default: the rod's centre of mass at l/3 from the crank pin, which lumps 2/3 of the rod at the
  // crank pin and 1/3 at the piston, as paper 004 does.
  auto a = f.positive("rod_com", dim::length, p.l / 3.0, true);
  p.a = a.value_or(p.l / 3.0);
  if (a && *a > p.l) f.error_at("rod_com", "field 'rod_com' (centre of mass from the crank pin) exceeds 'rod_length'");
  // Default: the two-point-mass equivalent rod, J = m a (l − a).
  p.J_rod = f.positive("rod_inertia", dim::inertia, p.m_rod * p.a * (p.l - p.a), true).value_or(0.0);
  p.m_p = f.positive("piston_mass", dim::mass, 0.0, true).value_or(0.0);
  p.J_c = f.positive("crank_inertia", dim::inertia).value_or(1.0);
  auto model = f.word("inertia_model", {"exact", "approximate"}, "exact");
  p.approximate = model && *model == "approximate";
  CrankSlider::ForceAgainst against = CrankSlider::ForceAgainst::none;
  LinearTable table;
  if (const SpecNode* pf = f.node("piston_force")) {
    FieldReader g(*pf, f.what() + " piston_force", f.diagnostics());
    auto w = g.word("against", {"angle", "position"});
    if (w) {
      against = *w == "angle" ? CrankSlider::ForceAgainst::angle : CrankSlider::ForceAgainst::position;
      read_pairs(g, "points", *w == "angle" ? dim::none : dim::length, dim::force, &table.x, &table.y, 1);
      if (*w == "angle") {
        table.period = g.positive("period", dim::none, 2 * kPi).value_or(2 * kPi);
        if (!table.x.empty() && table.x.back() - table.x.front() > table.period)
          g.error_at("points", fmt::format("the angles span more than one period ({:.6g} rad)", table.period));
      }
    } else {
      g.node("points");
      g.node("period");
    }
    g.finish();
    if (table.x.empty()) against = CrankSlider::ForceAgainst::none;
  }
  b.q0 = f.quantity("position", dim::none, 0.0).value_or(0.0);
  b.v0 = f.quantity("velocity", dim::angular_velocity, 0.0).value_or(0.0);
  auto mach = std::make_shared<CrankSlider>(p, against, std::move(table));
  check_positive_inertia(f, *mach, 0.0, 2 * kPi, "crank_inertia");
  return mach;
}

std::shared_ptr<const Machine> rolling_wheel(FieldReader& f, Body& b) {
  RollingWheel::Params p;
  p.scheme = static_cast<int>(f.integer("scheme", 1, 3).value_or(1));
  auto R1 = f.positive("R1", dim::length);
  p.R1 = R1.value_or(1.0);
  auto r1 = f.positive("r1", dim::length, p.scheme == 1 ? std::optional<double>(0.0) : std::nullopt, p.scheme == 1);
  p.r1 = r1.value_or(0.5 * p.R1);
  if (p.scheme != 1 && r1 && R1 && *r1 >= *R1)
    f.error_at("r1", fmt::format("field 'r1' (the small cylinder, {} m) must be smaller than 'R1' ({} m)", *r1, *R1));
  p.r2 = f.positive("r2", dim::length).value_or(0.1);
  p.H = f.positive("H", dim::length).value_or(10.0);
  p.m1 = f.positive("m1", dim::mass).value_or(1.0);
  p.m2 = f.positive("m2", dim::mass, 0.0, true).value_or(0.0);
  p.rho = f.positive("rho", dim::length, 0.0, true).value_or(0.0);
  p.F = f.quantity("F", dim::force).value_or(0.0);
  auto beta0 = f.quantity("beta0", dim::none);
  p.beta0 = beta0.value_or(kPi / 4);
  if (beta0 && !(*beta0 > 0.0 && *beta0 < kPi)) {
    f.error_at("beta0", fmt::format("field 'beta0' must lie strictly between 0 and pi rad, got {}", *beta0));
    p.beta0 = kPi / 4;
  }
  p.omega0 = f.quantity("omega0", dim::angular_velocity, 0.0).value_or(0.0);
  auto mach = std::make_shared<RollingWheel>(p);
  if (p.H <= std::abs(mach->Rt() - p.r2))
    f.error_at("H", fmt::format("field 'H' ({} m) must exceed |Rt − r2| = {} m, else the thread angle is not "
                                "a function of the wheel's position", p.H, std::abs(mach->Rt() - p.r2)));
  b.q0 = 0.0;  // φ is counted from the start, where β = β0
  b.v0 = p.omega0;
  return mach;
}

std::shared_ptr<const Machine> inertia_table(FieldReader& f, Body& b) {
  std::vector<double> q, I;
  const bool ok = read_pairs(f, "points", dim::none, dim::inertia, &q, &I, 2);
  auto periodic = f.word("periodic", {"true", "false"}, "false");
  const bool per = periodic && *periodic == "true";
  auto torque = read_expression(f, "torque", false);
  b.q0 = f.quantity("position", dim::none, 0.0).value_or(0.0);
  b.v0 = f.quantity("velocity", dim::angular_velocity, 0.0).value_or(0.0);
  if (!ok) return nullptr;
  for (size_t j = 0; j < I.size(); ++j)
    if (!(I[j] > 0.0)) {
      f.error_at("points", fmt::format("the inertia must be positive, got {} at q = {}", I[j], q[j]));
      return nullptr;
    }
  if (per && (q.size() < 3 || std::abs(I.front() - I.back()) > 1e-12 * std::abs(I.front()))) {
    f.error_at("points", "a periodic table needs at least 3 points and the same inertia at its first and last "
                         "angle (the last angle is the first plus the period)");
    return nullptr;
  }
  auto mach = std::make_shared<InertiaTable>(CubicSpline(q, I, per), std::move(torque));
  check_positive_inertia(f, *mach, q.front(), q.back(), "points");
  return mach;
}

std::shared_ptr<const Machine> inertia_expression(FieldReader& f, Body& b) {
  auto inertia = read_expression(f, "inertia", true);
  auto torque = read_expression(f, "torque", false);
  const double period = f.positive("period", dim::none, 0.0, true).value_or(0.0);
  b.q0 = f.quantity("position", dim::none, 0.0).value_or(0.0);
  b.v0 = f.quantity("velocity", dim::angular_velocity, 0.0).value_or(0.0);
  if (!inertia) return nullptr;
  auto mach = std::make_shared<InertiaExpression>(std::move(*inertia), std::move(torque), period);
  const double span = period > 0 ? period : 2 * kPi;
  check_positive_inertia(f, *mach, b.q0 - span, b.q0 + span, "inertia");
  return mach;
}

/// The gear pair of a gear-drive: `gears: FILE` (a `machdyn gears` spec, relative to the model
/// file) or the spec's fields inline as a map. Problems inside the spec keep their own place.
std::optional<gears::GearModel> read_gear_spec(FieldReader& f, gears::GearSynthesis* syn) {
  Diagnostics& diag = f.diagnostics();
  const SpecNode* g = f.node("gears");
  if (!g) {
    diag.error(f.map().loc, fmt::format("{}: missing field 'gears' (a gear spec file, as for `machdyn gears`, or "
                                        "its fields inline)", f.what()));
    return std::nullopt;
  }
  try {
    SpecNode spec;
    if (g->is_scalar()) {
      // The model layer reads no files: io (load_model, resolve_gear_includes) puts the included
      // spec in place of the file name before compile. A bare compile_model() of such a tree lands here.
      f.error_at("gears", fmt::format("field 'gears': the gear spec file '{}' was not read; load the model with "
                                      "load_model() or call resolve_gear_includes() before compile_model()",
                                      g->scalar));
      return std::nullopt;
    } else if (g->is_map()) {
      spec = *g;
    } else {
      f.error_at("gears", "field 'gears' expected a gear spec file name or a map of its fields");
      return std::nullopt;
    }
    gears::GearModel gm = gears::compile_gears(spec);
    if (gm.law.kind() != gears::RatioLaw::Kind::Walking) {
      diag.error(gm.where.law, "gear-drive: the propulsor's travel X(phi) is built in for 'law: walking' only "
                               "(a, b, c of the wheel-walking mechanism)");
      return std::nullopt;
    }
    *syn = gears::synthesize(gm);
    return gm;
  } catch (const InputError& e) {
    for (const auto& d : e.diagnostics()) diag.error(d.where, d.message);
    return std::nullopt;
  }
}

std::shared_ptr<const Machine> gear_drive(FieldReader& f, Body& b) {
  GearDrive::Params p;
  p.I_p = f.positive("pinion_inertia", dim::inertia).value_or(1.0);
  p.I_H = f.positive("wheel_inertia", dim::inertia, 0.0, true).value_or(0.0);
  p.m = f.positive("mass", dim::mass, 0.0, true).value_or(0.0);
  p.F_r = f.quantity("resistance", dim::force, 0.0).value_or(0.0);
  auto ratio = f.word("ratio", {"continuous", "stepwise"}, "continuous");
  p.ratio = ratio && *ratio == "stepwise" ? GearDrive::Ratio::stepwise : GearDrive::Ratio::continuous;
  b.q0 = f.quantity("position", dim::none, 0.0).value_or(0.0);
  b.v0 = f.quantity("velocity", dim::angular_velocity, 0.0).value_or(0.0);
  gears::GearSynthesis syn;
  auto gm = read_gear_spec(f, &syn);
  if (!gm) return nullptr;
  return std::make_shared<GearDrive>(p, std::move(*gm), syn);
}

}  // namespace

bool is_machine_type(const SpecNode& spec) {
  const SpecNode* t = spec.is_map() ? spec.find("type") : nullptr;
  if (!t || !t->is_scalar()) return false;
  return t->scalar == "crank-slider" || t->scalar == "rolling-wheel" || t->scalar == "inertia-table" ||
         t->scalar == "inertia-expression" || t->scalar == "gear-drive";
}

Body compile_machine_body(const std::string& name, const SpecNode& spec, Diagnostics& diag) {
  FieldReader f(spec, fmt::format("body '{}'", name), diag);
  if (name == "ground") diag.error(spec.loc, "'ground' is reserved for the fixed frame; name the body otherwise");
  Body b;
  b.name = name;
  b.kind = BodyKind::rotational;
  const std::string type = *f.text("type");
  if (type == "crank-slider") b.machine = crank_slider(f, b);
  else if (type == "rolling-wheel") b.machine = rolling_wheel(f, b);
  else if (type == "inertia-table") b.machine = inertia_table(f, b);
  else if (type == "gear-drive") b.machine = gear_drive(f, b);
  else b.machine = inertia_expression(f, b);
  f.finish();
  double I = 1.0, dI = 0.0;
  if (b.machine) b.machine->inertia(b.q0, &I, &dI);
  b.inertia = I > 0.0 && std::isfinite(I) ? I : 1.0;
  return b;
}

int resolve_link_end(const Model& m, const std::string& text, bool* point, std::string* error) {
  *point = false;
  const int i = m.body_index(text);
  if (i != -2) return i;
  const auto dot = text.rfind('.');
  if (dot != std::string::npos) {
    const int j = m.body_index(text.substr(0, dot));
    const std::string pname = text.substr(dot + 1);
    if (j >= 0) {
      const auto& mach = m.bodies[static_cast<size_t>(j)].machine;
      if (mach && mach->point_name() == pname) {
        *point = true;
        return j;
      }
      *error = mach && !mach->point_name().empty()
                   ? fmt::format("body '{}' has no point '{}'; its point is '{}'", text.substr(0, dot), pname,
                                 mach->point_name())
                   : fmt::format("body '{}' has no point '{}'", text.substr(0, dot), pname);
      return -2;
    }
  }
  *error = fmt::format("unknown body '{}'", text);
  return -2;
}

}  // namespace machdyn
