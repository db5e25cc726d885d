// The mechanism classes of ISO 4301-1 / FEM 1.001 and EN 13001's S-classes
// (analysis/duty_classes.hpp) against independent answers: a spectrum worked by hand (and published
// as a worked example), the class tables written out cell by cell as the public sources print them
// (docs/duty.md), and a closed-form integral.
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "machdyn/analysis/duty_classes.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// Claim: k_m = Σ (t_i/T)(P_i/P_max)³. By hand: 100 % of the load for 10 % of the time, 40 % for 30 %,
// 20 % for 60 %: 0.1·1 + 0.3·0.064 + 0.6·0.008 = 0.1 + 0.0192 + 0.0048 = 0.124 (the worked example of
// a hoist manufacturer's manual, docs/duty.md, prints 0.124) — L1, just under its limit 0.125.
TEST(DutyClasses, LoadSpectrumFactorOfAHandSpectrum) {
  const std::vector<LoadLevel> levels = {{10.0, 320e3}, {30.0, 128e3}, {60.0, 64e3}};
  EXPECT_NEAR(load_spectrum_factor(levels), 0.124, 1e-15);
  EXPECT_EQ(spectrum_class(load_spectrum_factor(levels)), 1);
  // A rated load above the largest level scales every ratio: P_max = 400 kN gives 0.124 · 0.8³.
  EXPECT_NEAR(load_spectrum_factor(levels, 400e3), 0.124 * 0.512, 1e-15);
  // Times in any unit (only t_i/T counts): hours instead of seconds, the same k_m.
  const std::vector<LoadLevel> hours = {{0.1, 320e3}, {0.3, 128e3}, {0.6, 64e3}};
  EXPECT_NEAR(load_spectrum_factor(hours), 0.124, 1e-15);
  // Constant full load: k_m = 1, L4.
  EXPECT_DOUBLE_EQ(load_spectrum_factor(std::vector<LoadLevel>{{5.0, -2.0}}), 1.0);
  EXPECT_THROW(load_spectrum_factor(std::vector<LoadLevel>{{0.0, 1.0}}), std::invalid_argument);
  EXPECT_THROW(load_spectrum_factor(std::vector<LoadLevel>{{1.0, 0.0}}), std::invalid_argument);
  EXPECT_THROW(load_spectrum_factor(std::vector<LoadLevel>{{-1.0, 1.0}, {2.0, 1.0}}), std::invalid_argument);
}

// Claim: the class limits are those of the tables (upper limits, "≤"): L by k_m 0.125, 0.25, 0.5, 1;
// T by the running hours 200, 400, 800, 1600, 3200, 6300, 12500, 25000, 50000 (T9 above).
TEST(DutyClasses, ClassBoundariesOfTheTables) {
  const double km_limits[] = {0.125, 0.25, 0.5, 1.0};
  for (int L = 1; L <= 4; ++L) {
    const double lim = km_limits[L - 1];
    EXPECT_EQ(spectrum_class(lim), L) << lim;
    EXPECT_EQ(spectrum_class(std::nextafter(lim, 0.0)), L) << lim;
    if (L < 4) {
      EXPECT_EQ(spectrum_class(std::nextafter(lim, 2.0)), L + 1) << lim;
    }
    EXPECT_EQ(spectrum_class_limit(L), lim);
  }
  EXPECT_EQ(spectrum_class(0.0), 1);
  EXPECT_EQ(spectrum_class(1.3), 4);  // loads above the rated one
  const double hours[] = {200, 400, 800, 1600, 3200, 6300, 12500, 25000, 50000};
  for (int T = 0; T <= 8; ++T) {
    EXPECT_EQ(utilization_class(hours[T]), T) << hours[T];
    EXPECT_EQ(utilization_class(hours[T] + 1.0), T + 1) << hours[T];
    EXPECT_EQ(utilization_class_limit_hours(T), hours[T]);
  }
  EXPECT_EQ(utilization_class(0.0), 0);
  EXPECT_EQ(utilization_class(1e6), 9);
  EXPECT_THROW(spectrum_class_limit(5), std::invalid_argument);
  EXPECT_THROW(utilization_class_limit_hours(9), std::invalid_argument);
}

