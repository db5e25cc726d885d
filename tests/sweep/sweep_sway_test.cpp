// Sweeps of the swinging load (docs/sway.md, docs/sweeps.md): a field only a case has is swept over
// that case, a field some cases lack is an input error naming the case, and the table's sway columns
// are the sway summary of `simulate` (summary.json `sway`) for the same points, on both integrators.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/results.hpp"
#include "machdyn/model/cases.hpp"
#include "machdyn/sweep/plot_data.hpp"
#include "machdyn/sweep/runner.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

namespace fs = std::filesystem;

/// The sway keys of summary.json that the table carries per rope (sway_summary_columns()).
const char* const kSwayKeys[] = {"max_sway_rad", "residual_sway_rad", "max_horizontal_force_N",
                                 "horizontal_dynamic_factor"};

size_t sway_column(const std::vector<std::string>& header, const std::string& name) {
  const auto it = std::find(header.begin(), header.end(), name);
  EXPECT_NE(it, header.end()) << "no column " << name;
  return static_cast<size_t>(it - header.begin());
}

/// The 40 t trolley move of examples/crane/trolley-sway.yaml, cut at 25 s (the residual sway is
/// taken from 20 s on, after every case's move: at least half a swing period, 4.0 s at 16 m).
SweepRequest trolley_request(const std::string& integrator, std::vector<std::string> cases, std::string vary) {
  SweepRequest r;
  r.model_path = test::example("crane/trolley-sway.yaml");
  r.sets = {"simulation.t_end=25", "simulation.integrator=" + integrator};
  r.vary = {std::move(vary)};
  r.cases = std::move(cases);
  r.apply_case = [](SpecNode& s, const std::string& name) { apply_case(s, name); };
  return r;
}

/// How close a case's row is to `simulate --case` (no energy books for a model without contacts)
/// where the sweep runs the case with the books (as `--all-cases`): the books' states are in the
/// step size control, so the two integrations (2647 and 2064 dopri5 steps for zv) agree to the
/// tolerance, rtol 1e-8, not to the bit: the angles and forces to 100 rtol (seen: 5e-12 and 1e-10
/// relative) ...
constexpr double kCaseVsBooks = 1e-6;
/// ... and the horizontal dynamic factor, whose m a is the difference of two velocity rows over
/// Δt = 10 ms: an error of rtol |v| in each (1e-8 × 0.63 m/s) is 2 × 6.3e-9/0.01 = 1.3e-6 m/s² on
/// a ≈ 0.21 m/s² (0.63 m/s in 3 s), 6e-6 relative; seen 1.8e-6 (bdf); allowed 5 times that.
constexpr double kFactorVsBooks = 3e-5;

/// Every sway column of `row` equals summary.json's `sway` of the rope `rope` in `j`: with `rel` 0 the
/// same bits (the table's numbers are the shortest text that reads back to the same double), else to
/// that relative difference.
void expect_sway_equal(const std::vector<std::string>& header, const std::vector<std::string>& row,
                       const nlohmann::json& j, const std::string& what, double rel = 0.0) {
  ASSERT_TRUE(j.contains("sway")) << what;
  const auto& s = j["sway"]["rope"];
  for (const char* k : kSwayKeys) {
    ASSERT_TRUE(s.contains(k)) << what << ": " << k;
    const double table = std::stod(row[sway_column(header, std::string("rope.") + k)]), json = s[k].get<double>();
    if (rel == 0.0)
      EXPECT_EQ(table, json) << what << ": " << k;
    else  // the dynamic factor's tolerance is its own (kFactorVsBooks)
      EXPECT_NEAR(table, json, (std::string(k) == "horizontal_dynamic_factor" ? kFactorVsBooks : rel) * std::abs(json))
          << what << ": " << k;
  }
}

class SweepSwayBoth : public ::testing::TestWithParam<std::string> {};
INSTANTIATE_TEST_SUITE_P(BothIntegrators, SweepSwayBoth, ::testing::Values("dopri5", "bdf"));

