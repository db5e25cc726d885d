// `machdyn duty MODEL DUTY` as a user meets it: the figures it prints and writes are those of its
// own cycle list (k, ν, s, Δ_eq and the Miner damage recomputed here from duty_cycles.csv by their
// definitions), the counts are those of the library's merge of the operations' runs, and bad duty
// files are located errors (exit 2) that write nothing.
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sys/wait.h>

#include "machdyn/analysis/load_history.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/sweep/mpi.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

namespace fs = std::filesystem;

const char* kModel = R"(
bodies:
  A: {type: translational, mass: 1 kg}
  B: {type: translational, mass: 1.5 kg, velocity: 0.5 m/s}
  C: {type: translational, mass: 2 kg}
links:
  ab: {type: spring-damper, between: [A, B], stiffness: 1e4 N/m, damping: 2 N*s/m}
  bc: {type: spring, between: [B, C], stiffness: 2e4 N/m, gap: 1 mm}
simulation: {t_end: 0.3 s, dt_out: 0.01 s, rtol: 1e-10, atol: 1e-12}
cases:
  fast: {bodies: {B: {velocity: 0.5 m/s}}}
  slow: {bodies: {B: {velocity: 0.2 m/s}}}
)";

// Claim: for a duty of 3 fast and 2 slow operations the CLI's cycles are the library's merge of the
// two runs' parts (merge_parts with n = 3, 2), and its figures follow from its cycle list by their
// definitions: N_t = Σ n, s = Σ n (Δ/Δ̂)³ / 2e6, Δ_eq = (Σ n Δ³ / N_t)^(1/3), D = Σ n / (1e6 (100/Δ)³).
TEST(DutyCli, FiguresFollowFromTheMergedCycles) {
  const std::string model = test::write_temp("duty-model.yaml", kModel);
  const std::string duty = test::write_temp("duty.yaml", R"(
operations:
  lift: {case: fast, repeat: 3}
  lower: {case: slow, repeat: 2}
links: [ab]
sn_curve: {m: 3, delta_ref: 100, n_ref: 1e6}
)");
  const auto dir = test::temp_dir() / "duty-out";
  const auto r = test::run_cli("duty '" + model + "' '" + duty + "' -o '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("ab"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(std::ifstream(dir / "duty.json"));
  ASSERT_EQ(j["links"].size(), 1u);
  // The cycles from the CSV.
  std::ifstream csv(dir / "duty_cycles.csv");
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "link,range,mean,count,from,to");
  double nt = 0, largest = 0, s3 = 0, d = 0;
  std::vector<double> ranges, counts;
  while (std::getline(csv, line)) {
    std::stringstream ss(line);
    std::string link, field;
    std::getline(ss, link, ',');
    std::vector<double> v;
    while (std::getline(ss, field, ',')) v.push_back(std::stod(field));
    ASSERT_EQ(v.size(), 5u);
    ranges.push_back(v[0]), counts.push_back(v[2]);
    nt += v[2], largest = std::max(largest, v[0]), s3 += v[2] * v[0] * v[0] * v[0];
    d += v[2] / (1e6 * std::pow(100.0 / v[0], 3));
  }
  ASSERT_GT(ranges.size(), 5u);
  const auto& l = j["links"][0];
  EXPECT_EQ(l["link"], "ab");
  EXPECT_NEAR(l["cycles"].get<double>(), nt, 1e-9 * nt);
  EXPECT_NEAR(l["largest_range"].get<double>(), largest, 1e-12 * largest);
  EXPECT_NEAR(l["s"].get<double>(), s3 / (largest * largest * largest) / 2e6, 1e-9 * l["s"].get<double>());
  {  // its EN 13001 class: the first of the table's limits at or above s
    const double sv = s3 / (largest * largest * largest) / 2e6;
    const double limits[] = {0.008, 0.016, 0.032, 0.063, 0.125, 0.25, 0.5, 1.0, 2.0, 4.0};
    int S = 0;
    while (S < 10 && sv > limits[S]) ++S;
    std::string name = "S";
    name += std::to_string(S);
    EXPECT_EQ(l["stress_history_class"], S < 10 ? name : ">S9") << sv;
  }
  EXPECT_NEAR(l["equivalent_range"].get<double>(), std::cbrt(s3 / nt), 1e-9 * largest);
  EXPECT_NEAR(l["damage"].get<double>(), d, 1e-9 * d);
  // The matrices hold the same cycles: their cells sum to N_t, and every cycle lies in its cell.
  for (const char* file : {"duty_range_mean.csv", "duty_from_to.csv"}) {
    std::ifstream mcsv(dir / file);
    std::getline(mcsv, line);
    double cells = 0;
    while (std::getline(mcsv, line)) cells += std::stod(line.substr(line.rfind(',') + 1));
    EXPECT_NEAR(cells, nt, 1e-9 * nt) << file;
  }
  // The library's merge of the two operations' runs: the same cycles.
  std::vector<RainflowPart> parts;
  for (const char* c : {"fast", "slow"}) {
    const Model m = load_model_case(model, {}, c);
    SimulateOptions opt;
    opt.record_series = false;
    const SimulationResult plain = simulate(m, opt);
    LinkCycleOptions count;
    count.links = {0};
    count.gates = {1e-6 * (plain.links[0].max - plain.links[0].min)};
    parts.push_back(link_parts(m, opt, count)[0]);
  }
  const auto merged = merge_parts(parts, std::vector<double>{3, 2});
  ASSERT_EQ(merged.size(), ranges.size());
  double total = 0;
  for (const auto& c : merged) total += c.count;
  EXPECT_DOUBLE_EQ(total, nt);
}

