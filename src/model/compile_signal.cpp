#include "model/compile_signal.hpp"

#include <algorithm>
#include <cmath>
#include <memory>
#include <numbers>
#include <fmt/format.h>

#include "machdyn/common/expression.hpp"
#include "machdyn/model/model.hpp"
#include "machdyn/model/shaper.hpp"

namespace machdyn::detail {
namespace {

/// Sums inside sums: bounded, so a hostile file cannot recurse without end.
constexpr int kMaxSignalNesting = 8;

std::optional<Signal> compile_signal_at(const SpecNode& node, const Dim& d, const std::string& what,
                                        Diagnostics& diag, int depth);

/// ω in rad/s from a `frequency` field: Hz (or 1/s, or a plain number) are cycles per second,
/// a unit with rad or rev (rad/s, rpm, rps) is an angular speed already.
/// ω (rad/s) of a sine's `frequency` value; nullopt (and `err`) if it is not a positive frequency.
std::optional<double> angular_frequency(const SpecNode& n, std::string* err) {
  auto q = n.is_scalar() ? parse_quantity(n.scalar, err) : std::nullopt;
  if (!q || (q->has_unit && q->dim != Dim{0, 0, -1}) || !(q->value > 0.0)) return std::nullopt;
  const std::string& s = n.scalar;
  const bool angular = s.find("rad") != std::string::npos || s.find("rev") != std::string::npos ||
                       s.find("rpm") != std::string::npos || s.find("rps") != std::string::npos;
  return angular ? q->value : 2.0 * std::numbers::pi * q->value;
}

std::optional<double> read_frequency(FieldReader& f) {
  const SpecNode* n = f.node("frequency");
  if (!n) {
    f.error_at("frequency", "missing field 'frequency' (e.g. 2 Hz or 12.57 rad/s)");
    return std::nullopt;
  }
  std::string err;
  auto omega = angular_frequency(*n, &err);
  if (!omega)
    f.diagnostics().error(n->loc, fmt::format("{}: field 'frequency' expected a positive frequency (Hz) or angular "
                                              "speed (rad/s, rpm){}", f.what(), err.empty() ? "" : ": " + err));
  return omega;
}

/// A pulse width: a time, or a percentage (any dimensionless quantity) of the period.
std::optional<double> read_width(FieldReader& f, double period) {
  const SpecNode* n = f.node("width");
  if (!n) {
    f.error_at("width", "missing field 'width' (a time, or a % of the period)");
    return std::nullopt;
  }
  std::string err;
  auto q = n->is_scalar() ? parse_quantity(n->scalar, &err) : std::nullopt;
  std::optional<double> w;
  if (q && (!q->has_unit || q->dim == dim::time)) w = q->value;
  else if (q && q->dim == dim::none) w = q->value * period;
  if (!w || !(*w > 0.0) || !(*w < period)) {
    f.diagnostics().error(n->loc, fmt::format("{}: field 'width' expected a time between 0 and the period ({:g} s) "
                                              "or a percentage of it, e.g. 50 %{}", f.what(), period,
                                              err.empty() ? "" : ": " + err));
    return std::nullopt;
  }
  return w;
}

/// The SI factor of a `unit` or `time_unit` field, checked against `d`; 1 if absent.
std::optional<double> unit_factor(FieldReader& f, std::string_view key, const Dim& d) {
  const SpecNode* n = f.node(key);
  if (!n) return 1.0;
  std::string err;
  auto q = n->is_scalar() ? parse_quantity("1 " + n->scalar, &err) : std::nullopt;
  if (!q || q->dim != d) {
    f.diagnostics().error(n->loc, fmt::format("{}: field '{}' expected a unit of {}{}", f.what(), key, describe(d),
                                              q ? fmt::format(", got '{}'", n->scalar) : ": " + err));
    return std::nullopt;
  }
  return q->value;
}

/// `type: shaped`: a reference `signal` shaped against an oscillation of `frequency` (or of a
/// pendulum of `length`, ω² = g/L with standard gravity) and `damping` ζ (model/shaper.hpp).
/// `shaper: none` passes the signal through unchanged (the same Signal), so that one file states a
/// move and a sweep over `shaper` runs it unshaped and shaped; its frequency (or length) and damping
/// may be left out and are checked as for the others when given.
std::optional<Signal> read_shaped(FieldReader& f, const Dim& d, int depth) {
  auto kind = f.word("shaper", {"none", "zv", "zvd", "two-step"});
  const bool pass = kind && *kind == "none";
  const bool by_length = f.node("length") != nullptr;
  std::optional<double> omega;
  bool design_ok = true;  // the frequency or length, where one is needed or given
  if (by_length && f.map().find("frequency")) {
    f.error_at("length", "give either 'frequency' or 'length' (a pendulum's, ω² = g/L), not both");
    design_ok = false;
  } else if (by_length) {
    auto L = f.positive("length", dim::length);
    if (L) omega = std::sqrt(kStandardGravity / *L);
    design_ok = omega.has_value();
  } else if (!pass || f.map().find("frequency")) {
    omega = read_frequency(f);
    design_ok = omega.has_value();
  }
  const std::optional<double> damping = f.quantity("damping", dim::none, 0.0);
  bool ok = damping.has_value();
  const double zeta = damping.value_or(0.0);
  if (ok && !(zeta >= 0.0 && zeta < 1.0)) {
    f.error_at("damping", fmt::format("field 'damping' expected a damping ratio ζ in [0, 1), got {:g}", zeta));
    ok = false;
  } else if (ok && kind && *kind == "two-step" && zeta != 0.0) {
    f.error_at("damping", "the two-step acceleration cancels an undamped swing only; for a damped one use zv or zvd");
    ok = false;
  }
  const SpecNode* base = f.node("signal");
  std::optional<Signal> s;
  if (!base) f.error_at("signal", "missing field 'signal' (the reference to shape, e.g. {type: ramp, value: 1 m/s, end: 2 s})");
  else s = compile_signal_at(*base, d, fmt::format("{}: field 'signal'", f.what()), f.diagnostics(), depth + 1);
  if (!kind || !design_ok || !ok || !s) return std::nullopt;
  if (pass) return s;
  try {
    if (*kind == "two-step") return two_step_signal(*s, *omega);
    return shaped_signal(*s, shaper_impulses(*kind == "zv" ? ShaperKind::zv : ShaperKind::zvd, *omega, zeta));
  } catch (const std::invalid_argument& e) {
    f.diagnostics().error(base->loc, fmt::format("{}: field 'signal': {}", f.what(), e.what()));
    return std::nullopt;
  }
}

}  // namespace

const std::vector<std::string>& signal_types() {
  static const std::vector<std::string> k = {"constant", "step", "ramp",       "table", "sine",
                                             "pulse",    "expression", "sum", "shaped", "file"};
  return k;
}

bool is_signal_type(std::string_view type) {
  const auto& k = signal_types();
  return std::find(k.begin(), k.end(), type) != k.end();
}

std::optional<Signal> read_table(FieldReader& f, const Dim& xd, const Dim& yd, bool jumps, bool units) {
  Diagnostics& diag = f.diagnostics();
  auto outside = f.word("outside", {"hold", "extrapolate"}, "hold");
  std::optional<double> xu = 1.0, yu = 1.0;
  const bool has_units = units && (f.map().find("unit") || f.map().find("time_unit"));
  if (units) xu = unit_factor(f, "time_unit", xd), yu = unit_factor(f, "unit", yd);
  const SpecNode* pts = f.node("points");
  if (!pts) {
    f.error_at("points", "missing field 'points' ([[x, value], ...])");
    return std::nullopt;
  }
  if (!pts->is_seq() || pts->items.empty()) {
    diag.error(pts->loc, fmt::format("{}: 'points' expected a list of [x, value] pairs", f.what()));
    return std::nullopt;
  }
  if (pts->items.size() > kMaxTablePoints) {
    diag.error(pts->loc, fmt::format("{}: a table of {} points, more than {}: its spec takes some 400 bytes a point "
                                     "while compiling, and every run of a sweep copies and compiles it again; "
                                     "thin the table", f.what(), pts->items.size(), kMaxTablePoints));
    return std::nullopt;
  }
  std::vector<double> x, y;
  x.reserve(pts->items.size()), y.reserve(pts->items.size());
  bool ok = true;
  for (const auto& p : pts->items) {
    if (!p.is_seq() || p.items.size() != 2 || !p.items[0].is_scalar() || !p.items[1].is_scalar()) {
      diag.error(p.loc, fmt::format("{}: expected a pair [x, value]", f.what()));
      ok = false;
      continue;
    }
    std::optional<double> v[2];
    for (int k = 0; k < 2; ++k) {
      const SpecNode& c = p.items[static_cast<std::size_t>(k)];
      std::string e;
      if (has_units) {  // plain numbers in the table's units
        auto q = parse_quantity(c.scalar, &e);
        if (q && q->has_unit) e = fmt::format("expected a plain number (the table's unit is given), got '{}'", c.scalar);
        else if (q) v[k] = q->value * (k == 0 ? xu.value_or(1.0) : yu.value_or(1.0));
      } else {
        v[k] = parse_as(c.scalar, k == 0 ? xd : yd, &e);
      }
      if (!v[k]) diag.error(c.loc, fmt::format("{}: {}", f.what(), e)), ok = false;
    }
    if (!v[0] || !v[1]) continue;
    if (!x.empty() && (*v[0] < x.back() || (*v[0] == x.back() && (!jumps || (x.size() >= 2 && x[x.size() - 2] == *v[0]))))) {
      diag.error(p.items[0].loc, fmt::format("{}: {} must {}", f.what(), jumps ? "times" : "the first column",
                                             jumps ? "not decrease (two equal times make a jump; three are too many)"
                                                   : "increase"));
      ok = false;
      continue;
    }
    x.push_back(*v[0]);
    y.push_back(*v[1]);
  }
  if (!ok || !xu || !yu || !outside || x.empty()) return std::nullopt;
  const bool extrapolate = *outside == "extrapolate";
  const std::size_t n = x.size();
  if (extrapolate && (n < 2 || x[1] == x[0] || x[n - 1] == x[n - 2])) {
    f.error_at("outside", "'outside: extrapolate' needs a first and a last segment of positive length");
    return std::nullopt;
  }
  return Signal::table(std::move(x), std::move(y), extrapolate);
}

std::optional<Signal> read_signal_fields(FieldReader& f, const std::string& type, const Dim& d) {
  Diagnostics& diag = f.diagnostics();
  if (type == "constant") {
    auto v = f.quantity("value", d);
    return v ? std::optional(Signal::constant(*v)) : std::nullopt;
  }
  if (type == "step") {
    auto after = f.quantity("value", d);
    auto before = f.quantity("before", d, 0.0);
    auto t0 = f.quantity("time", dim::time);
    if (!after || !before || !t0) return std::nullopt;
    return Signal::step(*before, *after, *t0);
  }
  if (type == "ramp") {
    auto after = f.quantity("value", d);
    auto before = f.quantity("before", d, 0.0);
    auto t0 = f.quantity("start", dim::time, 0.0);
    auto t1 = f.quantity("end", dim::time);
    if (t0 && t1 && *t1 <= *t0) {
      f.error_at("end", "field 'end' must be later than 'start'");
      return std::nullopt;
    }
    if (!after || !before || !t0 || !t1) return std::nullopt;
    return Signal::ramp(*before, *after, *t0, *t1);
  }
  if (type == "table") return read_table(f, dim::time, d, true, true);
  if (type == "sine") {
    auto amp = f.quantity("amplitude", d);
    auto omega = read_frequency(f);
    auto phase = f.quantity("phase", dim::none, 0.0);
    auto offset = f.quantity("offset", d, 0.0);
    auto start = f.quantity("start", dim::time, 0.0);
    if (!amp || !omega || !phase || !offset || !start) return std::nullopt;
    return Signal::sine(*amp, *omega, *phase, *offset, *start);
  }
  if (type == "pulse") {
    auto high = f.quantity("high", d);
    auto low = f.quantity("low", d, 0.0);
    auto period = f.positive("period", dim::time);
    auto width = period ? read_width(f, *period) : (f.node("width"), std::nullopt);
    auto start = f.quantity("start", dim::time, 0.0);
    auto count = f.integer("count", 0, 1'000'000'000L, -1L);
    if (!high || !low || !period || !width || !start || !count) return std::nullopt;
    return Signal::pulse(*low, *high, *period, *width, *start, *count);
  }
  if (type == "expression") {
    auto text = f.text("expression");
    if (!text) return std::nullopt;
    try {
      return Signal::expression(std::make_shared<const Expression>(*text, "t"));
    } catch (const ExpressionError& e) {
      f.error_at("expression", fmt::format("field 'expression' '{}': {} (an expression in t, seconds; the value is "
                                           "in SI)", text->size() > 60 ? text->substr(0, 57) + "..." : *text, e.what()));
      return std::nullopt;
    }
  }
  if (type == "sum") {
    const SpecNode* terms = f.node("terms");
    if (!terms || !terms->is_seq() || terms->items.empty()) {
      diag.error(terms ? terms->loc : f.map().loc,
                 fmt::format("{}: field 'terms' expected a list of signals, e.g. [200 N*m, {{type: sine, ...}}]", f.what()));
      return std::nullopt;
    }
    std::vector<Signal> parts;
    bool ok = true;
    for (std::size_t k = 0; k < terms->items.size(); ++k) {
      auto s = compile_signal_at(terms->items[k], d, fmt::format("{}: term {}", f.what(), k + 1), diag, 1);
      if (s) parts.push_back(std::move(*s));
      else ok = false;
    }
    if (!ok) return std::nullopt;
    return Signal::sum(std::move(parts));
  }
  if (type == "shaped") return read_shaped(f, d, 1);
  if (type == "file") {
    // io reads the CSV before compiling (io/model_file.hpp): a `file` left here was not read.
    for (const auto& [k, v] : f.map().fields) f.node(k);
    f.error_at("type", "a 'file' signal is read when the model file is read (load_model); this spec was compiled "
                       "without reading files");
    return std::nullopt;
  }
  f.error_at("type", fmt::format("'{}' is not a kind of signal", type));
  return std::nullopt;
}

namespace {

std::optional<Signal> compile_signal_at(const SpecNode& node, const Dim& d, const std::string& what,
                                        Diagnostics& diag, int depth) {
  if (node.is_scalar()) {
    std::string e;
    auto v = parse_as(node.scalar, d, &e);
    if (!v) diag.error(node.loc, fmt::format("{}: {}", what, e));
    return v ? std::optional(Signal::constant(*v)) : std::nullopt;
  }
  if (!node.is_map()) {
    diag.error(node.loc, fmt::format("{}: expected {} or a signal {{type: step|ramp|table|sine|pulse|expression|sum|"
                                     "shaped|file, ...}}", what, describe(d)));
    return std::nullopt;
  }
  if (depth > kMaxSignalNesting) {
    diag.error(node.loc, fmt::format("{}: sums are nested deeper than {} levels", what, kMaxSignalNesting));
    return std::nullopt;
  }
  FieldReader f(node, what, diag);
  auto type = f.word("type", signal_types());
  std::optional<Signal> s;
  if (type && *type == "sum") {
    // The terms one level deeper, for the nesting bound.
    const SpecNode* terms = f.node("terms");
    if (!terms || !terms->is_seq() || terms->items.empty()) {
      diag.error(terms ? terms->loc : node.loc, fmt::format("{}: field 'terms' expected a list of signals", what));
    } else {
      std::vector<Signal> parts;
      bool ok = true;
      for (std::size_t k = 0; k < terms->items.size(); ++k) {
        auto t = compile_signal_at(terms->items[k], d, fmt::format("{}: term {}", what, k + 1), diag, depth + 1);
        if (t) parts.push_back(std::move(*t));
        else ok = false;
      }
      if (ok) s = Signal::sum(std::move(parts));
    }
  } else if (type && *type == "shaped") {
    s = read_shaped(f, d, depth);
  } else if (type) {
    s = read_signal_fields(f, *type, d);
  } else {
    for (const auto& [k, v] : node.fields) f.node(k);
  }
  f.finish();
  return s;
}

}  // namespace

std::optional<Signal> compile_signal(const SpecNode& node, const Dim& d, const std::string& what, Diagnostics& diag) {
  return compile_signal_at(node, d, what, diag, 0);
}

void check_sine_periods(const SpecNode& root, double t_end, long max_steps, Diagnostics& diag) {
  const double max_periods = static_cast<double>(max_steps) / kMinStepsPerPeriod;
  std::vector<const SpecNode*> todo{&root};
  while (!todo.empty()) {  // without recursion: a spec may be deep
    const SpecNode* n = todo.back();
    todo.pop_back();
    for (const auto& item : n->items) todo.push_back(&item);
    for (const auto& [key, field] : n->fields)
      if (!(n == &root && key == "cases")) todo.push_back(&field);
    const SpecNode* type = n->is_map() ? n->find("type") : nullptr;
    const SpecNode* freq = type && type->is_scalar() && type->scalar == "sine" ? n->find("frequency") : nullptr;
    std::string err;
    const std::optional<double> omega = freq ? angular_frequency(*freq, &err) : std::nullopt;
    if (!omega) continue;  // none, or an error the signal's reader reports
    const double periods = *omega / (2.0 * std::numbers::pi) * t_end;
    if (periods > max_periods)
      diag.error(freq->loc, fmt::format("a sine of {:.6g} Hz makes {:.3g} periods before t_end = {:.6g} s; at least "
                                        "{:g} steps each would take more than max_steps = {} steps, so no run could "
                                        "end: lower the frequency or t_end (or raise simulation.max_steps)",
                                        *omega / (2.0 * std::numbers::pi), periods, t_end, kMinStepsPerPeriod,
                                        max_steps));
  }
}

}  // namespace machdyn::detail
