// The crane analysis (analysis/crane.hpp) and buffers (`buffers:`, model/compile_crane.cpp) against
// the closed forms of /work/shared/docs/crane-standards.md ("Closed forms a simulation must
// reproduce"), on both integrators, and the located errors of the `crane:` and `buffers:` sections.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/analysis/crane.hpp"
#include "machdyn/analysis/crane_standard.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/crane_results.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

Model model_of(const std::string& yaml) {
  return compile_model(parse_yaml_string(yaml, "crane.yaml"), "crane.yaml");
}

class Crane : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, Crane, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

const CraneFactorRow& row(const CraneReport& r, const std::string& factor, size_t nth = 0) {
  for (const auto& x : r.rows)
    if (x.factor == factor && nth-- == 0) return x;
  ADD_FAILURE() << "no row " << factor;
  static const CraneFactorRow none;
  return none;
}

// The hoisting model: a rigid drive (1e15 kg: its speed changes by < 1e-11 relative) lifts the load m
// resting on the ground through a rope c with slack s0.
const char* kHoist = R"(
gravity: 9.81 m/s^2
bodies:
  drive: {type: translational, mass: 1e15 kg}
  load: {type: translational, mass: 1000 kg, vertical: up}
links:
  rope: {type: rope, between: [drive, load], stiffness: 1e6 N/m, slack: 10 mm}
stops: {ground: {body: load, min: 0 m}}
simulation: {t_end: 0.5 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
crane: {hoisting_class: HC2, drive_class: DRIVE, hoist_speed: 0.5 m/s, creep_speed: 0.1 m/s, load: load, rope: rope}
)";

std::string with_drive_class(const std::string& hd) {
  std::string s = kHoist;
  s.replace(s.find("DRIVE"), 5, hd);
  return s;
}

// Claim (crane-standards.md, closed forms): hoisting at constant vh through a rope c lifts the
// grounded load with F_max = m g + vh √(c m), so the simulated φ2 = 1 + vh ω / g, ω = √(c/m), to
// 1e-9 — for HD1 at vh = vh,max = 0.5 m/s and HD4 at 0.5 vh,max, HD2 at the creep speed. The
// standard's value beside it is φ2,min + β2 vh of HC2 (1.10 + 0.34 vh; HD3/HD5 would have 1.05).
TEST_P(Crane, Phi2MatchesTheClosedFormForEachDriveClass) {
  const double g = 9.81, mass = 1000, c = 1e6, w = std::sqrt(c / mass);
  const std::pair<const char*, double> classes[] = {{"HD1", 0.5}, {"HD2", 0.1}, {"HD4", 0.25}};
  for (const auto& [hd, vh] : classes) {
    Model m = model_of(with_drive_class(hd));
    m.simulation.integrator = GetParam();
    const CraneReport r = crane_analysis(m);
    ASSERT_EQ(r.rows.size(), 1u);
    const CraneFactorRow& x = row(r, "phi2");
    EXPECT_NEAR(x.simulated, 1 + vh * w / g, 1e-9) << hd;
    EXPECT_DOUBLE_EQ(x.standard_lo, 1.10 + 0.34 * vh) << hd;
    EXPECT_DOUBLE_EQ(x.margin, x.standard_lo - x.simulated) << hd;
  }
  // HD5 (the drive starts from zero speed) runs the model's own drive: this one never moves, so the
  // load is never lifted — an error (CraneChecks.Phi2NeverReachedIsAnError); a drive that starts
  // from rest: Crane.PrescribedDriveHoistsInHD1AndItsOwnRampInHD5.
}

// Claim: φ2(vh) of the rigid drive follows the closed form 1 + vh ω / g at every speed of the sweep
// (a straight line in vh, as the standard's; slope ω/g = 3.22 s/m against β2 = 0.34 s/m of HC2).
TEST_P(Crane, Phi2SweepFollowsTheClosedFormBesideTheStandardLine) {
  Model m = model_of(with_drive_class("HD1"));
  m.simulation.integrator = GetParam();
  const double w = std::sqrt(1e6 / 1000.0);
  const auto pts = phi2_sweep(m, {0.1, 0.3, 0.5});
  ASSERT_EQ(pts.size(), 3u);
  for (const auto& p : pts) {
    EXPECT_NEAR(p.simulated, 1 + p.vh * w / 9.81, 1e-9) << p.vh;
    EXPECT_DOUBLE_EQ(p.standard, 1.10 + 0.34 * p.vh) << p.vh;
  }
  EXPECT_THROW(phi2_sweep(m, {0.0}), std::invalid_argument);
}

// Claim: the φ2 case starts the whole free group behind the rope in rigid motion: a drum (I, rope
// drum ratio i = 1/R in rad/m) hoisting through the rope turns at ω = vh i, so the rope's end moves
// at vh; with a huge drum inertia the closed form holds as for the linear drive.
TEST_P(Crane, Phi2DrivesTheGroupThroughTheRatio) {
  Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies:
  drum: {inertia: 1e15 kg*m^2}
  load: {type: translational, mass: 2000 kg, vertical: up}
links:
  rope: {type: rope, between: [drum, load], ratio: 4 rad/m, stiffness: 4e6 N/m, slack: 5 mm}
stops: {ground: {body: load, min: 0 m}}
simulation: {t_end: 0.1 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
crane: {hoisting_class: HC3, drive_class: HD1, hoist_speed: 0.4 m/s, load: load, rope: rope}
)");
  m.simulation.integrator = GetParam();
  const Model c = phi2_case_model(m, 0.4);
  EXPECT_DOUBLE_EQ(c.bodies[0].v0, 1.6);  // ω = vh i
  EXPECT_EQ(c.bodies[1].v0, 0.0);
  const CraneFactorRow x = row(crane_analysis(m), "phi2");
  EXPECT_NEAR(x.simulated, 1 + 0.4 * std::sqrt(4e6 / 2000) / 9.81, 1e-9);
  EXPECT_DOUBLE_EQ(x.standard_lo, 1.15 + 0.51 * 0.4);
}

