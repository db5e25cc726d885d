// Bodies losing part of their mass during a run (`releases:`, model/model.hpp: Release) against
// closed forms, on both integrators: the hanging load released at rest, a release in the middle of a
// free oscillation, a load released while a rigid drive hoists it, a release on a body slaved by an
// ideal gear, the energy books with the released part's kinetic energy, and the located input errors.
#include <cmath>
#include <numbers>
#include <string>
#include <gtest/gtest.h>

#include "machdyn/analysis/extra_outputs.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/report.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::series;

Model model_of(const std::string& yaml) { return test::model_text(yaml, "release.yaml"); }

class Release : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, Release, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

/// The relative tolerance of a run's values against a closed form: DOPRI5 1e-9; CVODE's BDF restarts at
/// order 1 at the release and carries a larger global error at the same rtol (up to ~5e-8 here).
double tol(IntegratorChoice i) { return i == IntegratorChoice::dopri5 ? 1e-9 : 1e-7; }

/// The largest |column − f(t)| over the output rows with t > t_from.
template <class F>
double max_error_after(const SimulationResult& r, const std::string& name, double t_from, F&& f) {
  const auto& t = series(r, "t_s");
  const auto& x = series(r, name);
  double e = 0.0;
  for (size_t k = 0; k < t.size() && k < x.size(); ++k)
    if (t[k] > t_from) e = std::max(e, std::abs(x[k] - f(t[k])));
  return e;
}

// Claim: a load m hanging at rest in equilibrium on a rope of stiffness c (x up, rope force
// F = −c x) loses Δm at t_r. Before t_r nothing moves: x = x_eq = −m g/c. After it
//   (m − Δm) x'' = −c x − (m − Δm) g,  x(t_r) = x_eq, x'(t_r) = 0
//   ⇒ x(t) = x_eq' − (Δm g / c) cos ω'(t − t_r),  x_eq' = −(m − Δm) g / c,  ω' = √(c/(m − Δm)),
// so F = (m − Δm) g + Δm g cos ω'(t − t_r): its extremes are m g (held until t_r) and (m − 2Δm) g
// at t_r + π/ω' (to 1e-9 relative). The mass column drops from m to m − Δm at t_r. A release at
// t_r = 0 acts at 0⁺: the start is still the full load's equilibrium (the same extremes, t_min = π/ω').
TEST_P(Release, HangingLoadReleasedAtRestOscillatesAboutItsNewEquilibrium) {
  const double g = 9.81, m = 1000, dm = 300, c = 1e6, tr = 0.0421;
  const double w = std::sqrt(c / (m - dm));
  for (const double t_r : {tr, 0.0}) {
    Model mod = model_of(R"(
gravity: 9.81 m/s^2
bodies: {load: {type: translational, mass: 1000 kg, vertical: up}}
links: {rope: {type: rope, between: [ground, load], stiffness: 1e6 N/m}}
releases: {grab: {body: load, mass: 300 kg, time: 0.0421 s}}
simulation: {t_end: 0.3 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-13, initial: equilibrium}
)");
    mod.simulation.integrator = GetParam();
    mod.releases[0].time = t_r;
    const SimulationResult r = simulate(mod);
    const LinkSummary& s = r.links[0];
    EXPECT_NEAR(s.max, m * g, 1e-9 * m * g) << t_r;
    EXPECT_NEAR(s.min, (m - 2 * dm) * g, 1e-9 * m * g) << t_r;
    const double t_min = t_r + std::numbers::pi / w;
    EXPECT_NEAR(s.t_min, t_min, 1e-9 * t_min) << t_r;
    const double err = max_error_after(r, "load.position_m", t_r, [&](double t) {
      return -(m - dm) * g / c - dm * g / c * std::cos(w * (t - t_r));
    });
    EXPECT_LT(err, tol(GetParam()) * dm * g / c) << t_r;
    EXPECT_EQ(series(r, "load.mass_kg").back(), m - dm);
    if (t_r > 0) {
      EXPECT_EQ(test::at(r, "load.mass_kg", 0.042), m);
      EXPECT_EQ(test::at(r, "load.position_m", 0.042), -m * g / c);  // at rest before the release
    }
    int releases = 0;
    for (const ModeEvent& e : r.hybrid.events)
      if (e.kind == "release") {
        ++releases;
        EXPECT_EQ(e.t, t_r);
        EXPECT_EQ(e.element, "grab");
      }
    EXPECT_EQ(releases, 1);
  }
}

