// A two-stage lossy gearbox (analysis/gear_train.hpp): two lossy gears on one shaft, decided, solved and
// evented together. Closed forms of the series law (forward drive, back-driven, the self-locking hold
// and its start, a reversal of the power flow), the stuck train's margins against its split (a second
// algorithm), a train whose second stage is lossless against the single gear's law, and the located
// errors of what stays unsupported.
#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/gear_train.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/events.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::events_of;
using test::series;

/// A lossy gear's spec and law (elements/lossy_gear.hpp) between bodies a and b.
struct GearSpec {
  LossyGear g;
  LossyGearLaw law() const { return LossyGearLaw::of(g); }
};
GearSpec make_gear(int a, int b, double i, double e1, double e2, double bf1 = 0.0, double bf2 = 0.0) {
  GearSpec s;
  s.g.name = "G";
  s.g.a = a, s.g.b = b, s.g.ratio = i;
  s.g.eta_forward = {e1}, s.g.eta_reverse = {e2}, s.g.bearing_forward = {bf1}, s.g.bearing_reverse = {bf2};
  return s;
}

// Claim: a stuck train's two start margins are both ≥ 0 exactly where a split of the shaft torque with
// both gears inside their locking ranges exists (stuck_train_torques' interval, found from the single
// gears' margins: a second algorithm), and the split it returns holds both gears; over random ratios,
// efficiencies, bearing friction, orientations and forces (cases within 1e-9 of the boundary skipped).
// Six seeds, each in two orders of the gears' draws (the two orders GCC and clang once took: the
// massless-shaft class of AMasslessShaft… was found by one of them only), 48 000 cases.
TEST(GearTrain, MarginsAndSplitAgree) {
  int held = 0, started = 0;
  for (unsigned seed = 7; seed < 13; ++seed)
    for (const bool ratio_first : {false, true}) {
      std::mt19937 rng(seed);
      std::uniform_real_distribution<double> U(0.0, 1.0);
      for (int n = 0; n < 4000; ++n) {
        // Bodies 0 (outer of gear 1), 1 (shared), 2 (outer of gear 2); each gear in either orientation.
        const bool flip1 = U(rng) < 0.5, flip2 = U(rng) < 0.5;
        // Every draw in its own statement: function arguments and a product's operands are evaluated in
        // the compiler's order (GCC and clang differ), and both builds must test the same cases.
        auto ratio = [&] {
          const double sign = U(rng) < 0.3 ? -1.0 : 1.0;
          return sign * std::exp(std::log(0.2) + U(rng) * std::log(25.0));
        };
        auto eta = [&] { return 0.3 + 0.7 * U(rng); };
        const double e2a = U(rng) < 0.2 ? 0.0 : eta(), e2b = U(rng) < 0.2 ? 0.0 : eta();
        const double bf = U(rng) < 0.5 ? 0.0 : 0.5 * U(rng);
        double eta1 = 0.0, i1 = 0.0, eta2 = 0.0, i2 = 0.0;
        if (ratio_first) {
          i1 = ratio(), eta1 = eta(), i2 = ratio(), eta2 = eta();
        } else {
          eta1 = eta(), i1 = ratio(), eta2 = eta(), i2 = ratio();
        }
        std::vector<GearSpec> specs{flip1 ? make_gear(1, 0, i1, eta1, e2a, bf, bf) : make_gear(0, 1, i1, eta1, e2a, bf, bf),
                                    flip2 ? make_gear(2, 1, i2, eta2, e2b) : make_gear(1, 2, i2, eta2, e2b)};
        std::vector<LossyGearLaw> laws{specs[0].law(), specs[1].law()};
        laws[0].spec = &specs[0].g, laws[1].spec = &specs[1].g;
        const std::vector<double> inertia{0.5 + U(rng), U(rng) < 0.3 ? 0.0 : U(rng), 0.5 + 2.0 * U(rng)};
        const std::vector<GearTrain> trains = find_gear_trains(laws, inertia);
        ASSERT_EQ(trains.size(), 1u);
        const GearTrain& tr = trains[0];
        const std::array<double, 3> F{4.0 * (U(rng) - 0.5), 4.0 * (U(rng) - 0.5), 4.0 * (U(rng) - 0.5)};
        const std::array<double, 3> I{inertia[0], inertia[1], inertia[2]};
        const double mp = train_start_margin(tr, laws, +1, F, I), mm = train_start_margin(tr, laws, -1, F, I);
        EXPECT_FALSE(mp < -1e-12 && mm < -1e-12) << "both directions start, seed " << seed << " case " << n;
        if (std::abs(mp) < 1e-9 || std::abs(mm) < 1e-9) continue;
        std::array<double, 2> iv{};
        const auto T = stuck_train_torques(tr, laws, F, &iv);
        const bool holds = mp >= 0.0 && mm >= 0.0;
        EXPECT_EQ(holds, iv[0] <= iv[1] + 1e-9 * (1.0 + std::abs(iv[0]))) << "seed " << seed << " order " << ratio_first << " case " << n << " margins " << mp << " " << mm
                                                                          << " interval " << iv[0] << " " << iv[1] << fmt::format(" flip {} {} i {:.17g} {:.17g} e {:.17g} {:.17g} r {:.17g} {:.17g} bf {:.17g} J {:.17g} {:.17g} {:.17g} F {:.17g} {:.17g} {:.17g}", flip1, flip2, i1, i2, eta1, eta2, e2a, e2b, bf, inertia[0], inertia[1], inertia[2], F[0], F[1], F[2]);
        if (!holds) {
          ++started;
          continue;
        }
        ++held;
        for (int k = 0; k < 2; ++k) {  // both gears inside their locking ranges; the bodies balanced
          const LossyGearLaw& L = laws[static_cast<size_t>(k)];
          const auto& t = T[static_cast<size_t>(k)];
          for (int s : {+1, -1}) EXPECT_GE(L.start_margin(s, t.X, -L.i * t.Y), -1e-9) << "case " << n << " gear " << k;
        }
        std::array<double, 3> net = F;
        for (int k = 0; k < 2; ++k) {
          const LossyGearLaw& L = laws[static_cast<size_t>(k)];
          net[static_cast<size_t>(L.a)] -= T[static_cast<size_t>(k)].X;
          net[static_cast<size_t>(L.b)] += L.i * T[static_cast<size_t>(k)].Y;
        }
        for (double x : net) EXPECT_NEAR(x, 0.0, 1e-9) << "case " << n;
      }
    }
  EXPECT_GT(held, 3000);
  EXPECT_GT(started, 3000);
}

