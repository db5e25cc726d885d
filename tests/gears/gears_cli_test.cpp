// `machdyn gears` end to end: outputs for the paper's example and the bad-input catalogue
// (every input error exits with 2 and names file:line:col).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <sys/wait.h>
#include <unistd.h>

namespace MACHDYN_UNITY_ID {

namespace fs = std::filesystem;

struct CliRun {
  int code = -1;
  std::string out;  ///< stdout and stderr
};

CliRun run(const std::string& args) {
  CliRun r;
  const std::string cmd = std::string(MACHDYN_CLI) + " gears " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf{};
  std::size_t n = 0;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  const int st = pclose(p);
  r.code = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

const std::string kExample = std::string(MACHDYN_SOURCE_DIR) + "/examples/walking-drive-gears.yaml";

fs::path temp_dir() {
  fs::path d = fs::temp_directory_path() / ("machdyn_gears_cli_" + std::to_string(::getpid()));
  fs::create_directories(d);
  return d;
}

std::string write_spec(const std::string& name, const std::string& text) {
  const fs::path p = temp_dir() / name;
  std::ofstream(p) << text;
  return p.string();
}

const std::string kGood =
    "law: walking\n"     // 1
    "a: 60 mm\n"         // 2
    "b: 100 mm\n"        // 3
    "c: 360 mm\n"        // 4
    "L: 143.5 mm\n"      // 5
    "L_installed: 144 mm\n"  // 6
    "z: 48\n"            // 7
    "zH: 96\n";          // 8

TEST(GearsCli, JsonHasUAndTheSectorTable) {
  const CliRun r = run(kExample + " --json");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_NEAR(j["u"].get<double>(), 1.25248, 0.5e-5);
  ASSERT_EQ(j["sectors"].size(), 24u);
  const auto& row1 = j["sectors"][0];
  EXPECT_EQ(row1["i"].get<int>(), 1);
  EXPECT_NEAR(row1["phi"].get<double>(), 0.7854, 0.5e-4);
  EXPECT_NEAR(row1["dphi"].get<double>(), 0.0756, 0.5e-4);
  EXPECT_NEAR(row1["rH"].get<double>(), 82.20, 0.005);  // mm
  EXPECT_NEAR(row1["theta"].get<double>(), 1.5708, 0.5e-4);
  EXPECT_NEAR(row1["dtheta"].get<double>(), 0.1013, 0.5e-4);
  EXPECT_NEAR(row1["r"].get<double>(), 61.30, 0.005);
}

TEST(GearsCli, OutputFolderHasTableDrawingsAndDxf) {
  const fs::path d = temp_dir() / "out";
  fs::remove_all(d);
  const CliRun r = run(kExample + " -o " + d.string());
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_NE(r.out.find("0.7854"), std::string::npos);
  for (const char* f : {"sectors.csv", "gears.json", "pitch_curves.svg", "ratio.svg", "teeth.svg", "gears.dxf"})
    EXPECT_TRUE(fs::exists(d / f)) << f;
  std::ifstream csv(d / "sectors.csv");
  int lines = 0;
  for (std::string l; std::getline(csv, l);) ++lines;
  EXPECT_EQ(lines, 25);
  std::stringstream dxf;
  dxf << std::ifstream(d / "gears.dxf").rdbuf();
  EXPECT_NE(dxf.str().find("TEETH_PINION"), std::string::npos);
  EXPECT_EQ(dxf.str().substr(dxf.str().size() - 4), "EOF\n");
}

// The example gives the installation as a clearance over L, so --set L alone moves both, as the
// issue's `--set L="150 mm"` expects; L_installed can still be set absolutely.
TEST(GearsCli, SetOverridesATopLevelField) {
  const CliRun r = run(kExample + " --json --set L=\"150 mm\"");
  ASSERT_EQ(r.code, 0) << r.out;
  const auto j = nlohmann::json::parse(r.out);
  // the sector angles do not depend on L, the radii scale with it
  EXPECT_NEAR(j["sectors"][0]["rH"].get<double>(), 82.19826833599573 * 150.0 / 143.5, 1e-6);
  // both forms of the installation distance at once are refused at the clearance
  const CliRun both = run(kExample + " --set L_installed=\"150.5 mm\"");
  EXPECT_EQ(both.code, 2);
  EXPECT_NE(both.out.find("give either 'L_installed' or 'clearance'"), std::string::npos) << both.out;
}

// The bad-input catalogue: each case names the exact place.
struct BadCase {
  const char* name;
  std::string spec;
  std::string extra;
  std::string expect;  ///< substring of the message, after the file name
};

TEST(GearsCli, BadInputsExitWith2AndTheirPlace) {
  const std::vector<BadCase> cases = {
      {"missing_field", "law: walking\na: 60 mm\nb: 100 mm\nc: 360 mm\nL: 143.5 mm\nz: 48\n", "",
       ":1:1: error: gears: missing field 'zH'"},
      {"wrong_unit", "law: walking\na: 60 mm\nb: 100 mm\nc: 360 mm\nL: 143.5 kg\nz: 48\nzH: 96\n", "",
       ":5:4: error: gears: field 'L': expected a length"},
      {"unknown_field", kGood + "teeth: 12\n", "", ":9:1: error: gears: unknown field 'teeth'"},
      {"installed_below_L", kGood, "--set L_installed=\"143 mm\"",
       "--set L_installed: error: gears: installation distance 143 mm is below"},
      {"installed_too_far", "law: walking\na: 60 mm\nb: 100 mm\nc: 360 mm\nL: 143.5 mm\nL_installed: 146 mm\n"
                            "z: 48\nzH: 96\n", "", ":6:14: error: gears: the installation distance exceeds"},
      {"not_closing", "law: expression\nratio: \"2.1\"\nL: 90 mm\nz: 20\nzH: 40\n", "",
       ":2:8: error: gears: the ratio law does not close"},
      {"not_positive", "law: expression\nnormalize: true\nratio: \"1 + 2*cos(4*phi)\"\nL: 90 mm\nz: 20\nzH: 40\n",
       "", ":3:8: error: gears: the ratio i(φ) must be finite and positive"},
      {"bad_expression", "law: expression\nratio: \"2 + foo(phi)\"\nL: 90 mm\nz: 20\nzH: 40\n", "",
       ":2:8: error: gears: field 'ratio': at character 5: unknown name 'foo'"},
      {"teeth_not_divisible", "law: expression\nratio: \"2\"\nL: 90 mm\nz: 21\nzH: 42\n", "",
       ":5:5: error: gears: zH = 42 must be a multiple"},
      // a 2-tooth circular pinion: r = L/3, module = r, dedendum 1.25 m > r
      {"pinion_too_small", "law: expression\nratio: \"2\"\nL: 90 mm\nz: 2\nzH: 4\n", "",
       ":4:4: error: gears: the pinion is too small"},
      {"corner_continuous", kGood + "profile:\n  basis: continuous\n", "",
       ":10:10: error: gears.profile: basis 'continuous' needs pitch curves without corners"},
      // an empty spec is located at its start (it used to have no line and column)
      {"empty", "", "", "empty.yaml:1:1: error: gears: expected a map of fields"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string path = write_spec(std::string(c.name) + ".yaml", c.spec);
    const CliRun r = run(path + " " + c.extra);
    EXPECT_EQ(r.code, 2) << r.out;
    EXPECT_NE(r.out.find(c.expect), std::string::npos) << r.out;
  }
}

}  // namespace
