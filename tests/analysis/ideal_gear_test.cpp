// Ideal gears (`type: ideal-gear`, model/compile_rigid.cpp): rigid connections merged by compile into
// one degree of freedom. Against closed forms of the reduced equation of motion (both integrators),
// a very stiff spring instead of the gear, the modes of the hand-reduced chain, and MSL's First
// example against an independent RK4 of its equations written here; bad input is a located error.
#include <algorithm>
#include <array>
#include <cmath>
#include <string>
#include <vector>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

Model compile_text(const std::string& text) { return test::model_text(text, "gear.yaml"); }

std::string errors_of(const std::string& text) { return test::compile_errors(text, "gear.yaml"); }

class IdealGearSim : public ::testing::TestWithParam<const char*> {
 protected:
  SimulationResult run(const std::string& yaml, double t_end, double rtol = 1e-11) const {
    const Model m = compile_text(yaml + fmt::format("simulation: {{t_end: {}, dt_out: {}, rtol: {}, atol: 1e-13, "
                                                    "integrator: {}}}\n", t_end, t_end / 100, rtol, GetParam()));
    return simulate(m);
  }
};

INSTANTIATE_TEST_SUITE_P(BothIntegrators, IdealGearSim, ::testing::Values("dopri5", "bdf"));

constexpr double kIA = 0.3, kIB = 2.0, kI = 3.5;  // kg·m², kg·m², q_A = i q_B

// Claim: A (I_A) and B (I_B) through an ideal gear q_A = i q_B, constant torques M_A on A and M_B on
// B, from rest. Lagrange's equation in q_B (T = ½ (I_B + i² I_A) ω_B², δW = (i M_A + M_B) δq_B):
//   J ω_B' = i M_A + M_B,  J = I_B + i² I_A  ⇒  ω_B = (i M_A + M_B) t / J,  q_B = ½ (i M_A + M_B) t² / J,
// and ω_A = i ω_B, q_A = i q_B. One state pair (dof 1); to 1e-12 relative at every row.
TEST_P(IdealGearSim, ConstantTorquesGiveTheReducedInertiaRamp) {
  const std::string yaml = fmt::format(R"(bodies:
  A: {{inertia: {} kg*m^2}}
  B: {{inertia: {} kg*m^2}}
links:
  G: {{type: ideal-gear, between: [A, B], ratio: {}}}
loads:
  MA: {{type: constant, body: A, value: 10 N*m}}
  MB: {{type: constant, body: B, value: -4 N*m}}
)", kIA, kIB, kI);
  const Model m = compile_text(yaml);
  ASSERT_EQ(m.dof(), 1);
  EXPECT_EQ(m.bodies[0].name, "A");  // the first body of the group is the master
  EXPECT_NEAR(m.bodies[0].inertia, kIA + kIB / (kI * kI), 1e-15);
  const SimulationResult r = run(yaml, 2.0);
  const double J = kIB + kI * kI * kIA, a = (kI * 10.0 - 4.0) / J;
  const auto& t = test::series(r, "t_s");
  const auto& wA = test::series(r, "A.velocity_rad_s");
  const auto& wB = test::series(r, "B.velocity_rad_s");
  const auto& qA = test::series(r, "A.position_rad");
  const auto& qB = test::series(r, "B.position_rad");
  ASSERT_EQ(t.size(), 101u);
  for (size_t k = 0; k < t.size(); ++k) {
    EXPECT_NEAR(wB[k], a * t[k], 1e-12 * (1.0 + a * t[k]));
    EXPECT_NEAR(qB[k], 0.5 * a * t[k] * t[k], 1e-12 * (1.0 + a * t[k] * t[k]));
    EXPECT_NEAR(wA[k], kI * a * t[k], 1e-12 * (1.0 + kI * a * t[k]));
    EXPECT_NEAR(qA[k], 0.5 * kI * a * t[k] * t[k], 1e-12 * (1.0 + kI * a * t[k] * t[k]));
  }
}

