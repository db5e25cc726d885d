// A rope wound on a drum with n falls (elements/link.hpp "Rope wound on a drum", `type: rope` with
// `length`, `EA` / `elastic_modulus` + `area`, `falls`): the Jacobian and the load rate against finite
// differences, a hoisting run against an RK4 integration written here, the static stretch, the
// hook's frequency and the slack rope's tightening time against closed forms, on both integrators.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>
#include <Eigen/Core>
#include <gtest/gtest.h>

#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/analysis/equilibrium.hpp"
#include "machdyn/analysis/extra_outputs.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/elements/contact.hpp"
#include "machdyn/elements/hold_allowance.hpp"
#include "machdyn/elements/link.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "support/models.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::model_of;

using test::series;


class Rope : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, Rope, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

// The hoist of these tests: drum R = 0.25 m (ratio 1/R = 4 rad/m), n = 2 falls, so i = n/R = 8 rad/m
// and s = 1/i = 0.125 m of hook travel per radian; E A = 2e7 N, fall length L_f0 = 10 m, so
// c0 = n E A / L_f0 = 4e6 N/m at the hook; hook mass 2 t.
constexpr double kS = 0.125, kEA = 2e7, kL0 = 10.0, kN = 2.0, kMass = 2000.0, kG = 9.81, kI = 50.0;

std::string hoist(const std::string& drum, const std::string& hook, const std::string& rope_extra,
                  const std::string& rest) {
  return "gravity: 9.81 m/s^2\nbodies:\n  drum: {inertia: 50 kg*m^2" + drum +
         "}\n  hook: {type: translational, mass: 2000 kg, vertical: up" + hook +
         "}\nlinks:\n  rope: {type: rope, between: [drum, hook], ratio: 4 rad/m, falls: 2, EA: 2e7 N, length: 10 m" +
         rope_extra + "}\n" + rest;
}

// Claim: the analytic Jacobian of a winding rope (the second derivatives of V = ½ c(q_a) e² and the
// damper, elements/link.hpp) equals central differences of the right-hand side, for the linear and
// the elasto-backlash flank law (on and off its cap); the load rate dF/dt equals the difference
// quotient of F along the motion. A state with a loaded rope (e = 12 mm) and a drum 2 rad from its
// reference (L_f = 9.75 m): every c′, c″ term is in play.
TEST(RopeJacobian, MatchesFiniteDifferences) {
  for (const char* law : {"linear", "elasto-backlash"}) {
    for (double hook_v : {0.2, -3.0}) {  // capped law: off the cap (ė small) and on it (d ė > c e)
      const Model m = model_of(hoist("", "", std::string(", damping: 2e5 N*s/m, flank_law: ") + law, ""));
      DriveSystem sys(m, false);
      sys.set_gap_mode(0, GapMode::closed_pos);
      const int N = sys.size();
      std::vector<double> y = {2.0, kS * 2.0 - 0.012, 3.0, hook_v};
      ASSERT_EQ(N, 4);
      Eigen::MatrixXd J = Eigen::MatrixXd::Zero(N, N), D(N, N);
      sys.jacobian(0.0, y.data(), J);
      std::vector<double> yp, ym, fp(4), fm(4);
      for (int j = 0; j < N; ++j) {
        const double h = 1e-7 * (1.0 + std::abs(y[static_cast<size_t>(j)]));
        yp = y, ym = y;
        yp[static_cast<size_t>(j)] += h, ym[static_cast<size_t>(j)] -= h;
        sys.rhs(0.0, yp.data(), fp.data());
        sys.rhs(0.0, ym.data(), fm.data());
        for (int i = 0; i < N; ++i) D(i, j) = (fp[static_cast<size_t>(i)] - fm[static_cast<size_t>(i)]) / (2 * h);
      }
      const double scale = J.cwiseAbs().maxCoeff();
      EXPECT_LT((J - D).cwiseAbs().maxCoeff(), 1e-7 * scale) << law << " v " << hook_v << "\nJ\n" << J << "\nD\n" << D;
      // The winding terms are really there: ∂(drum acc)/∂q_a differs from the constant-c value −c s²/I.
      const double c = 2 * kEA / (kL0 - 2.0 * kS);
      EXPECT_GT(std::abs(J(2, 0) + c * kS * kS / kI), 1e-3 * c * kS * kS / kI) << law;
      // dF/dt along the motion: F(y + h y′) − F(y − h y′) over 2h.
      std::vector<double> dy(4);
      sys.rhs(0.0, y.data(), dy.data());
      const double h = 1e-7;
      for (int i = 0; i < 4; ++i) yp[static_cast<size_t>(i)] = y[static_cast<size_t>(i)] + h * dy[static_cast<size_t>(i)];
      for (int i = 0; i < 4; ++i) ym[static_cast<size_t>(i)] = y[static_cast<size_t>(i)] - h * dy[static_cast<size_t>(i)];
      const double fd = (sys.link_load(0, yp.data()) - sys.link_load(0, ym.data())) / (2 * h);
      EXPECT_NEAR(sys.link_load_rate(0, y.data(), dy.data()), fd, 1e-6 * std::abs(fd)) << law << " v " << hook_v;
      EXPECT_TRUE(sys.link_rate_reads_state(0));
    }
  }
}

