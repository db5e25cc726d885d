// A stuck lossy gear as bounded rows of the split of the stuck set (analysis/gear_split.hpp): its
// locking range as pieces against the gear's own start margins, the bounded split with general rows
// against an enumeration of every active set, and a gear held at rest by a chain of stuck clutches
// beside it against a hand balance on both integrators.
#include <cmath>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <optional>
#include <random>
#include <string>

#include "analysis/gear_split.hpp"
#include "machdyn/analysis/bounded_split.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "support/events.hpp"
#include "support/models.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::series;

Model split_gear_model(double eta1, double eta2, double bf1, double bf2, double ratio) {
  return test::model_of(fmt::format(R"(bodies:
  A: {{inertia: 1 kg*m^2}}
  B: {{inertia: 2 kg*m^2}}
links:
  G: {{type: lossy-gear, between: [A, B], ratio: {}, efficiency: {}, efficiency_reverse: {},
      bearing_friction: {} N*m, bearing_friction_reverse: {} N*m}}
simulation: {{t_end: 1}}
)",
                                    ratio, eta1, eta2, bf1, bf2));
}

// Claim: the union of the four pieces (analysis/gear_split.hpp) is the gear's locking range as its own
// law states it: at random reactions (X, Y), gear_holds(X, Y) equals "both start margins
// LossyGearLaw::start_margin(±1, F_a = X, F_b = −i Y) ≥ 0" (stuck: X = F_a, Y = −F_b/i), for random
// efficiencies (η_mf2 = 0 self-locking among them), bearing torques and ratios of either sign; points
// within 1e-9 of the boundary are skipped (either answer is right there).
TEST(GearSplit, LockingPiecesAreTheGearsStartMargins) {
  std::mt19937 gen(29);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int held = 0, free = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const double eta1 = 0.2 + 0.8 * U(gen), eta2 = trial % 5 == 0 ? 0.0 : 0.05 + 0.95 * U(gen);
    const double bf1 = trial % 3 == 0 ? 0.0 : 3.0 * U(gen), bf2 = trial % 3 == 0 ? 0.0 : 3.0 * U(gen);
    const double ratio = (trial % 2 == 0 ? 1.0 : -1.0) * (0.3 + 20.0 * U(gen));
    const Model m = split_gear_model(eta1, eta2, bf1, bf2, ratio);
    const LossyGearLaw g = LossyGearLaw::of(m.lossy_gears[0]);
    for (int k = 0; k < 400; ++k) {
      const double X = 20.0 * (U(gen) - 0.5), Y = 20.0 * (U(gen) - 0.5);
      const double mp = g.start_margin(+1, X, -g.i * Y), mm = g.start_margin(-1, X, -g.i * Y);
      if (std::abs(mp) < 1e-9 || std::abs(mm) < 1e-9) continue;
      const bool want = mp >= 0.0 && mm >= 0.0;
      (want ? held : free) += 1;
      EXPECT_EQ(detail::gear_holds(g, X, Y, 0.0), want)
          << "trial " << trial << " X " << X << " Y " << Y << " m+ " << mp << " m- " << mm;
    }
  }
  EXPECT_GT(held, 1000);  // both answers occur often
  EXPECT_GT(free, 1000);
}

// The optimum by enumeration: every subset of the rows (the bounds as rows λ_i ≥ lo_i, −λ_i ≥ −hi_i,
// and D λ ≥ e) taken as equalities gives the weighted least-norm candidate on that face; a candidate
// that meets A λ = r and every row is feasible, and the convex problem's optimum is the feasible
// candidate of least Σ (λ_i / w_i)² (its own face's candidate is it).
std::optional<Eigen::VectorXd> enumerate_rows(const Eigen::MatrixXd& A, const Eigen::VectorXd& r, const Eigen::VectorXd& w,
                                              const Eigen::MatrixXd& R, const Eigen::VectorXd& h) {
  const Eigen::Index n = A.cols(), p = R.rows();
  std::optional<Eigen::VectorXd> best;
  double best_cost = HUGE_VAL;
  for (long mask = 0; mask < (1L << p); ++mask) {
    Eigen::Index na = 0;
    for (Eigen::Index k = 0; k < p; ++k) na += (mask >> k) & 1;
    Eigen::MatrixXd E(A.rows() + na, n);
    Eigen::VectorXd f(A.rows() + na);
    E.topRows(A.rows()) = A, f.head(A.rows()) = r;
    for (Eigen::Index k = 0, q = A.rows(); k < p; ++k)
      if ((mask >> k) & 1) E.row(q) = R.row(k), f(q++) = h(k);
    const Eigen::VectorXd lam = w.asDiagonal() * (E * w.asDiagonal()).completeOrthogonalDecomposition().solve(f);
    if ((E * lam - f).norm() > 1e-9 * (1.0 + f.norm())) continue;
    if (((R * lam - h).array() < -1e-9).any()) continue;
    const double cost = (lam.array() / w.array()).square().sum();
    if (cost < best_cost) best_cost = cost, best = lam;
  }
  return best;
}

