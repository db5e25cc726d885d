// The heat of every dissipative element (`--outputs heat`, analysis/heat.hpp): closed forms for a
// damper and a stop impact, the energy books of shipped models, and examples/msl/heat-losses-
// translational.yaml (MSL Translational.Examples.HeatLosses) against an independent RK4 of MSL's
// equations written here. Every case runs on both integrators.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/analysis/extra_outputs.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/results.hpp"
#include "support/rk4.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::sci;
using test::series;

class HeatLosses : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, HeatLosses, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

SimulationResult run_heat(Model m, IntegratorChoice integrator) {
  m.simulation.integrator = integrator;
  SimulateOptions books;
  books.event_driven = true;  // the energy books too
  return simulate(m, books, output_selection({"heat"}));
}

bool has_column(const SimulationResult& r, const std::string& name) {
  return std::find(r.column_names.begin(), r.column_names.end(), name) != r.column_names.end();
}

// Claim: a damper to the ground (d = 4 N·m·s/rad) stopping a flywheel (I = 2 kg·m², ω0 = 10 rad/s):
// I ω' = −d ω gives ω = ω0 e^{−t/τ}, τ = I/d = 0.5 s, so the damper's heat power is P = d ω² and its
// heat Q = ½ I ω0² (1 − e^{−2t/τ}) (all the kinetic energy lost); the model's total is the damper's.
// An undamped spring has no heat columns.
TEST_P(HeatLosses, DamperHeatFollowsTheClosedForm) {
  const Model m = test::model_text(R"(
bodies: {w: {inertia: 2, velocity: 10 rad/s}, v: {inertia: 1}}
links:
  d: {type: damper, between: [w, ground], damping: 4 N*m*s/rad}
  s: {type: spring, between: [v, ground], stiffness: 100 N*m/rad}
simulation: {t_end: 2 s, dt_out: 0.01 s, rtol: 1e-11, atol: 1e-12}
)");
  const SimulationResult r = run_heat(m, GetParam());
  EXPECT_FALSE(has_column(r, "s.heat_J"));
  const double tau = 0.5, E0 = 0.5 * 2 * 100;
  const double eP = test::max_error(r, "d.heat_power_W", [&](double t) { return 4 * 100 * std::exp(-2 * t / tau); });
  const double eQ = test::max_error(r, "d.heat_J", [&](double t) { return E0 * (1 - std::exp(-2 * t / tau)); });
  const double eT = test::max_error(r, "heat_J", [&](double t) { return E0 * (1 - std::exp(-2 * t / tau)); });
  EXPECT_LT(eP, 1e-6);
  EXPECT_LT(eQ, 1e-7);
  EXPECT_LT(eT, 1e-7);
  EXPECT_NEAR(series(r, "heat_J").back(), r.hybrid.energy.damping_loss, 1e-9 * E0);
}

// Claim: a mass (1 kg) gliding at v0 = 2 m/s into a stop at 0.5 m with restitution e = 0.5 loses
// ½ m v0² (1 − e²) = 1.5 J at the impact (t = 0.25 s, a jump of the stop's heat); the heat power of a
// stop is 0 (no friction), the heat 0 before the impact and 1.5 J after, the energy books' impact loss.
TEST_P(HeatLosses, StopImpactLossIsTheStopsHeat) {
  const Model m = test::model_text(R"(
bodies: {x: {type: translational, mass: 1 kg, velocity: 2 m/s}}
stops: {S: {body: x, max: 0.5 m, restitution: 0.5}}
simulation: {t_end: 0.5 s, dt_out: 0.01 s, rtol: 1e-11, atol: 1e-12}
)");
  const SimulationResult r = run_heat(m, GetParam());
  const auto &t = series(r, "t_s"), &Q = series(r, "S.heat_J"), &P = series(r, "S.heat_power_W"), &Qt = series(r, "heat_J");
  ASSERT_EQ(t.size(), 51u);
  for (size_t k = 0; k < t.size(); ++k) {
    const double expect = t[k] < 0.25 - 1e-9 ? 0.0 : t[k] > 0.25 + 1e-9 ? 1.5 : NAN;
    if (std::isnan(expect)) continue;
    EXPECT_NEAR(Q[k], expect, 1e-9) << t[k];
    EXPECT_NEAR(Qt[k], expect, 1e-9) << t[k];
    EXPECT_EQ(std::abs(P[k]), 0.0) << t[k];
  }
  EXPECT_NEAR(r.hybrid.energy.impact_loss, 1.5, 1e-9);
}

