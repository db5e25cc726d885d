// Buffer characteristics (`buffers:` `characteristic:`, law in elements/link.hpp): progressive,
// hydraulic and table buffers against closed forms and an RK4 + bisection written here, on both
// integrators; the crane analysis' ξb from each characteristic; located errors of bad input.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>
#include <gtest/gtest.h>

#include "support/support.hpp"

#include "machdyn/analysis/crane.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

Model model_of(const std::string& yaml) { return compile_model(parse_yaml_string(yaml, "buffer.yaml"), "buffer.yaml"); }

const std::vector<double>& column(const SimulationResult& r, const std::string& start) {
  for (size_t c = 0; c < r.column_names.size(); ++c)
    if (r.column_names[c].rfind(start, 0) == 0) return r.columns[c];
  ADD_FAILURE() << "no column " << start;
  static const std::vector<double> none;
  return none;
}

const CraneFactorRow& phi7_row(const CraneReport& r) {
  for (const auto& x : r.rows)
    if (x.factor == "phi7") return x;
  ADD_FAILURE() << "no phi7 row";
  static const CraneFactorRow none;
  return none;
}

class BufferShape : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, BufferShape, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

// The trolley m at v0 runs into a buffer at x_b = 0.3 m (contact at t_c = x_b / v0 = 0.25 s).
constexpr double kM = 2000.0, kV0 = 1.2, kXb = 0.3, kTc = kXb / kV0;

std::string trolley(const std::string& buffer, const std::string& sim) {
  return "bodies: {trolley: {type: translational, mass: 2000 kg, velocity: 1.2 m/s}}\n"
         "buffers: {east: {body: trolley, max: 0.3 m, " + buffer + "}}\n"
         "simulation: {" + sim + ", rtol: 1e-11, atol: 1e-12}\n"
         "crane: {buffers: [east]}\n";
}

// Claim: a progressive buffer F = c sⁿ (through F_ref at s_ref: c = F_ref / s_refⁿ) stops the rigid
// mass where its elastic energy equals the kinetic one: ½ m v0² = c s_maxⁿ⁺¹/(n + 1), so
// s_max = ((n + 1) m v0² / (2 c))^(1/(n+1)) and F_max = c s_maxⁿ (to 1e-9). Without damping it returns
// the mass at −v0. The energy books hold V = c sⁿ⁺¹/(n + 1) mid-contact: T + V = ½ m v0². The crane
// row: ξb = 1/(n + 1) (the area c sⁿ⁺¹/(n+1) over the rectangle c sⁿ · s), φ7 = 1.25 (ξb ≤ 0.5).
TEST_P(BufferShape, ProgressiveMatchesTheEnergyBalance) {
  const double n = 2.5, c = 2e5 / std::pow(0.1, n);
  Model m = model_of(trolley("characteristic: progressive, exponent: 2.5, force: 200 kN, stroke: 0.1 m",
                             "t_end: 1 s, dt_out: 1 ms"));
  m.simulation.integrator = GetParam();
  const double s_max = std::pow((n + 1) * kM * kV0 * kV0 / (2 * c), 1 / (n + 1)), F_max = c * std::pow(s_max, n);
  const SimulationResult res = simulate(m);
  EXPECT_NEAR(res.links[0].max, F_max, 1e-9 * F_max);
  EXPECT_GE(res.links[0].min, -1e-9 * F_max);
  EXPECT_NEAR(column(res, "trolley.velocity_").back(), -kV0, 1e-8 * kV0);
  const CraneReport report1 = crane_analysis(m);
  const CraneFactorRow& x = phi7_row(report1);
  EXPECT_NEAR(x.simulated, 1.0, 1e-9);  // its own rigid-body reference
  EXPECT_EQ(x.standard_lo, 1.25);
  EXPECT_NE(x.clause.find("xi_b = 0.2857 = 1/(n + 1)"), std::string::npos) << x.clause;

  // Mid-contact (t_end 0.28 s): T + V = ½ m v0² with V = c eⁿ⁺¹/(n + 1), e = x − x_b.
  m.simulation.t_end = 0.28;
  const SimulationResult mid = simulate(m);
  const double e = column(mid, "trolley.position_").back() - kXb, v = column(mid, "trolley.velocity_").back();
  ASSERT_GT(e, 0.0);
  const EnergyBalance& E = mid.hybrid.energy;
  EXPECT_NEAR(E.elastic_end, c * std::pow(e, n + 1) / (n + 1), 1e-9 * 0.5 * kM * kV0 * kV0);
  EXPECT_NEAR(E.kinetic_end, 0.5 * kM * v * v, 1e-9 * 0.5 * kM * kV0 * kV0);
  EXPECT_NEAR(E.kinetic_end + E.elastic_end, 0.5 * kM * kV0 * kV0, 1e-9 * 0.5 * kM * kV0 * kV0);
  EXPECT_NEAR(E.residual(), 0.0, 1e-9 * 0.5 * kM * kV0 * kV0);
}

