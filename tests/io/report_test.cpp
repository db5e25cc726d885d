// The HTML report: self-contained (nothing loaded from the network), the model and results as
// tables, every figure's data as one JSON block the page's charts read.
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/report.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "machdyn/analysis/crane.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

std::string hoist_report_html() {
  const Model m = load_model(test::example("hoist-3mass.yaml"), {"simulation.t_end=0.05"});
  const SimulationResult r = simulate(m);
  const Modes modes = compute_modes(m);
  report::Case c;
  c.model = &m, c.result = &r, c.modes = &modes;
  return report::to_html(report::simulation_report({c}, "machdyn report hoist-3mass.yaml"));
}

// Claim: the page embeds uPlot and loads nothing: no external script, stylesheet, image or import.
TEST(Report, SelfContainedNoNetwork) {
  if (!report::assets_available()) GTEST_SKIP() << "built with MACHDYN_REPORT=OFF: no report";
  EXPECT_EQ(report::uplot_version(), "1.6.32");
  const std::string h = hoist_report_html();
  EXPECT_NE(h.find("uPlot"), std::string::npos);
  for (const char* bad : {"<script src", "<link ", "@import", "url(http", "<img src=\"http", "<iframe"})
    EXPECT_EQ(h.find(bad), std::string::npos) << bad;
}

// Claim: the model, settings and results appear as tables with units; there is one data block per
// figure (link loads, body speeds, mode shapes) and a status element for tests.
TEST(Report, HasTablesWithUnitsAndFigures) {
  if (!report::assets_available()) GTEST_SKIP() << "built with MACHDYN_REPORT=OFF: no report";
  const std::string h = hoist_report_html();
  for (const char* s : {"<caption>Bodies</caption>", "kg·m²", "24000 N·m/rad", "M = 450 N·m", "<caption>Run settings",
                        "dopri5", "dynamic factor", "<td>354</td>", "185.102", "id=\"machdyn-status\""})
    EXPECT_NE(h.find(s), std::string::npos) << s;
  for (const char* id : {"data-figure=\"link_loads-1\"", "data-figure=\"body_speeds-2\"", "data-figure=\"mode_shapes-3\""})
    EXPECT_NE(h.find(id), std::string::npos) << id;
}

// Claim: a case with a crane analysis gets its own section: the factor table (the trolley's φ7 row
// with the standard's 1.25) and one chart per factor (data-figure="crane_phi7_0-…").
TEST(Report, CraneSectionHasTheTableAndAChartPerFactor) {
  if (!report::assets_available()) GTEST_SKIP() << "built with MACHDYN_REPORT=OFF: no report";
  const Model m = load_model(test::example("crane/trolley-buffers.yaml"));
  const SimulationResult r = simulate(m);
  const CraneReport cr = crane_analysis(m);
  report::Case c;
  c.model = &m, c.result = &r, c.crane = &cr;
  const report::Document d = report::simulation_report({c}, "machdyn report trolley-buffers.yaml");
  ASSERT_FALSE(d.sections.empty());
  const report::Section& s = d.sections.back();
  EXPECT_EQ(s.title, "Crane factors (EN 13001-2)");
  ASSERT_EQ(s.tables.size(), 1u);
  ASSERT_EQ(s.tables[0].rows.size(), 1u);
  EXPECT_EQ(s.tables[0].rows[0][0], "phi7");
  EXPECT_EQ(s.tables[0].rows[0][3], "1.25");
  ASSERT_EQ(s.figures.size(), 1u);
  const std::string h = report::to_html(d);
  EXPECT_NE(h.find("data-figure=\"crane_phi7_0"), std::string::npos);
}

