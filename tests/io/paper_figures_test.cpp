// The figures of papers 000, 001 and 004 and the mode shapes of a long chain: each figure carries the
// series and reference lines of the analysis it draws.
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/energy.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "support/travel_start.hpp"
#include "machdyn/io/figures.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/report.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

const plot::Series& series_named(const plot::Figure& f, const std::string& prefix) {
  for (const auto& s : f.series)
    if (s.name.rfind(prefix, 0) == 0) return s;
  throw std::runtime_error("figure " + f.id + " has no series " + prefix);
}

/// Linear interpolation of y(x) on ascending x.
double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  const auto it = std::upper_bound(x.begin(), x.end(), at);
  const auto k = static_cast<std::size_t>(std::clamp<long>(it - x.begin(), 1, static_cast<long>(x.size()) - 1));
  const double w = (at - x[k - 1]) / (x[k] - x[k - 1]);
  return y[k - 1] + w * (y[k] - y[k - 1]);
}

// Claim: the cyclogram of the travel start-up (paper 001) draws the link force c, the static
// adhesion limit F_sc = ΔG·μ_s = 50 kN · 0.18 = 9 kN (loads of 10 kN are drawn in kN) as its one
// reference line, one shaded band per
// slip phase of the adhesion (not of the resistance W, which slides all the time), and at every
// breakaway the link load, which for the first slip equals the closed form of stage 3,
// F_slip = [F_sc (mk + m2) − mk W]/m2 = 9225 N (analysis/travel_start.hpp).
TEST(PaperFigures, CyclogramMarksStaticAdhesionLimitSlipPhasesAndBreakaway) {
  const Model m = load_model(test::example("travel-start.yaml"));
  const SimulationResult r = simulate(m);
  const plot::Figure f = load_cyclogram_figure(m, r);
  EXPECT_EQ(f.id, "load_cyclogram");
  ASSERT_EQ(f.ref_lines.size(), 1u);
  EXPECT_EQ(f.y.label(), "link force F, kN");
  EXPECT_DOUBLE_EQ(f.ref_lines[0].value, 50e3 * 0.18 * 1e-3);
  EXPECT_EQ(f.ref_lines[0].label, "F_sc = 9 kN");
  long adhesion_phases = 0;
  for (const auto& p : r.hybrid.slip_phases) adhesion_phases += p.contact == "adhesion";
  EXPECT_EQ(static_cast<long>(f.bands.size()), adhesion_phases);
  EXPECT_GE(adhesion_phases, 20);
  EXPECT_EQ(f.bands_label, "adhesion slips");
  const auto& link = series_named(f, "c (m1–mk)");
  EXPECT_EQ(link.x.size(), r.columns[0].size());
  const auto& breakaway = series_named(f, "c at breakaway");
  ASSERT_EQ(static_cast<long>(breakaway.x.size()), adhesion_phases);
  paper001::TravelDrive d;
  d.m1 = 3000, d.mk = 300, d.m2 = 10000, d.c = 2.0e6, d.Delta = 4e-3, d.P = 6800, d.W = 1500, d.F_sc = 9000, d.F_d = 5500;
  const auto e = paper001::exact_stages(d);
  EXPECT_NEAR(breakaway.x[0], e.slip_time(), 1e-9);
  EXPECT_NEAR(breakaway.y[0] * 1e3, e.F_slip, 1e-6 * e.F_slip);
  for (std::size_t k = 0; k < f.bands.size(); ++k) EXPECT_DOUBLE_EQ(f.bands[k].x0, breakaway.x[k]);
}

// Claim: the contacts figure has force (left) and sliding velocity (right, dashed) of every contact.
TEST(PaperFigures, ContactsFigureHasForceAndSlidingVelocityOfEveryContact) {
  const Model m = load_model(test::example("travel-start.yaml"), {"simulation.t_end=0.3"});
  const SimulationResult r = simulate(m);
  const plot::Figure f = contacts_figure(m, r);
  ASSERT_EQ(f.series.size(), 4u);
  EXPECT_EQ(f.series[0].name, "adhesion: force");
  EXPECT_EQ(f.series[1].y_axis, 2);
  EXPECT_TRUE(f.series[1].dashed);
  EXPECT_EQ(f.y2.label(), "sliding velocity u, m/s");
  const auto figs = simulation_figures(m, r);
  ASSERT_EQ(figs.size(), 4u);
  EXPECT_EQ(figs[0].id, "load_cyclogram");
  EXPECT_EQ(figs[3].id, "contacts");
}