// Claim: with general rows D λ ≥ e besides the bounds (a stuck gear's piece: two rows on its two
// reactions), the bounded split is the enumerated optimum within 1e-7 of the load scale on random
// redundant sets, and finds no split exactly where the enumeration finds none.
TEST(GearSplit, BoundedSplitWithGeneralRowsEqualsTheOptimumOverEveryActiveSet) {
  std::mt19937 gen(2929);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int feasible = 0, infeasible = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const int n = 2 + trial % 3, bodies = 1 + static_cast<int>(U(gen) * n), nd = 1 + trial % 2;
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(n, bodies);
    for (int i = 0; i < n; ++i) {
      const int a = static_cast<int>(U(gen) * bodies), b = static_cast<int>(U(gen) * (bodies + 1)) - 1;
      G(i, a) += 1.0;
      if (b >= 0 && b != a) G(i, b) -= 0.5 + U(gen);
    }
    Eigen::VectorXd im(bodies);
    for (int j = 0; j < bodies; ++j) im(j) = 0.2 + 5.0 * U(gen);
    const Eigen::MatrixXd A = G * im.asDiagonal() * G.transpose();
    Eigen::VectorXd lam_true(n), w(n), lo(n), hi(n);
    for (int i = 0; i < n; ++i) {
      lam_true(i) = 20.0 * (U(gen) - 0.5);
      const double F = 0.5 + 10.0 * U(gen);
      if (U(gen) < 0.7) lo(i) = -F, hi(i) = F, w(i) = std::sqrt(F);
      else lo(i) = -HUGE_VAL, hi(i) = HUGE_VAL, w(i) = 1e3;
    }
    Eigen::MatrixXd D(nd, n);
    Eigen::VectorXd e(nd);
    for (int k = 0; k < nd; ++k) {
      for (int i = 0; i < n; ++i) D(k, i) = U(gen) < 0.5 ? 0.0 : 2.0 * (U(gen) - 0.5);
      e(k) = 5.0 * (U(gen) - 0.7);
    }
    const Eigen::VectorXd r = A * lam_true;
    // All rows for the enumeration: the finite bounds and D.
    std::vector<Eigen::VectorXd> rows;
    std::vector<double> rhs;
    for (int i = 0; i < n; ++i) {
      Eigen::VectorXd u = Eigen::VectorXd::Zero(n);
      u(i) = 1.0;
      if (std::isfinite(lo(i))) rows.push_back(u), rhs.push_back(lo(i));
      if (std::isfinite(hi(i))) rows.push_back(-u), rhs.push_back(-hi(i));
    }
    for (int k = 0; k < nd; ++k) rows.push_back(D.row(k).transpose()), rhs.push_back(e(k));
    Eigen::MatrixXd R(static_cast<Eigen::Index>(rows.size()), n);
    Eigen::VectorXd h(static_cast<Eigen::Index>(rows.size()));
    for (size_t k = 0; k < rows.size(); ++k) R.row(static_cast<Eigen::Index>(k)) = rows[k].transpose(), h(static_cast<Eigen::Index>(k)) = rhs[k];
    const auto got = bounded_split(A, r, w, lo, hi, D, e);
    const auto want = enumerate_rows(A, r, w, R, h);
    ASSERT_EQ(got.has_value(), want.has_value()) << "trial " << trial;
    if (!want) {
      ++infeasible;
      continue;
    }
    ++feasible;
    const double scale = 1.0 + want->cwiseAbs().maxCoeff();
    EXPECT_LT((*got - *want).cwiseAbs().maxCoeff(), 1e-7 * scale) << "trial " << trial;
  }
  EXPECT_GT(feasible, 50);
  EXPECT_GT(infeasible, 5);
}

