// The swinging load (elements/spatial_rope.hpp, `type: spatial-rope` under `links:`, a `type:
// point-mass` load under `bodies:`): small swings on a free trolley, the swing under a prescribed
// trolley acceleration, large swings on a fixed point (the elliptic integral), a load past the
// horizontal (a slack rope), the conical pendulum of uniform slewing, the rope's stretch mode, the
// energy books while hoisting and travelling, the linear model's pendulum and stretch modes — each
// against an independent closed form, on both integrators; located errors for bad input.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/extra_outputs.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/analysis/sway_summary.hpp"
#include "machdyn/elements/linearize.hpp"
#include "support/support.hpp"
#include "support/timed_model.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::num;
using test::series;
constexpr double kG = 9.80665;
constexpr double kPi = std::numbers::pi;

class Sway : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, Sway, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

/// The times where column y crosses 0 (linear interpolation between rows).
std::vector<double> zero_crossings(const SimulationResult& r, const std::string& y) {
  const auto &t = series(r, "t_s"), &v = series(r, y);
  std::vector<double> out;
  for (size_t k = 1; k < t.size(); ++k)
    if ((v[k - 1] > 0.0) != (v[k] > 0.0) && v[k - 1] != v[k])
      out.push_back(t[k - 1] + (t[k] - t[k - 1]) * v[k - 1] / (v[k - 1] - v[k]));
  return out;
}

// Claim: small swings of a load m on a free trolley M (no drive, no friction) have ω² = (g/ℓ)(1 + m/M).
// Derivation: with ξ = x_L − x_t and the rope's angle θ ≈ ξ/ℓ, the horizontal rope force is
// −m g ξ/ℓ on the load and +m g ξ/ℓ on the trolley, so m x_L'' = −m g ξ/ℓ, M x_t'' = m g ξ/ℓ and
// ξ'' = −(g/ℓ)(1 + m/M) ξ; from ξ(0) = a at rest, ξ = a cos ωt, and M x_t + m x_L = m a throughout.
// ℓ is the hanging length, L0 + m g/c. The load starts on the arc of radius ℓ (the rope at its static
// stretch): the relative swing follows a cos ωt within 1e-3 a over two periods (the elastic rope's
// shift of ω, (g/ℓ)/(c/m) ≈ 1e-5, and the amplitude's θ₀²/16 stay far below).
TEST_P(Sway, SmallSwingsOnAFreeTrolley) {
  const double M = 2000, m = 1000, L0 = 5, EA = 1e9, c = EA / L0, l = L0 + m * kG / c, a = 0.02;
  const double z0 = l - std::sqrt(l * l - a * a), w = std::sqrt(kG / l * (1 + m / M));
  const Model md = test::timed_model("bodies:\n  trolley: {type: translational, mass: 2000 kg}\n"
                              "  load: {type: point-mass, mass: 1000 kg, axes: [x, z], position: [0.02 m, " + num(z0) +
                                  " m]}\nlinks:\n  rope: {type: spatial-rope, load: load, trolley: trolley, length: 5 m, "
                                  "EA: 1e9 N}\n",
                              7.5, 1e-3, GetParam());
  const SimulationResult r = simulate(md);
  const auto &t = series(r, "t_s"), &xL = series(r, "load.x.position_m"), &xt = series(r, "trolley.position_m");
  double worst = 0.0, worst_cm = 0.0;
  for (size_t k = 0; k < t.size(); ++k) {
    worst = std::max(worst, std::abs(xL[k] - xt[k] - a * std::cos(w * t[k])));
    worst_cm = std::max(worst_cm, std::abs(M * xt[k] + m * xL[k] - m * a));
  }
  EXPECT_LT(worst, 1e-3 * a) << test::sci(worst / a);
  EXPECT_LT(worst_cm, 1e-6 * m * a);
  for (double mode : series(r, "rope.mode")) ASSERT_EQ(mode, 0.0) << "the rope stays taut";
}

