#include "machdyn/analysis/duty_classes.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>
#include <string>

namespace machdyn {
namespace {

// ISO 4301-1 / FEM 1.001: the upper limits of the classes (docs/duty.md, "The standards' tables").
constexpr std::array<double, 4> kSpectrumLimits = {0.125, 0.25, 0.5, 1.0};
constexpr std::array<double, 9> kUtilizationHours = {200, 400, 800, 1600, 3200, 6300, 12500, 25000, 50000};
// EN 13001-1: the upper limits of s of S0…S9 (docs/duty.md: one public source, verify).
constexpr std::array<double, 10> kStressHistoryLimits = {0.008, 0.016, 0.032, 0.063, 0.125, 0.25, 0.5, 1.0, 2.0, 4.0};

}  // namespace

double load_spectrum_factor(std::span<const LoadLevel> levels, double p_max) {
  double total = 0.0, peak = 0.0;
  for (const LoadLevel& l : levels) {
    if (!(l.time >= 0.0) || !std::isfinite(l.time) || !std::isfinite(l.load))
      throw std::invalid_argument("load spectrum: a level's time must be finite and >= 0 and its load finite");
    total += l.time;
    peak = std::max(peak, std::abs(l.load));
  }
  const double p = p_max > 0.0 ? p_max : peak;
  if (!(total > 0.0)) throw std::invalid_argument("load spectrum: no running time");
  if (!(p > 0.0)) throw std::invalid_argument("load spectrum: no load");
  double k = 0.0;
  for (const LoadLevel& l : levels) {
    const double r = std::abs(l.load) / p;
    k += l.time / total * r * r * r;
  }
  return k;
}

void CubicLoadIntegral::add(double t, double load) {
  const double a = std::abs(load), cube = a * a * a;
  if (started_) {
    const double dt = t - t_;
    if (dt > 0.0) integral_ += 0.5 * (cube_ + cube) * dt, duration_ += dt;
  }
  started_ = true, t_ = t, cube_ = cube;
  peak_ = std::max(peak_, a);
}

int spectrum_class(double k_m) {
  for (int i = 0; i < 3; ++i)
    if (k_m <= kSpectrumLimits[static_cast<std::size_t>(i)]) return i + 1;
  return 4;
}

int utilization_class(double hours) {
  for (int i = 0; i < 9; ++i)
    if (hours <= kUtilizationHours[static_cast<std::size_t>(i)]) return i;
  return 9;
}

int mechanism_group(int spectrum_class, int utilization_class) {
  if (spectrum_class < 1 || spectrum_class > 4 || utilization_class < 0 || utilization_class > 9)
    throw std::invalid_argument("mechanism group: L" + std::to_string(spectrum_class) + ", T" +
                                std::to_string(utilization_class) + " is not a class");
  return std::clamp(utilization_class + spectrum_class - 2, 1, 8);
}

int stress_history_class(double s) {
  for (int i = 0; i < 10; ++i)
    if (s <= kStressHistoryLimits[static_cast<std::size_t>(i)]) return i;
  return 10;
}

std::string stress_history_class_name(int stress_history_class) {
  if (stress_history_class < 0 || stress_history_class > 10) throw std::invalid_argument("stress history class: S0..S9");
  static constexpr std::array<const char*, 11> kNames = {"S0", "S1", "S2", "S3", "S4", "S5",
                                                         "S6", "S7", "S8", "S9", ">S9"};
  return kNames[static_cast<std::size_t>(stress_history_class)];
}

double stress_history_class_limit(int stress_history_class) {
  if (stress_history_class < 0 || stress_history_class > 9) throw std::invalid_argument("stress history class: S0..S9");
  return kStressHistoryLimits[static_cast<std::size_t>(stress_history_class)];
}

double spectrum_class_limit(int spectrum_class) {
  if (spectrum_class < 1 || spectrum_class > 4) throw std::invalid_argument("spectrum class: L1..L4");
  return kSpectrumLimits[static_cast<std::size_t>(spectrum_class - 1)];
}

double utilization_class_limit_hours(int utilization_class) {
  if (utilization_class < 0 || utilization_class > 8) throw std::invalid_argument("class of utilization: T0..T8 have a limit");
  return kUtilizationHours[static_cast<std::size_t>(utilization_class)];
}

}  // namespace machdyn
