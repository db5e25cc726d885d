// Sweeps through the library: plans and their input errors, tables identical for any thread
// count, failing runs as rows, the journal (torn lines, resume, refusal to overwrite), stop.
#include <filesystem>
#include <fstream>
#include <sstream>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "machdyn/sweep/journal.hpp"
#include "machdyn/sweep/plot_data.hpp"
#include "machdyn/sweep/runner.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::slurp;
using test::lines_of;

namespace fs = std::filesystem;



SweepRequest hoist_request(std::vector<std::string> vary) {
  SweepRequest r;
  r.model_path = test::example("hoist-3mass.yaml");
  r.sets = {"simulation.t_end=0.2"};
  r.vary = std::move(vary);
  return r;
}

SweepOutcome run_into(const SweepPlan& plan, const fs::path& dir, int jobs, bool resume = false) {
  SweepOptions o;
  o.out_dir = dir.string();
  o.jobs = jobs;
  o.resume = resume;
  return run_sweep(plan, o);
}

// Claim: a grid plan has n1·n2 runs in row-major order (first --vary slowest) and each run's
// spec is the base with exactly its values set.
TEST(SweepPlan, GridRunsInDocumentedOrder) {
  const auto plan = make_sweep_plan(hoist_request({"c1.stiffness=1e4:3e4:3", "I3.inertia=0.2,0.25"}));
  ASSERT_EQ(plan.runs.size(), 6u);
  EXPECT_EQ(plan.description, "grid 3 × 2 = 6 runs");
  EXPECT_EQ(plan.runs[1].values[0].si, 1e4);
  EXPECT_EQ(plan.runs[1].values[1].si, 0.25);
  EXPECT_EQ(plan.runs[2].values[0].si, 2e4);
  EXPECT_EQ(plan.runs[2].values[1].si, 0.2);
  const Model m = compile_model(run_spec(plan, plan.runs[5]), plan.request.model_path);
  EXPECT_EQ(m.links[0].c, 3e4);
  EXPECT_EQ(m.bodies[2].inertia, 0.25);
  EXPECT_EQ(m.simulation.t_end, 0.2);  // the --set of the base
}

// Claim: LHS and random plans have --samples runs whose values stay inside the ranges, and the
// same request gives the same runs.
TEST(SweepPlan, SampledPlansHaveSamplesRunsInsideRanges) {
  auto req = hoist_request({"c1.stiffness=1e4:5e4", "I3.inertia=0.1:1:log"});
  req.method = SweepMethod::lhs;
  req.samples = 16;
  req.seed = 3;
  const auto a = make_sweep_plan(req);
  const auto b = make_sweep_plan(req);
  ASSERT_EQ(a.runs.size(), 16u);
  for (size_t i = 0; i < a.runs.size(); ++i) {
    EXPECT_GE(a.runs[i].values[0].si, 1e4);
    EXPECT_LT(a.runs[i].values[0].si, 5e4);
    EXPECT_GE(a.runs[i].values[1].si, 0.1);
    EXPECT_LT(a.runs[i].values[1].si, 1.0);
    EXPECT_EQ(a.runs[i].values[0].text, b.runs[i].values[0].text);
  }
  EXPECT_EQ(a.fingerprint, b.fingerprint);
  req.method = SweepMethod::random;
  EXPECT_EQ(make_sweep_plan(req).runs.size(), 16u);
  req.seed = 4;
  EXPECT_NE(make_sweep_plan(req).fingerprint, a.fingerprint);
}

// Claim: mistakes in --vary are input errors before any run: an unknown element, an unknown field,
// a unit that does not fit the field, values all rejected, a grid range without n, a sampled
// method without --samples.
TEST(SweepPlan, VaryMistakesAreInputErrorsBeforeAnyRun) {
  auto expect_error = [](SweepRequest req, const std::string& part) {
    try {
      (void)make_sweep_plan(req);
      ADD_FAILURE() << "no error; expected one saying '" << part << "'";
    } catch (const InputError& e) {
      std::string all;
      for (const auto& d : e.diagnostics()) all += d.str() + "\n";
      EXPECT_NE(all.find(part), std::string::npos) << all;
    }
  };
  expect_error(hoist_request({"c9.stiffness=1:2:2"}), "no element named 'c9'");
  expect_error(hoist_request({"c1.stifness=1:2:2"}), "stifness");
  expect_error(hoist_request({"c1.stiffness=2 mm:8 mm:4"}), "the unit of '2 mm' does not fit c1.stiffness");
  expect_error(hoist_request({"c1.stiffness=1e4,2 mm"}), "the unit of '2 mm' does not fit c1.stiffness");
  expect_error(hoist_request({"c1.stiffness=-2:-1:3"}), "every value given (-2, -1) is rejected");
  expect_error(hoist_request({"c1.stiffness=1e4:2e4"}), "a grid needs the number of points");
  auto lhs = hoist_request({"c1.stiffness=1e4:2e4"});
  lhs.method = SweepMethod::lhs;
  expect_error(lhs, "needs --samples");
  lhs.samples = 4;
  lhs.vary = {"c1.stiffness=1e4:2e4:3"};
  expect_error(lhs, "drop the n");
}

