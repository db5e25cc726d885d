#include "machdyn/common/units.hpp"

#include <cctype>
#include <cmath>
#include <cerrno>
#include <cstdlib>
#include <limits>
#include <numbers>
#include <fmt/format.h>

namespace machdyn {
namespace {

struct UnitDef {
  std::string_view name;
  double factor;
  Dim dim;
  bool prefixable;
};

constexpr double pi = std::numbers::pi;

constexpr UnitDef kUnits[] = {
    {"m", 1.0, dim::length, true},       {"g", 1e-3, dim::mass, true},
    {"t", 1e3, dim::mass, false},        {"s", 1.0, dim::time, true},
    {"min", 60.0, dim::time, false},     {"h", 3600.0, dim::time, false},
    {"N", 1.0, dim::force, true},        {"J", 1.0, dim::torque, true},
    {"W", 1.0, {1, 2, -3}, true},        {"Pa", 1.0, {1, -1, -2}, true},
    {"Hz", 1.0, {0, 0, -1}, true},       {"rad", 1.0, dim::none, true},
    {"deg", pi / 180.0, dim::none, false}, {"rev", 2.0 * pi, dim::none, false},
    {"rpm", 2.0 * pi / 60.0, {0, 0, -1}, false}, {"rps", 2.0 * pi, {0, 0, -1}, false},
    {"%", 0.01, dim::none, false},
    {"Nm", 1.0, dim::torque, false},     {"kNm", 1e3, dim::torque, false},
    {"A", 1.0, dim::current, true},      {"V", 1.0, dim::voltage, true},
    {"ohm", 1.0, dim::resistance, true}, {"Ω", 1.0, dim::resistance, true},
    {"H", 1.0, dim::inductance, true},   {"K", 1.0, dim::temperature, true},
};

struct Prefix {
  std::string_view p;
  double f;
};
constexpr Prefix kPrefixes[] = {{"n", 1e-9}, {"u", 1e-6}, {"µ", 1e-6}, {"m", 1e-3}, {"c", 1e-2},
                                {"d", 1e-1}, {"k", 1e3},  {"M", 1e6},  {"G", 1e9}};

std::optional<Quantity> lookup_unit(std::string_view name) {
  for (const auto& u : kUnits)
    if (u.name == name) return Quantity{u.factor, u.dim, true, u.name == "Hz"};
  for (const auto& pr : kPrefixes) {
    if (name.size() <= pr.p.size() || name.substr(0, pr.p.size()) != pr.p) continue;
    auto base = name.substr(pr.p.size());
    for (const auto& u : kUnits)
      if (u.prefixable && u.name == base) return Quantity{pr.f * u.factor, u.dim, true, u.name == "Hz"};
  }
  return std::nullopt;
}

// Bounds that keep unit arithmetic exact and finite: no SI unit needs an exponent beyond 12, and
// parentheses nest a few levels in practice (the bound keeps a hostile text off the stack).
constexpr long kMaxExponent = 12;
constexpr int kMaxDimExponent = 64;
constexpr int kMaxNesting = 16;

bool starts_unit(std::string_view s, size_t i) {
  if (i >= s.size()) return false;
  const auto c = static_cast<unsigned char>(s[i]);
  return std::isalpha(c) || c == '%' || c == '(' || (c >= 0x80 && s.substr(i, 2) != "·");
}

/// Recursive-descent parser of a unit expression; positions are byte offsets into the text.
class UnitParser {
 public:
  UnitParser(std::string_view s, size_t pos) : s_(s), i_(pos) {}

  std::optional<Quantity> expr(std::string* err) {
    if (++depth_ > kMaxNesting) return fail(err, fmt::format("units nested deeper than {} parentheses", kMaxNesting));
    auto q = factor(err);
    if (!q) return q;
    for (;;) {
      const size_t before = i_;
      skip_ws();
      char op = 0;
      if (at("*")) op = '*', i_ += 1;
      else if (at("/")) op = '/', i_ += 1;
      else if (at("·")) op = '*', i_ += std::string_view("·").size();
      else if (at(".") ) op = '*', i_ += 1;
      else if (i_ > before && starts_unit(s_, i_)) op = '*';  // `kg m^2`: a space multiplies
      else {
        --depth_;
        return q;
      }
      auto r = factor(err);
      if (!r) return r;
      const Dim d = op == '*' ? q->dim * r->dim : q->dim / r->dim;
      if (std::abs(d.kg) > kMaxDimExponent || std::abs(d.m) > kMaxDimExponent || std::abs(d.s) > kMaxDimExponent ||
          std::abs(d.A) > kMaxDimExponent)
        return fail(err, "unit exponents out of range");
      q = Quantity{op == '*' ? q->value * r->value : q->value / r->value, d, true, q->hertz || r->hertz};
    }
  }
  [[nodiscard]] size_t pos() const { return i_; }
  void skip_ws() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\t')) ++i_;
  }

