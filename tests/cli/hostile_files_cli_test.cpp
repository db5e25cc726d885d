// Files and processes under hostile input (issue 28): case names that are paths, outputs over the
// input files or over devices, two runs in one output folder, the file-size limit, model files
// that are devices, FIFOs or huge, names that break CSV, and sweeps whose every run is refused.
// Every test runs in its own scratch folder under test::temp_dir() and checks what was written.
#include <chrono>
#include <csignal>
#include <memory>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <string>
#include <thread>
#include <utility>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>
#include <gtest/gtest.h>

#include "machdyn/common/csv.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/folder_lock.hpp"
#include "machdyn/io/input_file.hpp"
#include "machdyn/io/output_file.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

namespace fs = std::filesystem;

/// A fresh, empty scratch folder.
fs::path scratch(const std::string& name) {
  const auto d = test::temp_dir() / "hostile" / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// Every file and folder under `dir`, as paths relative to it.
std::set<std::string> tree(const fs::path& dir) {
  std::set<std::string> all;
  for (const auto& e : fs::recursive_directory_iterator(dir)) all.insert(fs::relative(e.path(), dir).string());
  return all;
}

/// Every file under `dir` whose name holds ".tmp." (a temporary file left behind).
std::vector<std::string> temp_files(const fs::path& dir) {
  std::vector<std::string> left;
  for (const auto& e : fs::recursive_directory_iterator(dir))
    if (e.path().filename().string().find(".tmp.") != std::string::npos) left.push_back(e.path().string());
  return left;
}

/// Runs `script` with bash -c (the machdyn binary is $M), stdout and stderr kept. No signal is
/// ignored on the way (unlike a shell `trap`), so the command meets SIGXFSZ as a user's would.
test::CliResult run_bash(const std::string& script, const fs::path& cwd) {
  static int counter = 0;
  const auto base = test::temp_dir() / (std::string("bash-") + std::to_string(++counter));
  std::ofstream(base.string() + ".sh") << "M='" << MACHDYN_CLI << "'\ncd '" << cwd.string() << "' || exit 99\n"
                                        << script << "\n";
  const std::string cmd = "bash '" + base.string() + ".sh' >'" + base.string() + ".out' 2>'" + base.string() +
                          ".err' </dev/null";
  const int status = std::system(cmd.c_str());
  test::CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = test::slurp(base.string() + ".out");
  r.err = test::slurp(base.string() + ".err");
  return r;
}

/// 'text' (built by appending: GCC 12 at -O3 warns falsely, -Wrestrict, on "'" + a temporary).
std::string single_quoted(const std::string& text) {
  std::string q(1, '\'');
  q += text;
  q += '\'';
  return q;
}

// A two-mass model; the case below it (line 9) gets the name under test.
std::string model_with_case(const std::string& yaml_key) {
  return R"(name: named cases
bodies:
  A: {type: translational, mass: 1 kg}
  B: {type: translational, mass: 2 kg}
links:
  c: {type: spring, between: [A, B], stiffness: 1e4 N/m}
simulation: {t_end: 0.05 s}
cases:
  )" + yaml_key + R"(: {description: hostile}
  fine: {description: a plain name}
)";
}

