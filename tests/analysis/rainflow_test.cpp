// Rainflow counting (analysis/rainflow.hpp) against independent answers: the published counts of
// ASTM E1049's worked example, closed forms (a sine, two commensurate cosines), and a second,
// deliberately different algorithm written here (the four-point method on a whole list, residue as
// halves) on random sequences, count for count.
#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <random>
#include <stdexcept>
#include <tuple>
#include <vector>

#include <gtest/gtest.h>

#include "machdyn/analysis/rainflow.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using Cycle = std::tuple<double, double, double>;  // (from, to, count)

std::vector<Cycle> sorted(const std::vector<RainflowCycle>& cs) {
  std::vector<Cycle> out;
  for (const auto& c : cs) out.emplace_back(c.from, c.to, c.count);
  std::sort(out.begin(), out.end());
  return out;
}

/// Total count of cycles whose range is within tol of r.
double count_of_range(const std::vector<RainflowCycle>& cs, double r, double tol = 1e-9) {
  double n = 0;
  for (const auto& c : cs)
    if (std::abs(c.range() - r) <= tol) n += c.count;
  return n;
}

double total(const std::vector<RainflowCycle>& cs) {
  double n = 0;
  for (const auto& c : cs) n += c.count;
  return n;
}

/// Total count per class (range, mean): what a range–mean matrix holds.
std::map<std::pair<double, double>, double> by_class(const std::vector<RainflowCycle>& cs) {
  std::map<std::pair<double, double>, double> m;
  for (const auto& c : cs) m[{c.range(), c.mean()}] += c.count;
  return m;
}

// ---- The second algorithm: the four-point method on a whole list -------------------------------
// Turning points by deleting every interior point that is not a strict reversal (plateaus merged),
// then repeated scans of the whole list: the first four consecutive points whose inner range is ≤
// both outer ranges give a cycle (inner pair removed) and the scan restarts; what is left at the end
// is the residue, each of its ranges half a cycle. (McInnes & Meehan 2008 show the four-point and
// the ASTM three-point method count alike.)
std::vector<double> reversals(const std::vector<double>& x) {
  std::vector<double> p;
  for (const double v : x) {
    if (!p.empty() && v == p.back()) continue;  // plateau
    if (p.size() >= 2 && (p[p.size() - 1] - p[p.size() - 2]) * (v - p.back()) > 0) p.back() = v;  // same direction
    else p.push_back(v);
  }
  return p;
}

std::vector<RainflowCycle> four_point(const std::vector<double>& x, bool residue_as_halves, std::vector<double>* residue = nullptr) {
  std::vector<double> p = reversals(x);
  std::vector<RainflowCycle> out;
  bool found = true;
  while (found) {
    found = false;
    for (size_t i = 0; i + 3 < p.size(); ++i) {
      const double inner = std::abs(p[i + 2] - p[i + 1]);
      if (inner <= std::abs(p[i + 1] - p[i]) && inner <= std::abs(p[i + 3] - p[i + 2])) {
        out.push_back({p[i + 1], p[i + 2], 1.0});
        p.erase(p.begin() + static_cast<long>(i) + 1, p.begin() + static_cast<long>(i) + 3);
        found = true;
        break;
      }
    }
  }
  if (residue_as_halves)
    for (size_t i = 0; i + 1 < p.size(); ++i) out.push_back({p[i], p[i + 1], 0.5});
  if (residue) *residue = p;
  return out;
}

