// The section `drives:` (model/compile_drive.hpp): DC motors and speed drives compile to SI with
// electrical units; every bad field is a located error, all listed at once; the CLI exits 2.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <gtest/gtest.h>

#include "machdyn/elements/dc_motor.hpp"
#include "machdyn/elements/speed_drive.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

Model compile_drives(const std::string& name, const std::string& drives) {
  return load_model(test::write_temp(name, "bodies:\n  R: {inertia: 1}\n  X: {type: translational, mass: 2}\ndrives:\n" +
                                               drives + "simulation: {t_end: 10 s}\n"));
}

std::string errors_of(const std::string& name, const std::string& drives) {
  try {
    compile_drives(name, drives);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Claim: the fields compile to SI: mΩ, mH, kV, N*m/A = V*s/rad, rpm; a linear motor on a translational
// body takes N/A; defaults: no torque limit, no lag, zero initial states.
TEST(DriveCompile, FieldsInSi) {
  const Model m = compile_drives("ok.yaml", R"(  M: {type: dc-motor, body: R, resistance: 250 mohm, inductance: 12 mH, motor_constant: 2 V*s/rad, voltage: 0.4 kV, initial_current: 3 A}
  lin: {type: dc-motor, body: X, resistance: 2 Ω, inductance: 1 H, motor_constant: 30 N/A, voltage: {type: step, value: 48 V, time: 1 s}}
  S: {type: speed-drive, body: R, reference: {type: ramp, value: 1500 rpm, end: 3 s}, gain: 20 N*m*s/rad, integral_time: 80 ms, torque_limit: 2 kN*m, rise_time: 5 ms, initial_torque: 300 N*m}
  P: {type: speed-drive, body: X, reference: 1 m/s, gain: 5 kN*s/m, integral_time: 1 s}
)");
  ASSERT_EQ(m.drives.size(), 4u);
  const auto& M = dynamic_cast<const DcMotor&>(*m.drives[0].law);
  EXPECT_STREQ(M.type(), "dc-motor");
  EXPECT_DOUBLE_EQ(M.R, 0.25);
  EXPECT_DOUBLE_EQ(M.L, 0.012);
  EXPECT_DOUBLE_EQ(M.k, 2.0);
  EXPECT_DOUBLE_EQ(M.u.value(0.0), 400.0);
  EXPECT_DOUBLE_EQ(M.i0, 3.0);
  EXPECT_EQ(m.drives[0].states(), 1);
  const auto& lin = dynamic_cast<const DcMotor&>(*m.drives[1].law);
  EXPECT_DOUBLE_EQ(lin.k, 30.0);
  EXPECT_DOUBLE_EQ(lin.u.value(2.0), 48.0);
  const auto& S = dynamic_cast<const SpeedDrive&>(*m.drives[2].law);
  EXPECT_STREQ(S.type(), "speed-drive");
  EXPECT_NEAR(S.ref.value(3.0), 1500 * 2 * M_PI / 60, 1e-12);
  EXPECT_DOUBLE_EQ(S.Kp, 20.0);
  EXPECT_DOUBLE_EQ(S.Ti, 0.08);
  EXPECT_DOUBLE_EQ(S.M_max, 2000.0);
  EXPECT_DOUBLE_EQ(S.T_m, 0.005);
  EXPECT_DOUBLE_EQ(S.M0, 300.0);
  EXPECT_EQ(m.drives[2].states(), 2);
  const auto& P = dynamic_cast<const SpeedDrive&>(*m.drives[3].law);
  EXPECT_DOUBLE_EQ(P.Kp, 5000.0);
  EXPECT_FALSE(std::isfinite(P.M_max));
  EXPECT_EQ(m.drives[3].states(), 1);
  // The reference's and the voltage's breakpoints are the run's.
  const auto b = m.breakpoints(10.0);
  EXPECT_NE(std::find(b.begin(), b.end(), 1.0), b.end());
  EXPECT_NE(std::find(b.begin(), b.end(), 3.0), b.end());
}

// Claim: every bad field is an error at its place (file:line:col), all listed together.
TEST(DriveCompile, BadFieldsAreLocatedAndListedTogether) {
  const std::string all = errors_of("bad.yaml", R"(  a: {type: dc-motor, body: R, resistance: -1 ohm, inductance: 2 mH, motor_constant: 1 N*m/A, voltage: 10 V}
  b: {type: dc-motor, body: R, resistance: 1 ohm, inductance: 2 s, motor_constant: 1 N*m/A, voltage: 10 V}
  c: {type: dc-motor, body: R, resistance: 1 ohm, inductance: 2 mH, motor_constant: 1 N/A, voltage: 10 A}
  d: {type: speed-drive, body: R, reference: 10 m/s, gain: 2, integral_time: 0 s}
  e: {type: speed-drive, body: R, reference: 10 rad/s, gain: 2, integral_time: 1 s, torque_limit: -5 N*m, rise_time: -1 s}
  f: {type: speed-drive, body: nobody, reference: 1, gain: 1, integral_time: 1}
  g: {type: dc-motor, body: R, resistance: 1 ohm, inductance: 2 mH, motor_constant: 1 N*m/A}
  h: {type: speed-drive, body: R, reference: 1, gain: 1, integral_time: 1, torque_limit: 10 N*m, initial_torque: 20 N*m}
  i: {type: stepper, body: R}
)");
  for (const char* want :
       {"bad.yaml:5:44: error: drive 'a': field 'resistance' must be positive, got -1",
        "bad.yaml:6:63: error: drive 'b': field 'inductance': expected an inductance (H), got a time (s)",
        "bad.yaml:7:85: error: drive 'c': field 'motor_constant': expected a motor constant (N*m/A = V*s/rad)",
        "bad.yaml:7:101: error: drive 'c': field 'voltage': expected a voltage (V), got a current (A)",
        "bad.yaml:8:46: error: drive 'd': field 'reference': expected an angular velocity (rad/s)",
        "bad.yaml:8:78: error: drive 'd': field 'integral_time' must be positive, got 0",
        "bad.yaml:9:99: error: drive 'e': field 'torque_limit' must be positive, got -5",
        "bad.yaml:9:118: error: drive 'e': field 'rise_time' must be zero or positive, got -1",
        "bad.yaml:10:32: error: drive 'f': unknown body 'nobody'",
        "bad.yaml:11:6: error: drive 'g': missing field 'voltage'",
        "bad.yaml:12:114: error: drive 'h': field 'initial_torque' (20) exceeds the torque limit 10",
        "bad.yaml:13:13: error: drive 'i': field 'type' is 'stepper'; expected one of: dc-motor, speed-drive, thermal-eddy-current-brake"})
    EXPECT_NE(all.find(want), std::string::npos) << want << "\n--- got:\n" << all;
  EXPECT_EQ(std::count(all.begin(), all.end(), '\n'), 11) << all;  // twelve problems, one line each
}

// Claim: a drive under `loads:` is pointed to `drives:`; through the CLI a bad drive exits 2 and
// writes nothing.
TEST(DriveCompile, WrongSectionHintAndCliExitsTwo) {
  const auto path = test::write_temp("bad-drive-cli.yaml", "bodies:\n  R: {inertia: 1}\nloads:\n"
                                                            "  M: {type: dc-motor, body: R}\n");
  const auto out = test::temp_dir() / "bad-drive-out";
  const auto r = test::run_cli("simulate '" + path + "' -o '" + out.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad-drive-cli.yaml:4:13: error: load 'M': type 'dc-motor' is not a kind of loads; a dc-motor goes under 'drives:'"),
            std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out / "timeseries.csv"));
}

}  // namespace
}  // namespace machdyn
