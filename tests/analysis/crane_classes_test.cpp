// φ2 of one hoist in every hoist drive class (crane_analysis(m, drive_classes), `machdyn crane
// --drive-classes`), against the closed form of a rigid drive and the numbers of the standard's table
// (/work/shared/docs/crane-standards.md, "φ2, hoisting an unrestrained grounded load").
#include <cmath>
#include <stdexcept>
#include <string>
#include <gtest/gtest.h>

#include "machdyn/analysis/crane.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace {

// A rigid drive (1e15 kg) hoists the grounded load m = 1000 kg through a rope c = 1e6 N/m with 10 mm
// of slack; HC3, vh,max = 0.5 m/s, creep speed 0.1 m/s.
const char* kHoist = R"(
gravity: 9.81 m/s^2
bodies:
  drive: {type: translational, mass: 1e15 kg}
  load: {type: translational, mass: 1000 kg, vertical: up}
links:
  rope: {type: rope, between: [drive, load], stiffness: 1e6 N/m, slack: 10 mm}
stops: {ground: {body: load, min: 0 m}}
simulation: {t_end: 0.5 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
crane: {hoisting_class: HC3, drive_class: HD1, hoist_speed: 0.5 m/s, creep_speed: 0.1 m/s, load: load, rope: rope}
)";

// Claim: one φ2 row per class, in the order asked. A rigid drive at constant vh through a rope c
// lifts the load with F_max = m g + vh √(c m), so φ2 = 1 + vh ω/g, ω = √(c/m) (to 1e-9), at the
// class's characteristic speed: HD1 vh,max = 0.5, HD2 and HD3 the creep speed 0.1, HD4 0.5 vh,max =
// 0.25 m/s; HD5 starts from zero speed and is not simulated. The standard's value is φ2,min + β2 vh
// with HC3's β2 = 0.51 s/m and φ2,min = 1.15 for HD1, HD2, HD4 and 1.05 for HD3, HD5 (the table).
TEST(CraneDriveClasses, Phi2InEveryDriveClassMatchesTheClosedFormAndTheTable) {
  const Model m = compile_model(parse_yaml_string(kHoist, "classes.yaml"), "classes.yaml");
  const CraneReport r = crane_analysis(m, {1, 2, 3, 4, 5});
  ASSERT_EQ(r.rows.size(), 5u);
  const double w = std::sqrt(1e6 / 1000.0), g = 9.81;
  const double vh[] = {0.5, 0.1, 0.1, 0.25, 0.0};
  const double phi2_min[] = {1.15, 1.15, 1.05, 1.15, 1.05};
  for (int k = 0; k < 5; ++k) {
    const CraneFactorRow& x = r.rows[static_cast<size_t>(k)];
    EXPECT_EQ(x.factor, "phi2");
    EXPECT_NE(x.case_name.find("HD" + std::to_string(k + 1)), std::string::npos) << x.case_name;
    EXPECT_NEAR(x.standard_lo, phi2_min[k] + 0.51 * vh[k], 1e-12) << "HD" << k + 1;
    if (k == 4) {
      EXPECT_TRUE(std::isnan(x.simulated));
      continue;
    }
    const double expected = 1.0 + vh[k] * w / g;
    EXPECT_NEAR(x.simulated, expected, 1e-9 * expected) << "HD" << k + 1;
  }
  EXPECT_THROW(crane_analysis(m, {6}), std::invalid_argument);
}

// Claim: a class that hoists at the creep speed without `creep_speed` in the section gives a row
// that says so instead of a simulation at speed 0.
TEST(CraneDriveClasses, CreepSpeedClassWithoutCreepSpeedSaysSo) {
  std::string text = kHoist;
  text.replace(text.find(", creep_speed: 0.1 m/s"), std::string(", creep_speed: 0.1 m/s").size(), "");
  const Model m = compile_model(parse_yaml_string(text, "classes.yaml"), "classes.yaml");
  const CraneReport r = crane_analysis(m, {2});
  ASSERT_EQ(r.rows.size(), 1u);
  EXPECT_TRUE(std::isnan(r.rows[0].simulated));
  EXPECT_NE(r.rows[0].note.find("creep_speed"), std::string::npos) << r.rows[0].note;
}

// Claim: `machdyn crane --drive-classes` prints one φ2 line per class and rejects an unknown class
// with a non-zero exit naming the option.
TEST(CraneDriveClasses, CliOption) {
  const std::string path = test::write_temp("classes.yaml", kHoist);
  const auto ok = test::run_cli("crane '" + path + "' --drive-classes HD1,HD4 -o classes_out");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("HC3/HD1"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("HC3/HD4"), std::string::npos) << ok.out;
  const auto bad = test::run_cli("crane '" + path + "' --drive-classes HD7 -o classes_bad");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--drive-classes"), std::string::npos) << bad.err;
}

}  // namespace
}  // namespace machdyn