// ---- ASTM E1049-85 (2017), Fig. 6 / Table 4 -----------------------------------------------------
TEST(Rainflow, AstmWorkedExampleCountsExactly) {
  // The standard's history A…I and its published rainflow counts (Table 4): range 3: 0.5,
  // 4: 1.5, 6: 0.5, 8: 1.0, 9: 0.5, none of 5, 7, 10.
  const std::vector<double> h = {-2, 1, -3, 5, -1, 3, -4, 4, -2};
  const auto cs = rainflow(h);
  EXPECT_DOUBLE_EQ(count_of_range(cs, 3), 0.5);
  EXPECT_DOUBLE_EQ(count_of_range(cs, 4), 1.5);
  EXPECT_DOUBLE_EQ(count_of_range(cs, 6), 0.5);
  EXPECT_DOUBLE_EQ(count_of_range(cs, 8), 1.0);
  EXPECT_DOUBLE_EQ(count_of_range(cs, 9), 0.5);
  EXPECT_DOUBLE_EQ(count_of_range(cs, 5) + count_of_range(cs, 7) + count_of_range(cs, 10), 0.0);
  EXPECT_DOUBLE_EQ(total(cs), 4.0);
  // The events of the standard's Fig. 6, in its order (a–g): A-B, B-C half; E-F whole; C-D half;
  // then the residue D-G, G-H, H-I halves.
  const std::vector<Cycle> expected = {{-2, 1, 0.5}, {1, -3, 0.5}, {-1, 3, 1.0}, {-3, 5, 0.5},
                                       {5, -4, 0.5}, {-4, 4, 0.5}, {4, -2, 0.5}};
  ASSERT_EQ(cs.size(), expected.size());
  for (size_t k = 0; k < cs.size(); ++k) {
    EXPECT_EQ(cs[k].from, std::get<0>(expected[k])) << k;
    EXPECT_EQ(cs[k].to, std::get<1>(expected[k])) << k;
    EXPECT_EQ(cs[k].count, std::get<2>(expected[k])) << k;
  }
  // The same by the four-point method (the second algorithm), cycle for cycle.
  EXPECT_EQ(sorted(cs), sorted(four_point(h, true)));
}

TEST(Rainflow, AstmExampleClosedByRepetition) {
  // Repeating the history: ASTM 5.4.5 (a repeating history counted from its largest peak, D = 5:
  // 5, −1, 3, −4, 4, −2, 1, −3, 5, whole cycles only) gives, by hand, E-F (−1→3, range 4), then
  // −2→1 (3), 4→−3 (7) and 5→−4 (9): four whole cycles. The library gets there streaming (the
  // residue −2, 1, −3, 5, −4, 4, −2 counted twice in a row); the four-point method of three periods
  // minus two periods (the first period's transient and the last residue cancel) says the same.
  const std::vector<double> h = {-2, 1, -3, 5, -1, 3, -4, 4, -2};
  const auto cs = rainflow(h, {.gate_fraction = 0.0, .residue = RainflowResidue::repeat});
  for (const auto& c : cs) EXPECT_EQ(c.count, 1.0);
  std::vector<std::pair<double, double>> by_hand = {{3, -0.5}, {4, 1}, {7, 0.5}, {9, 0.5}};
  std::vector<double> h2, h3;
  for (int k = 0; k < 3; ++k) {
    if (k < 2) h2.insert(h2.end(), h.begin(), h.end());
    h3.insert(h3.end(), h.begin(), h.end());
  }
  auto ranges = [](const std::vector<RainflowCycle>& v) {
    std::vector<std::pair<double, double>> r;
    for (const auto& c : v) r.emplace_back(c.range(), c.mean());
    std::sort(r.begin(), r.end());
    return r;
  };
  auto r3 = ranges(four_point(h3, false)), r2 = ranges(four_point(h2, false));
  std::vector<std::pair<double, double>> diff;
  std::set_difference(r3.begin(), r3.end(), r2.begin(), r2.end(), std::back_inserter(diff));
  EXPECT_EQ(ranges(cs), by_hand);
  EXPECT_EQ(ranges(cs), diff);
}

// ---- Closed forms -------------------------------------------------------------------------------
class RainflowSine : public ::testing::TestWithParam<int> {};

