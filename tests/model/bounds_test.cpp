// Bounds of what a model may ask for (issue 28, "inputs and bounds"): values that no double, no run
// or no table could hold are located input errors at compile (so every command refuses them alike),
// and the implicit defaults of a model without a `simulation:` section.
#include <cmath>
#include <limits>
#include <numbers>
#include <string>
#include <gtest/gtest.h>

#include "machdyn/common/units.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

/// A chain A–B–C–D of ideal gears of one ratio each (q_A = i q_B, ...), a spring on D and a torque on A.
std::string gear_chain(const std::string& ratio) {
  return "bodies:\n"
         "  A: {type: rotational, inertia: 1 kg*m^2}\n"
         "  B: {type: rotational, inertia: 1 kg*m^2}\n"
         "  C: {type: rotational, inertia: 1 kg*m^2}\n"
         "  D: {type: rotational, inertia: 1 kg*m^2}\n"
         "links:\n"
         "  g1: {type: ideal-gear, between: [A, B], ratio: " + ratio + "}\n"
         "  g2: {type: ideal-gear, between: [B, C], ratio: " + ratio + "}\n"
         "  g3: {type: ideal-gear, between: [C, D], ratio: " + ratio + "}\n"
         "  c1: {type: spring, between: [D, ground], stiffness: 100 N*m/rad}\n"
         "loads:\n"
         "  L: {type: constant, body: A, value: 1 N*m}\n"
         "simulation: {t_end: 0.1 s}\n";
}

// Claim: a chain of ideal gears whose product of ratios ρ has a square beyond 1e±200 is refused at
// the gear that takes it there: with 1e85 per gear, ρ_C = 1e-170 (ρ² = 1e-340 underflows: g2, line
// 8); with 1e-160, ρ_B = 1e160 (ρ² = 1e320 overflows: g1, line 7). A chain of 1e30 (ρ_D = 1e-90)
// compiles, with the reduced inertia I_A + Σ ρ² I = 1 + 1e-60 + 1e-120 + 1e-180 (= 1 in doubles).
TEST(Bounds, IdealGearRatioProductsOutsideDoublesAreLocatedErrors) {
  const std::string big = test::compile_errors(gear_chain("1e85"));
  EXPECT_NE(big.find("test.yaml:8:"), std::string::npos) << big;
  EXPECT_NE(big.find("ideal gear 'g2'"), std::string::npos) << big;
  const std::string tiny = test::compile_errors(gear_chain("1e-160"));
  EXPECT_NE(tiny.find("test.yaml:7:"), std::string::npos) << tiny;
  EXPECT_NE(tiny.find("ideal gear 'g1'"), std::string::npos) << tiny;
  const Model m = test::model_text(gear_chain("1e30"));
  ASSERT_EQ(m.dof(), 1);
  EXPECT_EQ(m.bodies[0].inertia, 1.0);
  EXPECT_TRUE(std::isfinite(m.links[0].ratio));
}

// Claim: a number below the smallest normal double (a subnormal, 5e-324) is out of range like 1e400,
// with or without a unit; the smallest normal value and zero are numbers.
TEST(Bounds, SubnormalNumbersAreOutOfRange) {
  std::string err;
  EXPECT_FALSE(parse_quantity("5e-324", &err));
  EXPECT_NE(err.find("out of range"), std::string::npos) << err;
  EXPECT_FALSE(parse_quantity("5e-324 kg*m^2", &err));
  EXPECT_FALSE(parse_quantity("1e-300 ng", &err));  // 1e-312 kg in SI: a subnormal after scaling
  EXPECT_TRUE(parse_quantity("2.2250738585072014e-308", &err));
  EXPECT_TRUE(parse_quantity("0 kg", &err));
  const std::string e = test::compile_errors("bodies:\n  I1: {type: rotational, inertia: 5e-324}\n");
  EXPECT_NE(e.find("test.yaml:2:"), std::string::npos) << e;
}

std::string sine_model(const std::string& frequency, const std::string& simulation) {
  return "bodies:\n"
         "  I1: {type: rotational, inertia: 1 kg*m^2}\n"
         "links:\n"
         "  c1: {type: spring, between: [I1, ground], stiffness: 100 N*m/rad}\n"
         "loads:\n"
         "  L: {type: sum, body: I1, terms: [1 N*m, {type: sine, amplitude: 1 N*m, frequency: " + frequency + "}]}\n"
         "simulation: " + simulation + "\n";
}

