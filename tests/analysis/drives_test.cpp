// Drives with states of their own (elements/dc_motor.hpp, elements/speed_drive.hpp) through the one
// engine, against closed forms, on both integrators and both paths (plain and event-driven); their
// Jacobian terms against finite differences; their torque in the quasi-static loads and the linear
// model.
#include <algorithm>
#include <cmath>
#include <string>
#include <tuple>
#include <vector>
#include <Eigen/Core>
#include <gtest/gtest.h>

#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/elements/linearize.hpp"
#include "machdyn/elements/speed_drive.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/solve/stepper.hpp"
#include "support/jacobian.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

Model compile_text(const std::string& text) {
  return compile_model_case(parse_yaml_string(text, "drives.yaml"), "drives.yaml", {}, "");
}

/// (integrator, event-driven path)
class DriveSim : public ::testing::TestWithParam<std::tuple<Method, bool>> {
 protected:
  Model model(const std::string& yaml, double t_end, double dt_out) const {
    const char* integ = std::get<0>(GetParam()) == Method::dopri5 ? "dopri5" : "bdf";
    return compile_text(yaml + "simulation: {t_end: " + std::to_string(t_end) + ", dt_out: " + std::to_string(dt_out) +
                        ", rtol: 1e-10, atol: 1e-12, integrator: " + integ + "}\n");
  }
  SimulationResult run(const Model& m) const {
    SimulateOptions o;
    o.event_driven = std::get<1>(GetParam());
    return simulate(m, o);
  }
};

INSTANTIATE_TEST_SUITE_P(BothIntegratorsBothPaths, DriveSim,
                         ::testing::Combine(::testing::Values(Method::dopri5, Method::bdf), ::testing::Bool()));

// Claim: with the rotor locked (an inertia of 1e15 kg·m², so k ω < 1e-12 V) the armature current
// rises as the RL circuit's: L i' = u − R i, i(0) = 0 ⇒ i(t) = (u/R)(1 − e^{−t R/L}), time constant
// L/R = 0.05 s, final value u/R = 40 A, and the torque is k i.
TEST_P(DriveSim, DcMotorLockedRotorCurrentRisesWithTimeConstantLOverR) {
  const Model m = model(R"(bodies:
  rotor: {inertia: 1e15 kg*m^2}
drives:
  M: {type: dc-motor, body: rotor, resistance: 0.5 ohm, inductance: 25 mH, motor_constant: 2 N*m/A, voltage: 20 V}
)", 0.5, 1e-3);
  const SimulationResult r = run(m);
  const auto& t = r.columns[0];
  const auto& i = r.columns[test::column(r, "M.current_A")];
  const auto& M = r.columns[test::column(r, "M.torque_N_m")];
  double worst = 0;
  for (size_t k = 0; k < t.size(); ++k) {
    const double ref = 40.0 * (1.0 - std::exp(-t[k] / 0.05));
    worst = std::max(worst, std::abs(i[k] - ref));
    ASSERT_NEAR(M[k], 2.0 * i[k], 1e-12 * 80);
  }
  EXPECT_LT(worst, 1e-7 * 40);
  EXPECT_NEAR(i.back(), 40.0 * (1.0 - std::exp(-10.0)), 1e-6);
}

