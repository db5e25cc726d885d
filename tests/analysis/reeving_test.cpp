// Reeving as drawn (model/reeving.hpp; `type: rope` with `falls`, `rope_ends`, `sheave_efficiency`):
// the ratio and stiffness of a 4/2 reeving, the force in one rope part and in the part at the drum
// with lossy sheaves against the parts' balance worked by hand, hoisting, lowering and at rest, on
// both integrators; old files keep their meaning; bad reeving is a located error.
#include <algorithm>
#include <cmath>
#include <vector>
#include <string>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/equilibrium.hpp"
#include "machdyn/analysis/linear_analysis.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/elements/linearize.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "machdyn/model/sheaves.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::series;

Model model_of(const std::string& yaml) { return compile_model(parse_yaml_string(yaml, "reeving.yaml"), "reeving.yaml"); }

std::string error_of(const std::string& yaml) {
  try {
    model_of(yaml);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

class Reeving : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, Reeving, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

constexpr double kG = 9.81, kMass = 12000.0, kEta = 0.98;

// Claim: a 4/2 reeving (two rope ends on a 0.5 m drum, four falls) hanging at rest, held by the brake.
// By hand: each end feeds 2 parts, so winding in Δs at each end lifts the hook by Δs/2: i = 2/R =
// 8 rad/m. The four parts are stretched by the hook's e each: c = 4 E A / L_f, e = m g L_f/(4 E A).
// One part carries m g / 4. With sheaves of η = 0.98, the part at the drum T_0 and the part over the
// hook block's sheave T_1 = η T_0 (hoisting; at rest the hoisting value is reported), and the hook's
// balance over both ends 2 (T_0 + T_1) = m g: T_0 = m g / (2 (1 + η)).
TEST_P(Reeving, FourTwoReevingAtRestCarriesAQuarterPerPart) {
  Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies:
  drum: {inertia: 50 kg*m^2, position: 3 rad}
  hook: {type: translational, mass: 12 t, vertical: up}
links:
  rope: {type: rope, between: [drum, hook], ratio: 4 rad/m, falls: 4, rope_ends: 2, sheave_efficiency: 0.98,
         EA: 2.5e7 N, length: 15 m, damping: 1e3 N*s/m}
brakes: {hold: {body: drum, holding: 1e5 N*m}}
simulation: {t_end: 0.1 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-13, initial: equilibrium}
)");
  m.simulation.integrator = GetParam();
  const double mg = kMass * kG, EA = 2.5e7, Lf = 15.0;
  EXPECT_DOUBLE_EQ(rope_ratio(m, m.links[0]), 2.0 / 0.25);  // the drum's, in its sheave gear (model/sheaves.hpp)
  EXPECT_DOUBLE_EQ(m.links[0].c, 4.0 * EA / Lf);
  const double e = mg * Lf / (4.0 * EA);
  const EquilibriumStart st = static_equilibrium(m);
  EXPECT_NEAR(st.q0[1], 3.0 / 8.0 - e, 1e-12);
  const SimulationResult r = simulate(m);
  const auto &F = series(r, "rope.load_N"), &T = series(r, "rope.fall_tension_N"), &T0 = series(r, "rope.rope_force_N");
  ASSERT_FALSE(F.empty());
  for (size_t k = 0; k < F.size(); ++k) {
    EXPECT_NEAR(F[k], mg, 1e-9 * mg);
    EXPECT_NEAR(T[k], mg / 4.0, 1e-9 * mg);
    EXPECT_NEAR(T0[k], mg / (2.0 * (1.0 + kEta)), 1e-9 * mg);
  }
}

// Claim: hoisting and lowering at 2 rad/s (rope speed R ω = 0.5 m/s at the drum, the hook at 0.25 m/s)
// with the load riding steadily on the stretched rope (F = m g). By hand, 4/2 reeving, η = 0.98:
// hoisting the rope runs towards the drum, T_1 = η T_0, 2 (T_0 + η T_0) = F; lowering it runs away,
// T_1 = T_0/η, 2 (T_0 + T_0/η) = F, T_0 = F η / (2 (1 + η)). 6/2 reeving (three parts per end,
// η = 0.95) hoisting: 2 T_0 (1 + η + η²) = F. The hook follows the drum at ω/i.
TEST_P(Reeving, PartAtTheDrumHoistingAndLowering) {
  struct Case {
    int falls;
    double eta, omega;
  };
  for (const Case c : {Case{4, kEta, 2.0}, Case{4, kEta, -2.0}, Case{6, 0.95, 2.0}}) {
    const double i = (c.falls / 2) / 0.25, cr = 4e6, mg = kMass * kG, v = c.omega / i;
    const std::string yaml =
        "gravity: 9.81 m/s^2\nbodies:\n  drum: {inertia: 1e12 kg*m^2, velocity: " + fmt::format("{:.17g}", c.omega) +
        " rad/s}\n  hook: {type: translational, mass: 12 t, vertical: up, position: " + fmt::format("{:.17g}", -mg / cr) +
        " m, velocity: " + fmt::format("{:.17g}", v) + " m/s}\nlinks:\n  rope: {type: rope, between: [drum, hook], ratio: "
        "4 rad/m, falls: " + std::to_string(c.falls) + ", rope_ends: 2, sheave_efficiency: " + std::to_string(c.eta) +
        ", stiffness: 4e6 N/m}\nsimulation: {t_end: 0.2 s, dt_out: 10 ms, rtol: 1e-11, atol: 1e-13}\n";
    Model m = model_of(yaml);
    m.simulation.integrator = GetParam();
    const double eta = c.eta;
    const double by_hand = c.falls == 6 ? 1.0 / (2.0 * (1.0 + eta + eta * eta))
                           : c.omega > 0.0 ? 1.0 / (2.0 * (1.0 + eta))
                                           : eta / (2.0 * (1.0 + eta));
    const SimulationResult r = simulate(m);
    const auto &F = series(r, "rope.load_N"), &T0 = series(r, "rope.rope_force_N"), &xv = series(r, "hook.velocity_m_s");
    for (size_t k = 0; k < F.size(); ++k) {
      EXPECT_NEAR(F[k], mg, 1e-6 * mg) << c.falls << " " << c.omega;
      EXPECT_NEAR(T0[k], by_hand * F[k], 1e-12 * mg) << c.falls << " " << c.omega;
      EXPECT_NEAR(xv[k], v, 1e-9) << c.falls << " " << c.omega;
    }
  }
}

// The crane of the frame tests: a girder (trolley + its share of the girder, 9 t, its coordinate from
// its static position, so no weight of its own) on the girder's stiffness c_g to the ground, the rope
// (c_r at the hook, its top on the girder: `frame`) carrying a 600 kg hook block, the 32 t load on
// its slings (c_s).
constexpr double kMg = 9000.0, kMh = 600.0, kMl = 32000.0, kCg = 3.2e7, kCr = 6e6, kCs = 2e7;
const char* kGirderCrane = R"(
gravity: 9.81 m/s^2
bodies:
  girder: {type: translational, mass: 9 t}
  hook: {type: translational, mass: 600 kg, vertical: up}
  load: {type: translational, mass: 32 t, vertical: up}
links:
  girder_spring: {type: spring, between: [ground, girder], stiffness: 3.2e7 N/m}
  rope: {type: rope, between: [ground, hook], frame: girder, stiffness: 6e6 N/m}
  slings: {type: rope, between: [hook, load], stiffness: 2e7 N/m}
simulation: {t_end: 0.5 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-13, initial: equilibrium}
)";