// Claim: the table is byte-identical for 1 and 2 worker threads, and its rows are in run order.
TEST(Sweep, TableIdenticalForOneAndTwoThreads) {
  const auto plan = make_sweep_plan(hoist_request({"c1.stiffness=1e4:5e4:5", "c2.stiffness=5e3,9e3,2e4"}));
  const auto d1 = test::temp_dir() / "threads1", d2 = test::temp_dir() / "threads2";
  const auto r1 = run_into(plan, d1, 1);
  const auto r2 = run_into(plan, d2, 2);
  ASSERT_TRUE(r1.complete && r2.complete);
  EXPECT_EQ(r1.ok, 15);
  const auto t1 = slurp(d1 / "sweep.csv");
  EXPECT_EQ(t1, slurp(d2 / "sweep.csv"));
  const auto rows = lines_of(t1);
  ASSERT_EQ(rows.size(), 16u);
  for (size_t i = 1; i < rows.size(); ++i) EXPECT_EQ(rows[i].substr(0, rows[i].find(',')), std::to_string(i - 1));
}

// Claim: a row holds the run's summary exactly as simulate() gives it for the same overrides.
TEST(Sweep, RowEqualsASingleSimulation) {
  const auto plan = make_sweep_plan(hoist_request({"c1.stiffness=3e4"}));
  const auto row = split_csv_line(execute_run(plan, plan.runs[0], standard_summary_columns()));
  const auto header = split_csv_line(sweep_header(plan, standard_summary_columns()));
  ASSERT_EQ(row.size(), header.size());
  const auto r = simulate(load_model(test::example("hoist-3mass.yaml"), {"simulation.t_end=0.2", "c1.stiffness=3e4"}));
  auto col = [&](const std::string& name) { return row[std::find(header.begin(), header.end(), name) - header.begin()]; };
  EXPECT_EQ(std::stod(col("c1.max_N_m")), r.links[0].max);
  EXPECT_EQ(std::stod(col("c2.dynamic_factor")), r.links[1].dynamic_factor);
  EXPECT_EQ(std::stol(col("steps")), r.stats.stepper.steps);
  EXPECT_EQ(col("status"), "ok");
}

// Claim: runs that fail — a value the field rejects (negative stiffness) or a solver failure
// (max_steps exceeded) — are rows with status error and the message; the others are ok.
TEST(Sweep, FailingRunsAreErrorRowsAmongGoodOnes) {
  const auto plan = make_sweep_plan(hoist_request({"c1.stiffness=-1e4,2.4e4", "simulation.max_steps=5,1000000"}));
  const auto dir = test::temp_dir() / "failing";
  const auto out = run_into(plan, dir, 2);
  ASSERT_TRUE(out.complete);
  EXPECT_EQ(out.ok, 1);
  EXPECT_EQ(out.errors, 3);
  const auto rows = lines_of(slurp(dir / "sweep.csv"));
  ASSERT_EQ(rows.size(), 5u);
  const auto header = split_csv_line(rows[0]);
  const auto r0 = split_csv_line(rows[1]), r2 = split_csv_line(rows[3]), r3 = split_csv_line(rows[4]);
  EXPECT_EQ(r0.size(), header.size());
  EXPECT_EQ(r0[r0.size() - 2], "error");
  EXPECT_NE(r0.back().find("stiffness"), std::string::npos) << r0.back();
  EXPECT_EQ(r2[r2.size() - 2], "error");  // 2.4e4 with max_steps 5
  EXPECT_NE(r2.back().find("steps"), std::string::npos) << r2.back();
  EXPECT_EQ(r3[r3.size() - 2], "ok");
  EXPECT_EQ(r2[3], "");  // summary columns of an error row are empty
}

