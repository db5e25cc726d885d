// Gear joints (model/compile_joint.hpp): the planetary gear and the ideal gear on a housing body,
// each checked against an answer computed here without the library's engine: closed forms of
// constant-torque motion, a second formulation in reduced coordinates (RK4 written here, or the
// generalized eigenproblem of the reduced mass and stiffness matrices), and for MSL's
// SimpleGearShift a piecewise RK4 of MSL's equations with every switch bisected. Event-driven
// tests run on both integrators.
#include <algorithm>
#include <cstdio>
#include <array>
#include <cmath>
#include <functional>
#include <string>
#include <vector>
#include <Eigen/Eigenvalues>
#include <gtest/gtest.h>

#include "machdyn/analysis/linear_analysis.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/elements/linearize.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::at;
using test::sci;
using test::series;

class Planetary : public ::testing::TestWithParam<IntegratorChoice> {
 protected:
  SimulationResult run(Model m) const {
    m.simulation.integrator = GetParam();
    return simulate(m);
  }
  /// dopri5 reaches the tolerance; BDF (orders ≤ 5, restarted at order 1 after each event) less.
  double tol(double dopri5, double bdf) const { return GetParam() == IntegratorChoice::bdf ? bdf : dopri5; }
};
INSTANTIATE_TEST_SUITE_P(Integrators, Planetary, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

// ---------------------------------------------------------------------------------------------
// Claim: three inertias on a planetary gear under constant torques accelerate uniformly, and the
// gear's torque columns are its constraint torques.
// Derivation: the row is w = (1, z, −(1 + z)) over (sun, ring, carrier); the gear puts −w_j λ on
// member j, so a_j = (M_j − w_j λ)/J_j, and Σ w_j a_j = 0 gives λ = (Σ w_j M_j/J_j)/(Σ w_j²/J_j).
// From rest, φ_j = ½ a_j t² and ω_j = a_j t.
const char* kThreeInertias = R"(
bodies:
  sun: {inertia: 0.5 kg*m^2}
  ring: {inertia: 2 kg*m^2}
  carrier: {inertia: 4 kg*m^2}
links:
  pg: {type: planetary-gear, sun: sun, ring: ring, carrier: carrier, teeth: {sun: 30, ring: 90}, planets: 4}
loads:
  Ms: {type: constant, body: sun, value: 10 N*m}
  Mr: {type: constant, body: ring, value: -3 N*m}
  Mc: {type: constant, body: carrier, value: -5 N*m}
simulation: {t_end: 2 s, dt_out: 10 ms, rtol: 1e-10, atol: 1e-12}
)";

TEST_P(Planetary, ConstantTorquesAccelerateUniformly) {
  const SimulationResult r = run(test::model_text(kThreeInertias));
  const double z = 3.0;  // 90/30
  const std::array<double, 3> J{0.5, 2.0, 4.0}, M{10.0, -3.0, -5.0}, w{1.0, z, -(1.0 + z)};
  double num = 0.0, den = 0.0;
  for (int j = 0; j < 3; ++j) num += w[j] * M[j] / J[j], den += w[j] * w[j] / J[j];
  const double lambda = num / den;
  const std::array<const char*, 3> names{"sun", "ring", "carrier"};
  for (double t : {0.5, 1.0, 2.0})
    for (int j = 0; j < 3; ++j) {
      const double a = (M[j] - w[j] * lambda) / J[j];
      EXPECT_NEAR(at(r, std::string(names[j]) + ".velocity_rad_s", t), a * t, 1e-9 * std::max(1.0, std::abs(a * t)));
      EXPECT_NEAR(at(r, std::string(names[j]) + ".position_rad", t), 0.5 * a * t * t, 1e-9 * std::max(1.0, t * t));
      EXPECT_NEAR(at(r, std::string("pg.torque_") + names[j] + "_N_m", t), -w[j] * lambda, 1e-9 * std::abs(lambda));
    }
  // The kinematic row holds at every output row (the invariant the projection keeps).
  const auto& ws = series(r, "sun.velocity_rad_s");
  const auto& wr = series(r, "ring.velocity_rad_s");
  const auto& wc = series(r, "carrier.velocity_rad_s");
  for (size_t i = 0; i < ws.size(); ++i) EXPECT_NEAR(ws[i] + z * wr[i] - (1 + z) * wc[i], 0.0, 1e-10);
  EXPECT_NEAR(r.hybrid.energy.residual(), 0.0, 1e-9 * r.hybrid.energy.source_work);
}