// Claim: a field that only a case has — the design rope length of case zv's shaped reference — is
// swept over that case (the file's own reference, a table, has no `length`), and every row is the
// run of `simulate --all-cases --set travel.reference.length=L`'s case zv: the solver's figures and
// the sway summary the same bits (and `simulate --case zv` to the tolerance, kCaseVsBooks). The
// shaper designed for the rope's own 12 m leaves the least residual sway (docs/sway.md: off the design the ZV residual is |cos(π ω/(2 ω_m))| of the unshaped one, 0.28 at
// 8 m and 0.24 at 16 m, against the drive's small rest at 12 m).
TEST_P(SweepSwayBoth, CaseOnlyFieldRowsEqualSimulateOfTheCase) {
  const auto req = trolley_request(GetParam(), {"zv"}, "travel.reference.length=8 m:16 m:3");
  const auto plan = make_sweep_plan(req);
  ASSERT_EQ(plan.runs.size(), 3u);
  const auto cols = standard_summary_columns();
  const auto header = split_csv_line(sweep_header(plan, cols));
  std::vector<double> residual;
  for (const auto& run : plan.runs) {
    const auto row = split_csv_line(execute_run(plan, run, cols));
    ASSERT_EQ(row.size(), header.size());
    ASSERT_EQ(row[sway_column(header, "status")], "ok") << row.back();
    auto sets = req.sets;
    sets.push_back("travel.reference.length=" + run.values[0].text);
    const Model m = load_model_case(req.model_path, sets, "zv");
    // The run of `simulate --all-cases` (the energy books kept, as a case sweep keeps them): the same
    // steps, the same bits; `simulate --case zv` (no books): to the integration's tolerance.
    SimulateOptions all_cases;
    all_cases.event_driven = true;
    const SimulationResult r = simulate(m, all_cases);
    EXPECT_EQ(std::stol(row[sway_column(header, "steps")]), r.stats.stepper.steps);
    expect_sway_equal(header, row, simulation_summary(m, r), "L = " + run.values[0].text);
    expect_sway_equal(header, row, simulation_summary(m, simulate(m)), "--case, L = " + run.values[0].text,
                      kCaseVsBooks);
    residual.push_back(std::stod(row[sway_column(header, "rope.residual_sway_rad")]));
  }
  EXPECT_LT(residual[1], residual[0] / 4);
  EXPECT_LT(residual[1], residual[2] / 4);
}

// Claim: the sway columns of a sweep of the file's model (no case: not event-driven) equal
// summary.json of `simulate --set rope.length=L` for each point, the same bits.
TEST_P(SweepSwayBoth, SwayColumnsEqualSimulateSummary) {
  const auto req = trolley_request(GetParam(), {}, "rope.length=10 m,14 m");
  const auto plan = make_sweep_plan(req);
  const auto cols = standard_summary_columns();
  const auto header = split_csv_line(sweep_header(plan, cols));
  for (const auto& run : plan.runs) {
    const auto row = split_csv_line(execute_run(plan, run, cols));
    ASSERT_EQ(row[sway_column(header, "status")], "ok") << row.back();
    auto sets = req.sets;
    sets.push_back("rope.length=" + run.values[0].text);
    const Model m = load_model(req.model_path, sets);
    expect_sway_equal(header, row, simulation_summary(m, simulate(m)), "L = " + run.values[0].text);
  }
}

// Claim: a --vary field that some of the sweep's cases lack is an input error before any run that
// names each such case and no other; without cases the file's model is checked (it lacks it too);
// a unit that fits no case is told once.
TEST(SweepSway, FieldSomeCasesLackIsAnErrorNamingTheCase) {
  auto req = trolley_request("dopri5", {"unshaped", "zv", "zvd"}, "travel.reference.length=8 m:16 m:3");
  try {
    (void)make_sweep_plan(req);
    ADD_FAILURE() << "accepted a field the case unshaped lacks";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("--vary travel.reference.length (case unshaped)"), std::string::npos) << what;
    EXPECT_NE(what.find("every value given"), std::string::npos) << what;
    EXPECT_NE(what.find("length"), std::string::npos) << what;
    EXPECT_EQ(what.find("(case zv)"), std::string::npos) << what;
    EXPECT_EQ(what.find("(case zvd)"), std::string::npos) << what;
  }
  req.cases.clear();
  try {
    (void)make_sweep_plan(req);
    ADD_FAILURE() << "accepted a field the file's model lacks";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("every value given"), std::string::npos) << what;
    EXPECT_EQ(what.find("(case "), std::string::npos) << what;
  }
  // A unit that does not fit is still told as such, on the case that has the field.
  req.cases = {"zv"};
  req.vary = {"travel.reference.length=8 s:16 s:3"};
  try {
    (void)make_sweep_plan(req);
    ADD_FAILURE() << "accepted seconds for a length";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("does not fit travel.reference.length"), std::string::npos) << e.what();
  }
  // A value every case refuses alike is told once, without a case.
  req.cases = {"unshaped", "zv", "zvd"};
  req.vary = {"rope.length=8 s:16 s:3"};
  try {
    (void)make_sweep_plan(req);
    ADD_FAILURE() << "accepted seconds for a rope length";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("does not fit rope.length"), std::string::npos) << what;
    EXPECT_EQ(what.find("(case "), std::string::npos) << what;
    EXPECT_EQ(what.find("does not fit"), what.rfind("does not fit")) << what;
  }
}

