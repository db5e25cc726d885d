// run_duty (io/duty.hpp) beyond the counts: k_m and the classes of a duty against a closed form,
// operations given per hour over a design life, the result of a parallel run equal to a serial one
// bit for bit, and the figures' data holding the counted cycles (io/duty_figures.hpp).
#include <cmath>
#include <numbers>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "machdyn/analysis/duty_classes.hpp"
#include "machdyn/io/duty.hpp"
#include "machdyn/io/duty_figures.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// One undamped oscillator: m = 1 kg on a spring of 100 N/m, ω = 10 rad/s, started at x = 0 with the
// velocity v0: the spring's load is P(t) = ±k (v0/ω) sin(ω t), amplitude 10 v0 N. t_end = 2 periods
// (4π/10 s).
const char* kOscillator = R"(
bodies:
  A: {type: translational, mass: 1 kg, velocity: 1 m/s}
links:
  s: {type: spring, between: [A, ground], stiffness: 100 N/m}
simulation: {t_end: 1.2566370614359172 s, dt_out: 0.01 s, rtol: 1e-11, atol: 1e-13}
cases:
  full: {bodies: {A: {velocity: 1 m/s}}}
  half: {bodies: {A: {velocity: 0.5 m/s}}}
)";

constexpr double kT = 1.2566370614359172;  // each operation's running time, s

// Claim: k_m = Σ n_i ∫|P|³dt / (P_max³ Σ n_i T_i). Over whole periods ∫|A sin|³ dt = (4/(3π)) A³ T
// (∫_0^π sin³ = 4/3), so with n = 3 runs of amplitude 10 N and 5 of 5 N (equal T):
// k_m = (4/(3π)) (3·1 + 5·(1/2)³)/8 = 0.42441·0.453125 = 0.19231 → L2; the running time 8 T is far
// below 200 h → T0, M = max(1, 0 + 2 − 2) = M1. With a rated load of 20 N every ratio halves:
// k_m/8 = 0.024039 → L1. The trapezoid over the solver's steps is O(Δt²): within 2e-3.
TEST(DutyRun, LoadSpectrumFactorOfTwoOscillations) {
  const std::string model = test::write_temp("duty-osc.yaml", kOscillator);
  const std::string duty = test::write_temp("duty-osc.duty.yaml", R"(
operations:
  big: {case: full, repeat: 3}
  small: {case: half, repeat: 5}
)");
  const DutyResult r = run_duty(model, duty, {});
  ASSERT_EQ(r.links.size(), 1u);
  const DutyLink& l = r.links[0];
  const double km = 4.0 / (3.0 * std::numbers::pi) * (3.0 + 5.0 / 8.0) / 8.0;
  EXPECT_NEAR(l.k_m, km, 2e-3 * km);
  EXPECT_NEAR(l.p_max, 10.0, 1e-8);
  EXPECT_FALSE(l.rated);
  EXPECT_EQ(l.spectrum_class, 2);
  ASSERT_EQ(r.op_seconds.size(), 2u);
  EXPECT_NEAR(r.op_seconds[0], kT, 1e-12);
  EXPECT_NEAR(r.running_hours, 8.0 * kT / 3600.0, 1e-12);
  EXPECT_EQ(r.utilization_class, 0);
  EXPECT_EQ(l.group, 1);

  const std::string rated = test::write_temp("duty-osc-rated.duty.yaml", R"(
operations:
  big: {case: full, repeat: 3}
  small: {case: half, repeat: 5}
rated: {s: 20}
)");
  const DutyResult q = run_duty(model, rated, {});
  EXPECT_TRUE(q.links[0].rated);
  EXPECT_EQ(q.links[0].p_max, 20.0);
  EXPECT_NEAR(q.links[0].k_m, km / 8.0, 2e-3 * km / 8.0);
  EXPECT_EQ(q.links[0].spectrum_class, 1);
}

// Claim: operations per hour over a design life: n = per_hour × life. 3600/h and 7200/h over
// 10 000 h are 3.6e7 and 7.2e7 operations; running time (3.6e7 + 7.2e7) T = 1.357e8 s = 37 699 h
// → T8 (25 000 < h ≤ 50 000); k_m = (4/(3π))(3.6e7 + 7.2e7/8)/1.08e8 = 0.42441·0.41667 = 0.17684 → L2;
// M = 8 + 2 − 2 = M8. The cycles scale with n: the largest range 2·10 N, and N_t = Σ n_i N_i.
TEST(DutyRun, OperationsPerHourOverTheDesignLife) {
  const std::string model = test::write_temp("duty-osc2.yaml", kOscillator);
  const std::string duty = test::write_temp("duty-osc-life.duty.yaml", R"(
design_life: 10000 h
operations:
  big: {case: full, per_hour: 3600}
  small: {case: half, per_hour: 7200}
)");
  const DutyResult r = run_duty(model, duty, {});
  ASSERT_EQ(r.spec.operations.size(), 2u);
  EXPECT_EQ(r.spec.operations[0].repeat, 3.6e7);
  EXPECT_EQ(r.spec.operations[1].repeat, 7.2e7);
  EXPECT_DOUBLE_EQ(r.spec.design_life_h, 10000.0);
  const double hours = 1.08e8 * kT / 3600.0;
  EXPECT_NEAR(r.running_hours, hours, 1e-9 * hours);
  EXPECT_EQ(r.utilization_class, 8);
  const double km = 4.0 / (3.0 * std::numbers::pi) * (3.6e7 + 7.2e7 / 8.0) / 1.08e8;
  EXPECT_NEAR(r.links[0].k_m, km, 2e-3 * km);
  EXPECT_EQ(r.links[0].spectrum_class, 2);
  EXPECT_EQ(r.links[0].group, 8);
  EXPECT_NEAR(r.links[0].history.largest, 20.0, 1e-7);
  // Each run of two periods is two whole cycles of 2A (0 → A → −A → A → −A → 0; the residue's
  // ranges close under repetition): N_t ≥ 2 (3.6e7 + 7.2e7), and the ranges of 2A = 20 N and 10 N
  // carry 2 n each.
  double n20 = 0.0, n10 = 0.0;
  for (const auto& c : r.links[0].cycles) {
    if (std::abs(c.range() - 20.0) < 1e-6) n20 += c.count;
    if (std::abs(c.range() - 10.0) < 1e-6) n10 += c.count;
  }
  EXPECT_NEAR(n20, 2 * 3.6e7, 2.0);
  EXPECT_NEAR(n10, 2 * 7.2e7, 2.0);
}