 private:
  bool at(std::string_view t) const { return s_.substr(i_, t.size()) == t; }

  std::optional<Quantity> factor(std::string* err) {
    skip_ws();
    std::optional<Quantity> q;
    if (at("(")) {
      ++i_;
      q = expr(err);
      if (!q) return q;
      skip_ws();
      if (!at(")")) return fail(err, "expected ')'");
      ++i_;
    } else if (at("1") && !(i_ + 1 < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_ + 1])))) {
      ++i_;  // `1/m`: a one as the numerator of a reciprocal unit
      q = Quantity{1.0, dim::none, true};
    } else {
      size_t start = i_;
      while (i_ < s_.size() && (std::isalpha(static_cast<unsigned char>(s_[i_])) || s_[i_] == '%' ||
                                static_cast<unsigned char>(s_[i_]) >= 0x80) &&
             !at("·") && !at("²") && !at("³"))
        ++i_;
      if (i_ == start) return fail(err, "expected a unit");
      auto name = s_.substr(start, i_ - start);
      q = lookup_unit(name);
      if (!q) {
        i_ = start;
        return fail(err, fmt::format("unknown unit '{}'", name));
      }
    }
    int p = 1;
    if (at("^")) {
      ++i_;
      char* end = nullptr;
      std::string rest(s_.substr(i_));
      errno = 0;
      long v = std::strtol(rest.c_str(), &end, 10);
      if (end == rest.c_str()) return fail(err, "expected an integer exponent after '^'");
      if (errno == ERANGE || v > kMaxExponent || v < -kMaxExponent)
        return fail(err, fmt::format("expected an exponent from -{0} to {0} after '^'", kMaxExponent));
      i_ += static_cast<size_t>(end - rest.c_str());
      p = static_cast<int>(v);
    } else if (at("²")) {
      i_ += std::string_view("²").size();
      p = 2;
    } else if (at("³")) {
      i_ += std::string_view("³").size();
      p = 3;
    }
    const Dim d = q->dim.pow(p);
    if (std::abs(d.kg) > kMaxDimExponent || std::abs(d.m) > kMaxDimExponent || std::abs(d.s) > kMaxDimExponent ||
          std::abs(d.A) > kMaxDimExponent)
      return fail(err, "unit exponents out of range");
    return Quantity{std::pow(q->value, p), d, true, q->hertz};
  }

  std::optional<Quantity> fail(std::string* err, const std::string& what) {
    if (err) *err = fmt::format("{} at character {} of '{}'", what, i_ + 1, s_);
    return std::nullopt;
  }

  std::string_view s_;
  size_t i_;
  int depth_ = 0;
};

}  // namespace

std::string describe(const Dim& d) {
  struct Named {
    Dim d;
    const char* text;
  };
  static const Named names[] = {
      {dim::none, "a plain number (ratio or angle in rad)"},
      {dim::mass, "a mass (kg)"},
      {dim::length, "a length (m)"},
      {dim::time, "a time (s)"},
      {dim::inertia, "a moment of inertia (kg*m^2)"},
      {dim::force, "a force (N)"},
      {dim::torque, "a torque (N*m) or a rotational stiffness (N*m/rad)"},
      {dim::velocity, "a velocity (m/s)"},
      {dim::angular_velocity, "an angular velocity (rad/s) or a frequency"},
      {dim::stiffness_lin, "a stiffness (N/m)"},
      {dim::damping_lin, "a damping coefficient (N*s/m)"},
      {dim::damping_rot, "a rotational damping coefficient (N*m*s/rad)"},
      {dim::inv_length, "a ratio per length (rad/m, 1/m)"},
      {dim::acceleration, "an acceleration (m/s^2)"},
      {dim::current, "a current (A)"},
      {dim::voltage, "a voltage (V)"},
      {dim::resistance, "a resistance (ohm)"},
      {dim::inductance, "an inductance (H)"},
      {dim::torque / dim::current, "a motor constant (N*m/A = V*s/rad)"},
      {dim::force / dim::current, "a motor constant (N/A = V*s/m)"},
      {dim::temperature, "a temperature difference (K)"},
      {dim::heat_capacity, "a heat capacity (J/K)"},
      {dim::thermal_conductance, "a thermal conductance (W/K)"},
  };
  for (const auto& n : names)
    if (n.d == d) return n.text;
  if (d.K != 0) return fmt::format("a quantity of dimension kg^{}*m^{}*s^{}*A^{}*K^{}", d.kg, d.m, d.s, d.A, d.K);
  if (d.A != 0) return fmt::format("a quantity of dimension kg^{}*m^{}*s^{}*A^{}", d.kg, d.m, d.s, d.A);
  return fmt::format("a quantity of dimension kg^{}*m^{}*s^{}", d.kg, d.m, d.s);
}

