// Issue 32, items 10–13: the report shows every element as the file wrote it (model/describe.hpp),
// link loads in panels by unit and size, mode shapes of mixed rad/m models on a common scale, a
// frequency response from the drive over a band that means something, and the figures' marks.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "support/support.hpp"

#include "machdyn/analysis/linear_analysis.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/figures.hpp"
#include "machdyn/io/linear_results.hpp"
#include "machdyn/io/plot.hpp"
#include "machdyn/io/report.hpp"
#include "machdyn/model/describe.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// A hoist as a crane engineer writes it: motor, coupling, brake with a thermal model, a lossy
// gearbox, an ideal gear, a rope of 4 falls with EA and length, the hook on a floor stop.
constexpr const char* kHoist = R"(
name: hoist
gravity: 9.81 m/s^2
bodies:
  motor: {inertia: 0.5 kg*m^2}
  input: {inertia: 0.1 kg*m^2}
  pinion: {inertia: 0 kg*m^2}
  drum: {inertia: 50 kg*m^2}
  hook: {type: translational, mass: 8 t, vertical: up}
links:
  coupling: {type: spring-damper, between: [motor, input], stiffness: 2e4 N*m/rad, damping: 5 N*m*s/rad}
  gearbox: {type: lossy-gear, between: [input, pinion], ratio: 5, efficiency: 0.95, efficiency_reverse: 0.9}
  stage: {type: ideal-gear, between: [pinion, drum], ratio: 4}
  rope: {type: rope, between: [drum, hook], ratio: 4 rad/m, falls: 4, EA: 2.4e7 N, length: 12 m}
loads:
  M: {type: motor-kloss, body: motor, breakdown_torque: 400 N*m, breakdown_slip: 0.2, synchronous_speed: 1500 rpm}
brakes:
  holding: {body: motor, holding: 300 N*m, braking: 250 N*m, time: 5 s, ramp: 0.1 s,
            thermal: {heat_capacity: 5.5 kJ/K, conductance: 15 W/K, ambient: 25 degC}}
stops:
  floor: {body: hook, min: 0 m}
simulation: {t_end: 0.5 s, dt_out: 1 ms}
)";

std::vector<std::string> row_of(const Model& m, const std::string& caption_start, const std::string& name) {
  for (const report::Table& t : report::model_tables(m))
    if (t.caption.rfind(caption_start, 0) == 0)
      for (const auto& r : t.rows)
        if (!r.empty() && r[0] == name) return r;
  return {};
}

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Claim: the rope row says rope, 4 falls, the EA and length as written, the drum's 1/R = 4 rad/m
// (R = 0.25 m) and the hook stiffness n·EA/L = 4 · 2.4e7 / 12 = 8e6 N/m computed here — not
// "spring-damper"; the stop row says end stop at 0 m (not "friction, static limit 1 N"); the brake
// row carries its thermal model (C 5500 J/K, G 15 W/K, 25 °C); the gearboxes table has the lossy
// gear's ratio and both efficiencies and the ideal gear's ratio 4.
TEST(ReportElements, EveryElementAsTheFileWroteIt) {
  const Model m = test::model_text(kHoist);
  const auto rope = row_of(m, "Links", "rope");
  ASSERT_FALSE(rope.empty());
  EXPECT_EQ(rope[1], "rope");
  ASSERT_GE(rope.size(), 7u);
  const std::string rd = rope[6];  // "as written" (a "gap" column follows when a link has one)
  EXPECT_TRUE(has(rd, "4 falls")) << rd;
  EXPECT_TRUE(has(rd, "EA = 2.4e+07 N")) << rd;
  EXPECT_TRUE(has(rd, "L = 12 m per fall")) << rd;
  EXPECT_TRUE(has(rd, "1/R = 4 rad/m (R = 0.25 m)")) << rd;
  EXPECT_TRUE(has(rd, fmt::format("n·EA/L = {:.6g} N/m", 4 * 2.4e7 / 12))) << rd;
  const auto stop = row_of(m, "Friction", "floor");
  ASSERT_FALSE(stop.empty());
  EXPECT_EQ(stop[1], "end stop");
  EXPECT_TRUE(has(stop.back(), "lower stop of 'hook' at 0 m")) << stop.back();
  EXPECT_FALSE(has(stop.back(), "static limit")) << stop.back();
  const auto brake = row_of(m, "Friction", "holding");
  ASSERT_FALSE(brake.empty());
  EXPECT_EQ(brake[1], "brake");
  EXPECT_TRUE(has(brake.back(), "holding F_s = 300 N·m, braking F_k = 250 N·m")) << brake.back();
  EXPECT_TRUE(has(brake.back(), "C = 5500 J/K, G = 15 W/K, ambient 25 °C, T(0) = 25 °C")) << brake.back();
  const auto lossy = row_of(m, "Gearboxes", "gearbox");
  ASSERT_FALSE(lossy.empty());
  EXPECT_EQ(lossy[1], "lossy gear");
  EXPECT_TRUE(has(lossy.back(), "ratio i = 5")) << lossy.back();
  EXPECT_TRUE(has(lossy.back(), "η = 0.95 while A drives, 0.9 while B drives")) << lossy.back();
  const auto ideal = row_of(m, "Gearboxes", "stage");
  ASSERT_FALSE(ideal.empty());
  EXPECT_EQ(ideal[1], "ideal gear");
}