/// det(K − λ M) of the chain ground – c_g – m_g – c_r – m_h – c_s – m_l by the three-term recurrence of
/// a tridiagonal matrix (independent of the modal solver).
double chain_determinant(double lambda) {
  const double d1 = kCg + kCr - lambda * kMg, d2 = kCr + kCs - lambda * kMh, d3 = kCs - lambda * kMl;
  const double p1 = d1, p2 = d2 * p1 - kCr * kCr;
  return d3 * p2 - kCs * kCs * p1;
}

// The roots ω of det(K − ω² M) = 0: sign changes of chain_determinant over ω² up to Gershgorin's
// bound, each bisected to the last bit (an answer independent of the engine's eigen-solvers).
std::vector<double> chain_frequencies() {
  const double bound = std::max({(kCg + 2 * kCr) / kMg, (2 * kCr + 2 * kCs) / kMh, 2 * kCs / kMl});
  std::vector<double> roots;
  const int steps = 200000;
  for (int k = 0; k < steps; ++k) {
    double lo = bound * k / steps, hi = bound * (k + 1) / steps;
    if ((chain_determinant(lo) > 0) == (chain_determinant(hi) > 0)) continue;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      ((chain_determinant(lo) > 0) == (chain_determinant(mid) > 0) ? lo : hi) = mid;
    }
    roots.push_back(std::sqrt(0.5 * (lo + hi)));
  }
  return roots;
}

