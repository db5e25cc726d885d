// `machdyn modes` as a user runs it: every topology, --topology, --case, --from-run, the frequency
// response, frequencies over a machine's position, the Campbell diagram, and located errors.
#include <cmath>
#include <filesystem>
#include <numbers>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "machdyn/io/model_file.hpp"
#include "machdyn/model/machine.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

namespace fs = std::filesystem;

bool has_frequency(const nlohmann::json& topologies, double w) {
  for (const auto& t : topologies)
    for (const auto& x : t["frequencies_rad_s"])
      if (std::abs(x.get<double>() - w) <= 1e-10 * w) return true;
  return false;
}

// Claim: without --topology the travel drive's eight topologies are listed, and paper 001's ω2, ω3
// and ω4 are among their frequencies (to 1e-10); the first topology's fields stay at the top level.
TEST(ModesCli, ListsEveryTopologyOfTheTravelDrive) {
  const auto r = test::run_cli("modes '" + test::example("travel-start.yaml") + "' --json");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["topologies"].size(), 8u);
  const double c = 2.0e6, m1 = 3000, mk = 300, m2 = 10000;
  for (double w : {std::sqrt(c / m1), std::sqrt(c / m1 + c / (mk + m2)), std::sqrt(c / m1 + c / mk)})
    EXPECT_TRUE(has_frequency(j["topologies"], w)) << w;
  EXPECT_EQ(j["topology"], j["topologies"][0]["topology"]);
  EXPECT_EQ(j["frequencies_rad_s"], j["topologies"][0]["frequencies_rad_s"]);
}

// Claim: --topology analyses exactly the named state; --case applies the load case first (paper
// 002's brake on I2 splits the chain: √(c1/I1), √(c2/I3)).
TEST(ModesCli, TopologyAndCase) {
  auto r = test::run_cli("modes '" + test::example("travel-start.yaml") + "' --json --topology 'c=closed, W=slip+'");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  auto j = nlohmann::json::parse(r.out);
  ASSERT_EQ(j["topologies"].size(), 1u);
  EXPECT_EQ(j["topology"], "c=closed+, adhesion=stuck, W=slip+");
  EXPECT_NEAR(j["frequencies_rad_s"][0].get<double>(), std::sqrt(2e6 / 3000 + 2e6 / 10300), 1e-9);
  r = test::run_cli("modes '" + test::example("hoist-modes.yaml") + "' --json --case brake_I2_lifting --topology T=applied");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  j = nlohmann::json::parse(r.out);
  const double w1 = std::sqrt(2.4e4 / 0.80), w3 = std::sqrt(9.0e3 / 0.25);
  EXPECT_NEAR(j["frequencies_rad_s"][0].get<double>(), std::min(w1, w3), 1e-10 * w1);
  EXPECT_NEAR(j["frequencies_rad_s"][1].get<double>(), std::max(w1, w3), 1e-10 * w1);
  EXPECT_EQ(j["rigid_body_modes"], 0);
}

