// The swinging-load examples of examples/crane/ (docs/sway.md, "Examples"): every case of
// trolley-sway-drive.yaml (a travel drive with wheel slip and end buffers, with and without shaping),
// bridge-trolley-sway.yaml (bridge and trolley moving together) and slewing-jib-sway.yaml (a slewing
// jib starting and stopping), each run event-driven with the invariant audit on both integrators,
// and their numbers against independent answers: a linear model of each carriage with its PI drive
// and the linear pendulum integrated here by RK4, the closed-form two-mass buffer impact, the
// symmetry of equal moves, the free carriages' swing frequencies, the conical pendulum and the
// jib's moment balance.
#include <algorithm>
#include <array>
#include <cmath>
#include <functional>
#include <numbers>
#include <string>
#include <vector>
#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/analysis/sway_summary.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/rk4.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::series;
constexpr double kG = 9.80665;
constexpr double kPi = std::numbers::pi;

class SwayExamples : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, SwayExamples, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

/// One case of an example, event-driven, with the invariant audit (a violation throws).
SimulationResult run_case(const std::string& file, const std::string& c, IntegratorChoice integ,
                          const std::vector<std::string>& sets = {}) {
  Model m = load_model_case(test::example(file), sets, c);
  m.simulation.integrator = integ;
  SimulateOptions o;
  o.event_driven = true;
  o.check = true;
  return simulate(m, o);
}

/// A speed reference: piecewise linear through points, the end values held.
using Signal = std::function<double(double)>;
Signal table(std::vector<std::pair<double, double>> p) {
  return [p](double t) {
    if (t <= p.front().first) return p.front().second;
    for (size_t k = 1; k < p.size(); ++k)
      if (t <= p[k].first) return p[k - 1].second + (p[k].second - p[k - 1].second) * (t - p[k - 1].first) / (p[k].first - p[k - 1].first);
    return p.back().second;
  };
}
/// The shapers of docs/model-files.md ("Reference shaping") for ζ = 0, written from the formulas:
/// Σ A_i s(t − t_i) with A = [1, 1]/2 at [0, T/2] (ZV), [1, 2, 1]/4 at [0, T/2, T] (ZVD), T/2 = π/ω;
/// the two-step form of a ramp Δv over [t0, t1]: half of Δv at the ramp's own acceleration from
/// t0, the other half from t0 + T/2.
Signal zv(Signal s, double w) {
  return [s, w](double t) { return 0.5 * s(t) + 0.5 * s(t - kPi / w); };
}
Signal zvd(Signal s, double w) {
  return [s, w](double t) { return 0.25 * s(t) + 0.5 * s(t - kPi / w) + 0.25 * s(t - 2 * kPi / w); };
}
Signal two_step(double t0, double t1, double dv, double w) {
  const double h = 0.5 * (t1 - t0);
  return [=](double t) {
    return 0.5 * dv * std::clamp((t - t0) / h, 0.0, 1.0) + 0.5 * dv * std::clamp((t - t0 - kPi / w) / h, 0.0, 1.0);
  };
}