// The friction to the ground on a stuck gear's bodies (analysis/gear_lock.hpp): contacts with e_k = −1 on a
// or on b (κ_k = −e_a − e_b/i), brakes with |λ| ≤ F_s (weight √F_s) and backstops with λ ≥ 0 or λ ≤ 0
// (weight 1). The joint events of the header: m_s(F + d_s) with every contact at its bound opposing s
// (1 where the bound is infinite).
double corner_margin(const LossyGearLaw& g, int s, double Fa, double Fb, const Eigen::VectorXd& ea, const Eigen::VectorXd& eb,
                     const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  for (Eigen::Index k = 0; k < ea.size(); ++k) {
    const double kappa = -ea(k) - eb(k) / g.i, lam = s * kappa > 0.0 ? hi(k) : lo(k);
    if (!std::isfinite(lam)) return 1.0;
    Fa += ea(k) * lam, Fb += eb(k) * lam;
  }
  return g.start_margin(s, Fa, Fb);
}

// Claim: gear_friction_split finds a split exactly where both joint events are ≥ 0 (random gears, one to
// three contacts on either body, forces; points within 1e-9 of an event's zero skipped), its split is
// within every bound and leaves the gear within its locking range (1e-9 of the load scale), it is 0 where
// the gear holds alone, and with one contact it is the admissible load nearest 0 — found here by
// bisection of the gear's own start margins along the contact's line (the set is an interval: X_± rise
// with Y) — within 1e-9 of the scale.
TEST(GearSplit, FrictionSplitExistsExactlyWhereTheJointEventsHoldAndIsTheLeastLoad) {
  std::mt19937 gen(4729);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  int held = 0, started = 0, single = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const double eta1 = 0.3 + 0.7 * U(gen), eta2 = trial % 4 == 0 ? 0.0 : 0.05 + 0.9 * U(gen);
    const double bf = trial % 3 == 0 ? 0.0 : 2.0 * U(gen), ratio = (trial % 2 == 0 ? 1.0 : -1.0) * (0.5 + 10.0 * U(gen));
    const Model m = split_gear_model(eta1, eta2, bf, bf, ratio);  // the law reads its spec
    const LossyGearLaw g = LossyGearLaw::of(m.lossy_gears[0]);
    const int n = 1 + trial % 3;
    Eigen::VectorXd ea = Eigen::VectorXd::Zero(n), eb = Eigen::VectorXd::Zero(n), w(n), lo(n), hi(n);
    for (int k = 0; k < n; ++k) {
      (U(gen) < 0.5 ? ea : eb)(k) = -1.0;
      const double Fs = 0.5 + 10.0 * U(gen), kind = U(gen);
      if (kind < 0.7) lo(k) = -Fs, hi(k) = Fs, w(k) = std::sqrt(Fs);
      else if (kind < 0.85) lo(k) = 0.0, hi(k) = HUGE_VAL, w(k) = 1.0;
      else lo(k) = -HUGE_VAL, hi(k) = 0.0, w(k) = 1.0;
    }
    const double Fa = 30.0 * (U(gen) - 0.5), Fb = 30.0 * std::abs(g.i) * (U(gen) - 0.5);
    const double mp = corner_margin(g, +1, Fa, Fb, ea, eb, lo, hi), mm = corner_margin(g, -1, Fa, Fb, ea, eb, lo, hi);
    if (std::abs(mp) < 1e-9 || std::abs(mm) < 1e-9) continue;
    const auto lam = detail::gear_friction_split(g, Fa, Fb, ea, eb, w, lo, hi);
    auto state = [&] {
      std::string o = fmt::format("trial {} m+ {} m- {} eta {} {} bf {} i {} F {} {}", trial, mp, mm, eta1, eta2, bf, g.i, Fa, Fb);
      for (int k = 0; k < n; ++k) o += fmt::format(" [e {} {} lo {} hi {} w {}{}]", ea(k), eb(k), lo(k), hi(k), w(k),
                                                   lam ? fmt::format(" lam {}", (*lam)(k)) : std::string());
      return o;
    };
    ASSERT_EQ(lam.has_value(), mp >= 0.0 && mm >= 0.0) << state();
    if (!lam) {
      ++started;
      continue;
    }
    ++held;
    const double scale = 1.0 + std::abs(Fa) + std::abs(Fb);
    double X = Fa, Fbp = Fb;
    for (int k = 0; k < n; ++k) {
      EXPECT_GE((*lam)(k), lo(k) - 1e-9 * scale);
      EXPECT_LE((*lam)(k), hi(k) + 1e-9 * scale);
      X += ea(k) * (*lam)(k), Fbp += eb(k) * (*lam)(k);
    }
    EXPECT_TRUE(detail::gear_holds(g, X, -Fbp / g.i, 1e-9 * scale)) << "trial " << trial;
    if (detail::gear_holds(g, Fa, -Fb / g.i, 0.0)) {
      EXPECT_EQ(lam->cwiseAbs().maxCoeff(), 0.0) << "trial " << trial;
    }
    if (n != 1) continue;
    // One contact: the admissible λ nearest 0, by bisection of the gear's margins between 0 and the
    // split (an admissible load: the interval's end nearest 0 lies between them).
    auto holds = [&](double l) { return g.start_margin(+1, Fa + ea(0) * l, Fb + eb(0) * l) >= 0.0 &&
                                        g.start_margin(-1, Fa + ea(0) * l, Fb + eb(0) * l) >= 0.0; };
    double want = 0.0;
    if (!holds(0.0)) {
      double in = (*lam)(0), out = 0.0;
      for (int it = 0; it < 200; ++it) {
        const double mid = 0.5 * (in + out);
        (holds(mid) ? in : out) = mid;
      }
      want = in;
    }
    ++single;
    EXPECT_NEAR((*lam)(0), want, 1e-9 * scale) << "trial " << trial;
  }
  EXPECT_GT(held, 100);
  EXPECT_GT(started, 50);
  EXPECT_GT(single, 40);
}

