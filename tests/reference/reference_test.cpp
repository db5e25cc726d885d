// The reference simulator itself against closed forms (so a later mismatch with the engine can be
// trusted to be the engine's), its convergence with the step, and the generator's files compiling.
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

// Claim: a lock carries a redundantly locked load before the friction beside it: a block held by a
// backstop and a brake (holding 5 N) under a backward load of 20 N stays at rest with the brake
// unloaded — no brake event, where a split by weights would overload it at once — and when the load
// turns forward (P = −20 + 40 t N) the backstop takes no share against its lock (docs/hybrid.md), so
// the brake holds alone until P = 5 N at t = 0.625 s, where the block breaks away forward and the
// backstop overruns.
TEST(ReferenceSimulator, ALockCarriesTheLoadBeforeTheBrakeBesideIt) {
  RefModel m;
  m.bodies = {{"block", 1.0, 0.0, 0.0}};
  Load P;
  P.name = "P", P.body = 0, P.s.kind = Signal::Kind::ramp, P.s.before = -20.0, P.s.value = 20.0, P.s.t0 = 0.0, P.s.t1 = 1.0;
  m.loads = {P};
  Friction fw, br;
  fw.kind = Friction::Kind::freewheel, fw.name = "backstop", fw.a = kGround, fw.b = 0;
  br.kind = Friction::Kind::brake, br.name = "brake", br.a = 0, br.b = kGround, br.Fs = 5.0, br.Fk = 5.0;
  m.frictions = {fw, br};
  m.t_end = 0.8, m.dt_out = 0.01;
  const RefResult r = simulate_reference(m);
  ASSERT_TRUE(r.error.empty()) << r.error;
  ASSERT_EQ(r.events.size(), 2u);
  for (const auto& e : r.events) {
    EXPECT_EQ(e.kind, "slip") << e.element;
    EXPECT_NEAR(e.t, 0.625, 1e-10) << e.element;
  }
  EXPECT_NE(r.events[0].element, r.events[1].element);
  EXPECT_EQ(r.v[static_cast<size_t>(std::lround(0.62 / 0.01))][0], 0.0);
  EXPECT_GT(r.v.back()[0], 0.0);
}

// Claim: the reference converges: halving its step changes no event time by more than 1e-9 s (a
// thousandth of the campaign's event tolerance) and no velocity by more than a hundredth of the
// campaign's state tolerance, on random models of every family (RK4: the error falls 16-fold).
TEST(ReferenceSimulator, ConvergesWithTheStepOnRandomModels) {
  double worst_t = 0.0, worst_x = 0.0;
  int compared = 0;
  for (const auto& fam : all_families())
    for (std::uint64_t i = 0; i < 3; ++i) {
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
        double scale = 1e-300;
        for (size_t k = 0; k < a.t.size(); ++k) scale = std::max(scale, std::abs(a.v[k][j]));
        for (size_t k = 0; k < a.t.size(); ++k) wx = std::max(wx, std::abs(a.v[k][j] - b.v[k][j]) / scale);
      }
      if (wt > 1e-9 || wx > 1e-2 * kStateTol) std::printf("  %s #%d: events %.2e s, velocities %.2e\n", fam.c_str(), static_cast<int>(i), wt, wx);
      worst_t = std::max(worst_t, wt), worst_x = std::max(worst_x, wx);
    }
  EXPECT_GE(compared, 20);
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
