// The eddy-current brake with its temperature (elements/eddy_current_brake.hpp, `type:
// thermal-eddy-current-brake` under `drives:`): MSL's Rotational and Translational EddyCurrentBrake
// examples against an independent RK4 of their two equations, on both integrators; the energy
// balance; the Jacobian against differences; the linear term; and a located error for every bad field.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>
#include <Eigen/Core>
#include <gtest/gtest.h>

#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/elements/linearize.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/jacobian.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::series;

/// MSL's EddyCurrentBrake, written here from its equations (not from the library's law): J = 1
/// (kg·m² or kg), ω(0) = 20, C = 1 J/K, T(0) = T_ref = 293.15 K, α = 3.92e-3 1/K (alpha20Copper),
/// w_nominal = 10, tau_nominal(t) a ramp 0 → 100 over [0.1, 0.2] s:
///   x = ω / (ω_n (1 + α (T − T_ref))),  τ = 2 τ_n(t) x / (1 + x²)   (MSL's tau: braking, flange.tau)
///   J ω' = −τ,   C T' = τ ω   (MSL's lossPower = tau w into the heat capacitor)
/// integrated by classical RK4 with h = 1e-5 s (the ramp's kinks at 0.1 and 0.2 s lie on the grid).
/// Rows every 1 ms: speed and temperature.
struct Reference {
  std::vector<double> omega, T;
};