// Claim: in shipped models with every kind of dissipative element — friction contacts, brakes,
// clutches, freewheels and stops with impacts (MSL Friction, CoupledClutches, OneWayClutch, the
// translational HeatLosses), dampers and gaps whose flanks open off the flank (MSL Backlash,
// ElastoGap: the gap release loss), lossy gears (MSL LossyGearDemo1, and the Rotational HeatLosses
// with a clutch on a gear's massless flange) — the heat of the links
// adds up to the energy books' damping and gap release losses, that of the friction elements and
// lossy gears to their friction and impact losses, and the total column to their sum and to
// W − ΔT − ΔV: each a second quadrature (Gauss–Legendre on the dense output against the books'
// states carried by the integrator).
TEST_P(HeatLosses, HeatAddsUpToTheLossesOfTheBooks) {
  for (const char* name : {"msl/friction.yaml", "msl/coupled-clutches.yaml", "msl/one-way-clutch.yaml",
                           "msl/heat-losses-translational.yaml", "msl/backlash.yaml", "msl/elasto-gap.yaml",
                           "msl/lossy-gear-demo1.yaml", "msl/heat-losses.yaml"}) {
    const Model m = load_model(test::example(name));
    const SimulationResult r = run_heat(m, GetParam());
    double links = 0, friction = 0;
    for (const auto& l : m.links)
      if (has_column(r, l.name + ".heat_J")) links += series(r, l.name + ".heat_J").back();
    for (const auto& c : m.contacts)
      if (has_column(r, c.name + ".heat_J")) friction += series(r, c.name + ".heat_J").back();
    for (const auto& g : m.lossy_gears) friction += series(r, g.name + ".heat_J").back();
    const EnergyBalance& E = r.hybrid.energy;
    const double total = series(r, "heat_J").back();
    const double scale = std::max(1.0, total), tol = GetParam() == IntegratorChoice::dopri5 ? 1e-8 : 1e-6;
    ASSERT_GT(total, 0.0) << name;
    EXPECT_NEAR(links, E.damping_loss + E.release_loss, tol * scale) << name;
    EXPECT_NEAR(friction, E.friction_loss + E.impact_loss, tol * scale) << name;
    EXPECT_NEAR(total, links + friction, 1e-12 * scale) << name;
    const double dissipated = E.source_work - (E.kinetic_end - E.kinetic_start) - (E.elastic_end - E.elastic_start) -
                              E.released_kinetic;
    EXPECT_NEAR(total, dissipated, tol * scale) << name;
  }
}

/// The books' dissipated energy, as summary.json's `energy.dissipated_J` (io/results.cpp) sums it.
double dissipated(const EnergyBalance& E) { return E.friction_loss + E.damping_loss + E.release_loss + E.impact_loss; }

