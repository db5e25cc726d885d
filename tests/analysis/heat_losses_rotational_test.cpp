// examples/msl/heat-losses.yaml (MSL Rotational.Examples.HeatLosses: a lossy gear's massless output
// flange driving a clutch, a one-way clutch and a brake) against an independent RK4 of MSL's equations
// written here, on both integrators: every body's angle and speed at every 1 ms row, each element's
// heat and the total.
#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/analysis/extra_outputs.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/rk4.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::sci;
using test::series;

// ---------------------------------------------------------------------------------------------
// An independent solution of MSL Rotational.Examples.HeatLosses (MSL 3.2, StopTime 1 s), written from
// MSL's component equations, not from the library's engine. Angles from MSL's start (all 0, every
// spring unstretched, the backlash centred), J = 2 kg·m² each:
//   inertia1: τ = 20 sin(2π·5 t); damper 10 w1 to the ground; springDamper τ_sd = 1e4 (φ1 − φ2) +
//             20 (w1 − w2) (−τ_sd on 1, +τ_sd on 2);
//   elastoBacklash (c = 1e5, d = 100, b = 1 mrad) from 2 to 3: φ_rel = φ3 − φ2, outside |φ_rel| ≤ b/2
//             τ_c = c (φ_rel ∓ b/2), τ = τ_c + clamp(d w_rel, −|τ_c|, |τ_c|) (+τ on 2, −τ on 3), its
//             lossPower the clamped damping torque times w_rel;
//   inertia3: bearingFriction (tau_pos = [0, 1], peak 1): 1 N·m holding and sliding; spring3
//             τ_3 = 1e4 (φ3 − φ4) (−τ_3 on 3, +τ_3 on 4);
//   inertia4 – lossyGear (ratio 2, lossTable [0, 0.8, 0.8, 1, 1; 1, 0.7, 0.7, 2, 2]: η = 0.8 − 0.1 |w4|,
//             τ_bf = 1 + |w4| for |w4| ≤ 1) – massless flange (w_f = w4/2) – clutch (fn = 10 sin 0.4πt,
//             μ = 0.5: F_K) – inertia5 – oneWayClutch (a freewheel, w6 − w5 ≥ 0, and a clutch of
//             F_O = 0.5 sin 0.4πt) – inertia6 – brake (F_B = sin 0.4πt) to the ground.
// The chain inertia4 … inertia6 in a mode: unknowns a4, a5, a6, X (the torque inertia4 puts into the
// gear), Y (the gear's output in 4's coordinate; the flange gets 2Y), τ_K, τ_O (torques passed
// 5-wards and 6-wards), τ_B (the brake's on 6, against it):
//   2 a4 = τ_3 − X,   0 = 2Y − τ_K,   2 a5 = τ_K − τ_O,   2 a6 = τ_O − τ_B,
// and one equation per element: the gear stuck a4 = 0, rolling in s with 4's side driving
// Y = η X − s τ_bf, with the flange's driving X = η (Y + s τ_bf) (MSL's quadrants; the bearing
// friction is τ_bf,a = 0, τ_bf,b = τ_bf); the clutch stuck a5 = a4/2, sliding τ_K = σ F_K; the
// one-way clutch stuck a6 = a5, overrunning τ_O = −F_O; the brake stuck a6 = 0, sliding τ_B = σ F_B.
// A stuck gear holds while its loss torque X − Y lies in MSL's locking range [L₋, L₊] (the quadrant
// losses at 0±: (1 − η) X ± τ_bf where s X ≥ 0, (1 − 1/η) X ± τ_bf otherwise). With everything stuck
// the torque t = τ_K = τ_O = τ_B carried from the gear to the ground is not unique: the set holds
// while some t lies within every limit and the gear's range. The modes at an event: every
// combination of the elements at zero relative speed, fewest moving first, the first whose stuck
// elements hold (strictly) and whose moving ones accelerate their way (within rounding). Fixed-step
// RK4 (h = 1e-5 s), a step whose event function turns negative bisected to its instant; every heat
// (MSL's lossPower) and the torque's work are RK4 states.
struct RotationalHeatLosses {
  enum : int { p1, w1, p2, w2, p3, w3, p4, w4, p5, w5, p6, w6, q_damper, q_sd, q_eb, q_bf, q_gear, q_cl, q_ow, q_br, work, kN };
  using Y = std::array<double, kN>;
  static constexpr double b2 = 0.5e-3;
  // Modes: bearing m3, gap g (−1, 0, +1), gear G (0, ±1) with side_b, clutch K (0, ±1), one-way O
  // (0, 1 overrunning), brake B (0, ±1).
  int m3 = 0, g = 0, G = 0, K = 0, O = 0, B = 0;
  bool side_b = false;
  std::vector<double> clutch_switches;  // the instants the clutch's mode changed