// Claim: a trolley given a constant acceleration a from rest swings the load as the linear pendulum
// with a moving support: ξ'' + ω² ξ = −a (ω² = g/ℓ), ξ(0) = ξ'(0) = 0, so ξ = −(a/ω²)(1 − cos ωt);
// the sway angle column is atan(ξ/(ℓ cos θ)) ≈ ξ/ℓ, and the horizontal force on the trolley is the
// load's m |x_L''| = m ω² |ξ| (m g tan θ). Each within 1e-3 of its amplitude over 10 s (a/g = 0.002:
// the nonlinear terms are O(θ²) ≈ 2e-5).
TEST_P(Sway, PrescribedTrolleyAccelerationSwingsTheLinearPendulum) {
  const double m = 1000, L0 = 10, c = 1e9 / L0, l = L0 + m * kG / c, a = 0.02, w2 = kG / l, amp = 2 * a / w2;
  const Model md = test::timed_model("bodies:\n  trolley: {type: translational, mass: 5 t, motion: {acceleration: 0.02 m/s^2}}\n"
                              "  load: {type: point-mass, mass: 1 t, axes: [x, z]}\n"
                              "links:\n  rope: {type: spatial-rope, load: load, trolley: trolley, length: 10 m, EA: 1e9 N}\n",
                              10.0, 1e-3, GetParam());
  const SimulationResult r = simulate(md);
  const auto &t = series(r, "t_s"), &xL = series(r, "load.x.position_m"), &xt = series(r, "trolley.position_m");
  const auto &th = series(r, "rope.sway_x_rad"), &H = series(r, "rope.horizontal_force_N");
  double worst = 0.0, worst_th = 0.0, worst_H = 0.0;
  for (size_t k = 0; k < t.size(); ++k) {
    const double xi = -a / w2 * (1 - std::cos(std::sqrt(w2) * t[k]));
    worst = std::max(worst, std::abs(xL[k] - xt[k] - xi));
    worst_th = std::max(worst_th, std::abs(th[k] - xi / l));
    worst_H = std::max(worst_H, std::abs(H[k] - m * w2 * std::abs(xi)));
  }
  EXPECT_LT(worst, 1e-3 * amp) << test::sci(worst / amp);
  EXPECT_LT(worst_th, 1e-3 * amp / l);
  EXPECT_LT(worst_H, 1e-3 * m * w2 * amp) << test::sci(worst_H / (m * w2 * amp));
}

// Claim: the summary values of a move: a trolley accelerated at a for T_a and then coasting leaves
// the linear pendulum swinging with ξ's amplitude (2a/ω²)|sin(ω T_a/2)| (from ξ(T_a), ξ'(T_a) of
// ξ = −(a/ω²)(1 − cos ωt); it is also the largest swing, since 1 − cos x ≤ 2|sin(x/2)|), so the
// largest and the residual sway after T_a are (2a/g)|sin(ω T_a/2)|, the largest horizontal force
// m g times it, the rigid force m a and the horizontal dynamic factor 2|sin(ω T_a/2)|; each within 1e-3.
TEST_P(Sway, SummaryOfAMove) {
  const double m = 1000, L0 = 10, c = 1e9 / L0, l = L0 + m * kG / c, a = 0.02, Ta = 2.0, w = std::sqrt(kG / l);
  const double th = 2 * a / kG * std::abs(std::sin(w * Ta / 2));
  const Model md = test::timed_model("bodies:\n  trolley: {type: translational, mass: 5 t, motion: {acceleration: {type: table, "
                              "points: [[0, 0.02], [2, 0.02], [2, 0], [100, 0]]}}}\n"
                              "  load: {type: point-mass, mass: 1 t, axes: [x, z]}\n"
                              "links:\n  rope: {type: spatial-rope, load: load, trolley: trolley, length: 10 m, EA: 1e9 N, "
                              "sway_after: 2 s}\n",
                              12.0, 1e-3, GetParam());
  const SimulationResult r = simulate(md);
  const std::vector<SwaySummary> s = r.sway;
  ASSERT_EQ(s.size(), 1u);
  EXPECT_EQ(s[0].rope, "rope");
  EXPECT_NEAR(s[0].max_sway_rad, th, 1e-3 * th);
  ASSERT_TRUE(s[0].residual_after.has_value());
  EXPECT_NEAR(s[0].residual_sway_rad, th, 1e-3 * th);
  EXPECT_NEAR(s[0].max_horizontal_force_N, m * kG * th, 1e-3 * m * kG * th);
  ASSERT_TRUE(s[0].dynamic_factor.has_value());
  EXPECT_NEAR(*s[0].rigid_force_N, m * a, 1e-6 * m * a);
  EXPECT_NEAR(*s[0].dynamic_factor, 2 * std::abs(std::sin(w * Ta / 2)), 1e-3);
}

