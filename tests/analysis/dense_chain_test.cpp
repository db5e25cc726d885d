// The small chain's fast right-hand side (analysis/drive_system.cpp: the fixed-size dense kernels,
// with and without the velocity block) against the equations of motion written out by hand.
#include <cmath>
#include <string>
#include <vector>
#include <gtest/gtest.h>

#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// Three masses, springs (c1, d1) between m1 and m2 and (c2, d2) between m2 and m3, constant loads P1
// on m1 and P2 on m2. By hand: F1 = c1 (q1 − q2) + d1 (v1 − v2), F2 = c2 (q2 − q3) + d2 (v2 − v3),
// a1 = (P1 − F1)/m1, a2 = (P2 + F1 − F2)/m2, a3 = F2/m3, and q̇ = v.
struct Chain {
  double m1 = 2.0, m2 = 4.0, m3 = 8.0, c1 = 1e4, c2 = 2e4, d1 = 0.0, d2 = 0.0, P1 = 100.0, P2 = -40.0;
  Model model() const {
    auto link = [](const char* name, const char* a, const char* b, double c, double d) {
      return std::string("  ") + name + ": {type: " + (d > 0 ? "spring-damper" : "spring") + ", between: [" + a +
             ", " + b + "], stiffness: " + std::to_string(c) + " N/m" +
             (d > 0 ? ", damping: " + std::to_string(d) + " N*s/m" : std::string()) + "}\n";
    };
    const std::string yaml = "bodies:\n  m1: {type: translational, mass: " + std::to_string(m1) +
                             " kg}\n  m2: {type: translational, mass: " + std::to_string(m2) +
                             " kg}\n  m3: {type: translational, mass: " + std::to_string(m3) + " kg}\nlinks:\n" +
                             link("k1", "m1", "m2", c1, d1) + link("k2", "m2", "m3", c2, d2) +
                             "loads:\n  P1: {type: constant, body: m1, value: " + std::to_string(P1) +
                             " N}\n  P2: {type: constant, body: m2, value: " + std::to_string(P2) +
                             " N}\nsimulation: {t_end: 1 s, dt_out: 0.1 s}\n";
    return compile_model(parse_yaml_string(yaml, "chain.yaml"), "chain.yaml");
  }
  void by_hand(const double* y, double* d) const {
    const double F1 = c1 * (y[0] - y[1]) + d1 * (y[3] - y[4]), F2 = c2 * (y[1] - y[2]) + d2 * (y[4] - y[5]);
    d[0] = y[3], d[1] = y[4], d[2] = y[5];
    d[3] = (P1 - F1) / m1, d[4] = (P2 + F1 - F2) / m2, d[5] = F2 / m3;
  }
};

// Claim: without dampers (the kernel without the velocity block) and with them (the full kernel),
// the right-hand side equals the hand-written equations to 1e-14 of the largest term at generic
// states; at rest with the springs relaxed the accelerations are P/m exactly and the unloaded body's
// is +0, as by hand (the masses are powers of 2: P/m and P·(1/m) are the same number).
TEST(DenseChain, RightHandSideEqualsTheEquationsByHand) {
  for (const double damping : {0.0, 7.0}) {
    Chain ch;
    ch.d1 = damping, ch.d2 = 2.0 * damping;
    const Model m = ch.model();
    DriveSystem sys(m, /*energy_books=*/false);
    ASSERT_EQ(sys.size(), 6);
    for (int s = 0; s < 4; ++s) {
      double y[6], got[6], want[6];
      for (int i = 0; i < 6; ++i) y[i] = s == 0 ? 0.0 : 0.01 * std::sin(1.3 * i + s) + (i >= 3 ? 0.2 * s : 0.0);
      sys.rhs(0.0, y, got);
      ch.by_hand(y, want);
      const double scale = std::abs(ch.P1 / ch.m1) + ch.c2 * 0.02 / ch.m1;
      for (int i = 0; i < 6; ++i) EXPECT_NEAR(got[i], want[i], 1e-14 * scale) << "state " << s << " row " << i;
      if (s == 0) {
        EXPECT_EQ(got[3], ch.P1 / ch.m1);
        EXPECT_EQ(got[4], ch.P2 / ch.m2);
        EXPECT_EQ(got[5], 0.0);
        EXPECT_FALSE(std::signbit(got[5])) << damping;
      }
    }
  }
}

}  // namespace
}  // namespace machdyn