// Claim: a girder in series with the rope (`frame`): the rope's stretch is x_girder − x_hook, its load
// pulls the girder down. Drum held, the hanging crane is the chain ground – c_g – m_g – c_r – m_h – c_s
// – m_l: its three frequencies are the roots of det(K − ω² M) (found here by bisection on the
// recurrence above, below the Gershgorin bound), to 1e-9. Statically by hand: the girder carries
// (m_h + m_l) g on c_g, the rope the same, the slings m_l g: x_g = −(m_h + m_l) g/c_g, x_h = x_g −
// (m_h + m_l) g/c_r, x_l = x_h − m_l g/c_s; the run stays there on both integrators.
TEST_P(Reeving, GirderAndHookBlockInSeriesWithTheRope) {
  Model m = model_of(kGirderCrane);
  m.simulation.integrator = GetParam();
  ASSERT_EQ(m.links[1].third, 0);
  const double W = (kMh + kMl) * kG, x_g = -W / kCg, x_h = x_g - W / kCr, x_l = x_h - kMl * kG / kCs;
  const EquilibriumStart st = static_equilibrium(m);
  EXPECT_NEAR(st.q0[0], x_g, 1e-12);
  EXPECT_NEAR(st.q0[1], x_h, 1e-12);
  EXPECT_NEAR(st.q0[2], x_l, 1e-12);
  const Modes md = compute_modes(with_equilibrium_start(m));
  ASSERT_EQ(md.omega.size(), 3);
  const std::vector<double> roots = chain_frequencies();
  ASSERT_EQ(roots.size(), 3u);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(md.omega(k), roots[static_cast<size_t>(k)], 1e-9 * roots[static_cast<size_t>(k)]) << k;
  const SimulationResult r = simulate(m);
  EXPECT_NEAR(series(r, "girder.position_m").back(), x_g, 1e-9);
  EXPECT_NEAR(series(r, "load.position_m").back(), x_l, 1e-9);
  EXPECT_NEAR(series(r, "rope.load_N").back(), W, 1e-6 * W);
}

// Claim: the frame is the body the file names also when ideal gears slave bodies listed before it
// (compile reduces the slaves away and renumbers the bodies: the frame is renumbered with the rope's
// ends). Two geared inertias on a torsion spring precede the crane of the test above; statically
// by hand the girder still sits at −(m_h + m_l) g/c_g and the load where it sat there.
TEST_P(Reeving, FrameNamedAfterGearedBodiesIsStillTheGirder) {
  std::string yaml = kGirderCrane;
  yaml.replace(yaml.find("  girder: {"), 0, "  a: {inertia: 2 kg*m^2}\n  b: {inertia: 1 kg*m^2}\n");
  yaml.replace(yaml.find("  girder_spring:"), 0,
               "  tie: {type: spring, between: [ground, a], stiffness: 100 N*m/rad}\n"
               "  gear: {type: ideal-gear, between: [a, b], ratio: 3}\n");
  Model m = model_of(yaml);
  m.simulation.integrator = GetParam();
  const double W = (kMh + kMl) * kG, x_g = -W / kCg, x_h = x_g - W / kCr, x_l = x_h - kMl * kG / kCs;
  const SimulationResult r = simulate(m);
  EXPECT_NEAR(series(r, "girder.position_m").back(), x_g, 1e-9);
  EXPECT_NEAR(series(r, "hook.position_m").back(), x_h, 1e-9);
  EXPECT_NEAR(series(r, "load.position_m").back(), x_l, 1e-9);
}

// The crane above with its rope given as drawn: 4/2 reeving on a 0.5 m drum held by its brake, EA =
// 1.5e7 N, 10 m per fall at the start: c(L_f0) = 4 EA / L_f0 = 6e6 N/m = c_r of the chain above.
const char* kGirderWindingCrane = R"(
gravity: 9.81 m/s^2
bodies:
  drum: {inertia: 50 kg*m^2}
  girder: {type: translational, mass: 9 t}
  hook: {type: translational, mass: 600 kg, vertical: up}
  load: {type: translational, mass: 32 t, vertical: up}
links:
  girder_spring: {type: spring, between: [ground, girder], stiffness: 3.2e7 N/m}
  rope: {type: rope, between: [drum, hook], frame: girder, ratio: 4 rad/m, falls: 4, rope_ends: 2, EA: 1.5e7 N, length: 10 m}
  slings: {type: rope, between: [hook, load], stiffness: 2e7 N/m}
