// Fatigue figures of counted cycles (analysis/fatigue.hpp) on a spectrum built by hand, against its
// hand-computed damage, equivalent range and EN 13001 stress history parameter, and against the
// identities that tie them together.
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "machdyn/analysis/fatigue.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// The spectrum: 10 cycles of range 100, 1000 of range 50 (mean 0), half a cycle of 80.
std::vector<RainflowCycle> spectrum() {
  std::vector<RainflowCycle> cs;
  for (int i = 0; i < 10; ++i) cs.push_back({0, 100, 1.0});
  for (int i = 0; i < 1000; ++i) cs.push_back({-25, 25, 1.0});
  cs.push_back({0, 80, 0.5});
  return cs;
}

// Claim: with N(Δ) = 1e5 (100/Δ)³, N(100) = 1e5, N(50) = 8e5, N(80) = 1e5 · 1.25³ = 195312.5, so
// D = 10/1e5 + 1000/8e5 + 0.5/195312.5 = 1e-4 + 1.25e-3 + 2.56e-6 = 1.35256e-3; repeated 700 times, 700 D.
TEST(Fatigue, MinerDamageOfAHandSpectrum) {
  const SNCurve c{.m = 3, .delta_ref = 100, .n_ref = 1e5, .n_knee = 0};
  const auto cs = spectrum();
  EXPECT_NEAR(miner_damage(cs, c), 1.35256e-3, 1e-15);
  EXPECT_NEAR(miner_damage(cs, c, 700.0), 700 * 1.35256e-3, 1e-12);
}

// Claim: a knee at N_knee = 2e5 lies at Δ_knee = 100 · (1e5/2e5)^(1/3) = 79.37; 80 stays on the first
// slope, 50 falls below: no damage with an endurance limit (D = 1e-4 + 2.56e-6), and with m₂ = 5
// N(50) = 2e5 (Δ_knee/50)⁵ = 2e5 · 2⁵ · 2^(−5/3). The curve is continuous at the knee.
TEST(Fatigue, KneeAndSecondSlope) {
  SNCurve c{.m = 3, .delta_ref = 100, .n_ref = 1e5, .n_knee = 2e5};
  EXPECT_NEAR(c.knee_range(), 100 * std::cbrt(0.5), 1e-12);
  EXPECT_NEAR(miner_damage(spectrum(), c), 1e-4 + 2.56e-6, 1e-15);
  c.m2 = 5;
  const double n50 = 2e5 * 32 * std::pow(2.0, -5.0 / 3.0);
  EXPECT_NEAR(c.cycles_to_failure(50), n50, 1e-9 * n50);
  EXPECT_NEAR(miner_damage(spectrum(), c), 1e-4 + 2.56e-6 + 1000 / n50, 1e-15);
  const double k = c.knee_range();
  EXPECT_NEAR(c.cycles_to_failure(k * (1 + 1e-12)), 2e5, 1e-6);
  EXPECT_NEAR(c.cycles_to_failure(k * (1 - 1e-12)), 2e5, 1e-6);
}

// Claim: Σ n Δ³ = 10·100³ + 1000·50³ + 0.5·80³ = 1.35256e8, so for N_eq = 1e6 Δ_eq = 135.256^(1/3);
// N_eq cycles of Δ_eq do the spectrum's damage (one slope): the same D by the second path.
TEST(Fatigue, EquivalentRangeDoesTheSameDamage) {
  const auto cs = spectrum();
  const double d_eq = equivalent_range(cs, 3, 1e6);
  EXPECT_NEAR(d_eq, std::cbrt(135.256), 1e-12);
  const SNCurve c{.m = 3, .delta_ref = 100, .n_ref = 1e5, .n_knee = 0};
  const std::vector<RainflowCycle> constant(1, RainflowCycle{0, d_eq, 1e6});
  EXPECT_NEAR(miner_damage(constant, c), miner_damage(cs, c), 1e-15);
}

// Claim: N_t = 1010.5, Δ̂ = 100, k = (10 + 1000 · 0.5³ + 0.5 · 0.8³)/N_t = 135.256/1010.5,
// ν = N_t/2e6, s = 135.256/2e6; a constant range for N_ref cycles has k = 1, ν = 1, s = 1.
TEST(Fatigue, En13001StressHistoryParameter) {
  const StressHistory h = stress_history(spectrum(), 3);
  EXPECT_DOUBLE_EQ(h.total_cycles, 1010.5);
  EXPECT_DOUBLE_EQ(h.largest, 100);
  EXPECT_NEAR(h.k, 135.256 / 1010.5, 1e-15);
  EXPECT_NEAR(h.nu, 1010.5 / 2e6, 1e-18);
  EXPECT_NEAR(h.s, 135.256 / 2e6, 1e-15);
  const std::vector<RainflowCycle> constant(1, RainflowCycle{-3, 4, 1.0});
  const StressHistory one = stress_history(constant, 5, 2e6, 2e6);
  EXPECT_DOUBLE_EQ(one.k, 1.0);
  EXPECT_DOUBLE_EQ(one.s, 1.0);
  EXPECT_EQ(stress_history({}, 3).s, 0.0);
}

TEST(Fatigue, BadCurvesThrow) {
  const auto cs = spectrum();
  EXPECT_THROW(miner_damage(cs, SNCurve{.m = 0, .delta_ref = 100, .n_ref = 1e5}), std::invalid_argument);  // no slope
  EXPECT_THROW(miner_damage(cs, SNCurve{.m = 3, .delta_ref = 0, .n_ref = 1e5}), std::invalid_argument);
  EXPECT_THROW(miner_damage(cs, SNCurve{.m = 3, .delta_ref = 100, .n_ref = -1}), std::invalid_argument);
  EXPECT_THROW(miner_damage(cs, SNCurve{.m = 3, .delta_ref = 100, .n_ref = 1e5, .n_knee = 1e6, .m2 = 0}),
               std::invalid_argument);
  EXPECT_THROW(miner_damage(cs, SNCurve{.m = 3, .delta_ref = 100, .n_ref = 1e5}, -1), std::invalid_argument);
  EXPECT_THROW(equivalent_range(cs, 3, 0), std::invalid_argument);
  EXPECT_THROW(stress_history(cs, NAN), std::invalid_argument);
}

}  // namespace
}  // namespace machdyn
