// The expression parser used for user-given I(q) and torque laws.
#include "machdyn/common/expression.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <stdexcept>

namespace machdyn {
namespace MACHDYN_UNITY_ID {

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

// Claim: nesting is bounded (Expression::kMaxDepth), so deep or long texts are a syntax error
// with a place, never a stack overflow while parsing or evaluating (the fuzzer's cases: 20 000
// parentheses, a chain of 200 000 '^', 400 000 unary minus, a left-deep sum of 10^5 terms).
TEST(Expression, DeepNestingIsAnErrorNotAStackOverflow) {
  auto rejected = [](const std::string& text) {
    try {
      Expression e(text, "q");
    } catch (const ExpressionError& ex) {
      return std::string(ex.what()).find("nested deeper than 200") != std::string::npos;
    }
    return false;
  };
  auto wrapped = [](std::size_t n) {
    std::string t(n, '(');
    t += 'q';
    t.append(n, ')');
    return t;
  };
  EXPECT_TRUE(rejected(wrapped(20000)));
  std::string pow_chain = "q";
  for (int i = 0; i < 200000; ++i) pow_chain += "^q";
  EXPECT_TRUE(rejected(pow_chain));
  std::string minus(400000, '-');
  minus += 'q';
  EXPECT_TRUE(rejected(minus));
  std::string sum = "q";
  for (int i = 0; i < 100000; ++i) sum += "+q";
  EXPECT_TRUE(rejected(sum));
  // Just inside the bound: a sum of 200 terms has height 199 and evaluates to 200 q.
  std::string ok = "q";
  for (int i = 1; i < 200; ++i) ok += "+q";
  EXPECT_DOUBLE_EQ(Expression(ok, "q")(0.5), 100.0);
  EXPECT_DOUBLE_EQ(Expression(wrapped(150), "q")(2.0), 2.0);
}

}  // namespace
}  // namespace machdyn
