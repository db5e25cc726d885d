// The elastic gear mesh (elements/gear_mesh.hpp, `type: gear-mesh` under `links:`): the torsional
// natural frequency of two inertias through the mesh, the free flight through the backlash and the
// elastic contact between, steady transmission with its efficiency, the energy books (the loss is
// the heat), on both integrators; the audit's invariants; located errors for bad fields.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "machdyn/analysis/extra_outputs.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/elements/gear_mesh.hpp"
#include "machdyn/elements/linearize.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::series;

class Mesh : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, Mesh, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

/// A pinion (J₁ = 0.01 kg·m², at `pinion_velocity` rad/s) and a wheel (J₂ = 0.5 kg·m², at rest) through
/// the mesh `mesh_fields`; `extra` continues the `links:` map (indented entries) and may add sections.
Model mesh_model(const std::string& mesh_fields, const std::string& extra, double t_end, double dt_out,
                 IntegratorChoice integ, const std::string& pinion_velocity = "0") {
  Model m = test::model_text("bodies:\n  pinion: {inertia: 0.01 kg*m^2, velocity: " + pinion_velocity +
                             " rad/s}\n  wheel: {inertia: 0.5 kg*m^2}\nlinks:\n  mesh: {type: gear-mesh, between: "
                             "[pinion, wheel], " + mesh_fields + "}\n" + extra +
                             "simulation: {t_end: " + std::to_string(t_end) + " s, dt_out: " + std::to_string(dt_out) +
                             " s, rtol: 1e-10, atol: 1e-12}\n",
                             "mesh.yaml");
  m.simulation.integrator = integ;
  return m;
}

/// Ω² = c (1/J₁ + i²/J₂) for the test's J₁ = 0.01, J₂ = 0.5 kg·m².
double omega_mesh(double c, double i) { return std::sqrt(c * (1.0 / 0.01 + i * i / 0.5)); }

// Claim: two inertias through a mesh without backlash, damping or loss vibrate at the torsional
// natural frequency Ω² = c (1/J₁ + i²/J₂). Derivation: J₁ φ₁'' = −c Δ, J₂ φ₂'' = i c Δ (the torques
// −τ, i τ with τ = c Δ), so Δ'' = φ₁'' − i φ₂'' = −c (1/J₁ + i²/J₂) Δ; from Δ(0) = 0, Δ'(0) = ω₀
// (the pinion at ω₀, the wheel at rest), Δ(t) = (ω₀/Ω) sin Ω t. The deflection column follows it at
// every row within 1e-6 of its amplitude, though both bodies reverse (the mesh's power-direction
// events) many times; and the linear model (its K over Δ = φ₁ − i φ₂) has the same Ω.
TEST_P(Mesh, TorsionalNaturalFrequencyOfTwoInertias) {
  const double c = 2e4, i = 3.0, w0 = 1.0, W = omega_mesh(c, i);
  const Model m = mesh_model("ratio: 3, stiffness: 2e4 N*m/rad", "", 0.02, 1e-4, GetParam(), "1");
  const SimulationResult r = simulate(m);
  const auto &t = series(r, "t_s"), &D = series(r, "mesh.deflection_rad"), &M2 = series(r, "mesh.wheel_torque_N_m");
  double worst = 0.0, worst_M = 0.0;
  for (size_t k = 0; k < t.size(); ++k) {
    worst = std::max(worst, std::abs(D[k] - w0 / W * std::sin(W * t[k])));
    worst_M = std::max(worst_M, std::abs(M2[k] - i * c * w0 / W * std::sin(W * t[k])));
  }
  EXPECT_LT(worst, 1e-6 * w0 / W) << "rad";
  EXPECT_LT(worst_M, 1e-6 * i * c * w0 / W) << "N·m";
  EXPECT_GT(r.hybrid.events.size(), 5u);  // the bodies reverse: power-direction switches

  // The linear model: K = c j jᵀ, j = (1, −i); M = diag(J₁, J₂): its nonzero eigenvalue is Ω².
  const LinearModel lin = linearize(m, initial_topology(m));
  const Eigen::MatrixXd K(lin.stiffness());
  Eigen::MatrixXd A = lin.M.cwiseInverse().asDiagonal() * K;
  const Eigen::VectorXd ev = A.eigenvalues().real();
  EXPECT_NEAR(ev.maxCoeff(), W * W, 1e-9 * W * W);
}

