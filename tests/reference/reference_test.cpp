// The reference simulator itself against closed forms (so a later mismatch with the engine can be
// trusted to be the engine's), its convergence with the step, and the generator's files compiling.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <gtest/gtest.h>

#include "reference/campaign.hpp"
#include "reference/generator.hpp"
#include "reference/reference.hpp"

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn::reference {
namespace MACHDYN_UNITY_ID {

/// True when the tests run against the library built with AddressSanitizer (the sanitizer tree of
/// `make test`, which compiles the test files themselves without it and defines
/// MACHDYN_TESTS_UNDER_ASAN; or a tree instrumenting everything): the tests over many random models
/// take fewer of them there.
#if defined(MACHDYN_TESTS_UNDER_ASAN) || defined(__SANITIZE_ADDRESS__)
constexpr bool kUnderAsan = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kUnderAsan = true;
#else
constexpr bool kUnderAsan = false;
#endif
#else
constexpr bool kUnderAsan = false;
#endif

std::vector<RefEvent> of_kind(const RefResult& r, const std::string& kind) {
  std::vector<RefEvent> out;
  for (const auto& e : r.events)
    if (e.kind == kind) out.push_back(e);
  return out;
}

Signal constant(double v) {
  Signal s;
  s.value = v;
  return s;
}

// Claim: two free masses m1 = 2 kg, m2 = 3 kg on a spring c = 1e4 N/m, m1 starting at v0 = 1 m/s:
// the centre of mass moves at v_c = m1 v0/(m1 + m2), the deflection δ = q1 − q2 oscillates as
// (v0/ω) sin ωt with ω = √(c (m1 + m2)/(m1 m2)); so q1 = v_c t + m2/(m1 + m2) δ, q2 = v_c t − m1/(m1 + m2) δ.
TEST(ReferenceSimulator, TwoMassOscillatorFrequency) {
  RefModel m;
  m.bodies = {{"a", 2.0, 0.0, 1.0}, {"b", 3.0, 0.0, 0.0}};
  Link L;
  L.name = "k", L.a = 0, L.b = 1, L.c = 1e4;
  m.links = {L};
  m.t_end = 1.0, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const double w = std::sqrt(1e4 * 5 / 6), vc = 2.0 / 5;
  double err = 0.0;
  for (size_t k = 0; k < r.t.size(); ++k) {
    const double t = r.t[k], d = std::sin(w * t) / w;
    err = std::max({err, std::abs(r.q[k][0] - (vc * t + 0.6 * d)), std::abs(r.q[k][1] - (vc * t - 0.4 * d))});
  }
  EXPECT_LT(err, 1e-9);  // ~15 periods at h ω = 0.01: the RK4 phase error is ~(hω)⁴/120 per radian
}

// Claim: a block (m = 4 kg) on the ground with F_s = 30 N, F_k = 20 N under a ramp force P = 100 t N
// sticks until P = F_s, t* = F_s/100 = 0.3 s (the stick→slip instant), then slides with
// m a = 100 t − F_k: v = [50 (t² − t*²) − F_k (t − t*)]/m.
TEST(ReferenceSimulator, BlockBreaksAwayUnderARampAtFsOverK) {
  RefModel m;
  m.bodies = {{"block", 4.0, 0.0, 0.0}};
  Load P;
  P.name = "P", P.body = 0, P.s.kind = Signal::Kind::ramp, P.s.value = 100.0, P.s.t0 = 0.0, P.s.t1 = 1.0;
  m.loads = {P};
  Friction f;
  f.name = "f", f.a = 0, f.b = kGround, f.Fs = 30.0, f.Fk = 20.0;
  m.frictions = {f};
  m.t_end = 0.8, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const auto slip = of_kind(r, "slip");
  ASSERT_EQ(slip.size(), 1u);
  EXPECT_NEAR(slip[0].t, 0.3, 1e-11);
  EXPECT_TRUE(of_kind(r, "stick").empty());
  for (size_t k = 0; k < r.t.size(); ++k) {
    const double t = r.t[k], v = t <= 0.3 ? 0.0 : (50 * (t * t - 0.09) - 20 * (t - 0.3)) / 4;
    EXPECT_NEAR(r.v[k][0], v, 1e-10) << t;
  }
}

// Claim: two contacts in parallel on one block (F_s 10 N and 30 N; F_k 5 N and 15 N) share a ramp
// force P = 100 t in proportion to their static limits, so both break away together at
// t* = (10 + 30)/100 = 0.4 s; the block then slides with 4 a = 100 t − 20.
TEST(ReferenceSimulator, ParallelContactsBreakAwayTogether) {
  RefModel m;
  m.bodies = {{"block", 4.0, 0.0, 0.0}};
  Load P;
  P.name = "P", P.body = 0, P.s.kind = Signal::Kind::ramp, P.s.value = 100.0, P.s.t0 = 0.0, P.s.t1 = 1.0;
  m.loads = {P};
  Friction f1, f2;
  f1.name = "f1", f1.a = 0, f1.b = kGround, f1.Fs = 10.0, f1.Fk = 5.0;
  f2.name = "f2", f2.a = 0, f2.b = kGround, f2.Fs = 30.0, f2.Fk = 15.0;
  m.frictions = {f1, f2};
  m.t_end = 0.8, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const auto slip = of_kind(r, "slip");
  ASSERT_EQ(slip.size(), 2u);
  EXPECT_NEAR(slip[0].t, 0.4, 1e-11);
  EXPECT_NEAR(slip[1].t, 0.4, 1e-11);
  const double v_end = (50 * (0.64 - 0.16) - 20 * 0.4) / 4;
  EXPECT_NEAR(r.v.back()[0], v_end, 1e-10);
}

// Claim: a ball (m = 2 kg, weight 19.62 N, g = 9.81) dropped from h = 1 m onto a stop with e = 0.5
// hits at t1 = √(2h/g); impact k + 1 follows after the flight 2 v_k/g with v_1 = e √(2 g h),
// v_{k+1} = e v_k; it comes to rest at t∞ = t1 (1 + e)/(1 − e) (the flights' geometric sum).
TEST(ReferenceSimulator, BouncingBallImpactTimes) {
  RefModel m;
  m.bodies = {{"ball", 2.0, 1.0, 0.0}};
  m.loads = {{"G", 0, constant(-19.62)}};
  Friction s;
  s.kind = Friction::Kind::stop, s.name = "floor", s.a = 0, s.stop_pos = 0.0, s.e = 0.5;
  m.frictions = {s};
  m.t_end = 2.0, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const double g = 9.81, e = 0.5, t1 = std::sqrt(2.0 / g);
  const auto impacts = of_kind(r, "impact");
  ASSERT_GE(impacts.size(), 10u);
  double t = t1, v = e * std::sqrt(2.0 * g);
  for (size_t k = 0; k < 10; ++k) {
    EXPECT_NEAR(impacts[k].t, t, 1e-10) << k;
    t += 2.0 * v / g, v *= e;
  }
  const auto rest = of_kind(r, "stick");
  ASSERT_EQ(rest.size(), 1u);
  // The reference rests once a flight would be below 1e-9·max(1, t) s: the flights left then sum to
  // less than 2e-9 s.
  EXPECT_NEAR(rest[0].t, t1 * (1 + e) / (1 - e), 3e-9);
  EXPECT_EQ(r.q.back()[0], 0.0);
  EXPECT_EQ(r.v.back()[0], 0.0);
}

// Claim: a plastic impact (e = 0) whose loads pull the body off the stop at once is one `impact`,
// not a rest (docs/hybrid.md, End stop): no `stick`, no `slip`. A body of 1 kg at q0 = 0.5 m moving
// at v0 = −2 m/s towards a lower stop at 0 under +1 N: q = 0.5 − 2t + t²/2 reaches 0 at
// t_i = 2 − √3 with v⁻ = −√3; v⁺ = 0 and a = +1 m/s² pulls it off, so q = (t − t_i)²/2 after.
TEST(ReferenceSimulator, PlasticImpactThatLeavesAtOnceIsOneImpact) {
  RefModel m;
  m.bodies = {{"b", 1.0, 0.5, -2.0}};
  m.loads = {{"P", 0, constant(1.0)}};
  Friction s;
  s.kind = Friction::Kind::stop, s.name = "stop", s.a = 0, s.stop_pos = 0.0, s.e = 0.0;
  m.frictions = {s};
  m.t_end = 1.0, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const double ti = 2.0 - std::sqrt(3.0);
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].kind, "impact");
  EXPECT_NEAR(r.events[0].t, ti, 1e-11);
  for (size_t k = 0; k < r.t.size(); ++k) {
    const double t = r.t[k];
    const double q = t <= ti ? 0.5 - 2 * t + t * t / 2 : (t - ti) * (t - ti) / 2;
    EXPECT_NEAR(r.q[k][0], q, 1e-10) << t;
  }
}