// Claim: a model with contacts on bodies of both kinds (a brake in N·m on the drive, wheel adhesion
// in N) draws every contact: one contacts figure per kind, each with force and sliding velocity of
// exactly the contacts of its kind.
TEST(PaperFigures, ContactsOfBothKindsAreAllDrawn) {
  const Model m = load_model(test::write_temp("mixed-contacts.yaml", R"(bodies:
  motor: {type: rotational, inertia: 0.5}
  cart: {type: translational, mass: 100}
links:
  rope: {type: spring, between: [motor, cart], ratio: 10, stiffness: 1e5}
loads:
  M: {type: constant, body: motor, value: 20}
contacts:
  rail: {between: [cart, ground], static: 300, kinetic: 250}
brakes:
  T: {body: motor, holding: 30, braking: 25, time: 0.05, ramp: 0.01}
simulation: {t_end: 0.1}
)"));
  const SimulationResult r = simulate(m);
  const auto figs = simulation_figures(m, r);
  std::vector<std::string> names;
  for (const auto& f : figs)
    if (f.id.rfind("contacts", 0) == 0)
      for (const auto& s : f.series) names.push_back(f.id + "/" + s.name);
  EXPECT_EQ(names, (std::vector<std::string>{"contacts/rail: force", "contacts/rail: sliding velocity",
                                             "contacts_torques/T: force", "contacts_torques/T: sliding velocity"}));
}

// Claim: simulate() with a progress callback on a hybrid model reports the mode events so far, and the last report (finished) counts every
// event of the result except the `initial` entries.
TEST(PaperFigures, HybridRunReportsProgressWithEvents) {
  const Model m = load_model(test::example("travel-start.yaml"), {"simulation.t_end=0.5"});
  std::vector<SimulationProgress> seen;
  SimulateOptions opt;
  opt.progress_interval_s = 0.0;
  opt.progress = [&](const SimulationProgress& p) { seen.push_back(p); };
  const SimulationResult r = simulate(m, opt);
  ASSERT_GE(seen.size(), 2u);
  long events = 0;
  for (const auto& e : r.hybrid.events) events += e.kind != "initial";
  EXPECT_TRUE(seen.back().finished);
  EXPECT_EQ(seen.back().events, events);
  EXPECT_DOUBLE_EQ(seen.back().t, 0.5);
  EXPECT_TRUE(std::is_sorted(seen.begin(), seen.end(), [](const auto& a, const auto& b) { return a.events < b.events; }));
  EXPECT_GT(events, 5);
}

// Claim: ω against distance (paper 000, Fig. 2) of the rolling wheel, scheme 1, has the energy
// analysis' limit speed as its reference line (8.92 rad/s, eq. 28), x ascending from 0 and ω
// approaching the limit at the right end (within 1 %); every point is the energy integral at that x.
TEST(PaperFigures, SpeedDistanceLimitLineIsTheEnergyAnalysisLimit) {
  const Model m = load_model(test::example("rolling-wheel-1.yaml"));
  const EnergyResult r = energy_analysis(m);
  ASSERT_TRUE(r.omega_limit);
  const plot::Figure f = speed_distance_figure(m, r);
  EXPECT_EQ(f.id, "speed_distance");
  ASSERT_EQ(f.ref_lines.size(), 1u);
  EXPECT_DOUBLE_EQ(f.ref_lines[0].value, *r.omega_limit);
  EXPECT_NEAR(f.ref_lines[0].value, 8.92, 0.005);
  EXPECT_EQ(f.x.label(), "distance travelled x, m");
  const auto& w = f.series.at(0);
  EXPECT_NEAR(w.x.front(), 0.0, 1e-12);
  EXPECT_TRUE(std::is_sorted(w.x.begin(), w.x.end()));
  EXPECT_NEAR(w.y.back(), *r.omega_limit, 1e-2 * *r.omega_limit);
  const EnergyIntegral I(m);
  for (std::size_t k = 0; k + 1 < w.x.size(); k += 37) EXPECT_NEAR(w.y[k], I.omega(w.x[k] / 0.5), 1e-12) << w.x[k];  // x = R1 φ
}

// Claim: scheme 2 turns back (paper 000, Fig. 3): no limit line, and the curve ends at ω = 0 at the
// stop distance 3.079 m.
TEST(PaperFigures, SpeedDistanceOfSchemeTwoEndsAtTheStop) {
  const Model m = load_model(test::example("rolling-wheel-2.yaml"));
  const plot::Figure f = speed_distance_figure(m, energy_analysis(m));
  EXPECT_TRUE(f.ref_lines.empty());
  EXPECT_NEAR(f.series[0].x.back(), 3.079201, 1e-5);
  EXPECT_NEAR(f.series[0].y.back(), 0.0, 1e-12);
}

// Claim: the crank's inertia moments from the energy integral (paper 004 eq. 5, ε from eq. 4) agree
// with the time integration's columns crank.M_crank/M_rod/M_piston over one revolution (an
// independent computation: DOPRI5 on the equation of motion) to 1e-4 of the largest moment.
TEST(PaperFigures, CrankInertiaMomentsAgreeWithTimeIntegration) {
  Model m = load_model(test::example("crank-slider.yaml"));
  const EnergyResult er = energy_analysis(m);
  const plot::Figure f = inertia_moments_figure(m, er);
  ASSERT_EQ(f.series.size(), 4u);  // crank, rod, piston, sum
  m.simulation.t_end = 0.045, m.simulation.dt_out = 1e-5;  // a little more than one revolution at 150 rad/s
  const SimulationResult r = simulate(m);
  auto col = [&](const std::string& name) -> const std::vector<double>& {
    for (std::size_t c = 0; c < r.column_names.size(); ++c)
      if (r.column_names[c] == name) return r.columns[c];
    throw std::runtime_error("no column " + name);
  };
  std::vector<double> deg = col("crank.position_rad");
  for (double& v : deg) v *= 180.0 / 3.141592653589793;
  double scale = 0;
  for (const auto& s : f.series)
    for (double v : s.y) scale = std::max(scale, std::abs(v));
  ASSERT_GT(scale, 10.0);
  for (int k = 0; k < 3; ++k) {
    const auto& s = f.series[static_cast<std::size_t>(k)];
    const auto& sim = col(fmt::format("crank.M_{}_N_m", s.name));
    for (std::size_t i = 0; i < s.x.size(); ++i)
      EXPECT_NEAR(s.y[i], interpolate(deg, sim, s.x[i]), 1e-4 * scale) << s.name << " at " << s.x[i] << " deg";
  }
  // d'Alembert: Σ M_k = −Q, the sum series is the negative generalized force.
  const EnergyIntegral I(m);
  for (std::size_t i = 0; i < er.table.size(); ++i) EXPECT_NEAR(f.series[3].y[i], -I.force_s(er.table[i].s), 1e-9 * scale);
  EXPECT_EQ(f.series[0].name, "crank");
}

// Claim: a chain of 20 masses gets a readable mode-shape figure: the 6 lowest of 19 modes (the title
// says so), lines without markers, and at most ~60 characters of body names on the x axis, the
// first body named, the last one too unless its neighbour is.
TEST(PaperFigures, ModeShapesOfTwentyMassChainStayReadable) {
  std::string y = "name: chain of 20\nbodies:\n";
  for (int i = 1; i <= 20; ++i) y += fmt::format("  J{}: {{type: rotational, inertia: 0.{} kg*m^2}}\n", i, 10 + i);
  y += "links:\n";
  for (int i = 1; i < 20; ++i) y += fmt::format("  c{}: {{type: spring, between: [J{}, J{}], stiffness: 1e4 N*m/rad}}\n", i, i, i + 1);
  y += "simulation: {t_end: 0.1 s, dt_out: 1 ms}\n";
  const Model m = load_model(test::write_temp("chain20.yaml", y));
  const Modes modes = compute_modes(m);
  ASSERT_EQ(modes.shapes.cols(), 19);
  const plot::Figure f = mode_shapes_figure(m, modes);
  EXPECT_EQ(f.series.size(), 6u);
  EXPECT_EQ(f.title, m.name + ": the 6 lowest of 19 elastic mode shapes (each scaled to max |φ| = 1)");
  EXPECT_EQ(f.series[0].style, plot::Style::line);
  std::size_t chars = 0;
  for (const auto& t : f.x.ticks) chars += t.second.size() + 2;
  EXPECT_LE(chars, 66u);
  EXPECT_EQ(f.x.ticks.front().second, "J1");
  EXPECT_EQ(f.x.ticks.back().second, "J19");  // every 2nd body: J1, J3, ..., J19
  EXPECT_EQ(mode_shapes_figure(m, modes, 100).series.size(), 19u);
}

// Claim: the report's events table lists every event of a hybrid run ({t, kind, element, from,
// to}); the slip-phase table has one row per phase with the breakaway load; the cases table has one
// row per case and link with the peak and its dynamic factor from LinkSummary (set_peak).
TEST(PaperFigures, ReportTablesOfEventsSlipPhasesAndCases) {
  const Model m = load_model(test::example("travel-start.yaml"), {"simulation.t_end=0.3"});
  const SimulationResult r = simulate(m);
  const report::Table ev = report::events_table(r);
  ASSERT_EQ(ev.rows.size(), r.hybrid.events.size());
  EXPECT_EQ(ev.header, (std::vector<std::string>{"t, s", "kind", "element", "from", "to"}));
  EXPECT_EQ(ev.rows[0][1], "initial");
  const report::Table sp = report::slip_phases_table(m, r);
  ASSERT_EQ(sp.rows.size(), r.hybrid.slip_phases.size());
  EXPECT_EQ(sp.header[6], "c at breakaway, N");
  const Model h = load_model(test::example("hoist-3mass.yaml"));
  const SimulationResult hr = simulate(h);
  report::Case a, b;
  a.name = "travel", a.model = &m, a.result = &r;
  b.name = "hoist", b.model = &h, b.result = &hr;
  const report::Table ct = report::cases_table({a, b});
  ASSERT_EQ(ct.rows.size(), 3u);  // 1 link + 2 links
  EXPECT_EQ(ct.rows[0][0], "travel");
  EXPECT_EQ(ct.rows[1][0], "hoist");
  EXPECT_EQ(ct.rows[2][0], "");
  const LinkSummary& p = hr.links[0];
  EXPECT_EQ(ct.rows[1][4], fmt::format("{:.6g}", p.peak));
  EXPECT_EQ(ct.rows[1][7], fmt::format("{:.3g}", p.dynamic_factor));
}

}  // namespace
}  // namespace machdyn