// Claim: through the backlash no torque acts, and the flanks' contact is elastic. The pinion at
// ω₀ = 2 rad/s, the wheel at rest, Δ(0) = 0 in the middle of b = 0.02 rad: free flight Δ = ω₀ t to
// the + flank at t₁ = (b/2)/ω₀ = 5 ms (the wheel at rest, the pinion at ω₀ until then, exactly);
// on the flank (c, no damping) Δ − b/2 = (ω₀/Ω) sin Ω(t − t₁), so the contact ends after half a
// period, t₂ = t₁ + π/Ω, with Δ' = −ω₀; free flight back across the whole play, t₃ = t₂ + b/ω₀, on
// the − flank.
TEST_P(Mesh, FreeFlightThroughTheBacklashAndElasticContact) {
  const double c = 2e4, i = 3.0, w0 = 2.0, b = 0.02, W = omega_mesh(c, i);
  const double t1 = 0.5 * b / w0, t2 = t1 + std::numbers::pi / W, t3 = t2 + b / w0;
  const Model m = mesh_model("ratio: 3, stiffness: 2e4 N*m/rad, backlash: 0.02 rad", "", 0.03, 1e-3, GetParam(), "2");
  const SimulationResult r = simulate(m);
  std::vector<double> closing, opening;
  for (const ModeEvent& e : r.hybrid.events) {
    if (e.element != "mesh" || e.kind == "initial") continue;
    if (e.from == "free play" && e.to != "free play") closing.push_back(e.t);
    if (e.from != "free play" && e.to == "free play") opening.push_back(e.t);
  }
  ASSERT_GE(closing.size(), 2u);
  ASSERT_GE(opening.size(), 1u);
  EXPECT_NEAR(closing[0], t1, 1e-10);
  EXPECT_NEAR(opening[0], t2, 1e-8);
  EXPECT_NEAR(closing[1], t3, 1e-8);
  const auto &t = series(r, "t_s"), &w1 = series(r, "pinion.velocity_rad_s"), &w2 = series(r, "wheel.velocity_rad_s");
  const auto& M1 = series(r, "mesh.torque_N_m");
  for (size_t k = 0; k < t.size() && t[k] < t1; ++k) {
    EXPECT_EQ(w1[k], w0) << t[k];
    EXPECT_EQ(w2[k], 0.0) << t[k];
    EXPECT_EQ(M1[k], 0.0) << t[k];
  }
}

// Claim: in the free play nothing happens at a load's step, though a body has reversed there since
// the last decision. The pinion (J₁ = 0.01 kg·m²) at ω₀ = −1 rad/s under 1 N·m: ω₁ = −1 + 100 t,
// φ₁ = −t + 50 t² (reversing at 0.01 s); the wheel (J₂ = 0.5 kg·m²) at rest until a step of 0.5 N·m
// at 0.05 s: φ₂ = ½ (t − 0.05)². With i = 1 and b = 1 rad, Δ = φ₁ − φ₂ stays inside ±b/2 (its
// minimum −0.005 rad at 0.01 s) until 49.5 t² − 0.95 t − 0.50125 = 0 (Δ = b/2), t_c = 0.110 68 s:
// the first event of the mesh is that contact. (The decision at the step re-read the signs of the
// speeds inside the free play and listed a `free play` → `free play` event at 0.05 s.)
TEST_P(Mesh, AStepInTheFreePlayIsNoEvent) {
  const Model m = mesh_model("ratio: 1, stiffness: 1e4 N*m/rad, backlash: 1 rad",
                             "loads:\n  drive: {type: constant, body: pinion, value: 1 N*m}\n"
                             "  brake: {type: step, body: wheel, value: 0.5 N*m, time: 0.05 s}\n",
                             0.12, 1e-3, GetParam(), "-1");
  const SimulationResult r = simulate(m);
  const double tc = (0.95 + std::sqrt(0.95 * 0.95 + 4 * 49.5 * 0.50125)) / 99.0;
  std::vector<const ModeEvent*> ev;
  for (const ModeEvent& e : r.hybrid.events)
    if (e.element == "mesh" && e.kind != "initial") ev.push_back(&e);
  ASSERT_GE(ev.size(), 1u);
  EXPECT_EQ(ev[0]->from, "free play");
  EXPECT_NE(ev[0]->to, "free play");
  EXPECT_NEAR(ev[0]->t, tc, 1e-9);
  const auto &t = series(r, "t_s"), &w1 = series(r, "pinion.velocity_rad_s"), &w2 = series(r, "wheel.velocity_rad_s");
  for (size_t k = 0; k < t.size() && t[k] < tc; ++k) {
    EXPECT_NEAR(w1[k], -1.0 + 100.0 * t[k], 1e-9) << t[k];
    EXPECT_NEAR(w2[k], t[k] > 0.05 ? t[k] - 0.05 : 0.0, 1e-9) << t[k];
  }
}

