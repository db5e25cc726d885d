// `machdyn simulate` on the wheel-walking propulsor drive (examples/walking-drive.yaml): the
// travel-speed report, the stepwise ratio by --set, and bad input with its place (exit 2).
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {
namespace fs = std::filesystem;

// Claim: the summary carries the travel-speed uniformity of the last period for both ratios, the
// stepwise run lists its jumps, and the series include the travel and its speed.
TEST(GearDriveCli, SimulateReportsTravelSpeedUniformity) {
  const auto dir = test::temp_dir() / "walking";
  const auto r = test::run_cli("simulate '" + test::example("walking-drive.yaml") + "' --quiet --json --set drive.ratio=stepwise -o '" +
                               dir.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto& d = j["machines"]["drive"];
  EXPECT_GT(d["jumps"].get<long>(), 100);
  EXPECT_GT(d["jump_loss_J"].get<double>(), 0.0);
  const double delta = d["travel_speed"]["delta"].get<double>();
  EXPECT_GT(delta, 0.01);
  EXPECT_LT(delta, 0.5);
  std::ifstream csv(dir / "timeseries.csv");
  std::string header;
  std::getline(csv, header);
  for (const char* col : {"drive.travel_m", "drive.travel_speed_m_s", "drive.phi_rad", "drive.ratio", "drive.M_wheel_N_m"})
    EXPECT_NE(header.find(col), std::string::npos) << col;
  const auto t = test::run_cli("simulate '" + test::example("walking-drive.yaml") + "' --quiet -o '" + dir.string() + "'");
  ASSERT_EQ(t.exit_code, 0) << t.err;
  EXPECT_NE(t.out.find("drive: travel speed mean"), std::string::npos) << t.out;
}

// Claim: a missing gear file, a wrong unit, an unknown ratio word and an error inside the gear
// spec are all reported at once with file:line:col (the gear spec's own place for the last), exit 2.
TEST(GearDriveCli, BadInputNamesEveryPlace) {
  const auto gear = test::write_temp("bad-gears.yaml", "law: walking\na: 60 mm\nb: 100 mm\nc: 360 mm\nL: 5 kg\nz: 48\nzH: 96\n");
  const auto bad = test::write_temp("bad-drive.yaml", R"Y(bodies:
  a: {type: gear-drive, gears: no-such-gears.yaml, pinion_inertia: 0.5}
  b: {type: gear-drive, gears: bad-gears.yaml, pinion_inertia: 3 N, ratio: smooth}
)Y");
  const auto r = test::run_cli("simulate '" + bad + "' -o '" + (test::temp_dir() / "never").string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  for (const std::string& expect :
       {bad + ":2:32: error: body 'a': field 'gears': cannot open the gear spec 'no-such-gears.yaml'",
        bad + ":3:64: error: body 'b': field 'pinion_inertia': expected a moment of inertia (kg*m^2), got a force (N)",
        bad + ":3:76: error: body 'b': field 'ratio' is 'smooth'",
        gear + ":5:4: error: gears: field 'L': expected a length (m), got a mass (kg)"})
    EXPECT_NE(r.err.find(expect), std::string::npos) << expect << "\n" << r.err;
  EXPECT_FALSE(fs::exists(test::temp_dir() / "never"));
}

// Claim: `energy` refuses the stepwise drive (its jumps lose energy, no energy integral), exit 2.
TEST(GearDriveCli, EnergyRefusesTheStepwiseRatio) {
  const auto r = test::run_cli("energy '" + test::example("walking-drive.yaml") + "' --set drive.ratio=stepwise");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("velocity jumps"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace machdyn
