// Frequency response (analysis/frequency_response.hpp) against the closed form of a damped two-mass
// chain and against the steady state of a time integration with a harmonic load.
#include <cmath>
#include <complex>
#include <numbers>
#include <gtest/gtest.h>

#include "machdyn/analysis/frequency_response.hpp"
#include "machdyn/analysis/topology.hpp"
#include "machdyn/elements/linearize.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/solve/stepper.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using C = std::complex<double>;
constexpr double m1 = 2, m2 = 3, c = 5000, d = 40;
const char* kPair = R"(name: pair
bodies:
  m1: {type: translational, mass: 2 kg}
  m2: {type: translational, mass: 3 kg}
links:
  k: {type: spring-damper, between: [m1, m2], stiffness: 5000 N/m, damping: 40 N*s/m}
loads:
  F: {type: constant, body: m1, value: 1 N}
)";

/// Closed form for a force F̂ on m1 of the free pair, k* = c + iωd, x = x1 − x2:
///   −ω² m1 X1 = F̂ − k* X,   −ω² m2 X2 = k* X
/// ⇒ −ω² X = F̂/m1 − k* X (1/m1 + 1/m2) ⇒ X = (F̂/m1)/(k*/μ − ω²), μ = m1 m2/(m1 + m2).
/// Link load L = k* X; m2's speed V2 = iω X2 = iω k* X/(−ω² m2).
C link_load(double w) {
  const double mu = m1 * m2 / (m1 + m2);
  const C k(c, w * d);
  return k * (1.0 / m1) / (k / mu - w * w);
}
C speed2(double w) { return C(0, w) * link_load(w) / (-w * w * m2); }

// Claim: H from the force F on m1 to the link load and to m2's speed equals the closed form at
// frequencies around and far from resonance, to 1e-8 relative.
TEST(FrequencyResponse, TwoMassEqualsClosedForm) {
  const Model m = load_model(test::write_temp("pair.yaml", kPair));
  const Topology topo = initial_topology(m);
  const Location at{"test", 1, 1};
  const auto r = frequency_response(linearize(m, topo), linear_input(m, "F", at),
                                    {linear_output(m, topo, "k.load", at), linear_output(m, topo, "m2.speed", at)},
                                    frequency_grid(1.0, 1000.0, 301, true));
  for (Eigen::Index f = 0; f < r.omega.size(); ++f) {
    const double w = r.omega(f);
    EXPECT_LT(std::abs(r.H(f, 0) - link_load(w)), 1e-8 * std::abs(link_load(w))) << w;
    EXPECT_LT(std::abs(r.H(f, 1) - speed2(w)), 1e-8 * std::abs(speed2(w))) << w;
  }
  EXPECT_EQ(r.outputs[0].unit, "N");
  EXPECT_EQ(r.outputs[1].unit, "m/s");
  // One resonance of the link load, at the grid point where the closed form's |L| is largest
  // (with ζ ≈ 0.26 it lies below the undamped √(c/μ)).
  std::vector<ResonancePeak> peaks;
  for (const auto& p : resonance_peaks(r))
    if (p.output == 0) peaks.push_back(p);
  ASSERT_EQ(peaks.size(), 1u);
  Eigen::Index best = 0;
  for (Eigen::Index f = 0; f < r.omega.size(); ++f)
    if (std::abs(link_load(r.omega(f))) > std::abs(link_load(r.omega(best)))) best = f;
  EXPECT_EQ(peaks[0].omega, r.omega(best));
  EXPECT_EQ(peaks[0].output, 0);
}

// Claim: at ω = 0 the free pair has a rigid-body mode: the dynamic stiffness is singular, H is NaN
// (not a number that looks valid); with a stuck brake to the ground it is finite.
TEST(FrequencyResponse, SingularAtZeroFrequencyOfAFreeDrive) {
  const Model m = load_model(test::write_temp("pair.yaml", kPair));
  const Topology topo = initial_topology(m);
  const Location at{"test", 1, 1};
  const auto r = frequency_response(linearize(m, topo), linear_input(m, "m1", at), {linear_output(m, topo, "k.load", at)},
                                    Eigen::VectorXd::Zero(1));
  EXPECT_TRUE(std::isnan(r.H(0, 0).real()));
}

