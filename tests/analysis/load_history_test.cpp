// Rainflow counts of a link load over the turning points located on the continuous solution
// (analysis/load_history.hpp) against the counts over a very finely sampled output of the same run
// (an independent reading of the same load: interpolated rows, no located extremes), on both
// integrators; and a coarse output that misses ranges.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "machdyn/analysis/load_history.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// Three masses, a plain spring-damper A–B and a spring with a 1 mm gap B–C; B starts at 0.5 m/s.
// The loads carry both modes (ω ≈ 70–170 rad/s) and the gap opens and closes (events, a load that
// rests at 0 while open): ranges of many sizes over 0.4 s.
const char* kModel = R"(
bodies:
  A: {type: translational, mass: 1 kg}
  B: {type: translational, mass: 1.5 kg, velocity: 0.5 m/s}
  C: {type: translational, mass: 2 kg}
links:
  ab: {type: spring-damper, between: [A, B], stiffness: 1e4 N/m, damping: 2 N*s/m}
  bc: {type: spring, between: [B, C], stiffness: 2e4 N/m, gap: 1 mm}
simulation: {t_end: 0.4 s, dt_out: 0.01 s, rtol: 1e-10, atol: 1e-12}
)";

class LoadHistory : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, LoadHistory, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

const std::vector<double>& column(const SimulationResult& r, const std::string& link) {
  for (size_t c = 0; c < r.column_names.size(); ++c)
    if (r.column_names[c].rfind(link + ".load", 0) == 0) return r.columns[c];
  throw std::runtime_error("no load column of " + link);
}

std::vector<double> ranges(const std::vector<RainflowCycle>& cs) {
  std::vector<double> r;
  for (const auto& c : cs) r.push_back(c.range());
  std::sort(r.begin(), r.end());
  return r;
}

double damage_sum(const std::vector<RainflowCycle>& cs) {  // Σ n Δ³: what a fatigue check reads
  double s = 0;
  for (const auto& c : cs) s += c.count * c.range() * c.range() * c.range();
  return s;
}

// Claim: the located turning points give the counts of the finely sampled output (dt_out = 2 µs, far
// below the steps; both through the same gate of 10⁻⁶ of the load's range) — the same number of
// cycles, each range equal to within the sampling error
// F ω² Δt²/8 ≈ 1e-6 of the largest range — while an output every 10 ms loses peaks between its rows:
// its largest range and its Σ n Δ³ fall short.
TEST_P(LoadHistory, LocatedTurningPointsCountLikeAFineOutput) {
  Model m = test::model_text(kModel, "history.yaml");
  m.simulation.integrator = GetParam();
  SimulateOptions opt;
  opt.record_series = false;
  // The gate h = 10⁻⁶ (max − min) of each load (from a plain run's extremes): at an event the gap
  // link's load is its law at the located instant, ±1e-10 N or so off its flank, and such reversals
  // of the order of the event tolerance are not load cycles.
  const SimulationResult plain = simulate(m, opt);
  LinkCycleOptions count;
  for (size_t l = 0; l < 2; ++l) count.gates.push_back(1e-6 * (plain.links[l].max - plain.links[l].min));
  SimulationResult run;
  const auto located = count_link_cycles(m, opt, count, &run);
  ASSERT_EQ(located.size(), 2u);
  // The run itself is unchanged by the hook: its peaks are those of a plain run.
  for (size_t l = 0; l < 2; ++l) {
    EXPECT_EQ(run.links[l].max, plain.links[l].max);
    EXPECT_EQ(run.links[l].min, plain.links[l].min);
  }
  Model fine_m = m;
  fine_m.simulation.dt_out = 2e-6;
  const SimulationResult fine = simulate(fine_m);
  Model coarse_m = m;
  coarse_m.simulation.dt_out = 0.01;
  const SimulationResult coarse = simulate(coarse_m);
  for (size_t l = 0; l < 2; ++l) {
    const std::string& name = located[l].link;
    const auto exact = ranges(located[l].cycles);
    std::vector<RainflowCycle> sampled_cycles;
    RainflowCounter counter([&](const RainflowCycle& c) { sampled_cycles.push_back(c); }, count.gates[l]);
    for (const double v : column(fine, name)) counter.add(v);
    counter.finish();
    const auto sampled = ranges(sampled_cycles);
    ASSERT_GT(exact.size(), 10u) << name;
    const double scale = exact.back();
    ASSERT_EQ(exact.size(), sampled.size()) << name;
    for (size_t k = 0; k < exact.size(); ++k) EXPECT_NEAR(exact[k], sampled[k], 1e-6 * scale) << name << " " << k;
    // The largest range is max − min of the run (the peak tracker's extremes).
    EXPECT_NEAR(scale, run.links[l].max - run.links[l].min, 1e-12 * scale) << name;
    EXPECT_LE(located[l].max_held, 64u);
    const auto rough = rainflow(column(coarse, name));
    EXPECT_LT(ranges(rough).back(), scale * (1 - 1e-3)) << name;
    EXPECT_LT(damage_sum(rough), 0.99 * damage_sum(located[l].cycles)) << name;
  }
}

