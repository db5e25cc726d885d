// The ratio-law expression language: values and exact first/second derivatives against closed forms.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "machdyn/common/expression.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// f = u(1 + k cos 2φ): f' = −2uk sin 2φ, f'' = −4uk cos 2φ.
TEST(ExpressionJet, WalkingLawAndItsDerivatives) {
  const Expression e("1.25*(1 + 0.9375*cos(2*phi))", "phi");
  for (double p : {-0.7, 0.0, 0.3}) {
    const Jet j = e.eval(Jet::variable(p));
    EXPECT_NEAR(j.v, 1.25 * (1 + 0.9375 * std::cos(2 * p)), 1e-15);
    EXPECT_NEAR(j.d, -2 * 1.25 * 0.9375 * std::sin(2 * p), 1e-14);
    EXPECT_NEAR(j.dd, -4 * 1.25 * 0.9375 * std::cos(2 * p), 1e-14);
  }
}

// Precedence and the other functions: -2^2 = -4, 2^3^2 = 2^9, x/y*z = (x/y)*z; d/dx of sqrt, exp, x^x.
TEST(ExpressionJet, PrecedenceAndFunctions) {
  EXPECT_DOUBLE_EQ(Expression("-2^2", "phi")(0.0), -4.0);
  EXPECT_DOUBLE_EQ(Expression("2^3^2", "phi")(0.0), 512.0);
  EXPECT_DOUBLE_EQ(Expression("8/4*2", "phi")(0.0), 4.0);
  EXPECT_NEAR(Expression("pi + abs(phi) + tan(0) + log(exp(1))", "phi")(-1.0), std::numbers::pi + 2.0, 1e-15);
  const Jet s = Expression("sqrt(phi)", "phi").eval(Jet::variable(4.0));
  EXPECT_NEAR(s.d, 0.25, 1e-15);
  EXPECT_NEAR(s.dd, -1.0 / 32.0, 1e-15);
  const Jet x = Expression("phi^phi", "phi").eval(Jet::variable(2.0));  // d/dx x^x = x^x (ln x + 1)
  EXPECT_NEAR(x.d, 4.0 * (std::log(2.0) + 1.0), 1e-13);
}

TEST(ExpressionJet, RejectsUnknownNamesWithTheirColumn) {
  try {
    Expression("1 + system(1)", "phi");
    FAIL();
  } catch (const ExpressionError& e) {
    EXPECT_EQ(e.column(), 5);
  }
  EXPECT_THROW(Expression("(1 + phi", "phi"), ExpressionError);
  EXPECT_THROW(Expression("1 +", "phi"), ExpressionError);
  EXPECT_THROW(Expression("1 2", "phi"), ExpressionError);
}

}  // namespace
}  // namespace machdyn

namespace machdyn {
namespace MACHDYN_UNITY_ID {

// Claim: the first and second derivatives of every function agree with central finite
// differences of the value (an independent answer for the hand-written chain rules).
TEST(ExpressionJet, EveryFunctionsDerivativesMatchFiniteDifferences) {
  for (const char* f : {"sin(x)", "cos(x)", "tan(x)", "asin(x)", "acos(x)", "atan(x)", "sinh(x)", "cosh(x)",
                        "tanh(x)", "exp(x)", "log(x)", "sqrt(x)", "abs(x - 1)", "x^2.5", "e^x", "2^x"}) {
    const Expression e(f, "x");
    for (double x : {0.3, 0.55, 0.8}) {
      const double h = 1e-4;
      const Jet j = e.eval(Jet::variable(x));
      const double d1 = (e(x + h) - e(x - h)) / (2 * h), d2 = (e(x + h) - 2 * e(x) + e(x - h)) / (h * h);
      EXPECT_NEAR(j.v, e(x), 1e-15) << f;
      EXPECT_NEAR(j.d, d1, 1e-6 * std::max(1.0, std::abs(d1))) << f << " at " << x;
      EXPECT_NEAR(j.dd, d2, 1e-4 * std::max(1.0, std::abs(d2))) << f << " at " << x;
    }
  }
}

}  // namespace
}  // namespace machdyn
