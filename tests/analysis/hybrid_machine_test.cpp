// Machines (position-dependent inertia) in the event-driven solver: a crank-slider braked to rest,
// stick/slip of a clutch between a motor and a crank, a gap link to the piston. Checked against
// answers that do not come from the solver: the energy integral by quadrature (stopping angle and
// time), the energy balance, and the smooth solver for a model without events.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <string>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/model/compile.hpp"
#include "machdyn/model/machine.hpp"
#include "support/models.hpp"
#include "support/events.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::integrator_name;

using test::events_of;
using test::column;


// Composite 10-point Gauss–Legendre quadrature of f over [a, b] in `panels` panels.
double gauss(const std::function<double(double)>& f, double a, double b, int panels) {
  static const double x[5] = {0.1488743389816312, 0.4333953941292472, 0.6794095682990244, 0.8650633666889845,
                              0.9739065285171717};
  static const double w[5] = {0.2955242247147529, 0.2692667193099963, 0.2190863625159820, 0.1494513491505806,
                              0.0666713443086881};
  const double h = (b - a) / panels;
  double s = 0;
  for (int p = 0; p < panels; ++p) {
    const double c = a + (p + 0.5) * h, r = 0.5 * h;
    for (int k = 0; k < 5; ++k) s += w[k] * r * (f(c - r * x[k]) + f(c + r * x[k]));
  }
  return s;
}

const std::string kCrank = test::kCrankSliderBody;

// Every claim holds on both integrators (BDF with the finite-difference Jacobian of the machine).
class HybridMachine : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, HybridMachine,
                         ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         integrator_name);

using test::with_integrator;
SimulationResult run(const Model& m, IntegratorChoice ic) { return simulate(with_integrator(m, ic)); }

// Claim: a crank-slider braked from 50 rad/s (braking torque M_b = 30 N·m, a constant gas force
// 500 N on the piston, so Q(φ) = F ds/dφ) stops where the energy integral says,
//   ½ I(φ0) ω0² + ∫_{φ0}^{φs} Q dφ − M_b (φs − φ0) = 0   (first root),
// to 1e-8 rad, at the time t_s = ∫ dφ/ω(φ), ω = √(2E(φ)/I(φ)), to 1e-8 relative (both by
// Gauss–Legendre quadrature here, not by the solver); afterwards it stays exactly at rest, since
// the holding torque 40 N·m exceeds |Q(φs)|.
TEST_P(HybridMachine, CrankBrakedToRestStopsWhereTheEnergyIntegralSays) {
  const std::string yaml = std::string("bodies:") + kCrank +
                           "    piston_force: {against: position, points: [[0, 500 N], [1 m, 500 N]]}\n"
                           "    velocity: 50 rad/s\n"
                           "brakes:\n  B: {body: crank, holding: 40 N*m, braking: 30 N*m}\n"
                           "simulation: {t_end: 0.4 s, dt_out: 1 ms, rtol: 1e-12, atol: 1e-12}\n";
  const Model m = load_model(test::write_temp("crank-brake.yaml", yaml));
  const Machine& mach = *m.bodies[0].machine;
  const double Mb = 30.0, w0 = 50.0, q0 = 0.0;
  double I0, dI;
  mach.inertia(q0, &I0, &dI);
  const auto Q = [&](double q) { return mach.force(q); };
  // E(φ) = T0 + A(φ) − M_b φ; the first root, by bracketing on a fine grid and bisection.
  const auto E = [&](double q) { return 0.5 * I0 * w0 * w0 + gauss(Q, q0, q, 40) - Mb * (q - q0); };
  double lo = q0, hi = q0;
  for (double q = q0 + 0.01;; q += 0.01) {
    if (E(q) < 0) {
      hi = q;
      break;
    }
    lo = q;
    ASSERT_LT(q, 20.0);
  }
  for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
    const double mid = 0.5 * (lo + hi);
    (E(mid) >= 0 ? lo : hi) = mid;
  }
  const double qs = 0.5 * (lo + hi);
  ASSERT_LT(std::abs(Q(qs)), 40.0) << "the brake must hold there";
  // t_s = ∫ dφ/ω with φ = φs − u²: dt = 2u du / ω, regular at u = 0. E near φs as ∫_φ^φs (M_b − Q).
  const auto integrand = [&](double u) {
    if (u == 0.0) return 0.0;  // not a Gauss node
    const double q = qs - u * u;
    const double Eq = gauss([&](double x) { return Mb - Q(x); }, q, qs, 8);
    double I, d;
    mach.inertia(q, &I, &d);
    return 2.0 * u / std::sqrt(2.0 * Eq / I);
  };
  const double ts = gauss(integrand, 0.0, std::sqrt(qs - q0), 200);

  const SimulationResult r = run(m, GetParam());
  const auto stick = events_of(r, "B", "stick");
  ASSERT_EQ(stick.size(), 1u);
  EXPECT_TRUE(events_of(r, "B", "slip").empty());
  EXPECT_NEAR(stick[0].t, ts, 1e-8 * ts) << "stop time";
  const auto& q = r.columns[column(r, "crank.position_rad")];
  const auto& v = r.columns[column(r, "crank.velocity_rad_s")];
  EXPECT_NEAR(q.back(), qs, 1e-8) << "stopping angle";
  // At rest after the stop: every output row after t_s has the same angle and zero speed.
  const auto& t = r.columns[0];
  for (size_t k = 0; k < t.size(); ++k) {
    if (t[k] <= stick[0].t) continue;
    EXPECT_EQ(v[k], 0.0) << "t = " << t[k];
    EXPECT_EQ(q[k], q.back()) << "t = " << t[k];
  }
  // The brake holds the gas torque there: its force column is Q(φs) (λ balances Q).
  EXPECT_NEAR(r.columns[column(r, "B.force_N_m")].back(), Q(qs), 1e-9 * 40.0);
  // The machine series are there in the hybrid path too: I(φ) at the end.
  double Is;
  mach.inertia(qs, &Is, &dI);
  EXPECT_NEAR(r.columns[column(r, "crank.inertia_kg_m2")].back(), Is, 1e-9 * Is);
}

