// The plotting layer: what goes to gnuplot (data, script), what comes back (SVG with the legend,
// PNG), the papers' figures built from real results, and the checks on a Figure.
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/plot.hpp"

#include <cmath>
#include <cstdlib>
#include <cstdio>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/figures.hpp"
#include "machdyn/model/cases.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::have_gnuplot;

plot::Figure two_series() {
  plot::Figure f;
  f.id = "demo";
  f.title = "A 'quoted' title";
  f.x = plot::make_axis("time t", "s");
  f.y = plot::make_axis("link torque M", "N·m");
  f.series.push_back(plot::make_series("c1 (I1–I2)", {0, 1, 2, 3}, {1, 2, NAN, 4}));
  f.series.push_back(plot::make_series("c2", {0, 1}, {5, 6}, plot::Style::steps));
  f.ref_lines.push_back(plot::make_ref_line(354, "c1* = 354 N·m", 0));
  return f;
}

// Claim: the data file has one block per series, in order, each headed by its name; a NaN breaks
// the curve with one blank line; blocks are separated by two blank lines (gnuplot `index`).
TEST(Plot, DataFileHasEverySeriesAndBreaksAtNaN) {
  const std::string d = plot::gnuplot_data(two_series());
  EXPECT_EQ(d, "# c1 (I1–I2)\n0 1\n1 2\n\n3 4\n\n\n# c2\n0 5\n1 6\n\n\n");
}

// Claim: the script labels both axes with quantity and unit, names every series in the legend,
// draws the reference line at its value in its series' colour, and quotes text safely.
TEST(Plot, ScriptHasLabelsLegendAndReferenceLine) {
  const std::string g = plot::gnuplot_script(two_series(), plot::Format::svg, "/tmp/d.dat", "/tmp/o.svg");
  EXPECT_NE(g.find("set xlabel 'time t, s'"), std::string::npos) << g;
  EXPECT_NE(g.find("set ylabel 'link torque M, N·m'"), std::string::npos);
  EXPECT_NE(g.find("set title \"A 'quoted' title\""), std::string::npos) << g;
  EXPECT_NE(g.find("index 0 using 1:2 with lines lc rgb '#0072B2' lw 2 dt 1 title 'c1 (I1–I2)'"), std::string::npos) << g;
  EXPECT_NE(g.find("index 1 using 1:2 with steps"), std::string::npos);
  EXPECT_NE(g.find("first 354 nohead lc rgb '#0072B2'"), std::string::npos);
  EXPECT_NE(g.find("set label 'c1* = 354 N·m'"), std::string::npos);
  EXPECT_NE(g.find("set terminal svg size 800,500"), std::string::npos);
  EXPECT_NE(plot::gnuplot_script(two_series(), plot::Format::png, "d", "o").find("pngcairo size 1600,1000"),
            std::string::npos);
}

// Claim: a Figure that cannot be drawn is refused with a message naming the figure and series.
TEST(Plot, ValidateRefusesBrokenFigures) {
  auto f = two_series();
  f.series[1].y.push_back(1.0);
  EXPECT_THROW(plot::validate(f), std::invalid_argument);
  f = two_series();
  f.series[0].y_axis = 2;  // y2 has no quantity
  EXPECT_THROW(plot::validate(f), std::invalid_argument);
  f = two_series();
  f.id = "../evil";
  EXPECT_THROW(plot::validate(f), std::invalid_argument);
}

TEST(Plot, PrettyUnits) {
  EXPECT_EQ(plot::pretty_unit("N*m"), "N·m");
  EXPECT_EQ(plot::pretty_unit("kg*m^2"), "kg·m²");
  EXPECT_EQ(plot::pretty_unit("rad/s"), "rad/s");
}

// Claim: gnuplot renders an SVG that carries the legend text and the reference label, and a PNG.
TEST(Plot, RenderProducesSvgWithLegendAndPng) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed (apt-get install gnuplot-nox): rendering not checked";
  const auto r = plot::render(two_series());
  EXPECT_NE(r.svg.find("<svg"), std::string::npos);
  EXPECT_NE(r.svg.find("c1 (I1–I2)"), std::string::npos);
  EXPECT_NE(r.svg.find("c1* = 354 N·m"), std::string::npos);
  ASSERT_GT(r.png.size(), 8u);
  EXPECT_EQ(r.png.substr(1, 3), "PNG");
}

