// --plot, report and the progress bar as a user meets them.
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sstream>
#include <unistd.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/report.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::slurp;
using test::have_gnuplot;

namespace fs = std::filesystem;



// Claim: simulate --plot writes the link-load figure (legend names the links, the static values
// labelled) and the body speeds, each as SVG and PNG, beside the CSV and JSON.
TEST(PlotCli, SimulatePlotWritesSvgAndPng) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed (apt-get install gnuplot-nox)";
  const auto dir = test::temp_dir() / "sim-plot";
  const auto r = test::run_cli("simulate '" + test::example("hoist-3mass.yaml") + "' --plot -o '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"link_loads.svg", "link_loads.png", "body_speeds.svg", "body_speeds.png", "timeseries.csv"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  const std::string svg = slurp(dir / "link_loads.svg");
  for (const char* s : {"c1 (I1–I2)", "c2 (I2–I3)", "c1* = 354 N·m", "c2* = 30 N·m", "link torque M, N·m", "time t, s"})
    EXPECT_NE(svg.find(s), std::string::npos) << s;
  EXPECT_EQ(slurp(dir / "link_loads.png").substr(1, 3), "PNG");
  EXPECT_NE(r.out.find("figures: "), std::string::npos);
}

// Claim: modes --plot writes mode_shapes.svg/.png; gears --plot writes Fig. 1 and Fig. 2 of paper 003.
TEST(PlotCli, ModesAndGearsPlot) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed (apt-get install gnuplot-nox)";
  const auto dir = test::temp_dir() / "modes-plot";
  auto r = test::run_cli("modes '" + test::example("hoist-3mass.yaml") + "' --plot -o '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(slurp(dir / "mode_shapes.svg").find("mode 1: 29.46 Hz"), std::string::npos);
  EXPECT_TRUE(fs::exists(dir / "mode_shapes.png"));
  const auto gdir = test::temp_dir() / "gears-plot";
  r = test::run_cli("gears '" + test::example("walking-drive-gears.yaml") + "' --plot -o '" + gdir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"pitch_curves.svg", "pitch_curves.png", "ratio.svg", "ratio.png", "sectors.csv"})
    EXPECT_TRUE(fs::exists(gdir / f)) << f;
  EXPECT_NE(slurp(gdir / "ratio.svg").find("stepwise Δθ_j/Δφ_j"), std::string::npos);
}

// Claim: without gnuplot, --plot fails before the run with exit 1, names the package, and writes
// no result file.
TEST(PlotCli, MissingGnuplotWritesNothing) {
  const auto dir = test::temp_dir() / "no-gnuplot";
  ::setenv("MACHDYN_GNUPLOT", "/nonexistent/gnuplot", 1);
  const auto r = test::run_cli("simulate '" + test::example("hoist-3mass.yaml") + "' --plot -o '" + dir.string() + "'");
  ::unsetenv("MACHDYN_GNUPLOT");
  EXPECT_EQ(r.exit_code, 1);
  EXPECT_NE(r.err.find("gnuplot-nox"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir));
}

// Claim: report writes one HTML file; bad input exits 2 with file:line:col and writes no file.
TEST(PlotCli, ReportWritesHtmlAndRefusesBadInput) {
  if (!report::assets_available()) GTEST_SKIP() << "built with MACHDYN_REPORT=OFF: no report";
  const auto html = test::temp_dir() / "rep" / "r.html";
  auto r = test::run_cli("report '" + test::example("hoist-3mass.yaml") + "' -o '" + html.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string h = slurp(html);
  EXPECT_EQ(h.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(h.find("Three-mass hoist"), std::string::npos);
  EXPECT_NE(h.find("data-figure=\"link_loads-1\""), std::string::npos);
  const auto bad = test::write_temp("bad-report.yaml", "bodies:\n  A: {inertia: -2}\n");
  const auto never = test::temp_dir() / "never" / "r.html";
  r = test::run_cli("report '" + bad + "' -o '" + never.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(bad + ":2:16: error:"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(never.parent_path()));
}

// Claim: the library reports progress with growing simulated time and ends with one report at
// t_end marked finished; events are 0 in a linear chain.
TEST(Progress, CallbackSeesTimeGrowAndTheEnd) {
  const Model m = load_model(test::example("hoist-3mass.yaml"), {"simulation.t_end=2"});
  std::vector<SimulationProgress> seen;
  SimulateOptions opt;
  opt.progress = [&](const SimulationProgress& p) { seen.push_back(p); };
  opt.progress_interval_s = 0.0;  // every check
  simulate(m, opt);
  ASSERT_GE(seen.size(), 3u);
  for (size_t k = 1; k < seen.size(); ++k) EXPECT_GE(seen[k].t, seen[k - 1].t);
  EXPECT_TRUE(seen.back().finished);
  EXPECT_DOUBLE_EQ(seen.back().t, 2.0);
  EXPECT_EQ(seen.back().events, 0);
  EXPECT_FALSE(seen.front().finished);
}

// Claim: on a terminal (script(1) gives one) the bar shows simulated time, events and time left on
// stderr; --quiet silences it; with stderr not a terminal nothing is drawn.
TEST(Progress, BarOnlyOnATerminalAndNotQuiet) {
  if (std::system("command -v script >/dev/null 2>&1") != 0) GTEST_SKIP() << "script(1) not installed";
  const std::string run = fmt::format("'{}' simulate '{}' --set simulation.t_end=20 -o out-progress", MACHDYN_CLI, test::example("hoist-3mass.yaml"));
  auto on_tty = [&](const std::string& extra) {
    const auto out = test::temp_dir() / "tty.out";
    const std::string cmd = "cd '" + test::temp_dir().string() + "' && MACHDYN_PROGRESS_DELAY=0 script -qec \"" + run +
                            extra + "\" /dev/null >'" + out.string() + "' 2>&1 </dev/null";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
    return slurp(out);
  };
  const std::string tty = on_tty("");
  EXPECT_NE(tty.find("events 0"), std::string::npos) << tty;
  EXPECT_NE(tty.find("t = "), std::string::npos);
  EXPECT_NE(tty.find("left"), std::string::npos);
  const std::string quiet = on_tty(" --quiet");
  EXPECT_EQ(quiet.find("events 0"), std::string::npos) << quiet;
  EXPECT_NE(quiet.find("c1"), std::string::npos) << quiet;  // the table is still printed
  const auto pipe = test::run_cli("simulate '" + test::example("hoist-3mass.yaml") + "' --set simulation.t_end=20 -o o2",
                                  test::temp_dir());
  EXPECT_EQ(pipe.err.find("events"), std::string::npos) << pipe.err;
}

}  // namespace
}  // namespace machdyn
