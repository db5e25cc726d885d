#include "machdyn/model/shaper.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

namespace machdyn {
namespace {

constexpr double kLow = -std::numeric_limits<double>::max();
constexpr double kHigh = std::numeric_limits<double>::max();
/// Breakpoints of all copies of a shaped reference together: the shaped table's size is bounded.
constexpr double kMaxShapedBreakpoints = 1e6;

bool piecewise_linear(const Signal& s) {
  switch (s.kind()) {
    case Signal::Kind::constant:
    case Signal::Kind::step:
    case Signal::Kind::ramp:
    case Signal::Kind::table:
    case Signal::Kind::pulse: return true;
    case Signal::Kind::sum:
      return std::all_of(s.terms().begin(), s.terms().end(), [](const Signal& t) { return piecewise_linear(t); });
    case Signal::Kind::sine:
    case Signal::Kind::expression: return false;
  }
  return false;
}

/// s(b⁻) of a piecewise-linear s whose previous breakpoint is `prev` (or none: −∞): s is linear on
/// (prev, b), so its value and slope at the middle of that interval give the left limit exactly.
double left_limit(const Signal& s, double b, double prev) {
  const double h = prev > kLow ? 0.5 * (b - prev) : 1.0;
  return s.value(b - h) + s.slope(b - h) * h;
}

void check_shaper(double omega, double zeta) {
  if (!(omega > 0.0) || !std::isfinite(omega)) throw std::invalid_argument("a shaper needs a frequency > 0");
  if (!(zeta >= 0.0 && zeta < 1.0)) throw std::invalid_argument("a shaper's damping ratio must be in [0, 1)");
}

}  // namespace

std::vector<ShaperImpulse> shaper_impulses(ShaperKind kind, double omega, double zeta) {
  check_shaper(omega, zeta);
  const double root = std::sqrt(1.0 - zeta * zeta);
  const double K = std::exp(-zeta * std::numbers::pi / root);
  const double half = std::numbers::pi / (omega * root);  // half a damped period
  if (kind == ShaperKind::zvd) {
    const double n = (1.0 + K) * (1.0 + K);
    return {{0.0, 1.0 / n}, {half, 2.0 * K / n}, {2.0 * half, K * K / n}};
  }
  return {{0.0, 1.0 / (1.0 + K)}, {half, K / (1.0 + K)}};
}

Signal shaped_signal(const Signal& s, const std::vector<ShaperImpulse>& impulses) {
  if (!piecewise_linear(s))
    throw std::invalid_argument("only a piecewise-linear reference (constant, step, ramp, table, pulse, a sum of "
                                "those) can be shaped");
  if (s.breakpoint_count(kLow, kHigh) * static_cast<double>(impulses.size()) > kMaxShapedBreakpoints)
    throw std::invalid_argument("the reference has too many breakpoints to be shaped (an unending pulse, or shapers "
                                "nested in shapers?)");
  const std::vector<double> own = s.breakpoints(kLow, kHigh);
  auto total = [&](double t) {
    double v = 0.0;
    for (const auto& p : impulses) v += p.amplitude * s.value(t - p.time);
    return v;
  };
  if (own.empty()) return Signal::constant(total(0.0));
  // Every copy's breakpoints (b_j + t_i, copy i, own index j), in time order. A copy is evaluated
  // at its own b_j where it has the breakpoint (b_j + t_i − t_i need not give b_j back), elsewhere at
  // T − t_i, where it is continuous.
  struct Corner {
    double at;
    std::size_t copy, own;
  };
  std::vector<Corner> corners;
  for (std::size_t i = 0; i < impulses.size(); ++i)
    for (std::size_t j = 0; j < own.size(); ++j) corners.push_back({own[j] + impulses[i].time, i, j});
  std::sort(corners.begin(), corners.end(), [](const Corner& x, const Corner& y) { return x.at < y.at; });
  const double first = corners.front().at, last = corners.back().at;
  // Points one time unit outside the breakpoints carry the end segments (held or extrapolated).
  std::vector<double> x{first - 1.0}, y{total(first - 1.0)};
  std::vector<char> here(impulses.size());
  for (std::size_t k = 0; k < corners.size();) {
    const double T = corners[k].at;
    std::fill(here.begin(), here.end(), 0);
    double l = 0.0, r = 0.0;
    for (; k < corners.size() && corners[k].at == T; ++k) {
      const Corner& c = corners[k];
      const double b = own[c.own], prev = c.own == 0 ? kLow : own[c.own - 1];
      l += impulses[c.copy].amplitude * left_limit(s, b, prev);
      r += impulses[c.copy].amplitude * s.value(b);
      here[c.copy] = 1;
    }
    for (std::size_t i = 0; i < impulses.size(); ++i)
      if (!here[i]) {
        const double v = impulses[i].amplitude * s.value(T - impulses[i].time);
        l += v, r += v;
      }
    if (l != r) x.push_back(T), y.push_back(l);
    x.push_back(T), y.push_back(r);
  }
  x.push_back(last + 1.0), y.push_back(total(last + 1.0));
  const bool slopes = s.slope(own.front() - 1.0) != 0.0 || s.slope(own.back() + 1.0) != 0.0;
  return Signal::table(std::move(x), std::move(y), slopes);
}

Signal two_step_signal(const Signal& ramp, double omega) {
  check_shaper(omega, 0.0);
  if (ramp.kind() != Signal::Kind::ramp)
    throw std::invalid_argument("the two-step acceleration shapes a ramp (a speed reference from one speed to another)");
  const std::vector<double> b = ramp.breakpoints(kLow, kHigh);
  const double t0 = b.front(), t1 = b.back();
  const double before = ramp.value(t0), after = ramp.value(t1), mid = 0.5 * (before + after);
  const double half = 0.5 * (t1 - t0), coast = std::numbers::pi / omega;
  if (half > coast)
    throw std::invalid_argument(fmt::format("the ramp's first half ({:.6g} s at its acceleration) lasts beyond half the "
                                            "period ({:.6g} s): no coasting is left; shape it with zv, or accelerate "
                                            "faster", half, coast));
  return Signal::sum({Signal::ramp(before, mid, t0, t0 + half), Signal::ramp(0.0, after - mid, t0 + coast, t0 + coast + half)});
}

}  // namespace machdyn
