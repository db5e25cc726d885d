// The report as a reader meets it: opened from disk in headless Chromium with no network, with
// 10^5 points per series. Skipped, with a message, when Chromium is not installed.
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <sstream>
#include <unistd.h>

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

}  // namespace
}  // namespace machdyn