// Claim: a force F = 10 N on m1 = 1 kg closes a gap Δ − gap_start = 2 mm to m2 at t1 = √(2 · 0.002 · m1/F)
// (the gap open: m1 flies alone); both flank laws agree there (no load before contact).
TEST(ReferenceSimulator, GapClosesAtTheFreeFlightTime) {
  for (bool elasto : {false, true}) {
    RefModel m;
    m.bodies = {{"m1", 1.0, 0.0, 0.0}, {"m2", 3.0, 0.0, 0.0}};
    Link L;
    L.kind = Link::Kind::gap, L.name = "c", L.a = 0, L.b = 1, L.c = 1e5, L.d = 50, L.gap = 0.003, L.gap_start = 0.001;
    L.elasto = elasto;
    m.links = {L};
    m.loads = {{"F", 0, constant(10.0)}};
    m.t_end = 0.1, m.dt_out = 0.001;
    const RefResult r = simulate_reference(m);
    ASSERT_TRUE(r.error.empty()) << r.error;
    const auto closed = of_kind(r, "gap_closed");
    ASSERT_GE(closed.size(), 1u);
    EXPECT_NEAR(closed[0].t, std::sqrt(2 * 0.002 / 10.0), 1e-11) << elasto;
  }
}

// Claim: a backstop with drag (F_d = 0.5 N) on a block (m = 2 kg) at rest holds a forward load below
// its drag — at zero overrun speed the drag is a friction level, λ ≥ −F_d (the reference's rule where
// the docs' lock·λ ≥ 0 has no consistent mode) — and overruns when a ramp P = t N passes F_d, at
// t* = 0.5 s; then m v' = P − F_d: v = (t² − t*²)/(2m) − F_d (t − t*)/m.
TEST(ReferenceSimulator, BackstopWithDragOverrunsWhenTheLoadPassesTheDrag) {
  RefModel m;
  m.bodies = {{"block", 2.0, 0.0, 0.0}};
  Load P;
  P.name = "P", P.body = 0, P.s.kind = Signal::Kind::ramp, P.s.value = 1.0, P.s.t0 = 0.0, P.s.t1 = 1.0;
  m.loads = {P};
  Friction f;
  f.kind = Friction::Kind::freewheel, f.name = "backstop", f.a = kGround, f.b = 0, f.drag = 0.5;
  m.frictions = {f};
  m.t_end = 0.9, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const auto slip = of_kind(r, "slip");
  ASSERT_EQ(slip.size(), 1u);
  // The hold rule's allowance of 1e-9 N (docs/hybrid.md, Freewheel) at a load rate of 1 N/s.
  EXPECT_NEAR(slip[0].t, 0.5, 2e-9);
  for (size_t k = 0; k < r.t.size(); ++k) {
    const double t = r.t[k], v = t <= 0.5 ? 0.0 : (t * t - 0.25) / 4 - 0.25 * (t - 0.5);
    EXPECT_NEAR(r.v[k][0], v, 1e-9) << t;
  }
}

// Claim (docs/hybrid.md, "Redundant locks: the bounded split"): a block (1 kg) held by a backstop
// (weight 1, lock·λ ≥ 0) and a brake (F_s = F_k = 10 N, weight 10) under P = −30 + 60 t N. Statics,
// λ_fw the backstop's push on the block, λ_br the brake's pull: λ_br − λ_fw = P. The weighted
// least-norm split min λ_fw² + λ_br²/10 gives λ_br = 10P/11, λ_fw = −P/11; backward (P < 0) that is
// within the bounds while 10|P|/11 ≤ 10, beyond it the bounded split holds the brake at its limit:
// λ_br = max(10P/11, −10), the backstop the rest. Forward (P > 0) the backstop's share would be
// against its lock, so it takes none: λ_br = P, until P = 10 N at t = 2/3 s, where the block
// breaks away forward and the backstop overruns (a brake event nowhere before).
TEST(ReferenceSimulator, ABrakeBesideAStoppedBackstopHoldsItsWeightedShareUpToItsLimit) {
  RefModel m;
  m.bodies = {{"block", 1.0, 0.0, 0.0}};
  Load P;
  P.name = "P", P.body = 0, P.s.kind = Signal::Kind::ramp, P.s.before = -30.0, P.s.value = 30.0, P.s.t0 = 0.0, P.s.t1 = 1.0;
  m.loads = {P};
  Friction fw, br;
  fw.kind = Friction::Kind::freewheel, fw.name = "backstop", fw.a = kGround, fw.b = 0;
  br.kind = Friction::Kind::brake, br.name = "brake", br.a = 0, br.b = kGround, br.Fs = 10.0, br.Fk = 10.0;
  m.frictions = {fw, br};
  m.t_end = 0.8, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(r.events.size(), 2u);
  for (const auto& e : r.events) {
    EXPECT_EQ(e.kind, "slip") << e.element;
    EXPECT_NEAR(e.t, 2.0 / 3.0, 1e-10) << e.element;
  }
  EXPECT_NE(r.events[0].element, r.events[1].element);
  ASSERT_EQ(r.lam.size(), r.t.size());
  int clamped = 0, shared = 0;
  for (size_t k = 0; k < r.t.size() && r.t[k] < 0.66; ++k) {
    const double p = -30.0 + 60.0 * r.t[k];
    const double br_want = p < 0.0 ? std::max(10.0 * p / 11.0, -10.0) : p;
    EXPECT_NEAR(std::abs(r.lam[k][1]), std::abs(br_want), 1e-9) << r.t[k];
    EXPECT_NEAR(std::abs(r.lam[k][0]), std::abs(br_want - p), 1e-9) << r.t[k];
    EXPECT_EQ(r.v[k][0], 0.0) << r.t[k];
    (p < -11.0 ? clamped : shared) += 1;
  }
  EXPECT_GT(clamped, 10);  // both branches of the split are checked
  EXPECT_GT(shared, 10);
  EXPECT_GT(r.v.back()[0], 0.0);
}