// Claim: EN 13001-1's S-classes of the stress history parameter s have the upper limits 4 · 2^(S−9)
// (S9: 4, halving per class down to S0), printed rounded to two digits (0.063, 0.032, 0.016, 0.008):
// every boundary belongs to the lower class, the next double above it to the next class; above
// S9's 4 no class of the table (">S9").
TEST(DutyClasses, StressHistoryClassBoundaries) {
  const double limits[] = {0.008, 0.016, 0.032, 0.063, 0.125, 0.25, 0.5, 1.0, 2.0, 4.0};
  for (int S = 0; S <= 9; ++S) {
    const double lim = limits[S];
    // The table's doubling, as printed: 4 · 2^(S−9) rounded (0.0078125 → 0.008: 2.4 %).
    EXPECT_NEAR(lim, 4.0 * std::pow(2.0, S - 9), 0.025 * lim) << S;
    EXPECT_EQ(stress_history_class(lim), S) << lim;
    EXPECT_EQ(stress_history_class(std::nextafter(lim, 0.0)), S) << lim;
    EXPECT_EQ(stress_history_class(std::nextafter(lim, 10.0)), S + 1) << lim;
    if (S > 0) {
      EXPECT_EQ(stress_history_class(std::nextafter(limits[S - 1], 10.0)), S) << lim;
    }
    EXPECT_EQ(stress_history_class_limit(S), lim);
    std::string name = "S";
    name += std::to_string(S);
    EXPECT_EQ(stress_history_class_name(S), name);
  }
  EXPECT_EQ(stress_history_class(0.0), 0);
  EXPECT_EQ(stress_history_class(100.0), 10);
  EXPECT_EQ(stress_history_class_name(10), ">S9");
  EXPECT_THROW(stress_history_class_limit(10), std::invalid_argument);
  EXPECT_THROW(stress_history_class_name(11), std::invalid_argument);
}

// Claim: the mechanism group is the table of ISO 4301-1 / FEM 1.001 — written out here cell by cell
// as the sources print it (0: a blank cell of the table), compared with the formula M = T + L − 2
// of the code; the blanks are M1 below the table's first group and M8 beyond its last.
TEST(DutyClasses, MechanismGroupTableCellByCell) {
  //                         T0 T1 T2 T3 T4 T5 T6 T7 T8 T9
  const int table[4][10] = {{0, 0, 1, 2, 3, 4, 5, 6, 7, 8},   // L1
                            {0, 1, 2, 3, 4, 5, 6, 7, 8, 0},   // L2
                            {1, 2, 3, 4, 5, 6, 7, 8, 0, 0},   // L3
                            {2, 3, 4, 5, 6, 7, 8, 0, 0, 0}};  // L4
  for (int L = 1; L <= 4; ++L)
    for (int T = 0; T <= 9; ++T) {
      const int cell = table[L - 1][T];
      const int expected = cell != 0 ? cell : (T < 3 ? 1 : 8);
      EXPECT_EQ(mechanism_group(L, T), expected) << "L" << L << " T" << T;
    }
  EXPECT_THROW(mechanism_group(0, 3), std::invalid_argument);
  EXPECT_THROW(mechanism_group(2, 10), std::invalid_argument);
}

// Claim: the continuous k_m over a sampled history. A load stepping between levels (a jump is two
// samples at one instant) gives the discrete k_m exactly; P = A sin(ω t) over whole periods gives
// the mean of |sin|³ = 4/(3π) (∫_0^π sin³ = 4/3 over a half period π), to the trapezoid's O(Δt²).
TEST(DutyClasses, CubicIntegralOfAHistory) {
  CubicLoadIntegral steps;
  steps.add(0.0, 320e3), steps.add(10.0, 320e3), steps.add(10.0, 128e3), steps.add(40.0, 128e3);
  steps.add(40.0, -64e3), steps.add(100.0, -64e3);
  EXPECT_DOUBLE_EQ(steps.duration(), 100.0);
  EXPECT_DOUBLE_EQ(steps.peak(), 320e3);
  EXPECT_NEAR(steps.integral() / (std::pow(steps.peak(), 3) * steps.duration()), 0.124, 1e-15);

  CubicLoadIntegral sine;
  const double A = 5.0, w = 2.0 * std::numbers::pi / 0.4;
  const int n = 20000;  // 3 periods of 0.4 s
  for (int k = 0; k <= n; ++k) {
    const double t = 1.2 * k / n;
    sine.add(t, A * std::sin(w * t));
  }
  const double km = sine.integral() / (std::pow(sine.peak(), 3) * sine.duration());
  EXPECT_NEAR(km, 4.0 / (3.0 * std::numbers::pi), 1e-5);  // the sampled peak and the trapezoid: ~1e-6
  EXPECT_EQ(spectrum_class(km), 3);  // 0.424: L3
}

}  // namespace
}  // namespace machdyn