// Claim: from the command line, `machdyn sweep --case zv` over the case's field writes the table
// whose sway columns equal `machdyn simulate --case zv --set ...`'s summary.json (to kCaseVsBooks), `--plot
// rope.residual_sway_rad` draws them (with its quantity and unit), and the same sweep over
// `--all-cases` exits 2 naming the case that lacks the field, writing nothing.
TEST(SweepSway, CommandLineCaseSweepAndPlot) {
  const std::string model = "'" + test::example("crane/trolley-sway.yaml") + "'";
  const std::string common = " --set simulation.t_end=25 --vary \"travel.reference.length=10 m,14 m\"";
  const bool plot = test::have_gnuplot();
  auto r = test::run_cli("sweep " + model + " --case zv" + common + " --jobs 1 -o sw" +
                         (plot ? " --plot rope.residual_sway_rad" : ""));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto table = test::lines_of(test::slurp(test::temp_dir() / "sw" / "sweep.csv"));
  ASSERT_EQ(table.size(), 3u);
  const auto header = split_csv_line(table[0]);
  const char* lengths[] = {"10 m", "14 m"};
  for (size_t i = 0; i < 2; ++i) {
    const std::string dir = "one" + std::to_string(i);
    r = test::run_cli("simulate " + model + " --case zv --set simulation.t_end=25 --set \"travel.reference.length=" +
                      lengths[i] + "\" -o " + dir);
    ASSERT_EQ(r.exit_code, 0) << r.err;
    std::ifstream in(test::temp_dir() / dir / "zv" / "summary.json");  // OUT/CASE/ (README)
    const auto j = nlohmann::json::parse(in);
    expect_sway_equal(header, split_csv_line(table[i + 1]), j, lengths[i], kCaseVsBooks);
  }
  if (plot) {
    const auto svg = test::slurp(test::temp_dir() / "sw" / "plot-rope.residual_sway_rad-vs-travel.reference.length-vs-case.svg");
    EXPECT_NE(svg.find("residual sway of rope"), std::string::npos);
  }
  r = test::run_cli("sweep " + model + " --all-cases" + common + " -o bad");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("(case unshaped)"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(test::temp_dir() / "bad" / "sweep.csv"));
}

/// A trolley move of 40 t on 12 m (the PI drive of examples/crane/trolley-sway.yaml): 0 → 0.63 m/s
/// over the ramp's `end`, its reference `reference` (a `shaped` one with `shaper: none`, or the ramp).
std::string move_model(const std::string& reference) {
  return "name: trolley move\nbodies:\n  trolley: {type: translational, mass: 8 t}\n"
         "  load: {type: point-mass, mass: 40 t, axes: [x, z]}\n"
         "links:\n  rope: {type: spatial-rope, load: load, trolley: trolley, length: 12 m, EA: 1.2e8 N, falls: 4, "
         "damping: 20 kN*s/m, sway_after: 14 s}\n"
         "drives:\n  travel:\n    type: speed-drive\n    body: trolley\n    reference: " + reference + "\n"
         "    gain: 4e5 N*s/m\n    integral_time: 0.5 s\n    torque_limit: 60 kN\n"
         "simulation: {t_end: 20 s, dt_out: 10 ms}\n";
}