Reference msl_reference() {
  const double J = 1.0, C = 1.0, Tref = 293.15, alpha = 3.92e-3, wn = 10.0;
  auto tau_n = [](double t) { return t <= 0.1 ? 0.0 : t >= 0.2 ? 100.0 : 1000.0 * (t - 0.1); };
  auto f = [&](double t, const double* s, double* ds) {
    const double x = s[0] / (wn * (1.0 + alpha * (s[1] - Tref)));
    const double tau = 2.0 * tau_n(t) * x / (1.0 + x * x);
    ds[0] = -tau / J;
    ds[1] = tau * s[0] / C;
  };
  Reference r;
  double s[2] = {20.0, Tref};
  const int per_row = 100, rows = 1000;
  const double h = 1e-5;
  r.omega.push_back(s[0]), r.T.push_back(s[1]);
  for (int k = 0; k < rows * per_row; ++k) {
    const double t = k * h;
    double k1[2], k2[2], k3[2], k4[2], y[2];
    f(t, s, k1);
    for (int i = 0; i < 2; ++i) y[i] = s[i] + 0.5 * h * k1[i];
    f(t + 0.5 * h, y, k2);
    for (int i = 0; i < 2; ++i) y[i] = s[i] + 0.5 * h * k2[i];
    f(t + 0.5 * h, y, k3);
    for (int i = 0; i < 2; ++i) y[i] = s[i] + h * k3[i];
    f(t + h, y, k4);
    for (int i = 0; i < 2; ++i) s[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
    if ((k + 1) % per_row == 0) r.omega.push_back(s[0]), r.T.push_back(s[1]);
  }
  return r;
}

const Reference& reference() {
  static const Reference r = msl_reference();
  return r;
}

class EddyBrake : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, EddyBrake, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

/// Runs a shipped example on the test's integrator and compares its speed and temperature columns
/// with the RK4 at every 1 ms row; returns the result for further checks.
SimulationResult run_and_compare(const std::string& example, const std::string& speed_column, IntegratorChoice integ) {
  Model m = load_model(test::example(example));
  m.simulation.integrator = integ;
  const SimulationResult r = simulate(m);
  const auto &t = series(r, "t_s"), &w = series(r, speed_column), &T = series(r, "brake.temperature_degC");
  const Reference& ref = reference();
  EXPECT_EQ(t.size(), ref.omega.size());
  const bool bdf = m.simulation.integrator == IntegratorChoice::bdf;
  double dw = 0.0, dT = 0.0;
  for (size_t k = 0; k < std::min(t.size(), ref.omega.size()); ++k) {
    EXPECT_NEAR(t[k], 1e-3 * static_cast<double>(k), 1e-12);
    dw = std::max(dw, std::abs(w[k] - ref.omega[k]));
    dT = std::max(dT, std::abs(T[k] + 273.15 - ref.T[k]));
  }
  EXPECT_LT(dw, bdf ? 1e-6 : 1e-7) << "speed, largest deviation from the RK4";
  EXPECT_LT(dT, bdf ? 1e-5 : 1e-6) << "temperature, largest deviation from the RK4, K";
  return r;
}

// Claim: the rotational example (J = 1 kg·m², 20 rad/s, M_k ramp to 100 N·m, ω_k = 10 rad/s at
// 20 °C, α = 3.92e-3 1/K, C = 1 J/K) follows MSL's equations: its speed and its temperature (near
// 500 K) agree with the RK4 at every 1 ms row within 1e-7 rad/s and 1e-6 K (dopri5), 1e-6 rad/s and
// 1e-5 K (bdf). The brake takes most of the
// kinetic energy (½·1·20² = 200 J): the disc warms by well over 100 K, and ω_k(T) grows with it.
TEST_P(EddyBrake, RotationalExampleFollowsTheRk4OfMslsEquations) {
  const SimulationResult r = run_and_compare("msl/eddy-current-brake.yaml", "inertia.velocity_rad_s", GetParam());
  const auto& T = series(r, "brake.temperature_degC");
  EXPECT_NEAR(T.front(), 20.0, 1e-12);
  EXPECT_GT(T.back() - T.front(), 100.0);
}

// Claim: the translational example (a 1 kg mass at 20 m/s, the same numbers in N and m/s) is the
// same element on a translational body: the same RK4, the same tolerances.
TEST_P(EddyBrake, TranslationalExampleFollowsTheRk4OfMslsEquations) {
  run_and_compare("msl/eddy-current-brake-translational.yaml", "mass.velocity_m_s", GetParam());
}

// Claim: the brake is adiabatic, so the kinetic energy lost, ½ J (ω0² − ω²), is the heat stored,
// C (T − T0), at every row (within 1e-6 J of the 200 J on dopri5, 1e-5 J on bdf: each state is
// integrated to its own tolerance); and the heat power column is −M ω, the
// product of the torque and speed columns.
TEST_P(EddyBrake, KineticEnergyLostIsHeatStored) {
  Model m = load_model(test::example("msl/eddy-current-brake.yaml"));
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const auto &w = series(r, "inertia.velocity_rad_s"), &T = series(r, "brake.temperature_degC");
  const auto &M = series(r, "brake.torque_N_m"), &P = series(r, "brake.heat_power_W");
  ASSERT_EQ(w.size(), 1001u);
  double worst = 0.0, worst_p = 0.0;
  for (size_t k = 0; k < w.size(); ++k) {
    worst = std::max(worst, std::abs(0.5 * (400.0 - w[k] * w[k]) - 1.0 * (T[k] - 20.0)));
    worst_p = std::max(worst_p, std::abs(P[k] + M[k] * w[k]));
  }
  EXPECT_LT(worst, GetParam() == IntegratorChoice::bdf ? 1e-5 : 1e-6) << "J";
  EXPECT_LT(worst_p, 1e-9) << "W";
  EXPECT_GT(0.5 * (400.0 - w.back() * w.back()), 150.0);  // most of the 200 J went into heat
}

// Claim: in the energy books of an event-driven run the brake's heat is a damping loss, not source
// work: the loss is the heat stored, C (T_end − T0), within 1e-5 J, the source work is 0 within
// 1e-9 J, and the balance closes (residual below 1e-5 J of the 200 J).
TEST_P(EddyBrake, EnergyBooksCountTheHeatAsALoss) {
  Model m = load_model(test::example("msl/eddy-current-brake.yaml"));
  m.simulation.integrator = GetParam();
  SimulateOptions o;
  o.event_driven = true;
  const SimulationResult r = simulate(m, o);
  const auto& T = series(r, "brake.temperature_degC");
  const EnergyBalance& e = r.hybrid.energy;
  EXPECT_NEAR(e.damping_loss, 1.0 * (T.back() - T.front()), 1e-5);
  EXPECT_NEAR(e.source_work, 0.0, 1e-9);
  EXPECT_LT(std::abs(e.residual()), 1e-5);
  EXPECT_GT(e.damping_loss, 150.0);
}

// Claim: the analytic Jacobian terms (∂M/∂ω, ∂M/∂T through ω_k(T), ∂T'/∂ω, ∂T'/∂T) equal central
// differences of the right-hand side, on a rotor and on a mass, above and below the breakdown speed.
TEST(EddyBrakeJacobian, MatchesFiniteDifferences) {
  const Model m = test::model_text(R"(bodies:
  R: {inertia: 2 kg*m^2}
  X: {type: translational, mass: 3 kg}
drives:
  a: {type: thermal-eddy-current-brake, body: R, breakdown_torque: {type: ramp, value: 80 N*m, end: 1 s}, breakdown_speed: 12 rad/s, temperature_coefficient: 0.004 1/K, heat_capacity: 5 J/K, initial_temperature: 60 degC}
  b: {type: thermal-eddy-current-brake, body: X, breakdown_torque: 30 N, breakdown_speed: 2 m/s, temperature_coefficient: 0.02 1/K, reference_temperature: 0 degC, heat_capacity: 0.5 J/K}
simulation: {t_end: 1 s}
)",
                                       "jac.yaml");
  DriveSystem sys(m, false);
  ASSERT_EQ(sys.size(), 2 * 2 + 2);
  EXPECT_EQ(sys.state_name(4), "drive 'a' (temperature)");
  for (const std::vector<double>& y : {std::vector<double>{0.3, -0.2, 17.0, 0.7, 340.0, 300.0},
                                       std::vector<double>{0.3, -0.2, -5.0, -4.1, 400.0, 280.0}}) {
    const int N = sys.size();
    Eigen::MatrixXd J = Eigen::MatrixXd::Zero(N, N);
    sys.jacobian(0.6, y.data(), J);
    const Eigen::MatrixXd D = test::central_difference_jacobian(sys, 0.6, y);
    const double scale = std::max(1.0, J.cwiseAbs().maxCoeff());
    EXPECT_LT((J - D).cwiseAbs().maxCoeff(), 1e-6 * scale) << "J\n" << J << "\nD\n" << D;
    EXPECT_NE(J(2, 4), 0.0);  // the temperature acts on the torque (α ≠ 0)
  }
}

