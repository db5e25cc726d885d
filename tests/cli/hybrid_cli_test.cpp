// The hybrid elements and load cases at the command line: summary events, --case, --all-cases and
// bad input for the new elements (file:line:col, exit 2, nothing written).
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

namespace fs = std::filesystem;

// Claim: summary.json of a hybrid run lists events {t, kind, element, from, to}, slip phases with
// link peaks, per-contact slips/period/F_max over the static limit, and the energy balance; the CSV
// has the contact forces and modes (the load cyclogram is c.load_N against t_s).
TEST(HybridCli, TravelStartSummaryHasEventsAndCyclogram) {
  const auto dir = test::temp_dir() / "travel";
  const auto r = test::run_cli("simulate '" + test::example("travel-start.yaml") + "' -o '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("mode events"), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(std::ifstream(dir / "summary.json"));
  ASSERT_TRUE(j.contains("events"));
  bool kinds[4] = {false, false, false, false};
  for (const auto& e : j["events"]) {
    for (const char* k : {"t", "kind", "element", "from", "to"}) EXPECT_TRUE(e.contains(k)) << k;
    const std::string kind = e["kind"];
    kinds[0] |= kind == "gap_closed", kinds[1] |= kind == "slip", kinds[2] |= kind == "stick";
    kinds[3] |= kind == "initial";
  }
  for (bool k : kinds) EXPECT_TRUE(k);
  EXPECT_GT(j["contacts"]["adhesion"]["slips"].get<int>(), 10);
  EXPECT_TRUE(j["contacts"]["adhesion"]["period_s"].is_number());
  EXPECT_FALSE(j["links"]["c"]["slip_phase_peaks"].empty());
  EXPECT_LT(std::abs(j["energy"]["residual_J"].get<double>()), 1e-8 * j["energy"]["source_work_J"].get<double>());
  std::ifstream csv(dir / "timeseries.csv");
  std::string header;
  std::getline(csv, header);
  for (const char* c : {"c.load_N", "adhesion.force_N", "adhesion.mode", "adhesion.sliding_velocity_m_s", "c.gap_mode"})
    EXPECT_NE(header.find(c), std::string::npos) << c;
}

// Claim: --case applies one operating mode (the brake sits on the named body; the motor is gone)
// and --all-cases prints one table over the eleven modes of paper 002 with outputs per case.
TEST(HybridCli, HoistCasesOneAndAll) {
  const auto dir = test::temp_dir() / "hoist-case";
  const auto r = test::run_cli("simulate '" + test::example("hoist-modes.yaml") + "' --case brake_I2_lifting --json -o '" +
                               dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["case"], "brake_I2_lifting");
  EXPECT_EQ(j["contacts"]["T"]["kind"], "brake");
  bool stick = false;
  for (const auto& e : j["events"]) stick |= e["element"] == "T" && e["kind"] == "stick";
  EXPECT_TRUE(stick);

  const auto all_dir = test::temp_dir() / "hoist-all";
  const auto a = test::run_cli("simulate '" + test::example("hoist-modes.yaml") + "' --all-cases -o '" + all_dir.string() + "'");
  ASSERT_EQ(a.exit_code, 0) << a.err;
  for (const char* c : {"accel_up", "brake_I1_lifting", "brake_I2_lifting", "brake_I3_lifting", "coast_up", "accel_down",
                        "brake_I1_lowering", "brake_I2_lowering", "brake_I3_lowering", "coast_down", "braked_lowering"}) {
    EXPECT_NE(a.out.find(c), std::string::npos) << c;
    EXPECT_TRUE(fs::exists(all_dir / c / "summary.json")) << c;
  }
  EXPECT_NE(a.out.find("dyn.factor"), std::string::npos);
  const auto cases = nlohmann::json::parse(std::ifstream(all_dir / "cases.json"));
  EXPECT_EQ(cases.size(), 11u);
  // One dynamic factor (LinkSummary): c2 in brake_I2_lifting is loaded mostly negatively (max 75.9,
  // min −204.1 N·m); its factor is min / quasi-static load at t_min, the same number in the single
  // case's JSON, the --all-cases JSON and both printouts — not max / static at t_max (once 85.53).
  const auto& c2 = j["links"]["c2"];
  EXPECT_EQ(c2["peak"].get<double>(), c2["min"].get<double>());
  EXPECT_EQ(c2["t_peak"].get<double>(), c2["t_min"].get<double>());
  EXPECT_EQ(c2["static"].get<double>(), c2["static_at_min"].get<double>());
  EXPECT_NEAR(c2["dynamic_factor"].get<double>(), c2["min"].get<double>() / c2["static_at_min"].get<double>(), 1e-12);
  EXPECT_NEAR(c2["dynamic_factor"].get<double>(), 1.701, 5e-4);
  for (const auto& cj : cases)
    if (cj["case"] == "brake_I2_lifting") {
      EXPECT_EQ(cj["links"]["c2"]["dynamic_factor"], c2["dynamic_factor"]);
    }
  const auto printed = test::run_cli("simulate '" + test::example("hoist-modes.yaml") + "' --case brake_I2_lifting -o '" +
                                     (test::temp_dir() / "hoist-case-print").string() + "'");
  EXPECT_NE(printed.out.find("1.701"), std::string::npos) << printed.out;
  EXPECT_EQ(printed.out.find("85.53"), std::string::npos) << printed.out;
  const auto bad = test::run_cli("simulate '" + test::example("hoist-modes.yaml") + "' --case nosuch");
  EXPECT_EQ(bad.exit_code, 2);
  EXPECT_NE(bad.err.find("no case named 'nosuch'"), std::string::npos) << bad.err;
}

// Claim: bad gaps, contacts, brakes and cases are reported all at once with file:line:col, exit 2,
// and nothing is written.
TEST(HybridCli, BadHybridInputExitsTwoWithPlaces) {
  const auto bad = test::write_temp("bad-hybrid.yaml", R"(bodies:
  A: {type: translational, mass: 1}
  B: {type: translational, mass: 1}
links:
  c: {type: spring, between: [A, B], stiffness: 1e5, gap: 2 mm, gap_start: 3 mm}
  d: {type: damper, between: [A, B], damping: 10, gap: 1 mm}
contacts:
  f1: {between: [A, Q], static: 10 N, kinetic: 5 N}
  f2: {between: [A, ground], static: 10 N, kinetic: 12 N}
  f3: {between: [ground, A], static: 10 N, kinetic: 5 N}
  f4: {between: [B, ground], mu_s: 0.2, static: 3 N, kinetic: 1 N}
  f5: {between: [B, ground], static: 10 N, kinetic: [[0.5, 4], [0.1, 3]]}
brakes:
  T: {body: A, holding: 100 N, braking: 150 N, ramp: -1 s}
cases:
  x: {remove: [nothing]}
)");
  const auto dir = test::temp_dir() / "never-hybrid";
  const auto r = test::run_cli("simulate '" + bad + "' -o '" + dir.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  for (const char* msg :
       {":5:76: error: link 'c': field 'gap_start' must lie in [0, gap]", ":6:56: error: link 'd': a damper cannot have a gap",
        ":8:21: error: contact 'f1': unknown body 'Q'",
        ":9:53: error: contact 'f2': the kinetic level at zero sliding speed (12) exceeds the static limit (10)",
        ":10:18: error: contact 'f3': write the body first", ":11:36: error: contact 'f4': field 'mu_s' needs 'normal_force'",
        ":12:65: error: contact 'f5': 'kinetic': the first entries must increase",
        ":14:41: error: brake 'T': the braking level (150) exceeds the holding level (100)",
        ":14:54: error: brake 'T': field 'ramp' must be zero or positive"})
    EXPECT_NE(r.err.find(bad + msg), std::string::npos) << msg << "\n" << r.err;
  EXPECT_FALSE(fs::exists(dir));
  const auto c = test::run_cli("simulate '" + bad + "' --all-cases -o '" + dir.string() + "'");
  EXPECT_EQ(c.exit_code, 2);
  EXPECT_NE(c.err.find(bad + ":16:16: error: case 'x': cannot remove 'nothing'"), std::string::npos) << c.err;
  EXPECT_FALSE(fs::exists(dir));
}

}  // namespace
}  // namespace machdyn