/// The linear model of one carriage with its speed drive and the load on it, in one horizontal
/// direction: the carriage (mass Mc: all that moves with it, e.g. the drive line behind stuck wheels)
/// at x, driven by the PI law of docs/model-files.md (e = v_ref − v, F = K_p e + x_I,
/// x_I' = (K_p/T_i) e, below its limit), pulled by the load at X through the linear pendulum's
/// spring k = m g/ℓ (the horizontal rope force m g tan θ for small θ = (X − x)/ℓ):
///   Mc v' = F + k (X − x),  m V' = −k (X − x).
/// Integrated by classical RK4 (support/rk4.hpp) at h = 1e-4 s (its error, O(h⁴), far below the
/// tests' tolerances).
struct Carriage {
  double Mc, m, l, Kp, Ti;
  Signal vref;
  double v0 = 0.0;
  struct Row {
    double t, x, v, a, xi;  ///< xi = X − x
  };
  [[nodiscard]] std::vector<Row> run(double t_end, double h = 1e-4) const {
    const double k = m * kG / l;
    using S = std::array<double, 5>;  // x, v, x_I, X, V
    auto f = [&](double t, const S& y) {
      const double e = vref(t) - y[1], F = Kp * e + y[2], xi = y[3] - y[0];
      return S{y[1], (F + k * xi) / Mc, Kp / Ti * e, y[4], -k * xi / m};
    };
    S y{0, v0, 0, 0, v0};
    std::vector<Row> out;
    const long n = std::lround(t_end / h);
    for (long i = 0; i <= n; ++i) {
      const double t = static_cast<double>(i) * h;
      out.push_back({t, y[0], y[1], f(t, y)[1], y[3] - y[0]});
      if (i < n) y = test::rk4_step(f, t, y, h);
    }
    return out;
  }
};