// Claim: a case name that is a path, or no plain name, is a located error (model.yaml:9:3, the
// case's key) with exit 2 in every command that makes a folder or a row of it — `simulate
// --all-cases`, `simulate --case`, `report --case`, `modes --case`, `sweep --case`, `sweep
// --all-cases` — and nothing at all is written: the scratch folder holds only the model afterwards,
// and the absolute target does not exist.
TEST(HostileFiles, CaseNamesThatArePathsAreLocatedErrorsAndWriteNothing) {
  const auto box = scratch("case-names");
  const auto work = box / "a" / "work";
  const auto abs_target = box / "abs-target";
  struct Name {
    std::string key;  ///< as written in YAML
    std::string arg;  ///< as given to --case (shell-quoted)
  };
  const std::vector<Name> names = {
      {"'../../escaped'", "'../../escaped'"},
      {single_quoted(abs_target.string()), single_quoted(abs_target.string())},
      {"'.'", "."},
      {"'..'", ".."},
      {"'sub/dir'", "sub/dir"},
      {"'back\\slash'", "'back\\slash'"},
      {"\"nul\\0byte\"", ""},
      {"\"new\\nline\"", "$'new\\nline'"},
      {single_quoted(std::string(129, 'x')), std::string(129, 'x')},
  };
  for (const auto& n : names) {
    SCOPED_TRACE(n.key);
    fs::remove_all(work);
    fs::create_directories(work);
    std::ofstream(work / "model.yaml") << model_with_case(n.key);
    std::vector<std::string> commands = {"simulate model.yaml --all-cases -o out", "sweep model.yaml --all-cases "
                                                                                   "--vary c.stiffness=1e4,2e4 -o out"};
    if (!n.arg.empty())
      for (const char* c : {"simulate model.yaml --quiet -o out --case ", "report model.yaml --quiet --case ",
                            "modes model.yaml -o out --case ",
                            "sweep model.yaml --vary c.stiffness=1e4,2e4 -o out --case "})
        commands.push_back(c + n.arg);
    for (const auto& cmd : commands) {
      SCOPED_TRACE(cmd);
      const auto r = run_bash("\"$M\" " + cmd, work);
      EXPECT_EQ(r.exit_code, 2) << r.err;
      EXPECT_NE(r.err.find("model.yaml:9:3: error: case '"), std::string::npos) << r.err;
      EXPECT_NE(r.err.find("must be a plain name"), std::string::npos) << r.err;
      EXPECT_EQ(tree(box), (std::set<std::string>{"a", "a/work", "a/work/model.yaml"}));
      EXPECT_FALSE(fs::exists(abs_target));
    }
  }
  // The empty name `''` is one too (as `.`, it would be the output folder itself).
  fs::remove_all(work);
  fs::create_directories(work);
  std::ofstream(work / "model.yaml") << model_with_case("''");
  const auto r = run_bash("\"$M\" simulate model.yaml --all-cases -o out", work);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("model.yaml:9:3: error: case '': the name is empty"), std::string::npos) << r.err;
  EXPECT_EQ(tree(box), (std::set<std::string>{"a", "a/work", "a/work/model.yaml"}));
}

// Claim (control): a name with spaces, a comma, a quote and non-ASCII letters is a plain name: each
// case gets its own folder OUT/NAME, and the `case` cells of the sweep table read back as written.
TEST(HostileFiles, PlainCaseNamesStillWork) {
  const auto work = scratch("plain-case-names");
  std::ofstream(work / "model.yaml") << model_with_case("'up, \"fast\" – Größe'");
  auto r = run_bash("\"$M\" simulate model.yaml --all-cases -o out", work);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::exists(work / "out" / "up, \"fast\" – Größe" / "timeseries.csv"));
  EXPECT_TRUE(fs::exists(work / "out" / "fine" / "summary.json"));
  r = run_bash("\"$M\" sweep model.yaml --all-cases --vary c.stiffness=1e4 -o sw --jobs 1", work);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(work / "sw" / "sweep.csv");
  std::string header, row;
  std::getline(in, header);
  std::getline(in, row);
  EXPECT_EQ(row.substr(0, row.find(",1", 3)), "0,\"up, \"\"fast\"\" – Größe\"") << row;
}

