// `energy --plot`, `simulate --plot` on a hybrid model, and `report --case/--all-cases` as a user
// meets them.
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>
#include <unistd.h>

#include "machdyn/io/report.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::slurp;
using test::have_gnuplot;

namespace fs = std::filesystem;



// Claim: energy --plot on the rolling wheel writes ω against distance with the limit line labelled
// ω_lim = 8.923 rad/s; on the crank-slider ω against crank angle and the inertia moments of crank,
// rod and piston; SVG and PNG each, into the -o folder beside the table energy.csv. The deprecated
// --plot-dir still names that folder, with a warning.
TEST(PaperPlotsCli, EnergyPlotWritesSpeedDistanceAndInertiaMoments) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed (apt-get install gnuplot-nox)";
  const auto dir = test::temp_dir() / "energy-plot";
  auto r = test::run_cli("energy '" + test::example("rolling-wheel-1.yaml") + "' --plot -o '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"speed_distance.svg", "speed_distance.png", "energy.csv", "energy.json"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  const std::string svg = slurp(dir / "speed_distance.svg");
  for (const char* s : {"ω_lim = 8.923 rad/s", "distance travelled x, m", "angular velocity ω, rad/s"})
    EXPECT_NE(svg.find(s), std::string::npos) << s;
  EXPECT_EQ(slurp(dir / "speed_distance.png").substr(1, 3), "PNG");
  const auto cdir = test::temp_dir() / "energy-plot-crank";
  r = test::run_cli("energy '" + test::example("crank-slider.yaml") + "' --plot --plot-dir '" + cdir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("--plot-dir is deprecated; use -o DIR"), std::string::npos) << r.err;
  EXPECT_TRUE(fs::exists(cdir / "energy.csv"));
  for (const char* f : {"speed_angle.svg", "speed_angle.png", "inertia_moments.svg", "inertia_moments.png"})
    EXPECT_TRUE(fs::exists(cdir / f)) << f;
  const std::string im = slurp(cdir / "inertia_moments.svg");
  for (const char* s : {"crank", "rod", "piston", "inertia moment M, N·m", "angle φ, deg"})
    EXPECT_NE(im.find(s), std::string::npos) << s;
  EXPECT_NE(r.out.find("figures: "), std::string::npos);
}

// Claim: energy --plot with bad input exits 2 with file:line:col and writes no figure.
TEST(PaperPlotsCli, EnergyPlotBadInputWritesNothing) {
  const auto dir = test::temp_dir() / "energy-plot-bad";
  const auto model = test::write_temp("bad-wheel.yaml", "name: bad\nbodies:\n  w: {type: rolling-wheel, scheme: 7}\n");
  const auto r = test::run_cli("energy '" + model + "' --plot -o '" + dir.string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("bad-wheel.yaml:3:"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir));
}

// Claim: simulate --plot on the travel start-up writes the load cyclogram (F_sc line, slip legend,
// breakaway dots) and the contacts figure beside the link loads and body speeds.
TEST(PaperPlotsCli, HybridSimulatePlotWritesCyclogram) {
  if (!have_gnuplot()) GTEST_SKIP() << "gnuplot not installed (apt-get install gnuplot-nox)";
  const auto dir = test::temp_dir() / "travel-plot";
  const auto r = test::run_cli("simulate '" + test::example("travel-start.yaml") + "' --plot -o '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"load_cyclogram.svg", "load_cyclogram.png", "contacts.svg", "contacts.png", "link_loads.png",
                        "body_speeds.png", "timeseries.csv", "summary.json"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
  const std::string svg = slurp(dir / "load_cyclogram.svg");
  for (const char* s : {"F_sc = 9 kN", "adhesion slips", "c at breakaway", "link force F, kN",
                        "Travel drive start-up (paper 001): load cyclogram"})
    EXPECT_NE(svg.find(s), std::string::npos) << s;
}

// Claim: report --all-cases on the hoist's eleven operating modes has a section for every case
// (its name and description), one comparison table, and an events table per case; report --case
// NAME has one case; giving both is refused with exit 2.
TEST(PaperPlotsCli, ReportAllCasesHasEveryCaseAndEventsTable) {
  if (!report::assets_available()) GTEST_SKIP() << "built with MACHDYN_REPORT=OFF: no report";
  const auto html = test::temp_dir() / "cases" / "report.html";
  auto r = test::run_cli("report '" + test::example("hoist-modes.yaml") + "' --all-cases --quiet -o '" + html.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string h = slurp(html);
  for (const char* c : {"accel_up", "brake_I1_lifting", "brake_I2_lifting", "brake_I3_lifting", "coast_up", "accel_down",
                        "brake_I1_lowering", "brake_I2_lowering", "brake_I3_lowering", "coast_down", "braked_lowering"})
    EXPECT_NE(h.find(std::string("Case ") + c), std::string::npos) << c;
  EXPECT_NE(h.find("Load cases compared: peak link loads and dynamic factors"), std::string::npos);
  EXPECT_NE(h.find("mode 2: braking of I1 at the end of lifting"), std::string::npos);
  EXPECT_NE(h.find("<th>t, s</th><th>kind</th><th>element</th><th>from</th><th>to</th>"), std::string::npos);
  EXPECT_NE(h.find("<h1>Hoist operating modes (paper 002)</h1>"), std::string::npos);
  r = test::run_cli("report '" + test::example("hoist-modes.yaml") + "' --case coast_up --quiet -o '" +
                    (html.parent_path() / "one.html").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string one = slurp(html.parent_path() / "one.html");
  EXPECT_NE(one.find("Case coast_up"), std::string::npos);
  EXPECT_EQ(one.find("Case accel_up"), std::string::npos);
  r = test::run_cli("report '" + test::example("hoist-modes.yaml") + "' --case coast_up --all-cases -o '" +
                    (html.parent_path() / "both.html").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(fs::exists(html.parent_path() / "both.html"));
}

// Claim: the report of a 1-DOF machine draws ω against distance (rolling wheel) from the energy
// integral; the report of the travel start-up has the cyclogram and the slip-phase table.
TEST(PaperPlotsCli, ReportOfMachineAndHybridModels) {
  if (!report::assets_available()) GTEST_SKIP() << "built with MACHDYN_REPORT=OFF: no report";
  const auto html = test::temp_dir() / "machine" / "wheel.html";
  auto r = test::run_cli("report '" + test::example("rolling-wheel-1.yaml") + "' --quiet -o '" + html.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(slurp(html).find("data-figure=\"speed_distance-"), std::string::npos);
  const auto travel = test::temp_dir() / "machine" / "travel.html";
  r = test::run_cli("report '" + test::example("travel-start.yaml") + "' --quiet -o '" + travel.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string t = slurp(travel);
  for (const char* s : {"data-figure=\"load_cyclogram-", "Slip phases with the link loads at breakaway and their maxima", "Mode events",
                        "adhesion slips"})
    EXPECT_NE(t.find(s), std::string::npos) << s;
}

}  // namespace
}  // namespace machdyn
