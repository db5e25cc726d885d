// The report as a reader meets it: opened from disk in headless Chromium with no network, with
// 10^5 points per series. Skipped, with a message, when Chromium is not installed.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>
#include <vector>

#include "machdyn/io/report.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

namespace fs = std::filesystem;

std::string find_chromium() {
  if (const char* env = std::getenv("MACHDYN_CHROMIUM"); env && *env) return env;
  for (const char* p : {"/usr/bin/chromium", "/usr/bin/chromium-browser"})
    if (::access(p, X_OK) == 0) return p;
  return "";
}

/// Runs headless Chromium on `url` with a fresh profile, no network and `extra` flags; returns stdout.
std::string chromium(const std::string& exe, const std::string& url, const std::string& extra, const std::string& tag) {
  const fs::path profile = test::temp_dir() / ("chromium-profile-" + tag), out = test::temp_dir() / (tag + ".out");
  const std::string cmd = "'" + exe + "' --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
                          "--disable-background-networking --disable-component-update --disable-sync "
                          "--disable-extensions --user-data-dir='" + profile.string() + "' --virtual-time-budget=20000 " +
                          extra + " '" + url + "' >'" + out.string() + "' 2>/dev/null </dev/null";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::ifstream in(out);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Claim: the report of the hoist with 10^5 points per series opens offline without script errors,
// every plot drew every series (pixels of each series' colour on its canvas), each time plot holds
// all 100001 points (the Bode plots their 400 frequencies), and drawing takes less than 5 s. A screenshot is saved for people to look at.
TEST(ReportBrowser, OpensOfflineAndDrawsEverySeries) {
  if (!report::assets_available()) GTEST_SKIP() << "built with MACHDYN_REPORT=OFF: no report";
  const std::string exe = find_chromium();
  if (exe.empty())
    GTEST_SKIP() << "chromium is not installed: the HTML report was NOT checked in a browser "
                    "(install it with `apt-get install chromium` or `make deps-browser`)";
  const fs::path html = test::temp_dir() / "browser" / "report.html";
  const auto r = test::run_cli("report '" + test::example("hoist-3mass.yaml") + "' --quiet -o '" + html.string() +
                               "' --set simulation.dt_out=5e-6");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string dom = chromium(exe, "file://" + html.string(), "--dump-dom", "dom");
  const auto a = dom.find("<pre id=\"machdyn-status\"");
  ASSERT_NE(a, std::string::npos) << dom.substr(0, 2000);
  const auto b = dom.find('>', a) + 1, e = dom.find("</pre>", b);
  const auto status = nlohmann::json::parse(dom.substr(b, e - b));
  EXPECT_TRUE(status["done"].get<bool>()) << status.dump();
  EXPECT_TRUE(status["errors"].empty()) << status["errors"].dump();
  // link loads, body speeds, mode shapes and the Bode plot (magnitude, phase; 400 frequencies).
  ASSERT_EQ(status["plots"].size(), 5u) << status.dump();
  for (const auto& p : status["plots"]) {
    const std::string id = p["id"];
    ASSERT_EQ(p["drawn"].size(), p["series"].get<size_t>()) << id;
    for (size_t k = 0; k < p["drawn"].size(); ++k) EXPECT_GT(p["drawn"][k].get<int>(), 50) << id << " series " << k;
    if (id.rfind("bode", 0) == 0) {
      for (const auto& n : p["points"]) EXPECT_EQ(n.get<int>(), 400) << id;
    } else if (id.rfind("mode_shapes", 0) != 0) {
      for (const auto& n : p["points"]) EXPECT_EQ(n.get<int>(), 100001) << id;
    }
    EXPECT_LT(p["ms"].get<int>(), 5000) << id;
  }
  const fs::path shot = fs::path(MACHDYN_TEST_OUTPUT) / "report-screenshot.png";
  fs::remove(shot);
  chromium(exe, "file://" + html.string(), "--window-size=1280,3000 --hide-scrollbars --screenshot='" + shot.string() + "'",
           "shot");
  EXPECT_TRUE(fs::exists(shot) && fs::file_size(shot) > 10000) << shot;
  std::cout << "[ screenshot ] " << shot.string() << "\n";
}

// Claim (issue 32): the crane hoist's report — links in panels by unit, a brake, an end stop, the
// mode shapes of a rad/m model weighted by √I, the Bode plot on log axes from the motor, the crane
// factors — opens offline without script errors and every plot draws every series; the Bode plot's
// frequencies end at twice its highest resonance, not at hundreds of Hz of noise. A screenshot is
// saved for people to look at.
TEST(ReportBrowser, CraneHoistReportDrawsEveryPanel) {
  if (!report::assets_available()) GTEST_SKIP() << "built with MACHDYN_REPORT=OFF: no report";
  const std::string exe = find_chromium();
  if (exe.empty()) GTEST_SKIP() << "chromium is not installed: the HTML report was NOT checked in a browser";
  const fs::path html = test::temp_dir() / "browser-crane" / "report.html";
  const auto r = test::run_cli("report '" + test::example("crane/main-hoist.yaml") + "' --quiet -o '" + html.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string page = test::slurp(html);
  EXPECT_NE(page.find("data-figure=\"link_loads_2-"), std::string::npos) << "the rope (N) in its own panel";
  EXPECT_NE(page.find("\"log\":true"), std::string::npos) << "the Bode plot's axes are logarithmic";
  const std::string dom = chromium(exe, "file://" + html.string(), "--dump-dom", "dom-crane");
  const auto a = dom.find("<pre id=\"machdyn-status\"");
  ASSERT_NE(a, std::string::npos) << dom.substr(0, 2000);
  const auto b = dom.find('>', a) + 1, e = dom.find("</pre>", b);
  const auto status = nlohmann::json::parse(dom.substr(b, e - b));
  EXPECT_TRUE(status["done"].get<bool>()) << status.dump();
  EXPECT_TRUE(status["errors"].empty()) << status["errors"].dump();
  ASSERT_GE(status["plots"].size(), 10u) << status.dump();
  for (const auto& p : status["plots"]) {
    const std::string id = p["id"];
    ASSERT_EQ(p["drawn"].size(), p["series"].get<size_t>()) << id;
    for (size_t k = 0; k < p["drawn"].size(); ++k) EXPECT_GT(p["drawn"][k].get<int>(), 20) << id << " series " << k;
  }
  const fs::path shot = fs::path(MACHDYN_TEST_OUTPUT) / "report-crane-screenshot.png";
  fs::remove(shot);
  chromium(exe, "file://" + html.string(), "--window-size=1280,6000 --hide-scrollbars --screenshot='" + shot.string() + "'",
           "shot-crane");
  EXPECT_TRUE(fs::exists(shot) && fs::file_size(shot) > 10000) << shot;
  std::cout << "[ screenshot ] " << shot.string() << "\n";
}

/// The status the report's script writes (plots drawn, their words laid out) of `html` in Chromium.
nlohmann::json page_status(const std::string& exe, const fs::path& html, const std::string& tag) {
  const std::string dom = chromium(exe, "file://" + html.string(), "--dump-dom", tag);
  const auto a = dom.find("<pre id=\"machdyn-status\"");
  if (a == std::string::npos) return {{"done", false}, {"errors", {"no status block: " + dom.substr(0, 500)}}, {"plots", {}}};
  const auto b = dom.find('>', a) + 1, e = dom.find("</pre>", b);
  return nlohmann::json::parse(dom.substr(b, e - b));
}

/// Whether an axis title names its unit ("quantity, unit") or is a quantity without one (a ratio,
/// a count, the bodies of a mode shape).
bool axis_title_ok(const std::string& label) {
  if (label.empty()) return false;
  if (label.find(", ") != std::string::npos) return true;
  for (const char* word : {"/", "ratio", "cycles", "body", "relative", "phi", "φ"})
    if (label.find(word) != std::string::npos) return true;
  return false;
}

/// Every figure of a report opened in the browser: drawn (each series' pixels), its title laid out
/// inside the page's column, each axis titled (with its unit where it has one) and inside its chart,
/// and no two tick labels of an axis alike; no table reaches past the column.
void expect_every_figure_readable(const nlohmann::json& status, size_t at_least, const std::string& what) {
  EXPECT_TRUE(status["done"].get<bool>()) << what << status.dump();
  EXPECT_TRUE(status["errors"].empty()) << what << status["errors"].dump();
  EXPECT_GE(status["plots"].size(), at_least) << what << status.dump();
  // Every table inside the page's column (a wide one scrolls in its own box).
  if (status.contains("tables_outside")) {
    EXPECT_TRUE(status["tables_outside"].empty()) << what << status["tables_outside"].dump();
  }
  for (const auto& p : status["plots"]) {
    const std::string id = p["id"];
    ASSERT_EQ(p["drawn"].size(), p["series"].get<size_t>()) << what << " " << id;
    EXPECT_GT(p["series"].get<size_t>(), 0u) << what << " " << id;
    // Each series shows (its pixels), unless it is one value throughout (on the zero line) or lies
    // under a series drawn after it (two bodies turning together); each figure shows something.
    int most = 0;
    for (size_t k = 0; k < p["drawn"].size(); ++k) {
      most = std::max(most, p["drawn"][k].get<int>());
      if (!p["flat"][k].get<bool>() && !p["covered"][k].get<bool>()) {
        EXPECT_GT(p["drawn"][k].get<int>(), 20) << what << " " << id << " series " << k;
      }
    }
    EXPECT_GT(most, 20) << what << " " << id << ": nothing drawn";
    EXPECT_FALSE(p["title"].get<std::string>().empty()) << what << " " << id;
    EXPECT_TRUE(p["title_fits"].get<bool>()) << what << " " << id << ": title cut: " << p["title"];
    ASSERT_GE(p["axes"].size(), 2u) << what << " " << id;
    for (const auto& ax : p["axes"]) {
      const std::string label = ax["label"];
      EXPECT_TRUE(axis_title_ok(label)) << what << " " << id << ": axis title '" << label << "' without a unit";
      EXPECT_TRUE(ax["fits"].get<bool>()) << what << " " << id << ": axis title cut: " << label;
      // No two ticks of an axis read the same (a log axis's 1e-4, 1e-5 once all read "0").
      if (ax.contains("ticks")) {
        std::vector<std::string> ticks = ax["ticks"].get<std::vector<std::string>>();
        std::sort(ticks.begin(), ticks.end());
        EXPECT_TRUE(std::adjacent_find(ticks.begin(), ticks.end()) == ticks.end())
            << what << " " << id << ": axis '" << label << "' ticks " << ax["ticks"].dump();
      }
    }
  }
}

/// Screenshot of `html` for people to look at (MACHDYN_TEST_OUTPUT/NAME.png).
void screenshot(const std::string& exe, const fs::path& html, const std::string& name, int height) {
  const fs::path shot = fs::path(MACHDYN_TEST_OUTPUT) / (name + ".png");
  fs::remove(shot);
  chromium(exe, "file://" + html.string(),
           fmt::format("--window-size=1280,{} --hide-scrollbars --screenshot='{}'", height, shot.string()), "shot-" + name);
  EXPECT_TRUE(fs::exists(shot) && fs::file_size(shot) > 10000) << shot;
  std::cout << "[ screenshot ] " << shot.string() << "\n";
}

// Claim (issue 32 item 6): the worked crane example's report with all its cases (the hoist's start,
// creep start and emergency stop, the trolley into its buffer: link panels, brake, crane factors with
// their histories, modes and frequency responses per case) opens offline without script errors, and
// every figure is drawn, titled inside the page and has axis titles with units inside its chart.
TEST(ReportBrowser, CraneExampleAllCasesEveryFigureReadable) {
  if (!report::assets_available()) GTEST_SKIP() << "built with MACHDYN_REPORT=OFF: no report";
  const std::string exe = find_chromium();
  if (exe.empty()) GTEST_SKIP() << "chromium is not installed: the HTML report was NOT checked in a browser";
  const fs::path html = test::temp_dir() / "browser-crane32" / "report.html";
  const auto r = test::run_cli("report '" + test::example("crane/overhead-crane-32t.yaml") + "' --all-cases --quiet -o '" +
                               html.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string page = test::slurp(html);
  for (const char* c : {"start", "creep", "estop", "trolley"}) EXPECT_NE(page.find(c), std::string::npos) << c;
  EXPECT_NE(page.find("data-figure=\"crane_"), std::string::npos) << "the crane factors' histories";
  expect_every_figure_readable(page_status(exe, html, "dom-crane32"), 16, "crane example");
  screenshot(exe, html, "report-crane32-screenshot", 12000);
}

// Claim (issue 31): the swinging load's report (the trolley move with and without shaping) has a
// sway section per case — the summary table and the figure of the sway angles and the horizontal
// force — and every figure is drawn, titled inside the page and has axis titles with units; a model
// without a spatial rope (the hoist) has no sway section.
TEST(ReportBrowser, SwaySectionEveryFigureReadable) {
  if (!report::assets_available()) GTEST_SKIP() << "built with MACHDYN_REPORT=OFF: no report";
  const fs::path hoist = test::temp_dir() / "browser-no-sway" / "report.html";
  const auto h = test::run_cli("report '" + test::example("hoist-3mass.yaml") + "' --quiet -o '" + hoist.string() + "'");
  ASSERT_EQ(h.exit_code, 0) << h.err;
  const std::string hoist_page = test::slurp(hoist);
  EXPECT_EQ(hoist_page.find("data-figure=\"sway-"), std::string::npos);
  EXPECT_EQ(hoist_page.find("<h2>Sway"), std::string::npos);
  const std::string exe = find_chromium();
  if (exe.empty()) GTEST_SKIP() << "chromium is not installed: the HTML report was NOT checked in a browser";
  const fs::path html = test::temp_dir() / "browser-sway" / "report.html";
  const auto r = test::run_cli("report '" + test::example("crane/trolley-sway.yaml") + "' --all-cases --quiet -o '" +
                               html.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string page = test::slurp(html);
  size_t sections = 0, figures = 0;
  for (size_t k = page.find("<h2>Sway — case "); k != std::string::npos; k = page.find("<h2>Sway — case ", k + 1)) ++sections;
  for (size_t k = page.find("data-figure=\"sway-"); k != std::string::npos; k = page.find("data-figure=\"sway-", k + 1)) ++figures;
  EXPECT_GE(sections, 2u) << "a sway section per case";
  EXPECT_EQ(figures, sections) << "a sway figure per case";
  EXPECT_NE(page.find("horizontal dynamic factor"), std::string::npos);
  expect_every_figure_readable(page_status(exe, html, "dom-sway"), 2, "sway");
  screenshot(exe, html, "report-sway-screenshot", 8000);
}

// Claim (issue 32 item 6): the report's duty section (the 32 t hoist's operations: cycles, load
// spectra and exceedance diagrams per link) is drawn with every figure readable as above.
TEST(ReportBrowser, DutySectionEveryFigureReadable) {
  if (!report::assets_available()) GTEST_SKIP() << "built with MACHDYN_REPORT=OFF: no report";
  const std::string exe = find_chromium();
  if (exe.empty()) GTEST_SKIP() << "chromium is not installed: the HTML report was NOT checked in a browser";
  const fs::path html = test::temp_dir() / "browser-duty" / "report.html";
  const auto r = test::run_cli("report '" + test::example("duty/hoist-32t.yaml") + "' --duty '" +
                               test::example("duty/hoist-32t.duty.yaml") + "' --quiet -o '" + html.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string page = test::slurp(html);
  EXPECT_NE(page.find("data-figure=\"duty_"), std::string::npos) << "the duty section's figures";
  expect_every_figure_readable(page_status(exe, html, "dom-duty"), 4, "duty");
  screenshot(exe, html, "report-duty-screenshot", 8000);
}

// Claim (issue 32 item 6): the sweep's and the crane's φ2(vh) figures (gnuplot SVG) as the browser
// draws them: each has its curves (one per case for a sweep over cases), and every word — title, axis
// titles with their units, legend — lies inside the picture (nothing cut at an edge).
TEST(ReportBrowser, SweepFiguresReadable) {
  const std::string exe = find_chromium();
  if (exe.empty()) GTEST_SKIP() << "chromium is not installed: the figures were NOT checked in a browser";
  if (!test::have_gnuplot()) GTEST_SKIP() << "gnuplot not installed: no SVG figures";
  const fs::path dir = test::temp_dir() / "browser-sweep";
  fs::remove_all(dir);
  const auto sw = test::run_cli("sweep '" + test::example("drives.yaml") + "' --set simulation.t_end=0.05 --vary "
                                "c1.stiffness=1e4,2e4,3e4 --case direct --case inverter --plot c1.max_N_m:c1.stiffness -o '" +
                                (dir / "sweep").string() + "'");
  ASSERT_EQ(sw.exit_code, 0) << sw.err;
  const auto cr = test::run_cli("crane '" + test::example("crane/main-hoist-inverter.yaml") + "' --plot --phi2-speeds 0.05:0.5:4 -o '" +
                                (dir / "crane").string() + "'");
  ASSERT_EQ(cr.exit_code, 0) << cr.err;
  std::vector<fs::path> svgs;
  for (const auto& sub : {dir / "sweep", dir / "crane"})
    for (const auto& e : fs::recursive_directory_iterator(sub))
      if (e.path().extension() == ".svg") svgs.push_back(e.path());
  std::sort(svgs.begin(), svgs.end());
  ASSERT_GE(svgs.size(), 2u);
  // One page with every SVG inline; its script measures each <text> against its picture.
  std::string page = "<!DOCTYPE html><html><body>\n";
  for (const auto& p : svgs) {
    std::string svg = test::slurp(p);
    svg = svg.substr(svg.find("<svg"));
    page += "<div class=\"fig\" data-name=\"" + p.filename().string() + "\">" + svg + "</div>\n";
  }
  page += R"js(<pre id="machdyn-status"></pre><script>
var out = [];
document.querySelectorAll("div.fig").forEach(function (d) {
  var svg = d.querySelector("svg"), box = svg.getBoundingClientRect(), texts = [], cut = [];
  svg.querySelectorAll("text").forEach(function (t) {
    var s = t.textContent.trim(); if (!s) return;
    var r = t.getBoundingClientRect();
    texts.push(s);
    if (r.left < box.left - 1 || r.right > box.right + 1 || r.top < box.top - 1 || r.bottom > box.bottom + 1) cut.push(s);
  });
  var longest = 0;
  svg.querySelectorAll("path, polyline").forEach(function (p) {
    var n = (p.getAttribute("d") || p.getAttribute("points") || "").split(/[MLml ]/).length;
    longest = Math.max(longest, n);
  });
  out.push({ name: d.getAttribute("data-name"), texts: texts, cut: cut, longest: longest, width: box.width });
});
document.getElementById("machdyn-status").textContent = JSON.stringify(out);
</script></body></html>
)js";
  const fs::path html = dir / "figures.html";
  std::ofstream(html) << page;
  const std::string dom = chromium(exe, "file://" + html.string(), "--dump-dom", "dom-sweep");
  const auto a = dom.find("<pre id=\"machdyn-status\">");
  ASSERT_NE(a, std::string::npos) << dom.substr(0, 500);
  const auto b = dom.find('>', a) + 1, e = dom.find("</pre>", b);
  const auto figs = nlohmann::json::parse(dom.substr(b, e - b));
  ASSERT_EQ(figs.size(), svgs.size());
  for (const auto& f : figs) {
    const std::string name = f["name"];
    EXPECT_GT(f["width"].get<double>(), 100.0) << name;
    EXPECT_TRUE(f["cut"].empty()) << name << ": words cut at the edge: " << f["cut"].dump();
    EXPECT_GE(f["longest"].get<int>(), 3) << name << ": no curve";
    size_t with_unit = 0;
    for (const auto& t : f["texts"]) with_unit += axis_title_ok(t.get<std::string>()) && t.get<std::string>().find(", ") != std::string::npos;
    EXPECT_GE(with_unit, 1u) << name << ": no axis title with its unit: " << f["texts"].dump();
  }
  // The sweep over two cases: one curve each (its legend names both).
  for (const auto& f : figs)
    if (f["name"].get<std::string>().rfind("plot-", 0) == 0) {
      const std::string texts = f["texts"].dump();
      EXPECT_NE(texts.find("direct"), std::string::npos) << texts;
      EXPECT_NE(texts.find("inverter"), std::string::npos) << texts;
    }
  // A picture of the page for people to look at.
  screenshot(exe, html, "sweep-figures-screenshot", 2400);
}

}  // namespace
}  // namespace machdyn
