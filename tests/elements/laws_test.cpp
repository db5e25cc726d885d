// The element laws (elements/link.hpp, elements/contact.hpp) on their own, against closed forms and
// finite differences: every consumer (drive system, static loads, linear models) relies on them.
#include <cmath>
#include <functional>
#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "machdyn/elements/contact.hpp"
#include "machdyn/elements/link.hpp"
#include "machdyn/elements/linearize.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

Model model_of(const std::string& yaml) { return compile_model(parse_yaml_string(yaml, "laws.yaml"), "laws.yaml"); }

// Claim: a gap link with Δ = 4 mm and gap_start 1 mm has flanks δ₋ = −1 mm, δ₊ = +3 mm; it carries
// F = c (δ − δ₊) + d δ̇ on the positive flank, c (δ − δ₋) + d δ̇ on the negative one, nothing open;
// its elastic energy is ½ c (δ − flank)² and its damper dissipates d δ̇² only while closed.
TEST(LinkLaw, GapFlanksAndLoads) {
  const Model m = model_of(R"(
bodies: {a: {type: translational, mass: 1}, b: {type: translational, mass: 2}}
links: {g: {type: spring-damper, between: [a, b], stiffness: 1e5, damping: 20, gap: 4 mm, gap_start: 1 mm}}
)");
  const LinkLaw k = LinkLaw::of(m, m.links[0]);
  EXPECT_DOUBLE_EQ(k.lo, -0.001);
  EXPECT_DOUBLE_EQ(k.hi, 0.003);
  EXPECT_DOUBLE_EQ(k.load(0.005, 0.1, GapMode::closed_pos), 1e5 * 0.002 + 20 * 0.1);
  EXPECT_DOUBLE_EQ(k.load(-0.004, -0.1, GapMode::closed_neg), 1e5 * -0.003 + 20 * -0.1);
  EXPECT_EQ(k.load(0.001, 0.1, GapMode::open), 0.0);
  EXPECT_DOUBLE_EQ(k.elastic_energy(0.005, GapMode::closed_pos), 0.5 * 1e5 * 0.002 * 0.002);
  EXPECT_EQ(k.dissipation(0.001, 0.3, GapMode::open), 0.0);
  EXPECT_DOUBLE_EQ(k.dissipation(-0.004, 0.3, GapMode::closed_neg), 20 * 0.09);
}

// Claim: the open gap's event functions are the distances to the flanks while inside, and the
// closed flank's function is its load: zero exactly where the law switches. An event on function 0
// of an open gap closes it on the positive flank, on function 1 on the negative one; any event of a
// closed flank opens it. The natural mode of a state pressing beyond a flank is that flank.
TEST(LinkLaw, EventsAndModes) {
  const Model m = model_of(R"(
bodies: {a: {type: translational, mass: 1}, b: {type: translational, mass: 2}}
links: {g: {type: spring, between: [a, b], stiffness: 1e5, gap: 4 mm, gap_start: 1 mm}}
)");
  const LinkLaw k = LinkLaw::of(m, m.links[0]);
  double ev[2];
  k.events(0.0, 0.0, GapMode::open, ev);
  EXPECT_DOUBLE_EQ(ev[0], 0.003);
  EXPECT_DOUBLE_EQ(ev[1], 0.001);
  k.events(0.0035, 0.0, GapMode::closed_pos, ev);
  EXPECT_DOUBLE_EQ(ev[0], k.load(0.0035, 0.0, GapMode::closed_pos));
  EXPECT_EQ(LinkLaw::mode_after(GapMode::open, 0), GapMode::closed_pos);
  EXPECT_EQ(LinkLaw::mode_after(GapMode::open, 1), GapMode::closed_neg);
  EXPECT_EQ(LinkLaw::mode_after(GapMode::closed_neg, 1), GapMode::open);
  EXPECT_EQ(k.natural_mode(0.004, 0.0), GapMode::closed_pos);
  EXPECT_EQ(k.natural_mode(-0.002, 0.0), GapMode::closed_neg);
  EXPECT_EQ(k.natural_mode(0.002, 0.0), GapMode::open);
  EXPECT_EQ(k.natural_mode(0.003, -1.0), GapMode::open);  // on the flank, moving away
}