/// The number after `key` in the line of `text` that starts with `line_start` (NaN if absent).
double printed(const std::string& text, const std::string& line_start, const std::string& key) {
  const size_t a = text.find(line_start);
  if (a == std::string::npos) return std::nan("");
  const size_t e = text.find('\n', a), k = text.find(key, a);
  if (k == std::string::npos || k > e) return std::nan("");
  return std::stod(text.substr(k + key.size()));
}

// Claim: `machdyn simulate` prints the sway summary: per case with --all-cases, the largest and the
// residual sway in degrees, (2a/g)|sin(ω T_a/2)| (the summary's closed form above) for the two moves
// T_a = 2 s and 3 s, and the horizontal dynamic factor 2|sin(ω T_a/2)| (within the four printed
// digits); a model without a spatial rope prints no sway line.
TEST(SwayCli, PrintsTheSummaryPerCase) {
  const double m = 1000, L0 = 10, c = 1e9 / L0, l = L0 + m * kG / c, a = 0.02, w = std::sqrt(kG / l);
  auto with = [](const std::string& T) { return "{type: table, points: [[0, 0.02], [" + T + ", 0.02], [" + T + ", 0], [100, 0]]}"; };
  const std::string yaml = "bodies:\n  trolley: {type: translational, mass: 5 t, motion: {acceleration: " + with("2") + "}}\n"
                           "  load: {type: point-mass, mass: 1 t, axes: [x, z]}\n"
                           "links:\n  rope: {type: spatial-rope, load: load, trolley: trolley, length: 10 m, EA: 1e9 N, "
                           "sway_after: 3 s}\n"
                           "simulation: {t_end: 12 s, dt_out: 1 ms, rtol: 1e-10, atol: 1e-12}\n"
                           "cases:\n  short: {description: two seconds}\n"
                           "  long: {description: three seconds, bodies: {trolley: {motion: {acceleration: " + with("3") + "}}}}\n";
  const auto path = test::write_temp("sway-cli.yaml", yaml);
  const auto out = test::temp_dir() / "sway-cli-out";
  const auto r = test::run_cli("simulate '" + path + "' --all-cases --quiet -o '" + out.string() + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const auto& [name, Ta] : {std::pair<std::string, double>{"short", 2.0}, {"long", 3.0}}) {
    const double th = 2 * a / kG * std::abs(std::sin(w * Ta / 2)) * 180 / kPi, f = 2 * std::abs(std::sin(w * Ta / 2));
    const std::string line = "case " + name + ": sway rope:";
    EXPECT_NEAR(printed(r.out, line, "largest "), th, 1e-3 * th) << r.out;
    EXPECT_NEAR(printed(r.out, line, "residual "), th, 1e-3 * th) << r.out;
    EXPECT_NEAR(printed(r.out, line, "horizontal dynamic factor "), f, 1e-3) << r.out;
    EXPECT_GT(printed(r.out, line, "horizontal force max "), 0.0) << r.out;
  }
  const auto none = test::write_temp("no-sway-cli.yaml", "bodies:\n  a: {inertia: 1}\nloads:\n  M: {type: constant, body: a, "
                                                         "value: 1}\nsimulation: {t_end: 0.1 s, dt_out: 0.01 s}\n");
  const auto r2 = test::run_cli("simulate '" + none + "' --quiet -o '" + (test::temp_dir() / "no-sway-out").string() + "'");
  ASSERT_EQ(r2.exit_code, 0) << r2.err;
  EXPECT_EQ(r2.out.find("\nsway "), std::string::npos) << r2.out;
}

/// K(k), the complete elliptic integral of the first kind, by the arithmetic–geometric mean:
/// K = π / (2 AGM(1, √(1 − k²))).
double elliptic_k(double k) {
  double x = 1.0, y = std::sqrt(1.0 - k * k);
  for (int i = 0; i < 40 && std::abs(x - y) > 1e-16 * x; ++i) {
    const double mean = 0.5 * (x + y);
    y = std::sqrt(x * y), x = mean;
  }
  return kPi / (2.0 * x);
}