// Claim (crane-standards.md, closed forms): releasing Δm from a load m hanging at rest on a rope c
// leaves m − Δm oscillating about its new equilibrium with amplitude Δm g / c: the rope force runs
// between m g (the start) and (m − 2Δm) g, so the simulated φ3 = 1 − 2Δm/m — the standard's value
// for rapid release (β3 = 1), margin 0 — and the load's lowest point stays the start, x = −m g / c.
TEST_P(Crane, Phi3SuddenReleaseOscillatesAboutTheNewEquilibrium) {
  Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies: {load: {type: translational, mass: 1000 kg, vertical: up}}
links: {rope: {type: rope, between: [ground, load], stiffness: 1e6 N/m}}
stops: {ground: {body: load, min: -5 m}}
simulation: {t_end: 0.3 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
crane: {load: load, rope: rope, release: {mass: 300 kg, kind: rapid}}
)");
  m.simulation.integrator = GetParam();
  const double g = 9.81, mass = 1000, dm = 300, c = 1e6;
  const Model start = phi3_case_model(m, dm);
  EXPECT_NEAR(start.bodies[0].q0, -mass * g / c, 1e-15);
  EXPECT_EQ(start.bodies[0].inertia, mass - dm);
  const SimulationResult res = simulate(start);
  EXPECT_NEAR(res.links[0].max, mass * g, 1e-9 * mass * g);
  EXPECT_NEAR(res.links[0].min, (mass - 2 * dm) * g, 1e-9 * mass * g);
  // the minimum comes half a period after the release: π / ω, ω = √(c / (m − Δm))
  EXPECT_NEAR(res.links[0].t_min, std::numbers::pi / std::sqrt(c / (mass - dm)), 1e-6);
  const CraneFactorRow x = row(crane_analysis(m), "phi3");
  EXPECT_NEAR(x.simulated, 1 - 2 * dm / mass, 1e-9);
  EXPECT_DOUBLE_EQ(x.standard_lo, crane::phi3(dm, mass, crane::ReleaseKind::rapid));
  EXPECT_NEAR(x.margin, 0.0, 1e-9);
}

// Claim: with the load on a drum (rope ratio i = 10 rad/m) the φ3 case holds the drum by its holding
// brake, so the load again oscillates on the rope alone: rope force between m g and (m − 2Δm) g, the
// drum stays at rest (the brake stuck throughout); slow release compares with β3 = 0.5:
// 1 − (500/2000)(1.5) = 0.625 against the simulated 1 − 2 · 500/2000 = 0.5 (margin −0.125).
TEST_P(Crane, Phi3HoldsTheDrumByItsBrake) {
  Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies:
  drum: {inertia: 50 kg*m^2}
  load: {type: translational, mass: 2000 kg, vertical: up}
links: {rope: {type: rope, between: [drum, load], ratio: 10 rad/m, stiffness: 2e6 N/m}}
simulation: {t_end: 0.3 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
crane: {load: load, rope: rope, release: {mass: 500 kg, kind: slow}}
)");
  m.simulation.integrator = GetParam();
  const double g = 9.81;
  const SimulationResult res = simulate(phi3_case_model(m, 500));
  EXPECT_NEAR(res.links[0].max, 2000 * g, 1e-9 * 2000 * g);
  EXPECT_NEAR(res.links[0].min, 1000 * g, 1e-9 * 2000 * g);
  for (size_t c = 0; c < res.column_names.size(); ++c) {
    if (res.column_names[c] != "drum.position_rad") continue;
    for (double q : res.columns[c]) ASSERT_EQ(q, 0.0);
  }
  const CraneFactorRow x = row(crane_analysis(m), "phi3");
  EXPECT_NEAR(x.simulated, 0.5, 1e-9);
  EXPECT_DOUBLE_EQ(x.standard_lo, 0.625);
  EXPECT_NEAR(x.margin, -0.125, 1e-9);
}

// Claim: `release: {time: t_r}` releases Δm at t_r of a run that hangs at rest in the same
// equilibrium (drum held): nothing moves before t_r, then the oscillation of the release at once,
// shifted by t_r — rope force between m g and (m − 2Δm) g, the minimum at t_r + π/ω', ω' = √(c/(m −
// Δm)) — so the row's φ3 is again 1 − 2Δm/m (to 1e-9) beside the same standard value.
TEST_P(Crane, Phi3ReleasedAtATimeOfAHangingRun) {
  Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies:
  drum: {inertia: 50 kg*m^2}
  load: {type: translational, mass: 2000 kg, vertical: up}
links: {rope: {type: rope, between: [drum, load], ratio: 10 rad/m, stiffness: 2e6 N/m}}
simulation: {t_end: 0.3 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
crane: {load: load, rope: rope, release: {mass: 500 kg, kind: rapid, time: 0.07 s}}
)");
  m.simulation.integrator = GetParam();
  const double g = 9.81, mass = 2000, dm = 500, c = 2e6, tr = 0.07;
  const CraneFactorRow x = row(crane_analysis(m), "phi3");
  EXPECT_NEAR(x.simulated, 1 - 2 * dm / mass, 1e-9);
  EXPECT_DOUBLE_EQ(x.standard_lo, crane::phi3(dm, mass, crane::ReleaseKind::rapid));
  EXPECT_NE(x.case_name.find("at t = 0.07 s hanging"), std::string::npos) << x.case_name;
  SimulateOptions opt;
  opt.extremes_from = tr;
  const SimulationResult res = simulate(phi3_release_case_model(m, dm, tr), opt);
  EXPECT_NEAR(res.links[0].t_min, tr + std::numbers::pi / std::sqrt(c / (mass - dm)), 1e-9);
  EXPECT_NEAR(res.links[0].max, mass * g, 1e-9 * mass * g);
}