TEST_P(RainflowSine, NPeriodsAreNCyclesOfTwiceTheAmplitude) {
  // x = A sin(2π t/T) over N periods from t = 0: turning points 0, A, −A, A, …, −A, 0.
  // Repetition: the residue after the first pass is 0, A, −A, 0 (every later peak pair is a cycle,
  // N − 1 of them); R·R = 0, A, −A, A, −A, 0 adds one more: N cycles of range 2A, nothing else.
  // ASTM halves: the same N − 1 whole cycles (as halves: 2N − 1 halves of 2A, since each equal range
  // holds the moving starting point), and the two quarter-waves 0→A and −A→0 as halves of range A.
  const int N = GetParam();
  const double A = 3.5;
  const int per = 400;  // samples per period: the peaks fall on samples
  std::vector<double> x;
  // The phase reduced to one period: every period has the same bits (0, ±A exactly at the quarters).
  for (int i = 0; i <= N * per; ++i) x.push_back(A * std::sin(2 * std::numbers::pi * (i % per) / per));
  const auto rep = rainflow(x, {.gate_fraction = 0.0, .residue = RainflowResidue::repeat});
  EXPECT_NEAR(count_of_range(rep, 2 * A, 1e-9), N, 0.0);
  EXPECT_DOUBLE_EQ(total(rep), N);
  const auto half = rainflow(x);
  EXPECT_DOUBLE_EQ(count_of_range(half, 2 * A, 1e-9), N - 0.5);
  EXPECT_DOUBLE_EQ(count_of_range(half, A, 1e-9), 1.0);
  EXPECT_DOUBLE_EQ(total(half), N + 0.5);
  // Starting at a peak (a cosine), both rules give N cycles of 2A.
  std::vector<double> c;
  for (int i = 0; i <= N * per; ++i) c.push_back(A * std::cos(2 * std::numbers::pi * (i % per) / per));
  EXPECT_DOUBLE_EQ(count_of_range(rainflow(c), 2 * A, 1e-9), N);
  EXPECT_DOUBLE_EQ(total(rainflow(c)), N);
  EXPECT_DOUBLE_EQ(count_of_range(rainflow(c, {.gate_fraction = 0.0, .residue = RainflowResidue::repeat}), 2 * A, 1e-9), N);
}

INSTANTIATE_TEST_SUITE_P(Periods, RainflowSine, ::testing::Values(1, 2, 7, 50));

TEST(Rainflow, TwoCommensurateCosines) {
  // x(θ) = cos θ + a cos 2θ, a = 1/2. x′ = −sin θ (1 + 4a cos θ): extremes at θ = 0 (x = 1 + a = 3/2,
  // the maximum), at cos θ₁ = −1/(4a) (x = −a − 1/(8a) = −3/4, the minimum, twice per period) and at
  // θ = π (x = a − 1 = −1/2, a local maximum between the two minima). Per period: one cycle of the
  // full range 9/4 and one small cycle of range (4a − 1)²/(8a) = 1/4 (mean −5/8). Over N periods
  // from θ = 0: N of each, by either residue rule (the history starts and ends at the maximum).
  const double a = 0.5;
  const int N = 5, per = 100000;
  std::vector<double> x;
  for (int i = 0; i <= N * per; ++i) {
    const double th = 2 * std::numbers::pi * (i % per) / per;
    x.push_back(std::cos(th) + a * std::cos(2 * th));
  }
  const double big = 1 + 2 * a + 1 / (8 * a), small = (4 * a - 1) * (4 * a - 1) / (8 * a);
  ASSERT_DOUBLE_EQ(big, 2.25);
  ASSERT_DOUBLE_EQ(small, 0.25);
  for (const auto residue : {RainflowResidue::half_cycles, RainflowResidue::repeat}) {
    const auto cs = rainflow(x, {.gate_fraction = 0.0, .residue = residue});
    EXPECT_NEAR(count_of_range(cs, big, 1e-8), N, 0.0);
    EXPECT_NEAR(count_of_range(cs, small, 1e-8), N, 0.0);
    EXPECT_DOUBLE_EQ(total(cs), 2 * N);
    for (const auto& c : cs)
      if (std::abs(c.range() - small) < 1e-8) {
        EXPECT_NEAR(c.mean(), -0.625, 1e-8);
      }
    // A gate above the small range (h = 0.2 · 9/4 = 0.45 > 1/4) removes the small cycles before
    // counting and leaves the big ones; one below it (0.1 · 9/4 = 0.225) keeps both.
    const auto gated = rainflow(x, {.gate_fraction = 0.2, .residue = residue});
    EXPECT_NEAR(count_of_range(gated, big, 1e-8), N, 0.0);
    EXPECT_DOUBLE_EQ(total(gated), N);
    EXPECT_DOUBLE_EQ(total(rainflow(x, {.gate_fraction = 0.1, .residue = residue})), 2 * N);
  }
}

