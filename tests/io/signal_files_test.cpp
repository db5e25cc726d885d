// Measured signals from CSV files (io/signal_files.hpp): read into a table with the header's or the
// spec's units, relative to the model file; every problem named with the CSV's row and column and
// the model file's place of the signal.
#include <filesystem>
#include <string>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

/// Writes `csv` beside a model whose load R.`sig` is `signal`, compiles it.
Model with_csv(const std::string& stem, const std::string& csv, const std::string& signal) {
  test::write_temp(stem + ".csv", csv);
  return load_model(test::write_temp(stem + ".yaml", "bodies:\n  R: {inertia: 1}\nloads:\n  sig: {body: R, " + signal +
                                                         "}\nsimulation: {t_end: 5 s}\n"));
}

std::string errors(const std::string& stem, const std::string& csv, const std::string& signal) {
  try {
    with_csv(stem, csv, signal);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Claim: the columns chosen by name (with or without their unit) give the table of the record, in SI
// from the header's units (ms, kN*m); comment lines and blank lines are skipped; equal times jump.
TEST(SignalFiles, ReadsColumnsByNameWithHeaderUnits) {
  const Model m = with_csv("rec", "# a record\nangle_deg,t_ms,torque_kN*m\n0,0,1\n\n5,500,2\n5,500,4\n9,1000,3\n",
                           "type: file, path: rec.csv, time: t, column: torque_kN*m");
  const Load& l = m.loads[0];
  EXPECT_EQ(l.kind, LoadKind::signal);
  EXPECT_DOUBLE_EQ(test::load_at(l, 0.25, 0, 0), 1500.0);
  EXPECT_DOUBLE_EQ(test::load_at(l, 0.5, 0, 0), 4000.0);  // two rows at one time: a jump
  EXPECT_DOUBLE_EQ(test::load_at(l, 3.0, 0, 0), 3000.0);  // held after the last row
  EXPECT_EQ(m.breakpoints(5.0), (std::vector<double>{0.5, 1.0}));
}

// Claim: units given in the spec override the header's; without any the numbers are SI; a file
// signal may be a term of a sum.
TEST(SignalFiles, SpecUnitsAndSums) {
  const Model m = with_csv("plain", "time;value\n0;1\n2;3\n",
                           "type: sum, terms: [{type: file, path: plain.csv, unit: kN*m, time_unit: min}, 5 N*m]");
  EXPECT_DOUBLE_EQ(test::load_at(m.loads[0], 60.0, 0, 0), 2005.0);  // t = 1 min of 2 min: 1 → 3 kN*m halfway
}

// Claim: a missing file is reported at the spec's `path` with the path looked for, and an unknown
// column at the spec's `column`, listing the file's columns — both at once.
TEST(SignalFiles, MissingFileAndUnknownColumnAreLocatedInTheModelFile) {
  test::write_temp("cols.csv", "t_s,F_N\n0,1\n");
  const std::string path = test::write_temp(
      "two-bad.yaml", "bodies:\n  R: {inertia: 1}\nloads:\n"
                      "  a: {body: R, type: file, path: nowhere.csv}\n"
                      "  b: {body: R, type: file, path: cols.csv, column: torque}\n");
  try {
    load_model(path);
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string all = e.what();
    EXPECT_NE(all.find("two-bad.yaml:4:34: error: load 'a': cannot open the signal file 'nowhere.csv'"), std::string::npos) << all;
    EXPECT_NE(all.find("two-bad.yaml:5:52: error: load 'b': field 'column': no column 'torque' in"), std::string::npos) << all;
    EXPECT_NE(all.find("its columns: t_s, F_N"), std::string::npos) << all;
    EXPECT_EQ(e.diagnostics().size(), 2u) << all;
  }
}

// Claim: a non-numeric cell, a short row and a decreasing time are errors at the CSV's row and
// column, naming the model file's place of the signal; all of them at once.
TEST(SignalFiles, BadRowsNameTheirRowAndColumn) {
  const std::string all = errors("rows", "t_s,torque_N*m\n0,1\n0.5, abc\n1\n1.2,3\n0.8,2\n",
                                 "type: file, path: rows.csv");
  const std::string csv = (test::temp_dir() / "rows.csv").string();
  EXPECT_NE(all.find(csv + ":3:6: error: load 'sig': column 'torque_N*m': expected a number, got 'abc' (the signal is given at"),
            std::string::npos) << all;
  EXPECT_NE(all.find(csv + ":4:2: error: load 'sig': the row has 1 cells; column 'torque_N*m' is number 2"), std::string::npos) << all;
  EXPECT_NE(all.find(csv + ":6:1: error: load 'sig': column 't_s': time 0.8 is earlier than the row before (1.2)"),
            std::string::npos) << all;
  EXPECT_NE(all.find("rows.yaml:4:"), std::string::npos) << all;  // where the signal is given
}

// Claim: a header unit of the wrong dimension is an error at the header cell (a force for a torque).
TEST(SignalFiles, WrongUnitIsLocatedAtTheHeader) {
  const std::string all = errors("force", "t_s,F_kN\n0,1\n1,2\n", "type: file, path: force.csv");
  const std::string csv = (test::temp_dir() / "force.csv").string();
  EXPECT_NE(all.find("got 'kN'"), std::string::npos) << all;
  EXPECT_NE(all.find(csv + ":1:5: error: load 'sig': field 'unit' expected a unit of a torque (N*m)"),
            std::string::npos) << all;
}

// Claim: the shipped example (examples/signals.yaml) reads its measured record relative to itself and
// runs; every row time inside the run, the contactor's closing (0.05 s) and the sine's start (0.1 s,
// both also row times) are breakpoints of the run: 299 rows at 0.01 … 2.99 s.
TEST(SignalFiles, ShippedExampleRunsWithItsRecord) {
  const Model m = load_model(test::example("signals.yaml"));
  SimulateOptions o;
  o.record_series = false;
  const SimulationResult r = simulate(m, o);
  ASSERT_EQ(r.hybrid.breakpoints.size(), 299u);
  EXPECT_DOUBLE_EQ(r.hybrid.breakpoints.front(), 0.01);
  EXPECT_DOUBLE_EQ(r.hybrid.breakpoints.back(), 2.99);
  EXPECT_GT(r.links[0].max, 0.0);
}

}  // namespace
}  // namespace machdyn