// Claim: without gnuplot, render() fails with the Debian package to install.
TEST(Plot, MissingGnuplotSaysWhatToInstall) {
  ::setenv("MACHDYN_GNUPLOT", "/nonexistent/gnuplot", 1);
  try {
    plot::render(two_series());
    ADD_FAILURE() << "no error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("gnuplot-nox"), std::string::npos) << e.what();
  }
  ::unsetenv("MACHDYN_GNUPLOT");
}

// Claim: the link-load figure of the paper 002 hoist has one curve per link and the particular
// solutions M12* = 354 N·m, M23* = 30 N·m (eq. 22) as reference lines in the links' colours, their
// values in the legend entries (one label per link, never overlapping) and not as labels on the
// plot; the title names the model; the peak (the extreme of larger magnitude over all links) is
// annotated at its time with its value.
TEST(Figures, HoistLinkLoadsMarkTheParticularSolution) {
  const Model m = load_model(test::example("hoist-3mass.yaml"), {"simulation.t_end=0.05"});
  const SimulationResult r = simulate(m);
  const plot::Figure f = link_loads_figure(m, r);
  ASSERT_EQ(f.series.size(), 2u);
  EXPECT_EQ(f.series[0].name, "c1 (I1–I2), c1* = 354 N·m");
  EXPECT_EQ(f.series[1].name, "c2 (I2–I3), c2* = 30 N·m");
  for (const auto& rl : f.ref_lines) EXPECT_EQ(rl.label, "");
  EXPECT_EQ(f.title.rfind(m.name + ": link loads", 0), 0u) << f.title;
  ASSERT_EQ(f.notes.size(), 1u);
  std::size_t top = 0;
  double top_abs = -1;
  for (std::size_t l = 0; l < r.links.size(); ++l)
    for (double v : {r.links[l].max, r.links[l].min})
      if (std::abs(v) > top_abs) top_abs = std::abs(v), top = l;
  const auto& S = r.links[top];
  const bool use_max = std::abs(S.max) >= std::abs(S.min);
  EXPECT_EQ(f.notes[0].series, static_cast<int>(top));
  EXPECT_DOUBLE_EQ(f.notes[0].y, use_max ? S.max : S.min);
  EXPECT_DOUBLE_EQ(f.notes[0].x, use_max ? S.t_max : S.t_min);
  EXPECT_NE(f.notes[0].text.find(fmt::format("{:.4g} N·m", use_max ? S.max : S.min)), std::string::npos)
      << f.notes[0].text;
  EXPECT_EQ(f.series[0].x.size(), r.columns[0].size());
  ASSERT_EQ(f.ref_lines.size(), 2u);
  EXPECT_NEAR(f.ref_lines[0].value, 354.0, 1e-9);
  EXPECT_NEAR(f.ref_lines[1].value, 30.0, 1e-9);
  EXPECT_EQ(f.ref_lines[1].series, 1);
  EXPECT_EQ(f.y.label(), "link torque M, N·m");
  const auto figs = simulation_figures(m, r);
  ASSERT_EQ(figs.size(), 2u);
  EXPECT_EQ(figs[1].series.size(), 3u);  // one speed per body
}

// Claim: the mode-shape figure has one curve per elastic mode, one point per body, max |φ| = 1.
TEST(Figures, ModeShapesOneCurvePerModeScaledToOne) {
  const Model m = load_model(test::example("hoist-3mass.yaml"));
  const plot::Figure f = mode_shapes_figure(m, compute_modes(m));
  ASSERT_EQ(f.series.size(), 2u);
  for (const auto& s : f.series) {
    ASSERT_EQ(s.y.size(), 3u);
    double mx = 0;
    for (double v : s.y) mx = std::max(mx, std::abs(v));
    EXPECT_NEAR(mx, 1.0, 1e-12);
  }
  EXPECT_EQ(f.x.ticks.size(), 3u);
  EXPECT_EQ(f.x.ticks[2].second, "I3");
}