// Claim: the law is the gradient of its energy. With the rope taut, the generalized forces of the
// link (apply_at: −F s − ½ c′ e² on the drum, +F on the hook; no damper) equal −∂V/∂q of the stored
// energy V = ½ c(q_a) e² (elastic_energy) by central differences, at drum positions on both sides of
// the reference; the hook load is n E A e / L_f and the winding term ½ c′ e² = ½ T ε R (T = F/n,
// ε = T/(E A), R = n s); below L_min = 1e-3 L_f0 the length is held and the stiffness with it.
TEST(RopeLaw, ForcesAreMinusTheGradientOfTheStoredEnergy) {
  const Model m = model_of(hoist("", "", "", ""));
  const LinkLaw k = LinkLaw::of(m, m.links[0]);
  ASSERT_TRUE(k.winding);
  for (double qa : {-5.0, 0.0, 30.0}) {
    const double e = 0.01, x = kS * qa - e, Lf = kL0 - kS * qa;
    double q[2] = {qa, x}, v[2] = {0.0, 0.0}, f[2] = {0.0, 0.0};
    const double F = k.apply_at(q, v, GapMode::closed_pos, f);
    EXPECT_NEAR(F, kN * kEA * e / Lf, 1e-12 * F);
    const double T = F / kN, eps = T / kEA, R = kN * kS;
    EXPECT_NEAR(-f[0] - F * kS, 0.5 * T * eps * R, 1e-9 * 0.5 * T * eps * R);
    for (int j = 0; j < 2; ++j) {
      const double h = 1e-6 * (1.0 + std::abs(q[j]));
      double qp[2] = {q[0], q[1]}, qm[2] = {q[0], q[1]};
      qp[j] += h, qm[j] -= h;
      auto V = [&](const double* y) { return k.elastic_energy(k.linear(y), GapMode::closed_pos, y[0]); };
      const double dV = (V(qp) - V(qm)) / (2 * h);
      EXPECT_NEAR(f[j], -dV, 1e-7 * std::abs(f[j])) << qa << " " << j;
    }
  }
  const double q_end = (kL0 - 1e-4 * kL0) / kS;  // L_f would be 1e-4 L_f0: held at 1e-3 L_f0
  EXPECT_DOUBLE_EQ(k.free_length(q_end), 1e-3 * kL0);
  EXPECT_DOUBLE_EQ(k.stiffness(q_end), kN * kEA / (1e-3 * kL0));
  EXPECT_EQ(k.stiffness_slope(q_end), 0.0);
}

