// A speed drive on its torque limit (elements/speed_drive.hpp, mode on-limit±): where the held
// integral pulls the command inside the limit and the integrating one pushes it out again, the
// drive stays on the limit (Filippov) instead of chattering between `linear` and `limited`.
#include <array>
#include <cmath>
#include <string>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "support/rk4.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// A free rotor (J = 1 kg·m²) run up by a speed drive along the ramp ω_ref = α t, α = 50 rad/s²:
// K_p = 20 N·m·s/rad, T_i = 0.05 s, M_max = 100 N·m, torque lag T_m = 0.05 s. The lag lets the
// speed error grow until the command reaches the limit; there the torque (still rising towards
// M_max > J α) already accelerates the rotor faster than the ramp, so held the command would fall
// back (K_p ė < 0), integrating it would rise (K_p ė + (K_p/T_i) e > 0): the drive is on the limit.
constexpr double kJ = 1.0, kAlpha = 50.0, kKp = 20.0, kTi = 0.05, kMmax = 100.0, kTm = 0.05, kTend = 0.8;

const char* kModel = R"(name: on the limit
bodies: {rotor: {inertia: 1 kg*m^2}}
drives:
  S: {type: speed-drive, body: rotor, reference: {type: ramp, value: 50 rad/s, end: 1 s}, gain: 20 N*m*s/rad,
      integral_time: 0.05 s, torque_limit: 100 N*m, rise_time: 0.05 s}
)";

// The reference solution, independent of the library's engine: fixed-step RK4 (h = 1e-5 s) on
// y = (ω, x_I, M) with the three laws written out, switches located by bisection of the step on
// the switching function (to 1e-14 s):
//   linear:    ω' = M/J, x_I' = (K_p/T_i) e, M' = (K_p e + x_I − M)/T_m,  e = α t − ω
//   limited:   x_I' = 0, M' = (M_max − M)/T_m
//   on-limit:  x_I' = −K_p ė = K_p (M/J − α), M' = (M_max − M)/T_m
// linear → (command K_p e + x_I reaches M_max): limited if held it stays out (K_p ė ≥ 0), else
// on-limit; on-limit → linear when K_p ė + (K_p/T_i) e reaches 0, → limited when K_p ė reaches 0.
struct Reference {
  enum Mode { linear, limited, on_limit };
  std::vector<std::pair<double, Mode>> switches;
  std::array<double, 3> end{};

  static double e(double t, const std::array<double, 3>& y) { return kAlpha * t - y[0]; }
  static double e_dot(const std::array<double, 3>& y) { return kAlpha - y[2] / kJ; }
  static std::array<double, 3> rate(Mode md, double t, const std::array<double, 3>& y) {
    const double err = e(t, y);
    if (md == linear) return {y[2] / kJ, kKp / kTi * err, (kKp * err + y[1] - y[2]) / kTm};
    return {y[2] / kJ, md == on_limit ? -kKp * e_dot(y) : 0.0, (kMmax - y[2]) / kTm};
  }
  static std::array<double, 3> rk4(Mode md, double t, const std::array<double, 3>& y, double h) {
    return test::rk4_step([md](double s, const std::array<double, 3>& z) { return rate(md, s, z); }, t, y, h);
  }
  // The switching function of mode md that ends it (< 0: it has ended), and the mode after.
  static double guard(Mode md, double t, const std::array<double, 3>& y, Mode* next) {
    switch (md) {
      case linear: *next = kKp * e_dot(y) >= 0 ? limited : on_limit; return kMmax - (kKp * e(t, y) + y[1]);
      case limited: {
        *next = kKp * e_dot(y) + kKp / kTi * e(t, y) > 0 ? on_limit : linear;
        return kKp * e(t, y) + y[1] - kMmax;
      }
      case on_limit: {
        const double g_lin = kKp * e_dot(y) + kKp / kTi * e(t, y), g_held = -kKp * e_dot(y);
        *next = g_lin < g_held ? linear : limited;
        return std::min(g_lin, g_held);
      }
    }
    return 1.0;
  }

  Reference() {
    const double h = 1e-5;
    Mode md = linear;
    std::array<double, 3> y{0.0, 0.0, 0.0};
    double t = 0.0;
    while (t < kTend - 1e-12) {
      const double step = std::min(h, kTend - t);
      Mode next = md;
      const auto y1 = rk4(md, t, y, step);
      if (guard(md, t + step, y1, &next) >= 0.0) {
        y = y1, t += step;
        continue;
      }
      double lo = 0.0, hi = step;  // the switch lies in (t + lo, t + hi]
      while (hi - lo > 1e-14) {
        const double mid = 0.5 * (lo + hi);
        (guard(md, t + mid, rk4(md, t, y, mid), &next) >= 0.0 ? lo : hi) = mid;
      }
      y = rk4(md, t, y, hi), t += hi;
      guard(md, t, y, &next);
      md = next;
      switches.emplace_back(t, md);
    }
    end = y;
  }
};

class DriveOnLimit : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, DriveOnLimit, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

// Claim: the run goes linear → on-limit+ → linear at the instants of the independent reference (to
// 1e-10 s, about 1e-9 relative), reports mode +2 on the limit without chattering, and ends at the
// reference's speed and torque (to 1e-8 relative) on both integrators. Before the on-limit mode this
// model stopped with "chattering: 50 mode switches" at the first switch.
TEST_P(DriveOnLimit, StaysOnTheLimitAndLeavesWhereTheReferenceDoes) {
  const Reference ref;
  ASSERT_EQ(ref.switches.size(), 2u) << "the reference itself must be linear → on-limit → linear";
  ASSERT_EQ(ref.switches[0].second, Reference::on_limit);
  ASSERT_EQ(ref.switches[1].second, Reference::linear);

  Model m = compile_model_case(parse_yaml_string(std::string(kModel) +
                                                     "simulation: {t_end: 0.8 s, dt_out: 1 ms, rtol: 1e-11, atol: 1e-12}\n",
                                                 "limit.yaml"),
                               "limit.yaml", {}, "");
  m.simulation.integrator = GetParam();
  const SimulationResult r = simulate(m);
  std::vector<std::pair<double, std::string>> seen;
  for (const auto& e : r.hybrid.events)
    if (e.element == "S" && e.kind != "initial") seen.emplace_back(e.t, e.to);
  ASSERT_EQ(seen.size(), 2u);
  EXPECT_EQ(seen[0].second, "on-limit+");
  EXPECT_EQ(seen[1].second, "linear");
  EXPECT_NEAR(seen[0].first, ref.switches[0].first, 1e-10);
  EXPECT_NEAR(seen[1].first, ref.switches[1].first, 1e-10);
  // On the limit the lagged torque rises towards M_max with time constant T_m and mode is +2.
  const auto& mode = test::series(r, "S.mode");
  const auto& ts = test::series(r, "t_s");
  for (size_t i = 0; i < ts.size(); ++i)
    if (ts[i] > seen[0].first + 1e-6 && ts[i] < seen[1].first - 1e-6) {
      EXPECT_EQ(mode[i], 2.0) << "t = " << ts[i];
    }
  EXPECT_NEAR(test::series(r, "rotor.velocity_rad_s").back(), ref.end[0], 1e-8 * ref.end[0]);
  EXPECT_NEAR(test::series(r, "S.torque_N_m").back(), ref.end[2], 1e-8 * ref.end[2]);
}

}  // namespace
}  // namespace machdyn
