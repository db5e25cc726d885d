// Results that are never lost or left half-written, at the command line: one output-folder
// convention for --case and --all-cases, --all-cases all or nothing, an output-size limit before
// the run, and a full disk (a file-size limit) as a clear error with nothing truncated left behind.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/output_file.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

namespace fs = std::filesystem;

/// Every file under `dir` whose name holds ".tmp." (a temporary file left behind).
std::vector<std::string> temp_files(const fs::path& dir) {
  std::vector<std::string> left;
  if (!fs::exists(dir)) return left;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().find(".tmp.") != std::string::npos) left.push_back(e.path().string());
  return left;
}

// A two-mass model with two cases; `late` fails numerically (too few steps allowed).
const char* kTwoCases = R"(name: two cases
bodies:
  A: {type: translational, mass: 1 kg}
  B: {type: translational, mass: 2 kg}
links:
  c: {type: spring, between: [A, B], stiffness: 1e4 N/m}
loads:
  P: {type: constant, body: A, value: 10 N}
simulation: {t_end: 0.5 s}
cases:
  early: {description: fine}
  late:
    description: runs out of steps
    simulation: {max_steps: 3}
)";

// Claim: `simulate --case NAME` writes to OUT/NAME/ — the folder `--all-cases` gives that case —
// with and without -o, and nothing into OUT itself.
TEST(OutputCli, CaseFolderIsTheSameForCaseAndAllCases) {
  const auto cwd = test::temp_dir() / "case-folder";
  fs::create_directories(cwd);
  const std::string model = test::example("hoist-modes.yaml");
  auto r = test::run_cli("simulate '" + model + "' --case coast_up --quiet", cwd);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(cwd / "out/hoist-modes/coast_up/summary.json"));
  EXPECT_TRUE(fs::exists(cwd / "out/hoist-modes/coast_up/timeseries.csv"));
  EXPECT_FALSE(fs::exists(cwd / "out/hoist-modes/summary.json"));
  r = test::run_cli("simulate '" + model + "' --case coast_up --quiet -o mine", cwd);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(cwd / "mine/coast_up/summary.json"));
  EXPECT_NE(r.out.find("mine/coast_up/timeseries.csv"), std::string::npos) << r.out;
  // The same case from --all-cases lands in the same place with the same numbers.
  r = test::run_cli("simulate '" + model + "' --all-cases -o all", cwd);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto one = nlohmann::json::parse(test::slurp(cwd / "mine/coast_up/summary.json"));
  const auto from_all = nlohmann::json::parse(test::slurp(cwd / "all/coast_up/summary.json"));
  EXPECT_EQ(one["case"], from_all["case"]);
}