// Claim: `report MODEL -o MODEL` and every other way of naming the model as the output (a
// symbolic link to it, a hard link, another spelling of the path) is refused before the run with
// exit 2, and the model file is unchanged; a FIFO as -o is refused and stays a FIFO.
TEST(HostileFiles, ReportNeverWritesOverItsInputOrAFifo) {
  const auto work = scratch("report-over-input");
  std::ofstream(work / "model.yaml") << model_with_case("'one'");
  const std::string model_text = test::slurp(work / "model.yaml");
  fs::create_symlink(work / "model.yaml", work / "link.html");
  fs::create_hard_link(work / "model.yaml", work / "hard.html");
  fs::create_directories(work / "sub");
  ASSERT_EQ(::mkfifo((work / "fifo.html").c_str(), 0644), 0);
  struct Case {
    std::string out, says;
  };
  for (const Case& c : {Case{"model.yaml", "it is the input file model.yaml of this run"},
                        Case{"./sub/../model.yaml", "it is the input file model.yaml of this run (the same file "
                                                    "under another name)"},
                        Case{"hard.html", "it is the input file model.yaml of this run (the same file under "
                                          "another name)"},
                        Case{"link.html", "it is a symbolic link to " + (work / "model.yaml").string() +
                                              ", the input file model.yaml of this run"},
                        Case{"fifo.html", "it is a FIFO (named pipe)"}}) {
    SCOPED_TRACE(c.out);
    const auto r = run_bash("timeout 60 \"$M\" report model.yaml --quiet -o '" + c.out + "'", work);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("-o " + c.out + ": error: refusing to write the report here: " + c.says), std::string::npos)
        << r.err;
    EXPECT_EQ(test::slurp(work / "model.yaml"), model_text);
  }
  struct stat st {};
  ASSERT_EQ(::lstat((work / "fifo.html").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_TRUE(fs::is_symlink(work / "link.html"));
  EXPECT_TRUE(temp_files(work).empty());
}

// Claim: the guard under every writer (write_file_atomic) refuses a result file that is a link to
// the model (`simulate -o DIR` where DIR/summary.json links to the model: exit 1, model unchanged,
// link kept), and says why a device would be refused — checked on /dev/null by stat alone: no
// test ever writes there.
TEST(HostileFiles, NoResultFileReplacesAnInputOrADevice) {
  const auto work = scratch("result-over-input");
  std::ofstream(work / "model.yaml") << model_with_case("'one'");
  const std::string model_text = test::slurp(work / "model.yaml");
  fs::create_directories(work / "out");
  fs::create_symlink(work / "model.yaml", work / "out" / "summary.json");
  const auto r = run_bash("\"$M\" simulate model.yaml --quiet -o out", work);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("refusing to write out/summary.json: it is a symbolic link to"), std::string::npos) << r.err;
  EXPECT_EQ(test::slurp(work / "model.yaml"), model_text);
  EXPECT_TRUE(fs::is_symlink(work / "out" / "summary.json"));
  EXPECT_TRUE(temp_files(work).empty());
  EXPECT_NE(output_target_problem("/dev/null").find("it is a character device"), std::string::npos);
  EXPECT_NE(output_target_problem(work.string()).find("it is a folder"), std::string::npos);
  EXPECT_EQ(output_target_problem(work / "new-file.csv"), "");
  std::ofstream(work / "plain.csv") << "x\n";
  EXPECT_EQ(output_target_problem(work / "plain.csv"), "");
}