// Claim: a mesh without backlash at rest starts on the + flank (τ = 0 reads as +, as a speed at 0
// does), so a load that turns τ negative is an event. Pinion J₁ = 0.01, wheel J₂ = 0.5 kg·m², i = 3,
// c = 2e4 N·m/rad, η = 1, at rest; a step of M = 5 N·m on the wheel at t_s = 0.1 s. Then
// Δ'' = −Ω² Δ − i M/J₂ (Ω² = c (1/J₁ + i²/J₂)), Δ = −(i M/(J₂ Ω²)) (1 − cos Ω(t − t_s)) ≤ 0: τ = c Δ
// turns negative at t_s, the mesh's first event (the start's mode, the − flank by its number 0, hid
// it: campaign gear-mesh seed 1 model 77).
TEST_P(Mesh, AMeshAtRestStartsOnThePlusFlank) {
  const double i = 3.0, M = 5.0, W = omega_mesh(2e4, i), A = i * M / (0.5 * W * W);
  const Model m = mesh_model("ratio: 3, stiffness: 2e4 N*m/rad",
                             "loads:\n  lift: {type: step, body: wheel, value: 5 N*m, time: 0.1 s}\n", 0.11, 1e-4, GetParam());
  const SimulationResult r = simulate(m);
  std::vector<const ModeEvent*> ev;
  for (const ModeEvent& e : r.hybrid.events)
    if (e.element == "mesh") ev.push_back(&e);
  ASSERT_GE(ev.size(), 2u);
  EXPECT_EQ(ev[0]->kind, "initial");
  EXPECT_EQ(ev[0]->to.rfind("flank+", 0), 0u) << ev[0]->to;
  EXPECT_NEAR(ev[1]->t, 0.1, 1e-9);
  EXPECT_EQ(ev[1]->to.rfind("flank-", 0), 0u) << ev[1]->to;
  const auto &t = series(r, "t_s"), &D = series(r, "mesh.deflection_rad");
  for (size_t k = 0; k < t.size(); ++k)
    EXPECT_NEAR(D[k], t[k] < 0.1 ? 0.0 : -A * (1.0 - std::cos(W * (t[k] - 0.1))), 1e-6 * A) << t[k];
}

// Claim: in steady motion the wheel gets η i times the pinion's torque. A constant 10 N·m on the
// pinion, a damper D = 5 N·m·s/rad from the wheel to the ground, i = 3, η = 0.9 (the pinion
// drives): τ = 10 N·m, the wheel's torque η i τ = 27 N·m = D ω₂, so ω₂ = 5.4 rad/s, ω₁ = i ω₂ = 16.2
// rad/s, and the loss (1 − η) τ i ω₂ = 16.2 W = 10·16.2 − 5·5.4² (input less output). From rest the
// time constant is about (J₂ + i² J₁/η)/D ≈ 0.12 s: at 3 s the transient is below e⁻²⁴.
TEST_P(Mesh, SteadyTransmissionWithEfficiency) {
  const Model m = mesh_model("ratio: 3, stiffness: 2e4 N*m/rad, damping: 2 N*m*s/rad, backlash: 0.001 rad, efficiency: 0.9",
                             "  drag: {type: damper, between: [wheel, ground], damping: 5 N*m*s/rad}\n"
                             "loads:\n  drive: {type: constant, body: pinion, value: 10 N*m}\n",
                             3.0, 0.01, GetParam());
  const SimulationResult r = simulate(m);
  EXPECT_NEAR(series(r, "wheel.velocity_rad_s").back(), 5.4, 1e-7);
  EXPECT_NEAR(series(r, "pinion.velocity_rad_s").back(), 16.2, 1e-7);
  EXPECT_NEAR(series(r, "mesh.torque_N_m").back(), -10.0, 1e-7);
  EXPECT_NEAR(series(r, "mesh.wheel_torque_N_m").back(), 27.0, 1e-7);
  EXPECT_NEAR(series(r, "mesh.heat_power_W").back(), 16.2, 1e-6);
  EXPECT_NEAR(series(r, "mesh.deflection_rad").back(), 0.0005 + 10.0 / 2e4, 1e-10);  // on the + flank: b/2 + τ/c
}