/// The model's sway column against the linear model's ξ/ℓ on the output rows (linear interpolation
/// of the 1e-4 s RK4 rows): the largest difference; `residual` gets both models' largest |θ| from t_r on.
double sway_difference(const SimulationResult& r, const std::string& col, const std::vector<Carriage::Row>& lin,
                       double l, double t_r, double residual[2]) {
  const auto &t = series(r, "t_s"), &th = series(r, col);
  double worst = 0.0;
  residual[0] = residual[1] = 0.0;
  for (size_t k = 0; k < t.size(); ++k) {
    const double pos = t[k] / (lin[1].t - lin[0].t);
    const size_t i = std::min(static_cast<size_t>(pos), lin.size() - 2);
    const double f = pos - static_cast<double>(i), want = ((1 - f) * lin[i].xi + f * lin[i + 1].xi) / l;
    worst = std::max(worst, std::abs(th[k] - want));
    if (t[k] >= t_r) residual[0] = std::max(residual[0], std::abs(th[k])), residual[1] = std::max(residual[1], std::abs(want));
  }
  return worst;
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

int count_events(const SimulationResult& r, const std::string& element, const std::string& kind) {
  int n = 0;
  for (const ModeEvent& e : r.hybrid.events) n += e.element == element && e.kind == kind;
  return n;
}

// --- examples/crane/trolley-sway-drive.yaml --------------------------------------------------------

constexpr const char* kTrolley = "crane/trolley-sway-drive.yaml";
// The example's data: drive line 1.5 t, trolley 8 t, load 40 t on four falls of 12 m (c = 4e7 N/m),
// the travel drive's PI law, the driven wheels' share of the wheel loads.
constexpr double kMd = 1500, kMt = 8000, kM = 40000, kC = 4 * 1.2e8 / 12, kKp = 4e5, kTi = 0.5, kN = 235.4e3;
const double kL = 12 + kM * kG / kC;  // ℓ: the rope hangs stretched by m g/c

// Claim: the moves of the trolley example (unshaped, ZV, ZVD, two-step) follow the linear model of
// the trolley with its PI drive and the linear pendulum (Carriage above; the wheels stay stuck, so
// drive line and trolley move as one, Mc = 9.5 t, and the drive stays below its limit — both
// asserted): the sway angle within θ_max³ + 1e-6 rad at every row (the linear model drops the
// pendulum's O(θ³) terms, sin θ and tan θ against θ, and the O(θ²) shift of its period), and so the
// summary's residual sway after 20 s; the reference column is the shaper's formula written here.
// The unshaped move leaves 0.074 rad, ZV 30 times and ZVD 900 times less.
TEST_P(SwayExamples, TrolleyMovesFollowTheLinearModel) {
  const double w = std::sqrt(kG / 12.0);  // the shapers' design: `length: 12 m`
  const Signal base = table({{0, 0}, {3, 0.63}, {10, 0.63}, {13, 0}});
  const Signal up = two_step(0, 3, 0.63, w), down = two_step(10, 13, -0.63, w);
  const std::pair<std::string, Signal> cases[] = {
      {"unshaped", base}, {"zv", zv(base, w)}, {"zvd", zvd(base, w)}, {"two_step", [=](double t) { return up(t) + down(t); }}};
  double residual[4][2] = {};
  for (size_t c = 0; c < 4; ++c) {
    const auto& [name, ref] = cases[c];
    SCOPED_TRACE(name);
    const SimulationResult r = run_case(kTrolley, name, GetParam());
    EXPECT_EQ(count_events(r, "adhesion", "slip"), 0);
    EXPECT_EQ(max_abs(series(r, "travel.mode")), 0.0) << "the drive below its limit";
    EXPECT_LT(test::max_error(r, "travel.reference_m_s", ref), 1e-12);
    const Carriage lin{kMd + kMt, kM, kL, kKp, kTi, ref};
    const double th_max = max_abs(series(r, "rope.sway_x_rad"));
    const double d = sway_difference(r, "rope.sway_x_rad", lin.run(30.0), kL, 20.0, residual[c]);
    EXPECT_LT(d, std::pow(th_max, 3) + 1e-6) << test::sci(d) << " at θ_max " << th_max;
    const std::vector<SwaySummary> s = r.sway;
    ASSERT_EQ(s.size(), 1u);
    EXPECT_EQ(s[0].residual_sway_rad, residual[c][0]);
    EXPECT_NEAR(residual[c][0], residual[c][1], std::pow(th_max, 3) + 1e-6);
  }
  EXPECT_NEAR(residual[0][0], 0.074, 0.001);
  EXPECT_LT(residual[1][0], residual[0][0] / 30);
  EXPECT_LT(residual[2][0], residual[0][0] / 800);
  EXPECT_LT(residual[3][0], residual[0][0] / 20);
}

// Claim: on a wet rail (μ_s = 0.1: the driven wheels pass on at most μ_s N = 23.5 kN) the move at
// a = 0.625 m/s², beyond μ_s g of the driven share (N over the weight of trolley and load: 0.49 m/s²),
// slips the wheels: not at once — the trolley alone needs M_t a = 5 kN — but once the lagging
// load's pull k ξ adds to it. The first slip comes where the linear model's adhesion force
// F_a = M_t v' − k ξ (Newton on the trolley) reaches μ_s N, within 10 ms (the pendulum's O(θ²) terms,
// θ ≈ 0.06: 2e-3 of the 18 kN pull, at dF_a/dt ≈ 20 kN/s, 2 ms); there the adhesion force is μ_s N.
// The wheels stick again and slip once more while braking; the drive never reaches its limit.
TEST_P(SwayExamples, TrolleyOnAWetRailSlips) {
  const double mu_s = 0.1, a = 1.0 / 1.6;
  EXPECT_GT(a, mu_s * kG * kN / ((kMt + kM) * kG));
  const Signal ref = table({{0, 0}, {1.6, 1.0}, {6, 1.0}, {7.6, 0}});
  const Carriage lin{kMd + kMt, kM, kL, kKp, kTi, ref};
  const double k = kM * kG / kL;
  double t_lin = -1;
  for (const Carriage::Row& row : lin.run(3.0))
    if (std::abs(kMt * row.a - k * row.xi) >= mu_s * kN) {
      t_lin = row.t;
      break;
    }
  ASSERT_GT(t_lin, 1.0);
  const SimulationResult r = run_case(kTrolley, "slip", GetParam());
  double t_slip = -1;
  for (const ModeEvent& e : r.hybrid.events)
    if (e.element == "adhesion" && e.kind == "slip") {
      t_slip = e.t;
      break;
    }
  EXPECT_NEAR(t_slip, t_lin, 0.01) << t_slip << " against " << t_lin;
  // Stuck up to the slip: the adhesion force's largest value on the rows before it lies within the
  // last 10 ms row's rise (about 200 N) below μ_s N, and never above it.
  const auto &t = series(r, "t_s"), &Fa = series(r, "adhesion.force_N");
  double Fa_max = 0;
  for (size_t i = 0; i < t.size() && t[i] < t_slip; ++i) Fa_max = std::max(Fa_max, std::abs(Fa[i]));
  EXPECT_LE(Fa_max, mu_s * kN * (1 + 1e-9));
  EXPECT_GT(Fa_max, 0.98 * mu_s * kN);
  EXPECT_EQ(count_events(r, "adhesion", "slip"), 2);
  EXPECT_EQ(count_events(r, "adhesion", "stick"), 2);
  EXPECT_EQ(max_abs(series(r, "travel.mode")), 0.0);
  // The unshaped move of the same trolley on the dry rail (a = 0.21 m/s²) does not slip (above).
}

// Claim: the trolley coasting into its buffer (drive off, all at v0 = 0.63 m/s, the load hanging
// straight) is the two-mass linear system from the contact at t_c = 0.5 m/v0 on: the carriage
// (drive line and trolley, the wheels stuck: Mc = 9.5 t) on the buffer c_b = 4e5 N/m and the load on
// the pendulum spring k = m g/ℓ,
//   [Mc 0; 0 m] ü + [c_b + k, −k; −k, k] u = 0,  u(0) = 0, u̇(0) = v0 (1, 1),
// u = Σ φ_i (φ_iᵀ M 1 v0)/(φ_iᵀ M φ_i) sin(ω_i τ)/ω_i over the two modes. The buffer's first
// contact ends where u_1 returns to 0 (within 1e-3 s) and its largest force is c_b max u_1 (within
// 1e-3: the pendulum's θ ≈ 0.03, θ² against 1, and the 10 ms rows); the load swings on (the
// trolley meets the buffer again three times, the residual sway is the load's).
TEST_P(SwayExamples, TrolleyCoastsIntoItsBuffer) {
  const double v0 = 0.63, cb = 4e5, k = kM * kG / kL, Mc = kMd + kMt, tc = 0.5 / v0;
  Eigen::Matrix2d M, K;
  M << Mc, 0, 0, kM;
  K << cb + k, -k, -k, k;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::Matrix2d> es(K, M);
  auto u1 = [&](double tau) {
    double u = 0;
    for (int i = 0; i < 2; ++i) {
      const Eigen::Vector2d phi = es.eigenvectors().col(i);
      const double w = std::sqrt(es.eigenvalues()[i]);
      u += phi[0] * (phi.dot(M * Eigen::Vector2d(v0, v0)) / phi.dot(M * phi)) * std::sin(w * tau) / w;
    }
    return u;
  };
  double u_max = 0, tau_end = 0;
  for (double tau = 1e-6; tau < 2.0; tau += 1e-6) {
    const double u = u1(tau);
    if (u < 0) {
      tau_end = tau;
      break;
    }
    u_max = std::max(u_max, u);
  }
  ASSERT_GT(tau_end, 0);
  const SimulationResult r = run_case(kTrolley, "buffer", GetParam());
  EXPECT_EQ(count_events(r, "adhesion", "slip"), 0);
  std::vector<double> closed, opened;
  for (const ModeEvent& e : r.hybrid.events)
    if (e.element == "east" && e.kind != "initial") (e.kind == "gap_closed" ? closed : opened).push_back(e.t);
  ASSERT_GE(closed.size(), 1u);
  ASSERT_GE(opened.size(), 1u);
  EXPECT_NEAR(closed[0], tc, 1e-6);
  EXPECT_NEAR(opened[0] - closed[0], tau_end, 1e-3) << opened[0] - closed[0] << " against " << tau_end;
  const auto &t = series(r, "t_s"), &F = series(r, "east.load_N");
  double F_max = 0;
  for (size_t i = 0; i < t.size(); ++i)
    if (t[i] <= opened[0]) F_max = std::max(F_max, F[i]);
  EXPECT_NEAR(F_max, cb * u_max, 1e-3 * cb * u_max) << F_max << " against " << cb * u_max;
  EXPECT_EQ(count_events(r, "west", "gap_closed"), 0);
}

// --- examples/crane/bridge-trolley-sway.yaml ------------------------------------------------------

constexpr const char* kBridge = "crane/bridge-trolley-sway.yaml";

// Claim: with the bridge and the trolley following the same move, each direction of the load in
// space swings as the linear model of its own carriage and drive (x: the trolley, 8 t, K_p = 4e5 N·s/m;
// y: the bridge, 30 t, 1.5e6 N·s/m; the coupling of the two directions through the rope is O(θ²)):
// the sway columns within θ_max³ + 1e-6 rad, unshaped and ZV-shaped; ZV leaves 30 times less.
TEST_P(SwayExamples, BridgeAndTrolleyFollowTheirLinearModels) {
  const double w = std::sqrt(kG / 12.0);
  const Signal base = table({{0, 0}, {3, 0.5}, {8, 0.5}, {11, 0}});
  double res_unshaped = 0;
  for (const std::string& c : std::vector<std::string>{"unshaped", "zv"}) {
    SCOPED_TRACE(c);
    const Signal ref = c == "zv" ? zv(base, w) : base;
    const SimulationResult r = run_case(kBridge, c, GetParam());
    const double th_max = std::max(max_abs(series(r, "rope.sway_x_rad")), max_abs(series(r, "rope.sway_y_rad")));
    double res[2][2];
    const Carriage x{8000, kM, kL, 4e5, 0.5, ref}, y{30000, kM, kL, 1.5e6, 0.5, ref};
    const double dx = sway_difference(r, "rope.sway_x_rad", x.run(25.0), kL, 15.0, res[0]);
    const double dy = sway_difference(r, "rope.sway_y_rad", y.run(25.0), kL, 15.0, res[1]);
    EXPECT_LT(dx, std::pow(th_max, 3) + 1e-6) << test::sci(dx);
    EXPECT_LT(dy, std::pow(th_max, 3) + 1e-6) << test::sci(dy);
    EXPECT_EQ(max_abs(series(r, "cross_travel.mode")) + max_abs(series(r, "long_travel.mode")), 0.0);
    const double residual = std::max(res[0][0], res[1][0]);
    if (c == "unshaped") res_unshaped = residual;
    else EXPECT_LT(residual, res_unshaped / 30);
  }
}

// Claim: equal moves of equal carriages (the bridge set to the trolley's mass and drive) are
// symmetric under x ↔ y, so the load swings in the vertical plane at 45° to both: the two sway
// angles agree within 1e-9 rad at every row (the integrator's tolerance), and the load's offset from
// below the suspension point points along the diagonal, atan2(ξ_y, ξ_x) = −135° while it lags.
TEST_P(SwayExamples, EqualMovesSwingInTheDiagonalPlane) {
  const SimulationResult r = run_case(kBridge, "unshaped", GetParam(),
                                      {"bridge.mass=8 t", "long_travel.gain=4e5", "long_travel.torque_limit=60 kN"});
  const auto &tx = series(r, "rope.sway_x_rad"), &ty = series(r, "rope.sway_y_rad"), &t = series(r, "t_s");
  double worst = 0;
  for (size_t k = 0; k < tx.size(); ++k) worst = std::max(worst, std::abs(tx[k] - ty[k]));
  EXPECT_LT(worst, 1e-9) << test::sci(worst);
  EXPECT_GT(max_abs(tx), 0.02);
  const double at = 1.5;  // accelerating: the load behind
  const double xi = test::at(r, "load.x.position_m", at, 1e-3) - test::at(r, "trolley.position_m", at, 1e-3);
  const double eta = test::at(r, "load.y.position_m", at, 1e-3) - test::at(r, "bridge.position_m", at, 1e-3);
  EXPECT_NEAR(std::atan2(eta, xi), -0.75 * kPi, 1e-8);
  EXPECT_GT(t.size(), 100u);
}

// Claim: small swings of a load on two free carriages (the drives removed): linearized, the x and y
// directions decouple and each is the free-trolley pendulum, ω² = (g/ℓ)(1 + m/M) with M the mass
// that moves in that direction — the trolley's 8 t across the bridge, the bridge's 30 t along the
// runway. The periods between the first and the fifth zero crossing of the relative swings
// ξ = x_load − x_t and η = y_load − y_b (two periods) agree within 1e-3 (θ₀ = 0.2 m/ℓ = 0.017 in each
// direction: the amplitude's θ₀²/16 ≈ 2e-5 and the two directions' O(θ²) coupling, 2.8e-4 across the
// light trolley; the crossings interpolated on 10 ms rows).
TEST_P(SwayExamples, FreeCarriagesSwingAtTheirOwnFrequencies) {
  const SimulationResult r = run_case(kBridge, "released", GetParam());
  const auto& t = series(r, "t_s");
  auto period = [&](const std::string& load, const std::string& carriage) {
    const auto &a = series(r, load), &b = series(r, carriage);
    std::vector<double> zc;
    for (size_t k = 1; k < t.size(); ++k) {
      const double p = a[k - 1] - b[k - 1], q = a[k] - b[k];
      if ((p > 0) != (q > 0)) zc.push_back(t[k - 1] + (t[k] - t[k - 1]) * p / (p - q));
    }
    return zc.size() >= 5 ? (zc[4] - zc[0]) / 2 : -1.0;
  };
  const double Tx = 2 * kPi / std::sqrt(kG / kL * (1 + kM / 8000)), Ty = 2 * kPi / std::sqrt(kG / kL * (1 + kM / 30000));
  EXPECT_NEAR(period("load.x.position_m", "trolley.position_m"), Tx, 1e-3 * Tx);
  EXPECT_NEAR(period("load.y.position_m", "bridge.position_m"), Ty, 1e-3 * Ty);
  for (double mode : series(r, "rope.mode")) ASSERT_EQ(mode, 0.0);
}

// --- examples/crane/slewing-jib-sway.yaml ---------------------------------------------------------

constexpr const char* kJib = "crane/slewing-jib-sway.yaml";

// Claim: while the jib slews steadily (ω = 0.1 rad/s from 12 s to 35 s) the load's radial sway
// swings about the conical pendulum's steady angle tan θ_c = ω² (r + ℓ sin θ_c)/g (r the trolley's
// mean position on the jib, ℓ the rope's mean length). Linearized about the steady circle, the free
// swing seen from the jib has the frequencies √(g/ℓ) ± ω, so a least-squares fit of
// θ_c' + Σ± (a± cos + b± sin)((√(g/ℓ) ± ω) t) to the radial sway column finds θ_c' = θ_c within 2 %
// (the trolley's drive lets r swing by ±2 cm and the jib's speed ripples by ±0.3 %, 0.6 % of ω²).
// Both cases, unshaped and ZV-shaped; the summary's largest sway is the tangential lag of the start
// or the stop, not the steady angle.
TEST_P(SwayExamples, SteadySlewingSwingsAboutTheConicalAngle) {
  for (const std::string& c : std::vector<std::string>{"unshaped", "zv"}) {
    SCOPED_TRACE(c);
    const SimulationResult r = run_case(kJib, c, GetParam());
    const auto &t = series(r, "t_s"), &th = series(r, "rope.sway_radial_rad"), &R = series(r, "trolley.position_m"),
               &L = series(r, "rope.length_m");
    std::vector<size_t> rows;
    double r_mean = 0, l_mean = 0;
    for (size_t k = 0; k < t.size(); ++k)
      if (t[k] >= 12 && t[k] <= 35) rows.push_back(k), r_mean += R[k], l_mean += L[k];
    r_mean /= static_cast<double>(rows.size()), l_mean /= static_cast<double>(rows.size());
    const double w = 0.1, W0 = std::sqrt(kG / l_mean);
    double th_c = 0.0;
    for (int i = 0; i < 100; ++i) th_c = std::atan(w * w * (r_mean + l_mean * std::sin(th_c)) / kG);
    Eigen::MatrixXd A(rows.size(), 5);
    Eigen::VectorXd b(rows.size());
    for (size_t i = 0; i < rows.size(); ++i) {
      const double tk = t[rows[i]];
      A.row(static_cast<Eigen::Index>(i)) << 1, std::cos((W0 + w) * tk), std::sin((W0 + w) * tk), std::cos((W0 - w) * tk),
          std::sin((W0 - w) * tk);
      b[static_cast<Eigen::Index>(i)] = th[rows[i]];
    }
    const Eigen::VectorXd fit = A.colPivHouseholderQr().solve(b);
    EXPECT_NEAR(fit[0], th_c, 0.02 * th_c) << fit[0] << " against " << th_c;
    EXPECT_NEAR(th_c, 0.0155, 1e-4);
    EXPECT_EQ(max_abs(series(r, "slew.mode")), 0.0);
  }
}

// Claim: the slewing drive feels the load's moment. The rope pulls the suspension point at radius r
// with the horizontal force F_z tan θ_t across the jib (F_z = rope.torque_N the rope force's vertical
// part, θ_t the tangential sway), so the jib (J = 1.5e6 kg·m²) needs M_drive = J θ̈ − r F_z tan θ_t:
// the drive's torque column against that, θ̈ by central differences of the jib's speed, within 3e-3
// of the largest torque (rows within 15 ms of a break of the reference, where θ̈ jumps, left out).
// Starting, the load lags (θ_t < 0) and the drive works against it; at steady slewing it carries
// only the load's swing.
TEST_P(SwayExamples, TheSlewingDriveFeelsTheLoadsMoment) {
  const double J = 1.5e6, half = kPi / std::sqrt(kG / 10.0);
  for (const std::string& c : std::vector<std::string>{"unshaped", "zv"}) {
    SCOPED_TRACE(c);
    const SimulationResult r = run_case(kJib, c, GetParam());
    const auto &t = series(r, "t_s"), &w = series(r, "jib.velocity_rad_s"), &M = series(r, "slew.torque_N_m"),
               &R = series(r, "trolley.position_m"), &Fz = series(r, "rope.torque_N"), &tt = series(r, "rope.sway_tangential_rad");
    std::vector<double> breaks = {0, 5, 35, 40};
    if (c == "zv")
      for (double b : {0.0, 5.0, 35.0, 40.0}) breaks.push_back(b + half);
    const double M_max = max_abs(M);
    double worst = 0;
    for (size_t k = 1; k + 1 < t.size(); ++k) {
      if (std::any_of(breaks.begin(), breaks.end(), [&](double b) { return std::abs(t[k] - b) < 0.015; })) continue;
      const double acc = (w[k + 1] - w[k - 1]) / (t[k + 1] - t[k - 1]);
      worst = std::max(worst, std::abs(M[k] - (J * acc - R[k] * Fz[k] * std::tan(tt[k]))));
    }
    EXPECT_LT(worst, 3e-3 * M_max) << test::sci(worst / M_max);
    EXPECT_LT(test::at(r, "rope.sway_tangential_rad", 4.0, 1e-3), -0.01) << "the load lags behind the starting jib";
  }
}

}  // namespace MACHDYN_UNITY_ID
}  // namespace machdyn
