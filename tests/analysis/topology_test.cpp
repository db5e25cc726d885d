// Topologies by name (analysis/topology.hpp): the --topology syntax and its errors, every topology
// of a model, and the topologies a simulation of paper 001's travel drive passes through.
#include <algorithm>
#include <cmath>
#include <set>
#include <gtest/gtest.h>

#include "machdyn/analysis/modal.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/analysis/topology.hpp"
#include "machdyn/elements/linearize.hpp"
#include "machdyn/io/model_file.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// Claim: the words set the modes they name; unnamed elements keep the initial state's modes.
TEST(Topology, ParsesModeWords) {
  const Model m = load_model(test::example("travel-start.yaml"));
  const Topology t = parse_topology(m, " c = closed- ,W=released", Location{"--topology", 1, 0});
  EXPECT_EQ(t.gaps[0], GapMode::closed_neg);
  EXPECT_EQ(t.contacts[0], ContactMode::stuck);  // adhesion: initial (at rest)
  EXPECT_EQ(t.engaged, (std::vector<bool>{true, false}));
  EXPECT_EQ(topology_label(m, t), "c=closed-, adhesion=stuck, W=released");
  EXPECT_EQ(topology_label(m, parse_topology(m, "adhesion=sliding", Location{"--topology", 1, 0})),
            "c=open, adhesion=slip+, W=stuck");
}

// Claim: every problem of a topology text is reported at once, each at its column: an unknown
// element, a wrong mode word, a link without a gap, an entry without '='.
TEST(Topology, ReportsEveryProblemAtItsColumn) {
  const Model m = load_model(test::example("travel-start.yaml"));
  try {
    (void)parse_topology(m, "wheel=stuck,c=shut,adhesion,W=slip+", Location{"--topology", 1, 0});
    FAIL() << "no error";
  } catch (const InputError& e) {
    ASSERT_EQ(e.diagnostics().size(), 3u) << e.what();
    EXPECT_EQ(e.diagnostics()[0].where.column, 1);
    EXPECT_NE(e.diagnostics()[0].message.find("'wheel'"), std::string::npos);
    EXPECT_NE(e.diagnostics()[0].message.find("c, adhesion, W"), std::string::npos);
    EXPECT_EQ(e.diagnostics()[1].where.column, 15);  // the word "shut"
    EXPECT_NE(e.diagnostics()[1].message.find("open, closed"), std::string::npos);
    EXPECT_EQ(e.diagnostics()[2].where.column, 20);
  }
  const Model h = load_model(test::example("hoist-3mass.yaml"));
  try {
    (void)parse_topology(h, "c1=closed", Location{"--topology", 1, 0});
    FAIL() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("has no gap"), std::string::npos) << e.what();
  }
}

// Claim: k switching elements give 2^k listed topologies, all distinct.
TEST(Topology, ListsEveryCombination) {
  const Model m = load_model(test::example("travel-start.yaml"));
  const auto all = all_topologies(m);
  ASSERT_EQ(all.size(), 8u);
  std::set<std::string> labels;
  for (const auto& t : all) labels.insert(topology_label(m, t));
  EXPECT_EQ(labels.size(), 8u);
  EXPECT_EQ(topology_label(m, all[0]), "c=closed+, adhesion=stuck, W=stuck");
  EXPECT_THROW((void)all_topologies(m, 2), InputError);
}

// Claim: the travel drive's start-up passes through the paper's stages: the topologies of its run
// cover [0, t_end] without gaps or overlaps, and among their frequencies are ω2 (gap closed,
// everything stuck), ω3 (the crane rolls) and ω4 (the wheels slip), each to 1e-10.
TEST(Topology, RunOfTravelDrivePassesThroughPaperTopologies) {
  const Model m = load_model(test::example("travel-start.yaml"));
  const SimulationResult r = simulate(m);
  const auto tops = run_topologies(m, r.hybrid, m.simulation.t_end);
  std::vector<std::pair<double, double>> all;
  std::vector<double> omegas;
  for (const auto& ti : tops) {
    all.insert(all.end(), ti.intervals.begin(), ti.intervals.end());
    const UndampedModes md = undamped_modes(linearize(m, ti.topology));
    for (double w : md.omega) omegas.push_back(w);
  }
  std::sort(all.begin(), all.end());
  ASSERT_FALSE(all.empty());
  EXPECT_EQ(all.front().first, 0.0);
  EXPECT_EQ(all.back().second, m.simulation.t_end);
  for (size_t i = 1; i < all.size(); ++i) EXPECT_EQ(all[i].first, all[i - 1].second);
  const double c = 2.0e6, m1 = 3000, mk = 300, m2 = 10000;
  for (double w : {std::sqrt(c / m1), std::sqrt(c / m1 + c / (mk + m2)), std::sqrt(c / m1 + c / mk)}) {
    bool found = false;
    for (double x : omegas) found = found || std::abs(x - w) <= 1e-10 * w;
    EXPECT_TRUE(found) << w;
  }
  EXPECT_EQ(topology_label(m, tops[0].topology), topology_label(m, initial_topology(m)));
}

}  // namespace
}  // namespace machdyn
