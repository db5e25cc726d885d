// `machdyn sweep` as a user runs it: input errors before any run, a kill and Ctrl-C halfway then
// --resume, and 2 MPI ranks — each compared byte for byte with an uninterrupted 1-thread table.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include "machdyn/sweep/mpi.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::slurp;

namespace fs = std::filesystem;


long count_lines(const fs::path& p) {
  const auto s = slurp(p);
  return static_cast<long>(std::count(s.begin(), s.end(), '\n'));
}

/// Runs a shell command in the test's temp dir; returns its exit status (or -1).
int sh(const std::string& cmd) {
  const int status = std::system(("cd '" + test::temp_dir().string() + "' || exit 1; " + cmd).c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string cli() { return "'" + std::string(MACHDYN_CLI) + "'"; }

// 40 runs of ~10 ms each on one thread: slow enough to interrupt halfway.
const std::string kSlowSweep = " sweep '" + test::example("hoist-3mass.yaml") +
                               "' --set simulation.t_end=15 --set simulation.dt_out=0.01"
                               " --vary c1.stiffness=1e4:5e4:8 --vary \"I3.inertia=0.2 kg*m^2:0.4 kg*m^2:5\"";

/// The uninterrupted reference table, computed once on one thread.
const std::string& reference_table() {
  static const std::string table = [] {
    const auto r = test::run_cli(kSlowSweep + " --jobs 1 -o ref");
    EXPECT_EQ(r.exit_code, 0) << r.err;
    EXPECT_NE(r.out.find("sweep: 40 runs, 40 ok"), std::string::npos) << r.out;
    return slurp(test::temp_dir() / "ref" / "sweep.csv");
  }();
  return table;
}

/// Starts the slow sweep in the background, waits until its journal holds `rows` rows, sends
/// `signal`, and returns the exit status of the sweep.
int interrupt_after(const std::string& dir, int rows, const char* signal) {
  const std::string script = cli() + kSlowSweep + " --jobs 1 -o " + dir + " >" + dir + ".out 2>" + dir +
                             ".err & pid=$!; for i in $(seq 1 2000); do n=$(cat " + dir +
                             "/sweep.journal 2>/dev/null | wc -l); [ \"$n\" -gt " + std::to_string(rows) +
                             " ] && break; sleep 0.005; done; kill -" + signal + " $pid; wait $pid";
  return sh(script);
}

// Claim: an unknown element and a unit that does not fit are reported before any run (exit 2),
// and nothing is written.
TEST(SweepCli, InputErrorsExitTwoBeforeAnyRun) {
  const auto model = test::example("hoist-3mass.yaml");
  auto r = test::run_cli("sweep '" + model + "' --vary c7.stiffness=1:2:3 -o bad1");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no element named 'c7'"), std::string::npos) << r.err;
  r = test::run_cli("sweep '" + model + "' --vary \"c1.stiffness=2 mm:8 mm:4\" -o bad2");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("does not fit c1.stiffness"), std::string::npos) << r.err;
  r = test::run_cli("sweep '" + model + "' --vary c1.stiffness=1:2:3 --plot c1.nothing -o bad3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_FALSE(fs::exists(test::temp_dir() / "bad1"));
  EXPECT_FALSE(fs::exists(test::temp_dir() / "bad2"));
  EXPECT_FALSE(fs::exists(test::temp_dir() / "bad3"));
}

// Claim: a sweep killed (SIGKILL) halfway keeps its finished rows in the journal, writes no table,
// and `--resume` completes it to a table byte-identical to an uninterrupted sweep.
TEST(SweepCli, KilledHalfwayThenResumedGivesSameTable) {
  const auto& ref = reference_table();
  interrupt_after("killed", 8, "KILL");
  const auto dir = test::temp_dir() / "killed";
  ASSERT_FALSE(fs::exists(dir / "sweep.csv")) << "the sweep finished before the kill; make it slower";
  const long journaled = count_lines(dir / "sweep.journal") - 1;
  EXPECT_GE(journaled, 8);
  EXPECT_LT(journaled, 40);
  const auto r = test::run_cli(kSlowSweep + " --jobs 2 -o killed --resume");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("resumed: "), std::string::npos) << r.err;
  EXPECT_EQ(slurp(dir / "sweep.csv"), ref);
  EXPECT_EQ(count_lines(dir / "sweep.journal"), 41);  // header + 40 rows: none lost, none twice
}

// Claim: Ctrl-C (SIGINT) stops cleanly — exit 130, a message how to continue, no table — and
// --resume completes the same table.
TEST(SweepCli, CtrlCStopsCleanlyAndResumes) {
  const auto& ref = reference_table();
  const int rc = interrupt_after("ctrlc", 5, "INT");
  const auto dir = test::temp_dir() / "ctrlc";
  ASSERT_FALSE(fs::exists(dir / "sweep.csv")) << "the sweep finished before Ctrl-C; make it slower";
  EXPECT_EQ(rc, 130);
  EXPECT_NE(slurp(test::temp_dir() / "ctrlc.err").find("--resume"), std::string::npos);
  const auto r = test::run_cli(kSlowSweep + " -o ctrlc --resume");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(dir / "sweep.csv"), ref);
}