// Claim: the period of a pendulum on a fixed point swung to θ₀ is 4 √(L/g) K(sin(θ₀/2)) (the complete
// elliptic integral from energy conservation, ½ L θ'² = g (cos θ − cos θ₀)); for θ₀ = 60° and 89°, the
// time between the first and third zero crossings of the load's x is that period within 1e-4 (the
// rope's stretch, m g/c ≈ 1e-5 L, changes the length by less than that).
TEST_P(Sway, LargeSwingPeriodIsTheEllipticIntegral) {
  for (double deg : {60.0, 89.0}) {
    const double m = 1000, L0 = 5, c = 1e9 / L0, th0 = deg * kPi / 180, h = L0 + m * kG / c;
    const double l0 = L0 + m * kG * std::cos(th0) / c;  // the stretch of the tension at rest there
    const double T = 4 * std::sqrt(L0 / kG) * elliptic_k(std::sin(th0 / 2));
    const Model md = test::timed_model("bodies:\n  load: {type: point-mass, mass: 1 t, axes: [x, z], position: [" +
                                    num(l0 * std::sin(th0)) + " m, " + num(h - l0 * std::cos(th0)) + " m]}\n"
                                    "links:\n  rope: {type: spatial-rope, load: load, length: 5 m, EA: 1e9 N}\n",
                                1.4 * T, 1e-3, GetParam());
    const SimulationResult r = simulate(md);
    const std::vector<double> zc = zero_crossings(r, "load.x.position_m");
    ASSERT_GE(zc.size(), 3u) << deg;
    EXPECT_NEAR(zc[2] - zc[0], T, 1e-4 * T) << deg << " deg: " << test::sci((zc[2] - zc[0]) / T - 1);
    EXPECT_NEAR(zc[0], T / 4, 1e-4 * T) << deg;
  }
}

// Claim: a load that swings past the horizontal is a slack rope, not an error: started at rest at
// 150° with the rope slack, it falls freely (z'' = −g, x constant: checked while the mode column says
// slack) until the rope is taut again — a located event — and the energy books balance throughout
// (the damping's heat included), within 1e-6 of the work turned over.
TEST_P(Sway, PastTheHorizontalTheRopeGoesSlack) {
  const double L0 = 5, th0 = 150 * kPi / 180, l0 = 0.9 * L0, h = L0 + 1000 * kG / (1e8 / L0);
  const double x0 = l0 * std::sin(th0), z0 = h - l0 * std::cos(th0);
  Model md = test::timed_model("bodies:\n  load: {type: point-mass, mass: 1 t, axes: [x, z], position: [" + num(x0) + " m, " +
                            num(z0) + " m]}\nlinks:\n  rope: {type: spatial-rope, load: load, length: 5 m, EA: 1e8 N, "
                            "damping: 2e4 N*s/m}\n",
                        3.0, 1e-3, GetParam());
  SimulateOptions o;
  o.event_driven = true;
  const SimulationResult r = simulate(md, o);
  const auto &t = series(r, "t_s"), &mode = series(r, "rope.mode"), &x = series(r, "load.x.position_m"),
             &z = series(r, "load.z.position_m");
  ASSERT_EQ(mode.front(), 1.0) << "slack at the start";
  size_t k = 0;
  for (; k < t.size() && mode[k] == 1.0; ++k) {
    EXPECT_NEAR(x[k], x0, 1e-9);
    EXPECT_NEAR(z[k], z0 - 0.5 * kG * t[k] * t[k], 1e-7);
  }
  ASSERT_LT(k, t.size()) << "the rope is taut again";
  int taut = 0;
  for (const ModeEvent& ev : r.hybrid.events) taut += ev.element == "rope" && ev.to == "taut";
  EXPECT_GE(taut, 1);
  const EnergyBalance& e = r.hybrid.energy;
  EXPECT_GT(e.damping_loss, 0.0);
  EXPECT_LT(std::abs(e.residual()), 1e-6 * (std::abs(e.source_work) + e.damping_loss));
}

