// The pendulum modes beside the drive line's (issue 31, analysis/mode_kinds.hpp, docs/sway.md
// "Pendulum modes"): each natural mode of a model with a spatial rope named pendulum, rope stretch or
// drive line by the loads' share of its kinetic energy — the frequencies of the modes so named
// against closed forms (the free trolley's ω² = (g/ℓ)(1 + m/M), the stretch c/m, the compound
// pendulum's roots), the examples' counts, and where a user reads them: `machdyn modes` (text and
// JSON), the report's table and Python (python/tests/test_sway.py).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>
#include <fmt/format.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "machdyn/analysis/hanging_rest.hpp"
#include "machdyn/analysis/linear_analysis.hpp"
#include "machdyn/analysis/mode_kinds.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/analysis/topology.hpp"
#include "machdyn/elements/linearize.hpp"
#include "machdyn/io/linear_results.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/support.hpp"
#include "support/timed_model.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::num;
constexpr double kG = 9.80665;

/// The modes of m's initial topology and their kinds.
struct Named {
  TopologyModes t;
  std::vector<ModeKind> kind;
  [[nodiscard]] std::vector<double> omega2_of(ModeKind k) const {
    std::vector<double> w;
    for (size_t i = 0; i < kind.size(); ++i)
      if (kind[i] == k) w.push_back(t.modes.omega(static_cast<Eigen::Index>(i)) * t.modes.omega(static_cast<Eigen::Index>(i)));
    return w;
  }
};
Named named(const Model& m) {
  Named n;
  n.t = analyse_topology(m, initial_topology(m));
  n.kind = mode_kinds(m, n.t.modes.shapes);
  return n;
}

// Claim: the example trolley-sway.yaml (40 t on a 12 m rope of 4 falls, EA 1.2e8 N: c = n EA/L0,
// hanging length ℓ = L0 + m g/c, below an 8 t trolley) names exactly one pendulum mode and one
// rope-stretch mode, at the closed forms:
// - its PI speed drive is, in the linear model, a spring k = K_p/T_i to the ground on the trolley
//   (docs/model-files.md, speed drive); the trolley X and the load's x then have
//   M = diag(M, m), K = [[k + m g/ℓ, −m g/ℓ], [−m g/ℓ, m g/ℓ]] (the pendulum's geometric stiffness
//   m g/ℓ between them), det(K − λ M) = 0:  M m λ² − ((k + m g/ℓ) m + (m g/ℓ) M) λ + k m g/ℓ = 0 —
//   the lower root is the pendulum mode, the upper one the drive line's (the load nearly still);
// - with the drive's integral time 1e12 s (k → 0) the trolley is free: ω² = (g/ℓ)(1 + m/M), the
//   centre of mass at rest (M X = −m x), so the load carries M/(M + m) of the kinetic energy;
// - the stretch mode ω² = c/m (the load's vertical motion against the rope; the trolley does not
//   move vertically). Each within 1e-9; the shares sum to 1.
TEST(ModeKinds, TrolleySwayPendulumFrequency) {
  const double M = 8000, ml = 40000, L0 = 12, c = 4 * 1.2e8 / L0, l = L0 + ml * kG / c, k = 4e5 / 0.5, p = ml * kG / l;
  const double A = M * ml, B = (k + p) * ml + p * M, C = k * p;
  const double lam[2] = {(B - std::sqrt(B * B - 4 * A * C)) / (2 * A), (B + std::sqrt(B * B - 4 * A * C)) / (2 * A)};
  const Named n = named(load_model(test::example("crane/trolley-sway.yaml")));
  ASSERT_EQ(n.omega2_of(ModeKind::pendulum).size(), 1u);
  ASSERT_EQ(n.omega2_of(ModeKind::drive_line).size(), 1u);
  ASSERT_EQ(n.omega2_of(ModeKind::rope_stretch).size(), 1u);
  EXPECT_NEAR(n.omega2_of(ModeKind::pendulum)[0], lam[0], 1e-9 * lam[0]);
  EXPECT_NEAR(n.omega2_of(ModeKind::drive_line)[0], lam[1], 1e-9 * lam[1]);
  EXPECT_NEAR(n.omega2_of(ModeKind::rope_stretch)[0], c / ml, 1e-9 * c / ml);

  const Model free = load_model(test::example("crane/trolley-sway.yaml"), {"drives.travel.integral_time=1e12 s"});
  const Named f = named(free);
  const std::vector<double> pend = f.omega2_of(ModeKind::pendulum), stretch = f.omega2_of(ModeKind::rope_stretch);
  ASSERT_EQ(pend.size(), 1u);
  ASSERT_EQ(stretch.size(), 1u);
  EXPECT_NEAR(pend[0], kG / l * (1 + ml / M), 1e-9 * kG / l * (1 + ml / M));
  EXPECT_NEAR(stretch[0], c / ml, 1e-9 * c / ml);
  const std::vector<ModeShares> s = mode_shares(free, mass_diagonal(free), f.t.modes.shapes);
  for (size_t i = 0; i < s.size(); ++i) {
    EXPECT_NEAR(s[i].sway + s[i].stretch + s[i].drive, 1.0, 1e-12);
    if (f.kind[i] == ModeKind::pendulum) {
      EXPECT_NEAR(s[i].sway, M / (M + ml), 1e-6);
      EXPECT_NEAR(s[i].stretch, 0.0, 1e-9);
    }
  }
}