// ---- Random sequences against the four-point method ---------------------------------------------
TEST(Rainflow, RandomSequencesMatchTheFourPointMethod) {
  std::mt19937 rng(20261127);
  for (int trial = 0; trial < 400; ++trial) {
    const int n = 1 + static_cast<int>(rng() % 200);
    std::vector<double> x;
    // Half the trials on a few integer levels: ties (equal ranges, plateaus) on purpose.
    if (trial % 2 == 0) {
      std::uniform_int_distribution<int> d(-4, 4);
      for (int i = 0; i < n; ++i) x.push_back(d(rng));
    } else {
      std::normal_distribution<double> d(0.0, 1.0);
      double s = 0;
      for (int i = 0; i < n; ++i) x.push_back(s += d(rng));  // a random walk: a long residue
    }
    const auto ours = rainflow(x);
    if (trial % 2 == 1) {
      // Distinct values: the same cycles, half for half, whole for whole.
      ASSERT_EQ(sorted(ours), sorted(four_point(x, true))) << "trial " << trial;
    } else {
      // Ties: ASTM's X ≥ Y takes a run of equal ranges at the starting point as halves where the
      // four-point rule takes pairs of them as whole cycles (4, −4, 4, −4: three halves against one
      // cycle and a half); the counts per (from, to) range agree, direction aside.
      ASSERT_EQ(by_class(ours), by_class(four_point(x, true))) << "trial " << trial;
    }
    // The largest range counted is max − min.
    if (!ours.empty()) {
      const auto [lo, hi] = std::minmax_element(x.begin(), x.end());
      double rmax = 0;
      for (const auto& c : ours) rmax = std::max(rmax, c.range());
      EXPECT_EQ(rmax, *hi - *lo);
    }
  }
}

TEST(Rainflow, RepetitionMatchesThreePeriodsMinusTwo) {
  // Closing the residue by repetition = one period of the repeated history, counted by the
  // four-point method as (three periods) − (two periods), for random histories.
  std::mt19937 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 2 + static_cast<int>(rng() % 60);
    std::vector<double> h;
    std::uniform_int_distribution<int> d(-6, 6);
    for (int i = 0; i < n; ++i) h.push_back(trial % 2 ? d(rng) : d(rng) + 0.01 * i);
    std::vector<double> h2, h3;
    for (int k = 0; k < 3; ++k) {
      if (k < 2) h2.insert(h2.end(), h.begin(), h.end());
      h3.insert(h3.end(), h.begin(), h.end());
    }
    auto ranges = [](const std::vector<RainflowCycle>& v) {
      std::vector<std::pair<double, double>> r;
      for (const auto& c : v) r.emplace_back(c.range(), c.mean());
      std::sort(r.begin(), r.end());
      return r;
    };
    const auto r3 = ranges(four_point(h3, false)), r2 = ranges(four_point(h2, false));
    std::vector<std::pair<double, double>> diff;
    std::set_difference(r3.begin(), r3.end(), r2.begin(), r2.end(), std::back_inserter(diff));
    ASSERT_EQ(ranges(rainflow(h, {.gate_fraction = 0.0, .residue = RainflowResidue::repeat})), diff) << trial;
  }
}

// ---- The gate -----------------------------------------------------------------------------------
TEST(Rainflow, GateDropsSmallReversalsBeforeCounting) {
  // Every range counted with a gate h exceeds h; with the gate the count equals the ungated count of
  // the gated turning points (the filter acts before counting, by definition), here built by hand:
  // 0, 5, 4.5, 6, −3, −2.8, 2 with h = 1 has turning points 0, 6, −3, 2.
  const std::vector<double> x = {0, 5, 4.5, 6, -3, -2.8, 2};
  std::vector<RainflowCycle> cs;
  RainflowCounter k([&](const RainflowCycle& c) { cs.push_back(c); }, 1.0);
  for (const double v : x) k.add(v);
  k.finish();
  EXPECT_EQ(sorted(cs), sorted(rainflow(std::vector<double>{0, 6, -3, 2})));
  std::mt19937 rng(3);
  std::normal_distribution<double> d(0.0, 1.0);
  std::vector<double> w;
  double s = 0;
  for (int i = 0; i < 5000; ++i) w.push_back(s += d(rng));
  const auto all = rainflow(w);
  const auto gated = rainflow(w, {.gate_fraction = 0.05});
  const auto [lo, hi] = std::minmax_element(w.begin(), w.end());
  for (const auto& c : gated) EXPECT_GT(c.range(), 0.05 * (*hi - *lo));
  EXPECT_LT(total(gated), total(all));
}

