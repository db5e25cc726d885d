// Input shaping of a reference (model/shaper.hpp, `type: shaped` signals): the shaped table against
// a direct evaluation of Σ A_i s(t − t_i), and the residual swing of a load hanging from a trolley
// whose speed follows the reference (the linear pendulum: a mass on a spring c = m g/L) against
// the closed forms derived below, on both integrators.
#include <cmath>
#include <numbers>
#include <random>
#include <string>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/model/model.hpp"
#include "machdyn/model/shaper.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

constexpr double kPi = std::numbers::pi;

// Claim: ZV and ZVD impulses are the textbook ones: Σ A_i = 1; ZV at 0 and π/ω_d with
// A = [1, K]/(1 + K); ZVD at 0, π/ω_d, 2π/ω_d with [1, 2K, K²]/(1 + K)²; K = exp(−ζπ/√(1 − ζ²)).
TEST(Shaper, ImpulsesAreTheZvAndZvdShapers) {
  const double w = 2.0, z = 0.1, wd = w * std::sqrt(1 - z * z), K = std::exp(-z * kPi / std::sqrt(1 - z * z));
  const auto zv = shaper_impulses(ShaperKind::zv, w, z);
  ASSERT_EQ(zv.size(), 2u);
  EXPECT_DOUBLE_EQ(zv[0].time, 0.0);
  EXPECT_DOUBLE_EQ(zv[1].time, kPi / wd);
  EXPECT_DOUBLE_EQ(zv[0].amplitude, 1 / (1 + K));
  EXPECT_DOUBLE_EQ(zv[1].amplitude, K / (1 + K));
  const auto zvd = shaper_impulses(ShaperKind::zvd, w, z);
  ASSERT_EQ(zvd.size(), 3u);
  EXPECT_DOUBLE_EQ(zvd[2].time, 2 * kPi / wd);
  EXPECT_NEAR(zvd[0].amplitude + zvd[1].amplitude + zvd[2].amplitude, 1.0, 1e-15);
  EXPECT_DOUBLE_EQ(zvd[1].amplitude, 2 * K / ((1 + K) * (1 + K)));
  EXPECT_THROW(shaper_impulses(ShaperKind::zv, 0.0, 0.0), std::invalid_argument);
  EXPECT_THROW(shaper_impulses(ShaperKind::zv, 1.0, 1.0), std::invalid_argument);
}

// Claim: the shaped signal is Σ A_i s(t − t_i) exactly — compared with that sum evaluated directly at
// 2000 random times and 1e-9 s after and before every breakpoint (jumps kept, on their side), for a ramp, a sum of a step and a table with a jump, a finite pulse and an extrapolating table.
TEST(Shaper, ShapedSignalIsTheSumOfShiftedCopies) {
  const std::vector<Signal> refs = {
      Signal::ramp(0.2, 1.5, 0.5, 2.5),
      Signal::sum({Signal::step(0.0, 2.0, 1.0), Signal::table({0.0, 1.0, 1.0, 3.0}, {0.0, 1.0, -1.0, 0.5})}),
      Signal::pulse(0.0, 3.0, 1.5, 0.5, 0.2, 3),
      Signal::table({0.0, 1.0, 2.0}, {0.0, 1.0, 3.0}, true),
  };
  const auto p = shaper_impulses(ShaperKind::zvd, 1.7, 0.05);
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> t_of(-2.0, 12.0);
  for (const Signal& s : refs) {
    const Signal sh = shaped_signal(s, p);
    auto direct = [&](double t) {
      double v = 0;
      for (const auto& i : p) v += i.amplitude * s.value(t - i.time);
      return v;
    };
    for (int k = 0; k < 2000; ++k) {
      const double t = t_of(rng);
      EXPECT_NEAR(sh.value(t), direct(t), 1e-12) << s.describe("") << " at " << t;
    }
    for (double b : sh.breakpoints(-10, 20)) {
      EXPECT_NEAR(sh.value(b + 1e-9), direct(b + 1e-9), 1e-8) << s.describe("") << " after " << b;
      EXPECT_NEAR(sh.value(b - 1e-9), direct(b - 1e-9), 1e-8) << s.describe("") << " before " << b;
    }
  }
  EXPECT_THROW(shaped_signal(Signal::sine(1, 1, 0, 0, 0), p), std::invalid_argument);
  EXPECT_THROW(shaped_signal(Signal::pulse(0, 1, 1, 0.5, 0, -1), p), std::invalid_argument);
  EXPECT_NEAR(shaped_signal(Signal::constant(2.0), p).value(5.0), 2.0, 1e-15);
}

