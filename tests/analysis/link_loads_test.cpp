// The drive system's per-row and per-step evaluations (analysis/drive_system.hpp): link_loads()
// and link_loads_and_rates() take each link by a path of its own (plain, gap in the rates' loop,
// the whole law) and contact_forces() a mode's small map inline; each must give the bits of the one
// law evaluated link by link (link_load, link_load_rate) and of evaluate(), and the closed form.
#include <cmath>
#include <string>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/analysis/drive_system.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// Four bodies; links: a plain spring-damper, a spring with a gap (flanks ±2 mm: Δ = 4 mm, δ = 0 in
// its middle), a spring-damper
// with a gap under the capped law (elasto-backlash: the whole law), and a damper to the ground.
const char* kModel = R"(
bodies:
  A: {type: translational, mass: 2 kg}
  B: {type: translational, mass: 3 kg}
  C: {type: translational, mass: 4 kg}
  D: {type: translational, mass: 5 kg}
links:
  plain: {type: spring-damper, between: [A, B], stiffness: 1e4 N/m, damping: 30 N*s/m}
  gap: {type: spring, between: [B, C], stiffness: 2e4 N/m, gap: 4 mm, gap_start: 2 mm}
  capped: {type: spring-damper, between: [C, D], stiffness: 3e4 N/m, damping: 200 N*s/m, gap: 2 mm, flank_law: elasto-backlash}
  ground: {type: damper, between: [D, ground], damping: 10 N*s/m}
contacts:
  grip: {between: [A, ground], static: 50 N, kinetic: 40 N}
simulation: {t_end: 1 s, dt_out: 0.01 s}
)";

// Claim: for every gap mode of the gap links, the loads and load rates of the loops equal the one
// law link by link to the bit, and the gap link's load is its closed form c (δ − flank) (0 open).
TEST(LinkLoads, LoopsEqualTheLawLinkByLink) {
  const Model m = test::model_text(kModel, "links.yaml");
  DriveSystem sys(m, true);
  const int N = sys.size();
  std::vector<double> y(static_cast<size_t>(N)), dy(static_cast<size_t>(N));
  for (int i = 0; i < N; ++i) y[static_cast<size_t>(i)] = 1e-3 * std::sin(1.0 + 2.7 * i);  // deflections of mm
  for (int i = 0; i < N; ++i) dy[static_cast<size_t>(i)] = 0.3 * std::cos(0.5 + 1.9 * i);
  const GapMode modes[] = {GapMode::open, GapMode::closed_pos, GapMode::closed_neg};
  int checked = 0;
  for (const GapMode g1 : modes)
    for (const GapMode g2 : modes) {
      sys.set_gap_mode(1, g1);
      sys.set_gap_mode(2, g2);
      std::vector<double> F(4), F2(4), R(4);
      sys.link_loads(y.data(), F.data());
      sys.link_loads_and_rates(y.data(), dy.data(), F2.data(), R.data());
      for (int l = 0; l < 4; ++l) {
        const double law = sys.link_load(l, y.data()), rate = sys.link_load_rate(l, y.data(), dy.data());
        EXPECT_EQ(std::signbit(F[static_cast<size_t>(l)]), std::signbit(law)) << l;
        EXPECT_EQ(F[static_cast<size_t>(l)], law) << "link " << l << " modes " << int(g1) << int(g2);
        EXPECT_EQ(F2[static_cast<size_t>(l)], law) << l;
        EXPECT_EQ(R[static_cast<size_t>(l)], rate) << l;
        ++checked;
      }
      // δ = q_B − q_C of [B, C], flanks ±Δ/2 = ±2 mm: F = c (δ ∓ 2 mm) on a flank, 0 open.
      const double delta = y[1] - y[2], flank = g1 == GapMode::closed_pos ? 2e-3 : -2e-3;
      const double expected = g1 == GapMode::open ? 0.0 : 2e4 * (delta - flank);
      EXPECT_NEAR(F[1], expected, 1e-12 * 2e4 * 1e-2) << int(g1);
      const double rate_expected = g1 == GapMode::open ? 0.0 : 2e4 * (dy[1] - dy[2]);
      EXPECT_NEAR(R[1], rate_expected, 1e-12 * 2e4) << int(g1);
    }
  EXPECT_EQ(checked, 36);
}

// Claim: contact_forces() — inline from the mode's small affine map once it is compiled — equals
// evaluate()'s contact forces in both modes of the contact, before and after the map is compiled.
TEST(LinkLoads, ContactForcesEqualEvaluate) {
  // No dampers: the modes run affine (drive_system.hpp), so contact_forces() takes the map.
  const Model m = test::model_text(R"(
bodies:
  A: {type: translational, mass: 2 kg}
  B: {type: translational, mass: 3 kg}
links:
  k: {type: spring, between: [A, B], stiffness: 1e4 N/m, gap: 4 mm, gap_start: 2 mm}
contacts:
  grip: {between: [B, ground], static: 50 N, kinetic: 40 N}
loads:
  P: {type: constant, body: A, value: 30 N}
simulation: {t_end: 1 s, dt_out: 0.01 s}
)",
                                   "contact.yaml");
  DriveSystem sys(m, true);
  const int N = sys.size();
  std::vector<double> y(static_cast<size_t>(N), 0.0), acc(2), fc(1), fe(1), dy(static_cast<size_t>(N));
  y[0] = 3e-3, y[1] = -1e-3, y[2] = 0.2, y[3] = 0.0;  // δ = 4 mm: pressing its positive flank (2 mm)
  sys.set_gap_mode(0, GapMode::closed_pos);
  for (const ContactMode md : {ContactMode::stuck, ContactMode::slip_pos}) {
    sys.set_contact_modes({md});
    sys.contact_forces(0.0, y.data(), fc.data());  // first call: compiles the mode's map
    sys.evaluate(0.0, y.data(), acc.data(), fe.data());
    EXPECT_EQ(fc[0], fe[0]) << int(md);
    sys.rhs(0.0, y.data(), dy.data());
    sys.contact_forces(0.0, y.data(), fc.data());  // now inline from the map
    EXPECT_EQ(fc[0], fe[0]) << int(md);
  }
  // Stuck: λ holds B (the ground's side) against the link's load F = c (δ − 2 mm) = 20 N on B; sliding
  // forward the kinetic force 40 N.
  sys.set_contact_modes({ContactMode::stuck});
  sys.contact_forces(0.0, y.data(), fc.data());
  EXPECT_NEAR(std::abs(fc[0]), 1e4 * (4e-3 - 2e-3), 1e-9);
  sys.set_contact_modes({ContactMode::slip_pos});
  sys.contact_forces(0.0, y.data(), fc.data());
  EXPECT_EQ(std::abs(fc[0]), 40.0);
}

}  // namespace
}  // namespace machdyn
