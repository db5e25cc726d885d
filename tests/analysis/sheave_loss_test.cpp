// A rope's sheave losses acting on the dynamics (model/sheaves.hpp; the reeving's law:
// model/reeving.hpp): steady hoisting and lowering at the drum torque of the parts' balance over the
// sheaves, a hold at rest anywhere inside the band between the two, a start just outside it in the
// direction it points, and the energy books (the loss is heat) with the invariant audit, on both
// integrators; what the drum cannot carry with the losses is a located error.
#include <cmath>
#include <string>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/model/sheaves.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::series;

class SheaveLoss : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, SheaveLoss, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

constexpr double kG = 9.81, kMass = 12000.0, kR = 0.25, kC = 4e6, kDrumInertia = 90.0;

/// The hook load F = m g hangs on n falls from n_e rope ends on a drum of radius R; each end feeds k = n/n_e
/// parts, part j over the j sheaves between it and the drum. Hoisting the rope runs towards the drum and
/// each sheave passes η of its tight side: T_j = η^j T_0, the hook's balance n_e Σ_j T_j = F; lowering
/// T_j = η^(−j) T_0. The drum carries the n_e parts at the drum: M = n_e T_0 R.
double drum_torque(int falls, int ends, double eta, bool hoisting) {
  const int k = falls / ends;
  double sum = 0.0;
  for (int j = 0; j < k; ++j) sum += std::pow(eta, hoisting ? j : -j);
  const double T0 = kMass * kG / (ends * sum);
  return ends * T0 * kR;
}

/// A drum (90 kg·m², its speed ω) hoisting a 12 t hook on a rope of c = 4e6 N/m with `falls` falls from
/// `ends` rope ends (ratio (n/n_e)/R), sheaves of η, the drum driven by the torque M; the hook at the
/// stretch m g / c below the drum's rope end, moving with it.
std::string hoist(int falls, int ends, double eta, double omega, double M, const std::string& extra = "") {
  const double i = static_cast<double>(falls / ends) / kR, v = omega / i;
  return fmt::format(R"(gravity: 9.81 m/s^2
bodies:
  drum: {{inertia: {} kg*m^2, velocity: {:.17g} rad/s}}
  hook: {{type: translational, mass: 12 t, vertical: up, position: {:.17g} m, velocity: {:.17g} m/s}}
links:
  rope: {{type: rope, between: [drum, hook], ratio: 4 rad/m, falls: {}, rope_ends: {}, sheave_efficiency: {},
         stiffness: 4e6 N/m}}
loads:
  M: {{type: constant, body: drum, value: {:.17g} N*m}}
{}simulation: {{t_end: 1 s, dt_out: 10 ms, rtol: 1e-10, atol: 1e-12}}
)",
                     kDrumInertia, omega, -kMass * kG / kC, v, falls, ends, eta, M, extra);
}

// Claim: a drum driven by the torque of the parts' balance over the sheaves (above) runs steadily:
// hoisting at M = F R / Σ η^j, lowering at F R / Σ η^(−j) (4/2 reeving with η = 0.98 and 6/2 with
// η = 0.95), the drum's speed and the hook load stay constant and the sheaves turn M ω − F v_hook into
// heat. The ideal reeving's torque F/i would accelerate the drum hoisting (decelerate it lowering) by
// (M − F/i)/I: 0.17 rad/s² for 4/2 — 1.7e-1 rad/s over the run, which the check below resolves to 1e-8.
TEST_P(SheaveLoss, SteadyHoistingAndLoweringAtTheTorqueOfThePartsBalance) {
  struct Case {
    int falls, ends;
    double eta, omega;
  };
  for (const Case c : {Case{4, 2, 0.98, 2.0}, Case{4, 2, 0.98, -2.0}, Case{6, 2, 0.95, 1.5}, Case{6, 2, 0.95, -1.5}}) {
    const bool hoisting = c.omega > 0.0;
    const double M = drum_torque(c.falls, c.ends, c.eta, hoisting), i = (c.falls / c.ends) / kR, F = kMass * kG;
    Model m = test::model_text(hoist(c.falls, c.ends, c.eta, c.omega, M));
    m.simulation.integrator = GetParam();
    const SimulationResult r = simulate(m);
    const std::string what = fmt::format("{}/{} eta {} omega {}", c.falls, c.ends, c.eta, c.omega);
    const auto &w = series(r, "drum.velocity_rad_s"), &xv = series(r, "hook.velocity_m_s"), &Fr = series(r, "rope.load_N");
    const auto& loss = series(r, "rope.sheaves.loss_power_W");
    const auto& mode = series(r, "rope.sheaves.mode");
    ASSERT_EQ(w.size(), 101u) << what;
    for (size_t k = 0; k < w.size(); ++k) {
      EXPECT_NEAR(w[k], c.omega, 1e-8) << what << " row " << k;
      EXPECT_NEAR(xv[k], c.omega / i, 1e-8) << what << " row " << k;
      EXPECT_NEAR(Fr[k], F, 1e-6 * F) << what << " row " << k;
      EXPECT_NEAR(loss[k], M * c.omega - F * c.omega / i, 1e-6 * M * std::abs(c.omega)) << what << " row " << k;
      EXPECT_EQ(mode[k], hoisting ? 1.0 : -1.0) << what << " row " << k;
    }
    EXPECT_GT(loss.back(), 0.005 * M * std::abs(c.omega)) << what;  // the losses are not negligible here
  }
}