// Claim: a 4/2 reeving with sheave losses hung from a girder is shown as written: 4 falls from 2 rope
// ends, η = 0.98, the drum's 1/R = 4 rad/m as the file gave it (the link's own ratio is (n/n_e)/R =
// 8 rad/m, model/reeving.hpp), the frame body by name, the reeving's efficiencies (1 + η)/2 and
// 2η/(1 + η) that act at the drum, and no row for the body and gear the losses are compiled into.
TEST(ReportElements, ReevingAndFrameAsTheFileWroteThem) {
  std::string yaml = kHoist;
  const std::string old_rope = "  rope: {type: rope, between: [drum, hook], ratio: 4 rad/m, falls: 4, EA: 2.4e7 N, length: 12 m}\n";
  const auto at = yaml.find(old_rope);
  ASSERT_NE(at, std::string::npos);
  yaml.replace(at, old_rope.size(),
               "  rope: {type: rope, between: [drum, hook], ratio: 4 rad/m, falls: 4, rope_ends: 2, "
               "sheave_efficiency: 0.98, stiffness: 8e6 N/m, frame: girder}\n"
               "  girder_spring: {type: spring, between: [ground, girder], stiffness: 5e7 N/m}\n");
  yaml.replace(yaml.find("  hook:"), 0, "  girder: {type: translational, mass: 5 t, vertical: up}\n");
  // The sheave losses act as a lossy gear at the drum (model/sheaves.hpp), which may not share the
  // gearbox's rigid group: the last stage is an elastic shaft here.
  const std::string stage = "stage: {type: ideal-gear, between: [pinion, drum], ratio: 4}";
  yaml.replace(yaml.find(stage), stage.size(), "stage: {type: spring, between: [pinion, drum], ratio: 4, stiffness: 1e7 N*m/rad}");
  const Model m = test::model_text(yaml);
  const auto rope = row_of(m, "Links", "rope");
  ASSERT_GE(rope.size(), 7u);
  const std::string rd = rope[6];
  EXPECT_EQ(rope[1], "rope") << rd;
  EXPECT_TRUE(has(rd, "4 falls from 2 rope ends on the drum (4/2 reeving)")) << rd;
  EXPECT_TRUE(has(rd, "sheave efficiency η = 0.98")) << rd;
  EXPECT_TRUE(has(rd, "drum 1/R = 4 rad/m")) << rd;
  EXPECT_TRUE(has(rd, "hung from the frame 'girder'")) << rd;
  // Between the drum and the hook with the drum's ratio (n/n_e)/R = 8 rad/m, as without the losses; the
  // reeving's efficiencies in its words; no body or gearbox row of its own (the rope's, model/sheaves.hpp).
  EXPECT_EQ(rope[2], "drum – hook") << rope[2];
  EXPECT_EQ(rope[3], "8 rad/m") << rope[3];
  EXPECT_TRUE(has(rd, "reeving efficiency 0.99 hoisting, 0.989899 lowering, acting at the drum")) << rd;
  EXPECT_TRUE(row_of(m, "Bodies", "rope.sheaves").empty());
  EXPECT_TRUE(row_of(m, "Gearboxes", "rope.sheaves").empty());
  EXPECT_FALSE(row_of(m, "Gearboxes", "gearbox").empty());
}