// Claim: a hydraulic buffer F = k v² (no return spring) gives m v′ = −k v², i.e. m v dv/ds = −k v²:
// v(s) = v0 exp(−k s / m), and in time s(τ) = (m/k) ln(1 + k v0 τ / m) (τ = t − t_c). Every output
// sample in contact lies on v(s) (to 1e-8 v0). The damper's books: dissipated ½ m v0² (1 − e^(−2kS/m))
// at the stroke S = s(t_end − t_c). ξb from the run's force–stroke curve F = k v0² e^(−2ks/m) over
// [0, S]: ∫F ds / (F(0) S) = m (1 − e^(−2kS/m)) / (2 k S); φ7 = 1.25 + 0.7 (ξb − 0.5) for ξb > 0.5.
TEST_P(BufferShape, HydraulicFollowsTheExponentialSpeedLaw) {
  const double k = 2e4;
  Model m = model_of(trolley("characteristic: hydraulic, hydraulic_damping: 2e4 N*s^2/m^2",
                             "t_end: 0.3 s, dt_out: 0.1 ms"));
  m.simulation.integrator = GetParam();
  const SimulationResult res = simulate(m);
  const auto& x = column(res, "trolley.position_");
  const auto& v = column(res, "trolley.velocity_");
  int inside = 0;
  for (size_t j = 0; j < x.size(); ++j) {
    const double s = x[j] - kXb;
    if (s <= 0.0) continue;
    ++inside;
    EXPECT_NEAR(v[j], kV0 * std::exp(-k * s / kM), 1e-8 * kV0) << "s = " << s;
  }
  EXPECT_GT(inside, 400);
  const double S = kM / k * std::log(1 + k * kV0 * (0.3 - kTc) / kM);
  EXPECT_NEAR(x.back() - kXb, S, 1e-9 * S);
  const double T0 = 0.5 * kM * kV0 * kV0;
  EXPECT_NEAR(res.hybrid.energy.damping_loss, T0 * (1 - std::exp(-2 * k * S / kM)), 1e-8 * T0);
  EXPECT_NEAR(res.hybrid.energy.residual(), 0.0, 1e-8 * T0);
  EXPECT_NEAR(res.links[0].max, k * kV0 * kV0, 1e-9 * k * kV0 * kV0);  // at first contact
  const CraneReport report2 = crane_analysis(m);
  const CraneFactorRow& r = phi7_row(report2);
  const double xi = kM * (1 - std::exp(-2 * k * S / kM)) / (2 * k * S);
  ASSERT_GT(xi, 0.5);
  // The run's curve is its 0.1 ms output samples (trapezoids, F(0) extrapolated): 1e-5.
  EXPECT_NEAR(r.standard_lo, 1.25 + 0.7 * (xi - 0.5), 1e-5);
  EXPECT_NE(r.clause.find("run's force-stroke curve"), std::string::npos) << r.clause;
}