/// (range, count) of the cycles of range above `floor`, by range.
std::vector<std::pair<double, double>> above(const std::vector<RainflowCycle>& cs, double floor) {
  std::vector<std::pair<double, double>> r;
  for (const auto& c : cs)
    if (c.range() > floor) r.emplace_back(c.range(), c.count);
  std::sort(r.begin(), r.end());
  return r;
}

// Claim: a duty of two operations — the run over [0, T] and the run over [T, 2T] started from the
// first one's end state (the model is autonomous, so the second is the continuation) — merged from
// the runs' parts (merge_parts, ASTM halves for the residue) counts what the one run over [0, 2T]
// counts: the residue rule across operations. Range for range within 10⁻⁶ of the largest; reversals
// below 10⁻⁶ of it (event noise, the junction's restart) are left out on both sides.
TEST_P(LoadHistory, TwoOperationsMergeLikeOneRun) {
  Model m = test::model_text(kModel, "history.yaml");
  m.simulation.integrator = GetParam();
  const double T = 0.2;
  Model first = m, second = m, whole = m;
  first.simulation.t_end = second.simulation.t_end = T;
  whole.simulation.t_end = 2 * T;
  SimulationResult r1;
  const auto p1 = link_parts(first, {}, {}, &r1);
  ASSERT_NEAR(r1.columns[0].back(), T, 1e-12);
  for (size_t i = 0; i < second.bodies.size(); ++i) {  // columns t, then position and velocity per body
    second.bodies[i].q0 = r1.columns[1 + 2 * i].back();
    second.bodies[i].v0 = r1.columns[2 + 2 * i].back();
  }
  const auto p2 = link_parts(second, {}, {});
  const auto one = count_link_cycles(whole, {}, {});
  // Each operation counted alone, its residue as halves: not the whole run's count (the residue rule
  // across operations is what makes them agree).
  const auto alone1 = count_link_cycles(first, {}, {}), alone2 = count_link_cycles(second, {}, {});
  for (size_t l = 0; l < 2; ++l) {
    const std::vector<RainflowPart> parts = {p1[l], p2[l]};
    const auto merged_cycles = merge_parts(parts, std::vector<double>{1, 1});
    double scale = 0;
    for (const auto& c : one[l].cycles) scale = std::max(scale, c.range());
    const auto merged = above(merged_cycles, 1e-6 * scale), direct = above(one[l].cycles, 1e-6 * scale);
    ASSERT_GT(direct.size(), 10u);
    auto both = alone1[l].cycles;
    both.insert(both.end(), alone2[l].cycles.begin(), alone2[l].cycles.end());
    EXPECT_NE(above(both, 1e-6 * scale), direct) << one[l].link;
    ASSERT_EQ(merged.size(), direct.size()) << one[l].link;
    for (size_t k = 0; k < direct.size(); ++k) {
      EXPECT_NEAR(merged[k].first, direct[k].first, 1e-6 * scale) << one[l].link << " " << k;
      EXPECT_EQ(merged[k].second, direct[k].second) << one[l].link << " " << k;
    }
  }
}

TEST(LoadHistoryInput, BadLinkOrGatesThrow) {
  const Model m = test::model_text(kModel, "history.yaml");
  LinkCycleOptions no_link, wrong_gates, negative_gate;
  no_link.links = {2};
  wrong_gates.links = {0, 1}, wrong_gates.gates = {1, 2, 3};
  negative_gate.links = {0}, negative_gate.gates = {-1};
  EXPECT_THROW(count_link_cycles(m, {}, no_link), std::invalid_argument);
  EXPECT_THROW(count_link_cycles(m, {}, wrong_gates), std::invalid_argument);
  EXPECT_THROW(count_link_cycles(m, {}, negative_gate), std::invalid_argument);
}

}  // namespace
}  // namespace machdyn
