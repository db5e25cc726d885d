// A one-sided link (`flank:` on a spring or spring-damper, model/model.hpp Link::tension_only; law:
// elements/link.hpp): the link carries load only from δ = flank on, wherever the flank lies —
// open at the start or preloaded — between two moving bodies, on both integrators, against the
// closed forms derived below; bad input is a located error.
#include <cmath>
#include <numbers>
#include <string>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::max_error;
using test::series;

Model model_of(const std::string& yaml) { return test::model_text(yaml, "test.yaml"); }

std::string errors_of(const std::string& yaml) { return test::compile_errors(yaml, "test.yaml"); }

class OneSidedLink : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, OneSidedLink, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

constexpr double kMA = 2.0, kMB = 3.0, kC = 6e4;

/// Two free bodies A, B on the link [A, B] (c = 6e4 N/m, no damping) with the given flank and start.
SimulationResult run(const std::string& flank, double vA, IntegratorChoice integrator) {
  Model m = model_of(R"(
bodies:
  A: {type: translational, mass: 2 kg, velocity: )" + std::to_string(vA) + R"( m/s}
  B: {type: translational, mass: 3 kg}
links:
  k: {type: spring, between: [A, B], stiffness: 6e4 N/m, flank: )" + flank + R"(}
simulation: {t_end: 0.05 s, dt_out: 1e-4 s, rtol: 1e-11, atol: 1e-13}
)");
  m.simulation.integrator = integrator;
  return simulate(m);
}


/// Checks positions, velocities and the load of A and B against δ(t), δ̇(t) of the relative motion
/// and the centre of mass X = V t (both start at x = 0): x_A = X + (m_B/M) δ, x_B = X − (m_A/M) δ.
template <class D, class Dd, class L>
void check(const SimulationResult& r, double V, D delta, Dd rate, L load) {
  const double M = kMA + kMB;
  EXPECT_LT(max_error(r, "A.position_m", [&](double t) { return V * t + kMB / M * delta(t); }), 1e-9);
  EXPECT_LT(max_error(r, "B.position_m", [&](double t) { return V * t - kMA / M * delta(t); }), 1e-9);
  EXPECT_LT(max_error(r, "A.velocity_m_s", [&](double t) { return V + kMB / M * rate(t); }), 1e-6);
  EXPECT_LT(max_error(r, "B.velocity_m_s", [&](double t) { return V - kMA / M * rate(t); }), 1e-6);
  EXPECT_LT(max_error(r, "k.load_N", load), 1e-4);
}

// Claim: a flank ahead of the start (flank = 20 mm, δ(0) = 0, A at v0 = 1 m/s, B at rest) is
// reached at t1 = flank / v0 = 0.02 s; the relative motion δ = x_A − x_B with μ = m_A m_B / M
// = 1.2 kg then obeys μ ë = −c e, e = δ − flank, so e = (v0/ω) sin ω(t − t1), ω = √(c/μ), and
// the flank opens at t2 = t1 + π/ω with δ̇ = −v0 (no damping). The centre of mass keeps
// V = m_A v0 / M. Load c e in contact, 0 elsewhere; events gap_closed at t1, gap_opened at t2.
TEST_P(OneSidedLink, FlankAheadIsReachedAndLeftAtTheClosedFormInstants) {
  const double v0 = 1.0, fl = 0.02, mu = kMA * kMB / (kMA + kMB), w = std::sqrt(kC / mu);
  const double t1 = fl / v0, t2 = t1 + std::numbers::pi / w;
  const SimulationResult r = run("20 mm", v0, GetParam());
  auto delta = [&](double t) {
    return t < t1 ? v0 * t : t < t2 ? fl + v0 / w * std::sin(w * (t - t1)) : fl - v0 * (t - t2);
  };
  auto rate = [&](double t) { return t < t1 ? v0 : t < t2 ? v0 * std::cos(w * (t - t1)) : -v0; };
  auto load = [&](double t) { return t < t1 || t > t2 ? 0.0 : kC * v0 / w * std::sin(w * (t - t1)); };
  check(r, kMA * v0 / (kMA + kMB), delta, rate, load);
  ASSERT_EQ(r.hybrid.events.size(), 3u);  // initial, closed, opened
  EXPECT_EQ(r.hybrid.events[1].kind, "gap_closed");
  EXPECT_NEAR(r.hybrid.events[1].t, t1, 1e-10);
  EXPECT_EQ(r.hybrid.events[2].kind, "gap_opened");
  EXPECT_NEAR(r.hybrid.events[2].t, t2, 1e-9);
}

