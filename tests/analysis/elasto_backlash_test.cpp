// The elasto-backlash flank law (elements/link.hpp, `flank_law: elasto-backlash`): a mass striking a
// spring–damper flank, checked phase by phase against the closed forms derived below, on both
// integrators.
#include "support/models.hpp"
#include "support/support.hpp"
#include "machdyn/analysis/simulate.hpp"

#include <cmath>
#include <gtest/gtest.h>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::model_of;

using test::at;
using test::series;


class ElastoBacklash : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, ElastoBacklash, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

constexpr double kM = 2.0, kC = 1e5, kD = 200.0, kV0 = 1.0, kGap = 0.01;

std::string model_text(const char* law) {
  return std::string(R"(
bodies: {A: {type: translational, mass: 2, velocity: 1 m/s}}
links: {c: {type: spring-damper, between: [A, ground], stiffness: 1e5 N/m, damping: 200 N*s/m, gap: 10 mm,
            flank_law: )") + law + R"(}}
simulation: {t_end: 0.03, dt_out: 1e-4, rtol: 1e-11, atol: 1e-13}
)";
}

// Claim: with the capped law the mass meets the flank (δ = x, flank 10 mm, reached at
// t0 = 0.01 s) without a load jump and is thrown back at the closed-form time and speed.
// e = x − 0.01 m, m ë = −F:
//  phase 1, on the cap (d ė ≥ c e, true at contact where e = 0, ė = v0): F = 2 c e, so
//    e = (v0/ω2) sin ω2 τ, ω2 = √(2c/m), until d ė = c e: tan ω2 τ1 = d ω2 / c;
//  phase 2, off the cap (d ė < c e for the rest of the contact: e > 0 while ė falls through 0 and
//    stays negative): m ë + d ė + c e = 0 from (e1, ė1): e = exp(−γτ)(e1 cos ωd τ + B sin ωd τ),
//    γ = d/2m, ωd = √(c/m − γ²), B = (ė1 + γ e1)/ωd, until F = c e + d ė = 0 at τ2 (found by
//    bisection on the closed form below); the mass leaves with ė(τ2) and flies on freely.
// The linear law on the same model jumps to d v0 = 200 N at contact.
TEST_P(ElastoBacklash, ImpactOnAFlankFollowsThePhaseClosedForms) {
  Model m = model_of(model_text("elasto-backlash"));
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);

  const double t0 = kGap / kV0, w2 = std::sqrt(2 * kC / kM);
  const double tau1 = std::atan(kD * w2 / kC) / w2;
  const double e1 = kV0 / w2 * std::sin(w2 * tau1), ed1 = kV0 * std::cos(w2 * tau1);
  const double g = kD / (2 * kM), wd = std::sqrt(kC / kM - g * g), B = (ed1 + g * e1) / wd;
  auto e = [&](double s) { return std::exp(-g * s) * (e1 * std::cos(wd * s) + B * std::sin(wd * s)); };
  auto ed = [&](double s) {
    return std::exp(-g * s) * ((B * wd - g * e1) * std::cos(wd * s) - (e1 * wd + g * B) * std::sin(wd * s));
  };
  auto F = [&](double s) { return kC * e(s) + kD * ed(s); };
  // F > 0 after the kink until it falls through zero within half a damped period.
  double lo = 0.5 / wd, hi = 3.2 / wd;
  ASSERT_GT(F(lo), 0.0);
  ASSERT_LT(F(hi), 0.0);
  for (int i = 0; i < 200; ++i) (F(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  const double tau2 = 0.5 * (lo + hi), v_out = ed(tau2);

  std::vector<double> t_closed, t_opened;
  for (const auto& ev : r.hybrid.events) {
    if (ev.element != "c") continue;
    if (ev.kind == "gap_closed") t_closed.push_back(ev.t);
    if (ev.kind == "gap_opened") t_opened.push_back(ev.t);
  }
  ASSERT_EQ(t_closed.size(), 1u);
  ASSERT_EQ(t_opened.size(), 1u);
  EXPECT_NEAR(t_closed[0], t0, 1e-12);
  EXPECT_NEAR(t_opened[0], t0 + tau1 + tau2, 1e-9 * t_opened[0]);
  EXPECT_NEAR(series(r, "A.velocity_m_s").back(), v_out, 1e-8);
  // Phase 1 on the grid: F = 2 c e (the damper acts as a second spring), not c e + d ė.
  const double t_in = 0.0105;
  ASSERT_LT(t_in, t0 + tau1);
  EXPECT_NEAR(at(r, "c.load_N", t_in), 2 * kC * kV0 / w2 * std::sin(w2 * (t_in - t0)), 1e-6);
  // Phase 2 on the grid.
  const double t_2 = 0.0140;
  ASSERT_GT(t_2, t0 + tau1);
  ASSERT_LT(t_2, t0 + tau1 + tau2);
  EXPECT_NEAR(at(r, "c.load_N", t_2), F(t_2 - t0 - tau1), 1e-6);
  // Energy: the spring still holds ½ c e(τ2)² when the mass lets go (c e = −d ė > 0 there); that is
  // released, and the rest of the kinetic energy lost was dissipated by the capped damper.
  const auto& E = r.hybrid.energy;
  const double released = 0.5 * kC * e(tau2) * e(tau2);
  EXPECT_NEAR(E.release_loss, released, 1e-7);
  EXPECT_NEAR(E.damping_loss, 0.5 * kM * (kV0 * kV0 - v_out * v_out) - released, 1e-7);
}

// Claim: under the linear law the load jumps to d v0 at contact, under the capped law it starts at
// 0; both give the same contact time only if d = 0 (here they differ, so the law is really in use).
TEST_P(ElastoBacklash, LinearLawJumpsAtContactCappedDoesNot) {
  Model lin = model_of(model_text("linear")), cap = model_of(model_text("elasto-backlash"));
  lin.simulation.integrator = cap.simulation.integrator = GetParam();
  lin.simulation.dt_out = cap.simulation.dt_out = 1e-6;
  const SimulationResult rl = simulate(lin), rc = simulate(cap);
  // First output after contact at 0.01 s: t = 0.010001 s, τ = 1e-6 s.
  EXPECT_NEAR(at(rl, "c.load_N", 0.010001), kD * kV0, 0.01 * kD * kV0);
  EXPECT_LT(at(rc, "c.load_N", 0.010001), 2 * kC * kV0 * 1.01e-6);
  EXPECT_GT(at(rc, "c.load_N", 0.010001), 0.0);
}

TEST(ElastoBacklashInput, OnlyOnAGapOrARope) {
  try {
    model_of(R"(
bodies: {A: {type: translational, mass: 2}}
links: {c: {type: spring-damper, between: [A, ground], stiffness: 1e5 N/m, damping: 1 N*s/m, flank_law: elasto-backlash}}
)");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("test.yaml:3:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("flank_law"), std::string::npos) << e.what();
  }
  try {
    model_of(R"(
bodies: {A: {type: translational, mass: 2}}
links: {c: {type: rope, between: [A, ground], stiffness: 1e5 N/m, flank_law: capped}}
)");
    FAIL() << "accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("expected one of: linear, elasto-backlash"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace machdyn
