#include "machdyn/analysis/fatigue.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace machdyn {
namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("S-N curve: " + what);
}

void check_repeat(double repeat) {
  if (!(repeat >= 0.0) || !std::isfinite(repeat))
    throw std::invalid_argument("fatigue: the repetitions must be finite and >= 0");
}

}  // namespace

void SNCurve::validate() const {
  require(m > 0.0 && std::isfinite(m), "the slope m must be finite and > 0 (a curve without a slope)");
  require(delta_ref > 0.0 && std::isfinite(delta_ref), "the reference range must be finite and > 0");
  require(n_ref > 0.0 && std::isfinite(n_ref), "the reference number of cycles must be finite and > 0");
  require(n_knee >= 0.0 && std::isfinite(n_knee), "the cycles at the knee must be finite and >= 0 (0: no knee)");
  require(m2 > 0.0 && !std::isnan(m2), "the second slope m2 must be > 0 (infinite: an endurance limit)");
}

double SNCurve::knee_range() const { return n_knee > 0.0 ? delta_ref * std::pow(n_ref / n_knee, 1.0 / m) : 0.0; }

double SNCurve::cycles_to_failure(double range) const {
  if (!(range > 0.0)) return std::numeric_limits<double>::infinity();
  const double knee = knee_range();
  if (n_knee <= 0.0 || range >= knee) return n_ref * std::pow(delta_ref / range, m);
  if (std::isinf(m2)) return std::numeric_limits<double>::infinity();
  return n_knee * std::pow(knee / range, m2);
}

double miner_damage(std::span<const RainflowCycle> cycles, const SNCurve& curve, double repeat) {
  curve.validate();
  check_repeat(repeat);
  double d = 0.0;
  for (const RainflowCycle& c : cycles) d += c.count / curve.cycles_to_failure(c.range());
  return repeat * d;
}

double equivalent_range(std::span<const RainflowCycle> cycles, double m, double n_eq, double repeat) {
  if (!(m > 0.0 && std::isfinite(m))) throw std::invalid_argument("equivalent range: the exponent m must be > 0");
  if (!(n_eq > 0.0 && std::isfinite(n_eq))) throw std::invalid_argument("equivalent range: N_eq must be > 0");
  check_repeat(repeat);
  double sum = 0.0;
  for (const RainflowCycle& c : cycles) sum += c.count * std::pow(c.range(), m);
  return std::pow(repeat * sum / n_eq, 1.0 / m);
}

StressHistory stress_history(std::span<const RainflowCycle> cycles, double m, double n_ref, double repeat) {
  if (!(m > 0.0 && std::isfinite(m))) throw std::invalid_argument("stress history: the exponent m must be > 0");
  if (!(n_ref > 0.0 && std::isfinite(n_ref))) throw std::invalid_argument("stress history: N_ref must be > 0");
  check_repeat(repeat);
  StressHistory h;
  for (const RainflowCycle& c : cycles) h.total_cycles += repeat * c.count, h.largest = std::max(h.largest, c.range());
  if (h.total_cycles <= 0.0 || h.largest <= 0.0) return h;
  double sum = 0.0;
  for (const RainflowCycle& c : cycles) sum += repeat * c.count * std::pow(c.range() / h.largest, m);
  h.k = sum / h.total_cycles;
  h.nu = h.total_cycles / n_ref;
  h.s = h.nu * h.k;
  return h;
}

}  // namespace machdyn