// Claim: --all-cases where a later case fails numerically writes nothing (no earlier case's files,
// no cases.json), exits 3, and names the failing case; the same file with the failing case fixed
// writes every case.
TEST(OutputCli, AllCasesWritesNothingWhenACaseFails) {
  const auto model = test::write_temp("two-cases.yaml", kTwoCases);
  const auto dir = test::temp_dir() / "all-or-nothing";
  auto r = test::run_cli("simulate '" + model + "' --all-cases -o '" + dir.string() + "'");
  EXPECT_EQ(r.exit_code, 3) << r.err;
  EXPECT_NE(r.err.find("case 'late' (2 of 2) failed; no result of this run was written"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir)) << "results left behind by a failed --all-cases";
  std::string fixed = kTwoCases;
  fixed.replace(fixed.find("max_steps: 3"), 12, "max_steps: 100000");
  const auto good = test::write_temp("two-cases-fixed.yaml", fixed);
  r = test::run_cli("simulate '" + good + "' --all-cases -o '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"early/timeseries.csv", "early/summary.json", "late/timeseries.csv", "late/summary.json", "cases.json"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
}

// Claim: the size estimate made before the run has exactly the rows and the columns the run
// writes (t_end/dt_out + 1 output times for this smooth chain), and its byte count is within a factor 2 of the real CSV (24 bytes per number is an
// upper estimate of "%.17g," for numbers that are not round).
TEST(OutputCli, SizeEstimateMatchesTheWrittenTimeSeries) {
  const auto dir = test::temp_dir() / "estimate";
  const std::string model = test::example("hoist-3mass.yaml");
  const auto r = test::run_cli("simulate '" + model + "' --quiet --set simulation.dt_out=1e-3 -o '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string csv = test::slurp(dir / "timeseries.csv");
  const auto lines = test::lines_of(csv);
  const auto header_columns = static_cast<std::uint64_t>(std::count(lines[0].begin(), lines[0].end(), ',') + 1);
  const OutputEstimate e = estimate_timeseries(load_model(model, {"simulation.dt_out=1e-3"}));
  EXPECT_EQ(e.rows, lines.size() - 1);
  EXPECT_EQ(e.columns, header_columns);
  EXPECT_LE(static_cast<double>(csv.size()), 1.2 * static_cast<double>(e.csv_bytes));
  EXPECT_GE(static_cast<double>(csv.size()), 0.5 * static_cast<double>(e.csv_bytes));
}

// Claim: a time series above the limit (the issue's `dt_out = 1e-7`) is refused before the run
// with exit 2, its estimated size and both ways out, and writes nothing — by simulate, by
// simulate --all-cases (the sum of the cases) and by report; a small one passes.
TEST(OutputCli, OversizeTimeSeriesIsRefusedBeforeTheRun) {
  const auto dir = test::temp_dir() / "oversize";
  const std::string model = test::example("hoist-3mass.yaml");
  const auto r = test::run_cli("simulate '" + model + "' --quiet --set simulation.dt_out=1e-7 -o '" + dir.string() + "'");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  for (const char* s : {"hoist-3mass.yaml: error: the time series would be about 1.08 GB", "5000001 rows × 9 columns",
                        "raise simulation.dt_out", "--large-output"})
    EXPECT_NE(r.err.find(s), std::string::npos) << s << "\n" << r.err;
  EXPECT_FALSE(fs::exists(dir));
  const auto all = test::run_cli("simulate '" + test::example("hoist-modes.yaml") +
                                 "' --all-cases --set simulation.dt_out=1e-6 -o '" + dir.string() + "'");
  EXPECT_EQ(all.exit_code, 2) << all.err;
  EXPECT_NE(all.err.find("--all-cases: the time series of the 11 cases would be about"), std::string::npos) << all.err;
  EXPECT_FALSE(fs::exists(dir));
  const auto rep = test::run_cli("report '" + model + "' --quiet --set simulation.dt_out=1e-7 -o '" +
                                 (dir / "r.html").string() + "'");
  EXPECT_EQ(rep.exit_code, 2) << rep.err;
  EXPECT_NE(rep.err.find("the report would embed about 1.08 GB"), std::string::npos) << rep.err;
  EXPECT_FALSE(fs::exists(dir));
  // The library check with a small limit, against the same estimate.
  const Model m = load_model(model);
  const auto e = estimate_timeseries(m);
  EXPECT_NO_THROW(check_output_size(m, e.csv_bytes, "--x"));
  EXPECT_THROW(check_output_size(m, e.csv_bytes - 1, "--x"), InputError);
}

// Claim: when the disk is full while writing (here: the file-size limit `ulimit -f` is reached,
// with SIGXFSZ ignored so write() fails with EFBIG) the run ends with exit 1 and a message naming
// the file and the cause, no temporary file is left, and the earlier result stays intact.
TEST(OutputCli, FullDiskIsAClearErrorAndKeepsTheEarlierFile) {
  const auto dir = test::temp_dir() / "full-disk";
  const std::string model = test::example("hoist-3mass.yaml");
  auto ok = test::run_cli("simulate '" + model + "' --quiet --set simulation.dt_out=1e-3 -o '" + dir.string() + "'");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const std::string before = test::slurp(dir / "timeseries.csv");
  ASSERT_GT(before.size(), 20u * 1024u);
  const auto err_file = test::temp_dir() / "full-disk.err";
  // ulimit -f counts 1024-byte blocks: 20 kB is less than the ~100 kB series.
  const std::string cmd = "trap '' XFSZ; ulimit -f 20; '" + std::string(MACHDYN_CLI) + "' simulate '" + model +
                          "' --quiet --set simulation.dt_out=1e-4 -o '" + dir.string() + "' >/dev/null 2>'" +
                          err_file.string() + "'";
  const int status = std::system(cmd.c_str());  // /bin/sh -c
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 1);
  const std::string err = test::slurp(err_file);
  EXPECT_NE(err.find("cannot write " + (dir / "timeseries.csv").string() + ": File too large"), std::string::npos) << err;
  EXPECT_EQ(test::slurp(dir / "timeseries.csv"), before);
  EXPECT_TRUE(temp_files(dir).empty());
}

}  // namespace
}  // namespace machdyn
