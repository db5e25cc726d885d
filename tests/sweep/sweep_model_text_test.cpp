// A sweep of a model given as text (SweepRequest::model_text, the Python module's models from a
// string) is the sweep of the same file: same fingerprint, same runs, byte-identical table. And a
// spec compiled with compile_model_case is the model load_model_case reads from the file.
#include <filesystem>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/model/cases.hpp"
#include "machdyn/sweep/runner.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

namespace fs = std::filesystem;

TEST(SweepModelText, TextSweepEqualsTheFileSweepByteForByte) {
  SweepRequest file;
  file.model_path = test::example("hoist-3mass.yaml");
  file.sets = {"simulation.t_end=0.2"};
  file.vary = {"c1.stiffness=1e4:4e4:3", "I3.inertia=0.2,0.3"};
  SweepRequest text = file;
  text.model_text = test::slurp(file.model_path);
  const SweepPlan a = make_sweep_plan(file), b = make_sweep_plan(text);
  EXPECT_EQ(a.fingerprint, b.fingerprint);
  ASSERT_EQ(a.runs.size(), 6u);
  ASSERT_EQ(b.runs.size(), a.runs.size());
  const fs::path dir = test::temp_dir() / "sweep-model-text";
  fs::remove_all(dir);
  SweepOptions o;
  o.jobs = 2;
  o.out_dir = (dir / "file").string();
  const SweepOutcome ra = run_sweep(a, o);
  o.out_dir = (dir / "text").string();
  const SweepOutcome rb = run_sweep(b, o);
  ASSERT_TRUE(ra.complete && rb.complete);
  EXPECT_EQ(ra.ok, 6);
  EXPECT_EQ(test::slurp(ra.table_path), test::slurp(rb.table_path));
}

TEST(SweepModelText, BadTextIsAnInputErrorNamingTheSource) {
  SweepRequest r;
  r.model_path = "<string>";
  r.model_text = "bodies: {I1: {type: rotational, inertia: -1}}\n";
  r.vary = {"I1.inertia=1,2"};
  try {
    (void)make_sweep_plan(r);
    FAIL() << "no InputError";
  } catch (const InputError& e) {
    ASSERT_FALSE(e.diagnostics().empty());
    EXPECT_EQ(e.diagnostics()[0].where.file, "<string>");
  }
}

TEST(CompileModelCase, SpecFromTextEqualsTheFileWithCaseAndOverrides) {
  const std::string path = test::example("hoist-modes.yaml");
  const auto names = case_names(read_yaml_file(path));
  ASSERT_GE(names.size(), 2u);
  const std::vector<std::string> sets = {"c1.stiffness=3e4"};
  const Model a = load_model_case(path, sets, names[1]);
  const Model b = compile_model_case(parse_yaml_string(test::slurp(path), path), path, sets, names[1]);
  EXPECT_EQ(a.name, b.name);
  EXPECT_EQ(b.load_case, names[1]);
  const SimulationResult ra = simulate(a), rb = simulate(b);
  EXPECT_EQ(ra.columns, rb.columns);  // the same model gives the same doubles
}

}  // namespace
}  // namespace machdyn