brakes: {hold: {body: drum, holding: 1e6 N*m}}
simulation: {t_end: 0.5 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-13, initial: equilibrium}
)";

// Claim: a rope given by its length and EA in series with the girder (`frame` with a winding rope,
// issue 32 item 3). Drum held by its brake, the rope's stiffness is c(L_f0) = 4 EA/L_f0 = 6e6 N/m at
// the initial length, so statically by hand x_g = −(m_h + m_l) g/c_g, x_h = x_g − (m_h + m_l) g/c(L_f0),
// x_l = x_h − m_l g/c_s, and the three frequencies of the hanging crane (the drum held) are the roots
// of det(K − ω² M) of the chain ground – c_g – m_g – c(L_f0) – m_h – c_s – m_l, to 1e-9; the run stays
// at rest there on both integrators.
TEST_P(Reeving, GirderInSeriesWithARopeGivenByLengthAndEA) {
  Model m = model_of(kGirderWindingCrane);
  m.simulation.integrator = GetParam();
  ASSERT_EQ(m.links[1].third, 1);
  EXPECT_DOUBLE_EQ(m.links[1].c, 4.0 * 1.5e7 / 10.0);
  const double W = (kMh + kMl) * kG, x_g = -W / kCg, x_h = x_g - W / kCr, x_l = x_h - kMl * kG / kCs;
  const EquilibriumStart st = static_equilibrium(m);
  EXPECT_NEAR(st.q0[0], 0.0, 1e-12);  // the drum, held
  EXPECT_NEAR(st.q0[1], x_g, 1e-12);
  EXPECT_NEAR(st.q0[2], x_h, 1e-12);
  EXPECT_NEAR(st.q0[3], x_l, 1e-12);
  // The hanging crane's topology: the brake stuck holds the drum (a constraint row).
  const Model me = with_equilibrium_start(m);
  const TopologyModes tm = analyse_topology(me, initial_topology(me, 0.0));
  EXPECT_EQ(tm.modes.constraints, 1);
  std::vector<double> elastic;
  for (Eigen::Index k = 0; k < tm.modes.omega.size(); ++k) elastic.push_back(tm.modes.omega(k));
  ASSERT_EQ(elastic.size(), 3u);
  const std::vector<double> roots = chain_frequencies();
  ASSERT_EQ(roots.size(), 3u);
  for (size_t k = 0; k < 3; ++k) EXPECT_NEAR(elastic[k], roots[k], 1e-9 * roots[k]) << k;
  const SimulationResult r = simulate(m);
  EXPECT_NEAR(series(r, "girder.position_m").back(), x_g, 1e-9);
  EXPECT_NEAR(series(r, "hook.position_m").back(), x_h, 1e-9);
  EXPECT_NEAR(series(r, "load.position_m").back(), x_l, 1e-9);
  EXPECT_NEAR(series(r, "rope.load_N").back(), W, 1e-6 * W);
}

// Claim: hoisting on a rope given by length and EA whose drum hangs from the girder: the stiffness
// follows the wound length. The drum turns at ω = 2 rad/s (prescribed), the hook (m = 12 t, the
// rope's damping d = 2e4 N·s/m) rides steadily: by hand, with s = 1/i = 1/8 m/rad and L_f(t) = L_f0 −
// s ω t, the hook does not accelerate, so F = c(t) e + d ė = m g, the girder sits at x_g = −m g/c_g,
// and e = (m g − d ė) L_f/(n EA); with L̇_f = −s ω and ė constant, ė = −(m g − d ė) s ω/(n EA), so
// m g − d ė = m g n EA/(n EA − d s ω) =: F_c and
//   x_h(t) = x_g + s ω t − F_c L_f(t)/(n EA),   ẋ_h = s ω + F_c s ω/(n EA).
// Started on that motion, the hook stays on it to 1e-7 m over 2 s (0.5 m hoisted of 10 m: c rises 5 %)
// on both integrators.
TEST_P(Reeving, HoistingOnAWindingRopeWithAFrame) {
  const double mg = kMass * kG, n = 4.0, EA = 1.5e7, L0 = 10.0, s = 1.0 / 8.0, w = 2.0, d = 2e4, cg = 3.2e7;
  const double x_g = -mg / cg, corr = mg * n * EA / (n * EA - d * s * w);
  auto x_hook = [&](double t) { return x_g + s * w * t - corr * (L0 - s * w * t) / (n * EA); };
  const double v_hook = s * w + corr * s * w / (n * EA);
  const std::string yaml = fmt::format(R"(
gravity: 9.81 m/s^2
bodies:
  drum: {{inertia: 50 kg*m^2, motion: {{speed: 2 rad/s}}}}
  girder: {{type: translational, mass: 9 t, position: {:.17g} m}}
  hook: {{type: translational, mass: 12 t, vertical: up, position: {:.17g} m, velocity: {:.17g} m/s}}
links:
  girder_spring: {{type: spring, between: [ground, girder], stiffness: 3.2e7 N/m}}
  rope: {{type: rope, between: [drum, hook], frame: girder, ratio: 4 rad/m, falls: 4, rope_ends: 2, EA: 1.5e7 N,
         length: 10 m, damping: 2e4 N*s/m}}
simulation: {{t_end: 2 s, dt_out: 10 ms, rtol: 1e-11, atol: 1e-13}}
)",
                                       x_g, x_hook(0.0), v_hook);
  Model m = model_of(yaml);
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  const auto &t = series(r, "t_s"), &xh = series(r, "hook.position_m"), &xg = series(r, "girder.position_m");
  ASSERT_GT(t.size(), 100u);
  for (size_t k = 0; k < t.size(); ++k) {
    EXPECT_NEAR(xh[k], x_hook(t[k]), 1e-7) << t[k];
    EXPECT_NEAR(xg[k], x_g, 1e-8) << t[k];
  }
  // The stiffness at the end: 4 EA / (L_f0 − s ω t_end), 5.3 % above the start's.
  EXPECT_NEAR(series(r, "rope.fall_length_m").back(), L0 - s * w * 2.0, 1e-9);
}