// A massless shaft S between two self-locking stages (η' = 0), S the driving side A of both: G1 S–R
// (v_S = i1 v_R, bearing friction τ on it), G2 S–C (v_S = i2 v_C, i2 < 0), loads F_R, F_C, F_S — the case
// of GearTrain.MarginsAndSplitAgree that one draw order found. In S's coordinate f_R = F_R/i1,
// f_C = F_C/i2, J_R = I_R/i1², J_C = I_C/i2². Neither R nor C can drive S (self-locking: X = 0 while B
// drives), so only F_S moves the train; with I_S = 0 the shaft's equation F_S = X1 + X2 has no rolling
// solution in a direction whose stages cannot take F_S, and the train cannot start there. Each gear
// alone (elements/lossy_gear.hpp start_margin with η_mf2 = 0, so τ_bf,a = 0, τ_bf,b = τ) holds while
//   0 ≤ X1 ≤ X1⁺ = (τ − f_R)/η1,   0 ≤ X2 ≤ X2⁺ = −f_C/η2        (for f_R + τ ≤ 0, f_C ≤ 0)
// (a start forward needs S to lift the loads through the mesh: η X − f − τ ≥ 0; backward, X < 0 would
// need S to drive backward, which F_S ≥ 0 does not). The train holds while 0 ≤ F_S ≤ X1⁺ + X2⁺ = F⁺,
// with the split of least losses X1 = clamp((F_S + f_C − f_R)/2, max(0, F_S − X2⁺), min(X1⁺, F_S))
// (gear_train.hpp: the least (X1 − Y1)² + (X2 − Y2)², Y1 = −f_R, Y2 = −f_C, X2 = F_S − X1), and starts
// forward where F_S passes F⁺: both stages driven by S, X_k = (J_k α − f_k + τ_k)/η_k, so
//   (J_R/η1 + J_C/η2) α = F_S − F⁺.
struct MasslessShaftCase {
  double i1 = 1.8535694978365846, i2 = -0.5812909742737753, e1 = 0.81182531397251667, e2 = 0.78875349939313155;
  double bf = 0.35056933630528359, IR = 1.3200918195469853, IC = 2.020821782939016;
  double FR = -0.83536183301473055, FS = 0.58190436883599617, FC = 0.43446884655886864;
  [[nodiscard]] double fR() const { return FR / i1; }
  [[nodiscard]] double fC() const { return FC / i2; }
  [[nodiscard]] double X1max() const { return (bf - fR()) / e1; }
  [[nodiscard]] double X2max() const { return -fC() / e2; }
  [[nodiscard]] double Fmax() const { return X1max() + X2max(); }
  [[nodiscard]] double M() const { return IR / (i1 * i1) / e1 + IC / (i2 * i2) / e2; }
  [[nodiscard]] double X1(double Fs) const {
    return std::clamp(0.5 * (Fs + fC() - fR()), std::max(0.0, Fs - X2max()), std::min(X1max(), Fs));
  }
};

