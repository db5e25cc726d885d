#include "machdyn/common/units.hpp"

#include <cmath>
#include <numbers>
#include <gtest/gtest.h>

namespace machdyn {
namespace {

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

}  // namespace
}  // namespace machdyn