// Claim: the energy books close with the mesh's teeth as elastic energy and its damping and
// efficiency loss as heat, driven back and forth (a sine torque reverses the power flow, the
// backlash opens and closes): the books' residual is below 1e-6 of the energy turned over; the
// damping loss (the integral of its heat power column: trapezoids on 0.1 ms rows, within 1e-3) plus
// the release loss (the teeth's energy left when a contact ends off the flank, its damper pulling)
// is the mesh's heat column, the only dissipating element.
TEST_P(Mesh, EnergyBalanceLossIsHeat) {
  Model m = mesh_model("ratio: 3, stiffness: 2e4 N*m/rad, damping: 2 N*m*s/rad, backlash: 0.01 rad, efficiency: 0.8",
                       "loads:\n  drive: {type: sine, body: pinion, amplitude: 10 N*m, frequency: 5 Hz}\n"
                       "  brake: {type: sine, body: wheel, amplitude: 20 N*m, frequency: 3 Hz}\n",
                       0.6, 1e-4, GetParam());
  SimulateOptions o;
  o.event_driven = true;
  const SimulationResult r = simulate(m, o, output_selection({"heat"}));
  const EnergyBalance& e = r.hybrid.energy;
  const auto &t = series(r, "t_s"), &P = series(r, "mesh.heat_power_W"), &Q = series(r, "mesh.heat_J");
  double trapz = 0.0, lo = 0.0;
  for (size_t k = 1; k < t.size(); ++k) trapz += 0.5 * (P[k] + P[k - 1]) * (t[k] - t[k - 1]);
  for (double p : P) lo = std::min(lo, p);
  EXPECT_GT(e.damping_loss, 0.1);
  // Two quadratures of the same power (the books' state, the heat group's): within 1e-8 (bdf 3.7e-9).
  EXPECT_NEAR(e.damping_loss + e.release_loss, Q.back(), 1e-8 * std::max(1.0, Q.back()));
  EXPECT_GT(e.release_loss, 0.0);  // contacts ended off the flank, the damper pulling
  EXPECT_NEAR(trapz, e.damping_loss, 1e-3 * e.damping_loss);
  EXPECT_LT(std::abs(e.residual()), 1e-6 * (std::abs(e.source_work) + e.damping_loss));
  EXPECT_GE(lo, 0.0) << "the loss is never negative";
  int closings = 0;
  for (const ModeEvent& ev : r.hybrid.events) closings += ev.element == "mesh" && ev.from == "free play";
  EXPECT_GT(closings, 2);
}

// Claim: the audit's invariants of the mesh can fail: a torque inside the backlash (|Δ| < b/2) is
// mesh.free_play, a negative heat power mesh.loss; the law's own values pass.
TEST(MeshAudit, InvariantsFailOnViolations) {
  GearMesh g;
  g.i = 3.0, g.c = 2e4, g.d = 2.0, g.b = 0.02, g.eta = 0.9;
  ElementMotion b;
  b.n = 2;
  b.q[0] = 0.003, b.q[1] = 0.0, b.v[0] = 1.0, b.v[1] = 0.2;  // Δ = 0.003 inside ±0.01
  const int free = GearMesh::mode_of(GapMode::open, 1, 1);
  double M[2];
  g.forces(0.0, b, nullptr, free, M);
  EXPECT_EQ(M[0], 0.0);
  EXPECT_EQ(g.violated(0.0, b, nullptr, free, M, 0.0, 1e-12), "");
  const double bad[2] = {-1.0, 3.0};
  EXPECT_EQ(g.violated(0.0, b, nullptr, free, bad, 0.0, 1e-12).rfind("mesh.free_play|", 0), 0u);
  b.q[0] = 0.02;  // Δ = 0.02 on the + flank, the pinion drives
  const int fwd = GearMesh::mode_of(GapMode::closed_pos, 1, 1);
  g.forces(0.0, b, nullptr, fwd, M);
  const double heat = g.heat_power(0.0, b, nullptr, fwd);
  EXPECT_GT(heat, 0.0);
  EXPECT_EQ(g.violated(0.0, b, nullptr, fwd, M, heat, 1e-12), "");
  EXPECT_EQ(g.violated(0.0, b, nullptr, fwd, M, -1.0, 1e-12).rfind("mesh.loss|", 0), 0u);
  // 100 N·m more on the pinion at ω₁ = 1 rad/s: the bodies would gain 100 W beyond the heat of
  // 12.37 W (τ = 200.8 N·m: loss 0.1·200.8·3·0.2, damping 0.8·0.4), more than the teeth release.
  const double gain[2] = {M[0] + 100.0, M[1]};
  EXPECT_EQ(g.violated(0.0, b, nullptr, fwd, gain, heat, 1e-12).rfind("mesh.loss|", 0), 0u);
}