// Claim: that case holds (both start margins ≥ 0; before the fix its margin backward was −0.569, from
// an inconsistent rolling solution), its interval of τ = −X1 is [−F_S, 0] and its split the closed
// form above; F_S beyond F⁺ starts it forward, F_S < 0 backward.
TEST(GearTrain, AMasslessShaftBetweenSelfLockingStagesHoldsUntilItsLoadLiftsBoth) {
  const MasslessShaftCase c;
  ASSERT_LT(c.fR() + c.bf, 0.0);
  ASSERT_LT(c.fC(), 0.0);
  std::vector<GearSpec> specs{make_gear(1, 0, c.i1, c.e1, 0.0, c.bf, c.bf), make_gear(1, 2, c.i2, c.e2, 0.0)};
  std::vector<LossyGearLaw> laws{specs[0].law(), specs[1].law()};
  laws[0].spec = &specs[0].g, laws[1].spec = &specs[1].g;
  const std::array<double, 3> I{c.IR, 0.0, c.IC};
  const GearTrain tr = find_gear_trains(laws, {I[0], I[1], I[2]}).at(0);
  for (double Fs : {c.FS, 0.3 * c.Fmax(), 0.9 * c.Fmax()}) {
    const std::array<double, 3> F{c.FR, Fs, c.FC};
    EXPECT_GT(train_start_margin(tr, laws, +1, F, I), 0.0) << Fs;
    EXPECT_GT(train_start_margin(tr, laws, -1, F, I), 0.0) << Fs;
    std::array<double, 2> iv{};
    const auto T = stuck_train_torques(tr, laws, F, &iv);
    EXPECT_NEAR(iv[0], -std::min(Fs, c.X1max()), 1e-9) << Fs;
    EXPECT_NEAR(iv[1], -std::max(0.0, Fs - c.X2max()), 1e-9) << Fs;
    EXPECT_NEAR(T[0].X, c.X1(Fs), 1e-9) << Fs;
    EXPECT_NEAR(T[1].X, Fs - c.X1(Fs), 1e-9) << Fs;
  }
  EXPECT_LT(train_start_margin(tr, laws, +1, {c.FR, 1.01 * c.Fmax(), c.FC}, I), 0.0);
  EXPECT_GT(train_start_margin(tr, laws, -1, {c.FR, 1.01 * c.Fmax(), c.FC}, I), 0.0);
  EXPECT_LT(train_start_margin(tr, laws, -1, {c.FR, -0.01, c.FC}, I), 0.0);
  EXPECT_GT(train_start_margin(tr, laws, +1, {c.FR, -0.01, c.FC}, I), 0.0);
}