// Claim (docs/hybrid.md, the bounded split): a loop of stuck contacts with one weak brake. Body b0
// (1 kg) on the ground by a contact C1 (F_s = F_k = 100 N), body b1 (2 kg) on b0 by a contact C2
// (100 N) and braked to the ground by a brake B (F_s = F_k = 1 N), P = 100 t N on b1. Statics: the
// brake carries x, the chain C2–C1 carries P − x on both; the weighted least-norm split
// min x²/1 + 2 (P − x)²/100 gives x = P/51, beyond the brake's limit from P = 51 N. The bounded split
// holds the brake at 1 N and the chain the rest, so nothing moves until no split within the bounds
// exists: P = 1 + 100 N, t* = 1.01 s (the weighted share alone would release the brake at 0.51 s).
TEST(ReferenceSimulator, ALoopOfStuckContactsHoldsAWeakBrakeAtItsLimit) {
  RefModel m;
  m.bodies = {{"b0", 1.0, 0.0, 0.0}, {"b1", 2.0, 0.0, 0.0}};
  Load P;
  P.name = "P", P.body = 1, P.s.kind = Signal::Kind::ramp, P.s.value = 200.0, P.s.t0 = 0.0, P.s.t1 = 2.0;
  m.loads = {P};
  Friction c1, c2, br;
  c1.name = "C1", c1.a = 0, c1.b = kGround, c1.Fs = 100.0, c1.Fk = 100.0;
  c2.name = "C2", c2.a = 1, c2.b = 0, c2.Fs = 100.0, c2.Fk = 100.0;
  br.kind = Friction::Kind::brake, br.name = "B", br.a = 1, br.b = kGround, br.Fs = 1.0, br.Fk = 1.0;
  m.frictions = {c1, c2, br};
  m.t_end = 1.1, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_FALSE(r.events.empty());
  for (const auto& e : r.events) EXPECT_NEAR(e.t, 1.01, 1e-9) << e.kind << " " << e.element;
  ASSERT_EQ(r.lam.size(), r.t.size());
  for (size_t k = 0; k < r.t.size() && r.t[k] < 1.005; ++k) {
    const double p = 100.0 * r.t[k], x = std::min(p / 51.0, 1.0);
    EXPECT_NEAR(std::abs(r.lam[k][2]), x, 1e-9) << r.t[k];
    EXPECT_NEAR(std::abs(r.lam[k][0]), p - x, 1e-9) << r.t[k];
    EXPECT_NEAR(std::abs(r.lam[k][1]), p - x, 1e-9) << r.t[k];
    EXPECT_EQ(r.v[k][0], 0.0) << r.t[k];
    EXPECT_EQ(r.v[k][1], 0.0) << r.t[k];
  }
  EXPECT_GT(r.v.back()[1], 0.0);
}

// Claim: the reference converges: halving its step changes no event time by more than 1e-9 s (a
// thousandth of the campaign's event tolerance) and no velocity by more than a hundredth of the
// campaign's state tolerance, on random models of every family (RK4: the error falls 16-fold).
// Three models per family; one under AddressSanitizer (the sanitizer run of `make test`), where the
// 57 runs took 130 s: every family's code still runs there.
TEST(ReferenceSimulator, ConvergesWithTheStepOnRandomModels) {
  constexpr std::uint64_t kPerFamily = kUnderAsan ? 1 : 3;
  double worst_t = 0.0, worst_x = 0.0;
  int compared = 0;
  for (const auto& fam : all_families())
    for (std::uint64_t i = 0; i < kPerFamily; ++i) {
      const RefModel m = random_model(fam, 7, i);
      const RefResult a = simulate_reference(m);
      RefOptions fine;
      fine.omega_h = 0.5 * RefOptions{}.omega_h, fine.h_max = 0.5 * RefOptions{}.h_max;
      const RefResult b = simulate_reference(m, fine);
      if (!a.error.empty() || !b.error.empty()) continue;
      if (std::isfinite(a.ambiguous_from) || a.events.size() != b.events.size()) continue;
      ++compared;
      double wt = 0.0, wx = 0.0;
      for (size_t k = 0; k < a.events.size(); ++k) {
        EXPECT_EQ(a.events[k].kind + a.events[k].element, b.events[k].kind + b.events[k].element) << fam << " " << i;
        wt = std::max(wt, std::abs(a.events[k].t - b.events[k].t));
      }
      for (size_t j = 0; j < m.bodies.size(); ++j) {
        double scale = 1e-12;  // m/s: a body at rest in both runs differs by rounding only
        for (size_t k = 0; k < a.t.size(); ++k) scale = std::max(scale, std::abs(a.v[k][j]));
        for (size_t k = 0; k < a.t.size(); ++k) wx = std::max(wx, std::abs(a.v[k][j] - b.v[k][j]) / scale);
      }
      if (wt > 1e-9 || wx > 1e-2 * kStateTol) std::printf("  %s #%d: events %.2e s, velocities %.2e\n", fam.c_str(), static_cast<int>(i), wt, wx);
      worst_t = std::max(worst_t, wt), worst_x = std::max(worst_x, wx);
    }
  EXPECT_GE(compared, static_cast<int>(20 * kPerFamily / 3));  // of 19 families × kPerFamily models
  EXPECT_LT(worst_t, 1e-9);
  EXPECT_LT(worst_x, 1e-2 * kStateTol);
  std::printf("reference self-convergence: %d models, event times %.2e s, velocities %.2e relative\n", compared, worst_t, worst_x);
}