// Claim: the thermal eddy-current brake (examples/msl/eddy-current-brake.yaml: J = 1 kg·m², ω0 =
// 20 rad/s, C = 1 J/K, adiabatic) is one of the heat group's elements. Its heat is the kinetic energy
// it took, brake.heat_J = ½ J (ω0² − ω²), and the heat its disc stores, C (T − T0), at every 1 ms row
// (within 1e-6 J of 200 J on dopri5, 1e-5 J on bdf: ω, T and the heat are integrated separately); the
// model's total heat_J is the brake's; at t_end it is the books' dissipated energy (source work − ΔT,
// within 1e-5 J) and summary.json's `dissipated_J`. Its heat power stays its own column, written once.
TEST_P(HeatLosses, EddyCurrentBrakeHeatIsInTheHeatGroupAndTheTotal) {
  const SimulationResult r = run_heat(load_model(test::example("msl/eddy-current-brake.yaml")), GetParam());
  EXPECT_EQ(std::count(r.column_names.begin(), r.column_names.end(), "brake.heat_power_W"), 1);
  const auto &w = series(r, "inertia.velocity_rad_s"), &T = series(r, "brake.temperature_degC");
  const auto &Q = series(r, "brake.heat_J"), &Qt = series(r, "heat_J");
  const auto &P = series(r, "brake.heat_power_W"), &Pt = series(r, "heat_power_W");
  ASSERT_EQ(Q.size(), 1001u);
  const double tol = GetParam() == IntegratorChoice::bdf ? 1e-5 : 1e-6;
  double worst_w = 0.0, worst_T = 0.0;
  for (size_t k = 0; k < Q.size(); ++k) {
    worst_w = std::max(worst_w, std::abs(Q[k] - 0.5 * 1.0 * (400.0 - w[k] * w[k])));
    worst_T = std::max(worst_T, std::abs(Q[k] - 1.0 * (T[k] - 20.0)));
    ASSERT_EQ(Qt[k], Q[k]);
    ASSERT_EQ(Pt[k], P[k]);
  }
  EXPECT_LT(worst_w, tol) << "J, against ½ J (ω0² − ω²)";
  EXPECT_LT(worst_T, tol) << "J, against C (T − T0)";
  std::printf("HeatLosses eddy brake %s: heat vs ½J(ω0²−ω²) %.2e J, vs C(T−T0) %.2e J, Q(t_end) %.6g J\n",
              GetParam() == IntegratorChoice::bdf ? "bdf" : "dopri5", worst_w, worst_T, Q.back());
  EXPECT_GT(Q.back(), 150.0);  // most of the 200 J
  const EnergyBalance& E = r.hybrid.energy;
  EXPECT_NEAR(Qt.back(), E.source_work - (E.kinetic_end - E.kinetic_start), tol);
  EXPECT_NEAR(Qt.back(), dissipated(E), tol);
  const auto summary = simulation_summary(load_model(test::example("msl/eddy-current-brake.yaml")), r);
  EXPECT_NEAR(Qt.back(), summary["energy"]["dissipated_J"].get<double>(), tol);
}