// The oscillation the next three tests release in: m = 2 kg on c = 800 N/m under g = 9.81 m/s²,
// from x0 = 0.1 m at rest, Δm = 1.5 kg released at t_r = 0.37 s.
constexpr const char* kMidOscillation = R"(
gravity: 9.81 m/s^2
bodies: {m: {type: translational, mass: 2 kg, vertical: up, position: 0.1 m}}
links: {c: {type: spring, between: [ground, m], stiffness: 800 N/m}}
releases: {part: {body: m, mass: 1.5 kg, time: 0.37 s}}
simulation: {t_end: 1 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-13}
)";

// Claim: a release in the middle of a free oscillation. A body m on a spring c to the ground under
// its weight (x up) starts at x0 at rest: x = x_eq + (x0 − x_eq) cos ωt, x_eq = −m g/c, ω = √(c/m).
// At t_r it loses Δm with x, v continuous (x_r, v_r from that form), then
//   x = x_eq' + (x_r − x_eq') cos ω'τ + (v_r/ω') sin ω'τ,  τ = t − t_r,  x_eq' = −(m − Δm) g/c,
// ω' = √(c/(m − Δm)). Every output row before and after t_r is checked against these.
TEST_P(Release, ReleaseInTheMiddleOfAFreeOscillation) {
  Model mod = model_of(kMidOscillation);
  mod.simulation.integrator = GetParam();
  const double g = 9.81, m = 2, dm = 1.5, c = 800, x0 = 0.1, tr = 0.37;
  const double w = std::sqrt(c / m), w2 = std::sqrt(c / (m - dm));
  const double xe = -m * g / c, xe2 = -(m - dm) * g / c;
  const double xr = xe + (x0 - xe) * std::cos(w * tr), vr = -(x0 - xe) * w * std::sin(w * tr);
  auto x = [&](double t) {
    if (t <= tr) return xe + (x0 - xe) * std::cos(w * t);
    const double tau = t - tr;
    return xe2 + (xr - xe2) * std::cos(w2 * tau) + vr / w2 * std::sin(w2 * tau);
  };
  const SimulationResult r = simulate(mod);
  const double amp = std::hypot(xr - xe2, vr / w2);
  EXPECT_LT(max_error_after(r, "m.position_m", -1.0, x), 1e-8 * amp);
  // The velocity is continuous across t_r: the closed form's derivative on both sides.
  EXPECT_LT(max_error_after(r, "m.velocity_m_s", -1.0, [&](double t) {
              if (t <= tr) return -(x0 - xe) * w * std::sin(w * t);
              const double tau = t - tr;
              return -(xr - xe2) * w2 * std::sin(w2 * tau) + vr * std::cos(w2 * tau);
            }),
            1e-8 * amp * w2);
}

// Claim: the power column of the weight load (`--outputs power`, P = F v) follows the weight the
// releases left: −m g v before t_r, −(m − Δm) g v after it, at every output row (the oscillation of
// ReleaseInTheMiddleOfAFreeOscillation; v is the run's own velocity column).
TEST(ReleaseOutputs, WeightPowerFollowsTheReleasedWeight) {
  const Model mod = model_of(kMidOscillation);
  const SimulationResult r = simulate(mod, SimulateOptions{}, output_selection({"power"}));
  const auto& t = series(r, "t_s");
  const auto& v = series(r, "m.velocity_m_s");
  const auto& P = series(r, "m.weight.power_W");
  ASSERT_EQ(P.size(), t.size());
  for (size_t k = 0; k < t.size(); ++k)
    ASSERT_NEAR(P[k], -(t[k] <= 0.37 ? 2.0 : 0.5) * 9.81 * v[k], 1e-12) << t[k];
}

// Claim: the report's model tables list each release: its body, Δm, t_r and the weight change
// +Δm g = 300 kg · 9.81 m/s² = 2943 N of a load hanging `vertical: up`.
TEST(ReleaseOutputs, ReportListsTheReleases) {
  const Model mod = model_of(R"(
gravity: 9.81 m/s^2
bodies: {load: {type: translational, mass: 1000 kg, vertical: up}}
links: {rope: {type: rope, between: [ground, load], stiffness: 1e6 N/m}}
releases: {grab: {body: load, mass: 300 kg, time: 0.0421 s}}
)");
  bool found = false;
  for (const report::Table& t : report::model_tables(mod)) {
    if (t.caption != "Releases") continue;
    found = true;
    ASSERT_EQ(t.rows.size(), 1u);
    EXPECT_EQ(t.rows[0], (std::vector<std::string>{"grab", "load", "300 kg", "0.0421 s", "2943 N"}));
  }
  EXPECT_TRUE(found);
}