// Claim: a DC motor on a free inertia, u = 100 V, k = 1 N·m/A, R = 1 Ω, L = 0.1 H, J = 0.1 kg·m²,
// from rest and i = 0, follows the second-order system obtained by eliminating i (J ω' = k i):
//   J L ω'' + J R ω' + k² ω = k u  ⇒  ω'' + 10 ω' + 100 ω = 10⁴.
// α = R/(2L) = 5, β = √(k²/(J L) − α²) = √75; ω(0) = 0 and ω'(0) = k i(0)/J = 0 give
//   ω(t) = ω∞ (1 − e^{−αt}(cos βt + (α/β) sin βt)),  ω∞ = u/k = 100 rad/s (the no-load speed),
// and i = J ω'/k = (J ω∞/k)(α²/β + β) e^{−αt} sin βt.
TEST_P(DriveSim, DcMotorOnInertiaMatchesSecondOrderClosedFormAndNoLoadSpeed) {
  const Model m = model(R"(bodies:
  rotor: {inertia: 0.1 kg*m^2}
drives:
  M: {type: dc-motor, body: rotor, resistance: 1 ohm, inductance: 100 mH, motor_constant: 1 V*s/rad, voltage: 100 V}
)", 4.0, 1e-3);
  const SimulationResult r = run(m);
  const auto& t = r.columns[0];
  const auto& w = r.columns[test::column(r, "rotor.velocity_rad_s")];
  const auto& i = r.columns[test::column(r, "M.current_A")];
  const double a = 5.0, b = std::sqrt(75.0), winf = 100.0;
  double worst_w = 0, worst_i = 0;
  for (size_t k = 0; k < t.size(); ++k) {
    const double e = std::exp(-a * t[k]);
    worst_w = std::max(worst_w, std::abs(w[k] - winf * (1.0 - e * (std::cos(b * t[k]) + a / b * std::sin(b * t[k])))));
    worst_i = std::max(worst_i, std::abs(i[k] - 0.1 * winf * (a * a / b + b) * e * std::sin(b * t[k])));
  }
  EXPECT_LT(worst_w, 1e-7 * winf);
  EXPECT_LT(worst_i, 1e-7 * 100);
  EXPECT_NEAR(w.back(), 100.0, 1e-6);  // e^{−20}·100 ≈ 2e-7: the no-load speed u/k
}

// Claim: a PI speed drive on a rigid inertia (no limit reached) is a linear 2nd-order system. With
// e = ω_ref − ω, z = ∫e dt and a constant reference: J e' = −K_p e − (K_p/T_i) z, so
//   J z'' + K_p z' + (K_p/T_i) z = 0,  z(0) = 0, z'(0) = ω_ref.
// J = 1, K_p = 2, T_i = 1: z'' + 2 z' + 2 z = 0, roots −1 ± i: z = ω_ref e^{−t} sin t, and
//   ω(t) = ω_ref − z' = ω_ref (1 − e^{−t}(cos t − sin t)).
TEST_P(DriveSim, SpeedDriveLinearRangeMatchesSecondOrderClosedForm) {
  const Model m = model(R"(bodies:
  rotor: {inertia: 1 kg*m^2}
drives:
  S: {type: speed-drive, body: rotor, reference: 10 rad/s, gain: 2 N*m*s/rad, integral_time: 1 s, torque_limit: 1 kN*m}
)", 6.0, 1e-3);
  const SimulationResult r = run(m);
  const auto& t = r.columns[0];
  const auto& w = r.columns[test::column(r, "rotor.velocity_rad_s")];
  const auto& mode = r.columns[test::column(r, "S.mode")];
  double worst = 0;
  for (size_t k = 0; k < t.size(); ++k) {
    worst = std::max(worst, std::abs(w[k] - 10.0 * (1.0 - std::exp(-t[k]) * (std::cos(t[k]) - std::sin(t[k])))));
    ASSERT_EQ(mode[k], 0.0);
  }
  EXPECT_LT(worst, 1e-7 * 10);
}