// Claim: a progressive buffer is described by its side, position and F = c sⁿ with c = F/sⁿ
// (200 kN at 0.1 m, n = 2.5: c = 2e5 / 0.1^2.5 computed here), and has no dynamic factor (its
// reference is φ7's rigid-body peak): NaN in the summary, "–" in the printout.
TEST(ReportElements, BufferDescribedAndWithoutDynamicFactor) {
  const std::string yaml =
      "bodies: {trolley: {type: translational, mass: 2000 kg, velocity: 1.2 m/s}}\n"
      "buffers: {east: {body: trolley, max: 0.3 m, characteristic: progressive, exponent: 2.5, force: 200 kN, "
      "stroke: 0.1 m}}\nsimulation: {t_end: 1 s, dt_out: 1 ms}\n";
  for (const IntegratorChoice integrator : {IntegratorChoice::dopri5, IntegratorChoice::bdf}) {
    Model m = test::model_text(yaml);
    m.simulation.integrator = integrator;
    const ElementText t = describe_link(m, m.links[0]);
    EXPECT_EQ(t.type, "buffer");
    EXPECT_TRUE(has(t.definition, "upper buffer of 'trolley' at 0.3 m")) << t.definition;
    EXPECT_TRUE(has(t.definition, fmt::format("c = {:.6g} N/mⁿ, n = 2.5", 2e5 / std::pow(0.1, 2.5)))) << t.definition;
    const SimulationResult r = simulate(m);
    EXPECT_GT(r.links[0].max, 0.0);
    EXPECT_TRUE(std::isnan(r.links[0].dynamic_factor)) << r.links[0].dynamic_factor;
    EXPECT_EQ(r.links[0].min, 0.0);  // compression only: never a negative force, not −1e−29
  }
  const auto path = test::write_temp("buffer32.yaml", yaml);
  const auto cli = test::run_cli("simulate '" + path + "' -o buffer32-out --quiet");
  ASSERT_EQ(cli.exit_code, 0) << cli.err;
  EXPECT_FALSE(has(cli.out, "nan")) << cli.out;
  EXPECT_TRUE(has(cli.out, "–")) << cli.out;
}

// Claim: extremes below 1e-12 of the link's largest magnitude are zero (set_peak), others kept.
TEST(ReportElements, TinyExtremesAreZero) {
  LinkSummary s;
  s.max = 1e5, s.min = -4.6e-29, s.static_at_max = 5e4;
  set_peak(s);
  EXPECT_EQ(s.min, 0.0);
  EXPECT_EQ(s.max, 1e5);
  EXPECT_DOUBLE_EQ(s.dynamic_factor, 2.0);
  LinkSummary t;
  t.max = 1e5, t.min = -1e-3;
  set_peak(t);
  EXPECT_EQ(t.min, -1e-3);
}

// Two shafts of very different loads and a rope in N: a 40 kN·m drum shaft (the drum torque m g R
// of 16 t on R = 0.25 m: 39.2 kN·m) and a motor coupling of M_L / i = 39.2 kN·m / 100 = 0.39 kN·m.
constexpr const char* kPanels = R"(
name: panels
gravity: 9.81 m/s^2
bodies:
  motor: {inertia: 2 kg*m^2}
  gear: {inertia: 1 kg*m^2}
  drum: {inertia: 500 kg*m^2}
  hook: {type: translational, mass: 16 t, vertical: up}
links:
  coupling: {type: spring-damper, between: [motor, gear], stiffness: 5e4 N*m/rad, damping: 20 N*m*s/rad}
  drum_shaft: {type: spring-damper, between: [gear, drum], ratio: 100, stiffness: 5e7 N*m/rad, damping: 1e4 N*m*s/rad}
  rope: {type: spring-damper, between: [drum, hook], ratio: 4 rad/m, stiffness: 2e7 N/m, damping: 1e5 N*s/m}