// Claim: `release: {time: t_r, while: hoisting}` hoists as the φ2 case — a rigid drive at vh takes up
// the slack s0 and lifts the grounded load m off at t_l = s0/vh + m g/(c vh), at rest — and releases
// Δm at t_r > t_l. Rope stretch e (F = c e): after lift-off e'' = −(c/m) e + g, e(t_l) = m g/c,
// e'(t_l) = vh ⇒ e = m g/c + (vh/ω) sin ω(t − t_l), ω = √(c/m). After t_r the same with m' = m − Δm
// from (e_r, e'_r): e = m' g/c + A cos ω'τ + B sin ω'τ, A = e_r − m' g/c, B = e'_r/ω', so the rope's
// minimum after the release is F_min = m' g − c √(A² + B²) (the rope stays taut) and φ3 = F_min/(m g)
// (to 1e-9). Before t_r the rope is slack (force 0): the minimum counts from t_r only.
TEST_P(Crane, Phi3ReleasedWhileHoistingMatchesTheClosedForm) {
  std::string yaml = with_drive_class("HD1");
  yaml.replace(yaml.find("hoist_speed: 0.5 m/s"), 20, "hoist_speed: 0.1 m/s");
  yaml.replace(yaml.find("rope: rope}"), 11, "rope: rope, release: {mass: 300 kg, time: 0.25 s, while: hoisting}}");
  Model m = model_of(yaml);
  m.simulation.integrator = GetParam();
  const double g = 9.81, mass = 1000, dm = 300, c = 1e6, vh = 0.1, s0 = 0.01, tr = 0.25;
  const double w = std::sqrt(c / mass), w2 = std::sqrt(c / (mass - dm));
  const double tl = s0 / vh + mass * g / (c * vh);
  const double er = mass * g / c + vh / w * std::sin(w * (tr - tl)), der = vh * std::cos(w * (tr - tl));
  const double A = er - (mass - dm) * g / c, B = der / w2;
  const double F_min = (mass - dm) * g - c * std::hypot(A, B);
  ASSERT_GT(F_min, 0.0);  // the closed form needs the rope taut
  const CraneFactorRow x = row(crane_analysis(m), "phi3");
  EXPECT_NEAR(x.simulated, F_min / (mass * g), 1e-9);
  EXPECT_NE(x.case_name.find("while hoisting"), std::string::npos) << x.case_name;
  // The whole run's minimum is the slack rope before lift-off: 0.
  const SimulationResult all = simulate(phi3_release_case_model(m, dm, tr));
  EXPECT_EQ(all.links[0].min, 0.0);
}

// Claim: the new release fields are checked with located errors: `while` without `time`, `while:
// hoisting` without the hoisting speed, a negative time.
TEST(CraneInput, ReleaseDuringARunErrors) {
  try {
    model_of(R"(
gravity: 9.81 m/s^2
bodies: {load: {type: translational, mass: 1000 kg, vertical: up}}
links: {rope: {type: rope, between: [ground, load], stiffness: 1e6 N/m}}
crane: {load: load, rope: rope, release: {mass: 300 kg, while: hoisting}}
)");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string s = e.what();
    EXPECT_NE(s.find("crane.yaml:5:"), std::string::npos) << s;
    EXPECT_NE(s.find("'while' needs the release 'time'"), std::string::npos) << s;
    EXPECT_NE(s.find("give it in the crane section"), std::string::npos) << s;
  }
  try {
    model_of(R"(
gravity: 9.81 m/s^2
bodies: {load: {type: translational, mass: 1000 kg, vertical: up}}
links: {rope: {type: rope, between: [ground, load], stiffness: 1e6 N/m}}
crane: {load: load, rope: rope, release: {mass: 300 kg, time: -1 s}}
)");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("crane.yaml:5:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("field 'time' must be zero or positive"), std::string::npos) << e.what();
  }
}