// Claim: a link's K term equals the Hessian of its elastic energy ½ c δ(q)² by central finite
// differences — including the geometric stiffness c δ p″ of a link to a crank-slider's piston
// (p(φ) nonlinear), linearized at a deflected position.
TEST(LinkLaw, LinearTermsAreTheEnergyHessian) {
  const Model m = model_of(std::string("bodies:") + test::kCrankSliderBody +
                           "  slider: {type: translational, mass: 2 kg}\n"
                           "links:\n  rod: {type: spring, between: [crank.piston, slider], stiffness: 1e5 N/m}\n");
  ASSERT_TRUE(m.links[0].a_point);
  const LinkLaw k = LinkLaw::of(m, m.links[0]);
  const int n = m.dof();
  std::vector<double> q(static_cast<size_t>(n)), v(q);
  for (int i = 0; i < n; ++i) q[static_cast<size_t>(i)] = 0.7 + 0.01 * i;  // a deflected, generic position
  LinearModel lin(n);
  k.add_linear(q.data(), GapMode::open, lin);
  const Eigen::MatrixXd K(lin.stiffness());
  auto energy = [&](std::vector<double> x) { return k.elastic_energy(k.kinematics(x.data(), v.data()).delta, GapMode::open); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double h = 1e-4;
      auto e = [&](double di, double dj) {
        auto x = q;
        x[static_cast<size_t>(i)] += di, x[static_cast<size_t>(j)] += dj;
        return energy(x);
      };
      const double fd = (e(h, h) - e(h, -h) - e(-h, h) + e(-h, -h)) / (4 * h * h);
      EXPECT_NEAR(K(i, j), fd, 1e-5 * std::max(1.0, std::abs(K.maxCoeff()))) << i << "," << j;
    }
}

// Claim: the stick rule holds a load up to F_s(t) = r(t) F_s0 and, unless judged strictly, up to a
// rounding allowance of 1e-12 F_s0 beyond; a brake's limit follows its ramp (half applied at half
// the ramp) and it is released before its application time.
TEST(ContactLaw, StickRuleAndBrakeRamp) {
  const Model m = model_of(R"(
bodies: {a: {inertia: 1}}
brakes: {B: {body: a, holding: 100 N*m, braking: 80 N*m, time: 0.25 s, ramp: 0.5 s}}
)");
  const ContactLaw c = ContactLaw::of(m.contacts[0]);
  EXPECT_TRUE(c.released(0.05));
  EXPECT_FALSE(c.released(0.25));
  EXPECT_DOUBLE_EQ(c.static_limit(0.5), 50.0);
  EXPECT_TRUE(c.holds(50.0, 0.5, true));
  EXPECT_FALSE(c.holds(50.0 + 1e-9, 0.5, true));
  EXPECT_TRUE(c.holds(50.0 + 0.5e-10, 0.5, false));
  EXPECT_FALSE(c.holds(50.0 + 1e-9, 0.5, false));
  EXPECT_DOUBLE_EQ(c.kinetic_force(ContactMode::slip_neg, 1.0, -3.0), -80.0);
}

// Claim: the kinetic slope dF/du of a tabulated kinetic level equals the finite difference of the
// kinetic force in the sliding direction, and the steepest rising slope is the table's largest.
TEST(ContactLaw, KineticSlopeIsTheDerivative) {
  const Model m = model_of(R"(
bodies: {a: {type: translational, mass: 1}}
contacts: {f: {between: [a, ground], static: 12 N, kinetic: [[0 m/s, 10 N], [1 m/s, 6 N], [3 m/s, 9 N]]}}
)");
  const ContactLaw c = ContactLaw::of(m.contacts[0]);
  for (double u : {0.4, 2.0}) {
    const double h = 1e-6;
    const double fd = (c.kinetic_force(ContactMode::slip_pos, 0, u + h) - c.kinetic_force(ContactMode::slip_pos, 0, u - h)) / (2 * h);
    EXPECT_NEAR(c.kinetic_slope(0, u), fd, 1e-6) << u;
  }
  EXPECT_DOUBLE_EQ(c.steepest_kinetic_slope(), 1.5);
}

}  // namespace
}  // namespace machdyn