// Claim: a DC motor's armature loss R i² is its heat (motor.heat_power_W, motor.heat_J), in the total.
// A motor (R = 2 Ω, L = 50 mH, k = 0.8 V·s/rad, 100 V from t = 0) runs up a rotor J = 0.5 kg·m² with a
// damper d = 0.1 N·m·s/rad to the ground:
//   J ω' = k i − d ω,   L i' = u − R i − k ω,   Q' = R i²,   W' = u i   (the supply's work)
// integrated here by RK4 (h = 1e-5 s). motor.heat_J follows Q within 1e-7 of Q(t_end) at every 10 ms
// row; the total heat is the motor's and the damper's; the books' source work is the work the supply
// put in less the inductance's stored energy, W − ½ L (i² − i0²), within 1e-7 relative, and the
// total heat at t_end is the books' dissipated energy.
TEST_P(HeatLosses, DcMotorArmatureLossFollowsAnRk4) {
  const Model m = test::model_text(R"(
bodies: {rotor: {inertia: 0.5 kg*m^2}}
links: {d: {type: damper, between: [rotor, ground], damping: 0.1 N*m*s/rad}}
drives:
  motor: {type: dc-motor, body: rotor, resistance: 2 ohm, inductance: 50 mH, motor_constant: 0.8 V*s/rad, voltage: 100 V}
simulation: {t_end: 2 s, dt_out: 10 ms, rtol: 1e-11, atol: 1e-12}
)");
  const SimulationResult r = run_heat(m, GetParam());
  const double J = 0.5, d = 0.1, R = 2.0, L = 0.05, k = 0.8, u = 100.0, h = 1e-5;
  auto f = [&](const std::array<double, 4>& z) {  // z = (ω, i, Q, W)
    return std::array<double, 4>{(k * z[1] - d * z[0]) / J, (u - R * z[1] - k * z[0]) / L, R * z[1] * z[1], u * z[1]};
  };
  auto add = [](const std::array<double, 4>& a, double c, const std::array<double, 4>& b) {
    std::array<double, 4> o{};
    for (size_t j = 0; j < 4; ++j) o[j] = a[j] + c * b[j];
    return o;
  };
  std::array<double, 4> z{};
  const auto &t = series(r, "t_s"), &Q = series(r, "motor.heat_J"), &Qd = series(r, "d.heat_J"), &Qt = series(r, "heat_J");
  const auto& P = series(r, "motor.heat_power_W");
  ASSERT_EQ(t.size(), 201u);
  std::vector<double> Qref;
  double tz = 0.0, worst = 0.0, worst_p = 0.0;
  for (size_t row = 0; row < t.size(); ++row) {
    for (; tz < t[row] - 0.5 * h; tz += h) {
      const auto k1 = f(z), k2 = f(add(z, 0.5 * h, k1)), k3 = f(add(z, 0.5 * h, k2)), k4 = f(add(z, h, k3));
      for (size_t j = 0; j < 4; ++j) z[j] += h / 6 * (k1[j] + 2 * k2[j] + 2 * k3[j] + k4[j]);
    }
    Qref.push_back(z[2]);
    worst_p = std::max(worst_p, std::abs(P[row] - R * z[1] * z[1]));
    ASSERT_NEAR(Qt[row], Q[row] + Qd[row], 1e-12 * std::max(1.0, Qt[row]));
  }
  for (size_t row = 0; row < t.size(); ++row) worst = std::max(worst, std::abs(Q[row] - Qref[row]));
  EXPECT_LT(worst, 1e-7 * Qref.back()) << worst << " J of " << Qref.back();
  EXPECT_LT(worst_p, 1e-6 * R * 50.0 * 50.0) << "W";  // of the stall loss R (u/R)² = 5 kW
  EXPECT_GT(Qref.back(), 1000.0);                     // a real loss, not a rounding
  const EnergyBalance& E = r.hybrid.energy;
  const double W = z[3] - 0.5 * L * z[1] * z[1];
  EXPECT_NEAR(E.source_work, W, 1e-7 * W);
  EXPECT_NEAR(Qt.back(), dissipated(E), 1e-7 * W);
  std::printf("HeatLosses DC motor %s: heat vs RK4 %.2e J of %.6g J, source work vs W − ½Li² %.2e J\n",
              GetParam() == IntegratorChoice::bdf ? "bdf" : "dopri5", worst, Qref.back(), E.source_work - W);
}

