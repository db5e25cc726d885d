// The transmitted torque of an ideal gear merged at compile time (model.hpp: MergedGear, the column
// NAME.torque_N_m or NAME.force_N) against closed forms: a motor–gear–drum group driving a load
// through a spring, with the group's master on either side of the gear, and MSL's RollingWheel; on
// both integrators.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

class MergedGearTorque : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, MergedGearTorque,
                         ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf), test::IntegratorName{});

// Claim: τ_B, the torque the gear exerts on the drum, follows the closed form below, whether the
// group's master is the motor (the side summed is the drum's) or the drum (the motor's side summed,
// τ_B = −i τ_A).
// Derivation: motor J1 = 0.5 under M = 10 N·m, ideal gear φ_m = 4 φ_d, drum J2 = 8 under L = −4 N·m,
// spring c = 1e4 N·m/rad from the drum to the load J3 = 2, all at rest. In φ = φ_m: I = J1 + J2/16 = 1,
// δ = φ/4 − φ_3, F = c δ:  I φ'' = M + L/4 − F/4,  J3 φ_3'' = F, so δ'' = (M + L/4)/(4I) − ω² δ with
// ω² = c (1/(16 I) + 1/J3) and δ = δ_s (1 − cos ω t), δ_s = (M + L/4)/(4 I ω²). The drum's own equation
// J2 φ_d'' = τ_B + L − F gives τ_B = J2 φ''/4 + F − L.
TEST_P(MergedGearTorque, MatchesTheClosedFormOnBothSides) {
  const std::string rest = R"(
links:
  G: {type: ideal-gear, between: [motor, drum], ratio: 4}
  shaft: {type: spring, between: [drum, load], stiffness: 1e4 N*m/rad}
loads:
  M: {type: constant, body: motor, value: 10 N*m}
  L: {type: constant, body: drum, value: -4 N*m}
simulation: {t_end: 0.5 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}
)";
  const double J1 = 0.5, J2 = 8.0, J3 = 2.0, c = 1e4, M = 10.0, L = -4.0, I = J1 + J2 / 16.0;
  const double w = std::sqrt(c * (1.0 / (16.0 * I) + 1.0 / J3)), ds = (M + L / 4.0) / (4.0 * I * w * w);
  auto tau = [&](double t) {
    const double F = c * ds * (1.0 - std::cos(w * t)), phi2 = (M + L / 4.0 - F / 4.0) / I;
    return J2 * phi2 / 4.0 + F - L;
  };
  for (const char* order : {"  motor: {inertia: 0.5 kg*m^2}\n  drum: {inertia: 8 kg*m^2}\n",
                            "  drum: {inertia: 8 kg*m^2}\n  motor: {inertia: 0.5 kg*m^2}\n"}) {
    Model m = test::model_text(std::string("bodies:\n") + order + "  load: {inertia: 2 kg*m^2}\n" + rest);
    m.simulation.integrator = GetParam();
    ASSERT_EQ(m.merged_gears.size(), 1u);
    const SimulationResult r = simulate(m);
    const double err = test::max_error(r, "G.torque_N_m", tau);
    EXPECT_LT(err, 1e-6 * tau(0.0)) << order << " largest error " << err << " N*m";
    std::printf("merged gear torque (%s, master %s): largest error %.2e N*m of %.4f\n",
                GetParam() == IntegratorChoice::bdf ? "bdf" : "dopri5", m.bodies[0].name.c_str(), err, tau(0.0));
  }
}

// Claim: in examples/msl/rolling-wheel.yaml the wheel's force on the mass (a translational B:
// the column NAME.force_N) is what the mass and its drag need, F = m a + k v², with MSL's closed form
// v = 5 tanh(t − 0.1 s) m/s (2 kg reduced mass, 10 N from 0.1 s, k = 0.4 N·s²/m²), a = 5 sech²(t − 0.1):
// F = 5 sech² + 10 tanh² N after the step, 0 before (the row at the step itself is left out).
TEST_P(MergedGearTorque, RollingWheelForceMatchesTheClosedForm) {
  Model m = load_model(std::string(MACHDYN_SOURCE_DIR) + "/examples/msl/rolling-wheel.yaml");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const auto& t = test::series(r, "t_s");
  const auto& F = test::series(r, "idealRollingWheel.force_N");
  ASSERT_EQ(t.size(), F.size());
  double err = 0.0;
  for (size_t k = 0; k < t.size(); ++k) {
    if (std::abs(t[k] - 0.1) < 1e-9) continue;
    const double x = t[k] - 0.1, th = std::tanh(x), want = x < 0 ? 0.0 : 5.0 * (1.0 - th * th) + 10.0 * th * th;
    err = std::max(err, std::abs(F[k] - want));
  }
  EXPECT_LT(err, GetParam() == IntegratorChoice::bdf ? 1e-5 : 1e-7) << "largest error " << err << " N";
  std::printf("rolling wheel force (%s): largest error %.2e N\n", GetParam() == IntegratorChoice::bdf ? "bdf" : "dopri5",
              err);
}

// Claim: a gear inside a loop of ideal gears (ratios agreeing) has no side to sum, so no column;
// the loop's other gears neither.
TEST(MergedGearTorqueColumns, NoneInALoop) {
  const Model m = test::model_text(R"(
bodies:
  a: {inertia: 1 kg*m^2}
  b: {inertia: 1 kg*m^2}
  c: {inertia: 1 kg*m^2}
links:
  g1: {type: ideal-gear, between: [a, b], ratio: 2}
  g2: {type: ideal-gear, between: [b, c], ratio: 3}
  g3: {type: ideal-gear, between: [a, c], ratio: 6}
)");
  EXPECT_TRUE(m.merged_gears.empty());
}

}  // namespace
}  // namespace machdyn
