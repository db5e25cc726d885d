// The main hoist started by a speed-controlled drive (examples/crane/main-hoist-inverter.yaml): the
// crane analysis with a drive that has states of its own, and the φ2 case's speed reference.
#include <cmath>
#include <string>
#include <gtest/gtest.h>

#include "machdyn/elements/speed_drive.hpp"
#include "machdyn/analysis/crane.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

const CraneFactorRow* find_row(const CraneReport& r, const std::string& factor) {
  for (const auto& x : r.rows)
    if (x.factor == factor) return &x;
  return nullptr;
}

// Claim: the φ2 case runs the hoist at vh: the motor's speed is vh · i_rope · i_gear = 0.2 m/s ·
// 13.333333 rad/m · 37 = 98.67 rad/s (kinematics of the drum link and the gear), and the speed
// drive's reference holds exactly that speed instead of its ramp from rest — so at t = 0 its speed
// error is 0.
TEST(CraneInverter, Phi2CaseHoldsTheDriveReferenceAtTheHoistingSpeed) {
  const Model m = load_model(test::example("crane/main-hoist-inverter.yaml"));
  const double vh = m.crane.hoist_speed;
  ASSERT_DOUBLE_EQ(vh, 0.2);
  const Model c = phi2_case_model(m, vh);
  const int motor = c.body_index("motor");
  ASSERT_GE(motor, 0);
  const double omega = vh * 13.333333 * 37.0;
  EXPECT_NEAR(c.bodies[static_cast<size_t>(motor)].v0, omega, 1e-12 * omega);
  ASSERT_EQ(c.drives.size(), 1u);
  const auto& drive = dynamic_cast<const SpeedDrive&>(*c.drives[0].law);
  for (double t : {0.0, 0.5, 1.0, 1.5}) EXPECT_NEAR(drive.ref.value(t), omega, 1e-12 * omega) << t;
}

// Claim: the inverter start (reference ramp over 1 s, torque limit 450 N·m, rise time 20 ms) loads
// the drive shaft less than the Kloss motor switched straight on (examples/crane/main-hoist.yaml):
// its φ5 is smaller, and its drive torque never exceeds the limit. The run passes the instants where
// the drive sits on its limit (mode on-limit+) without chattering.
TEST(CraneInverter, InverterStartHasASmallerPhi5ThanTheDirectStart) {
  const Model inverter = load_model(test::example("crane/main-hoist-inverter.yaml"));
  const Model direct = load_model(test::example("crane/main-hoist.yaml"));
  const CraneReport ri = crane_analysis(inverter), rd = crane_analysis(direct);
  const CraneFactorRow* pi = find_row(ri, "phi5");
  const CraneFactorRow* pd = find_row(rd, "phi5");
  ASSERT_NE(pi, nullptr);
  ASSERT_NE(pd, nullptr);
  EXPECT_LT(pi->simulated, pd->simulated);
  EXPECT_GT(pi->simulated, 1.0);
  const SimulationResult r = simulate(inverter);
  for (double M : test::series(r, "inverter.torque_N_m")) EXPECT_LE(std::abs(M), 450.0 * (1 + 1e-12));
}

}  // namespace
}  // namespace machdyn
