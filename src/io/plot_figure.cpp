// The renderer-independent part of a Figure: labels, colours, units, checks.
#include <array>
#include <cctype>
#include <stdexcept>

#include <fmt/format.h>

#include "machdyn/io/plot.hpp"

namespace machdyn::plot {

std::string Axis::label() const { return unit.empty() ? quantity : quantity + ", " + unit; }

Axis make_axis(std::string quantity, std::string unit) {
  Axis a;
  a.quantity = std::move(quantity);
  a.unit = std::move(unit);
  return a;
}

Series make_series(std::string name, std::vector<double> x, std::vector<double> y, Style style, int y_axis) {
  Series s;
  s.name = std::move(name);
  s.x = std::move(x);
  s.y = std::move(y);
  s.style = style;
  s.y_axis = y_axis;
  return s;
}

RefLine make_ref_line(double value, std::string label, int series, int y_axis) {
  RefLine r;
  r.value = value;
  r.label = std::move(label);
  r.series = series;
  r.y_axis = y_axis;
  return r;
}

std::string series_color(std::size_t k) {
  // Okabe & Ito (2008), without yellow (too light on white paper), black last.
  static constexpr std::array<const char*, 7> kColors = {"#0072B2", "#D55E00", "#009E73", "#CC79A7",
                                                         "#E69F00", "#56B4E9", "#000000"};
  return kColors[k % kColors.size()];
}

std::string pretty_unit(const std::string& unit) {
  std::string s;
  for (std::size_t i = 0; i < unit.size(); ++i) {
    const char ch = unit[i];
    if (ch == '*') {
      s += "·";
    } else if (ch == '^' && i + 1 < unit.size()) {
      const char e = unit[++i];
      if (e == '2') s += "²";
      else if (e == '3') s += "³";
      else if (e == '-' && i + 1 < unit.size() && unit[i + 1] == '1') s += "⁻¹", ++i;
      else s += std::string("^") + e;
    } else {
      s += ch;
    }
  }
  return s;
}

void validate(const Figure& fig) {
  if (fig.id.empty()) throw std::invalid_argument("figure: empty id");
  for (const char ch : fig.id)
    if (!(std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-'))
      throw std::invalid_argument(fmt::format("figure '{}': id may hold only letters, digits, '_' and '-'", fig.id));
  for (const auto& s : fig.series) {
    if (s.x.size() != s.y.size())
      throw std::invalid_argument(fmt::format("figure '{}': series '{}' has {} x and {} y values", fig.id, s.name,
                                              s.x.size(), s.y.size()));
    if (s.y_axis != 1 && s.y_axis != 2)
      throw std::invalid_argument(fmt::format("figure '{}': series '{}': y_axis must be 1 or 2", fig.id, s.name));
    if (s.y_axis == 2 && !fig.y2.used())
      throw std::invalid_argument(fmt::format("figure '{}': series '{}' is on y2, which has no quantity", fig.id, s.name));
  }
  for (const auto& r : fig.ref_lines) {
    if (r.series >= static_cast<int>(fig.series.size()))
      throw std::invalid_argument(fmt::format("figure '{}': reference line '{}' names series {}", fig.id, r.label,
                                              r.series));
    if (r.y_axis == 2 && !fig.y2.used())
      throw std::invalid_argument(fmt::format("figure '{}': reference line '{}' is on y2, which has no quantity",
                                              fig.id, r.label));
  }
}

}  // namespace machdyn::plot