// Claim: every crane example with a swinging load names its load's modes as its geometry has them —
// one pendulum mode per horizontal direction the load swings in (the trolley: x; bridge and trolley:
// x and y; the slewing jib: radial and tangential) and one stretch mode of its rope — in every
// topology of the linear analysis (the trolley with its drive line: wheels stuck or slipping,
// buffers open or closed), the rest named the drive line's.
TEST(ModeKinds, ExamplesNameTheirLoadModes) {
  struct Case {
    const char* file;
    size_t pendulum;
  };
  for (const Case& e : {Case{"crane/trolley-sway.yaml", 1}, Case{"crane/trolley-sway-drive.yaml", 1},
                        Case{"crane/bridge-trolley-sway.yaml", 2}, Case{"crane/slewing-jib-sway.yaml", 2}}) {
    const Model m = load_model(test::example(e.file));
    for (const Topology& topo : all_topologies(m)) {
      const TopologyModes t = analyse_topology(m, topo);
      const std::vector<ModeKind> kind = mode_kinds(m, t.modes.shapes);
      ASSERT_EQ(kind.size(), static_cast<size_t>(t.modes.omega.size()));
      EXPECT_EQ(std::count(kind.begin(), kind.end(), ModeKind::pendulum), static_cast<long>(e.pendulum)) << e.file << " " << t.label;
      EXPECT_EQ(std::count(kind.begin(), kind.end(), ModeKind::rope_stretch), 1) << e.file << " " << t.label;
    }
  }
}

