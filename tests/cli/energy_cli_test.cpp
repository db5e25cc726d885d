// The `energy` command and the new elements as a user meets them: JSON keys, --set on the machine,
// tables, and bad input with its place (exit 2).
#include <filesystem>
#include <fstream>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

namespace fs = std::filesystem;

// Claim: `energy --json` prints turning_points, omega_max, q_at_omega_max, omega_limit and, for the
// rolling wheel, beta_* and x_* values; `--set wheel.rho=...` changes the run (a larger radius of
// gyration lowers the speed maximum but not where it occurs).
TEST(EnergyCli, JsonKeysAndSetOnTheWheel) {
  const auto r = test::run_cli("energy '" + test::example("rolling-wheel-2.yaml") + "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  for (const char* k : {"turning_points", "omega_max", "q_at_omega_max", "omega_limit", "beta_turning_points",
                        "beta_at_omega_max", "x_turning_points", "x_at_omega_max", "table"})
    EXPECT_TRUE(j.contains(k)) << k;
  EXPECT_NEAR(j["x_turning_points"][1].get<double>(), 3.0792, 1e-4);
  EXPECT_NEAR(j["beta_turning_points"][1].get<double>(), 2.7613, 1e-4);
  EXPECT_TRUE(j["omega_limit"].is_null());
  const auto r2 = test::run_cli("energy '" + test::example("rolling-wheel-2.yaml") + "' --json --set wheel.rho=0.45");
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  const auto j2 = nlohmann::json::parse(r2.out);
  EXPECT_LT(j2["omega_max"].get<double>(), j["omega_max"].get<double>());
  EXPECT_NEAR(j2["x_at_omega_max"].get<double>(), j["x_at_omega_max"].get<double>(), 1e-7);
  const auto r1 = test::run_cli("energy '" + test::example("rolling-wheel-1.yaml") + "' --json");
  EXPECT_NEAR(nlohmann::json::parse(r1.out)["omega_limit"].get<double>(), 8.92, 0.005);
}