// Claim: a model "file" that is a device, a FIFO (without a writer: no hang) or a folder, or a file
// larger than the limit, is a located error with exit 2 in well under the 60 s timeout, reading no
// more than the limit (a /dev/zero that grew without bound took 1.9 GB).
TEST(HostileFiles, ModelFilesThatAreDevicesFifosOrHugeAreRefused) {
  const auto work = scratch("hostile-model-files");
  ASSERT_EQ(::mkfifo((work / "fifo.yaml").c_str(), 0644), 0);
  fs::create_directories(work / "folder.yaml");
  {
    std::ofstream big(work / "big.yaml");
    big << "name: big\n";
  }
  fs::resize_file(work / "big.yaml", kMaxModelFileBytes + 1);  // sparse: no disk used
  struct Case {
    std::string path, says;
  };
  for (const Case& c : {Case{"/dev/zero", "/dev/zero: error: the file is a character device; expected a regular file"},
                        Case{"fifo.yaml", "fifo.yaml: error: the file is a FIFO (named pipe); expected a regular file"},
                        Case{"folder.yaml", "folder.yaml: error: the file is a folder; expected a regular file"},
                        Case{"big.yaml", "big.yaml: error: the file has 16777217 bytes, more than the limit of 16 MiB"}}) {
    for (const auto& [verb, rest] : std::vector<std::pair<std::string, std::string>>{
             {"simulate", "--quiet"}, {"modes", ""}, {"sweep", "--vary c.stiffness=1,2 -o sw"}}) {
      SCOPED_TRACE(c.path + " " + verb);
      const auto r = run_bash("timeout 60 \"$M\" " + verb + " '" + c.path + "' " + rest, work);
      EXPECT_EQ(r.exit_code, 2) << r.err;
      EXPECT_NE(r.err.find(c.says), std::string::npos) << r.err;
    }
  }
  // The library reader itself: /dev/zero read without a limit would never end.
  try {
    (void)read_input_file("/dev/zero", kMaxModelFileBytes, "model file");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("is a character device"), std::string::npos) << e.what();
  }
}

// Claim: a signal file that is a FIFO is a located error at its `path:` (model line:col), not a hang.
TEST(HostileFiles, SignalFileFifoIsALocatedError) {
  const auto work = scratch("signal-fifo");
  ASSERT_EQ(::mkfifo((work / "torque.csv").c_str(), 0644), 0);
  std::ofstream(work / "model.yaml") << R"(bodies:
  A: {inertia: 1}
loads:
  M: {type: signal, body: A, signal: {type: file, path: torque.csv}}
simulation: {t_end: 0.1 s}
)";
  const auto r = run_bash("timeout 60 \"$M\" simulate model.yaml --quiet", work);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("model.yaml:4:"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("torque.csv"), std::string::npos) << r.err;
}