/// The free pair with a harmonic force F̂ sin(ωt) on m1, states [x1, x2, v1, v2] (the test's own
/// statement of the law, independent of the library's elements).
class HarmonicPair : public OdeSystem {
 public:
  explicit HarmonicPair(double w) : w_(w) {}
  int size() const override { return 4; }
  void rhs(double t, const double* y, double* f) override {
    const double L = c * (y[0] - y[1]) + d * (y[2] - y[3]);
    f[0] = y[2], f[1] = y[3];
    f[2] = (std::sin(w_ * t) - L) / m1;
    f[3] = L / m2;
  }

 private:
  double w_;
};

class FrequencyResponseSim : public ::testing::TestWithParam<Method> {};

// Claim: the steady-state amplitude of the link load under a unit harmonic force equals |H| to
// 1e-4 (and the phase to 1e-4 rad). The transient decays with σ = ζ ω_n ≈ 16.7 1/s, so after 1.6 s it
// is below 3e-12 of the start; the amplitude is the Fourier coefficient over the next 6 periods
// (the trapezoidal rule on 600 samples per period, exact for a periodic signal).
TEST_P(FrequencyResponseSim, SteadyStateAmplitudeEqualsFrf) {
  const Model m = load_model(test::write_temp("pair.yaml", kPair));
  const Topology topo = initial_topology(m);
  const Location at{"test", 1, 1};
  for (double w : {30.0, 64.0, 150.0}) {
    const auto r = frequency_response(linearize(m, topo), linear_input(m, "F", at), {linear_output(m, topo, "k.load", at)},
                                      Eigen::VectorXd::Constant(1, w));
    HarmonicPair sys(w);
    StepperOptions opt;
    opt.rtol = 1e-11, opt.atol = 1e-13;
    auto st = make_stepper(GetParam(), sys, opt);
    const double y0[4] = {0, 0, 0, 0};
    st->reset(0.0, y0);
    const double T = 2 * std::numbers::pi / w, t0 = 1.6;
    const int per = 600, N = 6 * per;
    double a = 0, b = 0, y[4];
    int j = 0;
    while (j < N) {
      st->step(t0 + N * T / per + 1e-9);
      for (; j < N && t0 + j * T / per <= st->t(); ++j) {
        const double t = t0 + j * T / per;
        st->interpolate(t, y);
        const double L = c * (y[0] - y[1]) + d * (y[2] - y[3]);
        a += L * std::sin(w * t), b += L * std::cos(w * t);
      }
    }
    a *= 2.0 / N, b *= 2.0 / N;  // L ≈ a sin ωt + b cos ωt = Im(H e^{iωt}): a = Re H, b = Im H
    const double amp = std::hypot(a, b);
    EXPECT_NEAR(amp, std::abs(r.H(0, 0)), 1e-4 * amp) << w;
    EXPECT_NEAR(std::atan2(b, a), std::arg(r.H(0, 0)), 1e-4) << w;
  }
}

INSTANTIATE_TEST_SUITE_P(Integrators, FrequencyResponseSim, ::testing::Values(Method::dopri5, Method::bdf),
                         [](const auto& p) { return p.param == Method::bdf ? "bdf" : "dopri5"; });

// Claim: unknown inputs and outputs are input errors at the given place, naming what is expected.
TEST(FrequencyResponse, UnknownSignalsAreLocatedInputErrors) {
  const Model m = load_model(test::write_temp("pair.yaml", kPair));
  const Topology topo = initial_topology(m);
  const Location at{"--input", 1, 1};
  try {
    (void)linear_input(m, "nope", at);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--input:1:1"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("m1"), std::string::npos) << e.what();
  }
  EXPECT_THROW((void)linear_output(m, topo, "k.speed", at), InputError);
  EXPECT_THROW((void)linear_output(m, topo, "m1.load", at), InputError);
  EXPECT_THROW((void)linear_output(m, topo, "zz.position", at), InputError);
}

}  // namespace
}  // namespace machdyn