  static double s04(double t) { return std::sin(0.4 * std::numbers::pi * t); }
  static double torque(double t) { return 20 * std::sin(10 * std::numbers::pi * t); }
  static double eta(double w) { return 0.8 - 0.1 * std::min(std::abs(w), 1.0); }
  static double tbf(double w) { return 1.0 + std::min(std::abs(w), 1.0); }
  struct Backlash {
    double tau, td;  // the torque (+ on 2, − on 3) and the damping part that acts
  };
  static Backlash backlash(const Y& y) {
    const double rel = y[p3] - y[p2], wr = y[w3] - y[w2];
    if (std::abs(rel) <= b2) return {0.0, 0.0};
    const double tc = 1e5 * (rel > 0 ? rel - b2 : rel + b2), td = std::clamp(100 * wr, -std::abs(tc), std::abs(tc));
    return {tc + td, td};
  }
  /// Whether the backlash touches with its damping clamped to −τ_c (τ = 0): machdyn's gap law is open
  /// there and has released the spring's ½ c e² already.
  static double clamped_energy(const Y& y) {
    const double rel = y[p3] - y[p2];
    if (std::abs(rel) <= b2) return 0.0;
    const Backlash k = backlash(y);
    const double e = std::abs(rel) - b2;
    return k.tau == 0.0 && e > 0 ? 0.5 * 1e5 * e * e : 0.0;
  }
  static double sd(const Y& y) { return 1e4 * (y[p1] - y[p2]) + 20 * (y[w1] - y[w2]); }
  static double s3(const Y& y) { return 1e4 * (y[p3] - y[p4]); }
  static double n3(const Y& y) { return -backlash(y).tau - s3(y); }