// Claim: a FIFO or a link named sweep.journal in the output folder is refused (exit 2, no hang on
// the FIFO), and stays what it was.
TEST(HostileFiles, SweepJournalThatIsAFifoOrALinkIsRefused) {
  const auto work = scratch("journal-fifo");
  std::ofstream(work / "model.yaml") << model_with_case("'one'");
  const std::string model_text = test::slurp(work / "model.yaml");
  fs::create_directories(work / "fifo");
  ASSERT_EQ(::mkfifo((work / "fifo" / "sweep.journal").c_str(), 0644), 0);
  fs::create_directories(work / "link");
  fs::create_symlink(work / "model.yaml", work / "link" / "sweep.journal");
  for (const char* dir : {"fifo", "link"}) {
    for (const char* resume : {"", " --resume"}) {
      SCOPED_TRACE(std::string(dir) + resume);
      const auto r = run_bash("timeout 60 \"$M\" sweep model.yaml --vary c.stiffness=1e4,2e4 --jobs 1 -o " +
                                  std::string(dir) + resume,
                              work);
      EXPECT_EQ(r.exit_code, 2) << r.err;
      EXPECT_NE(r.err.find(std::string(dir) + "/sweep.journal: error: this is not a regular file"), std::string::npos)
          << r.err;
    }
  }
  struct stat st {};
  ASSERT_EQ(::lstat((work / "fifo" / "sweep.journal").c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
  EXPECT_TRUE(fs::is_symlink(work / "link" / "sweep.journal"));
  EXPECT_EQ(test::slurp(work / "model.yaml"), model_text);
}

// Claim: under a file-size limit (`ulimit -f`, SIGXFSZ not ignored by the caller) `simulate` and
// `sweep` end with exit 1 and a message naming the file ("File too large", the limit named), not
// killed by SIGXFSZ, and leave no temporary file.
TEST(HostileFiles, FileSizeLimitIsAnOutputErrorWithNoTemporaryFileLeft) {
  const auto work = scratch("ulimit");
  std::ofstream(work / "model.yaml") << model_with_case("'one'");
  // 4 blocks of 1024 bytes: the 2 × 1001 rows of the series are ~60 kB.
  auto r = run_bash("ulimit -f 4; \"$M\" simulate model.yaml --quiet --set simulation.dt_out=5e-5 -o out", work);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("cannot write out/timeseries.csv: File too large (the file-size limit, ulimit -f, was "
                       "reached)"),
            std::string::npos)
      << r.err;
  // The sweep: the journal's rows of 200 runs (~150 bytes each) are more than 4 kB.
  std::string values = "10000";
  for (int k = 1; k < 200; ++k) {
    values += ',';
    values += std::to_string(10000 + k);
  }
  r = run_bash("ulimit -f 4; \"$M\" sweep model.yaml --vary c.stiffness=" + values + " -o sw --jobs 1", work);
  EXPECT_EQ(r.exit_code, 1) << r.err;
  EXPECT_NE(r.err.find("File too large"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("core dumped"), std::string::npos) << r.err;
  EXPECT_TRUE(temp_files(work).empty());
}

/// The pid of a process that has ended (a child reaped at once).
pid_t dead_pid() {
  const pid_t p = ::fork();
  if (p == 0) ::_exit(0);
  int status = 0;
  ::waitpid(p, &status, 0);
  return p;
}

// Claim: the temporary files of a killed writer (`sweep.journal.tmp.PID` of a dead PID) are removed
// by the next run into the folder; a live process's temporary file is kept, and so is a file that
// only looks like one but is no kind of result machdyn writes.
TEST(HostileFiles, StaleTemporaryFilesOfDeadProcessesAreRemoved) {
  const auto work = scratch("stale-tmp");
  std::ofstream(work / "model.yaml") << model_with_case("'one'");
  fs::create_directories(work / "sw");
  const auto stale = work / "sw" / (std::string("sweep.journal.tmp.") + std::to_string(dead_pid()));
  const auto live = work / "sw" / (std::string("sweep.csv.tmp.") + std::to_string(::getpid()));
  const auto other = work / "sw" / (std::string("notes.txt.tmp.") + std::to_string(dead_pid()));
  std::ofstream(stale) << "torn";
  std::ofstream(live) << "being written";
  std::ofstream(other) << "not a result of machdyn";
  const auto r = run_bash("\"$M\" sweep model.yaml --vary c.stiffness=1e4,2e4 -o sw --jobs 1", work);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_TRUE(fs::exists(live));
  EXPECT_TRUE(fs::exists(other));
  EXPECT_TRUE(fs::exists(work / "sw" / "sweep.csv"));
}

// Claim: while one run holds an output folder, a sweep into it (also --resume) fails at once with
// exit 2 naming the holder's pid, and writes nothing there; the holder's files stay byte for byte.
// A simulation, which holds a folder only while it writes, waits for the holder instead and then
// writes its complete set. (The holder here is this test process; the next test runs two sweeps.)
TEST(HostileFiles, ALockedOutputFolderIsRefusedNamingItsHolder) {
  const auto work = scratch("locked");
  std::ofstream(work / "model.yaml") << model_with_case("'one'");
  auto r = run_bash("\"$M\" sweep model.yaml --vary c.stiffness=1e4,2e4 -o sw --jobs 1", work);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string table = test::slurp(work / "sw" / "sweep.csv"), journal = test::slurp(work / "sw" / "sweep.journal");
  auto held = std::make_unique<FolderLock>(work / "sw");
  const std::string pid = std::string("pid ") + std::to_string(::getpid()) + ":";
  for (const char* cmd : {"sweep model.yaml --vary c.stiffness=3e4,4e4 -o sw --jobs 1",
                          "sweep model.yaml --vary c.stiffness=1e4,2e4 -o sw --jobs 1 --resume"}) {
    SCOPED_TRACE(cmd);
    r = run_bash("\"$M\" " + std::string(cmd), work);
    EXPECT_EQ(r.exit_code, 2) << r.err;
    EXPECT_NE(r.err.find("sw: error: the output folder is in use by another machdyn run (" + pid), std::string::npos)
        << r.err;
  }
  EXPECT_EQ(test::slurp(work / "sw" / "sweep.csv"), table);
  EXPECT_EQ(test::slurp(work / "sw" / "sweep.journal"), journal);
  // The holder lets go after 1.5 s; the simulation started meanwhile waits, then writes.
  std::thread release([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(1500));
    held.reset();
  });
  const auto t0 = std::chrono::steady_clock::now();
  r = run_bash("\"$M\" simulate model.yaml --quiet -o sw", work);
  const double waited = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  release.join();
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_GE(waited, 1.4);
  EXPECT_TRUE(fs::exists(work / "sw" / "timeseries.csv"));
  EXPECT_TRUE(fs::exists(work / "sw" / "summary.json"));
}

// Claim: two sweeps with different plans started into one folder: the second fails cleanly (exit 2,
// naming the first's pid and command), the first completes with exit 0 and its table has exactly
// its own rows (its stiffness values, in order).
TEST(HostileFiles, TwoSweepsInOneFolderDoNotMix) {
  const auto work = scratch("two-sweeps");
  // Stick-slip under a sine load: ~0.06 s a run, event-driven.
  std::ofstream(work / "model.yaml") << R"Y(bodies:
  A: {inertia: 1}
  B: {inertia: 2}
links:
  c: {type: spring-damper, between: [A, B], stiffness: 1e4, damping: 1}
loads:
  M: {type: expression, body: A, expression: "15*sin(2*pi*t)"}
contacts:
  f: {between: [B, ground], static: 10 N*m, kinetic: 8 N*m}
simulation: {t_end: 20 s}
)Y";
  // The first: 40 runs on one thread (a few seconds); the second starts once the first holds the lock.
  const auto r = run_bash(R"(
"$M" sweep model.yaml --vary c.stiffness=1e4:5e4:40 -o sw --jobs 1 >first.out 2>first.err &
first=$!
for i in $(seq 1 600); do [ -s sw/.machdyn.lock ] && break; sleep 0.05; done
"$M" sweep model.yaml --vary c.stiffness=7e4,8e4 -o sw --jobs 1
echo "second=$?"
wait $first
echo "first=$?"
)",
                          work);
  EXPECT_NE(r.out.find("second=2"), std::string::npos) << r.out << r.err;
  EXPECT_NE(r.out.find("first=0"), std::string::npos) << r.out << test::slurp(work / "first.err");
  EXPECT_NE(r.err.find("the output folder is in use by another machdyn run (pid "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("sweep model.yaml --vary c.stiffness=1e4:5e4:40"), std::string::npos) << r.err;
  std::ifstream in(work / "sw" / "sweep.csv");
  std::string line;
  std::getline(in, line);
  int rows = 0;
  while (std::getline(in, line)) {
    const double k = std::stod(line.substr(line.find(',') + 1));
    EXPECT_NEAR(k, 1e4 + 4e4 * rows / 39.0, 1e-6) << line;
    ++rows;
  }
  EXPECT_EQ(rows, 40);
}