// ---- Streaming memory ---------------------------------------------------------------------------
TEST(Rainflow, MemoryIsTheResidueNotTheLength) {
  // A stationary history (iid uniform samples) of 10^6 points: the residue stays tiny (it is a
  // diverging-then-converging sequence inside the history's range), while the turning points are
  // ~2/3 of the samples.
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> d(-1.0, 1.0);
  double counted = 0;
  RainflowCounter k([&](const RainflowCycle& c) { counted += c.count; });
  const int n = 1'000'000;
  for (int i = 0; i < n; ++i) k.add(d(rng));
  EXPECT_GT(k.turning_points(), static_cast<size_t>(n / 2));
  EXPECT_LT(k.max_held(), 100u);
  k.finish();
  // Every turning point but the first closes one half cycle: 2·(cycles) = turning points − 1.
  EXPECT_DOUBLE_EQ(2 * counted, static_cast<double>(k.turning_points() - 1));
}

// ---- Matrices -----------------------------------------------------------------------------------
TEST(Rainflow, MatricesBinByTheStatedRule) {
  const std::vector<double> h = {-2, 1, -3, 5, -1, 3, -4, 4, -2};
  const auto cs = rainflow(h);
  // From–to over [−4, 5], 9 bins of width 1: value v in bin floor(v + 4), 5 in the last (8).
  const auto ft = from_to_matrix(cs, 9);
  EXPECT_DOUBLE_EQ(ft.total(), 4.0);
  EXPECT_DOUBLE_EQ(ft.at(2, 5), 0.5);  // −2 → 1
  EXPECT_DOUBLE_EQ(ft.at(3, 7), 1.0);  // −1 → 3 whole
  EXPECT_DOUBLE_EQ(ft.at(8, 0), 0.5);  // 5 → −4 (5 = hi in the last bin)
  EXPECT_DOUBLE_EQ(ft.at(0, 8), 0.5);  // −4 → 4 (4 in bin 8 too)
  // Range–mean: ranges over [0, 9] in 3 bins of 3, means over [−0.5, 1] (−4→4 and −3→5 and …).
  const auto rm = range_mean_matrix(cs, 3, 3);
  EXPECT_DOUBLE_EQ(rm.row_hi, 9.0);
  EXPECT_DOUBLE_EQ(rm.total(), 4.0);
  double row0 = 0, row1 = 0, row2 = 0;  // ranges [0,3): none; [3,6): 3, 4, 4 → 2; [6,9]: 6, 8, 8, 9 → 2
  for (int j = 0; j < 3; ++j) row0 += rm.at(0, j), row1 += rm.at(1, j), row2 += rm.at(2, j);
  EXPECT_DOUBLE_EQ(row0, 0.0);
  EXPECT_DOUBLE_EQ(row1, 2.0);
  EXPECT_DOUBLE_EQ(row2, 2.0);
}

TEST(Rainflow, BadInputThrows) {
  EXPECT_THROW(rainflow(std::vector<double>{1, NAN, 2}), std::invalid_argument);
  EXPECT_THROW(rainflow(std::vector<double>{1, INFINITY}), std::invalid_argument);
  EXPECT_THROW(rainflow(std::vector<double>{1, 2}, {.gate_fraction = 1.0}), std::invalid_argument);
  EXPECT_THROW(rainflow(std::vector<double>{1, 2}, {.gate_fraction = -0.1}), std::invalid_argument);
  EXPECT_THROW(RainflowCounter([](const RainflowCycle&) {}, -1.0), std::invalid_argument);
  EXPECT_TRUE(rainflow(std::vector<double>{}).empty());
  EXPECT_TRUE(rainflow(std::vector<double>{2, 2, 2}).empty());
}

}  // namespace
}  // namespace machdyn