// ---------------------------------------------------------------------------------------------
// An independent solution of MSL Translational.Examples.HeatLosses, written from MSL's component
// equations as functions of the state, not from the library's engine. Displacements x from MSL's
// start (s = 0, 0.1, 0.2, 0.3 m; every spring unstretched), m = 1 kg each:
//   mass1: F = 20 sin 2πt; damper 10 v1; ElastoGap from a Fixed at 0 to mass1's left flange,
//          s_rel = x1 − 0.05, contact for s_rel < s_rel0 = −0.02: f_c = 100 (x1 − 0.03) < 0,
//          f_d = clamp(20 v1, f_c, −f_c), mass1 gets −(f_c + f_d), its lossPower f_d v1 (MSL's
//          Translational.Components.ElastoGap); springDamper f = 100 (x2 − x1) + 10 (v2 − v1);
//   mass2: −f; spring 100 (x3 − x2); SupportFriction (f_pos = [0, 1], peak 1): 1 N;
//   mass3: Brake, fn = 10 · 10 sin 4πt, free while fn ≤ 0, 0.5 fn sliding and holding;
//          springDamper1 f1 = 1e4 (x4 − x3) + 1000 (v4 − v3);
//   mass4 (MassWithStopAndFriction): −f1, F_prop = 0.5, sliding friction 1 + 2 e^{−2|v|}, holding
//          up to f0_max = 1.001 (F_C + F_S) = 3.003 N (MSL's peak; the file's `peak: 1.001`),
//          stops at x4 = −0.25 m, 0.05 m with reinit v = 0 (the kinetic energy lost goes to no heat
//          port in MSL: counted apart here).
// A stuck element's force is the sum of the other forces on its mass (a = 0), which needs no other
// element's acceleration, so each friction element is decided on its own. Events (≥ 0 while the
// mode holds): sliding s v (and the distance to the stop ahead), stuck limit − |force| (at a stop:
// only pulling away). The brake is released at 0.25, 0.75, … s and applied at 0.5, 1, 1.5 s (grid
// times). Fixed-step RK4 (h = 1e-5 s), a step whose event function turns negative bisected to its
// instant. The heat of each element (MSL's lossPower) and the force's work are RK4 states too.
struct HeatLossesReference {
  enum : int { x1, v1, x2, v2, x3, v3, x4, v4, q_damper, q_gap, q_sd, q_sd1, q_prop, q_sf, q_fr, q_brake, work, kN };
  using Y = std::array<double, kN>;
  static constexpr double xmin = -0.25, xmax = 0.05;
  int m2 = 0, m3 = 0, m4 = 0;  // 0 stuck, ±1 sliding; m3 = 2: the brake is free
  double impact = 0.0;         // kinetic energy lost at the stops, J
  std::vector<double> impact_times;

  static double force(double t) { return 20 * std::sin(2 * std::numbers::pi * t); }
  static double fn(double t) { return 100 * std::sin(4 * std::numbers::pi * t); }
  struct Gap {
    double fc, fd;
  };
  static Gap gap(const Y& y) {
    if (!(y[x1] < 0.03)) return {0.0, 0.0};
    const double fc = 100 * (y[x1] - 0.03), fd2 = 20 * y[v1];
    return {fc, fd2 < fc ? fc : fd2 > -fc ? -fc : fd2};
  }
  /// Whether the ElastoGap touches with its damping force clamped at −f_c (f = 0): machdyn's gap law
  /// is open there and has already released the spring's ½ c e².
  static bool clamped_off(const Y& y) {
    const Gap g = gap(y);
    return y[x1] < 0.03 && g.fd == -g.fc && g.fc < 0;
  }
  static double sd(const Y& y) { return 100 * (y[x2] - y[x1]) + 10 * (y[v2] - y[v1]); }
  static double sd1(const Y& y) { return 1e4 * (y[x4] - y[x3]) + 1000 * (y[v4] - y[v3]); }
  /// The forces on masses 2, 3, 4 other than their friction element's.
  static double n2(const Y& y) { return -sd(y) + 100 * (y[x3] - y[x2]); }
  static double n3(const Y& y) { return -100 * (y[x3] - y[x2]) + sd1(y); }
  static double n4(const Y& y) { return -sd1(y) - 0.5 * y[v4]; }
  static double kinetic4(double v) { return 1 + 2 * std::exp(-2 * std::abs(v)); }