// Claim: every family's random models are valid model files (they compile without error).
TEST(ReferenceGenerator, EveryFamilyCompiles) {
  for (const auto& fam : all_families())
    for (std::uint64_t i = 0; i < 20; ++i) {
      const RefModel m = random_model(fam, 3, i);
      const std::string y = to_yaml(m, "dopri5");
      EXPECT_NO_THROW(compile_model(parse_yaml_string(y, "random.yaml"), "random.yaml")) << fam << " " << i << "\n" << y;
    }
}

// Claim: the campaign sees a difference: the engine run on a model whose file says another force
// than the reference's input is a state mismatch (the comparison can fail).
TEST(ReferenceCampaign, ComparisonDetectsADifferentModel) {
  RefModel m = random_model("chain", 1, 0);
  const RefResult ref = simulate_reference(m);
  ASSERT_TRUE(ref.error.empty());
  EXPECT_EQ(compare(m, "dopri5", ref).kind, Outcome::Kind::pass) << compare(m, "dopri5", ref).detail;
  RefModel other = m;
  other.bodies[0].m *= 1.01;
  EXPECT_EQ(compare(other, "dopri5", ref).kind, Outcome::Kind::state_mismatch);
}

}  // namespace
}  // namespace machdyn::reference

namespace machdyn::reference {
namespace MACHDYN_UNITY_ID {

// Claim: the signal kinds read as docs/model-files.md ("Signals") states them. A free mass m = 2 kg
// under three loads — a pulse (high 10 N, low 2 N, period 0.2 s, width 0.05 s, from 0.1 s, 3 times),
// a table with a jump ([0, 0], [0.2, 10], [0.2, −5], [0.5, 5], extrapolated: the last segment's slope
// 10/0.3 continues) and an expression 1 + 3 t + 4 sin(2π·1.5 t + 0.3) − 2 e^(−t/0.1) — moves with
// v(t) = (1/m) ∫₀ᵗ ΣP: the pulse's integral counts its pieces, the table's is the trapezoids up to t,
// the expression's is t + 1.5 t² − (4/ω)(cos(ωt + 0.3) − cos 0.3) − 0.2 (1 − e^(−t/0.1)), ω = 3π.
TEST(ReferenceSimulator, SignalKindsIntegrateToTheirClosedForms) {
  Signal pulse, table, expr;
  pulse.kind = Signal::Kind::pulse, pulse.value = 10.0, pulse.before = 2.0, pulse.period = 0.2, pulse.width = 0.05, pulse.t0 = 0.1;
  pulse.count = 3;
  table.kind = Signal::Kind::table, table.points = {{0.0, 0.0}, {0.2, 10.0}, {0.2, -5.0}, {0.5, 5.0}}, table.extrapolate = true;
  expr.kind = Signal::Kind::expression, expr.offset = 1.0, expr.slope = 3.0, expr.amplitude = 4.0, expr.frequency_hz = 1.5;
  expr.phase = 0.3, expr.decay = -2.0, expr.tau = 0.1;
  EXPECT_EQ(table.at(0.2), -5.0);  // the jump: the second value from its time on
  EXPECT_EQ(table.at(0.1), 5.0);
  EXPECT_NEAR(table.at(0.8), 5.0 + 10.0 / 0.3 * 0.3, 1e-12);
  EXPECT_EQ(pulse.at(0.1), 10.0);
  EXPECT_EQ(pulse.at(0.16), 2.0);
  EXPECT_EQ(pulse.at(0.5), 10.0);  // the third pulse, 0.5 = 0.1 + 2·0.2
  EXPECT_EQ(pulse.at(0.7), 2.0);   // no fourth
  RefModel m;
  m.bodies = {{"m", 2.0, 0.0, 0.0}};
  m.loads = {{"P", 0, pulse}, {"T", 0, table}, {"E", 0, expr}};
  m.t_end = 1.0, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  auto pulse_int = [](double t) {  // 2 t plus 8 N over the high parts
    double s = 2.0 * t;
    for (int k = 0; k < 3; ++k) s += 8.0 * std::clamp(t - (0.1 + 0.2 * k), 0.0, 0.05);
    return s;
  };
  auto table_int = [](double t) {
    if (t <= 0.2) return 25.0 * t * t;                      // 50 t
    const double u = t - 0.2;                               // −5 + (10/0.3) u
    return 1.0 + (-5.0 * u + 0.5 * (10.0 / 0.3) * u * u);   // extrapolated beyond 0.5 on the same line
  };
  const double w = 2 * std::numbers::pi * 1.5;
  auto expr_int = [&](double t) {
    return t + 1.5 * t * t - 4.0 / w * (std::cos(w * t + 0.3) - std::cos(0.3)) - 0.2 * (1 - std::exp(-t / 0.1));
  };
  for (size_t k = 0; k < r.t.size(); ++k) {
    const double t = r.t[k];
    EXPECT_NEAR(r.v[k][0], (pulse_int(t) + table_int(t) + expr_int(t)) / 2.0, 1e-9) << t;
  }
}

// Claim: a brake released by its application signal r(t) (1 until 0.2 s, a ramp to 0 at 0.6 s)
// holding 100 N, braking 80 N, on a block m = 5 kg pushed by 50 N: stuck while 100 r ≥ 50, so it
// slips at r = ½, t* = 0.4 s; then 5 a = 50 − 80 r(t), r = (0.6 − t)/0.4 until 0.6 s, 0 after
// (released there): v(t) = [50 (t − t*) − 200 ∫_{t*}^{min(t, 0.6)} (0.6 − s) ds]/5.
TEST(ReferenceSimulator, BrakeReleasedByItsApplicationSignal) {
  RefModel m;
  m.bodies = {{"block", 5.0, 0.0, 0.0}};
  Load P;
  P.name = "P", P.body = 0, P.s.value = 50.0;
  m.loads = {P};
  Friction b;
  b.kind = Friction::Kind::brake, b.name = "B", b.a = 0, b.b = kGround, b.Fs = 100.0, b.Fk = 80.0;
  b.with_application = true;
  b.application.kind = Signal::Kind::ramp, b.application.before = 1.0, b.application.value = 0.0;
  b.application.t0 = 0.2, b.application.t1 = 0.6;
  m.frictions = {b};
  m.t_end = 1.0, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const auto slip = of_kind(r, "slip");
  ASSERT_EQ(slip.size(), 1u);
  EXPECT_NEAR(slip[0].t, 0.4, 1e-11);
  ASSERT_EQ(of_kind(r, "released").size(), 1u);
  EXPECT_NEAR(of_kind(r, "released")[0].t, 0.6, 1e-12);
  for (size_t k = 0; k < r.t.size(); ++k) {
    const double t = r.t[k], te = std::min(t, 0.6);
    const double v = t <= 0.4 ? 0.0 : (50 * (t - 0.4) - 200 * (0.6 * (te - 0.4) - 0.5 * (te * te - 0.16))) / 5;
    EXPECT_NEAR(r.v[k][0], v, 1e-10) << t;
  }
}

// Claim: a clutch's normal force as a sine through zero has its zeros as breakpoints: each found
// root t_z of 100 + 300 sin(2π·2 (t − 0.1) + 0.5) satisfies it to rounding, and they alternate
// falling and rising, every half period apart in pairs (4 roots per second at 2 Hz).
TEST(ReferenceSimulator, SineNormalForceZerosAreBreakpoints) {
  Signal s;
  s.kind = Signal::Kind::sine, s.offset = 100.0, s.amplitude = 300.0, s.frequency_hz = 2.0, s.phase = 0.5, s.t0 = 0.1;
  std::vector<double> bp;
  s.breakpoints(bp, 1.1, true);
  std::vector<double> zeros;
  for (double t : bp)
    if (t > 0.1) zeros.push_back(t);
  ASSERT_EQ(zeros.size(), 4u);  // 1 s of a 2 Hz sine: two falling, two rising zeros
  std::sort(zeros.begin(), zeros.end());
  for (double t : zeros) EXPECT_NEAR(s.at(t), 0.0, 1e-10) << t;
  EXPECT_NEAR(zeros[2] - zeros[0], 0.5, 1e-12);
  EXPECT_NEAR(zeros[3] - zeros[1], 0.5, 1e-12);
}

// Claim: an ideal gear q_a = i q_b (i = 2) slaving m_b = 1 kg to m_a = 3 kg reduces to one body of
// mass m_a + m_b/i² = 3.25 kg on which a load P_b on b acts as P_b/i (virtual work). With P = 100 t
// on a, P_b = −4 N on b and a ground contact F_s = 20 N, F_k = 15 N on a, the group stays stuck until
// 100 t − 2 = 20, t* = 0.22 s, then 3.25 a = 100 t − 2 − 15: v_a = [50 (t² − t*²) − 17 (t − t*)]/3.25
// and v_b = v_a/2 throughout.
TEST(ReferenceSimulator, IdealGearReducesTheMassAndTheLoads) {
  RefModel m;
  m.bodies = {{"a", 3.0, 0.0, 0.0}, {"b", 1.0, 0.0, 0.0}};
  m.gears = {{"G", 0, 1, 2.0}};
  Load P, Pb;
  P.name = "P", P.body = 0, P.s.kind = Signal::Kind::ramp, P.s.value = 100.0, P.s.t0 = 0.0, P.s.t1 = 1.0;
  Pb.name = "Pb", Pb.body = 1, Pb.s.value = -4.0;
  m.loads = {P, Pb};
  Friction f;
  f.name = "f", f.a = 0, f.b = kGround, f.Fs = 20.0, f.Fk = 15.0;
  m.frictions = {f};
  m.t_end = 0.8, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const auto slip = of_kind(r, "slip");
  ASSERT_EQ(slip.size(), 1u);
  EXPECT_NEAR(slip[0].t, 0.22, 1e-11);
  for (size_t k = 0; k < r.t.size(); ++k) {
    const double t = r.t[k], v = t <= 0.22 ? 0.0 : (50 * (t * t - 0.0484) - 17 * (t - 0.22)) / 3.25;
    EXPECT_NEAR(r.v[k][0], v, 1e-10) << t;
    EXPECT_NEAR(r.v[k][1], v / 2, 1e-10) << t;
    EXPECT_NEAR(r.q[k][1], r.q[k][0] / 2, 1e-12) << t;
  }
}


// Claim: a planetary gear ω_s + z ω_r − (1 + z) ω_c = 0 (z = 3) among a sun J_s = 0.5, a ring
// J_r = 4 and a carrier J_c = 2 kg·m², a torque M = 10 N·m on the sun. Free: the gear's load λ (on
// the sun −λ, the ring −z λ, the carrier +(1 + z) λ) keeps the row's accelerations at 0:
// (M − λ)/J_s − z² λ/J_r − (1 + z)² λ/J_c = 0, λ = (M/J_s)/(1/J_s + z²/J_r + (1 + z)²/J_c), every
// acceleration constant (φ = a t²/2). With the ring held by a contact (F_s = 1e4 N·m) the sun turns
// the carrier at 1/(1 + z): a_s = M/(J_s + J_c/(1 + z)²), the ring stays at rest.
TEST(ReferenceSimulator, PlanetaryGearSharesTheSunTorqueByWillis) {
  RefModel m;
  m.rotational = true;
  m.bodies = {{"sun", 0.5, 0.0, 0.0}, {"ring", 4.0, 0.0, 0.0}, {"carrier", 2.0, 0.0, 0.0}};
  Gear g;
  g.name = "PG", g.planetary = true, g.a = 0, g.b = 1, g.c = 2, g.ratio = 3.0;
  m.gears = {g};
  Load M;
  M.name = "M", M.body = 0, M.s.value = 10.0;
  m.loads = {M};
  m.t_end = 0.5, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const double lam = (10.0 / 0.5) / (1 / 0.5 + 9.0 / 4.0 + 16.0 / 2.0);
  const double a[3] = {(10.0 - lam) / 0.5, -3.0 * lam / 4.0, 4.0 * lam / 2.0};
  for (size_t k = 0; k < r.t.size(); ++k)
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(r.v[k][static_cast<size_t>(i)], a[i] * r.t[k], 1e-11) << r.t[k];
      EXPECT_NEAR(r.q[k][static_cast<size_t>(i)], 0.5 * a[i] * r.t[k] * r.t[k], 1e-11) << r.t[k];
    }
  Friction hold;
  hold.name = "hold", hold.a = 1, hold.b = kGround, hold.Fs = 1e4, hold.Fk = 1e4;
  m.frictions = {hold};
  const RefResult h = simulate_reference(m);
  ASSERT_TRUE(h.error.empty()) << h.error;
  EXPECT_TRUE(h.events.empty());
  const double as = 10.0 / (0.5 + 2.0 / 16.0);
  for (size_t k = 0; k < h.t.size(); ++k) {
    EXPECT_NEAR(h.v[k][0], as * h.t[k], 1e-11) << h.t[k];
    EXPECT_EQ(h.v[k][1], 0.0) << h.t[k];
    EXPECT_NEAR(h.v[k][2], as * h.t[k] / 4.0, 1e-11) << h.t[k];
  }
}


// Claim: a body moved by a prescribed acceleration a_p = 10 t (m/s², from rest) carries a block
// m = 3 kg on a contact F_s = 4.5 N, F_k = 3 N. Stuck, the contact gives the block m a_p = 30 t, so
// it slips at t* = 4.5/30 = 0.15 s; then the block accelerates at F_k/m = 1 m/s² while the body
// runs ahead: v_p = 5 t², v_b = 5 t*² + (t − t*). The prescribed body follows its signal whatever
// the contact does (q_p = 5 t³/3).
TEST(ReferenceSimulator, PrescribedAccelerationDragsABlockUntilItSlips) {
  RefModel m;
  m.bodies = {{"p", 50.0, 0.0, 0.0}, {"b", 3.0, 0.0, 0.0}};
  m.bodies[0].motion = Body::Motion::acceleration;
  m.bodies[0].prescribed.kind = Signal::Kind::ramp, m.bodies[0].prescribed.value = 10.0, m.bodies[0].prescribed.t1 = 1.0;
  Friction f;
  f.name = "f", f.a = 0, f.b = 1, f.Fs = 4.5, f.Fk = 3.0;
  m.frictions = {f};
  m.t_end = 0.6, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const auto slip = of_kind(r, "slip");
  ASSERT_EQ(slip.size(), 1u);
  EXPECT_NEAR(slip[0].t, 0.15, 1e-11);
  for (size_t k = 0; k < r.t.size(); ++k) {
    const double t = r.t[k];
    EXPECT_NEAR(r.v[k][0], 5 * t * t, 1e-12) << t;
    EXPECT_NEAR(r.q[k][0], 5 * t * t * t / 3, 1e-12) << t;
    EXPECT_NEAR(r.v[k][1], t <= 0.15 ? 5 * t * t : 5 * 0.0225 + (t - 0.15), 1e-10) << t;
  }
}


// Claim: a block m = 4 kg pushed by 8 N from rest that releases Δm = 1 kg at 0.5 s keeps its
// position and velocity there and accelerates at 8/3 m/s² after: v = 2 t until 0.5 s, then
// v = 1 + (8/3)(t − 0.5); x = t² until 0.5 s, then 0.25 + (t − 0.5) + (4/3)(t − 0.5)².
TEST(ReferenceSimulator, ReleaseKeepsTheVelocityAndChangesTheAcceleration) {
  RefModel m;
  m.bodies = {{"block", 4.0, 0.0, 0.0}};
  Load P;
  P.name = "P", P.body = 0, P.s.value = 8.0;
  m.loads = {P};
  m.releases = {{"R", 0, 1.0, 0.5}};
  m.t_end = 1.0, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(of_kind(r, "release").size(), 1u);
  EXPECT_EQ(of_kind(r, "release")[0].t, 0.5);
  for (size_t k = 0; k < r.t.size(); ++k) {
    const double t = r.t[k], u = t - 0.5;
    EXPECT_NEAR(r.v[k][0], t <= 0.5 ? 2 * t : 1 + 8.0 / 3 * u, 1e-12) << t;
    EXPECT_NEAR(r.q[k][0], t <= 0.5 ? t * t : 0.25 + u + 4.0 / 3 * u * u, 1e-12) << t;
  }
}


// Claim: a block m = 5 kg sliding at v0 = 1 m/s on a ground contact whose kinetic level is the table
// F_k(s) = 10 + 10 s N (points [0, 10], [2, 30]; F_s = 20 N) decelerates by m v' = −(10 + 10 v):
// v = 2 e^(−2t) − 1, which reaches 0 at t* = ln 2 / 2 = 0.34657 s, where it sticks (no load).
TEST(ReferenceSimulator, KineticTableOverTheSlidingSpeed) {
  RefModel m;
  m.bodies = {{"block", 5.0, 0.0, 1.0}};
  Friction f;
  f.name = "f", f.a = 0, f.b = kGround, f.Fs = 20.0, f.Fk = 10.0;
  f.kinetic_table = {{0.0, 10.0}, {2.0, 30.0}};
  m.frictions = {f};
  m.t_end = 0.6, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const auto stick = of_kind(r, "stick");
  ASSERT_EQ(stick.size(), 1u);
  EXPECT_NEAR(stick[0].t, std::log(2.0) / 2, 1e-11);
  for (size_t k = 0; k < r.t.size(); ++k) {
    const double t = r.t[k];
    EXPECT_NEAR(r.v[k][0], t < std::log(2.0) / 2 ? 2 * std::exp(-2 * t) - 1 : 0.0, 1e-10) << t;
  }
}


// Claim: a DC (linear) motor R = 2 Ω, L = 0.1 H, k = 1 N/A on a free mass m = 1 kg at u = 12 V from
// rest: x = [i; v], x' = A x + b with A = [[−R/L, −k/L], [k/m, 0]], b = [u/L; 0], so
// x = x∞ + e^(At)(x0 − x∞), x∞ = [0; u/k]; A has the distinct real eigenvalues λ = −10 ± √90 and
// e^(At) = (e^(λ1 t)(A − λ2 I) − e^(λ2 t)(A − λ1 I))/(λ1 − λ2) (Sylvester).
TEST(ReferenceSimulator, DcMotorOnAFreeMassFollowsItsLinearSystem) {
  RefModel m;
  m.bodies = {{"slider", 1.0, 0.0, 0.0}};
  DcMotor M;
  M.name = "motor", M.body = 0, M.R = 2.0, M.L = 0.1, M.k = 1.0, M.u.value = 12.0;
  m.motors = {M};
  m.t_end = 1.0, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const double A[2][2] = {{-20.0, -10.0}, {1.0, 0.0}}, l1 = -10 + std::sqrt(90.0), l2 = -10 - std::sqrt(90.0);
  const double d0[2] = {0.0, -12.0};  // x0 − x∞
  for (size_t k = 0; k < r.t.size(); ++k) {
    const double t = r.t[k], e1 = std::exp(l1 * t), e2 = std::exp(l2 * t);
    // v = 12 + [e^(At) d0]_1
    const double row1 = (e1 * (A[1][0] * d0[0] + (A[1][1] - l2) * d0[1]) - e2 * (A[1][0] * d0[0] + (A[1][1] - l1) * d0[1])) / (l1 - l2);
    EXPECT_NEAR(r.v[k][0], 12.0 + row1, 1e-9) << t;
  }
}

// Claim: a gear mesh (i = 2, c = 2e4 N·m/rad, no damping, backlash b = 0.02 rad, η = 0.9) between a
// pinion (J₁ = 0.01 kg·m², at ω₀ = 2 rad/s) and a wheel (J₂ = 0.02 kg·m², at rest). Free play until
// Δ = ω₀ t reaches b/2: t₁ = 0.005 s. On the + flank the pinion drives (τ > 0, ω₁ > 0, the wheel's
// speed at 0 keeps its + sign): J₁ ω₁' = −τ, J₂ ω₂' = η i τ, τ = c e, so e'' = −Ω² e with
// Ω² = c (1/J₁ + η i²/J₂) = 5.6e6 s⁻², e = (ω₀/Ω) sin Ω(t − t₁); the contact ends at t₂ = t₁ + π/Ω
// with ω₁ = ω₀ (1 − 2c/(J₁ Ω²)) = 4/7 rad/s, ω₂ = 2 η i c ω₀/(J₂ Ω²) = 9/7 rad/s (still both > 0:
// no reversal) and Δ' = −ω₀; free flight across the play to the − flank at t₃ = t₂ + b/ω₀. The kinetic
// energy lost, ½ J₁ ω₀² − ½ J₁ ω₁² − ½ J₂ ω₂², is (1 − η)/η × the wheel's gain.
TEST(ReferenceSimulator, GearMeshContactThroughTheBacklashWithItsEfficiency) {
  RefModel m;
  m.rotational = true;
  m.bodies = {{"pinion", 0.01, 0.0, 2.0}, {"wheel", 0.02, 0.0, 0.0}};
  Mesh G;
  G.name = "mesh", G.a = 0, G.b = 1, G.i = 2.0, G.c = 2e4, G.backlash = 0.02, G.eta = 0.9;
  m.meshes = {G};
  m.t_end = 0.02, m.dt_out = 1e-4;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const double W = std::sqrt(5.6e6), t1 = 0.005, t2 = t1 + std::numbers::pi / W, t3 = t2 + 0.01;
  ASSERT_GE(r.events.size(), 3u);  // (then the − flank's contact, not followed here)
  EXPECT_EQ(r.events[0].kind, "mesh");
  EXPECT_EQ(r.events[1].kind, "free play");
  EXPECT_EQ(r.events[2].kind, "mesh");
  EXPECT_NEAR(r.events[0].t, t1, 1e-12);
  EXPECT_NEAR(r.events[1].t, t2, 1e-10);
  EXPECT_NEAR(r.events[2].t, t3, 1e-10);
  const size_t k = 100;  // t = 0.01 s, in the free flight back
  ASSERT_NEAR(r.t[k], 0.01, 1e-15);
  EXPECT_NEAR(r.v[k][0], 4.0 / 7.0, 1e-9);
  EXPECT_NEAR(r.v[k][1], 9.0 / 7.0, 1e-9);
  const double lost = 0.5 * 0.01 * 4.0 - 0.5 * 0.01 * r.v[k][0] * r.v[k][0] - 0.5 * 0.02 * r.v[k][1] * r.v[k][1];
  EXPECT_NEAR(lost, (1.0 - 0.9) / 0.9 * 0.5 * 0.02 * r.v[k][1] * r.v[k][1], 1e-10);
}

// Claim: the reference's held flank (docs/model-files.md, "Elastic gear mesh"): a wheel J₂ = 0.5
// kg·m² at rest under −18 N·m, meshed (i = 2, c = 1000 N·m/rad, η = 0.8, no backlash) with a pinion
// prescribed at 1 rad/s from Δ₀ = 0.01 rad. The pinion feeds the teeth, τ = c (Δ₀ + t), so the wheel's
// range is [η i τ, i τ] = [16 + 1600 t, 20 + 2000 t] N·m: held (ω₂ = 0 exactly) until the lower
// bound reaches 18 at t₂ = 1.25e-3 s, one `mesh` event; then driven, x'' + ω² x = 3200 (t − t₂),
// ω² = η i² c/J₂ = 6400 s⁻²: ω₂ = ½ (1 − cos ω (t − t₂)).
TEST(ReferenceSimulator, GearMeshHoldsAWheelInsideItsLockingRange) {
  RefModel m;
  m.rotational = true;
  m.bodies = {{"pinion", 0.01, 0.01, 1.0}, {"wheel", 0.5, 0.0, 0.0}};
  m.bodies[0].motion = Body::Motion::speed, m.bodies[0].prescribed = constant(1.0);
  Mesh G;
  G.name = "mesh", G.a = 0, G.b = 1, G.i = 2.0, G.c = 1000.0, G.eta = 0.8;
  m.meshes = {G};
  m.loads = {{"L", 1, constant(-18.0)}};
  m.t_end = 0.02, m.dt_out = 1e-4;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const double t2 = 1.25e-3, w = 80.0;
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].kind, "mesh");
  EXPECT_NEAR(r.events[0].t, t2, 1e-11);
  for (size_t k = 0; k < r.t.size(); ++k) {
    if (r.t[k] < t2) EXPECT_EQ(r.v[k][1], 0.0) << r.t[k];
    else EXPECT_NEAR(r.v[k][1], 0.5 * (1.0 - std::cos(w * (r.t[k] - t2))), 1e-9) << r.t[k];
  }
}