// Claim: the text output names the limit speed; -o DIR (the output folder, as for every command)
// gets the ω(q) table as energy.csv and the JSON as energy.json; --delta adds the steady-running
// block with the flywheel inertia; the old `-o table.csv` is an input error that says what -o is.
TEST(EnergyCli, TextTableAndFlywheel) {
  const auto r = test::run_cli("energy '" + test::example("crank-slider.yaml") + "' --delta 0.02 -o om --points 50");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find("flywheel for delta = 0.02"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("wrote om/energy.csv and om/energy.json"), std::string::npos) << r.out;
  EXPECT_NEAR(nlohmann::json::parse(test::slurp(test::temp_dir() / "om/energy.json"))["steady"]["delta_with_flywheel"]
                  .get<double>(),
              0.02, 1e-9);
  const auto old = test::run_cli("energy '" + test::example("crank-slider.yaml") + "' -o om.csv");
  EXPECT_EQ(old.exit_code, 2);
  EXPECT_NE(old.err.find("-o: error: -o names the output folder"), std::string::npos) << old.err;
  std::ifstream csv(test::temp_dir() / "om/energy.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_NE(header.find("omega"), std::string::npos);
  int rows = 0;
  for (std::string line; std::getline(csv, line);) ++rows;
  EXPECT_EQ(rows, 50);
  const auto j = nlohmann::json::parse(
      test::run_cli("energy '" + test::example("crank-slider.yaml") + "' --json --delta 0.02").out);
  EXPECT_GT(j["steady"]["flywheel_inertia"].get<double>(), 0.0);
  EXPECT_NEAR(j["steady"]["delta_with_flywheel"].get<double>(), 0.02, 1e-9);
}

// Claim: on the scheme-3 wheel (speed without bound) the printout and the JSON carry the limiting
// angular acceleration of paper 000 eq. 30, ε = F (R1 − r1)/[m1 (ρ² + r1²) + (m2/2)(R1 − r1)²],
// beside `limit: unbounded`; a bounded scheme has null there.
TEST(EnergyCli, SchemeThreeReportsLimitingAcceleration) {
  const double eq30 = 200 * (0.6 - 0.3) / (50 * (0.42 * 0.42 + 0.3 * 0.3) + 5 * 0.3 * 0.3);
  const auto r = test::run_cli("energy '" + test::example("rolling-wheel-3.yaml") + "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["limit"], "unbounded");
  EXPECT_NEAR(j["epsilon_limit"].get<double>(), eq30, 1e-12 * eq30);
  EXPECT_EQ(j["units"]["epsilon_limit"], "rad/s^2");
  const auto t = test::run_cli("energy '" + test::example("rolling-wheel-3.yaml") + "'");
  EXPECT_NE(t.out.find(fmt::format("epsilon_limit = {:.9g} rad/s^2", eq30)), std::string::npos) << t.out;
  const auto one = nlohmann::json::parse(test::run_cli("energy '" + test::example("rolling-wheel-1.yaml") + "' --json").out);
  EXPECT_TRUE(one["epsilon_limit"].is_null());
}

// Claim: simulate works on the new examples and writes the inertia-moment and geometry columns.
TEST(EnergyCli, SimulateWritesMachineColumns) {
  const auto dir = test::temp_dir() / "wheel-out";
  const auto r = test::run_cli("simulate '" + test::example("rolling-wheel-2.yaml") + "' -o '" + dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::ifstream csv(dir / "timeseries.csv");
  std::string header;
  std::getline(csv, header);
  EXPECT_EQ(header,
            "t_s,wheel.position_rad,wheel.velocity_rad_s,wheel.inertia_kg_m2,wheel.acceleration_rad_s2,"
            "wheel.M_wheel_N_m,wheel.M_block_N_m,wheel.x_m,wheel.beta_rad");
  const auto e = test::run_cli("examples");
  for (const char* f : {"rolling-wheel-1.yaml", "rolling-wheel-2.yaml", "rolling-wheel-3.yaml", "crank-slider.yaml"})
    EXPECT_NE(e.out.find(f), std::string::npos) << f;
}

// Claim: bad machine input is reported with file:line:col for every problem at once, exit 2,
// and nothing is written.
TEST(EnergyCli, BadMachineInputNamesEveryPlace) {
  const auto bad = test::write_temp("bad-machines.yaml", R"Y(bodies:
  crank: {type: crank-slider, crank_radius: 50 mm, rod_length: 40 mm, crank_inertia: 0.1, inertia_model: exactly}
  wheel: {type: rolling-wheel, scheme: 2, R1: 0.6, r1: 0.7, r2: 0.3, H: 0.2, m1: 50, F: 200, beta0: 200 deg}
  cam: {type: inertia-table, points: [[0, 1], [0, 2]]}
  rot: {type: inertia-expression, inertia: "2 + sin(q"}
  load: {type: translational, mass: 1}
links:
  k: {type: spring, between: [crank.pistn, load], stiffness: 1}
)Y");
  const auto dir = test::temp_dir() / "never-machines";
  const auto r = test::run_cli("simulate '" + bad + "' -o '" + dir.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  for (const char* expect :
       {":2:64: error: body 'crank': field 'rod_length' (0.04 m) must exceed 'crank_radius' (0.05 m)",
        ":2:106: error: body 'crank': field 'inertia_model' is 'exactly'; expected one of: exact, approximate",
        ":3:56: error: body 'wheel': field 'r1' (the small cylinder, 0.7 m) must be smaller than 'R1' (0.6 m)",
        ":3:101: error: body 'wheel': field 'beta0' must lie strictly between 0 and pi rad",
        ":3:73: error: body 'wheel': field 'H' (0.2 m) must exceed |Rt − r2|",
        ":4:48: error: body 'cam': the first values in 'points' must increase",
        ":5:44: error: body 'rot': field 'inertia': expression '2 + sin(q': at character 10: expected ')'",
        ":8:31: error: link 'k': body 'crank' has no point 'pistn'; its point is 'piston'"})
    EXPECT_NE(r.err.find(bad + expect), std::string::npos) << expect << "\n" << r.err;
  EXPECT_FALSE(fs::exists(dir));
}

// Claim: `energy` refuses models without an energy integral (links, speed-dependent loads), exit 2.
TEST(EnergyCli, RefusesModelsWithoutEnergyIntegral) {
  const auto r = test::run_cli("energy '" + test::example("hoist-3mass.yaml") + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("needs a model with one body and no links"), std::string::npos) << r.err;
  // Located at the element that is too many: the second body of hoist-3mass.yaml, I2 (line 16).
  EXPECT_NE(r.err.find(test::example("hoist-3mass.yaml") + ":"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find(test::example("hoist-3mass.yaml") + ": error"), std::string::npos) << r.err;
  const auto motor = test::write_temp("motor-crank.yaml", R"Y(bodies:
  crank: {type: crank-slider, crank_radius: 0.05, rod_length: 0.2, piston_mass: 1, crank_inertia: 0.1}
loads:
  M: {type: motor-linear, body: crank, stall_torque: 10, no_load_speed: 100}
)Y");
  const auto m = test::run_cli("energy '" + motor + "'");
  EXPECT_EQ(m.exit_code, 2);
  EXPECT_NE(m.err.find(motor + ":4:3: error: load 'M' depends on time or speed"), std::string::npos) << m.err;
  EXPECT_EQ(test::run_cli("energy '" + test::example("hoist-3mass.yaml") + "' --points 1").exit_code, 2);
  EXPECT_EQ(test::run_cli("energy '" + test::example("crank-slider.yaml") + "' --to '-1 rad'").exit_code, 2);
}

}  // namespace
}  // namespace machdyn