// Claim: a train whose second stage is lossless (η = 1 both ways, no bearing friction) is the first
// gear alone with the shaft and the second stage's body on its side: J_b = I_m + I_c/i₂² (in m's
// coordinate) and F_b = F_m + F_c/i₂. Its start margins have the single gear's signs and its rolling
// acceleration the single gear's (LossyGearLaw::solve), both directions, over random cases.
TEST(GearTrain, ALosslessSecondStageIsTheSingleGear) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> U(0.0, 1.0);
  for (int n = 0; n < 500; ++n) {
    const double i1 = 0.5 + 4.0 * U(rng), i2 = 0.5 + 4.0 * U(rng);
    std::vector<GearSpec> specs{make_gear(0, 1, i1, 0.3 + 0.7 * U(rng), 0.7 * U(rng), 0.2 * U(rng), 0.3 * U(rng)),
                                make_gear(1, 2, i2, 1.0, 1.0)};
    std::vector<LossyGearLaw> laws{specs[0].law(), specs[1].law()};
    laws[0].spec = &specs[0].g, laws[1].spec = &specs[1].g;
    const std::array<double, 3> I{0.5 + U(rng), U(rng), 0.5 + U(rng)};
    const std::array<double, 3> F{3.0 * (U(rng) - 0.5), 3.0 * (U(rng) - 0.5), 3.0 * (U(rng) - 0.5)};
    const GearTrain tr = find_gear_trains(laws, {I[0], I[1], I[2]}).at(0);
    const double Ib = I[1] + I[2] / (i2 * i2), Fb = F[1] + F[2] / i2;
    const LossyGearLaw& one = laws[0];
    for (int s : {+1, -1}) {
      const double m_one = one.start_margin(s, F[0], Fb), m_train = train_start_margin(tr, laws, s, F, I);
      if (std::abs(m_one) > 1e-9) {
        EXPECT_EQ(m_one > 0.0, m_train > 0.0) << n << " s " << s << " " << m_one << " " << m_train;
      }
      // Rolling at v_a = 0.7 s: the same acceleration of body a.
      const double v = 0.7 * s;
      const TrainSolution x = train_rolling(tr, laws, s, F, I, v);
      const LossyGearLaw::Torques T = one.solve(one.rolling(s, F[0], Fb, I[0], Ib, v), F[0], Fb, I[0], Ib, v);
      EXPECT_NEAR(x.acc, T.acc, 1e-10 * (1.0 + std::abs(T.acc))) << n << " s " << s;
      EXPECT_NEAR(x.T[0].X, T.X, 1e-10 * (1.0 + std::abs(T.X))) << n;
    }
  }
}

// The two-stage hoist gearbox of the simulation tests: motor M (J1) –G1 (i1)– shaft S (J2) –G2 (i2)–
// drum D (J3), motor torque T(t) on M, load torque L on D (constant). In M's coordinate (α = M's
// acceleration, the shaft turns α/i1, the drum α/(i1 i2)) the bodies' equations are
//   J1 α = T − X1,   J2 α/i1 = i1 Y1 − X2,   J3 α/(i1 i2) = i2 Y2 + L.
// Forward with the motor driving both stages (Y_k = η_k X_k):
//   α (η1 η2 J1 + η2 J2/i1² + J3/(i1 i2)²) = η1 η2 T + L/(i1 i2),
// the drum torque i2 Y2 = i1 i2 η1 η2 (T − J1 α) − i2 η2 J2 α / i1 (= i1 i2 η1 η2 T at steady speed).
// Back-driven with the drum driving both (X_k = η'_k Y_k, η' the reverse efficiencies):
//   α (J1 + η'1 J2/i1² + η'1 η'2 J3/(i1 i2)²) = T + η'1 η'2 L/(i1 i2):
// the back efficiency of the train is η'1 η'2; with η'2 = 0 (a self-locking stage) no load on the
// drum moves the motor: the train holds any L while T lies between the forward start
// T = −L/(i1 i2 η1 η2) and 0.
struct Hoist {
  double J1 = 0.2, J2 = 0.05, J3 = 8.0, i1 = 4.0, i2 = 5.0;
  double e1 = 0.95, r1 = 0.9, e2 = 0.85, r2 = 0.7;
  [[nodiscard]] double forward_mass() const { return e1 * e2 * J1 + e2 * J2 / (i1 * i1) + J3 / (i1 * i1 * i2 * i2); }
  [[nodiscard]] double back_mass() const { return J1 + r1 * J2 / (i1 * i1) + r1 * r2 * J3 / (i1 * i1 * i2 * i2); }
  [[nodiscard]] double forward_acc(double T, double L) const { return (e1 * e2 * T + L / (i1 * i2)) / forward_mass(); }
  [[nodiscard]] double back_acc(double T, double L) const { return (T + r1 * r2 * L / (i1 * i2)) / back_mass(); }
  [[nodiscard]] double drum_torque_forward(double T, double L) const {
    const double a = forward_acc(T, L);
    return i1 * i2 * e1 * e2 * (T - J1 * a) - i2 * e2 * J2 * a / i1;
  }
  /// The model: motor torque `torque` (a load spec), drum load L, t_end.
  [[nodiscard]] std::string yaml(const std::string& torque, double L, double t_end, const char* integrator,
                                 double v0 = 0.0) const {
    return fmt::format(R"(bodies:
  M: {{inertia: {} kg*m^2, velocity: {} rad/s}}
  S: {{inertia: {} kg*m^2}}
  D: {{inertia: {} kg*m^2}}
links:
  G1: {{type: lossy-gear, between: [M, S], ratio: {}, efficiency: {}, efficiency_reverse: {}}}
  G2: {{type: lossy-gear, between: [S, D], ratio: {}, efficiency: {}, efficiency_reverse: {}}}
loads:
  T: {}
  L: {{type: constant, body: D, value: {} N*m}}
simulation: {{t_end: {}, dt_out: 0.01, rtol: 1e-11, atol: 1e-13, integrator: {}}}
)",
                       J1, v0, J2, J3, i1, e1, r1, i2, e2, r2, torque, L, t_end, integrator);
  }
};