std::optional<Quantity> parse_quantity(std::string_view text, std::string* error) {
  std::string s(text);
  {  // YAML spells NaN and infinity .nan and .inf
    std::string low;
    for (char ch : s) low += static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    size_t k = low.find_first_not_of("+-. ");
    if (k != std::string::npos && (low.compare(k, 3, "nan") == 0 || low.compare(k, 3, "inf") == 0)) {
      if (error) *error = fmt::format("expected a finite number, got '{}'", text);
      return std::nullopt;
    }
  }
  const char* begin = s.c_str();
  char* end = nullptr;
  double v = std::strtod(begin, &end);
  if (end == begin) {
    if (error) *error = fmt::format("expected a number, got '{}'", text);
    return std::nullopt;
  }
  if (!std::isfinite(v)) {
    if (error) *error = fmt::format("expected a finite number, got '{}'", text);
    return std::nullopt;
  }
  // A subnormal (5e-324) has lost its precision, and 1/x of it overflows: out of range like 1e400.
  auto out_of_range = [&] {
    if (error) *error = fmt::format("'{}' is out of range in SI units (beyond ±{:g} or below {:g})", text,
                                    std::numeric_limits<double>::max(), std::numeric_limits<double>::min());
    return std::nullopt;
  };
  if (v != 0.0 && std::abs(v) < std::numeric_limits<double>::min()) return out_of_range();
  UnitParser p(text, static_cast<size_t>(end - begin));
  p.skip_ws();
  if (p.pos() == text.size()) return Quantity{v, dim::none};
  auto u = p.expr(error);
  if (!u) return std::nullopt;
  p.skip_ws();
  if (p.pos() != text.size()) {
    if (error) *error = fmt::format("unexpected '{}' at character {} of '{}'", text.substr(p.pos()),
                                    p.pos() + 1, text);
    return std::nullopt;
  }
  // `5 km^400`, `1e308 kN`, `0 (km/m)^400`: a value that does not survive scaling is an input error,
  // not an infinity or NaN that fails later in a run.
  const double scaled = v * u->value;
  if (!std::isfinite(u->value) || u->value == 0.0 || !std::isfinite(scaled) ||
      (v != 0.0 && std::abs(scaled) < std::numeric_limits<double>::min()))
    return out_of_range();
  return Quantity{scaled, u->dim, true, u->hertz};
}

std::optional<double> parse_as(std::string_view text, const Dim& expected, std::string* error) {
  auto q = parse_quantity(text, error);
  if (!q) return std::nullopt;
  if (q->hertz && expected == dim::angular_velocity) {
    // Hz is cycles per second, but 1 Hz as an angular speed is 2π rad/s or 1 rad/s depending on the
    // reader: never guess a factor 2π.
    if (error)
      *error = fmt::format("'{}': Hz is ambiguous for an angular speed; write rpm, rps (revolutions per "
                           "second) or rad/s", text);
    return std::nullopt;
  }
  if (q->has_unit && !(q->dim == expected)) {
    if (error)
      *error = fmt::format("expected {}, got {} in '{}'", describe(expected), describe(q->dim), text);
    return std::nullopt;
  }
  return q->value;
}

std::optional<double> parse_temperature(std::string_view text, std::string* error) {
  std::string_view t = text;
  while (!t.empty() && t.back() == ' ') t.remove_suffix(1);
  double offset = 0.0;
  std::optional<double> v;
  for (std::string_view celsius : {std::string_view("degC"), std::string_view("°C")}) {
    if (t.size() > celsius.size() && t.substr(t.size() - celsius.size()) == celsius) {
      v = parse_as(t.substr(0, t.size() - celsius.size()), dim::none, error);
      if (!v) return std::nullopt;
      offset = kZeroCelsius;
      break;
    }
  }
  if (!v) {
    auto q = parse_quantity(text, error);
    if (!q) return std::nullopt;
    if (!q->has_unit || !(q->dim == dim::temperature)) {
      if (error)
        *error = fmt::format("expected a temperature with its unit, e.g. '20 degC', '20 °C' or '293.15 K', got '{}'", text);
      return std::nullopt;
    }
    v = q->value;
  }
  const double kelvin = *v + offset;
  if (!(kelvin >= 0.0)) {
    if (error) *error = fmt::format("'{}' is below absolute zero", text);
    return std::nullopt;
  }
  return kelvin;
}

}  // namespace machdyn
