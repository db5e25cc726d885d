// The optional output columns (analysis/extra_outputs.hpp) against closed forms, finite differences
// and the energy books: deflection and its rate, body accelerations, load and drive power, heat of
// the friction elements. Event-driven cases run on both integrators.
#include "machdyn/analysis/extra_outputs.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::series;

Model model_of(const std::string& yaml) { return compile_model(parse_yaml_string(yaml, "xo.yaml"), "xo.yaml"); }

OutputSelection all_outputs() { return output_selection({"all"}); }

// Claim: in the free two-mass oscillator (I_a = 2, I_b = 1 kg·m², c = 100 N·m/rad; a starts at
// v0 = 3 rad/s, b at rest, both at q = 0) the relative coordinate δ = q_a − q_b obeys
// δ'' = −c (1/I_a + 1/I_b) δ, so δ = (v0/Ω) sin Ωt, δ̇ = v0 cos Ωt, Ω² = c (1/I_a + 1/I_b) = 150 s⁻².
// The accelerations are F/I: a_b = c δ / I_b, a_a = −c δ / I_a; the deflection is load / c; the
// acceleration column agrees with a central difference of the velocity column (error h² v'''/6).
TEST(ExtraOutputs, TwoMassOscillatorAccelerationDeflection) {
  Model m = model_of(R"(
bodies: {a: {inertia: 2, velocity: 3 rad/s}, b: {inertia: 1}}
links: {s: {type: spring, between: [a, b], stiffness: 100 N*m/rad}}
simulation: {t_end: 1 s, dt_out: 0.0001 s, rtol: 1e-12, atol: 1e-14}
)");
  const SimulationResult r = simulate(m, SimulateOptions{}, all_outputs());
  const double v0 = 3.0, W = std::sqrt(150.0);
  const auto& t = series(r, "t_s");
  const auto &d = series(r, "s.deflection_rad"), &dr = series(r, "s.deflection_rate_rad_s"), &F = series(r, "s.load_N_m");
  const auto &aa = series(r, "a.acceleration_rad_s2"), &ab = series(r, "b.acceleration_rad_s2");
  const auto& vb = series(r, "b.velocity_rad_s");
  ASSERT_EQ(t.size(), 10001u);
  double fd_err = 0.0, fd_scale = 0.0;
  for (size_t k = 1; k + 1 < t.size(); ++k) {
    const double delta = v0 / W * std::sin(W * t[k]);
    EXPECT_NEAR(d[k], delta, 1e-9);
    EXPECT_NEAR(dr[k], v0 * std::cos(W * t[k]), 1e-8);
    EXPECT_NEAR(d[k] * 100.0, F[k], 1e-12 * std::abs(F[k]) + 1e-14);  // deflection = load / c
    EXPECT_NEAR(ab[k], 100.0 * delta, 1e-7);
    EXPECT_NEAR(aa[k], -100.0 * delta / 2.0, 1e-7);
    const double fd = (vb[k + 1] - vb[k - 1]) / (t[k + 1] - t[k - 1]);
    fd_err = std::max(fd_err, std::abs(fd - ab[k]));
    fd_scale = std::max(fd_scale, std::abs(ab[k]));
  }
  // |v'''| ≤ a_max Ω², h = 1e-4 s: the central difference is within a_max Ω² h² / 6 = 2.5e-7 a_max.
  EXPECT_LT(fd_err, 3e-7 * fd_scale);
  EXPECT_GT(fd_err, 0.0);  // a difference, not the same numbers
}

// Claim: a brake of constant braking torque M_b = 8 N·m stops a flywheel (I = 2 kg·m², ω0 = 10 rad/s)
// at t_s = I ω0 / M_b = 2.5 s; it turns all the kinetic energy into heat: Q(t_end) = ½ I ω0² = 100 J.
// While it slides, P = M_b ω = 8 (10 − 4 t) W and Q(t) = 8 (10 t − 2 t²) J; stuck, P = 0. The heat
// column equals the energy books' friction loss, on both integrators.
class ExtraOutputsIntegrators : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, ExtraOutputsIntegrators,
                         ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