// Claim: at rest the sheaves hold anything between the two torques: with the brake released and the motor
// torque M anywhere in the band [F R / Σ η^(−j), F R / Σ η^j] (at 2 %, 50 % and 98 % of it, 4/2 reeving,
// η = 0.98) nothing moves — the drum stays exactly at rest and the hook hangs where it hung. 2 % of the
// band outside it, the drum starts in the direction the torque points: lowering below, hoisting above.
TEST_P(SheaveLoss, HoldsAtRestInsideTheBandAndStartsOutsideIt) {
  const double lo = drum_torque(4, 2, 0.98, false), hi = drum_torque(4, 2, 0.98, true), band = hi - lo;
  const double x0 = -kMass * kG / kC;
  EXPECT_GT(band, 0.01 * hi);  // F R (1/(1 + η) − η/(1 + η))·2: 2 % of the load torque
  for (const double s : {0.02, 0.5, 0.98, -0.02, 1.02}) {
    Model m = test::model_text(hoist(4, 2, 0.98, 0.0, lo + s * band));
    m.simulation.integrator = GetParam();
    const SimulationResult r = simulate(m);
    const auto &w = series(r, "drum.velocity_rad_s"), &x = series(r, "hook.position_m");
    ASSERT_FALSE(w.empty());
    if (s > 0.0 && s < 1.0) {
      for (size_t k = 0; k < w.size(); ++k) {
        EXPECT_EQ(w[k], 0.0) << s << " row " << k;
        EXPECT_NEAR(x[k], x0, 1e-12) << s << " row " << k;
      }
      EXPECT_EQ(series(r, "rope.sheaves.mode").back(), 0.0) << s;
    } else {
      EXPECT_EQ(w.back() > 0.0, s > 1.0) << s << ": " << w.back();
      EXPECT_GT(std::abs(w.back()), 1e-3) << s;
    }
  }
}

// Claim: the energy books balance with the sheaves' heat in the friction column: a drum driven by a
// torque swinging ±3 bands about the band's middle (2 Hz) hoists, stops, lowers and sticks in turn; the
// source work equals the change of kinetic and elastic energy plus the damper's and the sheaves' losses
// (residual below 1e-7 of the work and losses), the friction column is the integral of the loss power column
// (trapezoid on the 0.1 ms grid, to 1e-3) and positive, and the invariant audit (loss power ≥ 0 at every
// step, simulate's `check`) passes.
TEST_P(SheaveLoss, EnergyBooksCountTheSheavesHeat) {
  const double lo = drum_torque(4, 2, 0.98, false), hi = drum_torque(4, 2, 0.98, true), band = hi - lo;
  std::string yaml = hoist(4, 2, 0.98, 0.0, 0.5 * (lo + hi),
                           fmt::format("  swing: {{type: sine, body: drum, amplitude: {:.17g} N*m, frequency: 2 Hz}}\n",
                                       3.0 * band));
  yaml.replace(yaml.find("stiffness: 4e6 N/m}"), 19, "stiffness: 4e6 N/m, damping: 2e4 N*s/m}");
  yaml.replace(yaml.find("dt_out: 10 ms"), 13, "dt_out: 0.1 ms");
  // The sine is a second load: its line goes under `loads:` (hoist() puts `extra` after them).
  Model m = test::model_text(yaml);
  m.simulation.integrator = GetParam();
  SimulateOptions opt;
  opt.check = true;
  const SimulationResult r = simulate(m, opt);
  const EnergyBalance& e = r.hybrid.energy;
  EXPECT_NEAR(e.residual(), 0.0, 1e-7 * (e.friction_loss + e.damping_loss + std::abs(e.source_work)));
  const auto &t = series(r, "t_s"), &p = series(r, "rope.sheaves.loss_power_W"), &w = series(r, "drum.velocity_rad_s");
  double heat = 0.0, wmin = 0.0, wmax = 0.0;
  for (size_t k = 1; k < t.size(); ++k) {
    heat += 0.5 * (p[k] + p[k - 1]) * (t[k] - t[k - 1]);
    EXPECT_GE(p[k], 0.0) << t[k];
    wmin = std::min(wmin, w[k]), wmax = std::max(wmax, w[k]);
  }
  EXPECT_GT(wmax, 0.0);  // it hoisted and lowered
  EXPECT_LT(wmin, 0.0);
  EXPECT_GT(e.friction_loss, 0.0);
  EXPECT_NEAR(e.friction_loss, heat, 1e-3 * heat);
}