// Claim (crane-standards.md, closed forms): a rigid mass m at v into a linear buffer c has
// F_max = v √(c m) (the buffer closes at x_b, then x − x_b = (v/ω) sin ω t, ω = √(c/m)); it is its
// own rigid-body reference, so φ7 simulated = 1 against 1.25 (ξb = 1/2 of a linear spring).
TEST_P(Crane, Phi7RigidMassIntoALinearBuffer) {
  Model m = model_of(R"(
bodies: {trolley: {type: translational, mass: 2000 kg, velocity: 1.2 m/s}}
buffers: {east: {body: trolley, max: 0.3 m, stiffness: 2e5 N/m}}
simulation: {t_end: 1 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
crane: {buffers: [east]}
)");
  m.simulation.integrator = GetParam();
  const double F = 1.2 * std::sqrt(2e5 * 2000), w = std::sqrt(2e5 / 2000);
  const SimulationResult res = simulate(m);
  EXPECT_NEAR(res.links[0].max, F, 1e-9 * F);
  EXPECT_NEAR(res.links[0].t_max, 0.3 / 1.2 + std::numbers::pi / (2 * w), 1e-6);
  EXPECT_GE(res.links[0].min, -1e-9 * F);  // a buffer only pushes
  const CraneFactorRow x = row(crane_analysis(m), "phi7");
  EXPECT_NEAR(x.simulated, 1.0, 1e-9);
  EXPECT_EQ(x.standard_lo, 1.25);
}

// Claim: a lower buffer (`min`) pushes the other way: the trolley moving at −v into it at x_b
// bounces back with the same F_max = v √(c m); with its elastic crab (m2 on a spring c2) the rigid
// reference is the whole free group, M = m1 + m2 at the group's momentum speed: F_rigid = v √(c M).
TEST_P(Crane, Phi7RigidReferenceLumpsTheFreeGroup) {
  Model m = model_of(R"(
bodies:
  trolley: {type: translational, mass: 1500 kg, velocity: -1 m/s}
  crab: {type: translational, mass: 500 kg, velocity: -1 m/s}
links: {frame: {type: spring, between: [trolley, crab], stiffness: 5e6 N/m}}
buffers: {west: {body: trolley, min: -0.2 m, stiffness: 3e5 N/m}}
simulation: {t_end: 1 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
crane: {buffers: west, drive: {links: [frame], force_change: sudden}}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult res = simulate(m);
  const CraneReport r = crane_analysis(m);
  const CraneFactorRow& x = row(r, "phi7");
  const double F_rigid = 1.0 * std::sqrt(3e5 * 2000);
  EXPECT_NEAR(res.links[1].max / x.simulated, F_rigid, 1e-9 * F_rigid);
  EXPECT_EQ(row(r, "phi5").standard_hi, 2.0);
}

// Claim: φ5 of a suddenly applied drive force on an undamped two-mass drive (force P on m1, m2
// behind a spring) is the classic 2: the spring load P m2/(m1 + m2) (1 − cos ω t) peaks at twice its
// quasi-static value; the row compares it with "sudden" 1.5–2.0, margin 0.
TEST_P(Crane, Phi5SuddenDriveForceIsTwo) {
  Model m = model_of(R"(
bodies:
  motor: {type: translational, mass: 300 kg}
  bridge: {type: translational, mass: 9000 kg}
links: {shaft: {type: spring, between: [motor, bridge], stiffness: 1e6 N/m}}
loads: {P: {type: constant, body: motor, value: 5 kN}}
simulation: {t_end: 1 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
crane: {drive: {links: [shaft], force_change: sudden}}
)");
  m.simulation.integrator = GetParam();
  const CraneFactorRow x = row(crane_analysis(m), "phi5");
  // BDF's peak carries its larger error (order ≤ 5, error control on the states): 1e-8 there.
  const double tol = GetParam() == IntegratorChoice::bdf ? 1e-8 : 1e-9;
  EXPECT_NEAR(x.simulated, 2.0, tol);
  EXPECT_EQ(x.standard_lo, 1.5);
  EXPECT_NEAR(x.margin, 0.0, tol);
}

// Claim: each simulated row carries its time history (load / reference on the output grid), whose
// largest value is the simulated φ2 up to the grid (the peak itself is located between output
// points), and crane_figures draws it with the standard's value as a dashed line.
TEST(CraneOutput, HistoryAndFigure) {
  const CraneReport r = crane_analysis(model_of(with_drive_class("HD1")));
  const CraneFactorRow& x = row(r, "phi2");
  ASSERT_EQ(x.t.size(), x.history.size());
  ASSERT_FALSE(x.t.empty());
  const double top = *std::max_element(x.history.begin(), x.history.end());
  EXPECT_LE(top, x.simulated + 1e-12);
  EXPECT_GT(top, x.simulated - 1e-3);
  const auto figs = crane_figures(r);
  ASSERT_EQ(figs.size(), 1u);
  EXPECT_EQ(figs[0].id, "crane_phi2_0");
  ASSERT_EQ(figs[0].ref_lines.size(), 1u);
  EXPECT_EQ(figs[0].ref_lines[0].value, x.standard_hi);
  EXPECT_EQ(figs[0].series[0].y, x.history);
}

// Claim: the φ2(vh) figure draws the sweep's simulated points (the rigid drive's closed form
// 1 + vh ω / g, ω = √(c/m)) beside the standard's line 1.10 + 0.34 vh of HC2/HD1 (EN 13001-2
// Tables 2 and 3, crane-standards.md), both against vh; an empty sweep is refused.
TEST(CraneOutput, Phi2SweepFigureDrawsBothLines) {
  const Model m = model_of(with_drive_class("HD1"));
  const std::vector<double> speeds = {0.1, 0.3, 0.5};
  const plot::Figure f = phi2_sweep_figure(phi2_sweep(m, speeds));
  EXPECT_EQ(f.id, "crane_phi2_sweep");
  ASSERT_EQ(f.series.size(), 2u);
  const double w = std::sqrt(1e6 / 1000.0);
  for (const auto& s : f.series) {
    EXPECT_EQ(s.x, speeds);
    ASSERT_EQ(s.y.size(), speeds.size());
  }
  for (size_t k = 0; k < speeds.size(); ++k) {
    EXPECT_NEAR(f.series[0].y[k], 1 + speeds[k] * w / 9.81, 1e-9) << speeds[k];
    EXPECT_DOUBLE_EQ(f.series[1].y[k], 1.10 + 0.34 * speeds[k]) << speeds[k];
  }
  EXPECT_FALSE(f.series[0].dashed);
  EXPECT_TRUE(f.series[1].dashed);
  EXPECT_THROW(phi2_sweep_figure({}), std::invalid_argument);
}

// Claim: the table's three forms carry the same rows: JSON (NaN → null), CSV (header + one line per
// row), terminal table (one line per row plus header, rule and notes).
TEST(CraneOutput, JsonCsvAndTableAgree) {
  CraneReport r;
  r.model = "m";
  auto add = [&](const char* factor, const char* name, double sim, double lo, double hi, const char* clause,
                 double margin, const char* note) {
    CraneFactorRow x;
    x.factor = factor, x.case_name = name, x.simulated = sim, x.standard_lo = lo, x.standard_hi = hi;
    x.clause = clause, x.margin = margin, x.note = note;
    r.rows.push_back(x);
  };
  add("phi2", "a, \"b\"", 1.25, 1.27, 1.27, "EN 13001-2", 0.02, "n");
  add("phi5", "c", std::nan(""), 1.0, 1.5, "EN 13001-2 phi5", std::nan(""), "");
  const auto j = crane_json(r);
  EXPECT_EQ(j["rows"][0]["simulated"].get<double>(), 1.25);
  EXPECT_TRUE(j["rows"][1]["simulated"].is_null());
  const std::string csv = crane_csv(r);
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "factor,case,simulated,standard_lo,standard_hi,clause,margin,note");
  EXPECT_NE(csv.find("phi2,\"a, \"\"b\"\"\",1.25,1.27,1.27,"), std::string::npos) << csv;
  EXPECT_NE(csv.find("phi5,\"c\",,1,1.5,"), std::string::npos) << csv;
  const std::string t = crane_table(r);
  EXPECT_NE(t.find("1-1.5"), std::string::npos) << t;
}

// Claim: bad `buffers:` and `crane:` input is located and listed together: a buffer with neither
// min nor max, an unknown body, a body starting beyond its buffer; a crane section naming an unknown
// rope, a hook load without weight, a buffer list naming a link that is no buffer, HD2 without
// its creep speed.
TEST(CraneInput, ErrorsAreLocatedAndListedTogether) {
  try {
    model_of(R"(
bodies:
  a: {type: translational, mass: 1, position: 1 m}
  load: {type: translational, mass: 1}
links: {s: {type: spring, between: [a, load], stiffness: 1}}
buffers:
  none: {body: a, stiffness: 1e5 N/m}
  lost: {body: z, max: 1 m, stiffness: 1e5 N/m}
  behind: {body: a, max: 0.5 m, stiffness: 1e5 N/m}
crane:
  drive_class: HD2
  load: load
  rope: hoist
  buffers: [s]
)");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string s = e.what();
    EXPECT_NE(s.find("crane.yaml:7:"), std::string::npos) << s;
    EXPECT_NE(s.find("give one of 'min'"), std::string::npos) << s;
    EXPECT_NE(s.find("unknown body 'z'"), std::string::npos) << s;
    EXPECT_NE(s.find("lies beyond the buffer"), std::string::npos) << s;
    EXPECT_NE(s.find("give 'creep_speed'"), std::string::npos) << s;
    EXPECT_NE(s.find("give it 'vertical: up'"), std::string::npos) << s;
    EXPECT_NE(s.find("unknown link 'hoist'"), std::string::npos) << s;
    EXPECT_NE(s.find("'s' is not a buffer"), std::string::npos) << s;
    EXPECT_NE(s.find("crane.yaml:14:"), std::string::npos) << s;
  }
}

// Claim: the φ2 case refuses a load that does not rest on the ground, and a model without a
// `crane:` section has no crane analysis — located input errors.
TEST(CraneInput, CaseErrors) {
  Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies:
  drive: {type: translational, mass: 1e3 kg}
  load: {type: translational, mass: 1000 kg, vertical: up}
links: {rope: {type: rope, between: [drive, load], stiffness: 1e6 N/m, slack: 10 mm}}
crane: {hoist_speed: 0.5 m/s, load: load, rope: rope}
)");
  try {
    (void)crane_analysis(m);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("crane.yaml:5:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("give it a lower stop"), std::string::npos) << e.what();
  }
  EXPECT_THROW(crane_analysis(model_of("bodies: {a: {inertia: 1}}\n")), InputError);
}

// Claim (`--drive-classes`): one φ2 row per class, in the order asked. The rigid drive of kHoist
// lifts the load with φ2 = 1 + vh ω/g, ω = √(c/m) (to 1e-9), at the class's characteristic speed:
// HD1 vh,max = 0.5, HD2 and HD3 the creep speed 0.1, HD4 0.5 vh,max = 0.25 m/s; HD5 starts from zero
// speed with the model's own drive (here one at rest: Crane.PrescribedDriveHoistsInHD1AndItsOwnRampInHD5
// has one that starts). The standard's value is φ2,min + β2 vh with HC2's β2 = 0.34 s/m and
// φ2,min = 1.10 for HD1, HD2, HD4 and 1.05 for HD3, HD5 (crane-standards.md, the φ2 table).
TEST(CraneDriveClasses, Phi2InEveryDriveClassMatchesTheClosedFormAndTheTable) {
  const Model m = model_of(with_drive_class("HD1"));
  const CraneReport r = crane_analysis(m, {1, 2, 3, 4});
  ASSERT_EQ(r.rows.size(), 4u);
  const double w = std::sqrt(1e6 / 1000.0), g = 9.81;
  const double vh[] = {0.5, 0.1, 0.1, 0.25};
  const double phi2_min[] = {1.10, 1.10, 1.05, 1.10};
  for (int k = 0; k < 4; ++k) {
    const CraneFactorRow& x = r.rows[static_cast<size_t>(k)];
    EXPECT_EQ(x.factor, "phi2");
    EXPECT_NE(x.case_name.find("HD" + std::to_string(k + 1)), std::string::npos) << x.case_name;
    EXPECT_NEAR(x.standard_lo, phi2_min[k] + 0.34 * vh[k], 1e-12) << "HD" << k + 1;
    const double expected = 1.0 + vh[k] * w / g;
    EXPECT_NEAR(x.simulated, expected, 1e-9 * expected) << "HD" << k + 1;
  }
  EXPECT_THROW(crane_analysis(m, {6}), std::invalid_argument);
}

// Claim: a class that hoists at the creep speed without `creep_speed` in the section gives a row
// that says so instead of a simulation at speed 0.
TEST(CraneDriveClasses, CreepSpeedClassWithoutCreepSpeedSaysSo) {
  std::string text = with_drive_class("HD1");
  text.replace(text.find(", creep_speed: 0.1 m/s"), std::string(", creep_speed: 0.1 m/s").size(), "");
  const Model m = model_of(text);
  const CraneReport r = crane_analysis(m, {2});
  ASSERT_EQ(r.rows.size(), 1u);
  EXPECT_TRUE(std::isnan(r.rows[0].simulated));
  EXPECT_NE(r.rows[0].note.find("creep_speed"), std::string::npos) << r.rows[0].note;
}

// Claim (issue 27): the φ2 case runs the hoist drive through a lossy gearbox as through an ideal one:
// the gear keeps its ratio v_a = i v_b in every mode, so the whole group — motor, gearbox, drum —
// starts at the class's speed: the motor at ω = vh · i_rope · i_gear. A rigid drive (1e15 kg·m² on
// both sides of the gear) then gives the closed form φ2 = 1 + vh ω/g, ω = √(c/m), in each class's
// row at its own speed (HD1 vh,max 0.5 m/s, HD2 the creep speed 0.1 m/s), beside φ2,min + β2 vh.
// (Before, the motor's side stayed at rest: the rows did not run at the class's speed.)
TEST_P(Crane, Phi2ThroughALossyGearboxRunsAtTheClassSpeed) {
  Model m = model_of(R"(
gravity: 9.81 m/s^2
bodies:
  motor: {inertia: 1e15 kg*m^2}
  drum: {inertia: 1e15 kg*m^2}
  load: {type: translational, mass: 1000 kg, vertical: up}
links:
  gearbox: {type: lossy-gear, between: [motor, drum], ratio: 10, efficiency: 0.9}
  rope: {type: rope, between: [drum, load], ratio: 4 rad/m, stiffness: 1e6 N/m, slack: 10 mm}
stops: {ground: {body: load, min: 0 m}}
simulation: {t_end: 0.5 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
crane: {hoisting_class: HC2, drive_class: HD1, hoist_speed: 0.5 m/s, creep_speed: 0.1 m/s, load: load, rope: rope}
)");
  m.simulation.integrator = GetParam();
  const Model c = phi2_case_model(m, 0.1);
  EXPECT_NEAR(c.bodies[static_cast<size_t>(c.body_index("motor"))].v0, 0.1 * 4 * 10, 1e-12);
  EXPECT_NEAR(c.bodies[static_cast<size_t>(c.body_index("drum"))].v0, 0.1 * 4, 1e-12);
  const CraneReport r = crane_analysis(m, {1, 2});
  ASSERT_EQ(r.rows.size(), 2u);
  const double w = std::sqrt(1e6 / 1000.0), g = 9.81;
  const double vh[] = {0.5, 0.1};
  for (size_t k = 0; k < 2; ++k) {
    const double expected = 1.0 + vh[k] * w / g;
    EXPECT_NEAR(r.rows[k].simulated, expected, 1e-9 * expected) << "HD" << k + 1;
    EXPECT_NEAR(r.rows[k].standard_lo, 1.10 + 0.34 * vh[k], 1e-12) << "HD" << k + 1;
  }
}

// Claim: `machdyn crane --drive-classes` prints one φ2 line per class and rejects an unknown class
// with a non-zero exit naming the option.
TEST(CraneDriveClasses, CliOption) {
  const std::string path = test::write_temp("classes.yaml", with_drive_class("HD1"));
  const auto ok = test::run_cli("crane '" + path + "' --drive-classes HD1,HD4 -o classes_out");
  ASSERT_EQ(ok.exit_code, 0) << ok.err;
  EXPECT_NE(ok.out.find("HC2/HD1"), std::string::npos) << ok.out;
  EXPECT_NE(ok.out.find("HC2/HD4"), std::string::npos) << ok.out;
  const auto bad = test::run_cli("crane '" + path + "' --drive-classes HD7 -o classes_bad");
  EXPECT_NE(bad.exit_code, 0);
  EXPECT_NE(bad.err.find("--drive-classes"), std::string::npos) << bad.err;
}

// ---- issue 32: the numbers checked, the drives a crane uses, the fields of crane.json ----

std::string with_t_end(const std::string& yaml, const std::string& t_end) {
  std::string s = yaml;
  s.replace(s.find("t_end: 0.5 s"), std::string("t_end: 0.5 s").size(), "t_end: " + t_end);
  return s;
}

// Claim: a φ2 case whose run ends before the load leaves the ground is an error, not a factor. With
// kHoist (slack 10 mm, vh = 0.5 m/s, c = 1e6 N/m, m g = 9810 N) the rope tightens at 20 ms and
// carries m g at 20 + 19.62 = 39.62 ms: a run of 30 ms never lifts the load — a located input error
// that names the weight; so is HD5 with a drive that never moves (the model's own, at rest), and a
// sweep point whose run ends before its lift-off.
TEST(CraneChecks, Phi2NeverReachedIsAnError) {
  try {
    (void)crane_analysis(model_of(with_t_end(with_drive_class("HD1"), "0.03 s")));
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string s = e.what();
    EXPECT_NE(s.find("crane.yaml:5:"), std::string::npos) << s;  // the load
    EXPECT_NE(s.find("does not lift the load 'load'"), std::string::npos) << s;
    EXPECT_NE(s.find("9810"), std::string::npos) << s;
  }
  EXPECT_THROW((void)crane_analysis(model_of(with_drive_class("HD5"))), InputError);
  // The same for a point of the φ2 sweep (`--phi2-speeds`): 0.1 m/s lifts the load only at 0.198 s.
  EXPECT_THROW((void)phi2_sweep(model_of(with_t_end(with_drive_class("HD1"), "0.15 s")), {0.5, 0.1}), InputError);
}

// Claim: a φ2 extreme at the end of the run gets a warning and keeps its number: with t_end = 60 ms
// the load lifts at t_l = 39.62 ms and the rope force m g + vh √(c m) sin ω(t − t_l) still rises at
// t_end (its peak is at t_l + π/(2ω) = 89.3 ms), so the row's value is that force at t_end over m g;
// the full run's row has no warning and its fields are the closed form's numbers: extreme
// m g + vh √(c m) at t_l + π/(2ω), reference m g, vh 0.5 m/s.
TEST(CraneChecks, ExtremeAtTheEndWarnsAndFieldsCarryTheNumbers) {
  const double g = 9.81, mass = 1000, c = 1e6, vh = 0.5, w = std::sqrt(c / mass);
  const double t_l = 0.01 / vh + mass * g / (c * vh);
  const CraneFactorRow x = row(crane_analysis(model_of(with_t_end(with_drive_class("HD1"), "0.06 s"))), "phi2");
  const double F_end = mass * g + vh * std::sqrt(c * mass) * std::sin(w * (0.06 - t_l));
  EXPECT_NEAR(x.simulated, F_end / (mass * g), 1e-9);
  EXPECT_NEAR(x.t_extreme, 0.06, 1e-12);
  EXPECT_NE(x.warning.find("end of the run"), std::string::npos) << x.warning;
  const CraneFactorRow y = row(crane_analysis(model_of(with_drive_class("HD1"))), "phi2");
  EXPECT_TRUE(y.warning.empty()) << y.warning;
  const double F_max = mass * g + vh * std::sqrt(c * mass);
  EXPECT_NEAR(y.extreme, F_max, 1e-9 * F_max);
  EXPECT_NEAR(y.t_extreme, t_l + std::numbers::pi / (2 * w), 1e-6);
  EXPECT_DOUBLE_EQ(y.reference, mass * g);
  EXPECT_DOUBLE_EQ(y.vh, vh);
  const auto j = crane_json(CraneReport{"m", "", {y}});
  EXPECT_NEAR(j["rows"][0]["extreme"].get<double>(), F_max, 1e-9 * F_max);
  EXPECT_DOUBLE_EQ(j["rows"][0]["reference"].get<double>(), mass * g);
  EXPECT_DOUBLE_EQ(j["rows"][0]["vh_m_s"].get<double>(), vh);
  EXPECT_TRUE(j["rows"][0]["xi_b"].is_null());
  EXPECT_TRUE(j["rows"][0]["warning"].is_null());
}

// Claim: a creep speed above the hoisting speed (80 against 8 m/min) is a located input error (said once
// as "crane: …", the section's prefix, not "crane: crane: …"); HD2
// without a creep speed (`--drive-classes HD2` on a file without one) gives neither a simulated nor a
// standard φ2 (φ2,min + β2 vh,CS needs vh,CS): both NaN, the note says why.
TEST(CraneChecks, CreepSpeedChecks) {
  std::string text = with_drive_class("HD2");
  text.replace(text.find("creep_speed: 0.1 m/s"), std::string("creep_speed: 0.1 m/s").size(), "creep_speed: 80 m/min");
  text.replace(text.find("hoist_speed: 0.5 m/s"), std::string("hoist_speed: 0.5 m/s").size(), "hoist_speed: 8 m/min");
  try {
    (void)model_of(text);
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("crane.yaml:10:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("error: crane: the creep speed 1.33333 m/s exceeds"), std::string::npos) << e.what();
  }
  std::string none = with_drive_class("HD1");
  none.replace(none.find(", creep_speed: 0.1 m/s"), std::string(", creep_speed: 0.1 m/s").size(), "");
  const CraneReport r = crane_analysis(model_of(none), {2, 3});
  for (const auto& x : r.rows) {
    EXPECT_TRUE(std::isnan(x.simulated));
    EXPECT_TRUE(std::isnan(x.standard_lo)) << x.case_name;
    EXPECT_NE(x.note.find("creep_speed"), std::string::npos) << x.note;
  }
}

// Claim: a load case's `crane:` is checked with the model: a bad field value in it (HD9) is located
// at the case's line, and `crane:` neither a map nor `none` is refused with what it expects.
TEST(CraneChecks, CaseCraneSectionIsChecked) {
  const std::string base = with_drive_class("HD1");
  try {
    (void)model_of(base + "cases:\n  slow:\n    crane: {drive_class: HD9}\n");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("crane.yaml:13:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("HD9"), std::string::npos) << e.what();
  }
  try {
    (void)model_of(base + "cases:\n  odd:\n    crane: [HD2]\n");
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("'crane' expected a map of fields"), std::string::npos) << e.what();
  }
}

// A rigid drive with prescribed motion lifting the kHoist load.
const char* kPrescribedHoist = R"(
gravity: 9.81 m/s^2
bodies:
  drive: {type: translational, mass: 100 kg, motion: {speed: MOTION}}
  load: {type: translational, mass: 1000 kg, vertical: up}
links:
  rope: {type: rope, between: [drive, load], stiffness: 1e6 N/m, slack: 10 mm}
stops: {ground: {body: load, min: 0 m}}
simulation: {t_end: 0.45 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
crane: {hoisting_class: HC2, drive_class: HD1, hoist_speed: 0.5 m/s, load: load, rope: rope}
)";

std::string prescribed(const std::string& motion) {
  std::string s = kPrescribedHoist;
  s.replace(s.find("MOTION"), 6, motion);
  return s;
}

// Claim: a prescribed-speed hoist drive (`motion: {speed: ...}`, the standard's rigid drive) is the
// φ2 case's hoist drive: in HD1 it runs at vh,max = 0.5 m/s from the start, whatever its own signal
// (here a ramp from rest), so φ2 = 1 + vh ω/g exactly. In HD5 the model's own drive runs: the ramp
// accelerates at a = 1 m/s² from rest (0.5 m/s at 0.5 s, after the run's 0.45 s); the load lifts at
// ½ a t_l² = s0 + m g/c, and the stretch then obeys ë + ω² e = a + g from e = m g/c, ė = a t_l:
// F_max/(m g) = 1 + a/g + (a/g) √(1 + (ω t_l)²) (reached at ≈ 0.30 s, inside the ramp).
TEST_P(Crane, PrescribedDriveHoistsInHD1AndItsOwnRampInHD5) {
  Model m = model_of(prescribed("{type: ramp, value: 0.5 m/s, end: 0.5 s}"));
  m.simulation.integrator = GetParam();
  const double g = 9.81, mass = 1000, c = 1e6, w = std::sqrt(c / mass), a = 1.0, s0 = 0.01;
  const CraneReport r = crane_analysis(m, {1, 5});
  ASSERT_EQ(r.rows.size(), 2u);
  EXPECT_NEAR(r.rows[0].simulated, 1 + 0.5 * w / g, 1e-9);
  const double t_l = std::sqrt(2 * (s0 + mass * g / c) / a);
  const double phi2_hd5 = 1 + a / g + (a / g) * std::sqrt(1 + (w * t_l) * (w * t_l));
  EXPECT_NEAR(r.rows[1].simulated, phi2_hd5, 1e-8);
  EXPECT_DOUBLE_EQ(r.rows[1].standard_lo, 1.05);
  EXPECT_TRUE(r.rows[1].warning.empty()) << r.rows[1].warning;
}

// Claim (φ7 at the speed of contact): a trolley (2000 kg at v0 = 1.2 m/s) slowed by a constant
// rolling resistance F = 1 kN reaches the buffer 0.3 m ahead at v_c = √(v0² − 2 F s/m) = √1.14 m/s
// at t_c = (v0 − v_c) m/F; the rigid-body reference is the same mass at v_c into the buffer,
// F_rigid = v_c √(c m), not v0 √(c m). The row's fields carry v_c, t_c, F_rigid, ξb = 1/2 of the
// linear buffer and the stroke (its largest compression on the output grid).
TEST_P(Crane, Phi7ReferenceAtTheSpeedOfContact) {
  Model m = model_of(R"(
bodies: {trolley: {type: translational, mass: 2000 kg, velocity: 1.2 m/s}}
contacts: {rolling: {between: [trolley, ground], static: 1 kN, kinetic: 1 kN}}
buffers: {east: {body: trolley, max: 0.3 m, stiffness: 2e5 N/m}}
simulation: {t_end: 1 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
crane: {buffers: [east]}
)");
  m.simulation.integrator = GetParam();
  const double mass = 2000, v0 = 1.2, F = 1000, s = 0.3, c = 2e5;
  const double v_c = std::sqrt(v0 * v0 - 2 * F * s / mass), t_c = (v0 - v_c) * mass / F;
  const CraneFactorRow x = row(crane_analysis(m), "phi7");
  EXPECT_NEAR(x.contact_speed, v_c, 1e-9 * v_c);
  EXPECT_NEAR(x.t_contact, t_c, 1e-9);
  EXPECT_NEAR(x.reference, v_c * std::sqrt(c * mass), 1e-9 * v_c * std::sqrt(c * mass));
  EXPECT_NEAR(x.simulated, x.extreme / x.reference, 1e-15);
  EXPECT_DOUBLE_EQ(x.xi_b, 0.5);
  // The largest stroke: below the frictionless v_c/ω (friction helps stop it), on the grid.
  EXPECT_GT(x.stroke, 0.0);
  EXPECT_LT(x.stroke, v_c / std::sqrt(c / mass));
  EXPECT_NE(x.note.find("trolley 2000"), std::string::npos) << x.note;
}

// Claim: a φ7 case whose run never reaches the buffer is an error (its force stays 0), located at
// the buffer.
TEST(CraneChecks, Phi7NeverReachedIsAnError) {
  try {
    (void)crane_analysis(model_of(R"(
bodies: {trolley: {type: translational, mass: 2000 kg, velocity: 0.1 m/s}}
buffers: {east: {body: trolley, max: 0.3 m, stiffness: 2e5 N/m}}
simulation: {t_end: 1 s, dt_out: 1 ms}
crane: {buffers: [east]}
)"));
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("crane.yaml:3:"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("does not reach the buffer 'east'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace machdyn