// Claim: one model file states the move and one --vary over `travel.reference.shaper` runs it unshaped
// (`none`) and shaped (zv, zvd, two-step) in ONE sweep, over the ramp's end: every ok row's sway columns
// and steps are `simulate`'s of the same point, bit for bit (the sweep keeps no series, its summary is
// the run's own); the `none` rows are the unshaped model's (the ramp itself as reference); the shapers
// designed for the rope's 12 m leave a fifth of the unshaped residual at most; the two-step move that
// cannot coast (a ramp of 8 s: its first half outlasts half a period, 3.5 s) is an error row with its
// message, and the sweep's other rows are all there (run_sweep: 7 ok, 1 error, the table complete).
TEST_P(SweepSwayBoth, OneSweepOverTheShaperKind) {
  const std::string shaped = test::write_temp(
      "move-shaped.yaml", move_model("{type: shaped, shaper: none, length: 12 m, signal: {type: ramp, value: 0.63 m/s, end: 3 s}}"));
  const std::string plain = test::write_temp("move-plain.yaml", move_model("{type: ramp, value: 0.63 m/s, end: 3 s}"));
  SweepRequest req;
  req.model_path = shaped;
  req.sets = {"simulation.integrator=" + GetParam()};
  req.vary = {"travel.reference.signal.end=3 s,8 s", "travel.reference.shaper=none,zv,zvd,two-step"};
  const auto plan = make_sweep_plan(req);
  ASSERT_EQ(plan.runs.size(), 8u);
  const auto cols = standard_summary_columns();
  const auto header = split_csv_line(sweep_header(plan, cols));
  const size_t status = sway_column(header, "status"), residual = sway_column(header, "rope.residual_sway_rad");
  std::vector<std::vector<std::string>> rows;
  for (const auto& run : plan.runs) rows.push_back(split_csv_line(execute_run(plan, run, cols)));
  for (size_t i = 0; i < rows.size(); ++i) {
    const auto& run = plan.runs[i];
    const std::string end = run.values[0].text, kind = run.values[1].text, what = kind + ", end " + end;
    ASSERT_EQ(rows[i].size(), header.size()) << what;
    if (kind == "two-step" && end == "8 s") {
      EXPECT_EQ(rows[i][status], "error") << what;
      EXPECT_NE(rows[i].back().find("no coasting"), std::string::npos) << rows[i].back();
      EXPECT_EQ(rows[i][residual], "") << what;
      continue;
    }
    ASSERT_EQ(rows[i][status], "ok") << what << ": " << rows[i].back();
    auto sets = req.sets;
    sets.push_back("travel.reference.signal.end=" + end);
    sets.push_back("travel.reference.shaper=" + kind);
    const Model m = load_model(shaped, sets);
    const SimulationResult r = simulate(m);
    EXPECT_EQ(std::stol(rows[i][sway_column(header, "steps")]), r.stats.stepper.steps) << what;
    expect_sway_equal(header, rows[i], simulation_summary(m, r), what);
    if (kind == "none") {  // the unshaped model: the same run
      const Model u = load_model(plain, {"simulation.integrator=" + GetParam(), "travel.reference.end=" + end});
      const SimulationResult ru = simulate(u);
      EXPECT_EQ(std::stol(rows[i][sway_column(header, "steps")]), ru.stats.stepper.steps) << what;
      expect_sway_equal(header, rows[i], simulation_summary(u, ru), what + " against the plain ramp");
    }
  }
  // Rows 0–3: end 3 s, none, zv, zvd, two-step (the last --vary fastest).
  const double unshaped = std::stod(rows[0][residual]);
  EXPECT_GT(unshaped, 0.01);
  for (size_t i = 1; i < 4; ++i) EXPECT_LT(std::stod(rows[i][residual]), unshaped / 5) << plan.runs[i].values[1].text;
  // The whole sweep on two threads: every finished row in the table, the failing one reported.
  SweepOptions opt;
  opt.out_dir = (test::temp_dir() / ("shapers-" + GetParam())).string();
  opt.jobs = 2;
  const SweepOutcome out = run_sweep(plan, opt);
  ASSERT_TRUE(out.complete);
  EXPECT_EQ(out.ok, 7);
  EXPECT_EQ(out.errors, 1);
  const auto table = test::lines_of(test::slurp(out.table_path));
  ASSERT_EQ(table.size(), 9u);
  for (size_t i = 0; i < rows.size(); ++i) EXPECT_EQ(split_csv_line(table[i + 1]), rows[i]) << "run " << i;
}

}  // namespace MACHDYN_UNITY_ID
}  // namespace machdyn