// Claim: a torque-limited start. A reference step to ω_r = 100 rad/s at t = 0 commands
// K_p ω_r = 5000 N·m > M_max = 100 N·m, so the drive starts limited; the integral is held
// (clamping anti-windup), so ω(t) = M_max t / J exactly until K_p (ω_r − ω) + 0 = M_max, i.e.
// ω = ω_r − M_max/K_p = 98 rad/s at t₁ = 0.98 s, where the drive leaves the limit (one event). The
// source work then equals the kinetic energy gained (no losses): ½ J ω(t_end)².
TEST_P(DriveSim, SpeedDriveTorqueLimitedStartIsRampOfMmaxOverJ) {
  const Model m = model(R"(bodies:
  rotor: {inertia: 1 kg*m^2}
drives:
  S: {type: speed-drive, body: rotor, reference: 100 rad/s, gain: 50 N*m*s/rad, integral_time: 0.5 s, torque_limit: 100 N*m}
)", 3.0, 1e-3);
  const SimulationResult r = run(m);
  const auto& t = r.columns[0];
  const auto& w = r.columns[test::column(r, "rotor.velocity_rad_s")];
  const auto& M = r.columns[test::column(r, "S.torque_N_m")];
  double worst = 0;
  for (size_t k = 0; k < t.size() && t[k] < 0.98; ++k) {
    worst = std::max(worst, std::abs(w[k] - 100.0 * t[k]));
    ASSERT_EQ(M[k], 100.0);
  }
  EXPECT_LT(worst, 1e-9 * 100);
  std::vector<double> leave;
  for (const auto& e : r.hybrid.events)
    if (e.element == "S" && e.kind == "unlimited") leave.push_back(e.t);
  ASSERT_EQ(leave.size(), 1u);
  EXPECT_NEAR(leave[0], 0.98, 1e-10);
  // Afterwards linear from e(t₁) = 2, x_I = 0. With z = ∫_{t₁} e dτ: z'' + K_p z' + (K_p/T_i) z = 0
  // (J = 1), i.e. z'' + 50 z' + 100 z = 0, roots r₁,₂ = −25 ± √525, z(0) = 0, z'(0) = 2:
  // z = A (e^{r₁τ} − e^{r₂τ}), A = 2/(r₁ − r₂), and ω = ω_r − z'. The integral must return to 0 (no
  // load), so ω overshoots the reference a little — the clamping only keeps it from winding up.
  const double r1 = -25 + std::sqrt(525.0), r2 = -25 - std::sqrt(525.0), A = 2 / (r1 - r2);
  double worst_after = 0;
  for (size_t k = 0; k < t.size(); ++k) {
    if (t[k] <= 0.98) continue;
    const double tau = t[k] - 0.98;
    worst_after = std::max(worst_after, std::abs(w[k] - (100.0 - A * (r1 * std::exp(r1 * tau) - r2 * std::exp(r2 * tau)))));
  }
  EXPECT_LT(worst_after, 1e-7 * 100);
  if (std::get<1>(GetParam())) {
    const auto& E = r.hybrid.energy;
    EXPECT_NEAR(E.source_work, E.kinetic_end - E.kinetic_start, 1e-7 * E.source_work);
  }
}

// Claim: with a torque rise time T_m the limited start follows the lagged torque
// M(t) = M_max (1 − e^{−t/T_m}) (T_m M' = M_max − M, M(0) = 0), so
// ω(t) = (M_max/J)(t − T_m (1 − e^{−t/T_m})) while limited.
TEST_P(DriveSim, SpeedDriveTorqueRiseTimeLagsTheLimitedTorque) {
  const Model m = model(R"(bodies:
  rotor: {inertia: 2 kg*m^2}
drives:
  S: {type: speed-drive, body: rotor, reference: 100 rad/s, gain: 50 N*m*s/rad, integral_time: 0.5 s, torque_limit: 100 N*m, rise_time: 50 ms}
)", 1.0, 1e-3);
  const SimulationResult r = run(m);
  const auto& t = r.columns[0];
  const auto& w = r.columns[test::column(r, "rotor.velocity_rad_s")];
  const auto& M = r.columns[test::column(r, "S.torque_N_m")];
  double worst_w = 0, worst_M = 0;
  for (size_t k = 0; k < t.size(); ++k) {
    const double lag = 1.0 - std::exp(-t[k] / 0.05);
    worst_M = std::max(worst_M, std::abs(M[k] - 100.0 * lag));
    worst_w = std::max(worst_w, std::abs(w[k] - 50.0 * (t[k] - 0.05 * lag)));
  }
  EXPECT_LT(worst_M, 1e-7 * 100);
  EXPECT_LT(worst_w, 1e-7 * 50);
}