// Claim: the reference's spatial rope (docs/sway.md) swings a load m = 1 kg on a free trolley
// M = 2 kg with ω² = (g/ℓ)(1 + m/M) (the relative swing ξ = x_L − x_t: m x_L'' = −m g ξ/ℓ,
// M x_t'' = m g ξ/ℓ), ℓ = L0 + m g/c the hanging length: ξ = a cos ωt within 1e-3 a over two periods
// (the rope's elasticity shifts ω² by (g/ℓ)/(c/m) = 2.5e-5, the amplitude a/ℓ = 0.01 by θ²/16), and
// the centre of mass stays at rest.
TEST(ReferenceSimulator, SpatialRopeSwingsTheLoadOfAFreeTrolley) {
  const double g = 9.80665, c = 4e5, L0 = 1.0, l = L0 + g / c, a = 0.01;
  RefModel m;
  m.bodies = {{"trolley", 2.0, 0.0, 0.0}, {"L.x", 1.0, a, 0.0}, {"L.z", 1.0, 0.0, 0.0}};
  m.bodies[1].load_coordinate = m.bodies[2].load_coordinate = true;
  SwayRope R;
  R.name = "rope", R.load = "L", R.x = 1, R.z = 2, R.trolley = 0, R.L0 = L0, R.EA = c * L0, R.h = l;
  m.bodies[2].q0 = l - std::sqrt(l * l - a * a);  // on the arc of radius ℓ
  m.sway = {R};
  const double w = std::sqrt(g / l * 1.5);
  m.t_end = 2 * 2 * std::numbers::pi / w, m.dt_out = m.t_end / 400;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  double err = 0.0, cm = 0.0;
  for (size_t k = 0; k < r.t.size(); ++k) {
    err = std::max(err, std::abs(r.q[k][1] - r.q[k][0] - a * std::cos(w * r.t[k])));
    cm = std::max(cm, std::abs(2.0 * r.q[k][0] + r.q[k][1] - a));
  }
  EXPECT_LT(err, 1e-3 * a) << err;
  EXPECT_LT(cm, 1e-9);
  EXPECT_TRUE(of_kind(r, "slack").empty());
}

