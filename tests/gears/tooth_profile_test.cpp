// Rack-cutter envelope: against the involute (closed form), the textbook undercut limit, and the
// feasibility rules of the continuous basis.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "machdyn/gears/tooth_profile.hpp"
#include "machdyn/io/yaml_reader.hpp"

namespace machdyn::gears {
namespace MACHDYN_UNITY_ID {

constexpr double kPi = std::numbers::pi;
constexpr double kDeg = kPi / 180.0;

double inv(double a) { return std::tan(a) - a; }

// A rack rolling on a circle of radius R generates the involute of the base circle r_b = R cos α:
// a point of the flank at radius ρ lies at polar angle β = β_f ∓ (inv α_ρ − inv α), cos α_ρ = r_b/ρ,
// where β_f = x_f/R is the flank's pitch point (− for the flank facing increasing s, which leans
// toward the tooth centre as it rises). Checked at every generated point of both flanks.
TEST(ToothProfile, RackOnCircleGeneratesTheInvolute) {
  const double R = 0.050, alpha = 20.0 * kDeg;
  const RackCutter rack{0.002, alpha, 1.0, 1.25};
  const Track circle = [&](double s) { return circle_frame(R, 0.0, s); };
  const double rb = R * std::cos(alpha);
  for (int sigma : {+1, -1}) {
    const double x_f = 0.0123 * sigma;
    const auto pts = rack_flank(circle, x_f, sigma, rack, -0.002, 0.002, 41);
    double worst = 0.0;
    for (const Vec2& q : pts) {
      const double rho = std::hypot(q.x, q.y), beta = std::atan2(q.y, q.x);
      ASSERT_GT(rho, rb);
      const double expected = x_f / R - sigma * (inv(std::acos(rb / rho)) - inv(alpha));
      worst = std::max(worst, std::abs(beta - expected));
    }
    EXPECT_LT(worst, 1e-12) << "sigma " << sigma;
  }
}

// Tooth thickness on the pitch circle of the generated circular gear is πm/2 (standard rack, no shift):
// the two flanks of a tooth cross the pitch circle πm/2 apart along the arc.
TEST(ToothProfile, CircularGearHasStandardToothThickness) {
  const double R = 0.040, m = 0.002;
  const RackCutter rack{m, 20.0 * kDeg, 1.0, 1.25};
  const Track circle = [&](double s) { return circle_frame(R, 0.0, s); };
  const double sc = 0.01;
  const auto l = rack_flank(circle, sc - kPi * m / 4, -1, rack, 0.0, 0.0, 2);
  const auto r = rack_flank(circle, sc + kPi * m / 4, +1, rack, 0.0, 0.0, 2);
  const double arc = R * (std::atan2(r[0].y, r[0].x) - std::atan2(l[0].y, l[0].x));
  EXPECT_NEAR(arc, kPi * m / 2, 1e-12);
}

// Undercut: a circular gear of z teeth (R = zm/2) is undercut by a standard rack exactly when
// z < 2 h_a*/sin²α = 17.1 for α = 20° (textbook minimum tooth count).
TEST(ToothProfile, UndercutLimitIsTheTextbookToothCount) {
  const double m = 0.001, alpha = 20.0 * kDeg;
  const RackCutter rack{m, alpha, 1.0, 1.25};
  const double zmin = 2.0 / std::pow(std::sin(alpha), 2);
  EXPECT_NEAR(zmin, 17.097, 1e-3);
  for (int z : {12, 17, 18, 30}) {
    const double R = z * m / 2;
    const Track circle = [&](double s) { return circle_frame(R, 0.0, s); };
    const double margin = undercut_margin(circle, 0.0, +1, rack);
    EXPECT_EQ(margin < 0.0, z < zmin) << "z = " << z << ", margin " << margin;
  }
}

GearModel model_from(const std::string& yaml) { return compile_gears(parse_yaml_string(yaml, "test.yaml")); }

// The paper's pair, stepwise basis: module m = l/π ≈ 1.98 mm, no undercut (smallest pinion sector
// radius 41.9 mm > h_a m/sin²α = 16.9 mm), one closed outline per gear with every tooth.
TEST(ToothProfile, PaperPairStepwiseHasNoUndercut) {
  const GearModel m = compile_gears(read_yaml_file(std::string(MACHDYN_SOURCE_DIR) +
                                                   "/examples/walking-drive-gears.yaml"));
  const GearSynthesis s = synthesize(m);
  const ToothProfiles p = generate_profiles(m, s);
  EXPECT_NEAR(p.rack.module, s.arc / kPi, 1e-15);
  EXPECT_NEAR(p.rack.module, 0.00198, 0.00001);
  EXPECT_TRUE(p.undercut.empty());
  EXPECT_EQ(p.wheel.teeth, 96);
  EXPECT_EQ(p.pinion.teeth, 48);
  // every outline point lies between root and tip of its gear's radius range
  for (const Vec2& q : p.pinion.outline) {
    const double r = std::hypot(q.x, q.y);
    EXPECT_GT(r, 0.04191 - 1.25 * p.rack.module - 1e-4);
    EXPECT_LT(r, 0.06130 + p.rack.module + 1e-4);  // tip on the largest sector circle
  }
}

// The paper's law has corners at the big-sector ends (i' jumps from −2uk to +2uk): the continuous
// basis is refused with the place of `basis`.
TEST(ToothProfile, ContinuousBasisRefusesTheCorneredPaperLaw) {
  const GearModel m = model_from(
      "a: 60 mm\nb: 100 mm\nc: 360 mm\nL: 143.5 mm\nz: 48\nzH: 96\nprofile:\n  basis: continuous\n");
  const GearSynthesis s = synthesize(m);
  try {
    generate_profiles(m, s);
    FAIL() << "expected InputError";
  } catch (const InputError& e) {
    ASSERT_EQ(e.diagnostics().size(), 1u);
    EXPECT_EQ(e.diagnostics()[0].where.line, 8);
    EXPECT_NE(e.diagnostics()[0].message.find("corner"), std::string::npos);
  }
}

// A smooth law on the continuous basis: the pinion's pitch-curve length equals z·p (the two curves
// roll on each other), the module is perimeter/(π z_H), and there is no undercut.
TEST(ToothProfile, ContinuousBasisOnSmoothLaw) {
  const GearModel m = model_from(
      "law: expression\nratio: \"2 + 0.1*cos(4*phi)\"\nL: 100 mm\nz: 24\nzH: 48\n"
      "profile:\n  basis: continuous\n");
  const GearSynthesis s = synthesize(m);
  const ToothProfiles p = generate_profiles(m, s);
  double len_w = 0.0, len_p = 0.0;
  for (std::size_t k = 1; k < p.wheel.pitch.size(); ++k)
    len_w += std::hypot(p.wheel.pitch[k].x - p.wheel.pitch[k - 1].x, p.wheel.pitch[k].y - p.wheel.pitch[k - 1].y);
  for (std::size_t k = 1; k < p.pinion.pitch.size(); ++k)
    len_p += std::hypot(p.pinion.pitch[k].x - p.pinion.pitch[k - 1].x,
                        p.pinion.pitch[k].y - p.pinion.pitch[k - 1].y);
  EXPECT_NEAR(len_w, 48 * p.pitch, 1e-5 * len_w);
  EXPECT_NEAR(len_p, 24 * p.pitch, 1e-5 * len_p);
  EXPECT_TRUE(p.undercut.empty());
}

// A law whose wheel curve is strongly non-convex is refused on the continuous basis.
TEST(ToothProfile, ContinuousBasisRefusesConcaveCurves) {
  const GearModel m = model_from(
      "law: expression\nnormalize: true\nratio: \"1 + 0.9*cos(4*phi)\"\nL: 100 mm\nz: 24\nzH: 48\n"
      "profile:\n  basis: continuous\n");
  const GearSynthesis s = synthesize(m);
  EXPECT_THROW(generate_profiles(m, s), InputError);
}

}  // namespace
}  // namespace machdyn::gears
