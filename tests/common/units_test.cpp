#include "machdyn/common/units.hpp"

#include <cmath>
#include <numbers>
#include <gtest/gtest.h>

namespace machdyn {
namespace MACHDYN_UNITY_ID {

double si(const char* text, Dim d) {
  std::string err;
  auto v = parse_as(text, d, &err);
  EXPECT_TRUE(v.has_value()) << text << ": " << err;
  return v.value_or(NAN);
}

// Claim: the unit strings the issue names convert to SI by their definitions.
TEST(Units, ConvertsTheIssuesExamplesToSI) {
  EXPECT_DOUBLE_EQ(si("2.5 kg*m^2", dim::inertia), 2.5);
  EXPECT_DOUBLE_EQ(si("143.5 mm", dim::length), 0.1435);
  EXPECT_DOUBLE_EQ(si("30 deg", dim::none), std::numbers::pi / 6);
  EXPECT_DOUBLE_EQ(si("1.2 kN*m", dim::torque), 1200.0);
  EXPECT_DOUBLE_EQ(si("1500 rpm", dim::angular_velocity), 1500 * 2 * std::numbers::pi / 60);
  EXPECT_DOUBLE_EQ(si("3e4 N*m/rad", dim::torque), 3e4);
  EXPECT_DOUBLE_EQ(si("7", dim::none), 7.0);
}

// Claim: products, quotients, powers, parentheses and prefixes compose like algebra.
TEST(Units, ComposesProductsQuotientsPowersAndPrefixes) {
  EXPECT_DOUBLE_EQ(si("2 t", dim::mass), 2000.0);
  EXPECT_DOUBLE_EQ(si("5 g*cm^2", dim::inertia), 5e-3 * 1e-4);
  EXPECT_DOUBLE_EQ(si("3 N/mm", dim::stiffness_lin), 3000.0);
  EXPECT_DOUBLE_EQ(si("2 kN*s/m", dim::damping_lin), 2000.0);
  EXPECT_DOUBLE_EQ(si("1 kg/(m*s^2)*m^2", dim::force), 1.0);
  EXPECT_DOUBLE_EQ(si("4 kg·m²", dim::inertia), 4.0);
  EXPECT_DOUBLE_EQ(si("2 Nm", dim::torque), 2.0);
  EXPECT_DOUBLE_EQ(si("10 ms", dim::time), 0.01);
  EXPECT_DOUBLE_EQ(si("1 rev", dim::none), 2 * std::numbers::pi);
  EXPECT_DOUBLE_EQ(si("60 min", dim::time), 3600.0);
  EXPECT_DOUBLE_EQ(si("-1.5e-3 m/s", dim::velocity), -1.5e-3);
}

// Claim: the electrical units of a DC motor follow their SI definitions with the ampere as the
// fourth base unit: V = W/A, Ω = V/A, H = V·s/A, so N·m/A = V·s/rad (k_t = k_e), and Ω·A = V.
TEST(Units, ElectricalUnitsFollowTheirDefinitions) {
  EXPECT_DOUBLE_EQ(si("12 mH", dim::inductance), 0.012);
  EXPECT_DOUBLE_EQ(si("250 mohm", dim::resistance), 0.25);
  EXPECT_DOUBLE_EQ(si("2 Ω", dim::resistance), 2.0);
  EXPECT_DOUBLE_EQ(si("0.4 kV", dim::voltage), 400.0);
  EXPECT_DOUBLE_EQ(si("3 mA", dim::current), 0.003);
  EXPECT_DOUBLE_EQ(si("2 V*s/rad", dim::torque / dim::current), 2.0);   // back-emf constant
  EXPECT_DOUBLE_EQ(si("2 N*m/A", dim::torque / dim::current), 2.0);     // torque constant: the same
  EXPECT_DOUBLE_EQ(si("3 ohm*A", dim::voltage), 3.0);
  EXPECT_DOUBLE_EQ(si("5 W/A", dim::voltage), 5.0);
  EXPECT_DOUBLE_EQ(si("1 H*A/s", dim::voltage), 1.0);
  std::string err;
  EXPECT_FALSE(parse_as("10 A", dim::voltage, &err).has_value());
  EXPECT_NE(err.find("expected a voltage (V), got a current (A)"), std::string::npos) << err;
  EXPECT_FALSE(parse_as("1 H", dim::time, &err).has_value());
  EXPECT_NE(err.find("got an inductance (H)"), std::string::npos) << err;
}

// Claim: a value of the wrong dimension is an error that names both dimensions.
TEST(Units, RejectsWrongDimensionNamingBoth) {
  std::string err;
  EXPECT_FALSE(parse_as("12 N", dim::torque, &err));
  EXPECT_NE(err.find("expected a torque"), std::string::npos) << err;
  EXPECT_NE(err.find("got a force"), std::string::npos) << err;
}

// Claim: unknown units, junk, NaN and infinity are rejected with a reason.
TEST(Units, RejectsUnknownUnitsJunkAndNonFinite) {
  for (const char* bad : {"3 furlong", "kg", "", "nan", "inf kg", "2 kg*", "2 kg^", "2 (kg", "1e999 kg"}) {
    std::string err;
    EXPECT_FALSE(parse_quantity(bad, &err)) << bad;
    EXPECT_FALSE(err.empty()) << bad;
  }
}

// Claim: an angular speed in Hz is refused with a hint (never a silent factor 2π or 1), while rps
// is revolutions per second by definition: 25 rps = 25·2π rad/s = 1500 rpm.
TEST(Units, HertzIsRejectedForAngularSpeedsAndRpsIsRevolutionsPerSecond) {
  std::string err;
  EXPECT_FALSE(parse_as("25 Hz", dim::angular_velocity, &err));
  EXPECT_NE(err.find("rpm"), std::string::npos) << err;
  EXPECT_NE(err.find("rad/s"), std::string::npos) << err;
  EXPECT_FALSE(parse_as("0.025 kHz", dim::angular_velocity, &err));
  EXPECT_FALSE(parse_as("25 rad*Hz", dim::angular_velocity, &err));
  EXPECT_DOUBLE_EQ(si("25 rps", dim::angular_velocity), si("1500 rpm", dim::angular_velocity));
  EXPECT_DOUBLE_EQ(si("25 rps", dim::angular_velocity), 25 * 2 * std::numbers::pi);
  EXPECT_DOUBLE_EQ(si("25 rev/s", dim::angular_velocity), 25 * 2 * std::numbers::pi);
}

// Claim: exponents are bounded (no int overflow, no wrap-around: 4294967298 = 2^32 + 2 used to
// read as 2) and a value that does not survive scaling to SI is an error, not inf or NaN.
TEST(Units, ExponentsAreBoundedAndScaledValuesFinite) {
  for (const char* bad : {"1 kg*m^4294967298", "1 N^6555565656", "5 km^400", "0 (km/m)^400*rad", "1e308 kN",
                          "1e308 t", "1e-300 nm^12", "1 m^13", "1 ((((((((((((((((((m))))))))))))))))))"}) {
    std::string err;
    EXPECT_FALSE(parse_quantity(bad, &err)) << bad;
    EXPECT_FALSE(err.empty()) << bad;
  }
  std::string deep = "1 ";
  deep.append(100000, '(');
  deep += 'm';
  std::string err;
  EXPECT_FALSE(parse_quantity(deep, &err));
  EXPECT_DOUBLE_EQ(si("2 m^12/m^11", dim::length), 2.0);
  EXPECT_DOUBLE_EQ(si("1e300 N", dim::force), 1e300);
  EXPECT_DOUBLE_EQ(si("0 kN", dim::force), 0.0);
}

// Claim: what the messages suggest is accepted: `1/m` (describe(dim::inv_length) offers it) and a
// space between units multiplies, as in print: 1.2 kg m^2 = 1.2 kg*m^2.
TEST(Units, AcceptsReciprocalUnitsAndSpacesAsProducts) {
  EXPECT_DOUBLE_EQ(si("4 1/m", dim::inv_length), 4.0);
  EXPECT_DOUBLE_EQ(si("4 1/mm", dim::inv_length), 4000.0);
  EXPECT_DOUBLE_EQ(si("4 rad/m", dim::inv_length), 4.0);
  EXPECT_DOUBLE_EQ(si("1.2 kg m^2", dim::inertia), 1.2);
  EXPECT_DOUBLE_EQ(si("3 kN m / rad", dim::torque), 3000.0);
  EXPECT_DOUBLE_EQ(si("2 N s/m", dim::damping_lin), 2.0);
  EXPECT_NE(describe(dim::inv_length).find("1/m"), std::string::npos);
}

}  // namespace
}  // namespace machdyn