// Claim: under `mpirun -np 2` the runs are split over two ranks and rank 0 writes one table,
// byte-identical to the 1-thread table.
TEST(SweepCli, TwoMpiRanksGiveSameTable) {
  if (!MpiSession::built()) GTEST_SKIP() << "built without MPI (install libopenmpi-dev and reconfigure)";
  if (sh("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun not found (apt-get install openmpi-bin)";
  const auto& ref = reference_table();
  const int rc = sh("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 "
                    "mpirun -np 2 --oversubscribe " + cli() + kSlowSweep + " --jobs 1 -o mpi2 >mpi2.out 2>mpi2.err");
  ASSERT_EQ(rc, 0) << slurp(test::temp_dir() / "mpi2.err");
  const auto out = slurp(test::temp_dir() / "mpi2.out");
  EXPECT_NE(out.find("1 thread(s) × 2 rank(s)"), std::string::npos) << out;
  EXPECT_EQ(slurp(test::temp_dir() / "mpi2" / "sweep.csv"), ref);
}

// Claim: a sampled sweep from the command line reproduces from its seed, and writes plot data.
TEST(SweepCli, LhsFromTheCommandLineReproduces) {
  const std::string args = " sweep '" + test::example("hoist-3mass.yaml") +
                           "' --set simulation.t_end=0.1 --method lhs --samples 12 --seed 7"
                           " --vary c1.stiffness=1e4:5e4:log --vary c2.stiffness=5e3:2e4 --plot c1.max_N_m";
  ASSERT_EQ(test::run_cli(args + " -o lhs1").exit_code, 0);
  const auto r = test::run_cli(args + " -o lhs2 --jobs 1");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(slurp(test::temp_dir() / "lhs1" / "sweep.csv"), slurp(test::temp_dir() / "lhs2" / "sweep.csv"));
  EXPECT_EQ(count_lines(test::temp_dir() / "lhs1" / "sweep.csv"), 13);
  EXPECT_EQ(count_lines(test::temp_dir() / "lhs1" / "plot-c1.max_N_m-vs-c1.stiffness-vs-c2.stiffness.csv"), 13);
}

// Claim: --all-cases runs every point for each of the eleven hoist modes (case outermost, a `case`
// column), --plot writes the data, an SVG holding the curve names and a PNG; --case with
// --all-cases and an unknown case are input errors.
TEST(SweepCli, AllCasesOfTheHoistModesWithPlot) {
  const std::string args = " sweep '" + test::example("hoist-modes.yaml") +
                           "' --set simulation.t_end=0.1 --vary \"MB.value=-300 N*m,-240 N*m\" --all-cases";
  auto r = test::run_cli(args + " --plot c1.dynamic_factor -o modes");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.err.find("grid 2 = 2 runs × 11 cases = 22 runs"), std::string::npos) << r.err;
  const auto table = slurp(test::temp_dir() / "modes" / "sweep.csv");
  EXPECT_EQ(count_lines(test::temp_dir() / "modes" / "sweep.csv"), 23);
  EXPECT_EQ(table.substr(0, 24), "run,case,MB.value,c1.max");
  EXPECT_NE(table.find("\n21,braked_lowering,-240,"), std::string::npos);
  const auto stem = test::temp_dir() / "modes" / "plot-c1.dynamic_factor-vs-MB.value-vs-case";
  EXPECT_EQ(count_lines(stem.string() + ".csv"), 23);
  if (sh("command -v gnuplot >/dev/null 2>&1") == 0) {
    EXPECT_NE(slurp(stem.string() + ".svg").find("dynamic factor of c1"), std::string::npos);
    EXPECT_NE(slurp(stem.string() + ".svg").find("braked_lowering"), std::string::npos);
    EXPECT_EQ(slurp(stem.string() + ".png").substr(1, 3), "PNG");
  }
  r = test::run_cli(args + " --case accel_up -o modes2");
  EXPECT_EQ(r.exit_code, 2);
  r = test::run_cli(" sweep '" + test::example("hoist-modes.yaml") + "' --vary MB.value=-300,-240 --case hover -o modes3");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("no case named 'hover'"), std::string::npos) << r.err;
}

// Claim: a case sweep over hybrid and smooth modes gives the same table on 1 thread, 2 threads and
// 2 MPI ranks.
TEST(SweepCli, CaseSweepIdenticalForThreadsAndRanks) {
  const std::string args = " sweep '" + test::example("hoist-modes.yaml") +
                           "' --set simulation.t_end=0.2 --vary MB.value=-300,-270,-240 --all-cases";
  ASSERT_EQ(test::run_cli(args + " --jobs 1 -o cases1").exit_code, 0);
  ASSERT_EQ(test::run_cli(args + " --jobs 2 -o cases2").exit_code, 0);
  const auto ref = slurp(test::temp_dir() / "cases1" / "sweep.csv");
  EXPECT_EQ(count_lines(test::temp_dir() / "cases1" / "sweep.csv"), 34);
  EXPECT_EQ(slurp(test::temp_dir() / "cases2" / "sweep.csv"), ref);
  if (!MpiSession::built() || sh("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "no MPI: ranks not checked";
  const int rc = sh("OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 "
                    "mpirun -np 2 --oversubscribe " + cli() + args + " --jobs 1 -o cases-mpi >cases-mpi.out 2>cases-mpi.err");
  ASSERT_EQ(rc, 0) << slurp(test::temp_dir() / "cases-mpi.err");
  EXPECT_EQ(slurp(test::temp_dir() / "cases-mpi" / "sweep.csv"), ref);
}

}  // namespace
}  // namespace machdyn