// ---------------------------------------------------------------------------------------------
// Claim: the natural frequencies of a chain with a planetary gear (constraint row in linearize)
// equal those of the reduced coordinates q = (φ_s, φ_r), φ_c = (φ_s + z φ_r)/(1 + z):
//   T = ½ [J_s ω_s² + J_r ω_r² + J_c ((ω_s + z ω_r)/(1 + z))²],  V = ½ c_s φ_s² + ½ c_c φ_c²,
// solved here as the generalized eigenproblem K x = ω² M x of the 2 × 2 matrices.
TEST(PlanetaryModes, FrequenciesEqualReducedCoordinates) {
  const Model m = test::model_text(R"(
bodies:
  sun: {inertia: 0.5 kg*m^2}
  ring: {inertia: 2 kg*m^2}
  carrier: {inertia: 4 kg*m^2}
links:
  pg: {type: planetary-gear, sun: sun, ring: ring, carrier: carrier, ratio: 2.5}
  cs: {type: spring, between: [sun, ground], stiffness: 1000 N*m/rad}
  cc: {type: spring, between: [carrier, ground], stiffness: 30000 N*m/rad}
)");
  const double z = 2.5, Js = 0.5, Jr = 2.0, Jc = 4.0, cs = 1000.0, cc = 30000.0;
  Eigen::Vector2d dc(1.0 / (1 + z), z / (1 + z));  // ∂φ_c/∂(φ_s, φ_r)
  Eigen::Matrix2d M = Jc * dc * dc.transpose(), K = cc * dc * dc.transpose();
  M(0, 0) += Js, M(1, 1) += Jr, K(0, 0) += cs;
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> es(K, M);
  const TopologyModes tm = analyse_topology(m, initial_topology(m));
  ASSERT_EQ(tm.modes.omega.size(), 2);
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(tm.modes.omega(k), std::sqrt(es.eigenvalues()(k)), 1e-9 * tm.modes.omega(k));
}