std::string full(double x) { return fmt::format("{:.17g}", x); }

// A trolley whose speed follows `speed` carries a load m on a rope of length L: in the linear pendulum
// the load's horizontal motion is that of a mass on a spring c = m g/L (and a damper d = 2 ζ √(c m)).
std::string trolley(const std::string& speed, double c, double d, double t_end) {
  return "bodies:\n  trolley: {type: translational, mass: 5000 kg, motion: {speed: " + speed +
         "}}\n  load: {type: translational, mass: 1000 kg}\nlinks:\n  rope: {type: spring-damper, between: [trolley, "
         "load], stiffness: " + full(c) + " N/m, damping: " + full(d) + " N*s/m}\nsimulation: {t_end: " +
         full(t_end) + " s, dt_out: 5 ms, rtol: 1e-10, atol: 1e-12}\n";
}

/// The largest free-swing amplitude of e = x_load − x_trolley after t0 (undamped: √(e² + (ė/ω)²)).
double residual(const SimulationResult& r, double omega, double t0) {
  const auto& t = test::series(r, "t_s");
  const auto& xl = test::series(r, "load.position_m");
  const auto& xt = test::series(r, "trolley.position_m");
  const auto& vl = test::series(r, "load.velocity_m_s");
  const auto& vt = test::series(r, "trolley.velocity_m_s");
  double a = 0;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] >= t0) a = std::max(a, std::hypot(xl[k] - xt[k], (vl[k] - vt[k]) / omega));
  return a;
}