// Claim: a jib slewing at a constant ω carries the load on the conical pendulum: the rope at the
// steady angle tan θ = ω² (r + ℓ sin θ)/g with the tension m g/cos θ (and ℓ = L0 + T/c), solved here
// by a fixed-point iteration; started there (on the circle at ω (r + ℓ sin θ)), the radial sway stays
// θ and the tangential 0 within 1e-7 rad, the tension m g/cos θ within 1e-6 (the rope's stretch mode at
// √(c/m) = 350 rad/s, excited by the integration's error: 2.6e-7 on bdf), and the jib feels no moment.
TEST_P(Sway, UniformSlewingIsTheConicalPendulum) {
  const double m = 1000, L0 = 8, c = 1e9 / L0, r0 = 10, w = 0.4, h = L0 + m * kG / c;
  double th = 0.1, l = L0;
  for (int i = 0; i < 200; ++i) {
    l = L0 + m * kG / std::cos(th) / c;
    th = std::atan(w * w * (r0 + l * std::sin(th)) / kG);
  }
  const double rho = r0 + l * std::sin(th), T = m * kG / std::cos(th);
  const Model md = test::timed_model("bodies:\n  jib: {inertia: 1e5 kg*m^2, motion: {speed: 0.4 rad/s}}\n"
                              "  load: {type: point-mass, mass: 1 t, position: [" + num(rho) + " m, 0 m, " +
                                  num(h - l * std::cos(th)) + " m], velocity: [0 m/s, " + num(w * rho) + " m/s, 0 m/s]}\n"
                                  "links:\n  rope: {type: spatial-rope, load: load, jib: jib, radius: 10 m, length: 8 m, "
                                  "EA: 1e9 N}\n",
                              6.0, 1e-2, GetParam());
  const SimulationResult r = simulate(md);
  double wr = 0.0, wt = 0.0, wT = 0.0, wM = 0.0;
  const auto &rad = series(r, "rope.sway_radial_rad"), &tan = series(r, "rope.sway_tangential_rad"),
             &F = series(r, "rope.tension_N"), &Mj = series(r, "jib.motion_torque_N_m");
  for (size_t k = 0; k < rad.size(); ++k) {
    wr = std::max(wr, std::abs(rad[k] - th));
    wt = std::max(wt, std::abs(tan[k]));
    wT = std::max(wT, std::abs(F[k] - T));
    wM = std::max(wM, std::abs(Mj[k]));
  }
  EXPECT_GT(th, 0.1);
  EXPECT_LT(wr, 1e-7) << test::sci(wr);
  EXPECT_LT(wt, 1e-7) << test::sci(wt);
  EXPECT_LT(wT, 1e-6 * T) << test::sci(wT / T);
  EXPECT_LT(wM, 1e-6 * T * r0) << test::sci(wM);
}

// Claim: the rope's stretch mode: a load hanging on n falls (c = n E A/L0) pulled down by δ from its
// rest below the suspension point oscillates as z = −δ cos(√(c/m) t) (the rope straight along z: the
// law is exactly the linear spring there), within 1e-6 δ over 2 s (six periods).
TEST_P(Sway, StretchModeIsSqrtCOverM) {
  const double m = 1000, c = 2 * 2e6 / 10, w = std::sqrt(c / m), dz = 0.01;
  const Model md = test::timed_model("bodies:\n  load: {type: point-mass, mass: 1 t, axes: [x, z], position: [0, -0.01 m]}\n"
                              "links:\n  rope: {type: spatial-rope, load: load, length: 10 m, EA: 2e6 N, falls: 2}\n",
                              2.0, 1e-3, GetParam());
  const SimulationResult r = simulate(md);
  const double err = test::max_error(r, "load.z.position_m", [&](double t) { return -dz * std::cos(w * t); });
  EXPECT_LT(err, 1e-6 * dz) << test::sci(err / dz);
}

// Claim: the energy books balance with the swinging load while the drum hoists and the trolley and
// bridge travel (a load in space, damping in the rope): the residual is below 1e-6 of the work
// turned over, the rope's damping is the only loss, and the rope stays taut (its L shortens).
TEST_P(Sway, EnergyBooksBalanceHoistingAndTravelling) {
  Model md = test::timed_model("bodies:\n  trolley: {type: translational, mass: 3 t}\n  bridge: {type: translational, mass: 8 t}\n"
                        "  drum: {inertia: 50 kg*m^2}\n  load: {type: point-mass, mass: 1 t}\n"
                        "links:\n  rope: {type: spatial-rope, load: load, trolley: trolley, bridge: bridge, drum: drum, "
                        "drum_radius: 0.3 m, falls: 2, length: 10 m, EA: 5e7 N, damping: 5e3 N*s/m}\n"
                        "loads:\n  travel: {type: ramp, body: trolley, value: 2 kN, end: 1 s}\n"
                        "  cross: {type: sine, body: bridge, amplitude: 3 kN, frequency: 0.3 Hz}\n"
                        "  hoist: {type: ramp, body: drum, value: 1600 N*m, end: 0.5 s, before: 1471.0 N*m}\n",
                        4.0, 1e-3, GetParam());
  SimulateOptions o;
  o.event_driven = true;
  const SimulationResult r = simulate(md, o);
  const EnergyBalance& e = r.hybrid.energy;
  EXPECT_GT(e.source_work, 1e3);
  EXPECT_GT(e.damping_loss, 0.0);
  EXPECT_LT(std::abs(e.residual()), 1e-6 * (std::abs(e.source_work) + e.damping_loss)) << e.residual();
  for (double mode : series(r, "rope.mode")) ASSERT_EQ(mode, 0.0);
  EXPECT_LT(series(r, "rope.free_length_m").back(), 9.5);
}

