// The sway summary taken during the run (analysis/sway_summary.hpp: SwayObserver, SimulationResult::sway)
// against a second algorithm, the same definitions read off the run's time series column by column
// after the run; and a run that keeps no series gives the same summary, bit for bit, on several
// models (a point mass in the plane and in space, a jib, a rigid load on two ropes, wheel slip and
// buffers) and both integrators.
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/analysis/sway_summary.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/support.hpp"
#include "support/timed_model.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

const std::vector<double>* column_of(const SimulationResult& r, const std::string& name) {
  const auto it = std::find(r.column_names.begin(), r.column_names.end(), name);
  return it == r.column_names.end() ? nullptr : &r.columns[static_cast<size_t>(it - r.column_names.begin())];
}

/// The summary from the recorded series, one quantity at a time over all rows (the rule of
/// sway_summary.hpp): the sway columns x, y, radial, tangential in turn, the horizontal force, the
/// tension, and the suspension point's acceleration from the trolley's and bridge's velocity columns.
/// `mass` and `after` are the rope's (the model file's values), `travel` its travel bodies' names.
SwaySummary from_series(const SimulationResult& r, const std::string& rope, double mass, double after,
                        const std::vector<std::string>& travel) {
  SwaySummary s;
  s.rope = rope;
  if (after >= 0) s.residual_after = after;
  const std::vector<double>& t = *column_of(r, "t_s");
  for (const char* col : {"sway_x_rad", "sway_y_rad", "sway_radial_rad", "sway_tangential_rad"}) {
    const std::vector<double>* th = column_of(r, rope + "." + col);
    if (!th) continue;
    for (size_t k = 0; k < t.size(); ++k) {
      const double a = std::abs((*th)[k]);
      // A tie between two columns at different rows: the earliest row (no column in these models ties).
      if (a > s.max_sway_rad || (a == s.max_sway_rad && t[k] < s.t_max_sway)) s.max_sway_rad = a, s.t_max_sway = t[k];
      if (after >= 0 && t[k] >= after) s.residual_sway_rad = std::max(s.residual_sway_rad, a);
    }
  }
  const std::vector<double>& H = *column_of(r, rope + ".horizontal_force_N");
  for (size_t k = 0; k < t.size(); ++k)
    if (H[k] > s.max_horizontal_force_N) s.max_horizontal_force_N = H[k], s.t_max_horizontal_force = t[k];
  for (double F : *column_of(r, rope + ".tension_N")) s.max_tension_N = std::max(s.max_tension_N, F);
  double a_max = 0;
  for (size_t k = 1; k < t.size() && !travel.empty(); ++k) {
    const double dt = t[k] - t[k - 1];
    if (dt <= 0) continue;
    double a2 = 0;
    for (const auto& b : travel) {
      const std::vector<double>& v = *column_of(r, b + ".velocity_m_s");
      a2 += std::pow((v[k] - v[k - 1]) / dt, 2);
    }
    a_max = std::max(a_max, std::sqrt(a2));
  }
  if (a_max > 0) s.rigid_force_N = mass * a_max, s.dynamic_factor = s.max_horizontal_force_N / *s.rigid_force_N;
  return s;
}

/// The same bits in every field (EXPECT_EQ on doubles: ==).
void expect_same(const SwaySummary& a, const SwaySummary& b, const std::string& what) {
  EXPECT_EQ(a.rope, b.rope) << what;
  EXPECT_EQ(a.max_sway_rad, b.max_sway_rad) << what;
  EXPECT_EQ(a.t_max_sway, b.t_max_sway) << what;
  EXPECT_EQ(a.residual_after, b.residual_after) << what;
  EXPECT_EQ(a.residual_sway_rad, b.residual_sway_rad) << what;
  EXPECT_EQ(a.max_horizontal_force_N, b.max_horizontal_force_N) << what;
  EXPECT_EQ(a.t_max_horizontal_force, b.t_max_horizontal_force) << what;
  EXPECT_EQ(a.max_tension_N, b.max_tension_N) << what;
  EXPECT_EQ(a.rigid_force_N, b.rigid_force_N) << what;
  EXPECT_EQ(a.dynamic_factor, b.dynamic_factor) << what;
}

struct RopeOf {
  std::string name;
  double mass, after;
  std::vector<std::string> travel;
};

struct Runs {
  SimulationResult with_series, without;
};

/// The run with its series and the run that keeps none (a sweep's), both audited as in every test.
Runs both_runs(const Model& m) {
  SimulateOptions no_series;
  no_series.record_series = false;
  return {simulate(m), simulate(m, no_series)};
}