// Claim: hoisting. A constant torque M0 = 2600 N·m on the drum (above the static m g s = 2452.5 N·m)
// winds the rope in from L_f = 10 m while the hook, started off its static stretch, oscillates on the
// stiffening rope. The run equals an RK4 integration (h = 2 µs) of the same equations written here:
//   e = s q_a − x,  L_f = L_f0 − s q_a,  c = n E A / L_f,  c′ = c s / L_f,  F = c e + d (s ω − v),
//   I ω′ = M0 − F s − ½ c′ e²,   m v′ = F − m g,
// (V = ½ c e² with c(q_a); elements/link.hpp) to 2e-8 m in the hook's position and 1e-6 m g in the
// hook load; the energy books balance (W = ΔT + ΔV + losses, V = ½ c(q_a) e²) to 1e-7 of M0's work;
// the fall columns hold T = F/n and L_f.
TEST_P(Rope, HoistingMatchesRk4AndBalancesEnergy) {
  Model m = model_of(hoist(", velocity: 8 rad/s", ", position: -4 mm, velocity: 1 m/s", ", damping: 2e3 N*s/m",
                           "loads: {M: {type: constant, body: drum, value: 2600 N*m}}\n"
                           "simulation: {t_end: 2 s, dt_out: 10 ms, rtol: 1e-11, atol: 1e-13}\n"));
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);

  const double M0 = 2600, d = 2e3;
  auto f = [&](const Eigen::Vector4d& z) {  // z = (q_a, x, ω, v)
    const double e = kS * z(0) - z(1), L = kL0 - kS * z(0), c = kN * kEA / L, c1 = c * kS / L;
    const double F = c * e + d * (kS * z(2) - z(3));
    return Eigen::Vector4d(z(2), z(3), (M0 - F * kS - 0.5 * c1 * e * e) / kI, F / kMass - kG);
  };
  auto load = [&](const Eigen::Vector4d& z) {
    const double e = kS * z(0) - z(1), c = kN * kEA / (kL0 - kS * z(0));
    return c * e + d * (kS * z(2) - z(3));
  };
  Eigen::Vector4d z(0.0, -0.004, 8.0, 1.0);
  const double h = 2e-6;
  const auto& t = r.columns[0];
  const auto &x = series(r, "hook.position_m"), &F = series(r, "rope.load_N"), &T = series(r, "rope.fall_tension_N"),
             &Lf = series(r, "rope.fall_length_m"), &qa = series(r, "drum.position_rad");
  double tz = 0.0, worst_x = 0.0, worst_F = 0.0, Fmin = HUGE_VAL;
  for (size_t k = 0; k < t.size(); ++k) {
    const int steps = static_cast<int>(std::lround((t[k] - tz) / h));
    for (int i = 0; i < steps; ++i) {
      const Eigen::Vector4d k1 = f(z), k2 = f(z + 0.5 * h * k1), k3 = f(z + 0.5 * h * k2), k4 = f(z + h * k3);
      z += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
      Fmin = std::min(Fmin, load(z));
    }
    tz += steps * h;
    ASSERT_NEAR(tz, t[k], 1e-12);
    worst_x = std::max(worst_x, std::abs(x[k] - z(1)));
    worst_F = std::max(worst_F, std::abs(F[k] - load(z)));
    EXPECT_NEAR(T[k], F[k] / kN, 1e-12 * std::abs(F[k]));
    EXPECT_NEAR(Lf[k], kL0 - kS * qa[k], 1e-12 * kL0);
  }
  ASSERT_GT(Fmin, 0.0);                   // taut throughout: one mode, the reference is valid
  EXPECT_LT(Lf.back(), 0.8 * kL0);        // really wound in (c up by a quarter or more)
  EXPECT_LT(worst_x, 2e-8) << worst_x;
  EXPECT_LT(worst_F, 1e-6 * kMass * kG) << worst_F;
  const EnergyBalance& E = r.hybrid.energy;
  const double work_M = M0 * qa.back();  // the drum torque's work, the scale of the books
  EXPECT_LT(std::abs(E.residual()), 1e-7 * work_M) << E.residual() << " of " << work_M;
  EXPECT_GT(E.damping_loss, 0.0);
}

// Claim (statics, n falls): a load m hanging on n = 4 falls from a braked drum stretches each fall by
// ε L_f with ε = T/(E A), T = m g / n, so the hook sinks by e = ε L_f = m g L_f / (n E A)
// = m g L / (n² E A) (L = n L_f the rope in the falls) below its unstretched position s q_a:
// c_hook = n E A / L_f. E = 1e11 Pa, A = 2.5e-4 m² (E A = 2.5e7 N), L_f = 15 m at the drum's 3 rad,
// R = 0.25 m: s = R/n = 1/16 m/rad. `initial: equilibrium` finds it to 1e-12; the run stays there
// (hook load m g, fall tension m g / n).
TEST_P(Rope, HangingLoadOnFourFallsStretchesByMgLOverN2EA) {
  Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies:
  drum: {inertia: 50 kg*m^2, position: 3 rad}
  hook: {type: translational, mass: 12 t, vertical: up}
links:
  rope: {type: rope, between: [drum, hook], ratio: 4 rad/m, falls: 4, elastic_modulus: 1e11 Pa, area: 2.5e-4 m^2,
         length: 15 m, damping: 1e3 N*s/m}
brakes: {hold: {body: drum, holding: 1e5 N*m}}
simulation: {t_end: 0.2 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-13, initial: equilibrium}
)");
  m.simulation.integrator = GetParam();
  const double mg = 12000 * kG, n = 4, EA = 1e11 * 2.5e-4, Lf = 15, s = 0.25 / n;
  const double e = mg * (n * Lf) / (n * n * EA), x = s * 3.0 - e;
  const EquilibriumStart st = static_equilibrium(m);
  EXPECT_NEAR(st.q0[0], 3.0, 1e-15);
  EXPECT_NEAR(st.q0[1], x, 1e-12 * std::abs(x));
  EXPECT_NEAR(e, mg / (n * EA / Lf), 1e-15);  // the same as m g / c_hook
  const SimulationResult r = simulate(m);
  EXPECT_NEAR(r.links[0].max, mg, 1e-9 * mg);
  EXPECT_NEAR(r.links[0].min, mg, 1e-9 * mg);
  EXPECT_NEAR(series(r, "rope.fall_tension_N").back(), mg / n, 1e-9 * mg / n);
}