// Claim: a speed-dependent load on the slave sees the slave's own speed ω_A = i ω_B: M_A = M0 − k ω_A
// (an expression in omega). J ω_B' = i (M0 − k i ω_B) ⇒ ω_B = (M0/(k i)) (1 − e^{−k i² t/J}).
TEST_P(IdealGearSim, SpeedDependentLoadOfTheSlaveSeesItsOwnSpeed) {
  const double k = 0.2, M0 = 10.0;
  const std::string yaml = fmt::format(R"(bodies:
  B: {{inertia: {} kg*m^2}}
  A: {{inertia: {} kg*m^2}}
links:
  G: {{type: ideal-gear, between: [A, B], ratio: {}}}
loads:
  MA: {{type: expression, body: A, expression: "{} - {}*omega"}}
)", kIB, kIA, kI, M0, k);
  const SimulationResult r = run(yaml, 3.0);
  const double J = kIB + kI * kI * kIA;
  const auto& t = test::series(r, "t_s");
  const auto& wB = test::series(r, "B.velocity_rad_s");
  const auto& wA = test::series(r, "A.velocity_rad_s");
  for (size_t n = 0; n < t.size(); ++n) {
    const double w = M0 / (k * kI) * (1.0 - std::exp(-k * kI * kI * t[n] / J));
    EXPECT_NEAR(wB[n], w, 1e-8);
    EXPECT_NEAR(wA[n], kI * w, 1e-8);
  }
}

// Claim: a position-dependent load on the slave sees the slave's own angle q_A = i q_B: M_A = −c φ_A,
// J q_B'' = −c i² q_B ⇒ q_B = q_B0 cos(Ω t), Ω² = c i²/J. The start is given on the slave only
// (q_A0 = 0.35 rad), so q_B0 = q_A0/i = 0.1 rad.
TEST_P(IdealGearSim, PositionDependentLoadOfTheSlaveAndStartGivenOnTheSlave) {
  const double c = 40.0;
  const std::string yaml = fmt::format(R"(bodies:
  B: {{inertia: {} kg*m^2}}
  A: {{inertia: {} kg*m^2, position: 0.35 rad}}
links:
  G: {{type: ideal-gear, between: [A, B], ratio: {}}}
loads:
  MA: {{type: expression, body: A, expression: "-{}*phi"}}
)", kIB, kIA, kI, c);
  const SimulationResult r = run(yaml, 2.0);
  const double W = std::sqrt(c * kI * kI / (kIB + kI * kI * kIA));
  const auto& t = test::series(r, "t_s");
  const auto& qB = test::series(r, "B.position_rad");
  const auto& qA = test::series(r, "A.position_rad");
  for (size_t n = 0; n < t.size(); ++n) {
    EXPECT_NEAR(qB[n], 0.1 * std::cos(W * t[n]), 1e-8);
    EXPECT_NEAR(qA[n], 0.35 * std::cos(W * t[n]), 1e-8);
  }
}

// Claim: the same two inertias joined by a spring of stiffness c (δ = q_A/i − q_B) instead of the ideal
// gear converge to the rigid answer as c grows: the vibration about the rigid motion has a speed
// amplitude ∝ F/√(c J_rel) → 0, so c × 100 shrinks the largest deviation of ω_B about 10 times.
TEST_P(IdealGearSim, StiffSpringConvergesToTheIdealGear) {
  const auto yaml = [&](const std::string& link) {
    return fmt::format(R"(bodies:
  A: {{inertia: {} kg*m^2}}
  B: {{inertia: {} kg*m^2}}
links:
  G: {}
loads:
  MA: {{type: constant, body: A, value: 10 N*m}}
)", kIA, kIB, link);
  };
  const SimulationResult rigid = run(yaml(fmt::format("{{type: ideal-gear, between: [A, B], ratio: {}}}", kI)), 0.5);
  std::vector<double> dev;
  for (double c : {1e3, 1e5, 1e7}) {
    const SimulationResult r =
        run(yaml(fmt::format("{{type: spring, between: [A, B], ratio: {}, stiffness: {}}}", kI, c)), 0.5, 1e-10);
    const auto& w = test::series(r, "B.velocity_rad_s");
    const auto& w0 = test::series(rigid, "B.velocity_rad_s");
    double d = 0.0;
    for (size_t k = 0; k < w.size(); ++k) d = std::max(d, std::abs(w[k] - w0[k]));
    dev.push_back(d);
  }
  const double scale = test::series(rigid, "B.velocity_rad_s").back();
  EXPECT_LT(dev[2], 1e-3 * scale);
  for (int k = 0; k < 2; ++k) {
    EXPECT_GT(dev[k] / dev[k + 1], 5.0) << k;
    EXPECT_LT(dev[k] / dev[k + 1], 20.0) << k;
  }
}