// Claim: the reference's lift-off: a load of 1 t resting on a ground stop at x = 0.2 m, 9.95 m below
// the suspension point, its rope (2 falls, L0 = 10 m: slack) wound in by a drum (J = 50 kg·m²,
// R = 0.3 m, a torque of 2 kN·m, unloaded while the rope is slack) at s = R/n = 0.15 m per radian:
// taut at t = √(2 (L0 − ℓ₀)/(s M/J)), ℓ₀ = √(0.2² + 9.95²) (within 1e-9 s), the stop lets the load go
// after that and the load rises.
TEST(ReferenceSimulator, SpatialRopeLiftsTheLoadOffTheGround) {
  RefModel m;
  m.bodies = {{"drum", 50.0, 0.0, 0.0}, {"L.x", 1000.0, 0.2, 0.0}, {"L.z", 1000.0, 0.0, 0.0}};
  m.bodies[0].angular = true;
  m.bodies[1].load_coordinate = m.bodies[2].load_coordinate = true;
  SwayRope R;
  R.name = "rope", R.load = "L", R.x = 1, R.z = 2, R.drum = 0, R.R = 0.3, R.falls = 2, R.L0 = 10, R.EA = 5e7, R.h = 9.95,
  R.d = 1e4;
  m.sway = {R};
  m.loads = {{"hoist", 0, constant(2000.0)}};
  Friction f;
  f.kind = Friction::Kind::stop, f.name = "ground", f.a = 2, f.b = kGround, f.stop_pos = 0.0;
  m.frictions = {f};
  m.t_end = 1.0, m.dt_out = 1e-3;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  const double l0 = std::hypot(0.2, 9.95), t_taut = std::sqrt(2 * (10 - l0) / (0.15 * 2000 / 50.0));
  const auto taut = of_kind(r, "taut"), slip = of_kind(r, "slip");
  ASSERT_FALSE(taut.empty());
  EXPECT_NEAR(taut[0].t, t_taut, 1e-9);
  ASSERT_FALSE(slip.empty());
  EXPECT_EQ(slip[0].element, "ground");
  EXPECT_GT(slip[0].t, taut[0].t);
  EXPECT_GT(r.q.back()[2], 0.01);
}