  struct Chain {
    double a4 = 0, a5 = 0, a6 = 0, X = 0, Yg = 0, tK = 0, tO = 0, tB = 0;
    bool ok = false;  // a unique solution (false: the all-stuck set, t not unique)
  };
  /// The chain's equations in modes (G, side, K, O, B) at (t, y), by Gaussian elimination.
  Chain chain(double t, const Y& y, int Gm, bool sb, int Km, int Om, int Bm) const {
    double A[8][9] = {};
    // columns: a4 a5 a6 X Y tK tO tB | rhs
    A[0][0] = 2, A[0][3] = 1, A[0][8] = s3(y);
    A[1][4] = 2, A[1][5] = -1;
    A[2][1] = 2, A[2][5] = -1, A[2][6] = 1;
    A[3][2] = 2, A[3][6] = -1, A[3][7] = 1;
    const double e = eta(y[w4]), tb = tbf(y[w4]);
    if (Gm == 0) A[4][0] = 1;
    else if (!sb) A[4][4] = 1, A[4][3] = -e, A[4][8] = -Gm * tb;
    else A[4][3] = 1, A[4][4] = -e, A[4][8] = e * Gm * tb;
    if (Km == 0) A[5][1] = 1, A[5][0] = -0.5;
    else A[5][5] = 1, A[5][8] = Km * 5 * s04(t);
    if (Om == 0) A[6][2] = 1, A[6][1] = -1;
    else A[6][6] = 1, A[6][8] = -0.5 * s04(t);
    if (Bm == 0) A[7][2] = 1;
    else A[7][7] = 1, A[7][8] = Bm * s04(t);
    for (int c = 0; c < 8; ++c) {
      int p = c;
      for (int r = c + 1; r < 8; ++r)
        if (std::abs(A[r][c]) > std::abs(A[p][c])) p = r;
      if (std::abs(A[p][c]) < 1e-12) return {};
      for (int k = 0; k < 9; ++k) std::swap(A[c][k], A[p][k]);
      for (int r = 0; r < 8; ++r) {
        if (r == c) continue;
        const double f = A[r][c] / A[c][c];
        for (int k = c; k < 9; ++k) A[r][k] -= f * A[c][k];
      }
    }
    Chain s;
    s.a4 = A[0][8] / A[0][0], s.a5 = A[1][8] / A[1][1], s.a6 = A[2][8] / A[2][2], s.X = A[3][8] / A[3][3];
    s.Yg = A[4][8] / A[4][4], s.tK = A[5][8] / A[5][5], s.tO = A[6][8] / A[6][6], s.tB = A[7][8] / A[7][7];
    s.ok = true;
    return s;
  }
  /// MSL's locking range of the stuck gear for its input torque X: [L₋, L₊].
  static void locking(double X, double* lo, double* hi) {
    const double e = eta(0.0), tb = tbf(0.0);
    *hi = X >= 0 ? (1 - e) * X + tb : (1 - 1 / e) * X + tb;
    *lo = X <= 0 ? (1 - e) * X - tb : (1 - 1 / e) * X - tb;
  }
  /// Everything stuck: the margin of the set of t within every limit and the gear's range (≥ 0: holds).
  static double all_stuck_margin(double t, const Y& y) {
    const double X = s3(y), FK = 5 * s04(t), FO = 0.5 * s04(t), FB = s04(t);
    double lo, hi;
    locking(X, &lo, &hi);  // X − t/2 ∈ [lo, hi]
    const double t_lo = std::max({-FK, -FO, -FB, 2 * (X - hi)}), t_hi = std::min({FK, FB, 2 * (X - lo)});
    return t_hi - t_lo;
  }
  bool all_stuck() const { return G == 0 && K == 0 && O == 0 && B == 0; }