// Claim: integral action: under a constant load torque −60 N·m the drive settles at ω = ω_ref
// exactly (no steady-state error) with its torque equal to the load, however small K_p.
TEST_P(DriveSim, SpeedDriveReachesReferenceUnderConstantLoad) {
  const Model m = model(R"(bodies:
  rotor: {inertia: 0.5 kg*m^2}
loads:
  hoist: {type: constant, body: rotor, value: -60 N*m}
drives:
  S: {type: speed-drive, body: rotor, reference: {type: ramp, value: 20 rad/s, end: 0.5 s}, gain: 3 N*m*s/rad, integral_time: 0.2 s, torque_limit: 200 N*m}
)", 20.0, 1e-2);
  const SimulationResult r = run(m);
  const auto& w = r.columns[test::column(r, "rotor.velocity_rad_s")];
  const auto& M = r.columns[test::column(r, "S.torque_N_m")];
  // Linear 2nd order with ζ ω_n = K_p/(2J) = 3, decay e^{−3·19.5}: the transient is far below 1e-9.
  EXPECT_NEAR(w.back(), 20.0, 1e-7);
  EXPECT_NEAR(M.back(), 60.0, 1e-6);
}

// Claim: the quasi-static load of a link uses the drive's torque at the extreme's instant. A drive
// limited throughout (M = M_max = 100 N·m) on J1 = 1 kg·m², a spring to J2 = 3 kg·m²: rigid
// acceleration a = M/(J1 + J2), link load J2 a = 75 N·m (paper 002's eq. 22 form).
TEST_P(DriveSim, QuasiStaticLoadUsesTheDriveTorque) {
  const Model m = model(R"(bodies:
  J1: {inertia: 1 kg*m^2}
  J2: {inertia: 3 kg*m^2}
links:
  c: {type: spring, between: [J1, J2], stiffness: 1e4 N*m/rad}
drives:
  S: {type: speed-drive, body: J1, reference: 1e4 rad/s, gain: 50 N*m*s/rad, integral_time: 1 s, torque_limit: 100 N*m}
)", 0.5, 1e-3);
  const SimulationResult r = run(m);
  ASSERT_EQ(r.links.size(), 1u);
  EXPECT_NEAR(r.links[0].static_load, 75.0, 1e-9);
  EXPECT_NEAR(r.links[0].peak, 150.0, 1e-4);  // a step load on an undamped spring: twice the static
}

// Claim: the shipped example's inverter start ends in steady hoisting: the drive holds the speed at
// its reference 960 rpm (integral action against M_B), so the links carry the static loads of
// constant speed — c1 the load torque M_B = 270 N·m, c2 nothing — and the drive's torque is M_B.
// The smooth start keeps c1's dynamic factor below the direct start's.
TEST(DriveExample, InverterStartEndsInSteadyHoisting) {
  const Model m = load_model_case(test::example("drives.yaml"), {}, "inverter");
  const SimulationResult r = simulate(m);
  const double w_ref = 960 * 2 * M_PI / 60;
  EXPECT_NEAR(r.columns[test::column(r, "I1.velocity_rad_s")].back(), w_ref, 0.05);
  EXPECT_NEAR(r.columns[test::column(r, "c1.load_N_m")].back(), 270.0, 1.0);
  EXPECT_NEAR(r.columns[test::column(r, "c2.load_N_m")].back(), 0.0, 1.0);
  EXPECT_NEAR(r.columns[test::column(r, "drive.torque_N_m")].back(), 270.0, 1.0);
  const SimulationResult d = simulate(load_model_case(test::example("drives.yaml"), {}, "direct"));
  EXPECT_LT(r.links[0].dynamic_factor, d.links[0].dynamic_factor);
}

// ∂f/∂y against central differences of the drive system's own rhs, for every drive state and mode.
void expect_jacobian_matches_differences(DriveSystem& sys, double t, const std::vector<double>& y) {
  const int N = sys.size();
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(N, N), D(N, N);
  sys.jacobian(t, y.data(), J);
  D = test::central_difference_jacobian(sys, t, y);
  const double scale = std::max(1.0, J.cwiseAbs().maxCoeff());
  EXPECT_LT((J - D).cwiseAbs().maxCoeff(), 1e-6 * scale) << "J\n" << J << "\nD\n" << D;
}