// Claim: linearized at rest the brake is a damper to the ground with its slope at ω = 0,
// dM/dω = −2 M_k / ω_k(T0): M_k = 40 N·m, ω_k = 10 rad/s (1 + 0.005·(30 − 20)) = 10.5 rad/s → 80/10.5.
TEST(EddyBrakeLinear, IsTheSlopeAtRestAsADamper) {
  const Model m = test::model_text(R"(bodies:
  R: {inertia: 2 kg*m^2}
drives:
  b: {type: thermal-eddy-current-brake, body: R, breakdown_torque: 40 N*m, breakdown_speed: 10 rad/s, temperature_coefficient: 0.005 1/K, heat_capacity: 5 J/K, initial_temperature: 30 degC}
)",
                                       "lin.yaml");
  const LinearModel lin = linearize(m, initial_topology(m));
  EXPECT_NEAR(Eigen::MatrixXd(lin.damping())(0, 0), 80.0 / 10.5, 1e-12);
  EXPECT_DOUBLE_EQ(Eigen::MatrixXd(lin.stiffness())(0, 0), 0.0);
}

/// The compile errors of one brake with `fields` on the rotor R.
std::string errors_of(const std::string& fields) {
  return test::compile_errors("bodies:\n  R: {inertia: 1}\ndrives:\n  b: {type: thermal-eddy-current-brake, body: R, " +
                                  fields + "}\n",
                              "bad.yaml");
}