/// The mode a run's initial decision gave element `name`.
std::string initial_mode(const SimulationResult& r, const std::string& name) {
  for (const auto& e : r.hybrid.events)
    if (e.element == name && e.kind == "initial") return e.to;
  return "";
}

class GearTrainSim : public ::testing::TestWithParam<const char*> {};
INSTANTIATE_TEST_SUITE_P(BothIntegrators, GearTrainSim, ::testing::Values("dopri5", "bdf"));

double tol_of(const char* integrator, double scale) { return (std::string(integrator) == "bdf" ? 1e-6 : 1e-8) * scale; }

// Claim: a constant motor torque lifting a load through both stages accelerates the drum at the
// closed form α/(i1 i2) from rest (v_D = α t/(i1 i2)), both gears started forward with the motor
// driving by the initial decision (no event after it), the drum torque −G2.torque_b = i1 i2 η1 η2 T minus the inertias' share
// (header), the heat of each stage ≥ 0; with and without the shaft's own inertia.
TEST_P(GearTrainSim, ForwardDriveFollowsTheSeriesEfficiency) {
  for (double J2 : {0.05, 0.0}) {
    Hoist h;
    h.J2 = J2;
    const double T = 30.0, L = -300.0;
    const SimulationResult r =
        simulate(test::model_text(h.yaml(fmt::format("{{type: constant, body: M, value: {} N*m}}", T), L, 1.0, GetParam()), "train.yaml"));
    for (const char* g : {"G1", "G2"}) {
      EXPECT_EQ(events_of(r, g).size(), 0u) << g << " J2 " << J2;
      EXPECT_EQ(initial_mode(r, g), "forward") << g;
    }
    const double a = h.forward_acc(T, L);
    ASSERT_GT(a, 0.0);
    const auto t = series(r, "t_s"), vD = series(r, "D.velocity_rad_s"), tb = series(r, "G2.torque_b_N_m"),
               q1 = series(r, "G1.loss_power_W"), q2 = series(r, "G2.loss_power_W");
    for (size_t k = 1; k < t.size(); ++k) {
      EXPECT_NEAR(vD[k], a * t[k] / (h.i1 * h.i2), tol_of(GetParam(), 1.0)) << "t " << t[k];
      EXPECT_NEAR(-tb[k], h.drum_torque_forward(T, L), 1e-9 * std::abs(L)) << "t " << t[k];
      EXPECT_GE(q1[k], 0.0);
      EXPECT_GE(q2[k], 0.0);
    }
  }
}

// Claim: an overhauling load lowers through both stages with the drum driving: from rest it starts
// backward at once (both gears backward, side b driving) and accelerates at the closed form of the
// reverse efficiencies η'1 η'2 (header), within the integrator's tolerance (no event after the
// initial decision).
TEST_P(GearTrainSim, BackDrivenLoadFollowsTheReverseEfficiencies) {
  Hoist h;
  const double T = 5.0, L = -300.0;  // the motor brakes with 5 N·m, less than the load's 300 η'1 η'2/20 = 9.45 N·m
  const SimulationResult r =
      simulate(test::model_text(h.yaml(fmt::format("{{type: constant, body: M, value: {} N*m}}", T), L, 1.0, GetParam()), "train.yaml"));
  for (const char* g : {"G1", "G2"}) {
    EXPECT_EQ(events_of(r, g).size(), 0u) << g;
    EXPECT_EQ(initial_mode(r, g), "backward_b_drives") << g;
  }
  const double a = h.back_acc(T, L);
  ASSERT_LT(a, 0.0);
  const auto t = series(r, "t_s"), vM = series(r, "M.velocity_rad_s");
  for (size_t k = 1; k < t.size(); ++k) EXPECT_NEAR(vM[k], a * t[k], tol_of(GetParam(), 10.0)) << "t " << t[k];
}

