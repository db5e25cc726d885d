// The bounds of issue 28 as a user meets them on the command line: every command that takes the
// model refuses it alike (exit 2, file:line:col, nothing written), and a model without a
// `simulation:` section runs with the section's defaults and takes `--set` / `--vary` of it.
#include <filesystem>
#include <string>
#include <gtest/gtest.h>

#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

namespace fs = std::filesystem;

std::string quoted(const std::string& s) { return "'" + s + "'"; }

const char* kOverflowingGears =
    "bodies:\n"
    "  A: {type: rotational, inertia: 1 kg*m^2}\n"
    "  B: {type: rotational, inertia: 1 kg*m^2}\n"
    "  C: {type: rotational, inertia: 1 kg*m^2}\n"
    "  D: {type: rotational, inertia: 1 kg*m^2}\n"
    "links:\n"
    "  g1: {type: ideal-gear, between: [A, B], ratio: 1e85}\n"
    "  g2: {type: ideal-gear, between: [B, C], ratio: 1e85}\n"
    "  g3: {type: ideal-gear, between: [C, D], ratio: 1e85}\n"
    "  c1: {type: spring, between: [D, ground], stiffness: 100 N*m/rad}\n"
    "loads:\n"
    "  L: {type: constant, body: A, value: 1 N*m}\n"
    "simulation: {t_end: 0.1 s}\n";

// Claim: the gear chain whose ratio product overflows (a SIGSEGV before) is refused by simulate,
// modes, report and sweep with exit 2 at g2's line (8), and none writes its output folder.
TEST(BoundsCli, OverflowingGearChainsAreRefusedByEveryCommand) {
  const std::string model = test::write_temp("gears-1e85.yaml", kOverflowingGears);
  const fs::path out = test::temp_dir() / "gears-out";
  for (const std::string& cmd : {"simulate " + quoted(model) + " -o " + quoted(out.string()),
                                "modes " + quoted(model),
                                "report " + quoted(model) + " -o " + quoted(out.string()),
                                "sweep " + quoted(model) + " --vary c1.stiffness=1:2:2 -o " + quoted(out.string())}) {
    const auto r = test::run_cli(cmd);
    EXPECT_EQ(r.exit_code, 2) << cmd << "\n" << r.err;
    EXPECT_NE(r.err.find(model + ":8:"), std::string::npos) << cmd << "\n" << r.err;
  }
  EXPECT_FALSE(fs::exists(out));
}

// Claim: a sine of 1e300 Hz (a run of hours before) is refused by simulate and modes alike, at
// its frequency (line 6), exit 2.
TEST(BoundsCli, AnUnfollowableSineIsRefusedBySimulateAndModes) {
  const std::string model = test::write_temp(
      "sine-1e300.yaml",
      "bodies:\n  I1: {type: rotational, inertia: 1 kg*m^2}\nlinks:\n"
      "  c1: {type: spring, between: [I1, ground], stiffness: 100 N*m/rad}\nloads:\n"
      "  L: {type: sine, body: I1, amplitude: 1 N*m, frequency: 1e300 Hz}\nsimulation: {t_end: 1 s}\n");
  for (const std::string& cmd : {"simulate " + quoted(model) + " -o sine-out", "modes " + quoted(model)}) {
    const auto r = test::run_cli(cmd);
    EXPECT_EQ(r.exit_code, 2) << cmd << "\n" << r.err;
    EXPECT_NE(r.err.find(model + ":6:"), std::string::npos) << cmd << "\n" << r.err;
  }
}

