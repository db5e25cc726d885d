// `machdyn crane` as a user meets it: the shipped crane examples run, the table is printed and
// written as crane.csv and crane.json with the same rows; a model without `crane:` exits 2.
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

namespace fs = std::filesystem;

// Claim: the main-hoist example gives the rows phi2, phi3, phi5 (in that order) in the JSON, the CSV
// (header + one line per row) and the terminal table; the φ2 standard value is HC2/HD1 at
// vh = 0.2 m/s: 1.10 + 0.34 · 0.2 = 1.168; φ3 rapid release of 4 t of 12 t: 1 − (1/3)·2 = 1/3.
TEST(CraneCli, MainHoistWritesTheTable) {
  const auto dir = test::temp_dir() / "crane-hoist";
  const auto r = test::run_cli("crane '" + test::example("crane/main-hoist.yaml") + "' -o '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(std::ifstream(dir / "crane.json"));
  ASSERT_EQ(j["rows"].size(), 3u);
  EXPECT_EQ(j["rows"][0]["factor"], "phi2");
  EXPECT_NEAR(j["rows"][0]["standard_lo"].get<double>(), 1.168, 1e-12);
  EXPECT_GT(j["rows"][0]["simulated"].get<double>(), 1.0);
  EXPECT_EQ(j["rows"][1]["factor"], "phi3");
  EXPECT_NEAR(j["rows"][1]["standard_lo"].get<double>(), 1.0 / 3.0, 1e-12);
  EXPECT_LT(j["rows"][1]["simulated"].get<double>(), 1.0);
  EXPECT_EQ(j["rows"][2]["factor"], "phi5");
  std::ifstream csv(dir / "crane.csv");
  int lines = 0;
  for (std::string line; std::getline(csv, line);) ++lines;
  EXPECT_EQ(lines, 4);
  EXPECT_NE(r.out.find("phi2"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("EN 13001-2"), std::string::npos) << r.out;
}

// Claim: the grab example releases 4 t of its 12 t at 1.2 s. `machdyn crane` gives the φ3 row of the
// release while hoisting (its case says so) beside 1 − (4/12)(1 + 1) = 1/3, the simulated value a
// rope minimum after the release above zero and below the weight; `machdyn simulate` runs the
// model's own release: a `release` event at 1.2 s, the column grab.mass_kg from 12000 to 8000, the
// released part's kinetic energy in the books, which close.
TEST(CraneCli, GrabReleaseExample) {
  const auto dir = test::temp_dir() / "crane-grab";
  const auto r = test::run_cli("crane '" + test::example("crane/grab-release.yaml") + "' --json -o '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["rows"].size(), 2u);
  EXPECT_EQ(j["rows"][1]["factor"], "phi3");
  EXPECT_NE(j["rows"][1]["case"].get<std::string>().find("at t = 1.2 s while hoisting"), std::string::npos) << j;
  EXPECT_NEAR(j["rows"][1]["standard_lo"].get<double>(), 1.0 / 3.0, 1e-12);
  EXPECT_GT(j["rows"][1]["simulated"].get<double>(), 0.0);
  EXPECT_LT(j["rows"][1]["simulated"].get<double>(), 1.0);
  const auto sim = test::run_cli("simulate '" + test::example("crane/grab-release.yaml") + "' -o '" +
                                 (test::temp_dir() / "grab-sim").string() + "'");
  ASSERT_EQ(sim.exit_code, 0) << sim.err;
  const auto s = nlohmann::json::parse(std::ifstream(test::temp_dir() / "grab-sim" / "summary.json"));
  bool released = false;
  for (const auto& e : s["events"])
    if (e["kind"] == "release") released = e["t"].get<double>() == 1.2 && e["element"] == "grab_opens";
  EXPECT_TRUE(released) << s["events"];
  const double E = s["energy"]["released_kinetic_J"].get<double>();
  EXPECT_GT(E, 0.0);
  EXPECT_LT(std::abs(s["energy"]["residual_J"].get<double>()), 1e-3 * E);
  const std::string csv = test::slurp(test::temp_dir() / "grab-sim" / "timeseries.csv");
  EXPECT_NE(csv.find("grab.mass_kg"), std::string::npos);
}

// Claim: --plot writes one figure per simulated factor (SVG and PNG): crane_phi7_0 for the trolley.
TEST(CraneCli, PlotWritesAFigurePerFactor) {
  const auto dir = test::temp_dir() / "crane-plot";
  const auto r = test::run_cli("crane '" + test::example("crane/trolley-buffers.yaml") + "' --plot -o '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(dir / "crane_phi7_0.svg"));
  EXPECT_TRUE(fs::exists(dir / "crane_phi7_0.png"));
}

// Claim: the trolley example's φ7 row compares with 1.25 (a linear buffer, ξb = 1/2).
TEST(CraneCli, TrolleyBuffersGivePhi7) {
  const auto r = test::run_cli("crane '" + test::example("crane/trolley-buffers.yaml") + "' --json -o '" +
                               (test::temp_dir() / "crane-trolley").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["rows"].size(), 1u);
  EXPECT_EQ(j["rows"][0]["factor"], "phi7");
  EXPECT_EQ(j["rows"][0]["standard_lo"].get<double>(), 1.25);
  EXPECT_GT(j["rows"][0]["simulated"].get<double>(), 0.5);
}

// Claim: --phi2-speeds FROM:TO:N writes phi2_sweep.csv (header + N rows, vh evenly spaced, the
// standard's 1.10 + 0.34 vh of HC2/HD1 beside each) and the same points under "phi2_sweep" in the
// JSON; a malformed list is an input error naming the option (exit 2).
TEST(CraneCli, Phi2SpeedsWritesTheCurve) {
  const auto dir = test::temp_dir() / "crane-sweep";
  const auto r = test::run_cli("crane '" + test::example("crane/main-hoist.yaml") + "' --phi2-speeds 0.1:0.3:3 -o '" +
                               dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream csv(dir / "phi2_sweep.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header, "vh_m_s,phi2_simulated,phi2_standard");
  const auto j = nlohmann::json::parse(std::ifstream(dir / "crane.json"));
  ASSERT_EQ(j["phi2_sweep"].size(), 3u);
  EXPECT_NEAR(j["phi2_sweep"][1]["vh_m_s"].get<double>(), 0.2, 1e-15);
  EXPECT_NEAR(j["phi2_sweep"][2]["standard"].get<double>(), 1.10 + 0.34 * 0.3, 1e-12);
  EXPECT_GT(j["phi2_sweep"][2]["simulated"].get<double>(), j["phi2_sweep"][0]["simulated"].get<double>());
  const auto bad = test::run_cli("crane '" + test::example("crane/main-hoist.yaml") + "' --phi2-speeds 0.1:0.3 -o '" +
                                 (test::temp_dir() / "crane-bad").string() + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("--phi2-speeds"), std::string::npos) << bad.err;
}

// Claim: --plot with --phi2-speeds adds the figure crane_phi2_sweep (SVG and PNG) whose SVG carries
// both series by their legend entries: the simulated curve and the standard's line.
TEST(CraneCli, Phi2SpeedsPlotDrawsTheCurveAndTheStandardLine) {
  const auto dir = test::temp_dir() / "crane-sweep-plot";
  const auto r = test::run_cli("crane '" + test::example("crane/main-hoist.yaml") + "' --plot --phi2-speeds 0.1:0.3:3 -o '" +
                               dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(fs::exists(dir / "crane_phi2_sweep.svg"));
  EXPECT_TRUE(fs::exists(dir / "crane_phi2_sweep.png"));
  std::ifstream in(dir / "crane_phi2_sweep.svg");
  const std::string svg((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(svg.find("simulated"), std::string::npos);
  EXPECT_NE(svg.find("EN 13001-2: phi2,min + beta2 vh"), std::string::npos);
  EXPECT_NE(r.out.find("crane_phi2_sweep"), std::string::npos) << r.out;
}

// Claim: the slewing example's φ5 row compares the ring's dynamic factor with 3.0 ("considerable
// backlash"); the knock when the backlash closes lifts it above the 2 of a sudden force.
TEST(CraneCli, SlewingBacklashGivesPhi5) {
  const auto r = test::run_cli("crane '" + test::example("crane/slewing-backlash.yaml") + "' --json -o '" +
                               (test::temp_dir() / "crane-slew").string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["rows"].size(), 1u);
  EXPECT_EQ(j["rows"][0]["factor"], "phi5");
  EXPECT_EQ(j["rows"][0]["standard_hi"].get<double>(), 3.0);
  EXPECT_GT(j["rows"][0]["simulated"].get<double>(), 2.0);
}

// Claim: a model without a `crane:` section is an input error (exit 2) and writes nothing.
TEST(CraneCli, NoCraneSectionExitsTwo) {
  const auto dir = test::temp_dir() / "crane-none";
  const auto r = test::run_cli("crane '" + test::example("hoist-3mass.yaml") + "' -o '" + dir.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no 'crane:' section"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir));
}

// The rigid hoist of tests/analysis/crane_test.cpp with load cases: `slow` hoists in HD2 (a case
// replacing a field of `crane:`), `off` drops the crane analysis, `short` ends before lift-off.
const char* kHoistCases = R"(gravity: 9.81 m/s^2
bodies:
  drive: {type: translational, mass: 1e15 kg}
  load: {type: translational, mass: 1000 kg, vertical: up}
links:
  rope: {type: rope, between: [drive, load], stiffness: 1e6 N/m, slack: 10 mm}
stops: {ground: {body: load, min: 0 m}}
simulation: {t_end: 0.5 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
crane: {hoisting_class: HC2, drive_class: HD1, hoist_speed: 0.5 m/s, creep_speed: 0.1 m/s, load: load, rope: rope}
cases:
  slow:
    crane: {drive_class: HD2}
  off:
    crane: none
  short:
    simulation: {t_end: 0.03 s}
)";

// Claim (load cases and the crane analysis): `crane --case slow` runs the case's crane section — HD2
// at the creep speed 0.1 m/s, φ2 = 1 + vh ω/g (ω = √(c/m)) — writes OUT/slow/crane.json with the
// case's name, and its table names the case; `--all-cases` runs `slow` and the file's own section
// in the other cases, lists `off` as without crane analysis, and stops with exit 2 at `short`, whose
// error names the case and says the load was not lifted; a case's crane error names its case in
// `report --all-cases` too.
TEST(CraneCli, LoadCasesRunTheirOwnCraneSection) {
  const std::string model = test::write_temp("hoist-cases.yaml", kHoistCases);
  const auto dir = test::temp_dir() / "crane-cases";
  const auto one = test::run_cli("crane '" + model + "' --case slow -o '" + dir.string() + "'");
  ASSERT_EQ(one.exit_code, 0) << one.err;
  EXPECT_NE(one.out.find("[slow]"), std::string::npos) << one.out;
  const auto j = nlohmann::json::parse(std::ifstream(dir / "slow" / "crane.json"));
  EXPECT_EQ(j["load_case"], "slow");
  ASSERT_EQ(j["rows"].size(), 1u);
  EXPECT_DOUBLE_EQ(j["rows"][0]["vh_m_s"].get<double>(), 0.1);
  const double expected = 1 + 0.1 * std::sqrt(1e6 / 1000.0) / 9.81;
  EXPECT_NEAR(j["rows"][0]["simulated"].get<double>(), expected, 1e-9 * expected);

  const auto off = test::run_cli("crane '" + model + "' --case off -o '" + dir.string() + "'");
  EXPECT_EQ(off.exit_code, 2);
  EXPECT_NE(off.err.find("load case 'off'"), std::string::npos) << off.err;

  const auto bad = test::run_cli("crane '" + model + "' --all-cases -o '" + (dir / "all").string() + "'");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("load case 'short'"), std::string::npos) << bad.err;
  EXPECT_NE(bad.err.find("does not lift the load"), std::string::npos) << bad.err;
  EXPECT_FALSE(fs::exists(dir / "all" / "slow" / "crane.json"));  // all or nothing

  const std::string fixed = test::write_temp("hoist-cases-ok.yaml", std::string(kHoistCases) + "    crane: none\n");
  const auto all = test::run_cli("crane '" + fixed + "' --all-cases -o '" + (dir / "ok").string() + "'");
  ASSERT_EQ(all.exit_code, 0) << all.err;
  EXPECT_NE(all.out.find("[slow]"), std::string::npos) << all.out;
  EXPECT_NE(all.out.find("load case 'off': no 'crane:' section"), std::string::npos) << all.out;
  EXPECT_NE(all.out.find("load case 'short': no 'crane:' section"), std::string::npos) << all.out;
  EXPECT_TRUE(fs::exists(dir / "ok" / "slow" / "crane.json"));

  const auto rep = test::run_cli("report '" + model + "' --all-cases --quiet -o '" + (dir / "r.html").string() + "'");
  EXPECT_EQ(rep.exit_code, 2);
  EXPECT_NE(rep.err.find("load case 'short'"), std::string::npos) << rep.err;
}

}  // namespace
}  // namespace machdyn