// Claim: with a self-locking second stage (η'2 = 0) the train holds the load at rest with no motor
// torque (no event, every speed exactly 0), and a motor torque ramp T = k t lifts it from the closed
// form instant t* = −L/(i1 i2 η1 η2 k) on (within 1e-8 s), after which v_M = η1 η2 k (t − t*)²/(2 M_f).
TEST_P(GearTrainSim, ASelfLockingStageHoldsTheLoadUntilTheMotorLiftsIt) {
  Hoist h;
  h.r2 = 0.0;
  const double L = -300.0, k = 40.0;
  const double ts = -L / (h.i1 * h.i2 * h.e1 * h.e2 * k);
  const SimulationResult r = simulate(test::model_text(
      h.yaml(fmt::format("{{type: ramp, body: M, before: 0 N*m, value: {} N*m, start: 0 s, end: 2 s}}", 2.0 * k), L, 2.0,
             GetParam()),
      "train.yaml"));
  for (const char* g : {"G1", "G2"}) {
    const auto ev = events_of(r, g);
    ASSERT_EQ(ev.size(), 1u) << g;
    EXPECT_EQ(ev[0].kind, "slip");
    EXPECT_EQ(ev[0].to, "forward");
    EXPECT_NEAR(ev[0].t, ts, 1e-8) << g;
  }
  const auto t = series(r, "t_s"), vM = series(r, "M.velocity_rad_s"), vD = series(r, "D.velocity_rad_s");
  for (size_t n = 0; n < t.size(); ++n) {
    if (t[n] <= ts) {
      EXPECT_EQ(vM[n], 0.0) << "t " << t[n];
      EXPECT_EQ(vD[n], 0.0) << "t " << t[n];
    } else {
      EXPECT_NEAR(vM[n], h.e1 * h.e2 * k * (t[n] - ts) * (t[n] - ts) / (2.0 * h.forward_mass()), tol_of(GetParam(), 10.0))
          << "t " << t[n];
    }
  }
}

// Claim: a motor torque falling through zero while the train rolls forward reverses the power flow
// stage by stage, each at its closed-form instant (within 1e-8 s). In the forward phase (header)
// X1 = T − J1 α is affine in T: the motor's stage switches first, where X1 = 0 (at T < 0: the motor
// brakes the drum's inertia). Then G1 runs on side b (X1 = η'1 Y1) and G2 still on side a
// (Y2 = η2 X2): from the bodies' equations
//   α (J3/(i1 i2) + i1 i2 η2 J1/η'1 + i2 η2 J2/i1) = i1 i2 η2 T/η'1 + L,
//   X2 = i1 (T − J1 α)/η'1 − J2 α/i1,
// and G2 switches where X2 = 0. T(t) = T0 − k t, both instants from the roots in T.
TEST_P(GearTrainSim, AReversalOfThePowerFlowSwitchesEachStageAtItsClosedFormInstant) {
  Hoist h;
  const double L = -50.0, T0 = 40.0, k = 40.0, v0 = 60.0;
  auto root = [](auto f) {  // an affine function's zero from two values
    const double f0 = f(0.0), f1 = f(1.0);
    return -f0 / (f1 - f0);
  };
  const double T1 = root([&](double T) { return T - h.J1 * h.forward_acc(T, L); });
  auto acc_mixed = [&](double T) {
    return (h.i1 * h.i2 * h.e2 * T / h.r1 + L) /
           (h.J3 / (h.i1 * h.i2) + h.i1 * h.i2 * h.e2 * h.J1 / h.r1 + h.i2 * h.e2 * h.J2 / h.i1);
  };
  const double T2 = root([&](double T) { return h.i1 * (T - h.J1 * acc_mixed(T)) / h.r1 - h.J2 * acc_mixed(T) / h.i1; });
  const double t1 = (T0 - T1) / k, t2 = (T0 - T2) / k;
  ASSERT_LT(t1, t2);
  const SimulationResult r = simulate(test::model_text(
      h.yaml(fmt::format("{{type: ramp, body: M, before: {} N*m, value: {} N*m, start: 0 s, end: 2 s}}", T0, T0 - 2.0 * k), L,
             t2 + 0.2, GetParam(), v0),
      "train.yaml"));
  const auto e1 = events_of(r, "G1"), e2 = events_of(r, "G2");
  ASSERT_EQ(e1.size(), 1u);
  EXPECT_EQ(e1[0].kind, "driving_side");
  EXPECT_EQ(e1[0].to, "forward_b_drives");
  EXPECT_NEAR(e1[0].t, t1, 1e-8);
  ASSERT_EQ(e2.size(), 1u);
  EXPECT_EQ(e2[0].kind, "driving_side");
  EXPECT_EQ(e2[0].to, "forward_b_drives");
  EXPECT_NEAR(e2[0].t, t2, 1e-8);
  const auto vM = series(r, "M.velocity_rad_s");
  EXPECT_GT(vM.back(), 0.0) << "still rolling forward at the end";
}