  Y rate(double t, const Y& y) const {
    Y d{};
    const Gap g = gap(y);
    d[x1] = y[v1];
    d[v1] = force(t) - 10 * y[v1] - (g.fc + g.fd) + sd(y);
    d[x2] = m2 == 0 ? 0.0 : y[v2];
    d[v2] = m2 == 0 ? 0.0 : n2(y) - m2 * 1.0;
    d[x3] = m3 == 0 ? 0.0 : y[v3];
    d[v3] = m3 == 0 ? 0.0 : n3(y) - (m3 == 2 ? 0.0 : m3 * 0.5 * fn(t));
    d[x4] = m4 == 0 ? 0.0 : y[v4];
    d[v4] = m4 == 0 ? 0.0 : n4(y) - m4 * kinetic4(y[v4]);
    d[q_damper] = 10 * y[v1] * y[v1];
    d[q_gap] = g.fd * y[v1];
    d[q_sd] = 10 * (y[v2] - y[v1]) * (y[v2] - y[v1]);
    d[q_sd1] = 1000 * (y[v4] - y[v3]) * (y[v4] - y[v3]);
    d[q_prop] = 0.5 * y[v4] * y[v4];
    d[q_sf] = m2 == 0 ? 0.0 : std::abs(y[v2]);
    d[q_fr] = m4 == 0 ? 0.0 : kinetic4(y[v4]) * std::abs(y[v4]);
    d[q_brake] = m3 == 1 || m3 == -1 ? 0.5 * fn(t) * std::abs(y[v3]) : 0.0;
    d[work] = force(t) * y[v1];
    return d;
  }
  /// Mass 4's stuck margin: at a stop only a pull away from it beyond f0_max = 3.003 N frees it.
  static double margin4(const Y& y) {
    const double n = n4(y), f0_max = 1.001 * 3;
    if (y[x4] >= xmax) return f0_max + n;
    if (y[x4] <= xmin) return f0_max - n;
    return f0_max - std::abs(n);
  }
  double event(double t, const Y& y) const {
    const double e2 = m2 == 0 ? 1 - std::abs(n2(y)) : m2 * y[v2];
    const double e3 = m3 == 2 ? 1.0 : m3 == 0 ? 0.5 * fn(t) - std::abs(n3(y)) : m3 * y[v3];
    const double e4 = m4 == 0 ? margin4(y) : std::min(m4 * y[v4], m4 > 0 ? xmax - y[x4] : y[x4] - xmin);
    return std::min({e2, e3, e4});
  }
  Y step(double t, const Y& y, double h) const {
    return test::rk4_step([this](double s, const Y& z) { return rate(s, z); }, t, y, h);
  }
  /// Re-decides every friction element at t: a slide that ended sticks (v = 0), a stop reached sets
  /// the position on it and v = 0, a stuck element whose force exceeds its limit slides that way.
  void decide(double t, Y& y) {
    if (m2 != 0 && m2 * y[v2] <= 0) y[v2] = 0.0, m2 = 0;
    if ((m3 == 1 || m3 == -1) && m3 * y[v3] <= 0) y[v3] = 0.0, m3 = 0;
    if (m4 != 0) {
      if (m4 > 0 ? y[x4] >= xmax : y[x4] <= xmin) {
        y[x4] = m4 > 0 ? xmax : xmin;
        impact += 0.5 * y[v4] * y[v4];
        impact_times.push_back(t);
        y[v4] = 0.0, m4 = 0;
      } else if (m4 * y[v4] <= 0) {
        y[v4] = 0.0, m4 = 0;
      }
    }
    if (m2 == 0 && std::abs(n2(y)) > 1) m2 = n2(y) > 0 ? 1 : -1;
    if (m3 == 0 && std::abs(n3(y)) > 0.5 * fn(t)) m3 = n3(y) > 0 ? 1 : -1;
    if (m4 == 0 && margin4(y) < 0) m4 = n4(y) > 0 ? 1 : -1;
  }
  /// The state at k dt, k = 0 … n (dt divides 0.25 s), and the impact loss so far at each.
  std::vector<Y> run(double dt, int n, std::vector<double>& impact_rows) {
    Y y{};
    std::vector<Y> out{y};
    impact_rows.assign(1, 0.0);
    double t = 0;
    for (int k = 1; k <= n; ++k) {
      const double stop = k * dt;
      while (t < stop) {
        const bool last = stop - t <= 1.000001e-5;
        double h = last ? stop - t : 1e-5;
        const Y y1 = step(t, y, h);
        if (event(t + h, y1) < 0) {
          double lo = 0, hi = h;
          while (std::nextafter(lo, hi) < hi) {
            const double mid = 0.5 * (lo + hi);
            (event(t + mid, step(t, y, mid)) < 0 ? hi : lo) = mid;
          }
          y = step(t, y, hi);
          t += hi;
          decide(t, y);
          continue;
        }
        y = y1;
        t = last ? stop : t + h;
      }
      // The brake's normal force crosses 0 at multiples of 0.25 s: free after 0.25, 0.75, …, applied
      // after 0.5, 1, 1.5 s (sliding the way mass3 moves, or decided at rest).
      const long quarter = std::lround(stop / 0.25);
      if (std::abs(stop - 0.25 * static_cast<double>(quarter)) < 1e-12) {
        if (quarter % 2 == 1) m3 = 2;
        else m3 = y[v3] > 0 ? 1 : y[v3] < 0 ? -1 : 0;
        decide(stop, y);
      }
      out.push_back(y);
      impact_rows.push_back(impact);
    }
    return out;
  }
};