// Claim: a journal with a torn last line (a kill during write) and lost rows, resumed, gives the
// same table as an uninterrupted sweep, without duplicating the rows it kept.
TEST(Sweep, ResumeAfterTornJournalGivesSameTable) {
  const auto plan = make_sweep_plan(hoist_request({"c1.stiffness=1e4:5e4:4", "I2.inertia=0.3,0.45,0.6"}));
  const auto full = test::temp_dir() / "resume-full", cut = test::temp_dir() / "resume-cut";
  ASSERT_TRUE(run_into(plan, full, 2).complete);
  // Keep the header record, 5 rows (out of order, as workers finish) and half of the 6th.
  const auto journal = lines_of(slurp(full / "sweep.journal"));
  ASSERT_EQ(journal.size(), 13u);
  std::string kept = journal[0] + "\n";
  for (int k : {3, 1, 7, 2, 10}) kept += journal[static_cast<size_t>(k)] + "\n";
  kept += journal[11].substr(0, journal[11].size() / 2);
  fs::create_directories(cut);
  std::ofstream(cut / "sweep.journal", std::ios::binary) << kept;

  const auto out = run_into(plan, cut, 2, /*resume=*/true);
  ASSERT_TRUE(out.complete);
  EXPECT_EQ(out.from_journal, 5);
  EXPECT_EQ(out.dropped, 1);
  EXPECT_EQ(out.computed, 7);
  EXPECT_EQ(slurp(cut / "sweep.csv"), slurp(full / "sweep.csv"));
  EXPECT_EQ(lines_of(slurp(cut / "sweep.journal")).size(), 13u);  // header + 12 rows, none twice

  // Resuming a finished sweep computes nothing and rewrites the same table.
  const auto again = run_into(plan, cut, 1, true);
  EXPECT_EQ(again.computed, 0);
  EXPECT_EQ(slurp(cut / "sweep.csv"), slurp(full / "sweep.csv"));
}

// Claim: a journal record is valid only whole and unaltered.
TEST(Sweep, JournalRecordsDetectDamage) {
  const auto rec = journal_record("3,1e4,ok,");
  std::string text;
  EXPECT_TRUE(parse_journal_record(rec, text));
  EXPECT_EQ(text, "3,1e4,ok,");
  EXPECT_FALSE(parse_journal_record(rec.substr(0, rec.size() - 1), text));  // no newline
  std::string flipped = rec;
  flipped[2] = '2';
  EXPECT_FALSE(parse_journal_record(flipped, text));
  EXPECT_FALSE(parse_journal_record(std::string(40, '\0') + "\n", text));
}

// Claim: a new sweep never overwrites a journal holding rows — neither of the same plan nor of a
// changed one (the README's `:5` → `:6`) — and --resume refuses the journal of another sweep; the
// earlier journal and table stay byte for byte.
TEST(Sweep, JournalIsNeverOverwrittenByMistake) {
  const auto plan = make_sweep_plan(hoist_request({"c1.stiffness=1e4,2e4"}));
  const auto dir = test::temp_dir() / "guard";
  ASSERT_TRUE(run_into(plan, dir, 1).complete);
  const std::string journal = slurp(dir / "sweep.journal"), table = slurp(dir / "sweep.csv");
  EXPECT_THROW(run_into(plan, dir, 1), InputError);
  const auto other = make_sweep_plan(hoist_request({"c1.stiffness=1e4,3e4"}));
  EXPECT_THROW(run_into(other, dir, 1, true), InputError);
  const auto changed = make_sweep_plan(hoist_request({"c1.stiffness=1e4:2e4:3"}));
  try {
    run_into(changed, dir, 1);
    ADD_FAILURE() << "a changed plan replaced the finished sweep";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("another sweep"), std::string::npos) << e.what();
  }
  EXPECT_EQ(slurp(dir / "sweep.journal"), journal);
  EXPECT_EQ(slurp(dir / "sweep.csv"), table);
  EXPECT_EQ(lines_of(journal).size(), 3u);
  // A file that is not a journal is not ours to replace.
  const auto alien = test::temp_dir() / "guard-alien";
  fs::create_directories(alien);
  std::ofstream(alien / "sweep.journal") << "my notes\n";
  EXPECT_THROW(run_into(plan, alien, 1), InputError);
  EXPECT_EQ(slurp(alien / "sweep.journal"), "my notes\n");
}

// Claim: with the stop flag set no run starts, no table is written, and --resume then finishes.
TEST(Sweep, StopLeavesJournalAndNoTable) {
  const auto plan = make_sweep_plan(hoist_request({"c1.stiffness=1e4,2e4,3e4"}));
  const auto dir = test::temp_dir() / "stop";
  std::atomic<bool> stop{true};
  SweepOptions o;
  o.out_dir = dir.string();
  o.stop = &stop;
  const auto r = run_sweep(plan, o);
  EXPECT_FALSE(r.complete);
  EXPECT_FALSE(fs::exists(dir / "sweep.csv"));
  EXPECT_TRUE(fs::exists(dir / "sweep.journal"));
  EXPECT_TRUE(run_into(plan, dir, 1, true).complete);
}

