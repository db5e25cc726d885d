// The command line as a user meets it: exit codes, files written (or not), JSON, --set, help.
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

namespace fs = std::filesystem;

// Claim: simulate writes timeseries.csv with a header naming every body and link, and
// summary.json with links {max, min, t_max, static, dynamic_factor} and solver statistics.
TEST(Cli, SimulateWritesCsvAndSummary) {
  const auto dir = test::temp_dir() / "sim-out";
  const auto r = test::run_cli("simulate '" + test::example("hoist-3mass.yaml") + "' -o '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream csv(dir / "timeseries.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "t_s,I1.position_rad,I1.velocity_rad_s,I2.position_rad,I2.velocity_rad_s,I3.position_rad,"
            "I3.velocity_rad_s,c1.load_N_m,c2.load_N_m");
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, 1001);  // t_end 0.5 s, dt_out 0.5 ms, both ends
  const auto j = nlohmann::json::parse(std::ifstream(dir / "summary.json"));
  for (const char* key : {"max", "min", "t_max", "static", "dynamic_factor"}) EXPECT_TRUE(j["links"]["c1"].contains(key)) << key;
  for (const char* key : {"steps", "rhs_evals", "wall_time_s", "method"}) EXPECT_TRUE(j["solver"].contains(key)) << key;
  EXPECT_NEAR(j["links"]["c1"]["static"].get<double>(), 354.0, 1e-9);
}

// Claim: --json prints the summary to stdout; --set changes the run (a stiffer c1 raises ω2).
TEST(Cli, JsonOutputAndSetOverrides) {
  const auto r = test::run_cli("simulate '" + test::example("hoist-3mass.yaml") + "' --json -o out1 --set simulation.t_end=0.1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_DOUBLE_EQ(j["settings"]["t_end_s"].get<double>(), 0.1);
  const auto m1 = nlohmann::json::parse(test::run_cli("modes '" + test::example("hoist-3mass.yaml") + "' --json").out);
  const auto m2 = nlohmann::json::parse(
      test::run_cli("modes '" + test::example("hoist-3mass.yaml") + "' --json --set c1.stiffness=\"48 kN*m/rad\"").out);
  EXPECT_EQ(m1["rigid_body_modes"], 1);
  EXPECT_EQ(m1["frequencies_rad_s"].size(), 2u);
  EXPECT_GT(m2["frequencies_rad_s"][1].get<double>(), m1["frequencies_rad_s"][1].get<double>());
  EXPECT_EQ(m1["shapes"].size(), 2u);
  EXPECT_NEAR(m1["frequencies_hz"][0].get<double>() * 2 * 3.14159265358979323846,
              m1["frequencies_rad_s"][0].get<double>(), 1e-9);
}

// Claim: bad input exits with 2, says file:line:col, and writes no result file or folder.
TEST(Cli, BadInputExitsTwoWithPlaceAndWritesNothing) {
  const auto bad = test::write_temp("bad.yaml", "bodies:\n  A: {inertia: -2}\nlinks:\n  c: {type: spring, between: [A, B], stiffness: 1}\n");
  const auto dir = test::temp_dir() / "never";
  const auto r = test::run_cli("simulate '" + bad + "' -o '" + dir.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find(bad + ":2:16: error: body 'A': field 'inertia' must be zero or positive"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find(bad + ":4:34: error: link 'c': unknown body 'B'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir));
  const auto s = test::run_cli("modes '" + test::example("hoist-3mass.yaml") + "' --set c9.stiffness=1");
  EXPECT_EQ(s.exit_code, 2);
  EXPECT_NE(s.err.find("no element named 'c9'"), std::string::npos) << s.err;
  EXPECT_EQ(test::run_cli("simulate /nonexistent/model.yaml").exit_code, 2);
  EXPECT_EQ(test::run_cli("simulate").exit_code, 2);
  EXPECT_EQ(test::run_cli("frobnicate").exit_code, 2);
}

// Claim: a numerical failure exits with 3, names the element and time, and writes no result file.
TEST(Cli, NumericalFailureExitsThreeAndWritesNothing) {
  const auto dir = test::temp_dir() / "failed";
  const auto r = test::run_cli("simulate '" + test::example("hoist-3mass.yaml") + "' -o '" + dir.string() +
                               "' --set simulation.max_steps=20");
  EXPECT_EQ(r.exit_code, 3);
  // The step limit names the state that held the steps short (here a body's), not "integrator".
  EXPECT_NE(r.err.find("numerical failure in 'body '"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("' at t = "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("the maximum number of steps was reached"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir / "timeseries.csv"));
}

// Claim: every command has --help; --version prints the version; examples lists the hoist.
TEST(Cli, HelpVersionAndExamples) {
  for (const char* cmd : {"", "simulate ", "modes ", "examples ", "demo "}) {
    const auto r = test::run_cli(std::string(cmd) + "--help");
    EXPECT_EQ(r.exit_code, 0) << cmd;
    EXPECT_NE(r.out.find("Usage"), std::string::npos) << cmd;
  }
  const auto v = test::run_cli("--version");
  EXPECT_EQ(v.exit_code, 0);
  EXPECT_NE(v.out.find("machdyn " MACHDYN_VERSION), std::string::npos) << v.out;
  const auto e = test::run_cli("examples");
  EXPECT_EQ(e.exit_code, 0);
  EXPECT_NE(e.out.find("hoist-3mass.yaml"), std::string::npos);
  EXPECT_NE(e.out.find("Three-mass hoist"), std::string::npos);
  // The sub-folders are listed by their relative path, and no description speaks of the project's issues.
  EXPECT_NE(e.out.find("crane/main-hoist.yaml"), std::string::npos) << e.out;
  EXPECT_NE(e.out.find("msl/first.yaml"), std::string::npos) << e.out;
  EXPECT_EQ(e.out.find("issue"), std::string::npos) << e.out;
}

// Claim: demo runs the default example and writes its results.
TEST(Cli, DemoRunsTheHoist) {
  const auto r = test::run_cli("demo -o demo-out");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("rigid-body modes: 1"), std::string::npos);
  EXPECT_TRUE(fs::exists(test::temp_dir() / "demo-out" / "summary.json"));
}

}  // namespace
}  // namespace machdyn