// Claim: a file without `rope_ends` means what it meant: `falls: 4` is one rope end feeding four
// falls (i = 4/R), one part carries F/4, and no rope_force column is added (the frictionless reeving).
TEST(ReevingFile, FallsAloneKeepTheirMeaning) {
  const Model m = model_of(R"(
bodies:
  drum: {inertia: 50 kg*m^2}
  hook: {type: translational, mass: 1 t}
links:
  rope: {type: rope, between: [drum, hook], ratio: 4 rad/m, falls: 4, stiffness: 1e6 N/m}
)");
  EXPECT_DOUBLE_EQ(m.links[0].ratio, 16.0);
  EXPECT_EQ(m.links[0].rope_ends, 1);
  EXPECT_FALSE(has_reeving(m.links[0]));
}

// Claim: reeving the drum cannot carry is a located error: falls not shared equally by the rope ends,
// an efficiency outside (0, 1], rope ends on a rope anchored to the ground, a rope field on a spring.
TEST(ReevingFile, BadReevingIsLocated) {
  const std::string head = "bodies:\n  drum: {inertia: 50 kg*m^2}\n  hook: {type: translational, mass: 1 t}\nlinks:\n";
  const std::string a = error_of(head + "  rope: {type: rope, between: [drum, hook], ratio: 4 rad/m, falls: 3, "
                                        "rope_ends: 2, stiffness: 1e6 N/m}\n");
  EXPECT_NE(a.find("reeving.yaml:5:82: error: link 'rope': the 3 falls must be shared equally by the 2 rope ends"),
            std::string::npos) << a;
  const std::string b = error_of(head + "  rope: {type: rope, between: [drum, hook], ratio: 4 rad/m, falls: 4, "
                                        "sheave_efficiency: 1.2, stiffness: 1e6 N/m}\n");
  EXPECT_NE(b.find("reeving.yaml:5:90: error: link 'rope': field 'sheave_efficiency' must lie in (0, 1]"),
            std::string::npos) << b;
  const std::string c = error_of(head + "  rope: {type: rope, between: [ground, hook], falls: 2, rope_ends: 2, "
                                        "stiffness: 1e6 N/m}\n");
  EXPECT_NE(c.find("'rope_ends' are wound on a drum"), std::string::npos) << c;
  const std::string d = error_of(head + "  s: {type: spring, between: [drum, hook], ratio: 4 rad/m, rope_ends: 2, "
                                        "stiffness: 1e6 N/m}\n");
  EXPECT_NE(d.find("field 'rope_ends' belongs to a rope"), std::string::npos) << d;
  const std::string f = error_of(head + "  rope: {type: rope, between: [drum, hook], ratio: 4 rad/m, frame: drum, "
                                        "stiffness: 1e6 N/m}\n");
  EXPECT_NE(f.find("the frame 'drum' must be a translational body"), std::string::npos) << f;
}

}  // namespace
}  // namespace machdyn