  Y rate(double t, const Y& y) const {
    Y d{};
    const Backlash k = backlash(y);
    d[p1] = y[w1], d[w1] = (torque(t) - 10 * y[w1] - sd(y)) / 2;
    d[p2] = y[w2], d[w2] = (sd(y) + k.tau) / 2;
    d[p3] = y[w3], d[w3] = m3 == 0 ? 0.0 : (n3(y) - m3 * 1.0) / 2;
    const Chain c = all_stuck() ? Chain{} : chain(t, y, G, side_b, K, O, B);
    d[p4] = y[w4], d[w4] = c.a4;
    d[p5] = y[w5], d[w5] = c.a5;
    d[p6] = y[w6], d[w6] = c.a6;
    d[q_damper] = 10 * y[w1] * y[w1];
    d[q_sd] = 20 * (y[w1] - y[w2]) * (y[w1] - y[w2]);
    d[q_eb] = k.td * (y[w3] - y[w2]);
    d[q_bf] = m3 == 0 ? 0.0 : std::abs(y[w3]);
    d[q_gear] = (c.X - c.Yg) * y[w4];
    d[q_cl] = K == 0 ? 0.0 : c.tK * (y[w4] / 2 - y[w5]);
    d[q_ow] = O == 0 ? 0.0 : 0.5 * s04(t) * (y[w6] - y[w5]);
    d[q_br] = B == 0 ? 0.0 : c.tB * y[w6];
    d[work] = torque(t) * y[w1];
    return d;
  }
  double event(double t, const Y& y) const {
    const double rel = y[p3] - y[p2];
    double e = g == 0 ? std::min(b2 - rel, rel + b2) : g > 0 ? rel - b2 : -b2 - rel;
    e = std::min(e, m3 == 0 ? 1 - std::abs(n3(y)) : m3 * y[w3]);
    if (all_stuck()) return std::min(e, all_stuck_margin(t, y));
    const Chain c = chain(t, y, G, side_b, K, O, B);
    if (G == 0) {
      double lo, hi;
      locking(c.X, &lo, &hi);
      e = std::min({e, hi - (c.X - c.Yg), (c.X - c.Yg) - lo});
    } else {
      e = std::min({e, G * y[w4], side_b ? -G * c.X : G * c.X});
    }
    e = std::min(e, K == 0 ? 5 * s04(t) - std::abs(c.tK) : K * (y[w4] / 2 - y[w5]));
    e = std::min(e, O == 0 ? c.tO + 0.5 * s04(t) : y[w6] - y[w5]);
    e = std::min(e, B == 0 ? s04(t) - std::abs(c.tB) : B * y[w6]);
    return e;
  }
  Y step(double t, const Y& y, double h) const {
    return test::rk4_step([this](double s, const Y& z) { return rate(s, z); }, t, y, h);
  }
  /// The stuck elements keep their relative speeds exactly 0.
  void hold(Y& y) const {
    if (m3 == 0) y[w3] = 0;
    if (G == 0) y[w4] = 0;
    if (K == 0) y[w5] = y[w4] / 2;
    if (O == 0) y[w6] = y[w5];
    if (B == 0) y[w6] = 0;
  }
  /// Re-decides every mode at t (header): speeds that reached 0 set to 0, then the combinations.
  void decide(double t, Y& y) {
    const double rel = y[p3] - y[p2];
    g = rel > b2 ? 1 : rel < -b2 ? -1 : 0;
    if (m3 != 0 && m3 * y[w3] <= 0) y[w3] = 0, m3 = 0;
    if (m3 == 0 && std::abs(n3(y)) > 1) m3 = n3(y) > 0 ? 1 : -1;
    if (G != 0 && G * y[w4] <= 0) y[w4] = 0;
    if (K != 0 && K * (y[w4] / 2 - y[w5]) <= 0) y[w5] = y[w4] / 2;
    if (O != 0 && y[w6] - y[w5] <= 0) y[w6] = y[w5];
    if (B != 0 && B * y[w6] <= 0) y[w6] = 0;
    auto sgn = [](double v) { return v > 0 ? 1 : v < 0 ? -1 : 0; };
    // The candidates of each element: its sliding direction if it moves, else stuck or either way.
    const int gs = sgn(y[w4]), ks = sgn(y[w4] / 2 - y[w5]), os = sgn(y[w6] - y[w5]), bs = sgn(y[w6]);
    std::vector<std::array<int, 5>> cands;  // G, side_b, K, O, B
    for (int Gm : gs != 0 ? std::vector<int>{gs} : std::vector<int>{0, 1, -1})
      for (int sb : Gm == 0 ? std::vector<int>{0} : std::vector<int>{0, 1})
        for (int Km : ks != 0 ? std::vector<int>{ks} : std::vector<int>{0, 1, -1})
          for (int Om : os != 0 ? std::vector<int>{1} : std::vector<int>{0, 1})
            for (int Bm : bs != 0 ? std::vector<int>{bs} : std::vector<int>{0, 1, -1}) cands.push_back({Gm, sb, Km, Om, Bm});
    auto moving = [](const std::array<int, 5>& c) { return (c[0] != 0) + (c[2] != 0) + (c[3] != 0) + (c[4] != 0); };
    std::stable_sort(cands.begin(), cands.end(), [&](const auto& a, const auto& b) { return moving(a) < moving(b); });
    for (const auto& c : cands) {
      if (consistent(t, y, c)) {
        if (c[2] != K) clutch_switches.push_back(t);
        G = c[0], side_b = c[1] != 0, K = c[2], O = c[3], B = c[4];
        hold(y);
        return;
      }
    }
    ADD_FAILURE() << "reference: no consistent modes at t = " << t;
  }
  bool consistent(double t, const Y& y, const std::array<int, 5>& m) const {
    if (m[0] == 0 && m[2] == 0 && m[3] == 0 && m[4] == 0) return all_stuck_margin(t, y) >= 0;
    const Chain c = chain(t, y, m[0], m[1] != 0, m[2], m[3], m[4]);
    if (!c.ok) return false;
    const double tol = 1e-12 * (std::abs(c.a4) + std::abs(c.a5) + std::abs(c.a6) + 1e-300);
    if (m[0] == 0) {
      double lo, hi;
      locking(c.X, &lo, &hi);
      if (c.X - c.Yg > hi || c.X - c.Yg < lo) return false;
    } else {
      if ((m[1] != 0 ? -m[0] * c.X : m[0] * c.X) < -1e-12 * std::abs(c.X)) return false;
      if (y[w4] == 0 && m[0] * c.a4 < -tol) return false;
    }
    if (m[2] == 0 ? std::abs(c.tK) > 5 * s04(t) : y[w4] / 2 == y[w5] && m[2] * (c.a4 / 2 - c.a5) < -tol) return false;
    if (m[3] == 0 ? c.tO < -0.5 * s04(t) : y[w6] == y[w5] && c.a6 - c.a5 < -tol) return false;
    if (m[4] == 0 ? std::abs(c.tB) > s04(t) : y[w6] == 0 && m[4] * c.a6 < -tol) return false;
    return true;
  }
  /// The state at k dt, k = 0 … n.
  std::vector<Y> run(double dt, int n) {
    Y y{};
    std::vector<Y> out{y};
    double t = 0;
    for (int k = 1; k <= n; ++k) {
      const double stop = k * dt;
      while (t < stop) {
        const bool last = stop - t <= 1.000001e-5;
        const double h = last ? stop - t : 1e-5;
        Y y1 = step(t, y, h);
        hold(y1);
        if (event(t + h, y1) < 0) {
          double lo = 0, hi = h;
          while (std::nextafter(lo, hi) < hi) {
            const double mid = 0.5 * (lo + hi);
            Y ym = step(t, y, mid);
            hold(ym);
            (event(t + mid, ym) < 0 ? hi : lo) = mid;
          }
          y = step(t, y, hi);
          hold(y);
          t += hi;
          decide(t, y);
          continue;
        }
        y = y1;
        t = last ? stop : t + h;
      }
      out.push_back(y);
    }
    return out;
  }
};