// Claim: a figure's JSON has the columns [x, y1, ...] on one grid: shared when the series share x,
// else the sorted union with null where a series has no point; NaN is null; "</" cannot end the
// script element.
TEST(Report, FigureJsonColumns) {
  plot::Figure f;
  f.id = "f";
  f.x = plot::make_axis("t", "s");
  f.y = plot::make_axis("M", "N·m");
  f.series.push_back(plot::make_series("a</script>", {0, 1, 2}, {1, NAN, 3}));
  f.series.push_back(plot::make_series("b", {0, 1, 2}, {4, 5, 6}));
  f.ref_lines.push_back(plot::make_ref_line(2.5, "a*", 0));
  auto j = nlohmann::json::parse(report::figure_json(f));
  EXPECT_EQ(j["data"].dump(), "[[0,1,2],[1,null,3],[4,5,6]]");
  EXPECT_FALSE(j["union"].get<bool>());
  EXPECT_EQ(j["refs"][0]["value"].get<double>(), 2.5);
  EXPECT_EQ(j["series"][0]["color"], plot::series_color(0));
  f.series[1] = plot::make_series("b", {0.5, 2}, {7, 8});
  j = nlohmann::json::parse(report::figure_json(f));
  EXPECT_EQ(j["data"].dump(), "[[0,0.5,1,2],[1,null,null,3],[null,7,null,8]]");
  EXPECT_TRUE(j["union"].get<bool>());
  f.series[1] = plot::make_series("b", {2, 1}, {7, 8});
  EXPECT_THROW(report::figure_json(f), std::invalid_argument);
}

/// Motor, gearbox and drum; an ideal gear slaves the gearbox to the motor (ρ = 1/4), so compile moves
/// the shaft's first end and the load M onto the motor (shaft ratio 2/ρ = 8, M reduced to ρ·40 = 10).
const char* kSlavedGearbox = R"(bodies:
  motor: {inertia: 2 kg*m^2}
  gearbox: {inertia: 1 kg*m^2}
  drum: {inertia: 5 kg*m^2}
links:
  g: {type: ideal-gear, between: [motor, gearbox], ratio: 4}
  shaft: {type: spring, between: [gearbox, drum], ratio: 2, stiffness: 1e4 N*m/rad}
loads:
  M: {type: constant, body: gearbox, value: 40 N*m}
simulation: {t_end: 0.01 s}
)";

/// The row of table `caption` whose first cell is `name` (empty if none).
std::vector<std::string> row_of(const Model& m, const std::string& caption, const std::string& name) {
  for (const report::Table& t : report::model_tables(m))
    if (t.caption == caption)
      for (const auto& r : t.rows)
        if (!r.empty() && r[0] == name) return r;
  return {};
}

// Claim: the model tables show a link and a load that compile moved onto the ideal-gear group's
// master on the body the file names, with the file's ratio and value (not "motor – drum", ratio 8,
// M = 10), while the compiled model holds the moved ones.
TEST(Report, MovedElementsShowTheUsersBodies) {
  const Model m = test::model_text(kSlavedGearbox);
  ASSERT_EQ(m.dof(), 2);
  ASSERT_EQ(m.links[0].a, m.body_index("motor"));
  ASSERT_DOUBLE_EQ(m.links[0].ratio, 8.0);
  ASSERT_DOUBLE_EQ(m.loads[0].value, 10.0);
  const auto link = row_of(m, "Links", "shaft"), load = row_of(m, "Loads", "M");
  ASSERT_GE(link.size(), 4u);
  EXPECT_EQ(link[2], "gearbox – drum");
  EXPECT_EQ(link[3], "2");
  ASSERT_GE(load.size(), 4u);
  EXPECT_EQ(load[2], "gearbox");
  EXPECT_EQ(load[3], "M = 40 N·m");
}

// Claim: `machdyn report` writes those rows into its page (exit 0).
TEST(Report, CliShowsTheUsersBodies) {
  if (!report::assets_available()) GTEST_SKIP() << "built with MACHDYN_REPORT=OFF: no report";
  const auto model = test::write_temp("slaved-gearbox.yaml", kSlavedGearbox);
  const auto out = test::temp_dir() / "slaved-gearbox.html";
  const auto r = test::run_cli("report '" + model + "' --quiet -o '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string html = test::slurp(out);
  EXPECT_NE(html.find(">gearbox – drum</td>"), std::string::npos);
  EXPECT_NE(html.find(">M = 40 N·m</td>"), std::string::npos);
  EXPECT_EQ(html.find(">motor – drum</td>"), std::string::npos);
}

}  // namespace
}  // namespace machdyn
