// The signal grammar in model files (model/compile_signal.hpp) and the state-dependent loads: each
// form compiles to the signal or law it says; bad fields are located errors, all listed at once.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/io/model_file.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

constexpr double kPi = std::numbers::pi;

Model compile_text(const std::string& name, const std::string& loads) {
  return load_model(test::write_temp(name, "bodies:\n  R: {inertia: 1}\n  X: {type: translational, mass: 2}\nloads:\n" +
                                               loads + "simulation: {t_end: 10 s}\n"));
}

/// The messages of the InputError that compiling `loads` throws ("" if none).
std::string errors_of(const std::string& name, const std::string& loads) {
  try {
    compile_text(name, loads);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// Claim: every signal kind compiles from its fields, in SI: sine in Hz and in rad/s, phase in deg,
// pulse width in % of the period, sums of quantities and maps, tables with jumps and units.
TEST(SignalCompile, EveryKindFromItsFields) {
  const Model m = compile_text("kinds.yaml", R"(  s1: {type: sine, body: R, amplitude: 2 kN*m, frequency: 5 Hz, phase: 90 deg, offset: 1 kN*m, start: 0.5 s}
  s2: {type: sine, body: R, amplitude: 1, frequency: 3 rad/s}
  p: {type: pulse, body: X, high: 2 kN, low: -1 kN, period: 0.4 s, width: 25 %, start: 1 s, count: 2}
  e: {type: expression, body: R, expression: "3*t + phi - 2*omega"}
  u: {type: sum, body: R, terms: [5 N*m, {type: step, value: 1 N*m, time: 2 s}]}
  tab: {type: table, body: X, unit: kN, time_unit: ms, outside: extrapolate, points: [[0, 0], [500, 1], [500, 3], [1000, 4]]}
  c: {type: constant, body: X, value: 3 kN}
)");
  ASSERT_EQ(m.loads.size(), 7u);
  const Load& s1 = m.loads[0];
  EXPECT_EQ(s1.kind, LoadKind::signal);
  EXPECT_NEAR(test::load_at(s1, 0.6, 0, 0), 1000 + 2000 * std::sin(2 * kPi * 5 * 0.1 + kPi / 2), 1e-9);
  EXPECT_NEAR(test::load_at(m.loads[1], 0.7, 0, 0), std::sin(3 * 0.7), 1e-14);
  const Load& p = m.loads[2];
  EXPECT_EQ(test::load_at(p, 1.05, 0, 0), 2000.0);
  EXPECT_EQ(test::load_at(p, 1.15, 0, 0), -1000.0);  // width 25 % of 0.4 s = 0.1 s
  EXPECT_EQ(test::load_at(p, 1.85, 0, 0), -1000.0);  // after two periods
  EXPECT_EQ(m.loads[3].kind, LoadKind::expression);
  EXPECT_DOUBLE_EQ(test::load_at(m.loads[3], 2, 0.5, 4), 6 + 0.5 - 8);
  EXPECT_DOUBLE_EQ(test::load_at(m.loads[4], 1, 0, 0), 5);
  EXPECT_DOUBLE_EQ(test::load_at(m.loads[4], 2, 0, 0), 6);
  const Load& tab = m.loads[5];
  EXPECT_DOUBLE_EQ(test::load_at(tab, 0.25, 0, 0), 500.0);
  EXPECT_DOUBLE_EQ(test::load_at(tab, 0.5, 0, 0), 3000.0);  // the jump
  EXPECT_DOUBLE_EQ(test::load_at(tab, 1.5, 0, 0), 5000.0);  // extrapolated along the last segment
  EXPECT_EQ(m.loads[6].kind, LoadKind::constant);     // a constant stays a constant (the fast path)
  EXPECT_EQ(m.loads[6].value, 3000.0);
  EXPECT_EQ(m.breakpoints(10.0), (std::vector<double>{0.5, 1.0, 1.1, 1.4, 1.5, 2.0}));
}

// Claim: the state-dependent loads compile with their laws: drag from one point of the curve
// (k = M_n/ω_n²), the eddy-current brake's maximum M_k at ω_k, a motor's catalogue curve, tables over
// speed and position, a contactor given by times and a reversing step.
TEST(SignalCompile, StateDependentLoadsAndMotorSwitching) {
  const Model m = compile_text("state.yaml", R"(  fan: {type: drag, body: R, load: 8 N*m, speed: 1000 rpm}
  eddy: {type: eddy-current-brake, body: R, breakdown_torque: 50 N*m, breakdown_speed: 20 rad/s}
  cat: {type: motor-table, body: R, points: [[0, 300 N*m], [90 rad/s, 250 N*m], [100 rad/s, 0]], on: 1 s, off: 3 s, reverse: 2 s}
  pos: {type: table, over: position, body: X, points: [[0, 0], [0.1 m, -50 N]]}
)");
  const double wn = 1000 * 2 * kPi / 60;
  EXPECT_NEAR(test::load_at(m.loads[0], 0, 0, wn), -8.0, 1e-12);
  EXPECT_NEAR(test::load_at(m.loads[0], 0, 0, -wn), 8.0, 1e-12);  // always against the motion
  EXPECT_NEAR(test::load_at(m.loads[1], 0, 0, 20), -50.0, 1e-12);
  EXPECT_NEAR(test::load_at(m.loads[1], 0, 0, -20), 50.0, 1e-12);
  EXPECT_LT(std::abs(test::load_at(m.loads[1], 0, 0, 19)), 50.0);
  const Load& cat = m.loads[2];
  EXPECT_TRUE(cat.switched);
  EXPECT_EQ(test::load_at(cat, 0.5, 0, 0), 0.0);                         // contactor open
  EXPECT_DOUBLE_EQ(test::load_at(cat, 1.5, 0, 45), 275.0);               // forward, on the curve
  EXPECT_DOUBLE_EQ(test::load_at(cat, 2.5, 0, -45), -275.0);             // reversed: the mirror image
  EXPECT_DOUBLE_EQ(test::load_at(cat, 2.5, 0, 45), -300.0);              // reversed while turning forward: held end
  EXPECT_EQ(test::load_at(cat, 3.5, 0, 45), 0.0);                        // open again
  EXPECT_EQ(m.breakpoints(10.0), (std::vector<double>{1.0, 2.0, 3.0}));
  EXPECT_DOUBLE_EQ(test::load_at(m.loads[3], 0, 0.05, 0), -25.0);
  EXPECT_EQ(m.loads[3].kind, LoadKind::position_table);
}

// Claim: ∂M/∂v and ∂M/∂q (Load::slopes_at) of every state-dependent load and of switched and
// reversed motors agree with central finite differences.
TEST(SignalCompile, LoadSlopesAgreeWithFiniteDifferences) {
  const Model m = compile_text("slopes.yaml", R"(  fan: {type: drag, body: R, coefficient: 0.02}
  eddy: {type: eddy-current-brake, body: R, breakdown_torque: 50 N*m, breakdown_speed: 20 rad/s}
  cat: {type: motor-table, body: R, points: [[0, 300], [90, 250], [100, 0]], direction: {type: step, before: 1, value: -1, time: 2 s}}
  lin: {type: motor-linear, body: R, stall_torque: 100, no_load_speed: 150, reverse: 2 s}
  kl: {type: motor-kloss, body: R, breakdown_torque: 700, breakdown_slip: 0.2, synchronous_speed: 100, reverse: 2 s}
  e: {type: expression, body: R, expression: "sin(phi)*omega^2 + t*phi"}
  sp: {type: table, over: speed, body: R, points: [[-5, 10], [5, -20], [50, 0]]}
  pos: {type: table, over: position, body: X, points: [[0, 0], [0.1, -50], [0.3, 10]]}
)");
  const double h = 1e-6;
  for (const Load& l : m.loads)
    for (double t : {1.0, 3.0})
      for (double q : {0.03, 0.2})
        for (double v : {-60.0, -7.0, 12.0, 47.0, 95.0}) {
          const double fv = (test::load_at(l, t, q, v + h) - test::load_at(l, t, q, v - h)) / (2 * h);
          const double fq = (test::load_at(l, t, q + h, v) - test::load_at(l, t, q - h, v)) / (2 * h);
          double dq, dv;
          test::load_slopes(l, t, q, v, &dq, &dv);
          EXPECT_NEAR(dv, fv, 1e-5 * std::max(1.0, std::abs(fv))) << l.name << " v " << v << " t " << t;
          EXPECT_NEAR(dq, fq, 1e-5 * std::max(1.0, std::abs(fq))) << l.name << " q " << q;
        }
}

// Claim: bad signal and load fields are located errors (file:line:col, what was expected), every one
// listed at once: wrong dimensions, a pulse wider than its period, a contactor signal that is not
// 0/1, a direction that is not ±1, an unknown expression name, a speed table with a jump.
TEST(SignalCompile, BadFieldsAreLocatedAndListedTogether) {
  const std::string all = errors_of("bad.yaml", R"(  a: {type: sine, body: R, amplitude: 2 N, frequency: 5 Hz}
  b: {type: pulse, body: R, high: 1, period: 0.2 s, width: 0.3 s}
  c: {type: motor-linear, body: R, stall_torque: 10, no_load_speed: 10, on: {type: ramp, value: 1, end: 1 s}}
  d: {type: motor-kloss, body: R, breakdown_torque: 10, breakdown_slip: 0.2, synchronous_speed: 10, direction: 2}
  e: {type: expression, body: X, expression: "omega*2"}
  f: {type: table, over: speed, body: R, points: [[0, 1], [0, 2]]}
  g: {type: sine, body: R, amplitude: 1, frequency: 2 m}
)");
  for (const char* want :
       {"bad.yaml:5:39: error: load 'a': field 'amplitude': expected a torque (N*m)",
        "bad.yaml:6:60: error: load 'b': field 'width' expected a time between 0 and the period (0.2 s)",
        "bad.yaml:7:77: error: load 'c': field 'on' expected a signal that is 0 (open) or 1 (closed)",
        "bad.yaml:8:112: error: load 'd': field 'direction' expected +1 (forward) or -1 (reversed)",
        "bad.yaml:9:46: error: load 'e': field 'expression' 'omega*2': at character 1: unknown name 'omega'; known: t, x, v,",
        "bad.yaml:10:60: error: load 'f': the first column must increase",
        "bad.yaml:11:53: error: load 'g': field 'frequency' expected a positive frequency (Hz)"})
    EXPECT_NE(all.find(want), std::string::npos) << want << "\n--- got:\n" << all;
  EXPECT_EQ(std::count(all.begin(), all.end(), '\n'), 6) << all;  // seven problems, one line each
}

// Claim: a motor's bare `on: 0` or `on: 1` (which read as "off"/"on" as often as "closes at t = 0",
// "at 1 s") or a yes/no word is a located error that names both explicit forms; `on: 0 s` closes the contactor
// at t = 0 (the motor drives from the start) and `on: {type: constant, value: 0}` keeps it off.
TEST(SignalCompile, BareOnIsAmbiguousAndRefused) {
  for (const char* v : {"0", "1", "false", "off"}) {
    const std::string all = errors_of("bare-on.yaml", std::string("  m: {type: motor-linear, body: R, stall_torque: 10 N*m, "
                                                                  "no_load_speed: 10 rad/s, on: ") + v + "}\n");
    EXPECT_NE(all.find("bare-on.yaml:5:87: error: load 'm': field 'on' is the time the contactor closes"),
              std::string::npos) << v << "\n" << all;
    EXPECT_NE(all.find("'on: 0 s'"), std::string::npos) << all;
    EXPECT_NE(all.find("'on: {type: constant, value: 0}'"), std::string::npos) << all;
  }
  auto torque = [](const char* on, double t = 0.0) {
    const Model m = compile_text("on.yaml", std::string("  m: {type: motor-linear, body: R, stall_torque: 10 N*m, "
                                                         "no_load_speed: 10 rad/s, on: ") + on + "}\n");
    return test::load_at(m.loads[0], t, 0.0, 0.0);
  };
  EXPECT_DOUBLE_EQ(torque("0 s"), 10.0);  // closed at t = 0: the stall torque at rest
  EXPECT_DOUBLE_EQ(torque("{type: constant, value: 0}"), 0.0);
  EXPECT_DOUBLE_EQ(torque("0.5"), 0.0);  // any other bare number is seconds, as before: closes at 0.5 s
  EXPECT_DOUBLE_EQ(torque("0.5", 1.0), 10.0);
}

// Claim: through the CLI a bad signal exits with code 2 and writes nothing.
TEST(SignalCompile, CliExitsTwoAndWritesNothing) {
  const auto path = test::write_temp("bad-cli.yaml", "bodies:\n  R: {inertia: 1}\nloads:\n"
                                                      "  a: {type: pulse, body: R, high: 1 N, period: 1 s, width: 2 s}\n");
  const auto out = test::temp_dir() / "bad-cli-out";
  const auto r = test::run_cli("simulate '" + path + "' -o '" + out.string() + "'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("bad-cli.yaml:4:"), std::string::npos) << r.err;
  EXPECT_FALSE(std::filesystem::exists(out / "timeseries.csv"));
}

}  // namespace
}  // namespace machdyn
