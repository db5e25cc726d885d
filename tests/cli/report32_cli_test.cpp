// Issue 32, items 11–14 and 17 at the command line: --links and --frf-* of `report`, figures of
// `simulate --all-cases --plot`, titles that fit their figure, sweep curves per case, the topology
// words of end stops and freewheels, and the examples list.
#include <filesystem>
#include <string>
#include <gtest/gtest.h>

#include "support/support.hpp"

#include "machdyn/analysis/topology.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/plot.hpp"
#include "machdyn/io/report.hpp"
#include "machdyn/model/cases.hpp"
#include "machdyn/sweep/plan.hpp"
#include "machdyn/sweep/plot_data.hpp"
#include "machdyn/sweep/runner.hpp"
#include "machdyn/sweep/table.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

namespace fs = std::filesystem;
bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Claim: `report --links` draws only the links named (its page has no chart of the other) and an
// unknown link or a bad --frf-band is a located input error (exit 2) before any run; --frf-input
// names the Bode plot's input in the page.
TEST(Report32Cli, LinksAndFrequencyResponseOptions) {
  if (!report::assets_available()) GTEST_SKIP() << "built with MACHDYN_REPORT=OFF: no report";
  const std::string model = test::example("hoist-3mass.yaml");
  const auto out = test::temp_dir() / "r32-links.html";
  const auto ok = test::run_cli("report '" + model + "' --quiet -o '" + out.string() + "' --links c2 --frf-input I1 "
                                "--frf-output c2.load --frf-band 1:200");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const std::string html = test::slurp(out);
  EXPECT_TRUE(has(html, "link loads (c2)")) << "title names the chosen link";
  EXPECT_FALSE(has(html, "\"name\":\"c1 (")) << "c1 is not drawn";
  EXPECT_TRUE(has(html, "from I1")) << "the Bode plot names its input";
  const auto bad = test::run_cli("report '" + model + "' --quiet -o '" + out.string() + "' --links shaft");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_TRUE(has(bad.err, "--links")) << bad.err;
  EXPECT_TRUE(has(bad.err, "c1, c2")) << bad.err;
  const auto band = test::run_cli("report '" + model + "' --quiet -o '" + out.string() + "' --frf-band 5:1");
  EXPECT_EQ(band.exit_code, 2);
  EXPECT_TRUE(has(band.err, "--frf-band")) << band.err;
}