// Claim: the hook's frequency on the rope. Drum I and hook m joined by the rope (taut, unloaded at
// q0): K = c [s², −s; −s, 1], M = diag(I, m), one rigid motion and ω² = c (1/m + s²/I) with
// c = n E A / L_f0; halving the length doubles ω². With the drum held (I → ∞) this is sqrt(c/m).
TEST(RopeModes, HookFrequencyIsSqrtOfNEAOverLm) {
  for (double L : {10.0, 5.0}) {
    const Model m = model_of("bodies:\n  drum: {inertia: 50 kg*m^2, position: 7 rad}\n"
                             "  hook: {type: translational, mass: 2000 kg, position: 0.875 m}\nlinks:\n"
                             "  rope: {type: rope, between: [drum, hook], ratio: 4 rad/m, falls: 2, EA: 2e7 N, length: " +
                             std::to_string(L) + " m}\n");
    const Modes md = compute_modes(m);
    ASSERT_EQ(md.omega.size(), 1);
    EXPECT_EQ(md.rigid_body_modes, 1);
    const double c = kN * kEA / L, w = std::sqrt(c * (1 / kMass + kS * kS / kI));
    EXPECT_NEAR(md.omega(0), w, 1e-12 * w) << L;
  }
}

// Claim: a slack rope tightens at the closed-form time. The drum turns freely at ω0 = 8 rad/s (no
// load on it while the rope is slack), the hook is thrown up at v0 = 1.5 m/s from x0 = 30 mm and
// falls under gravity. δ(t) = s (ω0 t) − (x0 + v0 t − ½ g t²) reaches the slack δ₊ = 20 mm when
//   ½ g t² + (s ω0 − v0) t − (δ₊ + x0) = 0,  t* = [−(s ω0 − v0) + √((s ω0 − v0)² + 2 g (δ₊ + x0))] / g,
// to 1e-9 relative; the rope then carries load. (The rope has a damper: under the linear flank law
// its load jumps to d δ̇ at contact, which the event locator brackets sharply.)
TEST_P(Rope, SlackRopeTightensAtTheClosedFormTime) {
  Model m = model_of(hoist(", velocity: 8 rad/s", ", position: 30 mm, velocity: 1.5 m/s", ", slack: 20 mm, damping: 2e3 N*s/m",
                           "simulation: {t_end: 0.3 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}\n"));
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const double b = kS * 8.0 - 1.5, t_star = (-b + std::sqrt(b * b + 2 * kG * (0.02 + 0.03))) / kG;
  std::vector<double> closed;
  for (const auto& ev : r.hybrid.events)
    if (ev.element == "rope" && ev.kind == "gap_closed") closed.push_back(ev.t);
  ASSERT_GE(closed.size(), 1u);
  EXPECT_NEAR(closed[0], t_star, 1e-9 * t_star);
  EXPECT_GT(r.links[0].max, kMass * kG);
}

