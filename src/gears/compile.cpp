#include <cmath>
#include <fmt/format.h>
#include <numbers>
#include <optional>
#include "common/constants.hpp"

#include "machdyn/gears/gear_model.hpp"

namespace machdyn::gears {

double GearModel::rH(double phi) const {
  const double i = law.ratio(phi).v;
  return L * i / (1.0 + i);
}
double GearModel::r(double phi) const { return L / (1.0 + law.ratio(phi).v); }

namespace {


std::optional<Expression> read_expression(FieldReader& fr, const char* key, bool required) {
  const SpecNode* n = fr.node(key);
  if (!n) {
    if (required)
      fr.diagnostics().error(fr.map().loc, fmt::format("{}: missing field '{}' (an expression of phi)", fr.what(), key));
    return std::nullopt;
  }
  if (!n->is_scalar()) {
    fr.diagnostics().error(n->loc, fmt::format("{}: field '{}' expected an expression of phi", fr.what(), key));
    return std::nullopt;
  }
  try {
    Expression e(n->scalar, "phi");
    e.refuse_switches(0, true, "the law needs its derivatives everywhere (a smooth function of phi)");
    return e;
  } catch (const ExpressionError& e) {
    Location at = n->loc;
    // Quote a long text by its start only (a runaway expression may be megabytes).
    const std::string shown = n->scalar.size() > 80 ? n->scalar.substr(0, 77) + "..." : n->scalar;
    fr.diagnostics().error(at, fmt::format("{}: field '{}': {} in '{}'", fr.what(), key, e.what(), shown));
    return std::nullopt;
  }
}

std::optional<PeriodicSpline> read_table(FieldReader& fr, double T, Diagnostics& diag) {
  const SpecNode* n = fr.node("ratio_table");
  if (!n) {
    diag.error(fr.map().loc, fmt::format("{}: missing field 'ratio_table' ([[phi, i], ...])", fr.what()));
    return std::nullopt;
  }
  if (!n->is_seq()) {
    diag.error(n->loc, fmt::format("{}: field 'ratio_table' expected a list of [phi, i] pairs", fr.what()));
    return std::nullopt;
  }
  std::vector<double> x, y;
  bool ok = true;
  for (const auto& row : n->items) {
    if (!row.is_seq() || row.items.size() != 2 || !row.items[0].is_scalar() || !row.items[1].is_scalar()) {
      diag.error(row.loc, "ratio_table: each row must be [phi, i], e.g. [10 deg, 1.3]");
      ok = false;
      continue;
    }
    std::string err;
    auto p = parse_as(row.items[0].scalar, dim::none, &err);
    if (!p) diag.error(row.items[0].loc, "ratio_table: angle: " + err);
    auto v = parse_as(row.items[1].scalar, dim::none, &err);
    if (!v) diag.error(row.items[1].loc, "ratio_table: ratio: " + err);
    if (!p || !v) {
      ok = false;
      continue;
    }
    x.push_back(*p);
    y.push_back(*v);
  }
  if (!ok) return std::nullopt;
  try {
    return PeriodicSpline(x, y, T);
  } catch (const std::invalid_argument& e) {
    diag.error(n->loc, fmt::format("ratio_table: {}", e.what()));
    return std::nullopt;
  }
}

}  // namespace

GearModel compile_gears(const SpecNode& root) {
  Diagnostics diag;
  FieldReader fr(root, "gears", diag);
  if (!root.is_map()) diag.throw_if_any();
  GearModel m;
  auto place = [&](const char* key) {
    const SpecNode* n = root.find(key);
    return n ? n->loc : root.loc;
  };
  m.where.root = root.loc;
  m.where.law = place("law");
  m.where.L = place("L");
  m.where.L_installed = root.find("L_installed") ? place("L_installed") : place("clearance");
  m.where.z = place("z");
  m.where.zH = place("zH");

  auto law_kind = fr.word("law", {"walking", "travel", "expression", "table"}, std::string("walking"));
  auto L = fr.positive("L", dim::length);
  // The installation distance: absolute (L_installed) or as the clearance over L, so that
  // `--set L=...` keeps the example's 0.5 mm of the paper (143.5 → 144 mm).
  const bool has_installed = root.find("L_installed") != nullptr, has_clearance = root.find("clearance") != nullptr;
  if (has_installed && has_clearance)
    fr.error_at("clearance", "give either 'L_installed' or 'clearance' (installation distance − L), not both");
  auto clearance = fr.quantity("clearance", dim::length, 0.0);
  auto L_inst = fr.positive("L_installed", dim::length,
                            L && clearance ? std::optional<double>(*L + *clearance) : std::optional<double>(1.0));
  auto z = fr.integer("z", 1, 100000);
  auto zH = fr.integer("zH", 1, 100000);
  auto N = fr.integer("sectors", 1, 1000, 4L);
  auto tol = fr.positive("tolerance", dim::none, 1e-6);
  auto maxit = fr.integer("max_iterations", 1, 100000000, 10000L);
  auto speed = fr.positive("pinion_speed", dim::angular_velocity, 1.0);

  // law-specific fields: read the ones the law needs, reject the others with a clear message
  const std::string kind = law_kind.value_or("walking");
  auto other_law_field = [&](const char* key, const char* owner) {
    if (const SpecNode* n = fr.node(key))
      diag.error(n->loc, fmt::format("gears: field '{}' belongs to law '{}', but law is '{}'", key, owner, kind));
  };
  std::optional<double> a, b, c;
  if (kind == "walking") {
    a = fr.positive("a", dim::length);
    b = fr.positive("b", dim::length);
    c = fr.positive("c", dim::length);
  } else {
    for (const char* k : {"a", "b", "c"}) other_law_field(k, "walking");
  }
  if (kind != "travel") other_law_field("travel", "travel");
  if (kind != "expression") other_law_field("ratio", "expression");
  if (kind != "table") other_law_field("ratio_table", "table");
  std::optional<std::string> normalize;
  if (kind == "expression" || kind == "table")
    normalize = fr.word("normalize", {"true", "false"}, std::string("false"));
  else
    other_law_field("normalize", "expression or table");

  // profile settings
  if (const SpecNode* p = fr.node("profile")) {
    FieldReader pr(*p, "gears.profile", diag);
    m.where.basis = p->find("basis") ? p->find("basis")->loc : p->loc;
    auto basis = pr.word("basis", {"stepwise", "continuous"}, std::string("stepwise"));
    auto alpha = pr.positive("pressure_angle", dim::none, 20.0 * kDeg);
    auto ha = pr.positive("addendum", dim::none, 1.0);
    auto hf = pr.positive("dedendum", dim::none, 1.25);
    auto pts = pr.integer("points", 3, 1000, 12L);
    pr.finish();
    if (basis) m.profile.basis = *basis == "continuous" ? ProfileBasis::Continuous : ProfileBasis::Stepwise;
    if (alpha) {
      if (*alpha >= 45.0 * kDeg) pr.error_at("pressure_angle", "field 'pressure_angle' must be below 45 deg");
      m.profile.pressure_angle = *alpha;
    }
    if (ha) m.profile.addendum = *ha;
    if (hf) m.profile.dedendum = *hf;
    if (ha && hf && *hf <= *ha) pr.error_at("dedendum", "field 'dedendum' must exceed 'addendum' (root clearance)");
    if (pts) m.profile.points = static_cast<int>(*pts);
  } else {
    m.profile.pressure_angle = 20.0 * kDeg;
    m.where.basis = root.loc;
  }

  std::optional<Expression> travel_expr, ratio_expr;
  if (kind == "travel") travel_expr = read_expression(fr, "travel", true);
  if (kind == "expression") ratio_expr = read_expression(fr, "ratio", true);

  // counts
  if (zH && N && *zH % *N != 0)
    fr.error_at("zH", fmt::format("zH = {} must be a multiple of the number of big sectors ({}), so that every big "
                                  "sector has the same whole number of teeth", *zH, *N));
  if (z && zH && N && (*z * *N) % *zH != 0)
    fr.error_at("z", fmt::format("the pinion must be made of whole big sectors: z·N/zH = {}·{}/{} is not a whole "
                                 "number", *z, *N, *zH));
  if (L && L_inst && *L_inst < *L)
    fr.error_at("L_installed", fmt::format("installation distance {:.6g} mm is below the calculation distance "
                                           "{:.6g} mm: the teeth would jam", *L_inst * 1e3, *L * 1e3));
  if (kind == "walking" && a && b && c && !(*a - *b + *c > 0.0))
    fr.error_at("b", "the walking law needs a − b + c > 0 (the hub must advance at every angle)");

  std::optional<PeriodicSpline> spline;
  if (kind == "table" && N) spline = read_table(fr, 2.0 * std::numbers::pi / static_cast<double>(*N), diag);
  fr.finish();
  diag.throw_if_any();

  // ---- the law
  m.L = *L;
  m.L_installed = *L_inst;
  m.z = static_cast<int>(*z);
  m.zH = static_cast<int>(*zH);
  m.N = static_cast<int>(*N);
  m.n = m.zH / m.N;
  m.tolerance = *tol;
  m.max_iterations = static_cast<int>(*maxit);
  m.pinion_speed = *speed;
  const double T = 2.0 * std::numbers::pi / m.N;
  const double Theta = 2.0 * std::numbers::pi * m.zH / (static_cast<double>(m.z) * m.N);
  const bool norm = normalize.value_or("false") == "true";
  if (kind == "walking") m.law = RatioLaw::walking(*a, *b, *c, T, Theta);
  else if (kind == "travel") m.law = RatioLaw::travel(std::move(*travel_expr), T, Theta);
  else if (kind == "expression") m.law = RatioLaw::expression(std::move(*ratio_expr), T, Theta, norm);
  else m.law = RatioLaw::table(std::move(*spline), T, Theta, norm);

  const char* law_field = kind == "walking" ? "law" : kind == "travel" ? "travel" : kind == "expression" ? "ratio" : "ratio_table";
  const Location law_loc = place(law_field);
  m.where.law = law_loc;

  // ---- the law must be finite and positive over the big sector
  if (!std::isfinite(m.law.u()) || m.law.u() <= 0.0) {
    diag.error(law_loc, fmt::format("gears: the law integrates to {:.6g} over a big sector; it must be positive to "
                                    "be scaled to close", m.law.sector_integral() / m.law.u()));
    diag.throw_if_any();
  }
  const int samples = 4096;
  for (int q = 0; q <= samples; ++q) {
    const double phi = -0.5 * T + T * q / samples;
    const Jet i = m.law.ratio(phi);
    if (!std::isfinite(i.v) || !std::isfinite(i.d) || !std::isfinite(i.dd) || i.v <= 0.0) {
      diag.error(law_loc, fmt::format("gears: the ratio i(φ) must be finite and positive (both pitch radii > 0); "
                                      "i({:.4g} deg) = {:.6g}", phi / kDeg, i.v));
      diag.throw_if_any();
    }
  }
  // ---- it must repeat from one big sector to the next (no jump of the pitch radius)
  const double i_end = m.law.ratio(0.5 * T).v, i_start = m.law.ratio(-0.5 * T).v;
  if (std::abs(i_end - i_start) > 1e-9 * std::max(1.0, std::abs(i_end)))
    diag.error(law_loc, fmt::format("gears: the ratio law does not repeat from one big sector to the next: "
                                    "i(+{0:.6g} deg) = {1:.9g} but i(−{0:.6g} deg) = {2:.9g}; the pitch curves "
                                    "would have a step", 0.5 * T / kDeg, i_end, i_start));
  // ---- closure: the pinion turns Θ per big sector
  const double S = m.law.sector_integral();
  if (std::abs(S - Theta) > m.tolerance)
    diag.error(law_loc, fmt::format("gears: the ratio law does not close: ∫ i dφ over a big sector = {:.9g} rad, but "
                                    "the pinion must turn 2π·zH/(z·N) = {:.9g} rad (zH/z = {}/{}, N = {}); multiply "
                                    "the law by {:.9g} or set 'normalize: true'",
                                    S, Theta, m.zH, m.z, m.N, Theta / S));
  diag.throw_if_any();
  return m;
}

}  // namespace machdyn::gears