class GearSplitSim : public ::testing::TestWithParam<const char*> {};
INSTANTIATE_TEST_SUITE_P(BothIntegrators, GearSplitSim, ::testing::Values("dopri5", "bdf"));

// ../shared/repro/physics/gear-clutch-at-rest-no-consistent-mode.yaml: a lossy gear G from b0 to b1
// (i = 20, η_mf1 = 0.99, η_mf2 = 0.1, no bearing friction), a torque P0 = 100 N·m on b0, P1 = 50 N·m on
// b2, a clutch K from b0 to b2 and ground friction Cb1 on b1, Cb2 on b2, each F_s = 300 N·m; all at rest.
// Reactions (contact loads act as a link's: +λ on the second body, −λ on the first; the gear puts −X on
// b0 and +i Y on b1), at rest:
//   b0:  P0 − λ_K − X = 0        b2:  P1 + λ_K − λ_Cb2 = 0        b1:  i Y − λ_Cb1 = 0.
// Admissible set: |λ_K|, |λ_Cb1|, |λ_Cb2| ≤ 300, and the gear within its locking range (stuck, its start
// margins ≥ 0; elements/lossy_gear.hpp with τ_bf = 0): for X ≥ 0, η_mf1 X ≤ Y ≤ X/η_mf2, for X ≤ 0,
// X/η_mf2 ≤ Y ≤ η_mf1 X (the gear passes at most η_mf1 of what a pushes in, and b pushes back through
// it only with at least 1/η_mf2). It is not empty: X = Y = 0, λ_K = 100, λ_Cb2 = 150, λ_Cb1 = 0 holds
// everything (the gear itself holds nothing: with Y = 0 it admits only X = 0). So all stuck is
// consistent and the bodies stay at rest; which admissible split the engine takes is its share rule.
// Claim, on both integrators: no event, every row at rest (|ω| ≤ 1e-12), every mode 0, the three
// balances above within 1e-9 N·m, each contact within its limit and the gear within its locking range
// (1e-9 N·m). Before the gear was bounded in the split it was a rigid support, took all of b0's load,
// and the run ended at t = 0 with exit 3 "no consistent modes of the lossy gear …".
TEST_P(GearSplitSim, AGearBesideAChainOfStuckClutchesStaysAtRestWithEveryShareWithinItsLimit) {
  const std::string yaml = fmt::format(R"(bodies:
  b0: {{type: rotational, inertia: 1}}
  b1: {{type: rotational, inertia: 1}}
  b2: {{type: rotational, inertia: 1}}
links:
  G: {{type: lossy-gear, between: [b0, b1], ratio: 20, efficiency: 0.99, efficiency_reverse: 0.1}}
loads:
  P0: {{type: constant, body: b0, value: 100}}
  P1: {{type: constant, body: b2, value: 50}}
contacts:
  Cb1: {{between: [b1, ground], static: 300, kinetic: 200}}
  Cb2: {{between: [b2, ground], static: 300, kinetic: 200}}
  K: {{between: [b0, b2], static: 300, kinetic: 200}}
simulation: {{t_end: 0.1, dt_out: 0.01, integrator: {}}}
)",
                                       GetParam());
  const SimulationResult r = simulate(test::model_text(yaml, "gear-split.yaml"));
  for (const char* e : {"G", "K", "Cb1", "Cb2"}) EXPECT_TRUE(test::events_of(r, e).empty()) << e;
  const double i = 20.0, eta1 = 0.99, eta2 = 0.1, Fs = 300.0, tol = 1e-9;
  const auto& t = series(r, "t_s");
  const auto &lK = series(r, "K.force_N_m"), &l1 = series(r, "Cb1.force_N_m"), &l2 = series(r, "Cb2.force_N_m");
  const auto &Xs = series(r, "G.torque_a_N_m"), &Tb = series(r, "G.torque_b_N_m");
  ASSERT_GT(t.size(), 5u);
  for (size_t j = 0; j < t.size(); ++j) {
    for (const char* b : {"b0", "b1", "b2"}) EXPECT_LE(std::abs(series(r, std::string(b) + ".velocity_rad_s")[j]), 1e-12);
    for (const char* e : {"G", "K", "Cb1", "Cb2"}) EXPECT_EQ(series(r, std::string(e) + ".mode")[j], 0.0) << e;
    const double X = Xs[j], Y = -Tb[j] / i;  // torque_b = −i Y (elements/lossy_gear.hpp)
    EXPECT_NEAR(100.0 - lK[j] - X, 0.0, tol) << t[j];
    EXPECT_NEAR(50.0 + lK[j] - l2[j], 0.0, tol) << t[j];
    EXPECT_NEAR(i * Y - l1[j], 0.0, tol) << t[j];
    for (double l : {lK[j], l1[j], l2[j]}) EXPECT_LE(std::abs(l), Fs + tol) << t[j];
    if (X >= 0.0) {
      EXPECT_GE(Y, eta1 * X - tol) << t[j];
      EXPECT_LE(eta2 * Y, X + tol) << t[j];
    } else {
      EXPECT_LE(Y, eta1 * X + tol) << t[j];
      EXPECT_GE(eta2 * Y, X - tol) << t[j];
    }
  }
}