/// Fields of RFC 4180 CSV text, record by record (quoted fields may hold commas, quotes, line
/// breaks): written here independently of common/csv.hpp.
std::vector<std::vector<std::string>> parse_csv(const std::string& text) {
  std::vector<std::vector<std::string>> records;
  std::vector<std::string> rec;
  std::string field;
  bool quoted = false, any = false;
  for (size_t i = 0; i < text.size(); ++i) {
    const char ch = text[i];
    if (quoted) {
      if (ch == '"' && i + 1 < text.size() && text[i + 1] == '"') field += '"', ++i;
      else if (ch == '"') quoted = false;
      else field += ch;
      continue;
    }
    any = true;
    if (ch == '"') quoted = true;
    else if (ch == ',') rec.push_back(field), field.clear();
    else if (ch == '\n') rec.push_back(field), field.clear(), records.push_back(rec), rec.clear(), any = false;
    else if (ch != '\r') field += ch;
  }
  if (any) rec.push_back(field), records.push_back(rec);
  return records;
}

// Claim: names holding a comma, a double quote or spaces at the ends give CSV files (time series,
// sweep table, energy table) whose header has as many fields as every row, and the header's fields
// read back (by an independent RFC 4180 parser) as the names written.
TEST(HostileFiles, CsvHeadersWithCommasAndQuotesReadBack) {
  const auto work = scratch("csv-names");
  std::ofstream(work / "model.yaml") << R"(bodies:
  'motor, left': {inertia: 1}
  'drum "big"': {inertia: 2}
links:
  ' shaft ': {type: spring, between: ['motor, left', 'drum "big"'], stiffness: 1e4}
loads:
  M: {type: constant, body: 'motor, left', value: 10 N*m}
simulation: {t_end: 0.05 s}
)";
  auto r = run_bash("\"$M\" simulate model.yaml --quiet -o out", work);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto csv = parse_csv(test::slurp(work / "out" / "timeseries.csv"));
  ASSERT_GT(csv.size(), 2u);
  for (const auto& row : csv) ASSERT_EQ(row.size(), csv[0].size());
  const std::set<std::string> header(csv[0].begin(), csv[0].end());
  EXPECT_TRUE(header.count("motor, left.position_rad")) << test::slurp(work / "out" / "timeseries.csv").substr(0, 300);
  EXPECT_TRUE(header.count("drum \"big\".velocity_rad_s"));
  r = run_bash("\"$M\" sweep model.yaml --vary ' shaft .stiffness=1e4,2e4' -o sw --jobs 1", work);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  csv = parse_csv(test::slurp(work / "sw" / "sweep.csv"));
  ASSERT_EQ(csv.size(), 3u);
  for (const auto& row : csv) EXPECT_EQ(row.size(), csv[0].size());
  EXPECT_EQ(csv[0][1], " shaft .stiffness");
  EXPECT_EQ(csv[1][csv[0].size() - 2], "ok");
  // A name on two lines cannot be one CSV header cell of a line-by-line journal: a located error.
  std::ofstream(work / "newline.yaml") << "bodies:\n  \"two\\nlines\": {inertia: 1}\nsimulation: {t_end: 0.1}\n";
  r = run_bash("\"$M\" simulate newline.yaml --quiet", work);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("newline.yaml:2:3: error: bodies name contains a control character"), std::string::npos) << r.err;
}