// The table of the next test: (s, F) in m and N, concave (ξb > 1/2).
const std::vector<double> kS{0.0, 0.01, 0.03, 0.08}, kF{0.0, 40e3, 70e3, 90e3};
double table_force(double s) {
  size_t j = 0;
  while (j + 2 < kS.size() && s >= kS[j + 1]) ++j;
  return kF[j] + (kF[j + 1] - kF[j]) / (kS[j + 1] - kS[j]) * (s - kS[j]);
}

// Claim: a table buffer F(s) (linear pieces) matches an RK4 of m s″ = −F(s) from (0, v0), whose step
// where s′ changes sign is bisected for the time and stroke of the stop: F_max = F(s_max) to 1e-9, its
// time to 1e-7 s, the rebound at −v0 (elastic). ξb = ∫₀^s_max F ds / (F(s_max) s_max) by the pieces'
// trapezoids, φ7 = 1.25 + 0.7 (ξb − 0.5).
TEST_P(BufferShape, TableMatchesRk4WithBisection) {
  Model m = model_of(trolley("characteristic: table, table: [[0, 0], [10 mm, 40 kN], [0.03 m, 70 kN], [0.08 m, 90 kN]]",
                             "t_end: 0.6 s, dt_out: 0.1 ms"));
  m.simulation.integrator = GetParam();
  // RK4 on y = (s, v) in contact; h = 1 µs.
  auto f = [](double s, double v, double* ds, double* dv) { *ds = v, *dv = -table_force(s) / kM; };
  auto step = [&](double s, double v, double h, double* s1, double* v1) {
    double k1s, k1v, k2s, k2v, k3s, k3v, k4s, k4v;
    f(s, v, &k1s, &k1v);
    f(s + 0.5 * h * k1s, v + 0.5 * h * k1v, &k2s, &k2v);
    f(s + 0.5 * h * k2s, v + 0.5 * h * k2v, &k3s, &k3v);
    f(s + h * k3s, v + h * k3v, &k4s, &k4v);
    *s1 = s + h / 6 * (k1s + 2 * k2s + 2 * k3s + k4s);
    *v1 = v + h / 6 * (k1v + 2 * k2v + 2 * k3v + k4v);
  };
  double s = 0.0, v = kV0, t = 0.0;
  const double h = 1e-6;
  for (;;) {
    double s1, v1;
    step(s, v, h, &s1, &v1);
    if (v1 <= 0.0) {  // bisect the step for v = 0
      double lo = 0.0, hi = h;
      for (int it = 0; it < 60; ++it) {
        const double mid = 0.5 * (lo + hi);
        step(s, v, mid, &s1, &v1);
        (v1 > 0.0 ? lo : hi) = mid;
      }
      step(s, v, lo, &s1, &v1);
      s = s1, t += lo;
      break;
    }
    s = s1, v = v1, t += h;
  }
  const double F_max = table_force(s);
  const SimulationResult res = simulate(m);
  EXPECT_NEAR(res.links[0].max, F_max, 1e-9 * F_max);
  EXPECT_NEAR(res.links[0].t_max, kTc + t, 1e-7);
  EXPECT_NEAR(column(res, "trolley.velocity_").back(), -kV0, 1e-8 * kV0);
  double V = 0.0;  // ∫₀^s F by the pieces' trapezoids (exact for linear pieces)
  for (size_t j = 0; j + 1 < kS.size() && kS[j] < s; ++j) {
    const double b = std::min(kS[j + 1], s);
    V += 0.5 * (kF[j] + table_force(b)) * (b - kS[j]);
  }
  EXPECT_NEAR(V, 0.5 * kM * kV0 * kV0, 1e-8 * V);  // the RK4's own energy check
  const double xi = V / (F_max * s);
  ASSERT_GT(xi, 0.5);
  const CraneReport report3 = crane_analysis(m);
  const CraneFactorRow& r = phi7_row(report3);
  EXPECT_NEAR(r.standard_lo, 1.25 + 0.7 * (xi - 0.5), 1e-5);  // s_max on the 0.1 ms output grid
  EXPECT_NEAR(r.simulated, 1.0, 1e-9);
}