// Claim: the operations run on several threads give what one thread gives, bit for bit: every
// cycle (from, to, count) and every figure. Four operations on 1, 2 and 3 threads.
TEST(DutyRun, ParallelRunEqualsSerialRun) {
  const std::string model = test::write_temp("duty-osc3.yaml", kOscillator);
  const std::string duty = test::write_temp("duty-osc-par.duty.yaml", R"(
operations:
  a: {case: full, repeat: 3}
  b: {case: half, repeat: 5}
  c: {repeat: 2}
  d: {case: half, repeat: 1}
residue: repeat
)");
  const DutyResult serial = run_duty(model, duty, {}, 1);
  for (const int jobs : {2, 3}) {
    const DutyResult par = run_duty(model, duty, {}, jobs);
    ASSERT_EQ(par.links.size(), serial.links.size());
    const auto& a = serial.links[0].cycles;
    const auto& b = par.links[0].cycles;
    ASSERT_EQ(a.size(), b.size()) << jobs;
    for (std::size_t k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a[k].from, b[k].from) << jobs << " " << k;
      EXPECT_EQ(a[k].to, b[k].to) << jobs << " " << k;
      EXPECT_EQ(a[k].count, b[k].count) << jobs << " " << k;
    }
    EXPECT_EQ(par.links[0].k_m, serial.links[0].k_m);
    EXPECT_EQ(par.links[0].history.s, serial.links[0].history.s);
    EXPECT_EQ(par.op_seconds, serial.op_seconds);
    EXPECT_EQ(duty_json(par).dump(), duty_json(serial).dump());
  }
}

// Claim: the figures hold the counted cycles: the heat map's cells sum to N_t, the exceedance
// staircase ends at N_t and starts at the largest range, and the report section lists every link.
TEST(DutyRun, FigureDataHoldTheCycles) {
  const std::string model = test::write_temp("duty-osc4.yaml", kOscillator);
  const std::string duty = test::write_temp("duty-osc-fig.duty.yaml", R"(
operations:
  big: {case: full, repeat: 3}
  small: {case: half, repeat: 5}
)");
  const DutyResult r = run_duty(model, duty, {});
  const DutyLink& l = r.links[0];
  double cells = 0.0;
  std::istringstream in(duty_heat_map_data(l));
  double r0, r1, m0, m1, n;
  while (in >> r0 >> r1 >> m0 >> m1 >> n) cells += n;
  EXPECT_NEAR(cells, l.history.total_cycles, 1e-12 * l.history.total_cycles);
  const Exceedance e = exceedance(l.cycles);
  ASSERT_FALSE(e.range.empty());
  EXPECT_EQ(e.range.front(), l.history.largest);
  EXPECT_NEAR(e.cycles.back(), l.history.total_cycles, 1e-12 * l.history.total_cycles);
  for (std::size_t k = 1; k < e.range.size(); ++k) EXPECT_LT(e.range[k], e.range[k - 1]);
  const plot::Figure f = duty_exceedance_figure(l, 3.0);
  EXPECT_NO_THROW(plot::validate(f));
  // The L-class limits at Δ̂ k^(1/3): 0.5, 0.62996, 0.79370 of Δ̂ = 20 N.
  ASSERT_EQ(f.ref_lines.size(), 4u);
  EXPECT_NEAR(f.ref_lines[1].value, 10.0, 1e-9);
  EXPECT_NEAR(f.ref_lines[2].value, 20.0 * std::cbrt(0.25), 1e-9);
  EXPECT_NEAR(f.ref_lines[3].value, 20.0 * std::cbrt(0.5), 1e-9);
  const report::Section s = duty_report_section(r);
  ASSERT_EQ(s.tables.size(), 2u);
  EXPECT_EQ(s.tables[1].rows.size(), 1u);
  EXPECT_EQ(s.figures.size(), 1u);
}

}  // namespace
}  // namespace machdyn