// Claim: a flank behind the start (flank = −5 mm, both at rest) is a preload: the link starts
// closed, compressed by e0 = 5 mm (F = c e0 = 300 N), pushes A back and B forward with
// e = e0 cos ω t until e = 0 at t1 = π/(2ω), and the bodies part with δ̇ = −e0 ω; the centre of
// mass stays at rest.
TEST_P(OneSidedLink, FlankBehindTheStartIsAPreload) {
  const double e0 = 0.005, mu = kMA * kMB / (kMA + kMB), w = std::sqrt(kC / mu), t1 = std::numbers::pi / (2 * w);
  const SimulationResult r = run("-5 mm", 0.0, GetParam());
  auto delta = [&](double t) { return t < t1 ? -e0 + e0 * std::cos(w * t) : -e0 - e0 * w * (t - t1); };
  auto rate = [&](double t) { return t < t1 ? -e0 * w * std::sin(w * t) : -e0 * w; };
  auto load = [&](double t) { return t > t1 ? 0.0 : kC * e0 * std::cos(w * t); };
  check(r, 0.0, delta, rate, load);
  ASSERT_EQ(r.hybrid.events.size(), 2u);  // initial (closed), opened
  EXPECT_EQ(r.hybrid.events[0].to, "closed+");
  EXPECT_EQ(r.hybrid.events[1].kind, "gap_opened");
  EXPECT_NEAR(r.hybrid.events[1].t, t1, 1e-9);
}

// Claim: `flank` is refused, at its line, beside a `gap`, on a damper and on a rope (whose free
// play is its `slack`); it takes the position unit of the second body.
TEST(OneSidedLinkInput, BadFlanksAreLocatedErrors) {
  const std::string head = "bodies:\n  A: {type: translational, mass: 1}\n  R: {inertia: 1}\nlinks:\n";
  std::string e = errors_of(head + "  k: {type: spring, between: [A, ground], stiffness: 1, gap: 1 mm, flank: 2 mm}\n");
  EXPECT_NE(e.find("test.yaml:5:"), std::string::npos) << e;
  EXPECT_NE(e.find("either a 'gap' (two flanks) or a 'flank'"), std::string::npos) << e;
  e = errors_of(head + "  k: {type: damper, between: [A, ground], damping: 1, flank: 2 mm}\n");
  EXPECT_NE(e.find("test.yaml:5:"), std::string::npos) << e;
  EXPECT_NE(e.find("a damper cannot have a flank"), std::string::npos) << e;
  e = errors_of(head + "  k: {type: rope, between: [A, ground], stiffness: 1, flank: 2 mm}\n");
  EXPECT_NE(e.find("test.yaml:5:"), std::string::npos) << e;
  EXPECT_NE(e.find("a rope has no 'flank'"), std::string::npos) << e;
  e = errors_of(head + "  k: {type: spring, between: [R, ground], stiffness: 1, flank: 2 mm}\n");
  EXPECT_NE(e.find("test.yaml:5:"), std::string::npos) << e;
  EXPECT_NE(e.find("flank"), std::string::npos) << e;
  // Accepted: any sign, with the capped flank law.
  const Model m = model_of(head + "  k: {type: spring-damper, between: [A, ground], stiffness: 1, damping: 1, "
                                  "flank: -2 mm, flank_law: elasto-backlash}\n");
  ASSERT_EQ(m.links.size(), 1u);
  EXPECT_TRUE(m.links[0].has_gap);
  EXPECT_TRUE(m.links[0].tension_only);
  EXPECT_DOUBLE_EQ(m.links[0].gap, -0.002);
  EXPECT_TRUE(m.links[0].damping_capped);
}

}  // namespace
}  // namespace machdyn