// Claim: `energy --to` beyond 1e6 periods (turns of 2π rad without a period) is refused at --to,
// exit 2 (1e300 printed a meaningless table, or std::bad_alloc for the crank); a near --to runs.
// The free body I = 2 kg·m², ω0 = 1 rad/s under 3 N·m: ω(10 rad) = √(1 + 2·3·10/2) = √31 rad/s.
TEST(BoundsCli, EnergyScansAreBounded) {
  const std::string model = test::write_temp(
      "energy-free.yaml", "bodies:\n  I1: {type: rotational, inertia: 2 kg*m^2, velocity: 1 rad/s}\n"
                          "loads:\n  L: {type: constant, body: I1, value: 3 N*m}\n");
  const auto far = test::run_cli("energy " + quoted(model) + " --to 1e300 -o energy-far");
  EXPECT_EQ(far.exit_code, 2) << far.err;
  EXPECT_NE(far.err.find("--to"), std::string::npos) << far.err;
  EXPECT_FALSE(fs::exists(test::temp_dir() / "energy-far"));
  const auto crank = test::run_cli("energy " + quoted(test::example("crank-slider.yaml")) + " --to 1e300 -o energy-crank");
  EXPECT_EQ(crank.exit_code, 2) << crank.err;
  const auto near = test::run_cli("energy " + quoted(model) + " --to 10 --json -o energy-near");
  ASSERT_EQ(near.exit_code, 0) << near.err;
  EXPECT_NE(near.out.find("\"omega_max\""), std::string::npos);
  EXPECT_NE(near.out.find("5.56776436283"), std::string::npos) << near.out;  // √31 = 5.567764362830022
}

// Claim: a sweep of more than 10^6 runs is refused before its plan is built (10^8 were allowed and
// ran out of memory listing them: some 230 bytes a run), as a grid and as --samples, exit 2.
TEST(BoundsCli, SweepsAreBoundedInRuns) {
  const std::string model = quoted(test::example("hoist-3mass.yaml"));
  const auto grid = test::run_cli("sweep " + model + " --vary c1.stiffness=1e4:2e4:1000001 -o big-grid");
  EXPECT_EQ(grid.exit_code, 2) << grid.err;
  EXPECT_NE(grid.err.find("more than 1000000 runs"), std::string::npos) << grid.err;
  const auto lhs = test::run_cli("sweep " + model + " --vary c1.stiffness=1e4:2e4 --method lhs --samples 1000001 -o big-lhs");
  EXPECT_EQ(lhs.exit_code, 2) << lhs.err;
  EXPECT_FALSE(fs::exists(test::temp_dir() / "big-grid" / "sweep.csv"));
}

const char* kNoSimulation =
    "bodies:\n  I1: {type: rotational, inertia: 1 kg*m^2}\nlinks:\n"
    "  c1: {type: spring, between: [I1, ground], stiffness: 100 N*m/rad}\n"
    "loads:\n  L: {type: constant, body: I1, value: 1 N*m}\n";

// Claim: a model without `simulation:` writes the default grid (t_end 1 s, dt_out = t_end/1000:
// 1001 rows, not 2), takes --set simulation.t_end=2 (1001 rows to t = 2 s) and sweeps
// --vary simulation.rtol as the README promises.
TEST(BoundsCli, AModelWithoutSimulationSectionRunsWithItsDefaults) {
  const std::string model = test::write_temp("no-simulation.yaml", kNoSimulation);
  const fs::path dir = test::temp_dir();
  const auto r = test::run_cli("simulate " + quoted(model) + " -o nosim-1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto rows = test::lines_of(test::slurp(dir / "nosim-1" / "timeseries.csv"));
  EXPECT_EQ(rows.size(), 1002u);  // header and t = 0, 1 ms, ..., 1 s
  const auto r2 = test::run_cli("simulate " + quoted(model) + " -o nosim-2 --set simulation.t_end=2");
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  rows = test::lines_of(test::slurp(dir / "nosim-2" / "timeseries.csv"));
  ASSERT_EQ(rows.size(), 1002u);
  EXPECT_EQ(rows.back().substr(0, rows.back().find(',')), "2");
  const auto s = test::run_cli("sweep " + quoted(model) + " --vary simulation.rtol=1e-6,1e-8 -o nosim-sweep");
  ASSERT_EQ(s.exit_code, 0) << s.err;
  rows = test::lines_of(test::slurp(dir / "nosim-sweep" / "sweep.csv"));
  EXPECT_EQ(rows.size(), 3u);
}

}  // namespace
}  // namespace machdyn
