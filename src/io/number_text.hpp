#pragma once
// How the result files and the figures write a number (private to src/io): each rule once, for every
// file that writes it.
#include <cmath>
#include <string>
#include <utility>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "machdyn/io/plot.hpp"

namespace machdyn {

/// A double in JSON: JSON has no NaN or infinity, so a value that is not finite is null.
inline nlohmann::json json_number(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

/// A number in a figure's titles, labels and tables: 4 significant digits.
inline std::string label_number(double v) { return fmt::format("{:.4g}", v); }

/// An engineering unit for loads of this size: the SI unit ("N", "N*m", printed "N·m") with k or M in
/// front when the largest magnitude reaches 10⁴ or 10⁷, so tick labels stay short decimals (43.5 kN,
/// not 43500 or 4.35e+04). Returns the factor to multiply SI values by and the printed unit.
inline std::pair<double, std::string> engineering_unit(double largest, const std::string& si_unit) {
  const std::string u = plot::pretty_unit(si_unit);
  if (largest >= 1e7) return {1e-6, "M" + u};
  if (largest >= 1e4) return {1e-3, "k" + u};
  return {1.0, u};
}

}  // namespace machdyn