// Claim: `simulate --all-cases --plot` writes each case's figures into its folder and says so.
TEST(Report32Cli, AllCasesPlotWritesFigures) {
  if (!test::have_gnuplot()) GTEST_SKIP() << "gnuplot not installed: figures not checked";
  const auto r = test::run_cli("simulate '" + test::example("drives.yaml") +
                               "' --all-cases --plot --quiet -o r32-cases --set simulation.t_end=0.2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* c : {"direct", "inverter"})
    for (const char* f : {"link_loads.svg", "link_loads.png", "body_speeds.svg"})
      EXPECT_TRUE(fs::exists(test::temp_dir() / "r32-cases" / c / f)) << c << "/" << f;
  EXPECT_TRUE(has(r.out, "figures: ")) << r.out;
}

// Claim: a title longer than the canvas is broken into lines of at most 84 characters at a "; ",
// ": " or ", " (gnuplot cut the contacts figure's title off at both ends); a short one stays whole.
TEST(Report32Cli, LongTitlesAreBroken) {
  plot::Figure f;
  f.id = "t";
  f.title = "Main hoist 32 t [estop]: contacts: force (solid, left), sliding velocity (dashed, right); dotted: events";
  f.x = plot::make_axis("time t", "s");
  f.y = plot::make_axis("F", "N");
  f.series.push_back(plot::make_series("a", {0, 1}, {0, 1}));
  const std::string g = plot::gnuplot_script(f, plot::Format::svg, "d", "o");
  const auto a = g.find("set title \""), e = g.find("\"\n", a + 11);
  ASSERT_NE(a, std::string::npos) << g;
  const std::string t = g.substr(a + 11, e - a - 11);
  ASSERT_TRUE(has(t, "\\n")) << t;
  std::size_t start = 0;
  for (std::size_t p; (p = t.find("\\n", start)) != std::string::npos || start < t.size(); start = p + 2) {
    const std::string line = t.substr(start, p == std::string::npos ? std::string::npos : p - start);
    std::size_t chars = 0;
    for (const char ch : line) chars += (static_cast<unsigned char>(ch) & 0xC0) != 0x80;
    EXPECT_LE(chars, 84u) << line;
    if (p == std::string::npos) break;
  }
  f.title = "short";
  EXPECT_TRUE(has(plot::gnuplot_script(f, plot::Format::svg, "d", "o"), "set title \"short\"\n"));
}

// Claim: with load cases, a sweep plot against one varied field draws one curve per case (it joined
// both cases' points into one zig-zag line), and its x axis carries the field's unit.
TEST(Report32Cli, SweepPlotOneCurvePerCase) {
  SweepRequest req;
  req.model_path = test::example("drives.yaml");
  req.sets = {"simulation.t_end=0.05"};
  req.vary = {"c1.stiffness=1e4,2e4,3e4"};
  req.cases = {"direct", "inverter"};
  req.apply_case = [](SpecNode& spec, const std::string& name) { apply_case(spec, name); };
  const auto plan = make_sweep_plan(req);
  SweepOptions o;
  o.out_dir = (test::temp_dir() / "r32-sweep").string();
  o.jobs = 1;
  const auto out = run_sweep(plan, o);
  const auto header = sweep_header(plan, standard_summary_columns());
  const auto spec = parse_plot_spec("c1.max_N_m:c1.stiffness", plan, header);
  ASSERT_EQ(spec.inputs.size(), 2u);
  EXPECT_EQ(spec.inputs[1], "case");
  EXPECT_EQ(spec.input_axes[0].label(), "c1.stiffness, N·m/rad");
  const auto fig = sweep_plot_figure(sweep_plot_csv(out.table_path, spec), spec);
  ASSERT_EQ(fig.series.size(), 2u);
  for (const auto& s : fig.series) EXPECT_EQ(s.x, (std::vector<double>{1e4, 2e4, 3e4})) << s.name;
}

// Claim: the x axis of a sweep carries the unit of the fields a crane engineer sweeps: a rope's EA
// and length, a stop's position, the crane section's hoisting speed.
TEST(Report32Cli, SweepFieldUnits) {
  const Model m = test::model_text(R"(
gravity: 9.81 m/s^2
bodies:
  drum: {inertia: 10 kg*m^2}
  hook: {type: translational, mass: 1 t, vertical: up}
links:
  rope: {type: rope, between: [drum, hook], ratio: 4 rad/m, falls: 2, EA: 1e7 N, length: 10 m}
stops:
  floor: {body: hook, min: 0 m}
simulation: {t_end: 0.1 s}
)");
  EXPECT_EQ(field_unit(m, "rope.EA"), "N");
  EXPECT_EQ(field_unit(m, "rope.length"), "m");
  EXPECT_EQ(field_unit(m, "floor.min"), "m");
  EXPECT_EQ(field_unit(m, "crane.hoist_speed"), "m/s");
}

// Claim: an end stop takes `open` (off the stop, no constraint: = released) and `closed` (= stuck),
// a freewheel `locked` and `free`; a wrong word lists the element's own words.
TEST(Report32Cli, TopologyWordsOfStopsAndFreewheels) {
  const Model m = test::model_text(R"(
gravity: 9.81 m/s^2
bodies:
  drum: {inertia: 10 kg*m^2}
  hook: {type: translational, mass: 1 t, vertical: up}
links:
  rope: {type: rope, between: [drum, hook], ratio: 4 rad/m, stiffness: 1e6 N/m}
stops:
  ground: {body: hook, min: 0 m}
simulation: {t_end: 0.1 s}
)");
  const Topology open = parse_topology(m, "ground=open, rope=closed", Location{"t", 1, 0});
  const Topology released = parse_topology(m, "ground=released, rope=closed", Location{"t", 1, 0});
  EXPECT_EQ(topology_label(m, open), topology_label(m, released));
  const Topology closed = parse_topology(m, "ground=closed", Location{"t", 1, 0});
  EXPECT_EQ(topology_label(m, closed), topology_label(m, parse_topology(m, "ground=stuck", Location{"t", 1, 0})));
  try {
    (void)parse_topology(m, "ground=lifted", Location{"t", 1, 0});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_TRUE(has(e.what(), "end stop 'ground'")) << e.what();
    EXPECT_TRUE(has(e.what(), "closed (at the stop), open (off it)")) << e.what();
  }
}

}  // namespace
}  // namespace machdyn