// Claim: csv_field quotes exactly what RFC 4180 needs and the independent parser reads every text
// back, line breaks inside a field included.
TEST(HostileFiles, CsvFieldRoundTrips) {
  const std::vector<std::string> texts = {"plain", "a,b", "say \"hi\"", "two\nlines", "cr\rlf", " lead", "trail ",
                                          "", "\"", ",,,", "ünï cødé"};
  const std::string line = csv_line(texts) + "\n" + csv_line({"x"}) + "\n";
  const auto back = parse_csv(line);
  ASSERT_EQ(back.size(), 2u);
  EXPECT_EQ(back[0], texts);
  EXPECT_EQ(csv_field("plain"), "plain");
  EXPECT_EQ(csv_field("a,b"), "\"a,b\"");
  EXPECT_EQ(csv_field("q\"q"), "\"q\"\"q\"");
  EXPECT_EQ(csv_field("x", true), "\"x\"");
}

// Claim: a sweep whose every run is refused on input — the model has no equilibrium, which
// `simulate` refuses with exit 2 — exits 2 with the first run's located message, and keeps its
// table (every row status `error`); a sweep where only some runs are refused exits 0.
TEST(HostileFiles, SweepWhoseEveryRunIsRefusedIsAnInputError) {
  const auto work = scratch("sweep-all-refused");
  std::ofstream(work / "eq.yaml") << R"(bodies:
  a: {inertia: 1}
  b: {inertia: 1}
links: {c: {type: spring, between: [a, b], stiffness: 100}}
loads: {M: {type: constant, body: a, value: 10 N*m}}
simulation: {initial: equilibrium, t_end: 0.1}
)";
  auto r = run_bash("\"$M\" simulate eq.yaml --quiet", work);
  ASSERT_EQ(r.exit_code, 2) << r.err;
  r = run_bash("\"$M\" sweep eq.yaml --vary c.stiffness=100,200,300 -o sw --jobs 2", work);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("every run of the sweep failed on its input"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("The first, run 0:\neq.yaml:2:"), std::string::npos) << r.err;
  const auto csv = parse_csv(test::slurp(work / "sw" / "sweep.csv"));
  ASSERT_EQ(csv.size(), 4u);
  for (size_t k = 1; k < csv.size(); ++k) EXPECT_EQ(csv[k][csv[0].size() - 2], "error");
  // M = 0 balances: one run is fine, the sweep is not an input error.
  r = run_bash("\"$M\" sweep eq.yaml --vary M.value=0,10 -o sw2 --jobs 1", work);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("2 runs, 1 ok, 1 error(s)"), std::string::npos) << r.out;
}

