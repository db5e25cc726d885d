// Sample specs and the three designs (grid, random, Latin hypercube): sizes, order, spacing,
// reproducibility from the seed, stratification.
#include <algorithm>
#include <cmath>
#include <gtest/gtest.h>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/sweep/sampling.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// Claim: our xoshiro256** seeded through splitmix64 gives the reference sequence. The numbers come
// from an independent Python transcription of the published algorithms (Vigna's splitmix64.c and
// xoshiro256starstar.c) with seed 42, so a table's random points are the same on every platform.
TEST(Sampling, XoshiroMatchesTheReferenceSequence) {
  Xoshiro256 rng(42);
  EXPECT_EQ(rng.next(), 0x15780b2e0c2ec716ULL);
  EXPECT_EQ(rng.next(), 0x6104d9866d113a7eULL);
  EXPECT_EQ(rng.next(), 0xae17533239e499a1ULL);
}

// Claim: below(n) returns every value in [0, n) and nothing outside; uniform() lies in [0, 1).
TEST(Sampling, BoundedDrawsStayInRange) {
  Xoshiro256 rng(7);
  std::vector<int> seen(5, 0);
  for (int i = 0; i < 1000; ++i) {
    const auto k = rng.below(5);
    ASSERT_LT(k, 5u);
    ++seen[k];
    const double u = rng.uniform();
    ASSERT_GE(u, 0.0);
    ASSERT_LT(u, 1.0);
  }
  for (int c : seen) EXPECT_GT(c, 150);  // 200 expected each
}

// Claim: a:b:n gives n evenly spaced values with exact end points.
TEST(Sampling, LinearSpecGivesEvenlySpacedValuesWithExactEnds) {
  const auto s = parse_sample_spec("0:1:5", "--vary x");
  const auto v = grid_values(s);
  ASSERT_EQ(v.size(), 5u);
  const double expected[] = {0.0, 0.25, 0.5, 0.75, 1.0};
  for (int k = 0; k < 5; ++k) EXPECT_EQ(v[k].si, expected[k]);
  EXPECT_EQ(v[4].text, "1");
  const auto one = grid_values(parse_sample_spec("3:7:1", "--vary x"));
  ASSERT_EQ(one.size(), 1u);
  EXPECT_EQ(one[0].si, 3.0);
}

// Claim: a:b:n:log gives a geometric sequence — a constant ratio (b/a)^(1/(n−1)) between
// neighbours — with exact end points; 1e3:1e5:3:log is 1e3, 1e4, 1e5.
TEST(Sampling, LogSpecGivesGeometricSpacing) {
  const auto v = grid_values(parse_sample_spec("1e3:1e5:3:log", "--vary x"));
  ASSERT_EQ(v.size(), 3u);
  EXPECT_EQ(v[0].si, 1e3);
  EXPECT_NEAR(v[1].si, 1e4, 1e4 * 1e-14);
  EXPECT_EQ(v[2].si, 1e5);
  const auto w = grid_values(parse_sample_spec("2:2000:7:log", "--vary x"));
  const double ratio = std::pow(1000.0, 1.0 / 6.0);
  for (size_t k = 1; k < w.size(); ++k) EXPECT_NEAR(w[k].si / w[k - 1].si, ratio, 1e-12);
  // Negative ranges work the same way.
  const auto n = grid_values(parse_sample_spec("-1:-100:3:log", "--vary x"));
  EXPECT_NEAR(n[1].si, -10.0, 1e-13);
}

// Claim: values carry units and are converted to SI; the text applied to the field is the SI
// number for ranges and what the user wrote for lists.
TEST(Sampling, UnitsAreConvertedToSi) {
  const auto v = grid_values(parse_sample_spec("2 mm:8 mm:4", "--vary x"));
  ASSERT_EQ(v.size(), 4u);
  EXPECT_DOUBLE_EQ(v[0].si, 0.002);
  EXPECT_DOUBLE_EQ(v[3].si, 0.008);
  EXPECT_EQ(v[0].text, "0.002");
  const auto l = grid_values(parse_sample_spec("1.2 kN*m, 1500 N*m", "--vary x"));
  ASSERT_EQ(l.size(), 2u);
  EXPECT_DOUBLE_EQ(l[0].si, 1200.0);
  EXPECT_EQ(l[0].text, "1.2 kN*m");
  EXPECT_DOUBLE_EQ(l[1].si, 1500.0);
  // A word is kept as text (the compiler checks it), its SI value is NaN.
  const auto w = grid_values(parse_sample_spec("dopri5,bdf", "--vary x"));
  EXPECT_EQ(w[1].text, "bdf");
  EXPECT_TRUE(std::isnan(w[1].si));
}

