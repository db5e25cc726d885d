// The expression parser used for user-given I(q) and torque laws.
#include "machdyn/common/expression.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <stdexcept>

namespace machdyn {
namespace {

// Claim: precedence and associativity are the usual ones (hand-evaluated values).
TEST(Expression, PrecedenceAndAssociativity) {
  EXPECT_DOUBLE_EQ(Expression("1 + 2*3", "q")(0), 7.0);
  EXPECT_DOUBLE_EQ(Expression("2^3^2", "q")(0), 512.0);  // right-associative: 2^(3^2)
  EXPECT_DOUBLE_EQ(Expression("-q^2", "q")(3), -9.0);     // -(q^2)
  EXPECT_DOUBLE_EQ(Expression("(1 + q)/2 - 8/4/2", "q")(3), 1.0);
  EXPECT_DOUBLE_EQ(Expression("2*pi", "q")(0), 2 * 3.14159265358979323846);
  EXPECT_DOUBLE_EQ(Expression("1e-3*q", "q")(2), 2e-3);
}

// Claim: the derivative from forward-mode differentiation equals the hand-derived one:
// f = 0.5 + 0.2 sin²q + exp(q/4)/sqrt(1+q²)
// f′ = 0.4 sin q cos q + exp(q/4)[1/4 (1+q²)^(−1/2) − q (1+q²)^(−3/2)].
TEST(Expression, DerivativeMatchesHandDerivation) {
  const Expression f("0.5 + 0.2*sin(q)^2 + exp(q/4)/sqrt(1 + q^2)", "q");
  for (double q : {-1.3, 0.0, 0.7, 2.9}) {
    double v, d;
    f.evaluate(q, &v, &d);
    const double s = 1 + q * q;
    const double dv = 0.4 * std::sin(q) * std::cos(q) + std::exp(q / 4) * (0.25 / std::sqrt(s) - q / std::pow(s, 1.5));
    EXPECT_NEAR(v, 0.5 + 0.2 * std::sin(q) * std::sin(q) + std::exp(q / 4) / std::sqrt(s), 1e-15);
    EXPECT_NEAR(d, dv, 1e-14);
  }
}

// Claim: bad text is rejected with the character position and what was expected; unknown names are
// not executed or looked up anywhere.
TEST(Expression, BadTextNamesThePlace) {
  auto message = [](const char* text) {
    try {
      Expression e(text, "q");
    } catch (const std::invalid_argument& ex) {
      return std::string(ex.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message("1 + (q"), "at character 7: expected ')'");
  EXPECT_NE(message("system(q)").find("unknown name 'system'"), std::string::npos);
  EXPECT_NE(message("2 * * q").find("at character 5"), std::string::npos);
  EXPECT_NE(message("sin q").find("expected '(' after sin"), std::string::npos);
  EXPECT_NE(message("q 2").find("unexpected '2'"), std::string::npos);
}

}  // namespace
}  // namespace machdyn