// Claim: base radii give the same mesh at the pinion: c = c_lin r_p², d = d_lin r_p², b = b_lin/r_p,
// i = r_w/r_p (r_p = 0.05 m, r_w = 0.15 m, 8e6 N/m → 2e4 N·m/rad, 1e-4 m → 2e-3 rad).
TEST(MeshCompile, BaseRadiiAreTheLineOfAction) {
  const Model m = test::model_text("bodies:\n  p: {inertia: 1}\n  w: {inertia: 1}\nlinks:\n  g: {type: gear-mesh, between: [p, w], "
                                   "pinion_radius: 50 mm, wheel_radius: 150 mm, stiffness: 8e6 N/m, damping: 400 N*s/m, "
                                   "backlash: 0.1 mm}\n");
  ASSERT_EQ(m.drives.size(), 1u);
  const auto& g = dynamic_cast<const GearMesh&>(*m.drives[0].law);
  EXPECT_DOUBLE_EQ(g.i, 3.0);
  EXPECT_NEAR(g.c, 2e4, 1e-9);
  EXPECT_NEAR(g.d, 1.0, 1e-12);
  EXPECT_NEAR(g.b, 2e-3, 1e-15);
  EXPECT_EQ(m.drives[0].others, std::vector<int>{1});
}

// Claim: every bad field of a mesh is an error at its place naming it, and nothing else.
TEST(MeshCompile, BadFieldsAreLocated) {
  auto errors_of = [](const std::string& fields) {
    return test::compile_errors("bodies:\n  p: {inertia: 1}\n  w: {inertia: 1}\n  x: {type: translational, mass: 1}\n"
                                "links:\n  g: {type: gear-mesh, " + fields + "}\n",
                                "bad.yaml");
  };
  EXPECT_EQ(errors_of("between: [p, w], ratio: 3, stiffness: 1e4 N*m/rad"), "");
  struct Case {
    std::string fields, want;
  };
  const Case cases[] = {
      {"between: [p, w], ratio: 3", "bad.yaml:6:6: error: link 'g': missing field 'stiffness'"},
      {"between: [p, w], ratio: 3, stiffness: 1e4 N/m", "field 'stiffness': expected"},
      {"between: [p, w], ratio: 3, stiffness: 1e4 N*m/rad, efficiency: 1.2",
       "bad.yaml:6:87: error: link 'g': field 'efficiency' must be in (0, 1], got 1.2"},
      {"between: [p, w], ratio: 3, stiffness: 1e4 N*m/rad, backlash: -1 rad", "field 'backlash' must be zero or positive"},
      {"between: [p, w], ratio: 3, pinion_radius: 1 cm, wheel_radius: 3 cm, stiffness: 1e6 N/m",
       "give either 'ratio' or the base radii"},
      {"between: [p, q], ratio: 3, stiffness: 1e4 N*m/rad", "bad.yaml:6:37: error: link 'g': unknown body 'q'"},
      {"between: [p, x], ratio: 3, stiffness: 1e4 N*m/rad", "joins two bodies of one kind"},
      {"between: [p, w], ratio: 3, stiffness: 1e4 N*m/rad, teeth: 20", "unknown field 'teeth'"},
  };
  for (const Case& c : cases) {
    const std::string got = errors_of(c.fields);
    EXPECT_NE(got.find(c.want), std::string::npos) << c.fields << "\n--- want: " << c.want << "\n--- got:\n" << got;
    EXPECT_EQ(std::count(got.begin(), got.end(), '\n'), 0) << got;
  }
  EXPECT_NE(test::compile_errors("bodies:\n  p: {inertia: 1}\ndrives:\n  g: {type: gear-mesh, body: p}\n", "hint.yaml")
                .find("type 'gear-mesh' is not a kind of drives; a gear-mesh goes under 'links:'"),
            std::string::npos);
}