// Claim: every bad field of the brake is an error at its place (file:line:col) naming the field.
TEST(EddyBrakeCompile, BadFieldsAreLocated) {
  const std::string ok = "breakdown_torque: 10 N*m, breakdown_speed: 5 rad/s, heat_capacity: 2 J/K";
  EXPECT_EQ(errors_of(ok), "");
  struct Case {
    std::string fields, want;
  };
  const Case cases[] = {
      {"breakdown_torque: -10 N*m, breakdown_speed: 5 rad/s, heat_capacity: 2 J/K",
       "bad.yaml:4:68: error: drive 'b': field 'breakdown_torque' must not be negative, got -10"},
      {"breakdown_torque: 10 N, breakdown_speed: 5 rad/s, heat_capacity: 2 J/K",
       "bad.yaml:4:68: error: drive 'b': field 'breakdown_torque': expected a torque (N*m)"},
      {"breakdown_speed: 5 rad/s, heat_capacity: 2 J/K", "bad.yaml:4:6: error: drive 'b': missing field 'breakdown_torque'"},
      {"breakdown_torque: 10 N*m, breakdown_speed: 0 rad/s, heat_capacity: 2 J/K",
       "bad.yaml:4:93: error: drive 'b': field 'breakdown_speed' must be positive, got 0"},
      {"breakdown_torque: 10 N*m, breakdown_speed: 5 rad/s, heat_capacity: 2 W/K",
       "bad.yaml:4:117: error: drive 'b': field 'heat_capacity': expected a heat capacity (J/K)"},
      {"breakdown_torque: 10 N*m, breakdown_speed: 5 rad/s", "bad.yaml:4:6: error: drive 'b': missing field 'heat_capacity'"},
      {ok + ", temperature_coefficient: -0.004 1/K",
       "bad.yaml:4:149: error: drive 'b': field 'temperature_coefficient' must be zero or positive, got -0.004"},
      {ok + ", reference_temperature: 20",
       "bad.yaml:4:147: error: drive 'b': field 'reference_temperature': expected a temperature with its unit"},
      {ok + ", initial_temperature: -300 degC",
       "bad.yaml:4:145: error: drive 'b': field 'initial_temperature': '-300 degC' is below absolute zero"},
      {ok + ", temperature_coefficient: 0.01 1/K, initial_temperature: -200 degC",
       "bad.yaml:4:180: error: drive 'b': field 'initial_temperature' (73.15 K) is so far below the reference temperature "
       "that the resistance 1 + α (T0 − T_ref) = -1.2 is not positive"},
      {ok + ", conductance: 2 W/K", "bad.yaml:4:124: error: drive 'b': unknown field 'conductance'"},
  };
  for (const Case& c : cases) {
    const std::string got = errors_of(c.fields);
    EXPECT_NE(got.find(c.want), std::string::npos) << c.fields << "\n--- want: " << c.want << "\n--- got:\n" << got;
    EXPECT_EQ(std::count(got.begin(), got.end(), '\n'), 0) << got;  // that one problem only
  }
}

// Claim: the type is known to the section hints through its registration (under `loads:` it is
// pointed to `drives:`), and through the CLI a bad brake exits 2 and writes nothing.
TEST(EddyBrakeCompile, WrongSectionHintAndCliExitsTwo) {
  EXPECT_NE(test::compile_errors("bodies:\n  R: {inertia: 1}\nloads:\n  b: {type: thermal-eddy-current-brake, body: R}\n",
                                 "hint.yaml")
                .find("hint.yaml:4:13: error: load 'b': type 'thermal-eddy-current-brake' is not a kind of loads; a "
                      "thermal-eddy-current-brake goes under 'drives:'"),
            std::string::npos);
  const auto path = test::write_temp("bad-brake-cli.yaml",
                                     "bodies:\n  R: {inertia: 1}\ndrives:\n  b: {type: thermal-eddy-current-brake, body: R, "
                                     "breakdown_torque: 10 N*m, breakdown_speed: -5 rad/s, heat_capacity: 2 J/K}\n");
  const auto out = test::temp_dir() / "bad-brake-out";
  const auto r = test::run_cli("simulate '" + path + "' -o '" + out.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad-brake-cli.yaml:4:93: error: drive 'b': field 'breakdown_speed' must be positive, got -5"),
            std::string::npos)
      << r.err;
  EXPECT_FALSE(std::filesystem::exists(out / "timeseries.csv"));
}

}  // namespace
}  // namespace machdyn