class RotationalHeatLossesTest : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, RotationalHeatLossesTest,
                         ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf), test::IntegratorName{});

// Claim: examples/msl/heat-losses.yaml follows the independent solution above: angles within 1e-8 rad
// and speeds within 1e-6 rad/s at every 1 ms row (the massless flange's as w4/2); each element's heat
// (the backlash's plus the ½ c e² machdyn's gap law releases where MSL's clamps its damping, as in
// the translational example) and the total within 1e-7 J at every row; the clutch on the flange
// switches at the reference's instants within 1e-8 s; the total at t_end is the books' W − ΔT − ΔV.
// Measured (dopri5 / bdf): angles 2.8e-10 / 1.9e-10 rad, speeds 2.2e-8 / 2.1e-8 rad/s, element heats
// 2.2e-9 / 2.9e-9 J, total 2.3e-9 / 2.7e-9 J of 0.329 J.
TEST_P(RotationalHeatLossesTest, FollowsAnIndependentSolution) {
  Model m = load_model(test::example("msl/heat-losses.yaml"));
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m, SimulateOptions{}, output_selection({"heat"}));
  const auto& ts = series(r, "t_s");
  ASSERT_EQ(ts.size(), 1001u);
  RotationalHeatLosses ref;
  const auto y = ref.run(1e-3, 1000);
  using R = RotationalHeatLosses;

  const std::array<std::pair<const char*, int>, 6> bodies{{{"inertia1", R::p1}, {"inertia2", R::p2}, {"inertia3", R::p3},
                                                           {"inertia4", R::p4}, {"inertia5", R::p5}, {"inertia6", R::p6}}};
  for (const auto& [b, i] : bodies) {
    const auto &q = series(r, std::string(b) + ".position_rad"), &v = series(r, std::string(b) + ".velocity_rad_s");
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
  const auto& wf = series(r, "flange.velocity_rad_s");
  for (size_t k = 0; k < ts.size(); ++k) EXPECT_NEAR(wf[k], y[k][R::w4] / 2, 1e-6) << ts[k];

  const std::array<std::pair<const char*, int>, 8> heats{{{"damper", R::q_damper}, {"springDamper", R::q_sd},
                                                          {"elastoBacklash", R::q_eb}, {"bearingFriction", R::q_bf},
                                                          {"lossyGear", R::q_gear}, {"clutch", R::q_cl},
                                                          {"oneWayClutch_clutch", R::q_ow}, {"brake", R::q_br}}};
  double released = 0;
  for (const auto& [name, i] : heats) {
    const auto& Q = series(r, std::string(name) + ".heat_J");
    double e = 0;
    for (size_t k = 0; k < ts.size(); ++k) {
      const double early = i == R::q_eb ? R::clamped_energy(y[k]) : 0.0;
      released = std::max(released, early);
      e = std::max(e, std::abs(Q[k] - (y[k][static_cast<size_t>(i)] + early)));
    }
    EXPECT_LT(e, 1e-7) << name;
    RecordProperty(std::string(name) + "_heat_error", sci(e));
  }
  const auto& total = series(r, "heat_J");
  double e_total = 0;
  for (size_t k = 0; k < ts.size(); ++k) {
    double ref_total = R::clamped_energy(y[k]);
    for (const auto& [name, i] : heats) ref_total += y[k][static_cast<size_t>(i)];
    e_total = std::max(e_total, std::abs(total[k] - ref_total));
  }
  EXPECT_LT(e_total, 1e-7);
  RecordProperty("total_heat_error", sci(e_total));
  RecordProperty("total_heat_J", sci(total.back()));
  RecordProperty("clamped_release_J", sci(released));
  // The clutch on the massless flange switches (stick, slip, reversal) at the reference's instants.
  // (The reference may take two decisions within one bisection width where machdyn takes one: the
  // instants are compared, each once.)
  std::vector<double> switches;
  for (const auto& e : r.hybrid.events)
    if (e.element == "clutch" && e.kind != "initial") switches.push_back(e.t);
  auto once = [](std::vector<double>& v) {
    v.erase(std::unique(v.begin(), v.end(), [](double a, double b) { return std::abs(a - b) < 1e-9; }), v.end());
  };
  once(switches);
  once(ref.clutch_switches);
  auto list = [](const std::vector<double>& v) {
    std::string s;
    for (double x : v) s += std::to_string(x) + " ";
    return s;
  };
  ASSERT_EQ(switches.size(), ref.clutch_switches.size()) << list(switches) << "\n" << list(ref.clutch_switches);
  EXPECT_GE(switches.size(), 10u);
  double e_switch = 0;
  for (size_t i = 0; i < switches.size(); ++i) e_switch = std::max(e_switch, std::abs(switches[i] - ref.clutch_switches[i]));
  EXPECT_LT(e_switch, 1e-8);
  RecordProperty("clutch_switch_error_s", sci(e_switch));
  const EnergyBalance& E = r.hybrid.energy;
  EXPECT_NEAR(total.back(), E.source_work - (E.kinetic_end - E.kinetic_start) - (E.elastic_end - E.elastic_start), 1e-7);
}

}  // namespace
}  // namespace machdyn