// ---- the held flank (elements/gear_mesh.hpp "Held flank") ----

/// A pinion at a prescribed 1 rad/s from φ₁(0) = Δ₀ = 0.01 rad and a wheel J₂ = 0.5 kg·m² at rest
/// through a mesh i = 2, c = 1000 N·m/rad, η = 0.8 (no backlash, no damping); `wheel` continues the
/// model (loads, contacts on the wheel). While the wheel rests, τ = c (Δ₀ + t) = 10 + 1000 t, and
/// the pinion feeds the teeth (T₁ ω₁ = −τ < 0): the wheel's locking range is
/// [η i τ, i τ] = [16 + 1600 t, 20 + 2000 t] N·m.
Model held_wheel_model(const std::string& wheel, double t_end, IntegratorChoice integ) {
  Model m = test::model_text(
      "bodies:\n  pinion: {inertia: 0.01 kg*m^2, position: 0.01 rad, motion: {speed: 1 rad/s}}\n"
      "  wheel: {inertia: 0.5 kg*m^2}\nlinks:\n  mesh: {type: gear-mesh, between: [pinion, wheel], ratio: 2, "
      "stiffness: 1000 N*m/rad, efficiency: 0.8}\n" +
          wheel + "simulation: {t_end: " + std::to_string(t_end) + " s, dt_out: 1e-4 s, rtol: 1e-10, atol: 1e-12}\n",
      "held.yaml");
  m.simulation.integrator = integ;
  return m;
}

/// The mesh's switches (kind "mesh") as (t, from, to).
std::vector<ModeEvent> mesh_switches(const SimulationResult& r) {
  std::vector<ModeEvent> out;
  for (const ModeEvent& e : r.hybrid.events)
    if (e.element == "mesh" && e.kind != "initial") out.push_back(e);
  return out;
}

// Claim: a wheel at rest whose load lies inside the mesh's locking range is held — it stays exactly
// at rest and the mesh carries exactly its load — and it leaves rest, driven, where the range's
// lower bound η i τ passes the load. Derivation: load −18 N·m on the wheel; held while
// 16 + 1600 t ≤ 18 ≤ 20 + 2000 t, so until t₂ = 2/1600 = 1.25e-3 s the wheel torque is 18 N·m and
// ω₂ = 0. After t₂ the wheel is driven (η on its side): J₂ x'' = η i c (Δ₀ + t − i x) − 18, i.e.
// x'' + ω² x = 3200 (t − t₂) with ω² = η i² c/J₂ = 6400 s⁻², x(t₂) = x'(t₂) = 0:
// x = ½ s − (1/(2ω)) sin ω s, ω₂ = ½ (1 − cos ω s), s = t − t₂ (≥ 0: no reversal before t_end).
TEST_P(Mesh, HoldsALoadInsideItsLockingRangeAndReleasesAtItsLowerBound) {
  const Model m = held_wheel_model("loads:\n  L: {type: constant, body: wheel, value: -18 N*m}\n", 0.02, GetParam());
  const SimulationResult r = simulate(m);
  const double t2 = 1.25e-3, w = 80.0;
  const std::vector<ModeEvent> ev = mesh_switches(r);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_NEAR(ev[0].t, t2, 1e-9);
  EXPECT_EQ(ev[0].from, "flank+/wheel held");
  EXPECT_EQ(ev[0].to, "flank+/pinion drives");
  const auto &t = series(r, "t_s"), &w2 = series(r, "wheel.velocity_rad_s"), &M2 = series(r, "mesh.wheel_torque_N_m");
  size_t held = 0;
  for (size_t k = 0; k < t.size(); ++k) {
    if (t[k] < t2) {
      EXPECT_EQ(w2[k], 0.0) << t[k];
      EXPECT_NEAR(M2[k], 18.0, 1e-9) << t[k];
      ++held;
    } else {
      const double s = t[k] - t2;
      EXPECT_NEAR(w2[k], 0.5 * (1.0 - std::cos(w * s)), 1e-7) << t[k];
    }
  }
  EXPECT_EQ(held, 13u);  // the rows 0 … 1.2e-3 s
}