loads:
  M: {type: constant, body: motor, value: 392.4 N*m}
simulation: {t_end: 0.2 s, dt_out: 1 ms, initial: equilibrium}
)";

// Claim: the link loads are drawn in panels by unit and size: the N·m links apart from the rope in
// N, and the 0.39 kN·m coupling apart from the 39 kN·m drum shaft (ratio 100 > 8); --links picks
// links (one panel naming them) and an unknown name is an input error listing the links.
TEST(ReportElements, LinkLoadsInPanelsByUnitAndSize) {
  const Model m = test::model_text(kPanels);
  const SimulationResult r = simulate(m);
  // The static loads by hand: drum shaft m g R = 16000·9.81/4, coupling that over the ratio 100.
  EXPECT_NEAR(r.links[1].max, 16000 * 9.81 / 4, 1e-3 * 16000 * 9.81 / 4);
  EXPECT_NEAR(r.links[0].max, 16000 * 9.81 / 4 / 100, 1e-3 * 16000 * 9.81 / 400);
  const auto groups = link_load_groups(m, r);
  ASSERT_EQ(groups.size(), 3u);
  EXPECT_EQ(groups[0], (std::vector<std::size_t>{1}));  // drum shaft, the largest N·m
  EXPECT_EQ(groups[1], (std::vector<std::size_t>{0}));  // coupling
  EXPECT_EQ(groups[2], (std::vector<std::size_t>{2}));  // rope, N
  const auto figs = link_loads_figures(m, r);
  ASSERT_EQ(figs.size(), 3u);
  EXPECT_EQ(figs[0].id, "link_loads");
  EXPECT_EQ(figs[1].id, "link_loads_2");
  EXPECT_EQ(figs[1].y.unit, "N·m");  // 0.39 kN·m shown in N·m, not a flat line in kN·m
  EXPECT_TRUE(has(figs[1].title, "coupling")) << figs[1].title;
  const auto chosen = link_loads_figures(m, r, {"rope", "coupling"});
  ASSERT_EQ(chosen.size(), 2u);
  EXPECT_EQ(chosen[0].series.size(), 1u);
  // A link that carries nothing in the run (a second machine at rest beside the hoist) gets no
  // empty panel of zero lines: the first panel's title names it; chosen by name, it is drawn.
  {
    std::string yaml = kPanels;
    yaml.replace(yaml.find("links:\n"), 7, "links:\n  idle: {type: spring, between: [ground, spare], stiffness: 1e3 N/m}\n");
    yaml.replace(yaml.find("bodies:\n"), 8, "bodies:\n  spare: {type: translational, mass: 1 kg}\n");
    const Model mi = test::model_text(yaml);
    const SimulationResult ri = simulate(mi);
    const auto panels = link_loads_figures(mi, ri);
    ASSERT_EQ(panels.size(), 3u);
    for (const auto& f : panels)
      for (const auto& sr : f.series) EXPECT_FALSE(has(sr.name, "idle")) << f.title;
    EXPECT_TRUE(has(panels[0].title, "no load in this run: idle")) << panels[0].title;
    EXPECT_EQ(link_loads_figures(mi, ri, {"idle"}).size(), 1u);
  }
  try {
    (void)link_load_groups(m, r, {"shaft"});
    FAIL() << "no error for an unknown link";
  } catch (const InputError& e) {
    EXPECT_TRUE(has(e.what(), "--links")) << e.what();
    EXPECT_TRUE(has(e.what(), "coupling, drum_shaft, rope")) << e.what();
  }
}