// Claim: the modes of a chain with an ideal gear are those of the chain reduced by hand, whichever
// body of the gear comes first in the file (and so is the master). Chain: b0 –(ideal gear q0 = 2 q1)–
// b1 –(spring, ratio 1.5, c = 4000)– b2 –(spring to ground, 900)–, plus a spring b0–ground (300).
// By hand in q0: I0 + I1/4; the spring's δ = q1/1.5 − q2 = q0/3 − q2 (ratio 3); in q1: I1 + 4 I0 and a
// ground spring δ = q0 = 2 q1, so 4 × 300 on q1.
TEST(IdealGearModes, EqualTheHandReducedChain) {
  const double I0 = 0.7, I1 = 1.3, I2 = 2.1;
  const std::string rest = R"(  b2: {inertia: 2.1 kg*m^2}
links:
  G: {type: ideal-gear, between: [b0, b1], ratio: 2}
  k: {type: spring, between: [b1, b2], ratio: 1.5, stiffness: 4000 N*m/rad}
  g2: {type: spring, between: [b2, ground], stiffness: 900 N*m/rad}
  g0: {type: spring, between: [b0, ground], stiffness: 300 N*m/rad}
)";
  const Model m0 = compile_text("bodies:\n  b0: {inertia: 0.7 kg*m^2}\n  b1: {inertia: 1.3 kg*m^2}\n" + rest);
  const Model m1 = compile_text("bodies:\n  b1: {inertia: 1.3 kg*m^2}\n  b0: {inertia: 0.7 kg*m^2}\n" + rest);
  const Model h0 = compile_text(fmt::format(R"(bodies:
  b0: {{inertia: {:.17g} kg*m^2}}
  b2: {{inertia: {} kg*m^2}}
links:
  k: {{type: spring, between: [b0, b2], ratio: 3, stiffness: 4000 N*m/rad}}
  g2: {{type: spring, between: [b2, ground], stiffness: 900 N*m/rad}}
  g0: {{type: spring, between: [b0, ground], stiffness: 300 N*m/rad}}
)", I0 + I1 / 4, I2));
  const Model h1 = compile_text(fmt::format(R"(bodies:
  b1: {{inertia: {:.17g} kg*m^2}}
  b2: {{inertia: {} kg*m^2}}
links:
  k: {{type: spring, between: [b1, b2], ratio: 1.5, stiffness: 4000 N*m/rad}}
  g2: {{type: spring, between: [b2, ground], stiffness: 900 N*m/rad}}
  g0: {{type: spring, between: [b1, ground], stiffness: 1200 N*m/rad}}
)", I1 + 4 * I0, I2));
  ASSERT_EQ(m0.dof(), 2);
  ASSERT_EQ(m1.dof(), 2);
  const Modes a = compute_modes(m0), b = compute_modes(m1), ha = compute_modes(h0), hb = compute_modes(h1);
  ASSERT_EQ(a.omega.size(), 2);
  ASSERT_EQ(b.omega.size(), 2);
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(a.omega(k), ha.omega(k), 1e-10 * ha.omega(k));
    EXPECT_NEAR(b.omega(k), hb.omega(k), 1e-10 * hb.omega(k));
    EXPECT_NEAR(a.omega(k), b.omega(k), 1e-10 * b.omega(k));  // the same system in either coordinate
  }
}