// Claim: a wrong topology exits 2 with every problem located in the option, and writes nothing.
TEST(ModesCli, BadTopologyExitsTwoLocatedAndWritesNothing) {
  const auto dir = test::temp_dir() / "modes-bad";
  const auto r = test::run_cli("modes '" + test::example("travel-start.yaml") + "' -o '" + dir.string() +
                               "' --topology 'wheel=stuck,c=shut'");
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_NE(r.err.find("--topology:1:1: error: no gap link, contact or brake 'wheel'"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("--topology:1:15: error: 'shut' is not a mode of gap link 'c'"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir));
  const auto o = test::run_cli("modes '" + test::example("hoist-3mass.yaml") + "' --frf Msp --output c9.load");
  EXPECT_EQ(o.exit_code, 2);
  EXPECT_NE(o.err.find("--output:1:1: error: no output 'c9.load'"), std::string::npos) << o.err;
  const auto w = test::run_cli("modes '" + test::example("hoist-3mass.yaml") + "' --frf Msp --omega 1:x");
  EXPECT_EQ(w.exit_code, 2);
  EXPECT_NE(w.err.find("--omega:1:3: error: 'x' is not a number"), std::string::npos) << w.err;
}

// Claim: --from-run lists the topologies of the simulated start-up with intervals that tile
// [0, t_end]; its first topology is the state at rest (gap open, all stuck).
TEST(ModesCli, FromRunGivesIntervals) {
  const auto r = test::run_cli("modes '" + test::example("travel-start.yaml") + "' --json --from-run");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  ASSERT_GE(j["topologies"].size(), 3u);
  EXPECT_EQ(j["topologies"][0]["topology"], "c=open, adhesion=stuck, W=stuck");
  double total = 0;
  for (const auto& t : j["topologies"])
    for (const auto& iv : t["intervals_s"]) total += iv[1].get<double>() - iv[0].get<double>();
  EXPECT_NEAR(total, 2.0, 1e-12);
  EXPECT_TRUE(has_frequency(j["topologies"], std::sqrt(2e6 / 3000 + 2e6 / 300)));
}

// Claim: --frf with -o writes frf.csv whose magnitudes are the JSON's, and the Campbell crossings
// lie where the order's line meets a natural frequency: speed = ω / order.
TEST(ModesCli, FrequencyResponseAndCampbellFiles) {
  const auto dir = test::temp_dir() / "modes-frf";
  const auto r = test::run_cli("modes '" + test::example("hoist-3mass.yaml") + "' --json -o '" + dir.string() +
                               "' --frf Msp --output c1.load --omega 10:1000:50 --campbell 0:3000 --order mesh=3");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto j = nlohmann::json::parse(r.out);
  const auto csv = test::lines_of(test::slurp(dir / "frf.csv"));
  ASSERT_EQ(csv.size(), 51u);
  EXPECT_EQ(csv[0], "omega_rad_s,f_Hz,c1.load.mag_N_m_per_N_m,c1.load.phase_deg");
  const double mag = std::stod(csv[1].substr(csv[1].find(',', csv[1].find(',') + 1) + 1));
  EXPECT_NEAR(mag, j["frequency_response"]["outputs"][0]["magnitude"][0].get<double>(), 1e-10 * mag);
  ASSERT_EQ(j["campbell"]["crossings"].size(), 2u);  // 3 × 3000 rpm = 150 Hz > both modes (29, 52 Hz)
  for (const auto& c : j["campbell"]["crossings"])
    EXPECT_NEAR(c["speed_rad_s"].get<double>(), c["omega_rad_s"].get<double>() / 3.0, 1e-12 * c["omega_rad_s"].get<double>());
  EXPECT_TRUE(fs::exists(dir / "modes.json"));
  EXPECT_TRUE(fs::exists(dir / "modes.csv"));
}

// Claim: a motor on a shaft of stiffness c driving a crank-slider has ω(q)² = c (1/I_m + 1/I(q)),
// I(q) the crank's reduced inertia at each position (the linearization at every point of the
// cycle); `--over crank` lists that over one revolution.
TEST(ModesCli, FrequenciesOverCrankPosition) {
  const std::string text = std::string("name: crank drive\nbodies:\n  motor: {type: rotational, inertia: 0.05 kg*m^2}\n") +
                           test::kCrankSliderBody + "links:\n  shaft: {type: spring, between: [motor, crank], stiffness: 2000 N*m/rad}\n";
  const std::string path = test::write_temp("crank-drive.yaml", text);
  const auto r = test::run_cli("modes '" + path + "' --json --over crank --points 13");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rows = nlohmann::json::parse(r.out)["frequencies_over_position"]["rows"];
  ASSERT_EQ(rows.size(), 13u);
  const Model m = load_model(path);
  const Machine& crank = *m.bodies[1].machine;
  double lo = INFINITY, hi = 0;
  for (const auto& row : rows) {
    double I, dI;
    crank.inertia(row["position"].get<double>(), &I, &dI);
    const double w = std::sqrt(2000 * (1 / 0.05 + 1 / I));
    EXPECT_NEAR(row["omega_rad_s"][0].get<double>(), w, 1e-10 * w);
    lo = std::min(lo, w), hi = std::max(hi, w);
  }
  EXPECT_GT(hi - lo, 1e-3 * hi);  // the frequency does vary over the cycle
}

// Claim: --plot writes the Bode figures next to the mode shapes.
TEST(ModesCli, PlotWritesBodeFigures) {
  if (!test::have_gnuplot()) GTEST_SKIP() << "gnuplot not installed (apt-get install gnuplot-nox)";
  const auto dir = test::temp_dir() / "modes-bode";
  const auto r = test::run_cli("modes '" + test::example("hoist-3mass.yaml") + "' --plot -o '" + dir.string() +
                               "' --frf Msp --campbell 0:1500 --order pole=2");
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"mode_shapes.svg", "bode_magnitude.svg", "bode_phase.png", "campbell.svg"})
    EXPECT_TRUE(fs::exists(dir / f)) << f;
}

}  // namespace
}  // namespace machdyn