// Claim: hostile expressions with the switches (issue 29) are located errors with exit 2 that write
// nothing: a condition that is not a comparison, chained comparisons, a jump of the state in a load,
// a switch nested past the depth bound; a model with 150 switches in t still runs (each a
// breakpoint found in bounded time).
TEST(HostileFiles, ExpressionSwitchesAreLocatedErrors) {
  const auto work = scratch("expression-switches");
  std::string deep = "t";
  for (int i = 0; i < 300; ++i) deep = "min(" + deep + ", 1)";
  const std::pair<std::string, std::string> bad[] = {
      {"if(t, 1, 2)", "at character 4: the condition of if must be a comparison"},
      {"1 < t < 2", "comparisons do not chain"},
      {"-5*step(v)", "step of v"},
      {deep, "nested deeper than 200"},
  };
  for (const auto& [text, what] : bad) {
    std::ofstream(work / "model.yaml") << "bodies:\n  A: {type: translational, mass: 1 kg}\nloads:\n"
                                          "  M: {type: expression, body: A, expression: \"" << text << "\"}\n"
                                          "simulation: {t_end: 1 s}\n";
    const auto r = run_bash("timeout 60 \"$M\" simulate model.yaml -o out --quiet", work);
    EXPECT_EQ(r.exit_code, 2) << text << r.err;
    EXPECT_NE(r.err.find("model.yaml:4:"), std::string::npos) << text << r.err;
    EXPECT_NE(r.err.find(what), std::string::npos) << text << r.err;
    EXPECT_FALSE(fs::exists(work / "out")) << text;
  }
  std::string many = "0";
  for (int i = 1; i <= 150; ++i) many += "+step(t - " + std::to_string(i) + "e-2)";
  std::ofstream(work / "model.yaml") << "bodies:\n  A: {type: translational, mass: 1 kg}\nloads:\n"
                                        "  M: {type: sum, body: A, terms: [{type: expression, expression: \"" << many << "\"}]}\n"
                                        "simulation: {t_end: 1.5 s}\n";
  const auto r = run_bash("timeout 120 \"$M\" simulate model.yaml -o ok --quiet", work);
  EXPECT_EQ(r.exit_code, 0) << r.err;
}


}  // namespace
}  // namespace machdyn