// Claim: a held wheel whose load grows past the range's upper bound i τ leaves rest backwards, its
// torque then i τ on both sides (it feeds the teeth with the pinion: no power passes). Derivation:
// load −(18 + 4000 t) N·m (a constant and a ramp); held while 18 + 4000 t ≤ 20 + 2000 t, until
// t_r = 1e-3 s; then J₂ x'' = i c (Δ₀ + t − i x) − 18 − 4000 t, x'' + ω² x = −4000 (t − t_r) with
// ω² = i² c/J₂ = 8000 s⁻²: ω₂ = −½ (1 − cos ω s), s = t − t_r.
TEST_P(Mesh, ReleasesWhereTheLoadPassesTheUpperBoundOfItsRange) {
  const Model m = held_wheel_model(
      "loads:\n  L: {type: constant, body: wheel, value: -18 N*m}\n"
      "  R: {type: ramp, body: wheel, value: -40 N*m, end: 0.01 s}\n",
      0.01, GetParam());
  const SimulationResult r = simulate(m);
  const double tr = 1e-3, w = std::sqrt(8000.0);
  const std::vector<ModeEvent> ev = mesh_switches(r);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_NEAR(ev[0].t, tr, 1e-9);
  EXPECT_EQ(ev[0].from, "flank+/wheel held");
  EXPECT_EQ(ev[0].to, "flank+/no transmission");
  const auto &t = series(r, "t_s"), &w2 = series(r, "wheel.velocity_rad_s"), &M2 = series(r, "mesh.wheel_torque_N_m");
  for (size_t k = 0; k < t.size(); ++k) {
    if (t[k] < tr) {
      EXPECT_EQ(w2[k], 0.0) << t[k];
      EXPECT_NEAR(M2[k], 18.0 + 4000.0 * t[k], 1e-9) << t[k];
    } else {
      EXPECT_NEAR(w2[k], -0.5 * (1.0 - std::cos(w * (t[k] - tr))), 1e-7) << t[k];
    }
  }
}

// Claim: a contact stuck on a held body carries what the mesh's range does not (the mesh holds what
// its range allows), and the body leaves rest where the contact breaks away. Derivation: load
// −24 N·m and a contact F_s = 5, F_k = 4 N·m on the wheel; the mesh takes clamp(24, 16 + 1600 t,
// 20 + 2000 t): 20 + 2000 t until 2e-3 s, then 24 until 5e-3 s, then 16 + 1600 t; the contact the
// rest, λ = −24 + M (λ = the free forces on the resting wheel, the contact's load on it −λ): −4 +
// 2000 t, 0, 1600 t − 8, which reaches F_s at t_b = 13/1600 = 8.125e-3 s: the contact slips (+) and
// the mesh lets the wheel go, driven.
TEST_P(Mesh, AContactStuckOnAHeldBodyCarriesWhatTheRangeDoesNot) {
  const Model m = held_wheel_model(
      "loads:\n  L: {type: constant, body: wheel, value: -24 N*m}\n"
      "contacts:\n  f: {between: [wheel, ground], static: 5 N*m, kinetic: 4 N*m}\n",
      0.01, GetParam());
  const SimulationResult r = simulate(m);
  const double tb = 13.0 / 1600.0;
  double slip = -1.0;
  for (const ModeEvent& e : r.hybrid.events)
    if (e.element == "f" && e.kind == "slip") slip = e.t;
  EXPECT_NEAR(slip, tb, 1e-9);
  const std::vector<ModeEvent> ev = mesh_switches(r);
  ASSERT_EQ(ev.size(), 1u);
  EXPECT_NEAR(ev[0].t, tb, 1e-9);
  EXPECT_EQ(ev[0].from, "flank+/wheel held");
  EXPECT_EQ(ev[0].to, "flank+/pinion drives");
  const auto &t = series(r, "t_s"), &w2 = series(r, "wheel.velocity_rad_s"), &M2 = series(r, "mesh.wheel_torque_N_m");
  const auto& F = series(r, "f.force_N_m");
  for (size_t k = 0; k < t.size() && t[k] < tb; ++k) {
    const double M = std::clamp(24.0, 16.0 + 1600.0 * t[k], 20.0 + 2000.0 * t[k]);
    EXPECT_EQ(w2[k], 0.0) << t[k];
    EXPECT_NEAR(M2[k], M, 1e-9) << t[k];
    EXPECT_NEAR(F[k], -24.0 + M, 1e-9) << t[k];
  }
  EXPECT_GT(w2.back(), 0.0);
}

}  // namespace MACHDYN_UNITY_ID
}  // namespace machdyn