// Claim: the analytic Jacobian terms of both drives (torque on the body, state rates) equal finite
// differences, in each limiter mode, with and without the torque lag.
TEST(DriveJacobian, DrivesMatchFiniteDifferences) {
  const Model m = compile_text(R"(bodies:
  J1: {inertia: 1.5 kg*m^2}
  J2: {inertia: 3 kg*m^2}
  J3: {inertia: 0.7 kg*m^2}
links:
  c: {type: spring-damper, between: [J1, J2], stiffness: 1e4 N*m/rad, damping: 20 N*m*s/rad}
  c2: {type: spring, between: [J2, J3], stiffness: 3e3 N*m/rad}
loads:
  fan: {type: drag, body: J2, coefficient: 0.3 N*m*s^2}
drives:
  M: {type: dc-motor, body: J3, resistance: 0.4 ohm, inductance: 8 mH, motor_constant: 1.7 N*m/A, voltage: {type: ramp, value: 400 V, end: 1 s}}
  S: {type: speed-drive, body: J1, reference: {type: ramp, value: 150 rad/s, end: 2 s}, gain: 40 N*m*s/rad, integral_time: 0.3 s, torque_limit: 500 N*m}
  L: {type: speed-drive, body: J2, reference: 30 rad/s, gain: 10 N*m*s/rad, integral_time: 0.8 s, torque_limit: 300 N*m, rise_time: 20 ms}
simulation: {t_end: 1 s}
)");
  DriveSystem sys(m, false);
  ASSERT_EQ(sys.size(), 2 * 3 + 1 + 1 + 2);
  EXPECT_EQ(sys.state_name(6), "drive 'M' (current)");
  EXPECT_EQ(sys.state_name(7), "drive 'S' (integral torque)");
  EXPECT_EQ(sys.state_name(9), "drive 'L' (torque)");
  std::vector<double> y(static_cast<size_t>(sys.size()));
  for (int i = 0; i < sys.size(); ++i) y[static_cast<size_t>(i)] = 3.0 * std::sin(1.7 * i + 0.4) + 0.5 * i;
  for (LimitMode md : {LimitMode::linear, LimitMode::limited_pos, LimitMode::limited_neg}) {
    SCOPED_TRACE(to_string(md));
    sys.set_drive_mode(1, static_cast<int>(md));
    sys.set_drive_mode(2, static_cast<int>(md));
    expect_jacobian_matches_differences(sys, 0.37, y);
  }
}

// Claim: linearized, a PI speed drive is a damper K_p and a spring K_p/T_i to the ground (about the
// reference motion), a DC motor its steady-state slope k²/R; the undamped natural frequency of the
// PI-controlled inertia is then √(K_p/(T_i J)) — for J = 1, K_p = 2, T_i = 1 the √2 rad/s whose
// damped response e^{−t}(cos t − sin t) the simulation above reproduces.
TEST(DriveLinear, PiDriveIsSpringAndDamperDcMotorIsDamper) {
  const Model m = compile_text(R"(bodies:
  rotor: {inertia: 1 kg*m^2}
  other: {inertia: 2 kg*m^2}
drives:
  S: {type: speed-drive, body: rotor, reference: 10 rad/s, gain: 2 N*m*s/rad, integral_time: 1 s}
  M: {type: dc-motor, body: other, resistance: 0.5 ohm, inductance: 1 mH, motor_constant: 2 N*m/A, voltage: 10 V}
)");
  const LinearModel lin = linearize(m, initial_topology(m));
  const Eigen::MatrixXd K(lin.stiffness()), D(lin.damping());
  EXPECT_DOUBLE_EQ(K(0, 0), 2.0);
  EXPECT_DOUBLE_EQ(D(0, 0), 2.0);
  EXPECT_DOUBLE_EQ(K(1, 1), 0.0);
  EXPECT_DOUBLE_EQ(D(1, 1), 8.0);  // k²/R = 4/0.5
  EXPECT_NEAR(std::sqrt(K(0, 0) / lin.M(0)), std::sqrt(2.0), 1e-15);
}

}  // namespace
}  // namespace machdyn