// Claim: a motor driving a crank-slider through a clutch (stick/slip as the crank's inertia and gas
// torques exceed its limit), then a ramped brake on the crank stopping it and holding it while the
// clutch slips: the work of the sources (motor and gas force Q) equals ΔT + friction losses to 1e-8
// of the source work, with T = ½ I_m ω_m² + ½ I(φ) ω².
TEST_P(HybridMachine, ClutchStickSlipAndBrakeKeepTheEnergyBalance) {
  const std::string yaml =
      std::string("bodies:\n  motor: {inertia: 0.3 kg*m^2, velocity: 100 rad/s}") + kCrank +
      "    velocity: 100 rad/s\n"
      "    piston_force: {against: angle, period: 360 deg, points: [[0 deg, 600 N], [20 deg, 250 N], [40 deg, 0 N],"
      " [180 deg, 0 N], [240 deg, 60 N], [290 deg, 200 N], [320 deg, 450 N], [335 deg, 600 N]]}\n"
      "contacts:\n  clutch: {between: [motor, crank], static: 20 N*m, kinetic: 15 N*m}\n"
      "brakes:\n  B: {body: crank, holding: 70 N*m, braking: 60 N*m, time: 0.3 s, ramp: 20 ms}\n"
      "loads:\n  M: {type: motor-linear, body: motor, stall_torque: 100 N*m, no_load_speed: 120 rad/s}\n"
      "simulation: {t_end: 0.6 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}\n";
  const Model m = load_model(test::write_temp("clutch-crank.yaml", yaml));
  const SimulationResult r = run(m, GetParam());
  EXPECT_GE(events_of(r, "clutch", "slip").size(), 2u);
  EXPECT_GE(events_of(r, "clutch", "stick").size(), 2u);
  ASSERT_EQ(events_of(r, "B", "stick").size(), 1u) << "the brake stops the crank";
  EXPECT_GT(events_of(r, "B", "stick")[0].t, 0.3);
  const auto& v = r.columns[column(r, "crank.velocity_rad_s")];
  EXPECT_EQ(v.back(), 0.0) << "held at rest";
  EXPECT_GT(r.columns[column(r, "motor.velocity_rad_s")].back(), 50.0) << "the clutch slips";
  const auto& E = r.hybrid.energy;
  // Kinetic energy at the start from the model, independently of the solver.
  double I0, dI;
  m.bodies[1].machine->inertia(0.0, &I0, &dI);
  EXPECT_NEAR(E.kinetic_start, 0.5 * 0.3 * 1e4 + 0.5 * I0 * 1e4, 1e-12 * E.kinetic_start);
  const double scale = std::max({std::abs(E.source_work), E.kinetic_start, E.friction_loss});
  EXPECT_LT(std::abs(E.residual()), 1e-8 * scale) << "residual " << E.residual() << " of " << scale;
}