namespace machdyn {
namespace MACHDYN_UNITY_ID {

std::map<std::pair<double, double>, double> classes(const std::vector<RainflowCycle>& cs) {
  std::map<std::pair<double, double>, double> m;
  for (const auto& c : cs) m[{c.range(), c.mean()}] += c.count;
  return m;
}

// ---- Parts of a history (operations of a duty) ------------------------------------------------
// Claim: part A repeated n_A times then part B n_B times, merged from the parts alone, counts what
// the whole history A^n_A · B^n_B counts, class for class (range, mean), under both residue rules —
// checked against the plain count of the concatenated history.
TEST(Rainflow, MergedPartsCountLikeTheWholeHistory) {
  std::mt19937 rng(30);
  const double reps[] = {0, 1, 2, 3, 5};
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<double> a, b;
    std::uniform_int_distribution<int> d(-7, 7);
    const int na = 1 + static_cast<int>(rng() % 15), nb = 1 + static_cast<int>(rng() % 15);
    for (int i = 0; i < na; ++i) a.push_back(trial % 2 ? d(rng) : d(rng) + 0.013 * i);
    for (int i = 0; i < nb; ++i) b.push_back(trial % 2 ? d(rng) : d(rng) - 0.007 * i);
    const double ra = reps[rng() % 5], rb = reps[1 + rng() % 4];
    std::vector<double> whole;
    for (int k = 0; k < ra; ++k) whole.insert(whole.end(), a.begin(), a.end());
    for (int k = 0; k < rb; ++k) whole.insert(whole.end(), b.begin(), b.end());
    const std::vector<RainflowPart> parts = {rainflow_part(a), rainflow_part(b)};
    const std::vector<double> n = {ra, rb};
    for (const auto residue : {RainflowResidue::half_cycles, RainflowResidue::repeat}) {
      const auto merged = classes(merge_parts(parts, n, residue));
      const auto direct = classes(rainflow(whole, {.gate_fraction = 0.0, .residue = residue}));
      ASSERT_EQ(merged.size(), direct.size()) << trial;
      for (const auto& [k, v] : direct) {
        ASSERT_TRUE(merged.count(k)) << trial;
        EXPECT_DOUBLE_EQ(merged.at(k), v) << trial << " n " << ra << " " << rb << " rule " << int(residue);
      }
    }
  }
  const std::vector<RainflowPart> one = {rainflow_part(std::vector<double>{0, 1})};
  EXPECT_THROW(merge_parts(one, std::vector<double>{1.5}), std::invalid_argument);
  EXPECT_THROW(merge_parts(one, std::vector<double>{-1}), std::invalid_argument);
  EXPECT_THROW(merge_parts(one, std::vector<double>{1, 1}), std::invalid_argument);
}

// Claim: flush() between two parts changes nothing when the history goes on — also when it goes on
// in the same direction past the flushed turning point (which then was none).
TEST(Rainflow, FlushThenContinueIsTheSameHistory) {
  const std::vector<std::vector<double>> cases = {{0, 5, 2, 7}, {0, 5, 2, 4}, {0, -3, 1, -6}, {1, 2, 3, 4}};
  for (const auto& x : cases)
    for (const auto residue : {RainflowResidue::half_cycles, RainflowResidue::repeat}) {
      std::vector<RainflowCycle> cs;
      RainflowCounter k([&](const RainflowCycle& c) { cs.push_back(c); }, 0.0, residue);
      k.add(x[0]), k.add(x[1]), k.add(x[2]);
      k.flush();
      k.add(x[3]);
      k.finish();
      EXPECT_EQ(sorted(cs), sorted(rainflow(x, {.gate_fraction = 0.0, .residue = residue}))) << x[3];
    }
}

// Claim: keeping only the turning points of a history (append_turning_point, gate 0) loses nothing a
// gated count sees: over random walks with plateaus and random gates, the part (whole cycles and
// residue) and the ASTM count with halves of the kept points equal those of all the samples, cycle
// for cycle — the duty counts a run's kept points once its range, and so the gate, is known.
TEST(Rainflow, KeptTurningPointsCountLikeAllTheSamples) {
  std::mt19937 rng(30);
  std::uniform_real_distribution<double> step(-1.0, 1.0);
  std::uniform_int_distribution<int> flat(0, 5);
  for (int trial = 0; trial < 300; ++trial) {
    std::vector<double> samples{0.0}, kept;
    for (int k = 0; k < 400; ++k) {
      const double x = flat(rng) == 0 ? samples.back() : std::round((samples.back() + step(rng)) * 8.0) / 8.0;
      samples.push_back(x);
    }
    for (const double x : samples) append_turning_point(kept, x);
    ASSERT_LT(kept.size(), samples.size());
    EXPECT_EQ(kept.front(), samples.front());
    EXPECT_EQ(kept.back(), samples.back());
    const double gate = trial % 3 == 0 ? 0.0 : 0.1 * (trial % 17);
    const RainflowPart a = rainflow_part(samples, gate), b = rainflow_part(kept, gate);
    EXPECT_EQ(sorted(a.cycles), sorted(b.cycles)) << "trial " << trial;
    EXPECT_EQ(a.residue, b.residue) << "trial " << trial;
    RainflowOptions o;
    o.gate_fraction = gate / 20.0;
    EXPECT_EQ(sorted(rainflow(samples, o)), sorted(rainflow(kept, o))) << "trial " << trial;
  }
}

}  // namespace
}  // namespace machdyn