TEST_P(ExtraOutputsIntegrators, BrakeHeatIsTheFlywheelsKineticEnergy) {
  Model m = model_of(R"(
bodies: {w: {inertia: 2, velocity: 10 rad/s}}
brakes: {B: {body: w, holding: 10 N*m, braking: 8 N*m}}
simulation: {t_end: 3 s, dt_out: 0.01 s, rtol: 1e-10, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m, SimulateOptions{}, output_selection({"heat", "acceleration"}));
  const auto &t = series(r, "t_s"), &Q = series(r, "B.heat_J"), &P = series(r, "B.heat_power_W");
  const auto& a = series(r, "w.acceleration_rad_s2");
  const double Q_end = 0.5 * 2.0 * 10.0 * 10.0;
  EXPECT_NEAR(Q.back(), Q_end, 1e-9 * Q_end);
  EXPECT_NEAR(Q.back(), r.hybrid.energy.friction_loss, 1e-9 * Q_end);
  for (size_t k = 0; k < t.size(); ++k) {
    if (t[k] < 2.49) {
      EXPECT_NEAR(P[k], 8.0 * (10.0 - 4.0 * t[k]), 1e-7) << t[k];
      EXPECT_NEAR(Q[k], 8.0 * (10.0 * t[k] - 2.0 * t[k] * t[k]), 1e-7) << t[k];
      EXPECT_NEAR(a[k], -4.0, 1e-12) << t[k];  // −M_b / I while sliding
    } else if (t[k] > 2.51) {
      EXPECT_EQ(P[k], 0.0) << t[k];
      EXPECT_EQ(a[k], 0.0) << t[k];  // held by the brake, no load
      EXPECT_NEAR(Q[k], Q_end, 1e-9 * Q_end) << t[k];
    }
  }
}

// Claim: a motor with the linear characteristic M = M_s (1 − ω/ω0) (M_s = 10 N·m, ω0 = 100 rad/s)
// accelerating a flywheel I = 1 kg·m² from rest, against a viscous spring–damper to the ground that
// is slack (c = 0 is not allowed, so a damper d = 0.5 N·m·s/rad): the input work ∫ M ω dt (Simpson
// on the power column) equals the energy books' source work, and ∫ d δ̇² dt their damping loss.
TEST_P(ExtraOutputsIntegrators, MotorPowerIntegratesToTheInputWork) {
  Model m = model_of(R"(
bodies: {w: {inertia: 1}}
links: {d: {type: damper, between: [w, ground], damping: 0.5 N*m*s/rad}}
loads: {M: {type: motor-linear, body: w, stall_torque: 10 N*m, no_load_speed: 100 rad/s}}
simulation: {t_end: 2 s, dt_out: 0.001 s, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  SimulateOptions books;
  books.event_driven = true;
  const SimulationResult r = simulate(m, books, output_selection({"power"}));
  const auto &P = series(r, "M.power_W"), &Pd = series(r, "d.damping_power_W"), &w = series(r, "w.velocity_rad_s");
  const auto& t = series(r, "t_s");
  ASSERT_EQ(t.size() % 2, 1u);  // an even number of intervals for Simpson's rule
  auto simpson = [&](const std::vector<double>& f) {
    double s = f.front() + f.back();
    for (size_t k = 1; k + 1 < f.size(); ++k) s += (k % 2 ? 4.0 : 2.0) * f[k];
    return s * (t[1] - t[0]) / 3.0;
  };
  // Closed form: ω' = (M_s − (M_s/ω0 + d) ω)/I, ω = ω∞ (1 − e^{−t/τ}), τ = I/(M_s/ω0 + d) = 1/0.6 s.
  const double tau = 1.0 / 0.6, w_inf = 10.0 * tau;
  for (size_t k = 0; k < t.size(); k += 100) {
    const double om = w_inf * (1.0 - std::exp(-t[k] / tau));
    EXPECT_NEAR(w[k], om, 1e-8);
    EXPECT_NEAR(P[k], 10.0 * (1.0 - om / 100.0) * om, 1e-6);
    EXPECT_NEAR(Pd[k], 0.5 * om * om, 1e-6);
  }
  const double W = simpson(P), D = simpson(Pd);
  EXPECT_NEAR(W, r.hybrid.energy.source_work, 1e-8 * W);
  EXPECT_NEAR(D, r.hybrid.energy.damping_loss, 1e-8 * D);
  EXPECT_NEAR(W - D, 0.5 * w.back() * w.back(), 1e-8 * W);  // what is left is kinetic energy
}

// Claim: the extra columns leave the standard ones untouched (the same run), and none is written
// without a selection.
TEST(ExtraOutputs, StandardColumnsAreTheSame) {
  Model m = model_of(R"(
bodies: {a: {inertia: 2, velocity: 3 rad/s}, b: {inertia: 1}}
links: {s: {type: spring-damper, between: [a, b], stiffness: 100 N*m/rad, damping: 1 N*m*s/rad}}
brakes: {B: {body: b, holding: 50 N*m, braking: 40 N*m}}
simulation: {t_end: 1 s, dt_out: 0.01 s}
)");
  const SimulationResult plain = simulate(m), extra = simulate(m, SimulateOptions{}, all_outputs());
  ASSERT_GT(extra.column_names.size(), plain.column_names.size());
  for (size_t c = 0; c < plain.column_names.size(); ++c) {
    EXPECT_EQ(plain.column_names[c], extra.column_names[c]);
    EXPECT_EQ(plain.columns[c], extra.columns[c]) << plain.column_names[c];
  }
  for (const char* n : {"s.deflection_rad", "s.deflection_rate_rad_s", "a.acceleration_rad_s2", "s.damping_power_W",
                        "B.heat_power_W", "B.heat_J"})
    EXPECT_NE(std::find(extra.column_names.begin(), extra.column_names.end(), n), extra.column_names.end()) << n;
}

// Claim: with every group on, a model with a machine (crank-slider with a brake) has each column
// name once: a machine body's acceleration is its machine column (the same right-hand side).
TEST(ExtraOutputs, ColumnNamesAreUniqueWithMachines) {
  const Model m = load_model(test::example("crank-slider-brake.yaml"));
  const SimulationResult r = simulate(m, SimulateOptions{}, all_outputs());
  std::vector<std::string> names = r.column_names;
  std::sort(names.begin(), names.end());
  EXPECT_EQ(std::adjacent_find(names.begin(), names.end()), names.end());
  EXPECT_EQ(r.columns.size(), r.column_names.size());
  for (const auto& c : r.columns) EXPECT_EQ(c.size(), r.columns[0].size());
}

// Claim: in the shipped models with friction elements (MSL CoupledClutches: three clutches; a brake;
// a one-way clutch; the travel start's wheel–rail contacts and brake; a crank-slider with a brake)
// the heat columns at t_end add up to the energy books' friction loss, a second quadrature of the
// same ∫ F u dt carried as a state by the integrator. Measured: within 2e-11 relative.
TEST(ExtraOutputs, HeatAddsUpToTheFrictionLossOfTheBooks) {
  for (const char* name : {"msl/coupled-clutches.yaml", "msl/brake.yaml", "msl/one-way-clutch.yaml", "travel-start.yaml",
                           "crank-slider-brake.yaml"}) {
    const Model m = load_model(test::example(name));
    const SimulationResult r = simulate(m, SimulateOptions{}, output_selection({"heat"}));
    double Q = 0.0;  // the friction elements' columns (links with dampers have theirs too)
    for (const auto& c : m.contacts)
      if (!c.joint) Q += series(r, c.name + ".heat_J").back();
    const double E = r.hybrid.energy.friction_loss;
    ASSERT_GT(E, 0.0) << name;
    EXPECT_NEAR(Q, E, 1e-9 * E) << name;
  }
}

// Claim: an unknown group is a located input error; the CLI writes the columns with --outputs and
// exits non-zero on a bad name.
TEST(ExtraOutputs, SelectionAndCli) {
  EXPECT_THROW(output_selection({"heat", "temperature"}), InputError);
  const auto s = output_selection({"deflection", "heat"});
  EXPECT_TRUE(s.deflection && s.heat && !s.power && !s.acceleration);
  const std::string path = test::write_temp("xo.yaml", R"(
bodies: {w: {inertia: 2, velocity: 10 rad/s}}
brakes: {B: {body: w, holding: 10 N*m, braking: 8 N*m}}
simulation: {t_end: 3 s, dt_out: 0.1 s}
)");
  const auto ok = test::run_cli("simulate " + path + " -q -o xo_out --outputs heat,acceleration");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  const std::string csv = test::slurp(test::temp_dir() / "xo_out" / "timeseries.csv");
  const std::string header = test::lines_of(csv).at(0);
  EXPECT_NE(header.find("B.heat_J"), std::string::npos) << header;
  EXPECT_NE(header.find(",heat_power_W,heat_J"), std::string::npos) << header;  // the model's total
  const std::string summary = test::slurp(test::temp_dir() / "xo_out" / "summary.json");
  EXPECT_NE(summary.find("\"dissipated_J\""), std::string::npos);
  EXPECT_NE(header.find("w.acceleration_rad_s2"), std::string::npos) << header;
  const auto plain = test::run_cli("simulate " + path + " -q -o xo_plain");
  ASSERT_EQ(plain.exit_code, 0) << plain.err;
  EXPECT_EQ(test::slurp(test::temp_dir() / "xo_plain" / "timeseries.csv").find("heat"), std::string::npos);
  const auto bad = test::run_cli("simulate " + path + " -q -o xo_bad --outputs temperature");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("temperature"), std::string::npos) << bad.err;
}

// Claim: the extra columns count against the memory limit of the output grid. One body on a spring
// with 5·10^7 output rows has 4 standard columns (t, q, v, load): 1.6 GB, under the 2 GiB limit, so
// the model compiles; all groups add 8 more (δ, δ̇, acceleration, damping power, heat power and heat
// of the spring-damper, the model's total heat power and heat) = 4.8 GB: an input error at `--outputs` before anything is allocated (the test would need 3 GB).
TEST(ExtraOutputs, WiderGridIsCheckedAgainstTheMemoryLimit) {
  const Model m = model_of(R"(
bodies: {w: {inertia: 2}}
links: {k: {type: spring-damper, between: [w, ground], stiffness: 100, damping: 1}}
simulation: {t_end: 50 s, dt_out: 1 us}
)");
  ASSERT_LT(output_bytes_bound(m), kMaxOutputBytes);
  EXPECT_EQ(extra_columns_bound(m, all_outputs()), 8u);
  try {
    (void)simulate(m, SimulateOptions{}, all_outputs());
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("GB"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace machdyn