// Claim: a hybrid run's link-load figure marks its events at their times (here the brake of the
// hoist sticking, slipping back and sticking again), and its title names the model and the case.
TEST(Figures, LinkLoadsMarkEventsAndNameTheCase) {
  const Model m = load_model_case(test::example("hoist-modes.yaml"), {}, "brake_I2_lifting");
  const SimulationResult r = simulate(m);
  const plot::Figure f = link_loads_figure(m, r);
  EXPECT_NE(f.title.find("[brake_I2_lifting]"), std::string::npos) << f.title;
  std::vector<double> expected;
  for (const auto& e : r.hybrid.events)
    if (e.kind != "initial") expected.push_back(e.t);
  ASSERT_FALSE(expected.empty());
  ASSERT_EQ(f.events.size(), expected.size());
  for (std::size_t k = 0; k < expected.size(); ++k) EXPECT_DOUBLE_EQ(f.events[k].x, expected[k]);
  EXPECT_EQ(f.events[0].label, "T sticks");
}

/// The [lo:hi] of `set NAME [lo:hi]` in a gnuplot script.
std::pair<double, double> range_in(const std::string& script, const std::string& name) {
  const auto at = script.find("set " + name + " [");
  if (at == std::string::npos) return {0, 0};
  double lo = 0, hi = 0;
  std::sscanf(script.c_str() + at + name.size() + 6, "%lf:%lf", &lo, &hi);
  return {lo, hi};
}

// Claim: with two y axes and a zero line, zero sits at the same height on both (the fraction of the
// height below zero is equal), every curve stays inside its axis' range, and tick labels are plain
// decimals, never e-notation.
TEST(Figures, DualAxisZerosAlignAndTicksArePlainDecimals) {
  plot::Figure f;
  f.id = "dual";
  f.x = plot::make_axis("time t", "s");
  f.y = plot::make_axis("link torque M", "kN·m");
  f.y2 = plot::make_axis("link force F", "kN");
  f.series.push_back(plot::make_series("M", {0, 1, 2}, {-3, 10, 4}));
  f.series.push_back(plot::make_series("F", {0, 1, 2}, {20, 43.5, 30}, plot::Style::line, 2));
  f.zero_line = true;
  const std::string g = plot::gnuplot_script(f, plot::Format::svg, "d.dat", "o.svg");
  const auto [lo1, hi1] = range_in(g, "yrange");
  const auto [lo2, hi2] = range_in(g, "y2range");
  ASSERT_LT(lo1, 0.0);
  EXPECT_NEAR(-lo1 / (hi1 - lo1), -lo2 / (hi2 - lo2), 1e-9) << g;
  EXPECT_LE(lo1, -3.0);
  EXPECT_GE(hi1, 10.0);
  EXPECT_LE(lo2, 0.0);
  EXPECT_GE(hi2, 43.5);
  for (const char* fmt : {"set format y '%.10g'", "set format y2 '%.10g'", "set format x '%.10g'"})
    EXPECT_NE(g.find(fmt), std::string::npos) << fmt;
}

// Claim: with the rpm option the body speeds of rotational bodies are n = 60 ω / 2π on an axis in
// rpm; the default stays in rad/s.
TEST(Figures, BodySpeedsInRpmOnRequest) {
  const Model m = load_model(test::example("hoist-3mass.yaml"), {"simulation.t_end=0.05"});
  const SimulationResult r = simulate(m);
  FigureOptions opt;
  opt.rpm = true;
  const plot::Figure f = body_speeds_figure(m, r, opt), g = body_speeds_figure(m, r);
  EXPECT_EQ(f.y.label(), "speed n, rpm");
  EXPECT_EQ(g.y.label(), "angular velocity ω, rad/s");
  const auto& omega = r.columns[test::column(r, "I1.velocity_rad_s")];
  ASSERT_EQ(f.series[0].y.size(), omega.size());
  for (std::size_t k = 0; k < omega.size(); k += 7) EXPECT_NEAR(f.series[0].y[k], omega[k] * 30.0 / M_PI,
                                                     1e-9 * (1 + std::abs(omega[k]) * 10));
}

}  // namespace
}  // namespace machdyn