struct BadDuty {
  const char* name;
  const char* text;
  const char* message;  // a part of the located message
  int line;             // its line in the duty file
};

// Claim: each bad duty file exits 2 with the problem at its file:line:col and writes nothing (an
// empty load history — every operation done 0 times — included).
TEST(DutyCli, BadDutyFilesAreLocatedAndWriteNothing) {
  const std::string model = test::write_temp("duty-model2.yaml", kModel);
  const BadDuty bad[] = {
      {"unknown-case", "operations:\n  lift: {case: heavy, repeat: 3}\n", "unknown load case 'heavy'", 2},
      {"negative", "operations:\n  lift: {case: fast, repeat: -1}\n", "whole number", 2},
      {"fraction", "operations:\n  lift: {case: fast, repeat: 2.5}\n", "whole number", 2},
      {"no-slope", "operations:\n  lift: {case: fast, repeat: 1}\nsn_curve: {delta_ref: 100, n_ref: 1e6}\n", "'m'", 3},
      {"unknown-field", "operations:\n  lift: {case: fast, repeat: 1}\nresidu: half\n", "residu", 3},
      {"unknown-link", "operations:\n  lift: {case: fast, repeat: 1}\nlinks: [cd]\n", "no link 'cd'", 3},
      {"empty", "operations: {}\n", "non-empty", 1},
      {"per-hour-no-life", "operations:\n  lift: {case: fast, per_hour: 12}\n", "design_life", 2},
      {"both-counts", "design_life: 100 h\noperations:\n  lift: {case: fast, per_hour: 12, repeat: 3}\n", "not both", 3},
      {"negative-rate", "design_life: 100 h\noperations:\n  lift: {case: fast, per_hour: -2}\n", ">= 0", 3},
      {"life-unit", "design_life: 100 m\noperations:\n  lift: {case: fast, repeat: 1}\n", "design_life", 1},
      {"rated-unknown", "operations:\n  lift: {case: fast, repeat: 1}\nlinks: [ab]\nrated: {bc: 20}\n", "'rated' names 'bc'", 4},
      {"no-history", "design_life: 100 h\noperations:\n  lift: {case: fast, repeat: 0}\n  lower: {case: slow, per_hour: 0}\n",
       "load history is empty", 3},
  };
  for (const BadDuty& b : bad) {
    const std::string duty = test::write_temp(std::string(b.name) + ".duty.yaml", b.text);
    const auto dir = test::temp_dir() / (std::string("bad-") + b.name);
    const auto r = test::run_cli("duty '" + model + "' '" + duty + "' -o '" + dir.string() + "'");
    EXPECT_EQ(r.exit_code, 2) << b.name << ": " << r.err;
    EXPECT_NE(r.err.find(b.message), std::string::npos) << b.name << ": " << r.err;
    EXPECT_NE(r.err.find(duty + ":" + std::to_string(b.line) + ":"), std::string::npos) << b.name << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir)) << b.name;
  }
}