// Claim: a link with a gap and damping to the crank's piston (δ = s(φ) − x) drives a slider held by
// ground friction: gap events and stick/slip happen, and the energy balance (source work = ΔT +
// ΔV + friction + damping losses + gap release) holds to 1e-8 of the source work.
TEST_P(HybridMachine, GapLinkToThePistonKeepsTheEnergyBalance) {
  const std::string yaml = std::string("bodies:") + kCrank +
                           "    velocity: 30 rad/s\n"
                           "  slider: {type: translational, mass: 2 kg}\n"
                           "links:\n  rod: {type: spring-damper, between: [crank.piston, slider], stiffness: 1e5 N/m,"
                           " damping: 20 N*s/m, gap: 2 mm, gap_start: 1 mm}\n"
                           "contacts:\n  guide: {between: [slider, ground], static: 200 N, kinetic: 150 N}\n"
                           "loads:\n  drive: {type: constant, body: crank, value: 8 N*m}\n"
                           "simulation: {t_end: 0.5 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-13}\n";
  const Model m = load_model(test::write_temp("crank-gap.yaml", yaml));
  const SimulationResult r = run(m, GetParam());
  EXPECT_GE(events_of(r, "rod", "gap_closed").size(), 2u);
  EXPECT_GE(events_of(r, "rod", "gap_opened").size(), 2u);
  EXPECT_GE(events_of(r, "guide", "stick").size() + events_of(r, "guide", "slip").size(), 2u);
  const auto& E = r.hybrid.energy;
  const double scale = std::max({std::abs(E.source_work), E.kinetic_start, E.friction_loss});
  EXPECT_LT(std::abs(E.residual()), 1e-8 * scale) << "residual " << E.residual() << " of " << scale;
  // The link-load column is F = c (δ − flank) + d δ̇ with δ = s(φ) − x from the model's p(φ).
  const auto& F = r.columns[column(r, "rod.load_N")];
  const auto& gm = r.columns[column(r, "rod.gap_mode")];
  const auto& phi = r.columns[column(r, "crank.position_rad")];
  const auto& w = r.columns[column(r, "crank.velocity_rad_s")];
  const auto& x = r.columns[column(r, "slider.position_m")];
  const auto& vx = r.columns[column(r, "slider.velocity_m_s")];
  for (size_t k = 0; k < F.size(); k += 37) {
    double s, ds, dds;
    m.bodies[0].machine->point(phi[k], &s, &ds, &dds);
    const double delta = s - x[k], flank = gm[k] > 0 ? 0.001 : -0.001;
    const double want = gm[k] == 0 ? 0.0 : 1e5 * (delta - flank) + 20 * (ds * w[k] - vx[k]);
    EXPECT_NEAR(F[k], want, 1e-9 * 1e3) << "row " << k;
  }
}

// Claim: carrying the energy books (SimulateOptions::event_driven: three more states in the step
// control) does not change the solution of a machine beyond the tolerances: the crank-slider
// example with and without them agrees to 1e-8 of the largest value in angle, speed, I(φ) and piston travel at every output row; the acceleration
// series (the right-hand side at states that differ by the integration error, sharpened by the
// gas-force table's kinks) to 1e-7.
TEST_P(HybridMachine, EnergyBooksDoNotChangeTheSolution) {
  const Model m = load_model(test::example("crank-slider.yaml"), {"simulation.t_end=0.2 s"});
  ASSERT_FALSE(m.is_hybrid());
  const SimulationResult smooth = run(m, GetParam());
  SimulateOptions books;
  books.event_driven = true;
  const SimulationResult hyb = simulate(with_integrator(m, GetParam()), books);
  ASSERT_TRUE(hyb.hybrid.active);
  ASSERT_FALSE(smooth.hybrid.active);
  const std::pair<const char*, double> checks[] = {{"crank.position_rad", 1e-8},    {"crank.velocity_rad_s", 1e-8},
                                                    {"crank.inertia_kg_m2", 1e-8},   {"crank.piston_m", 1e-8},
                                                    {"crank.acceleration_rad_s2", 1e-7}};
  for (const auto& [name, tol] : checks) {
    const auto& a = smooth.columns[column(smooth, name)];
    const auto& b = hyb.columns[column(hyb, name)];
    ASSERT_EQ(a.size(), b.size()) << name;
    double scale = 0, worst = 0;
    for (double x : a) scale = std::max(scale, std::abs(x));
    for (size_t k = 0; k < a.size(); ++k) worst = std::max(worst, std::abs(a[k] - b[k]) / scale);
    EXPECT_LT(worst, tol) << name;
    std::printf("%-28s max difference %.2e of its largest value\n", name, worst);
  }
  // The energy books: the drive's and the gas force's work equal ΔT.
  const auto& E = hyb.hybrid.energy;
  EXPECT_LT(std::abs(E.residual()), 1e-8 * E.kinetic_start);
}

}  // namespace
}  // namespace machdyn