// ---------------------------------------------------------------------------------------------
// Claim: an ideal gear whose housing is an elastically mounted body (MSL ElasticBearing's layout,
// with inertia on the output) follows the reduced-coordinate equations.
// Row: (ω_a − ω_h) = i (ω_b − ω_h). Reduced coordinates (φ_a, φ_h), φ_b = (φ_a − φ_h)/i + φ_h:
//   M = J_a e_a e_aᵀ + J_h e_h e_hᵀ + J_b g gᵀ, g = (1/i, 1 − 1/i),
//   f = (M_a(t), 0) + g M_b − (0, c φ_h + d ω_h),
// integrated here by RK4 (h = 1e-4 s) from rest, the torque a ramp 0 → 100 N·m over 5 s.
TEST_P(Planetary, GearOnElasticHousingMatchesReducedCoordinates) {
  const SimulationResult r = run(test::model_text(R"(
bodies:
  shaft: {inertia: 1 kg*m^2}
  housing: {inertia: 5 kg*m^2}
  load: {inertia: 50 kg*m^2}
links:
  gear: {type: ideal-gear, between: [shaft, load], ratio: 3, housing: housing}
  mount: {type: spring-damper, between: [housing, ground], stiffness: 1e5 N*m/rad, damping: 5 N*m*s/rad}
loads:
  torque: {type: ramp, body: shaft, value: 100 N*m, end: 5 s}
  brake: {type: constant, body: load, value: -2 N*m}
simulation: {t_end: 2 s, dt_out: 10 ms, rtol: 1e-10, atol: 1e-12}
)"));
  const double i = 3.0, Ja = 1.0, Jh = 5.0, Jb = 50.0, c = 1e5, d = 5.0;
  const Eigen::Vector2d g(1.0 / i, 1.0 - 1.0 / i);
  Eigen::Matrix2d M = Jb * g * g.transpose();
  M(0, 0) += Ja, M(1, 1) += Jh;
  const Eigen::Matrix2d Minv = M.inverse();
  auto rhs = [&](double t, const Eigen::Vector4d& y) {  // y = (φ_a, φ_h, ω_a, ω_h)
    Eigen::Vector2d f = g * -2.0;
    f(0) += 100.0 * t / 5.0;
    f(1) -= c * y(1) + d * y(3);
    Eigen::Vector4d dy;
    dy << y(2), y(3), Minv * f;
    return dy;
  };
  Eigen::Vector4d y = Eigen::Vector4d::Zero();
  const double h = 1e-4;
  double worst = 0.0;
  for (int k = 0; k < 20000; ++k) {
    const double t = k * h;
    const Eigen::Vector4d k1 = rhs(t, y), k2 = rhs(t + h / 2, y + h / 2 * k1), k3 = rhs(t + h / 2, y + h / 2 * k2),
                          k4 = rhs(t + h, y + h * k3);
    y += h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
    if ((k + 1) % 100 == 0) {  // every output row
      const double tn = (k + 1) * h;
      const double wb = y(2) / i + (1 - 1 / i) * y(3);
      worst = std::max({worst, std::abs(at(r, "shaft.velocity_rad_s", tn) - y(2)),
                        std::abs(at(r, "housing.velocity_rad_s", tn) - y(3)), std::abs(at(r, "load.velocity_rad_s", tn) - wb)});
    }
  }
  EXPECT_LT(worst, tol(1e-8, 1e-6)) << "largest speed difference " << worst << " rad/s";
  RecordProperty("speed_error", sci(worst));
  // The housing carries the reaction of the gear: at the end it is deflected by the mean of
  // −(torque on housing)/c, a check of the sign (the housing turns against the shaft's torque).
  EXPECT_LT(at(r, "housing.position_rad", 2.0), 0.0);
}

// ---------------------------------------------------------------------------------------------
// Claim: examples/msl/simple-gear-shift.yaml (MSL Rotational.Examples.SimpleGearShift) agrees
// with an independent piecewise solution of MSL's equations.
// Members sun = engine (J_s = 1), carrier = load (J_c = 10), ring massless; z = 1.5. The gear puts
// μ, z μ, −(1 + z) μ on sun, ring, carrier (μ a free multiplier); the clutch (sun–ring, u_c =
// ω_s − ω_r) puts −F_c on the sun and +F_c on the ring; the brake (ring–housing, u_b = ω_r) −F_b
// on the ring. Limits: clutch L_c = 100 N·m · (t − 2)/0.1 on [2, 2.1], brake L_b = 100 N·m − L_c
// (both cgeo μ f_N = 2 · 0.5 · f_N). Loads: M_e = 20 N·m from 0.5 s, M_L = −k ω_c², k = 20/ω_n².
//   brake stuck (ω_r = 0, ω_s = (1 + z) ω_c), clutch sliding with F_c = L_c (u_c > 0):
//     ω̇_c = ((1 + z)(M_e − F_c) + M_L) / (J_c + (1 + z)² J_s), μ = J_s ω̇_s − M_e + F_c,
//     brake load λ_b = z μ + F_c (ring balance), holds while |λ_b| ≤ L_b;
//   both sliding (ring balance 0 = z μ + F_c − F_b): μ = (F_b − F_c)/z,
//     J_s ω̇_s = M_e + μ − F_c, J_c ω̇_c = −(1 + z) μ + M_L, until u_c = 0;
//   clutch stuck (ω_s = ω_r = ω_c): (J_s + J_c) ω̇ = M_e + M_L − F_b; clutch load λ_c = F_b − z μ
//     with μ = (M_L − J_c ω̇)/(1 + z) must stay within L_c.
// RK4 with h = 1e-5 s on the grid of the breakpoints 0.5, 2, 2.1 s; the switches by bisection.
struct GearShiftReference {
  static constexpr double z = 1.5, Js = 1.0, Jc = 10.0;
  double k = 20.0 / std::pow(100.0 * 2.0 * M_PI / 60.0, 2);
  enum Phase { brake_stuck, both_slide, clutch_stuck } phase = brake_stuck;
  double t_brake_slips = NAN, t_clutch_sticks = NAN, max_clutch_load = 0.0, max_brake_load = 0.0;
  double min_ring_speed = INFINITY;
  double breakaway_load = 0.0;  // λ_b at the brake's breakaway: > 0, so it slides in +  // while both slide: > 0 (the brake slides in +)
  std::vector<double> times, ws, wc;  // every 10 ms

  bool torque_on = false;  // the 20 N·m step, switched on the grid at 0.5 s (between steps)
  double Me(double) const { return torque_on ? 20.0 : 0.0; }
  static double Lc(double t) { return t <= 2.0 ? 0.0 : t >= 2.1 ? 100.0 : 1000.0 * (t - 2.0); }
  static double Lb(double t) { return 100.0 - Lc(t); }
  double ML(double w) const { return -k * w * std::abs(w); }
  static double ring(const Eigen::Vector2d& y) { return ((1 + z) * y(1) - y(0)) / z; }

  Eigen::Vector2d rhs(double t, const Eigen::Vector2d& y) const {  // y = (ω_s, ω_c)
    const double Fc = Lc(t), Fb = Lb(t);  // both slide in + (u_c > 0, ω_r > 0) where they slide
    if (phase == brake_stuck) {
      const double ac = ((1 + z) * (Me(t) - Fc) + ML(y(1))) / (Jc + (1 + z) * (1 + z) * Js);
      return {(1 + z) * ac, ac};
    }
    if (phase == both_slide) {
      const double mu = (Fb - Fc) / z;
      return {(Me(t) + mu - Fc) / Js, (-(1 + z) * mu + ML(y(1))) / Jc};
    }
    const double a = (Me(t) + ML(y(1)) - Fb) / (Js + Jc);
    return {a, a};
  }
  double brake_load(double t, const Eigen::Vector2d& y) const {
    const double mu = Js * rhs(t, y)(0) - Me(t) + Lc(t);
    return z * mu + Lc(t);
  }
  double clutch_load(double t, const Eigen::Vector2d& y) const {
    const double mu = (ML(y(1)) - Jc * rhs(t, y)(1)) / (1 + z);
    return Lb(t) - z * mu;
  }
  /// The event function of the phase (its sign change ends it).
  double event(double t, const Eigen::Vector2d& y) const {
    if (phase == brake_stuck) return t > 2.0 ? Lb(t) - std::abs(brake_load(t, y)) : 1.0;
    if (phase == both_slide) return y(0) - ring(y);
    return 1.0;
  }
  Eigen::Vector2d step(double t, const Eigen::Vector2d& y, double h) const {
    const Eigen::Vector2d k1 = rhs(t, y), k2 = rhs(t + h / 2, y + h / 2 * k1), k3 = rhs(t + h / 2, y + h / 2 * k2),
                          k4 = rhs(t + h, y + h * k3);
    return y + h / 6 * (k1 + 2 * k2 + 2 * k3 + k4);
  }
  GearShiftReference() {
    Eigen::Vector2d y = Eigen::Vector2d::Zero();
    const double h = 1e-5;
    times.push_back(0.0), ws.push_back(0.0), wc.push_back(0.0);
    for (long n = 0; n < 500000; ++n) {
      const double t0 = static_cast<double>(n) * h;
      torque_on = t0 >= 0.5 - h / 2;
      Eigen::Vector2d y1 = step(t0, y, h);
      if (event(t0, y) > 0 && event(t0 + h, y1) <= 0) {  // bisect the switch inside the step
        double lo = 0.0, hi = h;
        for (int it = 0; it < 60; ++it) {
          const double mid = 0.5 * (lo + hi);
          (event(t0 + mid, step(t0, y, mid)) > 0 ? lo : hi) = mid;
        }
        const double te = t0 + hi;
        Eigen::Vector2d ye = step(t0, y, hi);
        if (phase == brake_stuck) {
          breakaway_load = brake_load(te, ye);
          t_brake_slips = te;
          phase = both_slide;
        } else {
          t_clutch_sticks = te;
          phase = clutch_stuck;
          ye(0) = ye(1);  // u_c = (1 + z)/z (ω_s − ω_c) = 0: exactly at the stick
        }
        y1 = step(te, ye, t0 + h - te);
      }
      y = y1;
      const double tn = static_cast<double>(n + 1) * h;
      if (phase == brake_stuck && tn > 0.5) max_brake_load = std::max(max_brake_load, std::abs(brake_load(tn, y)));
      if (phase == both_slide) min_ring_speed = std::min(min_ring_speed, ring(y));
      if (phase == clutch_stuck) max_clutch_load = std::max(max_clutch_load, std::abs(clutch_load(tn, y)) / Lc(tn));
      if ((n + 1) % 1000 == 0) times.push_back(tn), ws.push_back(y(0)), wc.push_back(y(1));
    }
  }
};

TEST_P(Planetary, MslSimpleGearShiftMatchesPiecewiseSolution) {
  static const GearShiftReference ref;
  Model m = load_model(std::string(MACHDYN_SOURCE_DIR) + "/examples/msl/simple-gear-shift.yaml");
  const SimulationResult r = run(m);
  // The reference's own premises: the brake holds until 2 s, the stuck clutch holds after.
  ASSERT_LT(ref.max_brake_load, 100.0);
  ASSERT_LT(ref.max_clutch_load, 1.0);
  ASSERT_GT(ref.t_brake_slips, 2.0);
  ASSERT_GT(ref.t_clutch_sticks, ref.t_brake_slips);
  ASSERT_GT(ref.breakaway_load, 0.0);
  ASSERT_GE(ref.min_ring_speed, 0.0);
  double brake_slips = NAN, clutch_sticks = NAN;
  for (const auto& e : r.hybrid.events) {
    if (e.element == "brake" && e.kind == "slip") brake_slips = e.t;
    if (e.element == "clutch" && e.kind == "stick") clutch_sticks = e.t;
  }
  EXPECT_NEAR(brake_slips, ref.t_brake_slips, tol(1e-8, 1e-6));
  EXPECT_NEAR(clutch_sticks, ref.t_clutch_sticks, tol(1e-8, 1e-6));
  double worst = 0.0;
  for (size_t n = 0; n < ref.times.size(); ++n) {
    const double ring = ((1 + GearShiftReference::z) * ref.wc[n] - ref.ws[n]) / GearShiftReference::z;
    worst = std::max({worst, std::abs(at(r, "engine.velocity_rad_s", ref.times[n]) - ref.ws[n]),
                      std::abs(at(r, "load.velocity_rad_s", ref.times[n]) - ref.wc[n]),
                      std::abs(at(r, "ring.velocity_rad_s", ref.times[n]) - ring)});
  }
  EXPECT_LT(worst, tol(1e-7, 1e-5)) << "largest speed difference " << worst << " rad/s";
  RecordProperty("speed_error", sci(worst));
  RecordProperty("stick_error", sci(std::abs(clutch_sticks - ref.t_clutch_sticks)));
  RecordProperty("slip_error", sci(std::abs(brake_slips - ref.t_brake_slips)));
  // MSL's documented gear ratios: load/engine = 1/(1 + z) = 0.4 before the shift, 1 after.
  EXPECT_NEAR(at(r, "load.velocity_rad_s", 1.5) / at(r, "engine.velocity_rad_s", 1.5), 0.4, 1e-9);
  EXPECT_NEAR(at(r, "load.velocity_rad_s", 4.0) / at(r, "engine.velocity_rad_s", 4.0), 1.0, 1e-9);
  EXPECT_NEAR(r.hybrid.energy.residual(), 0.0, 1e-7 * r.hybrid.energy.source_work);
}

// ---------------------------------------------------------------------------------------------
// Bad input: every problem located, nothing simulated.
TEST(PlanetaryErrors, AreLocated) {
  auto errors = [](const std::string& links, const std::string& bodies = "") {
    return test::compile_errors("bodies:\n  s: {inertia: 1 kg*m^2}\n  r: {inertia: 1 kg*m^2}\n"
                                "  c: {inertia: 1 kg*m^2}\n  t: {type: translational, mass: 1 kg}\n" + bodies +
                                "links:\n" + links,
                                "gear.yaml");
  };
  EXPECT_NE(errors("  pg: {type: planetary-gear, sun: s, ring: r, carrier: c, teeth: {sun: 50, ring: 75}}\n")
                .find("gear.yaml:7:"), std::string::npos);
  EXPECT_NE(errors("  pg: {type: planetary-gear, sun: s, ring: r, carrier: c, teeth: {sun: 50, ring: 75}}\n")
                .find("cannot be built"), std::string::npos);
  EXPECT_NE(errors("  pg: {type: planetary-gear, sun: s, ring: r, carrier: c, ratio: 0.5}\n").find("z > 1"),
            std::string::npos);
  EXPECT_NE(errors("  pg: {type: planetary-gear, sun: s, ring: r, carrier: c, teeth: {sun: 30, ring: 90}, planets: 7}\n")
                .find("cannot be assembled"), std::string::npos);
  EXPECT_NE(errors("  pg: {type: planetary-gear, sun: s, ring: s, carrier: c, ratio: 2}\n").find("both sun and ring"),
            std::string::npos);
  EXPECT_NE(errors("  pg: {type: planetary-gear, sun: s, ring: q, carrier: c, ratio: 2}\n").find("unknown body 'q'"),
            std::string::npos);
  EXPECT_NE(errors("  pg: {type: planetary-gear, sun: s, ring: t, carrier: c, ratio: 2}\n").find("translational"),
            std::string::npos);
  const std::string massless = "  x: {inertia: 0 kg*m^2}\n  y: {inertia: 0 kg*m^2}\n";
  EXPECT_NE(errors("  pg: {type: planetary-gear, sun: x, ring: y, carrier: c, ratio: 2}\n", massless)
                .find("2 of its members"), std::string::npos);
  const std::string on_x = errors("  pg: {type: planetary-gear, sun: s, ring: x, carrier: c, ratio: 2}\n"
                                  "  k: {type: rope, between: [x, t], ratio: 2 rad/m, EA: 1e7 N, length: 10 m}\n"
                                  "  pg2: {type: planetary-gear, sun: s, ring: y, carrier: r, ratio: 2}\n",
                                  massless);
  EXPECT_NE(on_x.find("gear.yaml:10:3: error: link 'k'"), std::string::npos) << on_x;
  EXPECT_NE(on_x.find("a rope wound on a drum on it is not supported"), std::string::npos) << on_x;
  EXPECT_NE(errors("  g: {type: ideal-gear, between: [s, c], ratio: 3, housing: nobody}\n").find("unknown body 'nobody'"),
            std::string::npos);
  // Initial velocities that contradict the gear.
  const std::string v = test::compile_errors(R"(
bodies:
  s: {inertia: 1 kg*m^2, velocity: 1 rad/s}
  r: {inertia: 1 kg*m^2}
  c: {inertia: 1 kg*m^2}
links:
  pg: {type: planetary-gear, sun: s, ring: r, carrier: c, ratio: 2}
)", "gear.yaml");
  EXPECT_NE(v.find("gear.yaml:7:"), std::string::npos) << v;
  EXPECT_NE(v.find("initial velocities contradict"), std::string::npos) << v;
}

}  // namespace
}  // namespace machdyn