// Claim: a load resting on a ground stop under its z body lifts off as on a rope link: the drum
// (J = 50 kg·m², torque M = 2 kN·m, unloaded while the rope is slack) winds in the slack
// ℓ₀ − L0 < 0 (ℓ₀ = √(0.2² + 9.95²) from the load at x = 0.2 m to the suspension point 9.95 m above
// it) at s = R/n = 0.15 m per radian: the rope is taut at t = √(2 (L0 − ℓ₀)/(s M/J)) (within 1e-9 s),
// the stop lets the load go after that (an event of the stop), the load rises, and the energy books
// balance within 1e-6 of the work turned over.
TEST_P(Sway, LiftOffFromAGroundStop) {
  Model md = test::timed_model("bodies:\n  drum: {inertia: 50 kg*m^2}\n  trolley: {type: translational, mass: 3 t}\n"
                        "  load: {type: point-mass, mass: 1 t, axes: [x, z], position: [0.2 m, 0 m]}\n"
                        "links:\n  rope: {type: spatial-rope, load: load, trolley: trolley, drum: drum, drum_radius: 0.3 m, "
                        "falls: 2, length: 10 m, EA: 5e7 N, height: 9.95 m, damping: 1e4 N*s/m}\n"
                        "loads:\n  hoist: {type: constant, body: drum, value: 2000 N*m}\n"
                        "stops:\n  ground: {body: load.z, min: 0 m}\n",
                        1.0, 1e-3, GetParam());
  SimulateOptions o;
  o.event_driven = true;
  const SimulationResult r = simulate(md, o);
  const double l0 = std::hypot(0.2, 9.95), t_taut = std::sqrt(2 * (10 - l0) / (0.15 * 2000 / 50.0));
  double taut = -1, lift = -1;
  for (const ModeEvent& ev : r.hybrid.events) {
    if (taut < 0 && ev.element == "rope" && ev.to == "taut" && ev.kind != "initial") taut = ev.t;
    if (lift < 0 && ev.element == "ground" && ev.kind != "initial") lift = ev.t;
  }
  EXPECT_NEAR(taut, t_taut, 1e-9);
  EXPECT_GT(lift, taut);
  EXPECT_GT(series(r, "load.z.position_m").back(), 0.01);
  const EnergyBalance& e = r.hybrid.energy;
  EXPECT_LT(std::abs(e.residual()), 1e-6 * (std::abs(e.source_work) + e.damping_loss)) << e.residual();
}

// Claim: linearized about the hanging load, a load on a free trolley has the pendulum mode
// ω² = (g/ℓ)(1 + m/M) and the stretch mode c/m (and the trolley's rigid mode 0): the eigenvalues of
// M⁻¹K of linearize() within 1e-9 (the geometric stiffness F ∂²ℓ/∂q² is the pendulum's m g/ℓ).
TEST(SwayLinear, PendulumAndStretchModes) {
  const double M = 2000, m = 1000, L0 = 5, c = 1e9 / L0, l = L0 + m * kG / c;
  const Model md = test::model_text("bodies:\n  trolley: {type: translational, mass: 2000 kg}\n"
                                    "  load: {type: point-mass, mass: 1000 kg, axes: [x, z]}\n"
                                    "links:\n  rope: {type: spatial-rope, load: load, trolley: trolley, length: 5 m, "
                                    "EA: 1e9 N}\n");
  const LinearModel lin = linearize(md, initial_topology(md));
  const Eigen::MatrixXd K(lin.stiffness());
  Eigen::MatrixXd A = lin.M.cwiseInverse().asDiagonal() * K;
  Eigen::EigenSolver<Eigen::MatrixXd> es(A);
  std::vector<double> ev;
  for (int i = 0; i < 3; ++i) ev.push_back(es.eigenvalues()[i].real());
  std::sort(ev.begin(), ev.end());
  EXPECT_NEAR(ev[0], 0.0, 1e-9);
  EXPECT_NEAR(ev[1], kG / l * (1 + m / M), 1e-9 * kG / l);
  EXPECT_NEAR(ev[2], c / m, 1e-9 * c / m);
}