// Claim: the worked example of docs/duty.md, as the doc checks it by hand. The 32 t main hoist's duty
// (2, 4, 6, 8 lifts, 0.05 emergency stops and 2 lowerings of the full load an hour, each 24 s, over
// 20 000 h): n = 40 000, 80 000, 120 000, 160 000, 1 000, 40 000; running time 441 000 × 24 s =
// 2 940 h → T4; k_m within 0.5 % of the static loads' estimate
// (2·1 + 4·0.63³ + 6·0.25³ + 8·0.025³ + 0.05·1 + 2·1)/22.05 = 0.23329 → L2; M4 (T4 with L2). The
// rope's largest range is the peak of a plain run of the full lift (its minimum is 0: slack before
// the lift). The lowering starts with the load hanging: its rope never goes slack and stays near m g
// — during the 2 s speed ramp it carries m (g − a), a = 0.279 m/s / 2 s, 0.986 m g, and the drive's
// PI response swings about that by a few per cent: within 5 % of m g throughout.
TEST(DutyCli, WorkedExampleOfThe32tHoist) {
  const std::string src = MACHDYN_SOURCE_DIR;
  const std::string model = src + "/examples/duty/hoist-32t.yaml", duty = src + "/examples/duty/hoist-32t.duty.yaml";
  const auto dir = test::temp_dir() / "duty-hoist32";
  const auto r = test::run_cli("duty '" + model + "' '" + duty + "' --json -o '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const double n[] = {40000, 80000, 120000, 160000, 1000, 40000};
  ASSERT_EQ(j["operations"].size(), 6u);
  EXPECT_EQ(j["operations"][5]["case"], "lower");
  for (std::size_t k = 0; k < 6; ++k) {
    EXPECT_EQ(j["operations"][k]["repeat"].get<double>(), n[k]);
    EXPECT_NEAR(j["operations"][k]["seconds"].get<double>(), 24.0, 1e-9);
  }
  EXPECT_NEAR(j["running_hours"].get<double>(), 441000.0 * 24.0 / 3600.0, 1e-6);
  EXPECT_EQ(j["utilization_class"], "T4");
  const double km =
      (2.0 + 4.0 * std::pow(0.63, 3) + 6.0 * std::pow(0.25, 3) + 8.0 * std::pow(0.025, 3) + 0.05 + 2.0) / 22.05;
  for (const auto& l : j["links"]) {
    EXPECT_NEAR(l["k_m"].get<double>(), km, 5e-3 * km) << l["link"];
    EXPECT_EQ(l["spectrum_class"], "L2") << l["link"];
    EXPECT_EQ(l["mechanism_group"], "M4") << l["link"];
    EXPECT_TRUE(l["p_max_rated"].get<bool>());
    // s = N_t (Δ_eq/Δ̂)³ / N_ref by the definitions of Δ_eq and s (m = 3): the doc's hand check
    const double ratio = l["equivalent_range"].get<double>() / l["largest_range"].get<double>();
    const double s = l["cycles"].get<double>() * ratio * ratio * ratio / 2e6;
    EXPECT_NEAR(l["s"].get<double>(), s, 1e-9 * s) << l["link"];
    EXPECT_EQ(l["stress_history_class"], "S3") << l["link"];  // 0.032 < s ≤ 0.063
  }
  const Model full = load_model_case(model, {}, "full");
  SimulateOptions opt;
  opt.record_series = false;
  const SimulationResult plain = simulate(full, opt);
  std::size_t rope = 0;
  while (full.links[rope].name != "rope") ++rope;
  EXPECT_EQ(j["links"][0]["link"], "rope");
  EXPECT_NEAR(plain.links[rope].min, 0.0, 1e-6);
  EXPECT_NEAR(j["links"][0]["largest_range"].get<double>(), plain.links[rope].max - plain.links[rope].min,
              1e-6 * plain.links[rope].max);
  const double mg = 32e3 * 9.81;
  for (const char* integrator : {"dopri5", "bdf"}) {
    const Model lower = load_model_case(model, {std::string("simulation.integrator=") + integrator}, "lower");
    const SimulationResult l = simulate(lower, opt);
    EXPECT_GT(l.links[rope].min, 0.95 * mg) << integrator;
    EXPECT_LT(l.links[rope].min, 0.986 * mg) << integrator;
    EXPECT_LT(l.links[rope].max, 1.05 * mg) << integrator;
  }
}

// Claim: `machdyn report --duty` adds the duty's section (its title, the classes, an exceedance chart
// per link); a bad duty file stops the report at its line before any run and writes no report.
TEST(DutyCli, ReportWithADutySection) {
  const std::string model = test::write_temp("duty-report-model.yaml", kModel);
  const std::string duty = test::write_temp("duty-report.duty.yaml", R"(
operations:
  lift: {case: fast, repeat: 3}
  lower: {case: slow, repeat: 2}
links: [ab, bc]
)");
  const auto html = test::temp_dir() / "duty-report.html";
  fs::remove(html);
  const auto r = test::run_cli("report '" + model + "' --quiet --duty '" + duty + "' -o '" + html.string() + "'");
  if (r.exit_code != 0 && r.err.find("MACHDYN_REPORT=OFF") != std::string::npos) GTEST_SKIP() << "no report assets";
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream in(html);
  const std::string page((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(page.find("Duty: load cycles and classification"), std::string::npos);
  EXPECT_NE(page.find("data-figure=\"duty_exceedance_ab-"), std::string::npos);
  EXPECT_NE(page.find("data-figure=\"duty_exceedance_bc-"), std::string::npos);
  EXPECT_NE(page.find("class of utilization T0"), std::string::npos);

  const std::string bad = test::write_temp("duty-report-bad.duty.yaml", "operations:\n  lift: {case: heavy, repeat: 3}\n");
  const auto html2 = test::temp_dir() / "duty-report-bad.html";
  fs::remove(html2);
  const auto b = test::run_cli("report '" + model + "' --quiet --duty '" + bad + "' -o '" + html2.string() + "'");
  EXPECT_EQ(b.exit_code, 2) << b.err;
  EXPECT_NE(b.err.find(bad + ":2:"), std::string::npos) << b.err;
  EXPECT_FALSE(fs::exists(html2));
}

// Claim: --plot writes per link the exceedance diagram and the heat map (SVG + PNG) beside the other
// files; when gnuplot fails (an executable that exits 1), nothing at all is written.
TEST(DutyCli, PlotWritesTheFiguresOrNothing) {
  if (!test::have_gnuplot()) GTEST_SKIP() << "no gnuplot";
  const std::string model = test::write_temp("duty-plot-model.yaml", kModel);
  const std::string duty = test::write_temp("duty-plot.duty.yaml", "operations:\n  lift: {case: fast, repeat: 3}\n");
  const auto dir = test::temp_dir() / "duty-plot";
  fs::remove_all(dir);
  auto r = test::run_cli("duty '" + model + "' '" + duty + "' --plot -o '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* link : {"ab", "bc"})
    for (const char* kind : {"duty_exceedance_", "duty_heatmap_"})
      for (const char* ext : {".svg", ".png"}) EXPECT_TRUE(fs::exists(dir / (std::string(kind) + link + ext))) << kind << link << ext;
  std::ifstream svg(dir / "duty_exceedance_ab.svg");
  const std::string text((std::istreambuf_iterator<char>(svg)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("cumulative spectrum"), std::string::npos);

  const auto dir2 = test::temp_dir() / "duty-plot-fails";
  fs::remove_all(dir2);
  ::setenv("MACHDYN_GNUPLOT", "/bin/false", 1);
  r = test::run_cli("duty '" + model + "' '" + duty + "' --plot -o '" + dir2.string() + "'");
  ::unsetenv("MACHDYN_GNUPLOT");
  EXPECT_NE(r.exit_code, 0);
  EXPECT_FALSE(fs::exists(dir2));
}

// Claim: under `mpirun -np 2` (the sweep runner's MPI path) the operations are split over the two
// ranks — operation i on rank i mod 2 — and rank 0 merges them in the duty's order: the terminal
// table and every file byte for byte those of a one-process, one-thread run of the same duty (five
// operations, so each rank has some and the ranks' parts interleave in the merge). An operation that
// fails on rank 1 (the second, whose case allows 5 solver steps) is reported by rank 0 with the
// message and exit code (3) a one-process run gives, and nothing is written.
TEST(DutyCli, TwoMpiRanksGiveTheSameDuty) {
  if (!MpiSession::built()) GTEST_SKIP() << "built without MPI (install libopenmpi-dev and reconfigure)";
  const auto sh = [](const std::string& cmd) {
    const int status = std::system(("cd '" + test::temp_dir().string() + "' || exit 1; " + cmd).c_str());
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  };
  if (sh("command -v mpirun >/dev/null 2>&1") != 0) GTEST_SKIP() << "mpirun not found (apt-get install openmpi-bin)";
  const std::string model = test::write_temp("duty-mpi-model.yaml", std::string(kModel) + "  broken: {simulation: {max_steps: 5}}\n");
  const std::string duty = test::write_temp("duty-mpi.yaml", R"(
operations:
  lift: {case: fast, repeat: 3}
  lower: {case: slow, repeat: 2}
  lift2: {case: fast, repeat: 1}
  swing: {repeat: 4}
  last: {case: slow, repeat: 5}
residue: repeat
sn_curve: {m: 3, delta_ref: 100, n_ref: 1e6}
)");
  const std::string bad = test::write_temp("duty-mpi-bad.yaml", R"(
operations:
  lift: {case: fast, repeat: 3}
  stuck: {case: broken, repeat: 2}
  lower: {case: slow, repeat: 1}
)");
  std::string cli = "'";
  cli.append(MACHDYN_CLI).append("'");
  const std::string mpirun = "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 OMPI_MCA_rmaps_base_oversubscribe=1 "
                             "mpirun -np 2 --oversubscribe ";
  for (const char* d : {"duty-mpi1", "duty-mpi2", "duty-mpi-bad1", "duty-mpi-bad2"}) fs::remove_all(test::temp_dir() / d);
  const std::string args = " duty '" + model + "' '" + duty + "' -j 1 -o ";
  ASSERT_EQ(sh(cli + args + "duty-mpi1 >duty-mpi1.out 2>duty-mpi1.err"), 0) << test::slurp(test::temp_dir() / "duty-mpi1.err");
  ASSERT_EQ(sh(mpirun + cli + args + "duty-mpi2 >duty-mpi2.out 2>duty-mpi2.err"), 0)
      << test::slurp(test::temp_dir() / "duty-mpi2.err");
  EXPECT_EQ(test::slurp(test::temp_dir() / "duty-mpi2.out"), test::slurp(test::temp_dir() / "duty-mpi1.out"));
  for (const char* f : {"duty.json", "duty_cycles.csv", "duty_range_mean.csv", "duty_from_to.csv"}) {
    const std::string one = test::slurp(test::temp_dir() / "duty-mpi1" / f);
    EXPECT_GT(one.size(), 100u) << f;
    EXPECT_EQ(test::slurp(test::temp_dir() / "duty-mpi2" / f), one) << f;
  }
  const std::string bad_args = " duty '" + model + "' '" + bad + "' -j 1 -o ";
  EXPECT_EQ(sh(cli + bad_args + "duty-mpi-bad1 >/dev/null 2>duty-mpi-bad1.err"), 3);
  EXPECT_EQ(sh(mpirun + cli + bad_args + "duty-mpi-bad2 >/dev/null 2>duty-mpi-bad2.err"), 3);
  const std::string one = test::slurp(test::temp_dir() / "duty-mpi-bad1.err");
  ASSERT_NE(one.find("maximum number of steps"), std::string::npos) << one;
  // rank 0's message, once (the other rank is silent; mpirun adds its own lines after it)
  const std::string two = test::slurp(test::temp_dir() / "duty-mpi-bad2.err");
  EXPECT_EQ(two.substr(0, one.size()), one) << two;
  EXPECT_EQ(two.find(one, 1), std::string::npos) << two;
  EXPECT_FALSE(fs::exists(test::temp_dir() / "duty-mpi-bad1"));
  EXPECT_FALSE(fs::exists(test::temp_dir() / "duty-mpi-bad2"));
}

}  // namespace
}  // namespace machdyn