// Claim: the rigid load's compound pendulum (a body m, J on one rope attached a above its centre,
// from a fixed point) has its two pendulum modes named pendulum at the roots of
// L J λ² − g (m a² + J + m a L) λ + m g² a = 0 (tests/elements/rigid_load_test.cpp derives them),
// and its stretch mode named rope stretch at c/m (z is decoupled at ψ = 0); a spreader on two
// parallel ropes at a = (±3 m, 0.4 m) has its sway named pendulum, its heave and its roll (ψ moving
// the rope points vertically: a_z²/(a_z² + a_h²) = 1.7 % sway) named rope stretch: the heave at
// ω² = 2c/m, the roll at 2 c a_h²/J within the geometric terms' share (F/ℓ against c: 1e-3).
TEST(ModeKinds, RigidLoadsCompoundPendulumAndSpreader) {
  const double m = 1000, J = 2000, a = 1.0, L0 = 6, EA = 1e10, c = EA / L0, l = L0 + m * kG / c, h = l + a;
  const Model cp = test::model_text("bodies:\n  beam: {type: rigid-load, mass: " + num(m) + " kg, inertia: " + num(J) +
                                    " kg*m^2}\nlinks:\n  rope: {type: spatial-rope, load: beam, attach: [0 m, " + num(a) +
                                    " m], length: " + num(L0) + " m, EA: " + num(EA) + " N, height: " + num(h) + " m}\n");
  const Named n = named(cp);
  const double A = l * J, B = kG * (m * a * a + J + m * a * l), C = m * kG * kG * a;
  const double lam[2] = {(B - std::sqrt(B * B - 4 * A * C)) / (2 * A), (B + std::sqrt(B * B - 4 * A * C)) / (2 * A)};
  std::vector<double> pend = n.omega2_of(ModeKind::pendulum);
  ASSERT_EQ(pend.size(), 2u);
  std::sort(pend.begin(), pend.end());
  for (int k = 0; k < 2; ++k) EXPECT_NEAR(pend[static_cast<size_t>(k)], lam[k], 1e-8 * lam[k]) << k;
  const std::vector<double> st = n.omega2_of(ModeKind::rope_stretch);
  ASSERT_EQ(st.size(), 1u);
  EXPECT_NEAR(st[0], c / m, 1e-9 * c / m);

  // The spreader (20 t, J = 9e4 kg m², ropes of 8 m, EA 2e9 N), its centre at z = 0 hanging at rest.
  const double ms = 20000, Js = 9e4, ah = 3, az = 0.4, Ls = 8, EAs = 2e9, cs = EAs / Ls, hs = az + Ls + ms * kG / 2 / cs;
  std::string rope = ", length: 8 m, EA: 2e9 N, height: " + num(hs) + " m}\n";
  const Model sp = test::model_text("bodies:\n  trolley: {type: translational, mass: 10 t}\n"
                                    "  spreader: {type: rigid-load, mass: 20 t, inertia: 9e4 kg*m^2}\nlinks:\n"
                                    "  left: {type: spatial-rope, load: spreader, trolley: trolley, attach: [-3 m, 0.4 m], offset: -3 m" +
                                    rope + "  right: {type: spatial-rope, load: spreader, trolley: trolley, attach: [3 m, 0.4 m], offset: 3 m" + rope);
  const Named s = named(sp);
  ASSERT_EQ(s.omega2_of(ModeKind::pendulum).size(), 1u);
  std::vector<double> st2 = s.omega2_of(ModeKind::rope_stretch);
  ASSERT_EQ(st2.size(), 2u);
  std::sort(st2.begin(), st2.end());
  const double heave = 2 * cs / ms, roll = 2 * cs * ah * ah / Js;
  const double lo = std::min(heave, roll), hi = std::max(heave, roll);
  EXPECT_NEAR(st2[0], lo, 2e-3 * lo);
  EXPECT_NEAR(st2[1], hi, 2e-3 * hi);
}

// Claim: a model without a spatial rope has drive-line modes only and its `modes --json` keeps the
// fields it had (no `kinds`); the trolley example's JSON lists each shape's kind and energy shares,
// and `kinds` at the top level equals the first topology's.
TEST(ModeKinds, JsonKindsOnlyWithASwingingLoad) {
  const Model hoist = load_model(test::example("hoist-3mass.yaml"));
  const Named h = named(hoist);
  for (ModeKind k : h.kind) EXPECT_EQ(k, ModeKind::drive_line);
  EXPECT_FALSE(linear_modes_json(hoist, {h.t}).contains("kinds"));
  const Model m = load_model(test::example("crane/trolley-sway.yaml"));
  const Named n = named(m);
  const nlohmann::json j = linear_modes_json(m, {n.t});
  ASSERT_TRUE(j.contains("kinds"));
  ASSERT_EQ(j["kinds"].size(), n.kind.size());
  for (size_t k = 0; k < n.kind.size(); ++k) {
    EXPECT_EQ(j["kinds"][k], to_string(n.kind[k]));
    EXPECT_EQ(j["shapes"][k]["kind"], to_string(n.kind[k]));
    const auto& e = j["shapes"][k]["energy_shares"];
    EXPECT_NEAR(e["sway"].get<double>() + e["stretch"].get<double>() + e["drive"].get<double>(), 1.0, 1e-12);
  }
}