// Claim: MSL Rotational.Examples.First (examples/msl/first.yaml) matches an independent RK4 of MSL's
// equations written here in inertia2's angle φ2 (φ_motor = 10 φ2, the gear's torque balance
// τ_b = −10 τ_a eliminated): (J2 + 10² J1) φ2'' = 10 τ(t) − d φ2' − c (φ2 − φ3), J3 φ3'' = c (φ2 − φ3),
// τ = 10 sin(2π 5 t), J1 = 0.1, J2 = J3 = 2, c = 1e4, d = 10, at rest at t = 0. RK4 with h = 1e-5 s
// (h ω_max ≈ 1e-3): speeds at every 10 ms within 1e-8 rad/s (dopri5), 1e-6 rad/s (bdf).
void check_msl_first(const std::string& file, const std::string& motor, const char* integrator) {
  Model m = load_model(test::example(file), {std::string("simulation.integrator=") + integrator});
  ASSERT_EQ(m.dof(), 2);
  const SimulationResult r = simulate(m);
  const double J = 2.0 + 100.0 * 0.1, J3 = 2.0, c = 1e4, d = 10.0, pi = std::acos(-1.0);
  auto f = [&](double t, const std::array<double, 4>& y) {
    const double tau = 10.0 * std::sin(2 * pi * 5.0 * t), s = c * (y[0] - y[2]);
    return std::array<double, 4>{y[1], (10.0 * tau - d * y[1] - s) / J, y[3], s / J3};
  };
  std::array<double, 4> y{0, 0, 0, 0};
  const double h = 1e-5;
  const auto& t = test::series(r, "t_s");
  const auto& w2 = test::series(r, "inertia2.velocity_rad_s");
  const auto& w3 = test::series(r, "inertia3.velocity_rad_s");
  const auto& w1 = test::series(r, motor + ".velocity_rad_s");
  long step = 0;
  int checked = 0;
  const double tol = std::string(integrator) == "dopri5" ? 1e-8 : 1e-6;  // rad/s; bdf measured ≤ 1e-7
  for (size_t k = 0; k < t.size(); k += 10) {
    const long target = std::lround(t[k] / h);
    for (; step < target; ++step) {
      const double s = static_cast<double>(step) * h;
      std::array<double, 4> k1 = f(s, y), y2, y3, y4;
      for (int i = 0; i < 4; ++i) y2[i] = y[i] + 0.5 * h * k1[i];
      const auto k2 = f(s + 0.5 * h, y2);
      for (int i = 0; i < 4; ++i) y3[i] = y[i] + 0.5 * h * k2[i];
      const auto k3 = f(s + 0.5 * h, y3);
      for (int i = 0; i < 4; ++i) y4[i] = y[i] + h * k3[i];
      const auto k4 = f(s + h, y4);
      for (int i = 0; i < 4; ++i) y[i] += h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
    EXPECT_NEAR(w2[k], y[1], tol) << "t = " << t[k];
    EXPECT_NEAR(w3[k], y[3], tol) << "t = " << t[k];
    EXPECT_NEAR(w1[k], 10.0 * y[1], 10 * tol) << "t = " << t[k];
    ++checked;
  }
  EXPECT_EQ(checked, 101);
}

TEST_P(IdealGearSim, MslFirstMatchesAnIndependentRk4) { check_msl_first("msl/first.yaml", "motor", GetParam()); }

// Claim: MSL Rotational.Examples.FirstGrounded (examples/msl/first-grounded.yaml: First with the
// torque source and the gear grounded instead of tied to a housing flange) has First's equations
// and matches the same independent RK4 within the same tolerances (its motor is `inertia1`).
TEST_P(IdealGearSim, MslFirstGroundedMatchesAnIndependentRk4) {
  check_msl_first("msl/first-grounded.yaml", "inertia1", GetParam());
}

// Claim: a massless flange (inertia 0) tied by an ideal gear to a body with inertia is accepted and
// costs no state; a rigid loop with consistent ratios (2 · 3 = 6) is accepted.
TEST(IdealGearCompile, MasslessFlangeAndConsistentLoop) {
  const Model m = compile_text(R"(bodies:
  motor: {inertia: 0.5}
  flange: {inertia: 0}
  load: {inertia: 4}
links:
  G: {type: ideal-gear, between: [motor, flange], ratio: 5}
  shaft: {type: spring, between: [flange, load], stiffness: 1000}
)");
  ASSERT_EQ(m.dof(), 2);
  EXPECT_DOUBLE_EQ(m.bodies[0].inertia, 0.5);
  ASSERT_EQ(m.slaves.size(), 1u);
  EXPECT_EQ(m.slaves[0].name, "flange");
  EXPECT_DOUBLE_EQ(m.slaves[0].ratio, 0.2);
  EXPECT_DOUBLE_EQ(m.links[0].ratio, 5.0);  // δ = q_flange − q_load = q_motor/5 − q_load
  const Model loop = compile_text(R"(bodies:
  A: {inertia: 1}
  B: {inertia: 1}
  C: {inertia: 1}
links:
  AB: {type: ideal-gear, between: [A, B], ratio: 2}
  BC: {type: ideal-gear, between: [B, C], ratio: 3}
  AC: {type: ideal-gear, between: [A, C], ratio: 6}
)");
  ASSERT_EQ(loop.dof(), 1);
  EXPECT_NEAR(loop.bodies[0].inertia, 1.0 + 1.0 / 4 + 1.0 / 36, 1e-15);
}

// Claim: each misuse is a located error (file:line:col) that says why.
TEST(IdealGearCompile, BadInputIsALocatedError) {
  const std::string massless = errors_of("bodies:\n  A: {inertia: 1}\n  F: {inertia: 0}\n");
  EXPECT_NE(massless.find("gear.yaml:3:"), std::string::npos) << massless;
  EXPECT_NE(massless.find("massless"), std::string::npos) << massless;
  const std::string all_zero = errors_of(
      "bodies:\n  A: {inertia: 0}\n  F: {inertia: 0}\nlinks:\n  G: {type: ideal-gear, between: [A, F], ratio: 2}\n");
  EXPECT_NE(all_zero.find("zero inertia together"), std::string::npos) << all_zero;
  const std::string loop = errors_of(R"(bodies:
  A: {inertia: 1}
  B: {inertia: 1}
  C: {inertia: 1}
links:
  AB: {type: ideal-gear, between: [A, B], ratio: 2}
  BC: {type: ideal-gear, between: [B, C], ratio: 3}
  AC: {type: ideal-gear, between: [A, C], ratio: 5}
)");
  // The error sits at the ratio of the gear that closes the loop in the search (BC or AC, lines 7-8).
  EXPECT_TRUE(loop.find("gear.yaml:7:") != std::string::npos || loop.find("gear.yaml:8:") != std::string::npos) << loop;
  EXPECT_NE(loop.find("ratios disagree"), std::string::npos) << loop;
  const std::string start = errors_of(
      "bodies:\n  A: {inertia: 1, velocity: 3}\n  B: {inertia: 1, velocity: 2}\nlinks:\n"
      "  G: {type: ideal-gear, between: [A, B], ratio: 2}\n");
  EXPECT_NE(start.find("gear.yaml:3:"), std::string::npos) << start;
  EXPECT_NE(start.find("contradicts"), std::string::npos) << start;
  EXPECT_EQ(errors_of("bodies:\n  A: {inertia: 1, velocity: 4}\n  B: {inertia: 1, velocity: 2}\nlinks:\n"
                      "  G: {type: ideal-gear, between: [A, B], ratio: 2}\n"),
            "");
  const std::string ground =
      errors_of("bodies:\n  A: {inertia: 1}\nlinks:\n  G: {type: ideal-gear, between: [A, ground], ratio: 2}\n");
  EXPECT_NE(ground.find("gear.yaml:4:"), std::string::npos) << ground;
  const std::string brake = errors_of(R"(bodies:
  A: {inertia: 1}
  B: {inertia: 1}
links:
  G: {type: ideal-gear, between: [A, B], ratio: 2}
brakes:
  K: {body: B, holding: 5}
)");
  EXPECT_NE(brake.find("not supported yet"), std::string::npos) << brake;
  const std::string second_end = errors_of(R"(bodies:
  A: {inertia: 1}
  B: {inertia: 1}
  C: {inertia: 1}
links:
  G: {type: ideal-gear, between: [A, B], ratio: 2}
  k: {type: spring, between: [C, B], stiffness: 10}
)");
  EXPECT_NE(second_end.find("gear.yaml:7:"), std::string::npos) << second_end;
  const std::string stiff = errors_of(
      "bodies:\n  A: {inertia: 1}\n  B: {inertia: 1}\nlinks:\n  G: {type: ideal-gear, between: [A, B], stiffness: 3}\n");
  EXPECT_NE(stiff.find("stiffness"), std::string::npos) << stiff;
}

}  // namespace
}  // namespace machdyn