// Claim: a model mixing rad and m draws each mode's √I·φ (scaled to max 1): for the drum (J) on a
// rope to a hook (m), with mass-normalized φ, Σ (√I_i φ_i)² = 1, so the plotted values squared sum
// to 1 / max² — checked here against the 2-DOF eigenvectors of K φ = ω² M φ solved by hand, and the
// hook's bounce (its mode) reaches 1 where the raw φ of 1/√m ≈ 0.01 looked like rest.
TEST(ReportElements, MixedModeShapesOnACommonScale) {
  const Model m = test::model_text(R"(
bodies:
  drum: {inertia: 50 kg*m^2}
  hook: {type: translational, mass: 10 t}
links:
  rope: {type: spring, between: [drum, hook], ratio: 4 rad/m, stiffness: 1e7 N/m}
  brake_shaft: {type: spring, between: [ground, drum], stiffness: 1e6 N*m/rad}
simulation: {t_end: 0.1 s}
)");
  const Modes modes = compute_modes(m);
  ASSERT_EQ(modes.omega.size(), 2);
  const plot::Figure f = mode_shapes_figure(m, modes);
  EXPECT_TRUE(has(f.title, "√I")) << f.title;
  EXPECT_TRUE(has(f.y.label(), "√I·φ")) << f.y.label();
  // The 2-DOF problem by hand: q = (φ_drum, x_hook), δ = φ/i − x, i = 4 rad/m: the rope's stiffness
  // in the coordinates is c [[1/i², −1/i], [−1/i, 1]], plus k on the drum.
  const double J = 50, mh = 1e4, c = 1e7, i = 4, k = 1e6;
  const double K11 = c / (i * i) + k, K12 = -c / i, K22 = c;
  // det(K − λ M) = 0: J mh λ² − (K11 mh + K22 J) λ + K11 K22 − K12² = 0.
  const double A = J * mh, B = -(K11 * mh + K22 * J), C = K11 * K22 - K12 * K12;
  const double lam_lo = (-B - std::sqrt(B * B - 4 * A * C)) / (2 * A);
  EXPECT_NEAR(modes.omega(0), std::sqrt(lam_lo), 1e-9 * std::sqrt(lam_lo));
  // Its shape: (K11 − λ J) a + K12 b = 0 → b/a = −(K11 − λ J)/K12; weighted: (√J a, √mh b).
  const double ratio = -(K11 - lam_lo * J) / K12;
  const double wa = std::sqrt(J), wb = std::sqrt(mh) * ratio, top = std::max(std::abs(wa), std::abs(wb));
  ASSERT_EQ(f.series[0].y.size(), 2u);
  const double sign = f.series[0].y[0] * wa >= 0 ? 1.0 : -1.0;
  EXPECT_NEAR(f.series[0].y[0], sign * wa / top, 1e-9);
  EXPECT_NEAR(f.series[0].y[1], sign * wb / top, 1e-9);
  EXPECT_GT(std::max(std::abs(f.series[0].y[1]), std::abs(f.series[1].y[1])), 0.99);
}

// Claim: the report's frequency response starts at the drive (the motor load, not the hook's
// weight) and its band ends at twice the highest resonance the outputs show (within the grid):
// here the one elastic mode of the motor–rope–hook chain, ω = √(c_eff / m_eff) computed here.
// A named input, output and band are taken as given; an unknown input names --frf-input.
TEST(ReportElements, FrequencyResponseFromTheDriveOverAMeaningfulBand) {
  const Model m = test::model_text(R"(
gravity: 9.81 m/s^2
bodies:
  motor: {inertia: 20 kg*m^2}
  hook: {type: translational, mass: 2 t, vertical: up}
links:
  rope: {type: spring-damper, between: [motor, hook], ratio: 4 rad/m, stiffness: 1e6 N/m, damping: 2e3 N*s/m}
loads:
  M: {type: motor-linear, body: motor, stall_torque: 3000 N*m, no_load_speed: 100 rad/s}
simulation: {t_end: 0.1 s}
)");
  EXPECT_EQ(default_frf_input(m), "M");
  const auto list = run_topology_modes(m, simulate(m).hybrid, m.simulation.t_end);
  std::string label;
  const auto frf = default_frequency_response(m, list, &label);
  ASSERT_TRUE(frf);
  EXPECT_EQ(frf->input.name, "M");
  // Motor J on the drum side (J/... reduced to the hook: J i²), hook m: ω² = c (1/(J i²) + 1/m).
  const double w = std::sqrt(1e6 * (1.0 / (20 * 16) + 1.0 / 2000));
  const double w_hi = frf->omega(frf->omega.size() - 1);
  EXPECT_NEAR(w_hi, 2 * w, 0.03 * 2 * w) << "band ends at " << w_hi;
  FrfChoice choice;
  choice.input = "hook";
  choice.outputs = {"hook.speed"};
  choice.f_lo_hz = 0.5, choice.f_hi_hz = 20;
  const auto named = default_frequency_response(m, list, &label, choice);
  ASSERT_TRUE(named);
  EXPECT_EQ(named->input.name, "hook");
  ASSERT_EQ(named->outputs.size(), 1u);
  EXPECT_NEAR(named->omega(named->omega.size() - 1), 2 * std::numbers::pi * 20, 1e-9);
  choice.input = "nothing";
  EXPECT_THROW((void)default_frequency_response(m, list, &label, choice), InputError);
}