// Claim: every bad input of a load or a spatial rope is an error at its place naming it: a
// suspension naming no body or one of the wrong kind, a zero or negative length, a planar load given
// three coordinates (or hung from a bridge), a slewing radius without a jib (and a jib without its
// radius), a load that is no point mass; through the CLI such a file exits 2 and writes nothing.
TEST(SwayCompile, BadInputIsLocated) {
  const std::string bodies = "bodies:\n  T: {type: translational, mass: 1 t}\n  J: {inertia: 10}\n"
                             "  P: {type: point-mass, mass: 1 t, axes: [x, z]}\n  S: {type: point-mass, mass: 1 t}\n";
  auto errors_of = [&](const std::string& rope) {
    return test::compile_errors(bodies + "links:\n  r: {type: spatial-rope, " + rope + "}\n", "bad.yaml");
  };
  EXPECT_EQ(errors_of("load: P, trolley: T, length: 5 m, EA: 1e8 N"), "");
  EXPECT_EQ(errors_of("load: S, jib: J, radius: 4 m, length: 5 m, EA: 1e8 N"), "");
  struct Case {
    std::string rope, want;
  };
  const Case cases[] = {
      {"load: P, trolley: X, length: 5 m, EA: 1e8 N", "bad.yaml:7:45: error: link 'r': 'trolley': unknown body 'X'"},
      {"load: P, trolley: J, length: 5 m, EA: 1e8 N", "'trolley': body 'J' is rotational"},
      {"load: S, jib: T, radius: 4 m, length: 5 m, EA: 1e8 N", "'jib': body 'T' is translational"},
      {"load: P, trolley: T, length: 0 m, EA: 1e8 N", "bad.yaml:7:56: error: link 'r': field 'length' must be positive"},
      {"load: P, trolley: T, length: -5 m, EA: 1e8 N", "field 'length' must be positive"},
      {"load: S, radius: 4 m, length: 5 m, EA: 1e8 N", "a slewing 'radius' needs the 'jib'"},
      {"load: S, jib: J, length: 5 m, EA: 1e8 N", "a slewing 'jib' needs the load's 'radius'"},
      {"load: P, bridge: T, length: 5 m, EA: 1e8 N", "the load 'P' moves in the xz plane"},
      {"load: T, length: 5 m, EA: 1e8 N", "'T' is a body of its own"},
      {"load: Q, length: 5 m, EA: 1e8 N", "unknown load 'Q'"},
      {"load: P, trolley: T, length: 5 m", "missing field 'EA'"},
  };
  for (const Case& c : cases) {
    const std::string got = errors_of(c.rope);
    EXPECT_NE(got.find(c.want), std::string::npos) << c.rope << "\n--- want: " << c.want << "\n--- got:\n" << got;
    EXPECT_EQ(std::count(got.begin(), got.end(), '\n'), 0) << got;
  }
  // A planar load given three coordinates.
  const std::string three = test::compile_errors("bodies:\n  P: {type: point-mass, mass: 1 t, axes: [x, z], position: [0, 0, 0]}\n",
                                                 "three.yaml");
  EXPECT_NE(three.find("three.yaml:2:60: error: body 'P': 'position' expected 2 values, one per axis"), std::string::npos)
      << three;
  // Through the CLI: exit 2, nothing written.
  const auto path = test::write_temp("bad-sway-cli.yaml", bodies + "links:\n  r: {type: spatial-rope, load: P, trolley: X, "
                                                                   "length: 5 m, EA: 1e8 N}\n");
  const auto out = test::temp_dir() / "bad-sway-out";
  const auto r = test::run_cli("simulate '" + path + "' -o '" + out.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad-sway-cli.yaml:7:45: error: link 'r': 'trolley': unknown body 'X'"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out / "timeseries.csv"));
}

}  // namespace MACHDYN_UNITY_ID
}  // namespace machdyn
