#include "machdyn/analysis/crane_standard.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <fmt/format.h>

namespace machdyn::crane {
namespace {

int index_of(HoistingClass hc) {
  const int k = static_cast<int>(hc);
  if (k < 1 || k > 4) throw std::invalid_argument(fmt::format("hoisting class {} is not one of HC1 … HC4", k));
  return k - 1;
}
int index_of(HoistDriveClass hd) {
  const int k = static_cast<int>(hd);
  if (k < 1 || k > 5) throw std::invalid_argument(fmt::format("hoist drive class {} is not one of HD1 … HD5", k));
  return k - 1;
}
void check_nonnegative(double x, const char* what) {
  if (!(x >= 0.0) || !std::isfinite(x))
    throw std::invalid_argument(fmt::format("{} must be a finite value ≥ 0, got {}", what, x));
}

// EN 13001-2, φ2 table (crane-standards.md): β2 and φ2,min for HD1, HD2, HD4, by HC1 … HC4.
constexpr double kBeta2[4] = {0.17, 0.34, 0.51, 0.68};
constexpr double kPhi2Min[4] = {1.05, 1.10, 1.15, 1.20};
constexpr double kPhi2MinStepless = 1.05;  // HD3 and HD5, every hoisting class

}  // namespace

std::string to_string(HoistingClass hc) { return fmt::format("HC{}", index_of(hc) + 1); }
std::string to_string(HoistDriveClass hd) { return fmt::format("HD{}", index_of(hd) + 1); }

HoistingClass parse_hoisting_class(const std::string& s) {
  for (int k = 1; k <= 4; ++k)
    if (s == fmt::format("HC{}", k)) return static_cast<HoistingClass>(k);
  throw std::invalid_argument(fmt::format("'{}' is not a hoisting class; expected HC1, HC2, HC3 or HC4", s));
}
HoistDriveClass parse_hoist_drive_class(const std::string& s) {
  for (int k = 1; k <= 5; ++k)
    if (s == fmt::format("HD{}", k)) return static_cast<HoistDriveClass>(k);
  throw std::invalid_argument(fmt::format("'{}' is not a hoist drive class; expected HD1 … HD5", s));
}

double beta2(HoistingClass hc) { return kBeta2[index_of(hc)]; }

double phi2_min(HoistingClass hc, HoistDriveClass hd) {
  const int c = index_of(hc), d = index_of(hd);
  return d == 2 || d == 4 ? kPhi2MinStepless : kPhi2Min[c];
}

double characteristic_hoisting_speed(HoistDriveClass hd, double vh_max, double vh_creep) {
  check_nonnegative(vh_max, "vh,max");
  switch (index_of(hd)) {
    case 0: return vh_max;                              // HD1: no creep speed
    case 1:                                             // HD2
    case 2: check_nonnegative(vh_creep, "vh,CS"); return vh_creep;  // HD3
    case 3: return 0.5 * vh_max;                        // HD4
    default: return 0.0;                                // HD5: stepless from zero
  }
}

double phi2(HoistingClass hc, HoistDriveClass hd, double vh) {
  check_nonnegative(vh, "vh");
  return phi2_min(hc, hd) + beta2(hc) * vh;
}

double beta3(ReleaseKind k) { return k == ReleaseKind::rapid ? 1.0 : 0.5; }

double phi3(double released_mass, double hoist_mass, ReleaseKind k) {
  check_nonnegative(released_mass, "the released mass Δm");
  if (!(hoist_mass > 0.0) || !std::isfinite(hoist_mass))
    throw std::invalid_argument(fmt::format("the hoist load's mass m must be > 0, got {}", hoist_mass));
  if (released_mass > hoist_mass)
    throw std::invalid_argument(fmt::format("the released mass Δm = {} exceeds the hoist load m = {}", released_mass,
                                            hoist_mass));
  return 1.0 - released_mass / hoist_mass * (1.0 + beta3(k));
}

Range phi5_range(DriveForceChange c) {
  switch (c) {
    case DriveForceChange::centrifugal: return {1.0, 1.0};
    case DriveForceChange::smooth: return {1.0, 1.5};
    case DriveForceChange::sudden: return {1.5, 2.0};
    case DriveForceChange::backlash: return {3.0, 3.0};
  }
  throw std::invalid_argument("unknown kind of drive force change");
}

std::string to_string(DriveForceChange c) {
  switch (c) {
    case DriveForceChange::centrifugal: return "centrifugal";
    case DriveForceChange::smooth: return "smooth";
    case DriveForceChange::sudden: return "sudden";
    case DriveForceChange::backlash: return "backlash";
  }
  throw std::invalid_argument("unknown kind of drive force change");
}

double phi6_dynamic(double phi2_value) { return 0.5 * (1.0 + phi2_value); }

double phi7(double xi_b) {
  if (!(xi_b >= 0.0 && xi_b <= 1.0))
    throw std::invalid_argument(fmt::format("the buffer's energy-absorption ratio ξb must lie in [0, 1], got {}", xi_b));
  return xi_b <= 0.5 ? 1.25 : 1.25 + 0.7 * (xi_b - 0.5);
}

double buffer_energy_ratio(const std::vector<double>& stroke, const std::vector<double>& force) {
  if (stroke.size() < 2 || stroke.size() != force.size())
    throw std::invalid_argument("a buffer characteristic needs two or more (stroke, force) points");
  if (stroke[0] != 0.0) throw std::invalid_argument(fmt::format("the buffer's stroke must start at 0, got {}", stroke[0]));
  double work = 0.0, F_max = 0.0;
  for (size_t k = 0; k < stroke.size(); ++k) {
    check_nonnegative(force[k], "a buffer force");
    F_max = std::max(F_max, force[k]);
    if (k == 0) continue;
    if (!(stroke[k] > stroke[k - 1]))
      throw std::invalid_argument(fmt::format("the buffer's strokes must increase, got {} after {}", stroke[k],
                                              stroke[k - 1]));
    work += 0.5 * (force[k] + force[k - 1]) * (stroke[k] - stroke[k - 1]);
  }
  if (F_max == 0.0) throw std::invalid_argument("the buffer characteristic carries no force");
  return work / (F_max * stroke.back());
}

double fem_psi(CraneType t, double vL) {
  check_nonnegative(vL, "the lifting speed vL");
  const double xi = t == CraneType::jib ? 0.3 : 0.6;
  return std::max(1.15, 1.0 + xi * std::min(vL, 1.0));
}

double din_psi(int hoisting_class, double v) {
  if (hoisting_class < 1 || hoisting_class > 4)
    throw std::invalid_argument(fmt::format("DIN 15018 hoisting class H{} is not one of H1 … H4", hoisting_class));
  check_nonnegative(v, "the hoisting speed v");
  const double k = 1.0 + 0.1 * hoisting_class, l = 0.0022 * hoisting_class;
  return k + l * (v * 60.0);  // v in m/min
}

}  // namespace machdyn::crane