class Shaping : public ::testing::TestWithParam<IntegratorChoice> {
 protected:
  SimulationResult run(const std::string& speed, double c, double d, double t_end) {
    Model m = test::model_text(trolley(speed, c, d, t_end));
    m.simulation.integrator = GetParam();
    return simulate(m);
  }
};
INSTANTIATE_TEST_SUITE_P(Integrators, Shaping, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

constexpr double kM = 1000.0, kL = 10.0, kV = 0.5, kTa = 2.0;
const std::string kRamp = "{type: ramp, value: 0.5 m/s, end: 2 s}";

// Claim: an unshaped speed ramp (a = V/T_a over [0, T_a]) leaves the load swinging with the closed-form
// amplitude, and a ZV shaper tuned to the pendulum (`length: 10 m`, ω² = g/L) leaves it at rest.
// Derivation: e = x_l − x_t obeys e'' + ω² e = −a on [0, T_a] (the trolley's acceleration), 0 after;
// from rest e = −(a/ω²)(1 − cos ωt), and after the ramp e = −(a/ω²)(cos ω(t − T_a) − cos ωt), of
// amplitude (2a/ω²)|sin(ωT_a/2)|. The ZV copies (½ at 0 and ½ at π/ω) swing in opposite phase: 0.
TEST_P(Shaping, ZvShapedRampLeavesNoSwingAndTheUnshapedOneTheClosedForm) {
  const double w = std::sqrt(kStandardGravity / kL), c = kM * w * w, a = kV / kTa;
  const double closed = 2 * a / (w * w) * std::abs(std::sin(w * kTa / 2));
  const double plain = residual(run(kRamp, c, 0, 12), w, kTa);
  EXPECT_NEAR(plain, closed, 1e-7 * closed);
  const double zv = residual(run("{type: shaped, shaper: zv, length: 10 m, signal: " + kRamp + "}", c, 0, 12), w,
                             kTa + kPi / w);
  EXPECT_LT(zv, 1e-7 * closed) << "unshaped " << closed;
}

// Claim: with the pendulum 10 % faster than the shaper's design (ω = 1.1 ω_m), the residual over the
// unshaped one is the shaper's vibration ratio V = |Σ A_i e^{iωt_i}|: for ZV (½ at 0, ½ at π/ω_m)
// |cos(θ/2)|, for ZVD (¼, ½, ¼ at 0, π/ω_m, 2π/ω_m) cos²(θ/2), θ = π ω/ω_m — so ZVD is the robust one.
TEST_P(Shaping, MistunedShapersLeaveTheirVibrationRatio) {
  const double wm = std::sqrt(kStandardGravity / kL), w = 1.1 * wm, c = kM * w * w, a = kV / kTa;
  const double plain = 2 * a / (w * w) * std::abs(std::sin(w * kTa / 2));
  const double th = kPi * w / wm;
  const std::string head = "{type: shaped, length: 10 m, signal: " + kRamp + ", shaper: ";
  const double zv = residual(run(head + "zv}", c, 0, 14), w, kTa + kPi / wm);
  const double zvd = residual(run(head + "zvd}", c, 0, 16), w, kTa + 2 * kPi / wm);
  EXPECT_NEAR(zv / plain, std::abs(std::cos(th / 2)), 1e-6);
  EXPECT_NEAR(zvd / plain, std::cos(th / 2) * std::cos(th / 2), 1e-6);
  EXPECT_LT(zvd, 0.2 * zv);
}

// Claim: on a damped pendulum (ζ = 0.05) a ZV shaper with `damping: 0.05` leaves it at rest, and one
// designed without damping does not (its copies' amplitudes and spacing are those of ζ = 0). The
// residual is read as max |e| + |ė|/ω after the move (both tend to 0 at rest).
TEST_P(Shaping, DampedZvCancelsADampedSwing) {
  const double w = std::sqrt(kStandardGravity / kL), c = kM * w * w, z = 0.05, d = 2 * z * std::sqrt(c * kM);
  const double t1 = kTa + kPi / (w * std::sqrt(1 - z * z));
  const std::string head = "{type: shaped, shaper: zv, length: 10 m, signal: " + kRamp;
  const double plain = residual(run(kRamp, c, d, 12), w, t1);
  const double tuned = residual(run(head + ", damping: 0.05}", c, d, 12), w, t1);
  const double untuned = residual(run(head + "}", c, d, 12), w, t1);
  EXPECT_LT(tuned, 1e-7 * plain);
  EXPECT_GT(untuned, 1e-2 * plain);
}

// Claim: the two-step acceleration with coasting — half the speed at the ramp's acceleration, coast,
// the other half from half a period after the start — leaves an undamped pendulum at rest (the two
// acceleration pulses' swings are equal and half a period apart), and the trolley's speed is the
// profile by hand: 0.125 m/s at 0.5 s, 0.25 m/s while coasting, 0.25 + a (t − π/ω) in the second step (t = 3.7 s), 0.5 m/s after.
TEST_P(Shaping, TwoStepAccelerationLeavesNoSwing) {
  const double w = std::sqrt(kStandardGravity / kL), c = kM * w * w, a = kV / kTa;
  const SimulationResult r = run("{type: shaped, shaper: two-step, length: 10 m, signal: " + kRamp + "}", c, 0, 12);
  EXPECT_LT(residual(r, w, kPi / w + 1), 1e-7 * 2 * a / (w * w));
  EXPECT_NEAR(test::at(r, "trolley.velocity_m_s", 0.5, 1e-3), 0.125, 1e-9);
  EXPECT_NEAR(test::at(r, "trolley.velocity_m_s", 2.0, 1e-3), 0.25, 1e-9);
  EXPECT_NEAR(test::at(r, "trolley.velocity_m_s", 3.7, 1e-3), 0.25 + a * (3.7 - kPi / w), 1e-9);
  EXPECT_NEAR(test::at(r, "trolley.velocity_m_s", 10.0, 1e-3), 0.5, 1e-9);
}

// Claim: the shipped example (examples/trolley-sway-shaped.yaml: 40 t on 12 m, 0 → 0.63 m/s in 3 s)
// swings on after the unshaped move by the closed form (2a/ω²)|sin(ω T_a/2)| (derived above; 0.502 m)
// and not after any shaped one (below 1e-6 m, 2e-6 of it).
TEST_P(Shaping, TheShippedExampleSwingsOnlyUnshaped) {
  const double w = std::sqrt(kStandardGravity / 12.0), a = 0.63 / 3.0;
  const double closed = 2 * a / (w * w) * std::abs(std::sin(w * 3.0 / 2));
  for (const char* c : {"unshaped", "zv", "zvd", "two_step"}) {
    Model m = load_model_case(test::example("trolley-sway-shaped.yaml"), {}, c);
    m.simulation.integrator = GetParam();
    const double res = residual(simulate(m), w, 3.0 + 2 * kPi / w);
    if (std::string(c) == "unshaped") EXPECT_NEAR(res, closed, 1e-6 * closed);
    else EXPECT_LT(res, 1e-6) << c;
  }
}

// Claim: `shaper: none` passes the reference through: the run is the unshaped model's, every column
// of every row the same bits, whether the design (a length, or a frequency and damping) is given or not.
TEST_P(Shaping, NoneIsTheUnshapedReference) {
  const double w = std::sqrt(kStandardGravity / kL), c = kM * w * w;
  const SimulationResult plain = run(kRamp, c, 0, 8);
  for (const std::string& none : {"{type: shaped, shaper: none, length: 10 m, signal: " + kRamp + "}",
                                  "{type: shaped, shaper: none, frequency: 0.2 Hz, damping: 0.1, signal: " + kRamp + "}",
                                  "{type: shaped, shaper: none, signal: " + kRamp + "}"}) {
    const SimulationResult r = run(none, c, 0, 8);
    ASSERT_EQ(r.column_names, plain.column_names) << none;
    ASSERT_GT(plain.columns[0].size(), 1000u);
    for (size_t j = 0; j < r.columns.size(); ++j) EXPECT_EQ(r.columns[j], plain.columns[j]) << none << ": " << r.column_names[j];
    EXPECT_EQ(r.stats.stepper.steps, plain.stats.stepper.steps) << none;
  }
  // and the shapers do change it (the comparison above can fail)
  EXPECT_NE(run("{type: shaped, shaper: zv, length: 10 m, signal: " + kRamp + "}", c, 0, 8).columns[1], plain.columns[1]);
}

// Claim: bad shaping is a located error naming what was expected.
TEST(Shaper, BadShapingIsALocatedError) {
  auto err = [](const std::string& speed) { return test::compile_errors(trolley(speed, 1000, 0, 5)); };
  const std::string kind = err("{type: shaped, shaper: zx, length: 10 m, signal: 1 m/s}");
  EXPECT_NE(kind.find("test.yaml:2:"), std::string::npos) << kind;
  for (const char* k : {"none", "zv", "zvd", "two-step"}) EXPECT_NE(kind.find(k), std::string::npos) << kind;
  // `none` needs no design, but one given is checked as for the others.
  EXPECT_EQ(err("{type: shaped, shaper: none, signal: 1 m/s}"), "");
  EXPECT_NE(err("{type: shaped, shaper: none, length: -1 m, signal: 1 m/s}").find("length"), std::string::npos);
  EXPECT_NE(err("{type: shaped, shaper: none, frequency: 0 Hz, signal: 1 m/s}").find("'frequency'"), std::string::npos);
  EXPECT_NE(err("{type: shaped, shaper: none, frequency: 1 Hz, damping: 2, signal: 1 m/s}").find("[0, 1)"),
            std::string::npos);
  EXPECT_NE(err("{type: shaped, shaper: none}").find("missing field 'signal'"), std::string::npos);
  EXPECT_NE(err("{type: shaped, shaper: none, length: 10 m, frequency: 1 Hz, signal: 1 m/s}").find("not both"),
            std::string::npos);
  EXPECT_NE(err("{type: shaped, shaper: zv, length: 10 m, frequency: 1 Hz, signal: 1 m/s}").find("not both"),
            std::string::npos);
  EXPECT_NE(err("{type: shaped, shaper: zv, frequency: 1 Hz, damping: 1, signal: 1 m/s}").find("[0, 1)"),
            std::string::npos);
  EXPECT_NE(err("{type: shaped, shaper: two-step, frequency: 1 Hz, damping: 0.1, signal: 1 m/s}").find("undamped"),
            std::string::npos);
  EXPECT_NE(err("{type: shaped, shaper: zv, frequency: 1 Hz, signal: {type: sine, amplitude: 1 m/s, frequency: 1 Hz}}")
                .find("piecewise-linear"),
            std::string::npos);
  EXPECT_NE(err("{type: shaped, shaper: zv, frequency: 1 Hz}").find("missing field 'signal'"), std::string::npos);
  EXPECT_NE(err("{type: shaped, shaper: two-step, frequency: 1 Hz, signal: {type: ramp, value: 1 m/s, end: 5 s}}")
                .find("no coasting"),
            std::string::npos);
  EXPECT_NE(err("{type: shaped, shaper: zv, length: -1 m, signal: 1 m/s}").find("length"), std::string::npos);
  // Shapers nested in shapers multiply the breakpoints by 2–3 each: bounded, an error, not a memory blow-up.
  std::string nested = "{type: pulse, high: 1 m/s, period: 1 s, width: 50 %, count: 20000}";
  for (int k = 0; k < 6; ++k) nested = "{type: shaped, shaper: zvd, frequency: 0.37 Hz, signal: " + nested + "}";
  EXPECT_NE(err(nested).find("too many breakpoints"), std::string::npos);
}

}  // namespace MACHDYN_UNITY_ID
}  // namespace machdyn