// Claim: the case hook makes the case the outermost factor with a `case` column: runs
// [c·P, (c+1)·P) are case c over the same points.
TEST(Sweep, CasesAreTheOutermostFactor) {
  auto req = hoist_request({"c1.stiffness=1e4,2e4"});
  req.cases = {"light", "heavy"};
  req.apply_case = [](SpecNode& s, const std::string& name) {
    apply_set(s, name == "heavy" ? "MB.value=-400" : "MB.value=-100");
  };
  const auto plan = make_sweep_plan(req);
  ASSERT_EQ(plan.runs.size(), 4u);
  const auto header = sweep_header(plan, standard_summary_columns());
  EXPECT_EQ(header.substr(0, 31), "run,case,c1.stiffness,c1.max_N_");
  const auto row2 = split_csv_line(execute_run(plan, plan.runs[2], standard_summary_columns()));
  EXPECT_EQ(row2[1], "heavy");
  EXPECT_EQ(row2[2], "10000");
  auto bad = req;
  bad.apply_case = [](SpecNode&, const std::string& name) {
    throw InputError(Location{"--case", 0, 0}, "no case '" + name + "'");
  };
  EXPECT_THROW(make_sweep_plan(bad), InputError);
}

// Claim: the plot data holds the chosen inputs and output of the ok rows, in run order; an unknown
// output column is an input error naming the columns.
TEST(Sweep, PlotDataPicksColumns) {
  const auto plan = make_sweep_plan(hoist_request({"c1.stiffness=-1,1e4,2e4", "I3.inertia=0.2,0.3"}));
  const auto dir = test::temp_dir() / "plot";
  const auto out = run_into(plan, dir, 2);
  const auto header = sweep_header(plan, standard_summary_columns());
  const auto spec = parse_plot_spec("c2.max_N_m", plan, header);
  EXPECT_EQ(spec.inputs, (std::vector<std::string>{"c1.stiffness", "I3.inertia"}));
  const auto data = lines_of(sweep_plot_csv(out.table_path, spec));
  ASSERT_EQ(data.size(), 5u);  // header + 4 ok runs (c1.stiffness = -1 fails)
  EXPECT_EQ(data[0], "c1.stiffness,I3.inertia,c2.max_N_m");
  EXPECT_EQ(data[1].substr(0, 10), "10000,0.2,");
  EXPECT_EQ(parse_plot_spec("c1.static_N_m:I3.inertia", plan, header).inputs, std::vector<std::string>{"I3.inertia"});
  EXPECT_THROW(parse_plot_spec("c3.max", plan, header), InputError);
  EXPECT_THROW(parse_plot_spec("c1.max_N_m:c2.stiffness", plan, header), InputError);
}

// Claim: a sweep plot names the model and what it shows in its title, gives every swept field
// its unit (also those a plain lookup of value/stiffness misses: a motor's stall torque, a ramp's
// end time) and draws a log-spaced design (`:log`) on a log axis, a linear one on a linear axis.
TEST(Sweep, PlotHasTitleUnitsAndLogAxes) {
  const std::string model = test::write_temp("sweep-units.yaml", R"(name: motor ramp
bodies:
  A: {inertia: 1}
  B: {inertia: 2}
links:
  c: {type: spring, between: [A, B], stiffness: 1e4}
loads:
  M: {type: motor-linear, body: A, stall_torque: 100 N*m, no_load_speed: 100 rad/s}
  R: {type: ramp, body: B, value: -20 N*m, end: 0.1 s}
simulation: {t_end: 0.2}
)");
  SweepRequest req;
  req.model_path = model;
  req.vary = {"M.stall_torque=50:500:3:log", "R.end=0.05:0.15:3"};
  const auto plan = make_sweep_plan(req);
  const auto header = sweep_header(plan, standard_summary_columns());
  const auto spec = parse_plot_spec("c.max_N_m:M.stall_torque:R.end", plan, header);
  ASSERT_EQ(spec.input_axes.size(), 2u);
  EXPECT_EQ(spec.input_axes[0].label(), "M.stall_torque, N·m");
  EXPECT_TRUE(spec.input_axes[0].log);
  EXPECT_EQ(spec.input_axes[1].label(), "R.end, s");
  EXPECT_FALSE(spec.input_axes[1].log);
  EXPECT_EQ(spec.title, "motor ramp: peak load of c against M.stall_torque and R.end");
  const std::string csv = "M.stall_torque,R.end,c.max_N_m\n50,0.05,1\n158.1,0.05,2\n500,0.05,3\n"
                          "50,0.15,1.5\n158.1,0.15,2.5\n500,0.15,3.5\n";
  const plot::Figure f = sweep_plot_figure(csv, spec);
  EXPECT_EQ(f.title, spec.title);
  EXPECT_TRUE(f.x.log);
  EXPECT_NE(plot::gnuplot_script(f, plot::Format::svg, "d", "o").find("set logscale x"), std::string::npos);
  EXPECT_EQ(f.series[0].name, "R.end = 0.05 s");
}

}  // namespace
}  // namespace machdyn