// Claim: examples/msl/heat-losses-translational.yaml (MSL Translational.Examples.HeatLosses) follows
// the independent solution above: positions within 1e-8 m and speeds within 1e-6 m/s at every 1 ms
// row; each element's heat and the total within 1e-7 J at every row — the ElastoGap's plus the ½ c e² machdyn's gap
// law releases when it opens at zero force off its flank while MSL's clamps its damping force at
// −f_c and dissipates the same energy as the spring relaxes; the stop's heat is the reference's
// impact loss (MSL's reinit: in no heat port), at the same instants (within 1e-8 s); the total
// heat_J is the sum of the reference's heats and impact losses, and at t_end W − ΔT − ΔV of the books
// and summary.json's `dissipated_J`.
// Measured (dopri5 / bdf): positions 1.2e-10 / 1.4e-10 m, speeds 5.0e-9 / 6.2e-8 m/s, element heats
// 1.8e-9 / 2.5e-8 J, total 2.3e-9 / 2.2e-8 J of 19.49 J.
TEST_P(HeatLosses, TranslationalHeatLossesFollowAnIndependentSolution) {
  Model m = load_model(test::example("msl/heat-losses-translational.yaml"));
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m, SimulateOptions{}, output_selection({"heat"}));
  const auto& ts = series(r, "t_s");
  ASSERT_EQ(ts.size(), 2001u);
  HeatLossesReference ref;
  std::vector<double> impacts;
  const auto y = ref.run(1e-3, 2000, impacts);
  using R = HeatLossesReference;

  const std::array<std::pair<const char*, int>, 4> bodies{
      {{"mass1", R::x1}, {"mass2", R::x2}, {"mass3", R::x3}, {"massWithStopAndFriction", R::x4}}};
  for (const auto& [b, i] : bodies) {
    const auto &q = series(r, std::string(b) + ".position_m"), &v = series(r, std::string(b) + ".velocity_m_s");
    double eq = 0, ev = 0;
    for (size_t k = 0; k < ts.size(); ++k) {
      eq = std::max(eq, std::abs(q[k] - y[k][static_cast<size_t>(i)]));
      ev = std::max(ev, std::abs(v[k] - y[k][static_cast<size_t>(i + 1)]));
    }
    EXPECT_LT(eq, 1e-8) << b;
    EXPECT_LT(ev, 1e-6) << b;
    RecordProperty(std::string(b) + "_position_error", sci(eq));
    RecordProperty(std::string(b) + "_speed_error", sci(ev));
  }

  const std::array<std::pair<const char*, int>, 8> heats{{{"damper", R::q_damper},
                                                          {"elastoGap", R::q_gap},
                                                          {"springDamper", R::q_sd},
                                                          {"springDamper1", R::q_sd1},
                                                          {"massWithStopAndFriction_prop", R::q_prop},
                                                          {"supportFriction", R::q_sf},
                                                          {"massWithStopAndFriction_friction", R::q_fr},
                                                          {"brake", R::q_brake}}};
  const auto& total = series(r, "heat_J");
  const auto& stop = series(r, "massWithStopAndFriction_max.heat_J");
  double e_total = 0, e_stop = 0, released = 0;
  for (const auto& [name, i] : heats) {
    const auto& Q = series(r, std::string(name) + ".heat_J");
    double e = 0;
    for (size_t k = 0; k < ts.size(); ++k) {
      // machdyn's gap law has released ½ c e² that MSL's ElastoGap still holds while clamped.
      const double early = i == R::q_gap && R::clamped_off(y[k]) ? 50 * (y[k][R::x1] - 0.03) * (y[k][R::x1] - 0.03) : 0.0;
      if (early > 0) released = std::max(released, early);
      e = std::max(e, std::abs(Q[k] - (y[k][static_cast<size_t>(i)] + early)));
    }
    EXPECT_LT(e, 1e-7) << name;
    RecordProperty(std::string(name) + "_heat_error", sci(e));
  }
  EXPECT_GT(released, 1e-3);  // the example does open its gap off the flank (the difference is tested)
  for (size_t k = 0; k < ts.size(); ++k) {
    double ref_total = impacts[k] + (R::clamped_off(y[k]) ? 50 * (y[k][R::x1] - 0.03) * (y[k][R::x1] - 0.03) : 0.0);
    for (const auto& [name, i] : heats) ref_total += y[k][static_cast<size_t>(i)];
    e_total = std::max(e_total, std::abs(total[k] - ref_total));
    e_stop = std::max(e_stop, std::abs(stop[k] - impacts[k]));
  }
  EXPECT_LT(e_total, 1e-7);
  EXPECT_LT(e_stop, 1e-7);
  RecordProperty("total_heat_error", sci(e_total));
  RecordProperty("impact_heat_error", sci(e_stop));

  // The stop's impacts (logged as the stop holding the mass at rest) at the reference's instants.
  std::vector<double> hits;
  for (const auto& e : r.hybrid.events)
    if (e.element == "massWithStopAndFriction_max" && e.kind == "stick") hits.push_back(e.t);
  ASSERT_EQ(ref.impact_times.size(), 2u);
  ASSERT_EQ(hits.size(), ref.impact_times.size());
  for (size_t i = 0; i < hits.size(); ++i) EXPECT_NEAR(hits[i], ref.impact_times[i], 1e-8);

  // Energy: the reference balances on its own (W = ΔT + ΔV + heat + impacts, V with the ElastoGap's
  // spring while it touches); machdyn's total is its books' W − ΔT − ΔV.
  const auto& Y = y.back();
  const double T = 0.5 * (Y[R::v1] * Y[R::v1] + Y[R::v2] * Y[R::v2] + Y[R::v3] * Y[R::v3] + Y[R::v4] * Y[R::v4]);
  const double V = 50 * (Y[R::x2] - Y[R::x1]) * (Y[R::x2] - Y[R::x1]) + 50 * (Y[R::x3] - Y[R::x2]) * (Y[R::x3] - Y[R::x2]) +
                   5e3 * (Y[R::x4] - Y[R::x3]) * (Y[R::x4] - Y[R::x3]) +
                   (Y[R::x1] < 0.03 ? 50 * (Y[R::x1] - 0.03) * (Y[R::x1] - 0.03) : 0.0) - 50 * 0.03 * 0.03;
  double Q_ref = impacts.back();
  for (const auto& [name, i] : heats) Q_ref += Y[static_cast<size_t>(i)];
  EXPECT_NEAR(Y[R::work] - T - V, Q_ref, 1e-7);
  const EnergyBalance& E = r.hybrid.energy;
  EXPECT_NEAR(total.back(), E.source_work - (E.kinetic_end - E.kinetic_start) - (E.elastic_end - E.elastic_start), 1e-7);
  EXPECT_NEAR(simulation_summary(m, r)["energy"]["dissipated_J"].get<double>(), total.back(), 1e-7);  // summary.json
  RecordProperty("total_heat_J", sci(total.back()));
}

}  // namespace
}  // namespace machdyn