// Claim: the drum of a rope with sheave losses must be able to carry the lossy gear they act as: a rope
// from the ground, a drum already on a lossy gear and a model with a prescribed motion are located errors
// at the rope; k = 1 (each end straight to the hook block) has no sheave and no loss; the model's tables
// show the rope as written (no extra body or gear).
TEST(SheaveLossFile, WhatTheDrumCannotCarryIsLocated) {
  const std::string base = hoist(4, 2, 0.98, 0.0, 0.0);
  auto with = [&](const std::string& from, const std::string& to) {
    std::string y = base;
    y.replace(y.find(from), from.size(), to);
    return y;
  };
  std::string e = test::compile_errors(with("between: [drum, hook], ratio: 4 rad/m, falls: 4, rope_ends: 2",
                                            "between: [ground, hook], falls: 4"));
  EXPECT_NE(e.find("test.yaml:6:3: error: rope 'rope': its sheave losses"), std::string::npos) << e;
  EXPECT_NE(e.find("not the ground"), std::string::npos) << e;
  EXPECT_EQ(test::compile_errors(with("  hook:", "  motor: {inertia: 1 kg*m^2}\n  hook:")), "");
  std::string geared = with("  hook:", "  motor: {inertia: 1 kg*m^2}\n  hook:");
  geared = geared.replace(geared.find("links:\n"), 7,
                          "links:\n  gearbox: {type: lossy-gear, between: [motor, drum], ratio: 20, efficiency: 0.9}\n");
  e = test::compile_errors(geared);
  EXPECT_NE(e.find("rope 'rope': its sheave losses"), std::string::npos) << e;
  EXPECT_NE(e.find("lossy gear 'gearbox' already gears"), std::string::npos) << e;
  e = test::compile_errors(with("  hook:", "  winch: {inertia: 1 kg*m^2, motion: {speed: 1 rad/s}}\n  hook:"));
  EXPECT_NE(e.find("rope 'rope': its sheave losses"), std::string::npos) << e;
  EXPECT_NE(e.find("prescribed motion ('winch')"), std::string::npos) << e;
  // k = 1: 2 falls from 2 ends, no sheave between drum and hook block: nothing added.
  const Model straight = test::model_text(with("falls: 4, rope_ends: 2", "falls: 2, rope_ends: 2"));
  EXPECT_TRUE(straight.lossy_gears.empty());
  EXPECT_EQ(straight.dof(), 2);
  // 4/2: the massless body and the gear, named after the rope, with the reeving's efficiencies.
  const Model m = test::model_text(base);
  ASSERT_EQ(m.lossy_gears.size(), 1u);
  const LossyGear& g = m.lossy_gears[0];
  EXPECT_EQ(g.name, "rope.sheaves");
  EXPECT_TRUE(is_sheave_gear(m, g));
  EXPECT_TRUE(is_sheave_body(m, g.b));
  EXPECT_EQ(m.bodies[static_cast<size_t>(g.b)].inertia, 0.0);
  EXPECT_DOUBLE_EQ(g.ratio, 8.0);
  EXPECT_DOUBLE_EQ(g.eta_forward[0], (1.0 + 0.98) / 2.0);
  EXPECT_DOUBLE_EQ(g.eta_reverse[0], 1.0 / ((1.0 + 1.0 / 0.98) / 2.0));
  EXPECT_EQ(sheave_gear(m, m.links[0]), 0);
  EXPECT_EQ(rope_drum(m, m.links[0]), 0);
  EXPECT_EQ(m.links[0].given_a, "drum");
}

}  // namespace
}  // namespace machdyn