// Claim: a sine is refused where its periods before t_end (f·t_end) exceed max_steps/4 — no run
// could follow it — located at its frequency (line 6), wherever it is (here a term of a sum); at the
// bound it compiles. 1e300 Hz: f·t_end = 1e300. max_steps 4e6, t_end 1 s: 1e6 periods is the last
// allowed (1e6 Hz), 1.0001e6 Hz is one too many; 6.2832e6 rad/s = 1.00000e6 Hz in rad/s.
TEST(Bounds, SinesFasterThanAnyRunCouldFollowAreLocatedErrors) {
  const std::string e = test::compile_errors(sine_model("1e300 Hz", "{t_end: 1 s}"));
  EXPECT_NE(e.find("test.yaml:6:"), std::string::npos) << e;
  EXPECT_NE(e.find("max_steps"), std::string::npos) << e;
  EXPECT_EQ(test::compile_errors(sine_model("1e6 Hz", "{t_end: 1 s, max_steps: 4000000}")), "");
  EXPECT_NE(test::compile_errors(sine_model("1.0001e6 Hz", "{t_end: 1 s, max_steps: 4000000}")), "");
  EXPECT_EQ(test::compile_errors(sine_model("6.2831e6 rad/s", "{t_end: 1 s, max_steps: 4000000}")), "");
  EXPECT_NE(test::compile_errors(sine_model("6.2833e6 rad/s", "{t_end: 1 s, max_steps: 4000000}")), "");
  // A legitimate long run: 50 Hz for an hour is 1.8e5 periods.
  EXPECT_EQ(test::compile_errors(sine_model("50 Hz", "{t_end: 3600 s}")), "");
}

// Claim: a table of more than 10^6 points is a located error at its `points` (line 6); 10^6 compile.
// The points are put into the parsed spec directly (12 MB of YAML text would take seconds to read).
TEST(Bounds, TablesAreBoundedInSize) {
  auto errors_with = [](size_t n) {
    SpecNode root = parse_yaml_string(
        "bodies:\n  I1: {type: rotational, inertia: 1 kg*m^2}\nlinks:\n"
        "  c1: {type: spring, between: [I1, ground], stiffness: 100 N*m/rad}\nloads:\n"
        "  L: {type: table, body: I1, time_unit: ms, points: [[0, 1]]}\nsimulation: {t_end: 0.01 s}\n",
        "test.yaml");
    SpecNode& points = *root.find("loads")->find("L")->find("points");
    SpecNode pair = points.items[0];
    points.items.assign(n, pair);
    for (size_t i = 0; i < n; ++i) points.items[i].items[0].scalar = std::to_string(i);
    try {
      (void)compile_model(root, "test.yaml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  const std::string e = errors_with(1'000'001);
  EXPECT_NE(e.find("test.yaml:6:"), std::string::npos) << e.substr(0, 300);
  EXPECT_NE(e.find("1000001 points"), std::string::npos) << e.substr(0, 300);
  EXPECT_EQ(errors_with(1'000'000), "");
}

// Claim: a file with a flood of errors (2·10^5 decreasing table times) lists the first 100 and counts
// the rest, quickly (the de-duplication was quadratic: minutes for 10^6 errors).
TEST(Bounds, AFloodOfErrorsIsListedShort) {
  std::string pts;
  for (int i = 0; i < 200'000; ++i) pts += (i ? ",[" : "[") + std::to_string(200'000 - i) + ",1]";
  const std::string text = "bodies:\n  I1: {type: rotational, inertia: 1 kg*m^2}\nloads:\n"
                           "  L: {type: table, body: I1, points: [" + pts + "]}\n";
  try {
    (void)load_model(test::write_temp("flood.yaml", text));
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    ASSERT_EQ(e.diagnostics().size(), 101u);
    EXPECT_EQ(e.diagnostics().back().message, "... and 199899 more errors");
  }
}

const char* kNoSimulation =
    "bodies:\n  I1: {type: rotational, inertia: 1 kg*m^2}\nlinks:\n"
    "  c1: {type: spring, between: [I1, ground], stiffness: 100 N*m/rad}\n";

// Claim: a model without `simulation:` has the section's defaults (t_end 1 s, dt_out = t_end/1000,
// as docs/model-files.md lists them), and `--set simulation.FIELD` works on it, creating the section;
// an element named `simulation` is still found first.
TEST(Bounds, TheSimulationSectionExistsImplicitly) {
  const Model m = test::model_text(kNoSimulation);
  EXPECT_EQ(m.simulation.t_end, 1.0);
  EXPECT_EQ(m.simulation.dt_out, 1e-3);
  SpecNode root = parse_yaml_string(kNoSimulation, "test.yaml");
  apply_set(root, "simulation.t_end=2 s");
  apply_set(root, "simulation.rtol=1e-6");
  const Model m2 = compile_model(root, "test.yaml");
  EXPECT_EQ(m2.simulation.t_end, 2.0);
  EXPECT_EQ(m2.simulation.dt_out, 2e-3);
  EXPECT_EQ(m2.simulation.rtol, 1e-6);
  SpecNode named = parse_yaml_string("bodies:\n  simulation: {type: rotational, inertia: 1 kg*m^2}\n", "t.yaml");
  apply_set(named, "simulation.inertia=3");
  EXPECT_EQ(compile_model(named, "t.yaml").bodies[0].inertia, 3.0);
  SpecNode other = parse_yaml_string(kNoSimulation, "test.yaml");
  EXPECT_THROW(apply_set(other, "nothing.t_end=2"), InputError);
}

}  // namespace
}  // namespace machdyn