// The model above with P1 a ramp, P1 = k t (k = 1000 N·m/s). From the admissible set above (the gear
// with Cb1 at its limit, |Y| ≤ F_s/i = 15, holds |X| ≤ 15/η_mf1 on both sides of 0), the set holds
// while λ_Cb2 = P1 + λ_K ≤ F_s with λ_K = P0 − X ≥ P0 − 15/η_mf1, i.e. until
//   t* = (F_s − P0 + F_s/(i η_mf1)) / k = (200 + 15/0.99)/1000 s = 0.215151… s,
// where Cb2, Cb1 and the gear reach their limits together (K at 84.85 N·m within its 300). Then b0 and
// b2 start together (K stuck), the gear rolls forward with a driving, Cb1 and Cb2 slide with their
// kinetic 200 N·m: with the lumped side a, I_a = 2 (b0 and b2), J_b = I_b1/i² = 1/400, F_a = P0 + k t −
// 200, F_b' = −200/i = −10 (elements/lossy_gear.hpp, a drives):
//   (η_mf1 I_a + J_b) a = η_mf1 F_a + F_b'  ⇒  v(t) = (η_mf1 k (t² − t*²)/2 − (η_mf1 (200 − P0) + 10)(t − t*)) / E,
// E = 1.9825; a(t*) = 104/E > 0 (consistent), and K carries λ_K = a − k t + 200 (b2's balance), within
// its limit over the run.
// Claim, on both integrators: Cb1, Cb2 and G break away at t* within 1e-9 s as the first and only
// events (Cb1, Cb2 slip+, G forward), every row before it at rest with the three balances and every
// limit as above, after it v_b0 = v_b2 = v(t) within 1e-8 rad/s (1e-6 on BDF), v_b1 = v/i, and K stuck
// with λ_K = a − k t + 200 within 1e-6 N·m.
TEST_P(GearSplitSim, TheChainAndTheGearBreakAwayTogetherWhereTheLockingRangeAndTheLimitsRunOut) {
  const std::string yaml = fmt::format(R"(bodies:
  b0: {{type: rotational, inertia: 1}}
  b1: {{type: rotational, inertia: 1}}
  b2: {{type: rotational, inertia: 1}}
links:
  G: {{type: lossy-gear, between: [b0, b1], ratio: 20, efficiency: 0.99, efficiency_reverse: 0.1}}
loads:
  P0: {{type: constant, body: b0, value: 100}}
  P1: {{type: ramp, body: b2, value: 1000, end: 1 s}}
contacts:
  Cb1: {{between: [b1, ground], static: 300, kinetic: 200}}
  Cb2: {{between: [b2, ground], static: 300, kinetic: 200}}
  K: {{between: [b0, b2], static: 300, kinetic: 200}}
simulation: {{t_end: 0.3, dt_out: 0.01, rtol: 1e-10, integrator: {}}}
)",
                                       GetParam());
  const SimulationResult r = simulate(test::model_text(yaml, "gear-split-ramp.yaml"));
  const double i = 20.0, eta1 = 0.99, k = 1000.0, P0 = 100.0, Fs = 300.0, Fk = 200.0, E = eta1 * 2.0 + 1.0 / (i * i);
  const double ts = (Fs - P0 + Fs / (i * eta1)) / k;
  const auto& ev = r.hybrid.events;
  int n = 0;
  for (const auto& e : ev) {
    if (e.kind == "initial") continue;
    ++n;
    EXPECT_NEAR(e.t, ts, 1e-9) << e.element;
    EXPECT_EQ(e.kind, "slip") << e.element;
    EXPECT_EQ(e.to, e.element == "G" ? "forward" : "slip+") << e.element;
  }
  EXPECT_EQ(n, 3);
  EXPECT_TRUE(test::events_of(r, "K").empty());
  const double tol = std::string(GetParam()) == "bdf" ? 1e-6 : 1e-8;
  const auto& t = series(r, "t_s");
  const auto &lK = series(r, "K.force_N_m"), &l1 = series(r, "Cb1.force_N_m"), &l2 = series(r, "Cb2.force_N_m");
  const auto &v0 = series(r, "b0.velocity_rad_s"), &v1 = series(r, "b1.velocity_rad_s"), &v2 = series(r, "b2.velocity_rad_s");
  const auto &Xs = series(r, "G.torque_a_N_m"), &Tb = series(r, "G.torque_b_N_m");
  for (size_t j = 0; j < t.size(); ++j) {
    const double P1 = k * t[j];
    if (t[j] < ts - 1e-9) {
      EXPECT_EQ(v0[j], 0.0) << t[j];
      const double X = Xs[j], Y = -Tb[j] / i;
      EXPECT_NEAR(P0 - lK[j] - X, 0.0, 1e-9) << t[j];
      EXPECT_NEAR(P1 + lK[j] - l2[j], 0.0, 1e-9) << t[j];
      EXPECT_NEAR(i * Y - l1[j], 0.0, 1e-9) << t[j];
      for (double l : {lK[j], l1[j], l2[j]}) EXPECT_LE(std::abs(l), Fs + 1e-9) << t[j];
      EXPECT_LE(std::abs(X), 15.0 / eta1 + 1e-9) << t[j];
    } else if (t[j] > ts + 1e-9) {
      const double v = (eta1 * k * (t[j] * t[j] - ts * ts) / 2.0 - (eta1 * (Fk - P0) + Fk / i) * (t[j] - ts)) / E;
      const double a = (eta1 * (P0 + P1 - Fk) - Fk / i) / E;
      EXPECT_NEAR(v0[j], v, tol) << t[j];
      EXPECT_EQ(v2[j], v0[j]) << t[j];
      EXPECT_NEAR(v1[j], v0[j] / i, 1e-12 * (1.0 + std::abs(v0[j]))) << t[j];
      EXPECT_NEAR(lK[j], a - P1 + Fk, 1e-6) << t[j];
      EXPECT_EQ(series(r, "K.mode")[j], 0.0) << t[j];
    }
  }
}

}  // namespace MACHDYN_UNITY_ID
}  // namespace machdyn