// Claim: a lower hydraulic buffer with a return spring pushes the body back out: the contact ends
// where F = c e + k ė|ė| reaches 0 (before e = 0, as the throttle resists the return), the buffer never
// pulls, and the energy books balance (V = ½ c e², dissipation k |ė|³).
TEST_P(BufferShape, HydraulicWithReturnSpringReleasesAtZeroForce) {
  Model m = model_of(R"(
bodies: {trolley: {type: translational, mass: 1000 kg, velocity: -1 m/s}}
buffers: {west: {body: trolley, min: -0.1 m, characteristic: hydraulic, hydraulic_damping: 1e4 N*s^2/m^2, stiffness: 1e5 N/m}}
simulation: {t_end: 1 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}
)");
  m.simulation.integrator = GetParam();
  const SimulationResult res = simulate(m);
  EXPECT_GE(res.links[0].min, -1e-7 * res.links[0].max);
  const double T0 = 0.5 * 1000 * 1.0;
  EXPECT_GT(res.hybrid.energy.damping_loss, 0.01 * T0);
  EXPECT_NEAR(res.hybrid.energy.residual(), 0.0, 1e-8 * T0);
  EXPECT_NEAR(res.hybrid.energy.elastic_end, 0.0, 1e-12 * T0);  // released: no spring energy left
  EXPECT_GT(column(res, "trolley.velocity_").back(), 0.0);       // moving away
}

// Claim: bad characteristics are located errors, listed together: an exponent ≤ 1, a table whose
// strokes do not increase, a table not starting at [0, 0], a negative force, an unknown word, a
// hydraulic buffer without its coefficient.
TEST(BufferInput, BadCharacteristicsAreLocated) {
  try {
    model_of(R"(
bodies: {a: {type: translational, mass: 1}}
buffers:
  p: {body: a, max: 1 m, characteristic: progressive, exponent: 1, force: 1 kN, stroke: 0.1 m}
  t1: {body: a, max: 1 m, characteristic: table, table: [[0, 0], [0.2 m, 5 kN], [0.1 m, 6 kN]]}
  t2: {body: a, max: 1 m, characteristic: table, table: [[0.01 m, 0], [0.2 m, 5 kN]]}
  t3: {body: a, max: 1 m, characteristic: table, table: [[0, 0], [0.2 m, -5 kN]]}
  w: {body: a, max: 1 m, characteristic: cubic}
  h: {body: a, max: 1 m, characteristic: hydraulic}
)");
    FAIL() << "no error";
  } catch (const InputError& e) {
    const std::string s = e.what();
    EXPECT_NE(s.find("buffer.yaml:4:"), std::string::npos) << s;
    EXPECT_NE(s.find("must be > 1"), std::string::npos) << s;
    EXPECT_NE(s.find("buffer.yaml:5:"), std::string::npos) << s;
    EXPECT_NE(s.find("the strokes must increase, got 0.1 after 0.2"), std::string::npos) << s;
    EXPECT_NE(s.find("buffer.yaml:6:"), std::string::npos) << s;
    EXPECT_NE(s.find("starts at [0, 0]"), std::string::npos) << s;
    EXPECT_NE(s.find("buffer.yaml:7:"), std::string::npos) << s;
    EXPECT_NE(s.find("must be >= 0, got -5000"), std::string::npos) << s;
    EXPECT_NE(s.find("buffer.yaml:8:"), std::string::npos) << s;
    EXPECT_NE(s.find("cubic"), std::string::npos) << s;
    EXPECT_NE(s.find("buffer.yaml:9:"), std::string::npos) << s;
    EXPECT_NE(s.find("hydraulic_damping"), std::string::npos) << s;
  }
}

}  // namespace
}  // namespace machdyn
