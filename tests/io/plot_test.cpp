// The plotting layer: what goes to gnuplot (data, script), what comes back (SVG with the legend,
// PNG), the papers' figures built from real results, and the checks on a Figure.
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/plot.hpp"

#include <cmath>
#include <cstdlib>
#include <gtest/gtest.h>

#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/figures.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace {

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
  EXPECT_NE(g.find("set title 'A ''quoted'' title'"), std::string::npos);
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
// solutions M12* = 354 N·m, M23* = 30 N·m (eq. 22) as reference lines in the links' colours.
TEST(Figures, HoistLinkLoadsMarkTheParticularSolution) {
  const Model m = load_model(test::example("hoist-3mass.yaml"), {"simulation.t_end=0.05"});
  const SimulationResult r = simulate(m);
  const plot::Figure f = link_loads_figure(m, r);
  ASSERT_EQ(f.series.size(), 2u);
  EXPECT_EQ(f.series[0].name, "c1 (I1–I2)");
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

}  // namespace
}  // namespace machdyn