// Claim: a rigid drive (1e15 kg, its speed changes by < 1e-11 relative) hoists at vh a load m hanging
// on a rope c, lifted and in steady motion: the rope stretch e = x_d − x is m g/c, the rope force m g.
// At t_r the load loses Δm: e'' = −(c/m') e + g, e(t_r) = m g/c, e'(t_r) = 0 (m' = m − Δm), so
//   x(t) = vh t − m' g/c − (Δm g/c) cos ω'(t − t_r),  F = m' g + Δm g cos ω'(t − t_r),
// the same extremes as at rest, the minimum at t_r + π/ω'. The quasi-static rope load at both
// extremes is the weight of the load at that instant (no rigid acceleration): m g before, m' g after.
TEST_P(Release, LoadReleasedWhileARigidDriveHoistsIt) {
  Model mod = model_of(R"(
gravity: 9.81 m/s^2
bodies:
  drive: {type: translational, mass: 1e15 kg, velocity: 0.4 m/s}
  load: {type: translational, mass: 1000 kg, vertical: up, position: -9.81 mm, velocity: 0.4 m/s}
links: {rope: {type: rope, between: [drive, load], stiffness: 1e6 N/m}}
releases: {slip: {body: load, mass: 250 kg, time: 0.13 s}}
simulation: {t_end: 0.4 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-13}
)");
  mod.simulation.integrator = GetParam();
  const double g = 9.81, m = 1000, dm = 250, c = 1e6, vh = 0.4, tr = 0.13;
  const double w = std::sqrt(c / (m - dm));
  const SimulationResult r = simulate(mod);
  EXPECT_NEAR(r.links[0].max, m * g, 1e-9 * m * g);
  EXPECT_NEAR(r.links[0].min, (m - 2 * dm) * g, tol(GetParam()) * m * g);
  EXPECT_NEAR(r.links[0].t_min, tr + std::numbers::pi / w, 1e-9 * (tr + std::numbers::pi / w));
  EXPECT_LT(max_error_after(r, "load.position_m", -1.0, [&](double t) {
              if (t <= tr) return vh * t - m * g / c;
              return vh * t - (m - dm) * g / c - dm * g / c * std::cos(w * (t - tr));
            }),
            tol(GetParam()) * dm * g / c);
  EXPECT_NEAR(r.links[0].static_at_min, (m - dm) * g, 1e-6 * m * g);
  EXPECT_NEAR(r.links[0].static_at_max, m * g, 1e-6 * m * g);
}

// Claim: the energy books close with the released part's kinetic energy. The oscillation of
// ReleaseInTheMiddleOfAFreeOscillation run with the books (event_driven): the released part carries
// away ½ Δm v_r² (v_r from the closed form), and W − (ΔT + ΔV + ½ Δm v_r²) is the integration error
// only (< tol of the energies moved); without that term the balance would miss it by ½ Δm v_r².
TEST_P(Release, EnergyBooksCloseWithTheReleasedKineticEnergy) {
  Model mod = model_of(kMidOscillation);
  mod.simulation.integrator = GetParam();
  const double g = 9.81, m = 2, dm = 1.5, c = 800, x0 = 0.1, tr = 0.37;
  const double w = std::sqrt(c / m), xe = -m * g / c;
  const double vr = -(x0 - xe) * w * std::sin(w * tr);
  SimulateOptions opt;
  opt.event_driven = true;
  const SimulationResult r = simulate(mod, opt);
  const EnergyBalance& E = r.hybrid.energy;
  EXPECT_NEAR(E.released_kinetic, 0.5 * dm * vr * vr, tol(GetParam()) * 0.5 * dm * vr * vr);
  EXPECT_NEAR(E.kinetic_start, 0.0, 1e-15);
  EXPECT_NEAR(E.elastic_start, 0.5 * c * x0 * x0, 1e-12);
  const double scale = std::max({std::abs(E.source_work), E.elastic_start, E.released_kinetic});
  EXPECT_LT(std::abs(E.residual()), tol(GetParam()) * scale);
  EXPECT_GT(E.released_kinetic, 1e3 * std::abs(E.residual()));
}