// Claim: bad specs are input errors located at the --vary they came from.
TEST(Sampling, BadSpecsAreInputErrors) {
  for (const char* bad : {"1:2:0", "1:2:x", "1:2:3:4", "0:1:3:log", "-1:1:3:log", "1 mm:2 s:3", "1 mm,2 s", "1,,2",
                          "a:b:3"}) {
    try {
      (void)parse_sample_spec(bad, "--vary c1.stiffness");
      ADD_FAILURE() << "accepted '" << bad << "'";
    } catch (const InputError& e) {
      EXPECT_EQ(e.diagnostics().at(0).where.file, "--vary c1.stiffness") << bad;
    }
  }
}

// Claim: the grid is the full factorial in row-major order — the first axis slowest, the last
// fastest — with n1·n2·n3 points, each combination exactly once.
TEST(Sampling, GridOrderIsRowMajorLastAxisFastest) {
  const auto g = grid_indices({2, 3});
  ASSERT_EQ(g.size(), 6u);
  const std::vector<std::vector<int>> expected{{0, 0}, {0, 1}, {0, 2}, {1, 0}, {1, 1}, {1, 2}};
  EXPECT_EQ(g, expected);
  const auto h = grid_indices({3, 1, 4});
  EXPECT_EQ(h.size(), 12u);
  auto sorted = h;
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
  EXPECT_EQ(h[5], (std::vector<int>{1, 0, 1}));  // 5 = 1·4 + 0·4 + 1
}

// Claim: a Latin hypercube of N points hits each of the N strata of every dimension exactly once.
TEST(Sampling, LatinHypercubeIsStratified) {
  for (int n : {1, 7, 50, 1000}) {
    const auto p = latin_hypercube_unit(n, 3, 12345);
    ASSERT_EQ(p.size(), static_cast<size_t>(n));
    for (int d = 0; d < 3; ++d) {
      std::vector<int> hits(n, 0);
      for (const auto& x : p) {
        ASSERT_GE(x[d], 0.0);
        ASSERT_LT(x[d], 1.0);
        ++hits[static_cast<int>(std::floor(x[d] * n))];
      }
      for (int k = 0; k < n; ++k) EXPECT_EQ(hits[k], 1) << "N=" << n << " dim " << d << " stratum " << k;
    }
  }
}

// Claim: LHS and random designs are pure functions of the seed: the same seed gives the same
// points bit for bit, another seed other points.
TEST(Sampling, SeededDesignsReproduce) {
  EXPECT_EQ(latin_hypercube_unit(20, 2, 99), latin_hypercube_unit(20, 2, 99));
  EXPECT_NE(latin_hypercube_unit(20, 2, 99), latin_hypercube_unit(20, 2, 100));
  EXPECT_EQ(random_unit(20, 2, 99), random_unit(20, 2, 99));
  EXPECT_NE(random_unit(20, 2, 99), random_unit(20, 2, 100));
  // The random design is documented as consecutive uniform() draws, point by point.
  Xoshiro256 rng(5);
  const auto r = random_unit(3, 2, 5);
  for (const auto& p : r)
    for (double u : p) EXPECT_EQ(u, rng.uniform());
}

// Claim: value_at maps the unit interval onto the range (log: geometrically) and onto list items
// in equal parts.
TEST(Sampling, UnitCoordinatesMapOntoRangesAndLists) {
  const auto lin = parse_sample_spec("10:20", "--vary x");
  EXPECT_DOUBLE_EQ(value_at(lin, 0.25).si, 12.5);
  const auto lg = parse_sample_spec("1:100:log", "--vary x");
  EXPECT_NEAR(value_at(lg, 0.5).si, 10.0, 1e-13);
  const auto list = parse_sample_spec("a,b,c", "--vary x");
  EXPECT_EQ(value_at(list, 0.0).text, "a");
  EXPECT_EQ(value_at(list, 0.34).text, "b");
  EXPECT_EQ(value_at(list, 0.999).text, "c");
}

}  // namespace
}  // namespace machdyn