// Claim: a winding rope's damping_power_W (the `power` group) is its damper's F_d δ̇ with the stiffness
// of the current free length. With `flank_law: elasto-backlash` the damper force is capped at the
// spring force, F_d = min(c e, d δ̇), so the stiffness enters: the test takes F_d = F − c(L_f) e from
// the rope's load F, c(L_f) = n E A / L_f with L_f = L_f0 − s q_a computed here from the drum's
// position, e = δ − slack from the deflection columns, and checks the column against F_d δ̇ at every
// row (to 1e-9 of the largest F δ̇). The drum winds 0.5 m of slack in before the rope tightens (L_f =
// 9.5 m and less, c 5 % and more above c0), and the cap holds for a while after contact, so the
// product with the start stiffness c0 = n E A / L_f0 differs from the column by far more than that.
TEST_P(Rope, DampingPowerUsesTheCurrentFreeLength) {
  Model m = model_of(hoist(", velocity: 8 rad/s", "", ", slack: 0.5 m, damping: 2e5 N*s/m, flank_law: elasto-backlash",
                           "loads: {M: {type: constant, body: drum, value: 2600 N*m}}\n"
                           "stops: {floor: {body: hook, min: 0 m}}\n"
                           "simulation: {t_end: 0.6 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}\n"));
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m, {}, output_selection({"deflection", "power"}));
  const auto &qa = series(r, "drum.position_rad"), &delta = series(r, "rope.deflection_m"),
             &rate = series(r, "rope.deflection_rate_m_s"), &F = series(r, "rope.load_N"),
             &P = series(r, "rope.damping_power_W"), &Lf = series(r, "rope.fall_length_m");
  const double slack = 0.5, d = 2e5;
  double scale = 0.0;
  for (size_t k = 0; k < F.size(); ++k) scale = std::max(scale, std::abs(F[k] * rate[k]));
  double worst = 0.0, worst_c0 = 0.0;
  int capped = 0;
  for (size_t k = 0; k < F.size(); ++k) {
    const double L = kL0 - kS * qa[k], c = kN * kEA / L, e = delta[k] - slack;
    EXPECT_NEAR(Lf[k], L, 1e-12 * kL0);
    if (e <= 0.0) {  // slack: no load, no loss
      EXPECT_EQ(F[k], 0.0);
      EXPECT_EQ(P[k], 0.0);
      continue;
    }
    const double Fd = F[k] - c * e;
    worst = std::max(worst, std::abs(P[k] - Fd * rate[k]));
    worst_c0 = std::max(worst_c0, std::abs(P[k] - (F[k] - kN * kEA / kL0 * e) * rate[k]));
    if (Fd < d * rate[k] - 1e-6 * std::abs(d * rate[k])) ++capped;
  }
  ASSERT_GT(scale, 0.0);
  EXPECT_LT(worst, 1e-9 * scale) << worst << " W of " << scale;
  EXPECT_GT(capped, 5);                     // the cap held at several rows
  EXPECT_GT(worst_c0, 1e-3 * scale);        // c0 instead of c(L_f) would fail the check above
  EXPECT_LT(Lf.back(), kL0 - slack);        // wound in past the slack
  std::printf("Rope damping power %s: %.2e W of %.3g W (start stiffness would be off by %.2e W), %d capped rows\n",
              GetParam() == IntegratorChoice::bdf ? "bdf" : "dopri5", worst, scale, worst_c0, capped);
}

// Claim (examples/rope-hoist.yaml): the 12 t load resting on the ground lifts off when its 4-fall
// rope carries its weight: the stop holds while its force m g − F ≥ −ε_h (the hold allowance, the
// resolution of its load: k atol through the rope, elements/hold_allowance.hpp), so the load at the
// release event is F = m g + ε_h (to 1e-9), after the rope tightened; each fall then carries F/4; the energy
// books (V = ½ c(q_a) e²) balance to 1e-6 of the source work; the rope has wound in (L_f < 8 m).
TEST_P(Rope, ExampleLiftsTheLoadWhenTheRopeCarriesItsWeight) {
  Model m = load_model(test::example("rope-hoist.yaml"));
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  double t_tight = -1, t_lift = -1;
  for (const auto& ev : r.hybrid.events) {
    if (ev.element == "rope" && ev.kind == "gap_closed" && t_tight < 0) t_tight = ev.t;
    if (ev.element == "ground" && ev.kind == "slip" && t_lift < 0) t_lift = ev.t;
  }
  ASSERT_GT(t_tight, 0.0);
  ASSERT_GT(t_lift, t_tight);
  ASSERT_FALSE(r.hybrid.slip_phases.empty());
  const double mg = 12000 * 9.81;
  double eps = 0.0;
  for (const auto& c : m.contacts)
    if (c.name == "ground") eps = hold_allowance(ContactLaw::hold_stiffness(c, m), m.simulation.atol);
  EXPECT_GT(eps, 1e-9);
  EXPECT_NEAR(r.hybrid.slip_phases[0].link_start[1], mg + eps, 1e-9 * mg);
  const auto &F = series(r, "rope.load_N"), &T = series(r, "rope.fall_tension_N"), &Lf = series(r, "rope.fall_length_m");
  for (size_t k = 0; k < F.size(); k += 97) EXPECT_NEAR(T[k], F[k] / 4, 1e-12 * mg);
  EXPECT_LT(Lf.back(), 8.0 - 0.1);
  const EnergyBalance& E = r.hybrid.energy;
  EXPECT_LT(std::abs(E.residual()), 1e-6 * E.source_work);  // 100 rtol (the example's default 1e-8)
}