// Claim: an output the frequency response's input does not reach (a second machine beside the first,
// no link between them) has |H| of the rounding (≤ 1e-9 of the reached outputs'): its Bode curves are
// left out and the title names it, so the log axis spans the reached outputs only (the worked crane's
// trolley case drew 1e-23 … 7 and the page's script failed on it). The reached output's curve stays:
// a spring c to a mass m driven by a force has |H| of its spring load = c/|c − ω² m|, 1 at ω → 0.
TEST(ReportElements, BodePlotsLeaveOutOutputsTheInputDoesNotReach) {
  const Model m = test::model_text(R"(
bodies:
  a: {type: translational, mass: 10 kg}
  b: {type: translational, mass: 20 kg}
links:
  sa: {type: spring, between: [ground, a], stiffness: 1e4 N/m}
  sb: {type: spring, between: [ground, b], stiffness: 2e4 N/m}
loads:
  F: {type: constant, body: a, value: 1 N}
simulation: {t_end: 0.01 s}
)");
  const auto list = run_topology_modes(m, simulate(m).hybrid, m.simulation.t_end);
  std::string label;
  FrfChoice choice;
  choice.input = "F";
  const auto frf = default_frequency_response(m, list, &label, choice);
  ASSERT_TRUE(frf);
  ASSERT_EQ(frf->outputs.size(), 2u);
  for (const bool phase : {false, true}) {
    const plot::Figure f = phase ? bode_phase_figure(m, *frf, label) : bode_magnitude_figure(m, *frf, label);
    ASSERT_EQ(f.series.size(), 1u) << f.title;
    EXPECT_TRUE(has(f.series[0].name, "sa.load")) << f.series[0].name;
    EXPECT_TRUE(has(f.title, "not excited: sb.load")) << f.title;
    if (!phase) {
      const double w = 2 * std::numbers::pi * f.series[0].x.front();
      EXPECT_NEAR(f.series[0].y.front(), 1e4 / std::abs(1e4 - w * w * 10), 1e-6);
    }
  }
}

// Claim: a brake never applied in the run draws no "applied" mark (it did at t_end) and its
// summary has applied_at_s null; a brake applied at 0.2 s draws its mark there.
TEST(ReportElements, BrakeMarkOnlyWhenApplied) {
  auto model = [](const std::string& time) {
    return test::model_text("bodies: {disc: {inertia: 1 kg*m^2, velocity: 10 rad/s}}\n"
                            "brakes: {b: {body: disc, holding: 20 N*m, braking: 10 N*m, time: " + time + "}}\n"
                            "links: {s: {type: spring, between: [ground, disc], stiffness: 1e3 N*m/rad}}\n"
                            "simulation: {t_end: 0.5 s, dt_out: 1 ms}\n");
  };
  const Model never = model("5 s"), soon = model("0.2 s");
  const auto marks_of = [](const Model& m) {
    const plot::Figure f = link_loads_figure(m, simulate(m));
    std::vector<std::pair<double, std::string>> v;
    for (const auto& e : f.events) v.emplace_back(e.x, e.label);
    return v;
  };
  for (const auto& [x, label] : marks_of(never)) EXPECT_FALSE(has(label, "applied")) << x << " " << label;
  bool found = false;
  for (const auto& [x, label] : marks_of(soon)) found = found || (has(label, "b applied") && std::abs(x - 0.2) < 1e-12);
  EXPECT_TRUE(found);
}

}  // namespace
}  // namespace machdyn