// Claim: the reference's rigid load (docs/sway.md: the rope's point c + R(ψ) a, its moment
// F u·∂r/∂ψ on ψ) swings the compound pendulum — a body m = 1 kg, J = 2 kg·m² on a rope of hanging
// length ℓ attached a = 1 m above its centre, from a fixed point — in its first mode: with the rope's
// angle θ and ψ small, T = ½ m (ℓ θ' + a ψ')² + ½ J ψ'², V = ½ m g (ℓ θ² + a ψ²), so
// det(K − λ M) = 0 is ℓ J λ² − g (m a² + J + m a ℓ) λ + m g² a = 0 and the mode's shape
// θ/ψ = λ a/(g − λ ℓ); started there at ψ0 = 0.01 rad, ψ = ψ0 cos(√λ₁ t) within 2e-3 ψ0 over two
// periods (the nonlinear terms O(ψ0²), the rope's stretch (g/ℓ)/(c/m) = 1e-4 relative in λ), and
// a spreader on two parallel ropes (a = (±1 m, 0.2 m) from offsets ±1 m: a parallelogram) swings
// its centre as the point pendulum x0 cos(√(g/ℓ) t) whatever J (within 2e-3 x0: the swing's
// nonlinear frequency shift θ²/16 over 2 s) and barely turns: the ropes' horizontal pulls, m g u_h
// in all, act a_z above the centre, a moment m g u_h a_z that the ropes' stretch answers with the
// roll stiffness 2 c a_h², so ψ stays within twice the quasi-static tilt m g (x0/ℓ) a_z/(2 c a_h²)
// (the roll mode, 100 times faster than the swing, started from ψ = 0: at most twice it, within 10 %).
TEST(ReferenceSimulator, RigidLoadSwingsAsTheCompoundPendulum) {
  const double g = 9.80665, m0 = 1.0, J = 2.0, a = 1.0, L0 = 1.0, c = 1e5, l = L0 + m0 * g / c, h = l + a;
  const double A = l * J, B = g * (m0 * a * a + J + m0 * a * l), C = m0 * g * g * a;
  const double lam = (B - std::sqrt(B * B - 4 * A * C)) / (2 * A), psi0 = 0.01, th0 = psi0 * lam * a / (g - lam * l);
  const double xr = l * std::sin(th0), zr = h - l * std::cos(th0);  // the rope's point; the centre R(ψ0)(0, a) below it
  RefModel m;
  m.bodies = {{"L.x", m0, xr + a * std::sin(psi0), 0.0}, {"L.z", m0, zr - a * std::cos(psi0), 0.0}, {"L.psi", J, psi0, 0.0}};
  for (auto& b : m.bodies) b.load_coordinate = true;
  m.bodies[2].angular = true;
  SwayRope R;
  R.name = "rope", R.load = "L", R.x = 0, R.z = 1, R.psi = 2, R.L0 = L0, R.EA = c * L0, R.h = h, R.attach[1] = a;
  m.sway = {R};
  const double w = std::sqrt(lam);
  m.t_end = 2 * 2 * std::numbers::pi / w, m.dt_out = m.t_end / 400;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  double err = 0.0;
  for (size_t k = 0; k < r.t.size(); ++k) err = std::max(err, std::abs(r.q[k][2] - psi0 * std::cos(w * r.t[k])));
  EXPECT_LT(err, 2e-3 * psi0) << err;
  EXPECT_TRUE(of_kind(r, "slack").empty());

  // The spreader: both ropes carry m g/2, ℓ = L0 + m g/(2c); the centre 0.05 m aside.
  RefModel s;
  const double ls = L0 + m0 * g / (2 * c), hs = ls + 0.2, x0 = 0.05;
  s.bodies = {{"L.x", m0, x0, 0.0}, {"L.z", m0, hs - 0.2 - std::sqrt(ls * ls - x0 * x0), 0.0}, {"L.psi", J, 0.0, 0.0}};
  for (auto& b : s.bodies) b.load_coordinate = true;
  s.bodies[2].angular = true;
  SwayRope P = R;
  P.h = hs, P.attach[0] = 1.0, P.attach[1] = 0.2, P.offset = 1.0;
  SwayRope Q = P;
  Q.name = "rope2", Q.attach[0] = -1.0, Q.offset = -1.0;
  s.sway = {P, Q};
  s.t_end = 2.0, s.dt_out = 0.01;
  const RefResult rs = simulate_reference(s);
  ASSERT_TRUE(rs.error.empty()) << rs.error;
  double psi = 0.0, swing = 0.0;
  const double ws = std::sqrt(g / ls);
  for (size_t k = 0; k < rs.t.size(); ++k)
    psi = std::max(psi, std::abs(rs.q[k][2])), swing = std::max(swing, std::abs(rs.q[k][0] - x0 * std::cos(ws * rs.t[k])));
  const double tilt = m0 * g * (x0 / ls) * 0.2 / (2 * c * 1.0 * 1.0);
  EXPECT_LT(psi, 2.2 * tilt) << psi / tilt;
  EXPECT_LT(swing, 2e-3 * x0) << swing;
}

}  // namespace
}  // namespace machdyn::reference