// Claim: examples/crane/two-stage-gearbox.yaml (README.md beside it) lifts from the closed-form instant
// t* = 2500/(i1 i2 η1 η2 · 45 N·m/s) and coasts to rest at 4 s + v(4)/|α_off| after the switch-off
// (within 1e-7 s): v(4) = η1 η2 45 (1 − t*)²/(2 M_f) + 3 α_45, α_45 = (45 η1 η2 − 25)/M_f,
// α_off = −25/M_f (the motor's inertia still drives both stages while it coasts), M_f as in Hoist;
// after it the self-locking worm stage holds the load: both gears stuck, every speed exactly 0.
TEST_P(GearTrainSim, TheTwoStageGearboxExampleLiftsAndHoldsAtTheClosedFormInstants) {
  Model m = load_model(test::example("crane/two-stage-gearbox.yaml"));
  m.simulation.integrator = std::string(GetParam()) == "bdf" ? IntegratorChoice::bdf : IntegratorChoice::dopri5;
  const SimulationResult r = simulate(m);
  Hoist h;
  h.J1 = 0.25, h.J2 = 0.02, h.J3 = 60.0, h.i1 = 5.0, h.i2 = 20.0, h.e1 = 0.97, h.e2 = 0.72;
  const double L = -2500.0, ts = -L / (h.i1 * h.i2 * h.e1 * h.e2 * 45.0);
  const double a45 = h.forward_acc(45.0, L), aoff = h.forward_acc(0.0, L);
  const double v4 = h.e1 * h.e2 * 45.0 * (1.0 - ts) * (1.0 - ts) / (2.0 * h.forward_mass()) + 3.0 * a45;
  const double t_stop = 4.0 - v4 / aoff;
  for (const char* g : {"helical", "worm"}) {
    const auto ev = events_of(r, g);
    ASSERT_EQ(ev.size(), 2u) << g;
    EXPECT_EQ(ev[0].kind, "slip");
    EXPECT_NEAR(ev[0].t, ts, 1e-8) << g;
    EXPECT_EQ(ev[1].kind, "stick");
    EXPECT_NEAR(ev[1].t, t_stop, 1e-7) << g;
  }
  const auto t = series(r, "t_s"), v = series(r, "motor.velocity_rad_s");
  for (size_t k = 0; k < t.size(); ++k)
    if (t[k] > t_stop || t[k] < ts) {
      EXPECT_EQ(v[k], 0.0) << "t " << t[k];
    }
}