// Claim: a release on a body an ideal gear slaves acts on its master through the ratio: a drum
// (I_M = 2 kg·m²) on a torsion spring c = 500 N·m/rad drives a flywheel through q_f = ρ q_M, ρ = 3
// (I_f = 1 kg·m²): reduced inertia I = I_M + ρ² I_f = 11. Releasing ΔI = 0.6 kg·m² of the flywheel
// at t_r leaves I' = 11 − 9 · 0.6 = 5.6; from φ0 at rest φ = φ0 cos ωt before, then
//   φ = φ_r cos ω'τ + (ω_r/ω') sin ω'τ, ω = √(c/I), ω' = √(c/I'), τ = t − t_r;
// the drum's inertia column shows I then I'.
TEST_P(Release, ReleaseOnASlavedBodyActsThroughTheRatio) {
  Model mod = model_of(R"(
bodies:
  drum: {inertia: 2 kg*m^2, position: 0.2 rad}
  flywheel: {inertia: 1 kg*m^2}
links:
  c: {type: spring, between: [ground, drum], stiffness: 500 N*m/rad}
  gear: {type: ideal-gear, between: [flywheel, drum], ratio: 3}
releases: {shed: {body: flywheel, inertia: 0.6 kg*m^2, time: 0.5 s}}
simulation: {t_end: 1.5 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-13}
)");
  mod.simulation.integrator = GetParam();
  const double c = 500, I = 11, I2 = 11 - 9 * 0.6, p0 = 0.2, tr = 0.5;
  const double w = std::sqrt(c / I), w2 = std::sqrt(c / I2);
  const double pr = p0 * std::cos(w * tr), vr = -p0 * w * std::sin(w * tr);
  const SimulationResult r = simulate(mod);
  EXPECT_LT(max_error_after(r, "drum.position_rad", -1.0, [&](double t) {
              if (t <= tr) return p0 * std::cos(w * t);
              return pr * std::cos(w2 * (t - tr)) + vr / w2 * std::sin(w2 * (t - tr));
            }),
            1e-8 * p0);
  EXPECT_NEAR(test::at(r, "drum.inertia_kg_m2", 0.25), I, 1e-12);
  EXPECT_NEAR(series(r, "drum.inertia_kg_m2").back(), I2, 1e-12);
}

// Claim: bad `releases:` input is located (file:line:col) and listed together: an unknown body, a
// zero mass, a release that (with an earlier one of the same body) reaches the body's mass, a
// negative time, `mass` on a rotational body, a body with variable inertia.
TEST(ReleaseInput, ErrorsAreLocatedAndListedTogether) {
  try {
    model_of(R"(bodies:
  load: {type: translational, mass: 100 kg}
  wheel: {inertia: 1 kg*m^2}
  crank: {type: crank-slider, crank_radius: 40 mm, rod_length: 160 mm, rod_mass: 1.2 kg, rod_com: 80 mm, rod_inertia: 0.00256 kg*m^2, piston_mass: 1.6 kg, crank_inertia: 0.08 kg*m^2}
links: {s: {type: spring, between: [load, ground], stiffness: 1 N/m}}
releases:
  lost: {body: nobody, mass: 1 kg, time: 1 s}
  none: {body: load, mass: 0 kg, time: 1 s}
  first: {body: load, mass: 60 kg, time: 1 s}
  second: {body: load, mass: 40 kg, time: 2 s}
  early: {body: load, mass: 1 kg, time: -1 s}
  kind: {body: wheel, mass: 0.5 kg, time: 1 s}
  machine: {body: crank, inertia: 0.01 kg*m^2, time: 1 s}
)");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string s = e.what();
    EXPECT_NE(s.find("release.yaml:7:"), std::string::npos) << s;
    EXPECT_NE(s.find("unknown body 'nobody'"), std::string::npos) << s;
    EXPECT_NE(s.find("release.yaml:8:"), std::string::npos) << s;
    EXPECT_NE(s.find("release.yaml:10:"), std::string::npos) << s;
    EXPECT_NE(s.find("would lose 100 kg of its mass 100 kg"), std::string::npos) << s;
    EXPECT_NE(s.find("release.yaml:11:"), std::string::npos) << s;
    EXPECT_NE(s.find("field 'time' must be zero or positive"), std::string::npos) << s;
    EXPECT_NE(s.find("release.yaml:12:"), std::string::npos) << s;
    EXPECT_NE(s.find("a rotational body releases 'inertia', not 'mass'"), std::string::npos) << s;
    EXPECT_NE(s.find("release.yaml:13:"), std::string::npos) << s;
    EXPECT_NE(s.find("has a variable inertia"), std::string::npos) << s;
    EXPECT_EQ(s.find("release.yaml:9:"), std::string::npos) << s;  // 60 of 100 kg is fine
  }
}

}  // namespace
}  // namespace machdyn