// Claim: the same without a damper (the event function −c (δ − δ₊) beyond the flank is continuous
// with a kink of slopes δ̇ : c δ̇): the tightening time is the closed form above to 1e-9 relative.
TEST_P(Rope, UndampedSlackRopeTightensAtTheClosedFormTime) {
  Model m = model_of(hoist(", velocity: 8 rad/s", ", position: 30 mm, velocity: 1.5 m/s", ", slack: 20 mm",
                           "simulation: {t_end: 0.3 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}\n"));
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const double b = kS * 8.0 - 1.5, t_star = (-b + std::sqrt(b * b + 2 * kG * (0.02 + 0.03))) / kG;
  double closed = -1;
  for (const auto& ev : r.hybrid.events)
    if (ev.element == "rope" && ev.kind == "gap_closed" && closed < 0) closed = ev.t;
  EXPECT_NEAR(closed, t_star, 1e-9 * t_star);
}

std::string error_of(const std::string& yaml) {
  try {
    model_of(yaml);
  } catch (const InputError& e) {
    return e.what();
  }
  return "accepted";
}

// Claim: a rope's length fields are checked, located: `length` without E A, E A without `length`,
// `stiffness` beside `length`, both `EA` and `elastic_modulus`, `falls` without a stiffness, and
// the rope fields on another link type.
TEST(RopeInput, LengthFieldsAreCheckedAndLocated) {
  const std::string head = "bodies:\n  drum: {inertia: 50}\n  hook: {type: translational, mass: 2}\nlinks:\n";
  auto rope = [&](const std::string& f) { return head + "  r: {type: rope, between: [drum, hook], ratio: 4 rad/m, " + f + "}\n"; };
  EXPECT_NE(error_of(rope("length: 10 m")).find("test.yaml:5:"), std::string::npos);
  EXPECT_NE(error_of(rope("length: 10 m")).find("needs"), std::string::npos) << error_of(rope("length: 10 m"));
  EXPECT_NE(error_of(rope("EA: 1e7 N")).find("needs its free 'length'"), std::string::npos) << error_of(rope("EA: 1e7 N"));
  EXPECT_NE(error_of(rope("EA: 1e7 N, length: 10 m, stiffness: 1e6 N/m")).find("give no 'stiffness'"), std::string::npos);
  EXPECT_EQ(error_of(rope("EA: 1e7 N, length: 10 m, stiffness: 1e6 N/m")).find("has no stiffness"), std::string::npos);
  // A rope takes a damper (its hook's, N·s/m).
  EXPECT_EQ(model_of(rope("stiffness: 1e6 N/m, damping: 1e3 N*s/m")).links[0].d, 1e3);
  EXPECT_NE(error_of(rope("EA: 1e7 N, elastic_modulus: 1e11 Pa, area: 1e-4 m^2, length: 10 m")).find("not both"),
            std::string::npos);
  EXPECT_NE(error_of(rope("falls: 4")).find("a rope with 'falls' needs"), std::string::npos) << error_of(rope("falls: 4"));
  EXPECT_NE(error_of(rope("falls: 0, stiffness: 1e6 N/m")).find("falls"), std::string::npos);
  EXPECT_NE(error_of(head + "  r: {type: spring, between: [drum, hook], ratio: 4 rad/m, stiffness: 1e6 N/m, length: 3 m}\n")
                .find("belongs to a rope"),
            std::string::npos);
  // With falls and a stiffness (at the hook) the ratio becomes n/R.
  const Model m = model_of(rope("falls: 3, stiffness: 1e6 N/m"));
  EXPECT_DOUBLE_EQ(m.links[0].ratio, 12.0);
  EXPECT_EQ(m.links[0].EA, 0.0);
}

}  // namespace
}  // namespace machdyn