/// Checks both runs of `m` against from_series() for each rope, and the no-series run keeps no rows.
void check_model(const Model& m, const std::vector<RopeOf>& ropes, const std::string& what) {
  const Runs r = both_runs(m);
  ASSERT_EQ(r.with_series.sway.size(), ropes.size()) << what;
  ASSERT_EQ(r.without.sway.size(), ropes.size()) << what;
  for (const auto& col : r.without.columns) EXPECT_TRUE(col.empty()) << what << ": a series kept";
  EXPECT_EQ(r.without.stats.stepper.steps, r.with_series.stats.stepper.steps) << what;
  EXPECT_GT(column_of(r.with_series, "t_s")->size(), 100u) << what;
  for (size_t k = 0; k < ropes.size(); ++k) {
    const RopeOf& p = ropes[k];
    const SwaySummary ref = from_series(r.with_series, p.name, p.mass, p.after, p.travel);
    EXPECT_GT(ref.max_sway_rad, 1e-4) << what << ": the load swings";
    expect_same(r.with_series.sway[k], ref, what + ", " + p.name + " (series kept)");
    expect_same(r.without.sway[k], ref, what + ", " + p.name + " (no series)");
  }
  EXPECT_EQ(r.without.sway.size(), ropes.size()) << what;  // one summary per rope, in sway_rope_names' order
}

class SwaySummaryOnline : public ::testing::TestWithParam<IntegratorChoice> {
 protected:
  Model example_case(const std::string& file, const std::string& name) {
    Model m = load_model_case(test::example(file), {}, name);
    m.simulation.integrator = GetParam();
    return m;
  }
};
INSTANTIATE_TEST_SUITE_P(Integrators, SwaySummaryOnline,
                         ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf), test::IntegratorName{});

// Claim: a point mass in the xz-plane below a trolley with a PI speed drive (examples/crane/
// trolley-sway.yaml), unshaped and ZV: the run's summary equals the series' in every bit, with and
// without the series kept.
TEST_P(SwaySummaryOnline, TrolleyInThePlane) {
  const RopeOf rope{"rope", 40e3, 20.0, {"trolley"}};
  for (const char* c : {"unshaped", "zv"}) check_model(example_case("crane/trolley-sway.yaml", c), {rope}, c);
}

// Claim: the same with the drive line on the rail: the wheels slipping (contacts, events) and the
// trolley running into its end buffer (examples/crane/trolley-sway-drive.yaml, cases slip, buffer).
TEST_P(SwaySummaryOnline, DriveLineWithSlipAndBuffers) {
  const RopeOf rope{"rope", 40e3, 20.0, {"trolley"}};
  for (const char* c : {"slip", "buffer"}) check_model(example_case("crane/trolley-sway-drive.yaml", c), {rope}, c);
}

// Claim: a load in space below a bridge (y) and a trolley (x) moving together: two sway columns and
// the suspension point's acceleration from both travel bodies (examples/crane/bridge-trolley-sway.yaml).
TEST_P(SwaySummaryOnline, BridgeAndTrolleyInSpace) {
  check_model(example_case("crane/bridge-trolley-sway.yaml", "unshaped"), {{"rope", 40e3, 15.0, {"trolley", "bridge"}}},
              "unshaped");
}

// Claim: a slewing jib: the sway in x, y, radial and tangential, no dynamic factor (the point turns).
TEST_P(SwaySummaryOnline, SlewingJib) {
  const Model m = example_case("crane/slewing-jib-sway.yaml", "zv");
  check_model(m, {{"rope", 10e3, 45.0, {}}}, "zv");
}

// Claim: a rigid beam on two ropes of a free trolley pushed by a sine force (each rope its own
// summary; no `sway_after`: no residual).
TEST_P(SwaySummaryOnline, RigidLoadOnTwoRopes) {
  const std::string rope = "type: spatial-rope, load: beam, trolley: trolley, length: " + test::num(std::hypot(1.5, 6.0) - 1e-3) +
                           " m, EA: 5e8 N, damping: 2e4 N*s/m, height: 6.5 m";
  const Model m = test::timed_model("bodies:\n  trolley: {type: translational, mass: 4 t}\n"
                                    "  beam: {type: rigid-load, mass: 10 t, inertia: 3e4 kg*m^2, angular_velocity: 0.1}\n"
                                    "links:\n  left: {" + rope + ", attach: [-2.5 m, 0.5 m], offset: -1 m}\n"
                                    "  right: {" + rope + ", attach: [2.5 m, 0.5 m], offset: 1 m}\n"
                                    "loads:\n  push: {type: sine, body: trolley, amplitude: 20 kN, frequency: 0.4 Hz}\n",
                                    5.0, 1e-3, GetParam());
  check_model(m, {{"left", 10e3, -1, {"trolley"}}, {"right", 10e3, -1, {"trolley"}}}, "beam");
  EXPECT_FALSE(simulate(m).sway[0].residual_after.has_value());
}

}  // namespace MACHDYN_UNITY_ID
}  // namespace machdyn
