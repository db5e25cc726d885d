// The contact-mode decision at an event (analysis/contact_decision.hpp) on the travel start-up's
// wheel and trolley at rest: a force F on the wheel mk, the adhesion between mk and the trolley m2,
// the resistance W between m2 and the ground. The run forms the returned modes only once because
// the decision leaves the drive system in them: that is checked with every answer.
#include <string>
#include <utility>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/analysis/contact_decision.hpp"
#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// F_sc = 9 kN, F_d = 5.5 kN (adhesion); W = 1.5 kN static and kinetic; mk = 300 kg, m2 = 10 000 kg.
Model wheel_and_trolley(double F) {
  const std::string yaml = R"(
bodies:
  mk: {type: translational, mass: 300 kg}
  m2: {type: translational, mass: 10000 kg}
contacts:
  adhesion: {between: [mk, m2], static: 9 kN, kinetic: 5.5 kN}
  W: {between: [m2, ground], static: 1.5 kN, kinetic: 1.5 kN}
loads:
  F: {type: constant, body: mk, value: )" + std::to_string(F) + R"( N}
)";
  return compile_model(parse_yaml_string(yaml, "decision.yaml"), "decision.yaml");
}

int contact_index(const Model& m, const std::string& name) {
  for (size_t k = 0; k < m.contacts.size(); ++k)
    if (m.contacts[k].name == name) return static_cast<int>(k);
  ADD_FAILURE() << "no contact " << name;
  return -1;
}

struct Decided {
  ContactMode adhesion, W;
  double lambda_adhesion;  // the adhesion's force in the decided modes, N
  bool system_in_modes;    // the drive system is left in the returned modes
};

Decided decide_at_rest(double F) {
  const Model m = wheel_and_trolley(F);
  DriveSystem sys(m, false);
  std::vector<double> y(static_cast<size_t>(sys.size()), 0.0);
  const int a = contact_index(m, "adhesion"), w = contact_index(m, "W");
  const std::vector<ContactMode> modes = decide_contacts(sys, 0.0, y.data(), {0, 1}, {});
  std::vector<double> acc(2), fc(2);
  sys.evaluate(0.0, y.data(), acc.data(), fc.data());
  return {modes[static_cast<size_t>(a)], modes[static_cast<size_t>(w)], fc[static_cast<size_t>(a)],
          sys.contact_modes() == modes};
}

// Claim: F = 1 kN ≤ W_s = 1.5 kN: both hold; the adhesion carries all of F to the trolley (λ = F).
TEST(ContactDecision, BothHoldBelowTheResistance) {
  const Decided d = decide_at_rest(1000.0);
  EXPECT_EQ(d.adhesion, ContactMode::stuck);
  EXPECT_EQ(d.W, ContactMode::stuck);
  EXPECT_NEAR(d.lambda_adhesion, 1000.0, 1e-9);
  EXPECT_TRUE(d.system_in_modes);
}

// Claim: F = 3 kN: stuck, W would carry 3 kN > 1.5 kN (ratio 2 against the adhesion's 1/3), so W
// slides forward; mk and m2 then move together with a = (F − W)/(mk + m2), and the adhesion holds
// λ = F − mk a = 3000 − 300 · 1500/10300 = 2956.3 N ≤ 9 kN (the stage 3 of the travel start-up).
TEST(ContactDecision, TheResistanceSlidesAndTheWheelHolds) {
  const Decided d = decide_at_rest(3000.0);
  EXPECT_EQ(d.adhesion, ContactMode::stuck);
  EXPECT_EQ(d.W, ContactMode::slip_pos);
  EXPECT_NEAR(d.lambda_adhesion, 3000.0 - 300.0 * 1500.0 / 10300.0, 1e-9);
  EXPECT_TRUE(d.system_in_modes);
}

// Claim: F = 20 kN: W goes first (20/1.5 against 20/9), then the adhesion would need
// λ = 20000 − 300 · 18500/10300 = 19461 N > 9 kN: it slips too, at F_d = 5.5 kN, and the wheel runs
// ahead (ü_k = (20000 − 5500)/300 > ü_2 = (5500 − 1500)/10000): both slide forward.
TEST(ContactDecision, BothSlideAboveTheAdhesionLimit) {
  const Decided d = decide_at_rest(20000.0);
  EXPECT_EQ(d.adhesion, ContactMode::slip_pos);
  EXPECT_EQ(d.W, ContactMode::slip_pos);
  EXPECT_NEAR(d.lambda_adhesion, 5500.0, 1e-9);
  EXPECT_TRUE(d.system_in_modes);
}

// Claim: the form that writes into a kept vector (the run's, reused at every event) gives the same
// answers as above whatever the vector held before: stale modes of another length are overwritten.
// F = 20 kN: both slide forward (above); then F = 1 kN into the same vector: both hold.
TEST(ContactDecision, IntoAKeptVectorOverwritesWhatItHeld) {
  std::vector<ContactMode> modes(5, ContactMode::slip_neg);
  for (const auto& [F, expected] : {std::pair{20000.0, ContactMode::slip_pos}, std::pair{1000.0, ContactMode::stuck}}) {
    const Model m = wheel_and_trolley(F);
    DriveSystem sys(m, false);
    std::vector<double> y(static_cast<size_t>(sys.size()), 0.0);
    decide_contacts(sys, 0.0, y.data(), {0, 1}, {}, modes);
    ASSERT_EQ(modes.size(), 2U);
    EXPECT_EQ(modes[static_cast<size_t>(contact_index(m, "adhesion"))], expected) << "F = " << F;
    EXPECT_EQ(modes[static_cast<size_t>(contact_index(m, "W"))], expected) << "F = " << F;
    EXPECT_TRUE(sys.contact_modes() == modes);
  }
}

}  // namespace
}  // namespace machdyn