// Claim: the massless-shaft case as a run: with F_S held at its value the train stays at rest (no event,
// every speed exactly 0, the split's torques X1, X2 of the closed form); F_S ramped at k from t0 lifts
// both stages at t* = t0 + (F⁺ − F_S)/k (within 1e-8 s), after which v_S = k (t − t*)²/(2 M),
// M = J_R/η1 + J_C/η2 (MasslessShaftCase).
TEST_P(GearTrainSim, AMasslessShaftBetweenSelfLockingStagesIsLiftedAtTheClosedFormInstant) {
  const MasslessShaftCase c;
  const double k = 2.0, t0 = 0.5, ts = t0 + (c.Fmax() - c.FS) / k;
  const std::string text = fmt::format(R"(bodies:
  R: {{inertia: {} kg*m^2}}
  S: {{inertia: 0 kg*m^2}}
  C: {{inertia: {} kg*m^2}}
links:
  G1: {{type: lossy-gear, between: [S, R], ratio: {}, efficiency: {}, efficiency_reverse: 0, bearing_friction: {} N*m}}
  G2: {{type: lossy-gear, between: [S, C], ratio: {}, efficiency: {}, efficiency_reverse: 0}}
loads:
  LR: {{type: constant, body: R, value: {} N*m}}
  LC: {{type: constant, body: C, value: {} N*m}}
  LS: {{type: ramp, body: S, before: {} N*m, value: {} N*m, start: {} s, end: {} s}}
simulation: {{t_end: {}, dt_out: 0.01, rtol: 1e-11, atol: 1e-13, integrator: {}}}
)",
                                       c.IR, c.IC, c.i1, c.e1, c.bf, c.i2, c.e2, c.FR, c.FC, c.FS,
                                       c.FS + k * 10.0, t0, t0 + 10.0, ts + 0.3, GetParam());
  const SimulationResult r = simulate(test::model_text(text, "massless-shaft.yaml"));
  for (const char* g : {"G1", "G2"}) {
    EXPECT_EQ(initial_mode(r, g), "stuck") << g;
    const auto ev = events_of(r, g);
    ASSERT_EQ(ev.size(), 1u) << g;
    EXPECT_EQ(ev[0].kind, "slip");
    EXPECT_EQ(ev[0].to, "forward");
    EXPECT_NEAR(ev[0].t, ts, 1e-8) << g;
  }
  const auto t = series(r, "t_s"), vS = series(r, "S.velocity_rad_s"), vR = series(r, "R.velocity_rad_s"),
             X1 = series(r, "G1.torque_a_N_m"), X2 = series(r, "G2.torque_a_N_m");
  for (size_t n = 0; n < t.size(); ++n) {
    const double Fs = c.FS + k * std::max(0.0, t[n] - t0);
    if (t[n] < ts) {
      EXPECT_EQ(vS[n], 0.0) << "t " << t[n];
      EXPECT_EQ(vR[n], 0.0) << "t " << t[n];
      EXPECT_NEAR(X1[n], c.X1(Fs), 1e-9) << "t " << t[n];
      EXPECT_NEAR(X2[n], Fs - c.X1(Fs), 1e-9) << "t " << t[n];
    } else {
      EXPECT_NEAR(vS[n], k * (t[n] - ts) * (t[n] - ts) / (2.0 * c.M()), tol_of(GetParam(), 10.0)) << "t " << t[n];
    }
  }
}

// Claim: what stays unsupported on a two-stage train is a located error (exit 2 from the CLI): a
// friction element on one of its bodies, a third stage, a massless outer body.
TEST(GearTrainCompile, UnsupportedCombinationsAreLocatedErrors) {
  const std::string base = R"(bodies:
  M: {inertia: 0.2 kg*m^2}
  S: {inertia: 0.05 kg*m^2}
  D: {inertia: 8 kg*m^2}
  E: {inertia: 1 kg*m^2}
links:
  G1: {type: lossy-gear, between: [M, S], ratio: 4, efficiency: 0.9}
  G2: {type: lossy-gear, between: [S, D], ratio: 5, efficiency: 0.8}
)";
  EXPECT_EQ(test::compile_errors(base, "ok.yaml"), "");
  auto fails = [&](const std::string& extra, const std::string& words) {
    const std::string e = test::compile_errors(base + extra, "bad.yaml");
    EXPECT_NE(e.find(words), std::string::npos) << e;
    EXPECT_NE(e.find("bad.yaml:"), std::string::npos) << e;
  };
  fails("  G3: {type: lossy-gear, between: [D, E], ratio: 2, efficiency: 0.8}\n", "more than two lossy gears");
  fails("brakes:\n  br: {body: S, holding: 2 N*m}\n", "two-stage train");
  const std::string massless = std::string(base).replace(base.find("M: {inertia: 0.2"), 16, "M: {inertia: 0  ");
  EXPECT_NE(test::compile_errors(massless, "bad.yaml").find("zero inertia"), std::string::npos);
}

}  // namespace MACHDYN_UNITY_ID
}  // namespace machdyn