// Claim: `machdyn modes` prints the kind of each mode of the trolley example (a `kind` column with
// one `pendulum` and one `rope stretch` row) and none for the hoist (its table as before); the
// report's table of natural frequencies marks the pendulum mode's frequency (the lower root of the
// trolley-on-its-drive pair, TrolleySwayPendulumFrequency) to its five digits, `(pendulum)`.
TEST(ModeKinds, CliAndReportShowThePendulumMode) {
  const auto r = test::run_cli("modes '" + test::example("crane/trolley-sway.yaml") + "'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_NE(r.out.find(" kind "), std::string::npos) << r.out;
  size_t pendulum = 0, stretch = 0;
  for (const std::string& line : test::lines_of(r.out)) pendulum += line.find(" pendulum ") != std::string::npos,
                                                         stretch += line.find(" rope stretch ") != std::string::npos;
  EXPECT_EQ(pendulum, 1u) << r.out;
  EXPECT_EQ(stretch, 1u) << r.out;
  const auto h = test::run_cli("modes '" + test::example("hoist-3mass.yaml") + "'");
  ASSERT_EQ(h.exit_code, 0) << h.err;
  EXPECT_EQ(h.out.find(" kind "), std::string::npos);
  EXPECT_EQ(h.out.find("drive line"), std::string::npos);

  const auto dir = test::temp_dir() / "mode-kinds-report";
  const auto rep = test::run_cli("report '" + test::example("crane/trolley-sway.yaml") + "' --quiet -o '" +
                                 (dir / "report.html").string() + "'");
  ASSERT_EQ(rep.exit_code, 0) << rep.err;
  const std::string page = test::slurp(dir / "report.html");
  const double M = 8000, ml = 40000, L0 = 12, c = 4 * 1.2e8 / L0, l = L0 + ml * kG / c, k = 4e5 / 0.5, p = ml * kG / l;
  const double A = M * ml, B = (k + p) * ml + p * M, lam = (B - std::sqrt(B * B - 4 * A * k * p)) / (2 * A);
  const std::string f = fmt::format("{:.5g} (pendulum)", std::sqrt(lam) / (2 * 3.14159265358979323846));
  EXPECT_NE(page.find(f), std::string::npos) << f;
  EXPECT_NE(page.find("(rope stretch)"), std::string::npos);
}

// A load that starts on the floor is linearized about its hanging rest in the topologies that free
// it (analysis/hanging_rest.hpp, docs/sway.md "Pendulum modes", docs/modes.md): the hanging topology
// of a floor-start variant of examples/crane/trolley-sway.yaml shows the pendulum mode of the
// hanging model at the closed forms; the topology with the floor holding keeps the linearization at
// the start; models that start hanging are linearized at their start, unchanged.

/// trolley-sway.yaml with its load at z = 0 on a floor (a lower end stop on load.z at 0 m), hung
/// from the height h (the example's own: L0 + m g/c), the drive's integral time T_i.
Model floor_variant(double h, const std::string& integral_time = "0.5 s") {
  std::string text = test::slurp(test::example("crane/trolley-sway.yaml"));
  const std::string rope_end = "sway_after: 20 s}", ti = "integral_time: 0.5 s";
  const size_t r = text.find(rope_end), i = text.find(ti);
  EXPECT_NE(r, std::string::npos);
  EXPECT_NE(i, std::string::npos);
  text.replace(r, rope_end.size(), "sway_after: 20 s, height: " + num(h) + " m}");
  text.replace(text.find(ti), ti.size(), "integral_time: " + integral_time);
  return test::model_text(text + "stops:\n  floor: {body: load.z, min: 0 m}\n");
}

/// ω² of the modes of `t` named `k`.
std::vector<double> omega2(const Model& m, const TopologyModes& t, ModeKind k) {
  const std::vector<ModeKind> kind = mode_kinds(m, t.modes.shapes);
  std::vector<double> w;
  for (size_t i = 0; i < kind.size(); ++i)
    if (kind[i] == k) w.push_back(t.modes.omega(static_cast<Eigen::Index>(i)) * t.modes.omega(static_cast<Eigen::Index>(i)));
  return w;
}

/// The lower root λ of M m λ² − ((k + p) m + p M) λ + k p = 0: a trolley M on a spring k to the ground
/// with a load m whose horizontal coordinate is tied to it by the geometric stiffness p = F/ℓ of a
/// rope of tension F and length ℓ (M = diag(M, m), K = [[k + p, −p], [−p, p]], det(K − λ M) = 0).
double pendulum_root(double M, double m, double k, double p) {
  const double A = M * m, B = (k + p) * m + p * M, C = k * p;
  return (B - std::sqrt(B * B - 4 * A * C)) / (2 * A);
}

// Claim: the load on the floor (its rope slack: h = 11.5 m below L0 = 12 m; or carrying half the
// weight: h = L0 + ½ m g/c) is linearized, where the floor does not hold it (floor=open, and
// all_topologies' floor sliding off), about its hanging rest: x under the trolley, z = h − ℓ with
// ℓ = L0 + m g/c (the rope's tension c e = m g), at rest — so that topology has one pendulum mode at
// the hanging model's frequency (trolley-sway.yaml's, within 1e-9: the same K and M), the lower root
// of the trolley-on-its-drive quadratic with p = m g/ℓ (k = K_p/T_i, as in ModeKinds'
// TrolleySwayPendulumFrequency) and, with the drive's spring removed (T_i = 1e12 s), ω² =
// (g/ℓ)(1 + m/M), and one stretch mode c/m. Where the floor holds (floor=closed) the start is kept:
// the half-weight rope's geometric stiffness p = F/h with F = ½ m g gives its pendulum root.
TEST(ModeKinds, FloorStartHangsInItsHangingTopology) {
  const double M = 8000, ml = 40000, L0 = 12, c = 4 * 1.2e8 / L0, l = L0 + ml * kG / c, k = 4e5 / 0.5;
  const Model hanging = load_model(test::example("crane/trolley-sway.yaml"));
  const TopologyModes ref = analyse_topology(hanging, initial_topology(hanging));
  for (const double h : {11.5, L0 + 0.5 * ml * kG / c}) {
    SCOPED_TRACE(h);
    const Model m = floor_variant(h);
    const Topology open = parse_topology(m, "floor=open", Location{"t", 1, 0});
    const std::vector<double> y = linearization_state(m, open);
    ASSERT_EQ(y.size(), static_cast<size_t>(2 * m.dof()));
    const auto z = static_cast<size_t>(m.body_index("load.z")), x = static_cast<size_t>(m.body_index("load.x"));
    EXPECT_NEAR(y[z], h - l, 1e-12 * l);
    EXPECT_EQ(y[x], 0.0);  // under the trolley at 0
    for (const Topology& topo : {open, parse_topology(m, "floor=sliding", Location{"t", 1, 0})}) {
      const TopologyModes t = analyse_topology(m, topo);
      ASSERT_EQ(t.modes.omega.size(), ref.modes.omega.size()) << t.label;
      for (Eigen::Index i = 0; i < t.modes.omega.size(); ++i)
        EXPECT_NEAR(t.modes.omega(i), ref.modes.omega(i), 1e-9 * ref.modes.omega(i)) << t.label << " " << i;
      const std::vector<double> pend = omega2(m, t, ModeKind::pendulum), st = omega2(m, t, ModeKind::rope_stretch);
      ASSERT_EQ(pend.size(), 1u) << t.label;
      ASSERT_EQ(st.size(), 1u) << t.label;
      const double lam = pendulum_root(M, ml, k, ml * kG / l);
      EXPECT_NEAR(pend[0], lam, 1e-9 * lam) << t.label;
      EXPECT_NEAR(st[0], c / ml, 1e-9 * c / ml) << t.label;
    }
    const Model free = floor_variant(h, "1e12 s");
    const TopologyModes f = analyse_topology(free, parse_topology(free, "floor=open", Location{"t", 1, 0}));
    const std::vector<double> pend = omega2(free, f, ModeKind::pendulum);
    ASSERT_EQ(pend.size(), 1u);
    EXPECT_NEAR(pend[0], kG / l * (1 + ml / M), 1e-9 * kG / l * (1 + ml / M));

    // The floor holding: linearized at the start (the state untouched), as linearize() there.
    const Topology held = parse_topology(m, "floor=closed", Location{"t", 1, 0});
    EXPECT_TRUE(linearization_state(m, held).empty());
    const TopologyModes t = analyse_topology(m, held);
    const UndampedModes at_start = undamped_modes(linearize(m, held));
    ASSERT_EQ(t.modes.omega.size(), at_start.omega.size());
    for (Eigen::Index i = 0; i < t.modes.omega.size(); ++i) EXPECT_EQ(t.modes.omega(i), at_start.omega(i)) << i;
  }
  // The half-weight rope held on the floor: its tension F = c (h − L0) = ½ m g at the length h, the
  // load's z held, so the horizontal pair has p = F/h: the pendulum root of the start.
  const double h = L0 + 0.5 * ml * kG / c;
  const Model m = floor_variant(h);
  const TopologyModes t = analyse_topology(m, parse_topology(m, "floor=closed", Location{"t", 1, 0}));
  const std::vector<double> pend = omega2(m, t, ModeKind::pendulum);
  ASSERT_EQ(pend.size(), 1u);
  const double lam = pendulum_root(M, ml, k, 0.5 * ml * kG / h);
  EXPECT_NEAR(pend[0], lam, 1e-8 * lam);
}

// Claim: models whose loads start hanging (every crane example with a spatial rope; a floor below a
// hanging load: the load not on it) are linearized at their start in every topology —
// linearization_state is empty, so `machdyn modes` prints them as before.
TEST(ModeKinds, LoadsThatStartHangingKeepTheirStart) {
  for (const char* file : {"crane/trolley-sway.yaml", "crane/trolley-sway-drive.yaml", "crane/bridge-trolley-sway.yaml",
                           "crane/slewing-jib-sway.yaml"}) {
    const Model m = load_model(test::example(file));
    for (const Topology& topo : all_topologies(m)) EXPECT_TRUE(linearization_state(m, topo).empty()) << file;
  }
  std::string text = test::slurp(test::example("crane/trolley-sway.yaml"));
  const Model above = test::model_text(text + "stops:\n  floor: {body: load.z, min: -1 m}\n");
  for (const Topology& topo : all_topologies(above)) EXPECT_TRUE(linearization_state(above, topo).empty());
}

// Claim: `modes --from-run` of a load hoisted off the floor (tests/elements/spatial_rope_test.cpp's
// LiftOffFromAGroundStop: 1 t at x = 0.2 m on the floor, its rope of 2 falls slack, a drum winding it
// in, below a free 3 t trolley) shows, in the run's topology after lift-off, the hanging load's
// pendulum mode at ω² = (g/ℓ)(1 + m/M), ℓ = L0 + m g/c (c = n EA/L0, the drum at its initial
// angle), within 1e-9 — on both integrators; the topology on the floor before it has none.
TEST(ModeKinds, FromRunLiftOffShowsThePendulum) {
  const double m = 1000, M = 3000, L0 = 10, c = 2 * 5e7 / L0, l = L0 + m * kG / c, w2 = kG / l * (1 + m / M);
  for (const IntegratorChoice integ : {IntegratorChoice::dopri5, IntegratorChoice::bdf}) {
    const Model md = test::timed_model(
        "bodies:\n  drum: {inertia: 50 kg*m^2}\n  trolley: {type: translational, mass: 3 t}\n"
        "  load: {type: point-mass, mass: 1 t, axes: [x, z], position: [0.2 m, 0 m]}\n"
        "links:\n  rope: {type: spatial-rope, load: load, trolley: trolley, drum: drum, drum_radius: 0.3 m, "
        "falls: 2, length: 10 m, EA: 5e7 N, height: 9.95 m, damping: 1e4 N*s/m}\n"
        "loads:\n  hoist: {type: constant, body: drum, value: 2000 N*m}\n"
        "stops:\n  ground: {body: load.z, min: 0 m}\n",
        1.0, 1e-3, integ);
    SimulateOptions o;
    o.event_driven = true;
    const std::vector<TopologyModes> list = run_topology_modes(md, simulate(md, o).hybrid, md.simulation.t_end);
    ASSERT_EQ(list.size(), 2u);
    EXPECT_TRUE(omega2(md, list[0], ModeKind::pendulum).empty()) << list[0].label;
    const std::vector<double> pend = omega2(md, list[1], ModeKind::pendulum);
    ASSERT_EQ(pend.size(), 1u) << list[1].label;
    EXPECT_NEAR(pend[0], w2, 1e-9 * w2);
  }
}

}  // namespace MACHDYN_UNITY_ID
}  // namespace machdyn
