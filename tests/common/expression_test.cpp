// The expression parser used for user-given I(q) and torque laws.
#include "machdyn/common/expression.hpp"

#include <cmath>
#include <gtest/gtest.h>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

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

// Claim: the switches take the values and derivatives written in common/expression.hpp, checked by
// hand at points on each side: comparisons are 1 or 0 with derivative 0; step(x) is 1 from x = 0 on;
// min and max carry the chosen argument's first and second derivative (at a tie the right
// derivative: the argument that stays smaller, or larger, for growing t); if(c, a, b) is a where c
// holds and evaluates only that branch (sqrt of a negative number in the other gives no NaN).
TEST(ExpressionSwitch, ValuesAndDerivativesOnEachSide) {
  auto jet = [](const char* text, double t) { return Expression(text, "t").eval(Jet::variable(t)); };
  EXPECT_EQ(jet("t < 1", 0.5).v, 1.0);
  EXPECT_EQ(jet("t < 1", 1.0).v, 0.0);
  EXPECT_EQ(jet("t <= 1", 1.0).v, 1.0);
  EXPECT_EQ(jet("t > 1", 1.0).v, 0.0);
  EXPECT_EQ(jet("t >= 1", 1.0).v, 1.0);
  EXPECT_EQ(jet("2*t >= 1 + t", 3.0).v, 1.0);
  EXPECT_EQ(jet("t < 1", 0.5).d, 0.0);
  EXPECT_EQ(jet("step(t - 2)", 2.0).v, 1.0);
  EXPECT_EQ(jet("step(t - 2)", std::nextafter(2.0, 0.0)).v, 0.0);
  EXPECT_EQ(jet("step(t - 2)", 3.0).d, 0.0);
  // min(t², 4 − t): t² below 4 − t for t < (√17 − 1)/2 ≈ 1.56.
  const Jet lo = jet("min(t^2, 4 - t)", 1.0), hi = jet("min(t^2, 4 - t)", 2.0);
  EXPECT_EQ(lo.v, 1.0);
  EXPECT_EQ(lo.d, 2.0);
  EXPECT_EQ(lo.dd, 2.0);
  EXPECT_EQ(hi.v, 2.0);
  EXPECT_EQ(hi.d, -1.0);
  EXPECT_EQ(hi.dd, 0.0);
  const Jet mx = jet("max(t^2, 4 - t)", 1.0);
  EXPECT_EQ(mx.v, 3.0);
  EXPECT_EQ(mx.d, -1.0);
  // A tie at t = 1: min(t, 2 − t) = 1; to the right 2 − t is the smaller (slope −1), max's is t (+1).
  EXPECT_EQ(jet("min(t, 2 - t)", 1.0).d, -1.0);
  EXPECT_EQ(jet("max(t, 2 - t)", 1.0).d, 1.0);
  const Jet br = jet("if(t < 1, 3*t^2, sqrt(-t))", 0.5);
  EXPECT_EQ(br.v, 0.75);
  EXPECT_EQ(br.d, 3.0);
  EXPECT_EQ(br.dd, 6.0);
  const Jet other = jet("if(t < 1, sqrt(-t), 5*t)", 2.0);
  EXPECT_EQ(other.v, 10.0);
  EXPECT_EQ(other.d, 5.0);
  // Comparisons are numbers: (t > 1)*(t < 2) is 1 on (1, 2).
  EXPECT_EQ(jet("(t > 1)*(t < 2)", 1.5).v, 1.0);
  EXPECT_EQ(jet("(t > 1)*(t < 2)", 2.5).v, 0.0);
  // NaN in, NaN out (a domain error is not hidden by a switch).
  EXPECT_TRUE(std::isnan(jet("step(sqrt(t))", -1.0).v));
  EXPECT_TRUE(std::isnan(jet("min(log(t), 1)", -1.0).v));
  EXPECT_TRUE(std::isnan(jet("if(sqrt(t) < 1, 1, 2)", -1.0).v));
  // Several variables: the derivative with respect to the one asked for.
  const Expression f("max(x, 0)*(t < 3) + min(v, 2*t)", std::vector<std::string>{"t", "x", "v"});
  const double at[3] = {1.0, 0.5, 3.0};
  EXPECT_EQ(f.eval_at(at, 1).d, 1.0);  // ∂/∂x of max(x, 0) at x > 0, t < 3
  EXPECT_EQ(f.eval_at(at, 2).d, 0.0);  // v = 3 > 2 t = 2: min is 2 t
  EXPECT_EQ(f.eval_at(at, 0).d, 2.0);  // ∂/∂t of 2 t
  EXPECT_EQ(f.eval_at(at, -1).v, 2.5);
}

// Claim: bad forms of the switches are errors at their character: a condition that is not a
// comparison, chained comparisons, '=', too few or too many arguments.
TEST(ExpressionSwitch, BadFormsNameThePlace) {
  auto message = [](const char* text) {
    try {
      Expression e(text, "t");
    } catch (const ExpressionError& ex) {
      return std::string(ex.what());
    }
    return std::string("accepted");
  };
  EXPECT_EQ(message("if(t, 1, 2)"), "at character 4: the condition of if must be a comparison (<, >, <= or >=)");
  EXPECT_EQ(message("1 < t < 2"), "at character 7: comparisons do not chain: write if(a < b, ...) or (a < b)*(b < c)");
  EXPECT_EQ(message("t == 1"), "at character 3: '=' is not an operator here; compare with <, >, <= or >=");
  EXPECT_EQ(message("min(t)"), "at character 6: min(a, b): expected ',' before argument 2");
  EXPECT_EQ(message("max(t, 1, 2)"), "at character 11: max(a, b): too many arguments");
  EXPECT_EQ(message("if(t < 1, 2)"), "at character 12: if(c, a, b): expected ',' before argument 3");
  EXPECT_EQ(message("step t"), "at character 6: expected '(' after step");
  EXPECT_EQ(message("t <"), "at character 4: expected a number, a name or '(' but the expression ended");
}

// Claim: switch_points lists each switch of an argument in the one variable as the first double on
// its new side (the expression is on the old side at the double before), so a breakpoint there lets
// a step end on the old value and the next start on the new one. Hand values: step(t − 0.3) first
// holds at t = 0.3 (0.3 − 0.3 = 0 ≥ 0); t > 0.3 at the double after 0.3; min(t, 1 − t) has its kink
// where t = 1 − t; (t − 0.5)² < 0.01 holds on (0.4, 0.6); sin(2π (t − 1e-4)) > 1 − 1e-8 holds on a
// window of ±acos(1 − 1e-8)/(2π) = ±2.25e-5 s around 0.2501 s, narrower than the sample step
// 1/4096 s, and is found through the extremum of its argument inside that step. A switch of another variable,
// or of two, is not listed (a law of the state has no breakpoints).
TEST(ExpressionSwitch, SwitchPointsAreTheFirstDoublesOnTheNewSide) {
  auto points = [](const char* text, double lo, double hi) { return Expression(text, "t").switch_points(0, lo, hi); };
  EXPECT_EQ(points("step(t - 0.3)", 0.0, 1.0), std::vector<double>{0.3});
  EXPECT_EQ(points("t > 0.3", 0.0, 1.0), std::vector<double>{std::nextafter(0.3, 1.0)});
  EXPECT_EQ(points("if(t >= 0.25, 1, 0) + (t < 0.75)", 0.0, 1.0), (std::vector<double>{0.25, 0.75}));
  const auto kink = points("min(t, 1 - t)", 0.0, 1.0);
  ASSERT_EQ(kink.size(), 1u);
  EXPECT_EQ(kink[0], std::nextafter(0.5, 1.0));  // t ≤ 1 − t holds at 0.5, not at the double after
  const auto window = points("(t - 0.5)^2 < 0.01", 0.0, 1.0);
  ASSERT_EQ(window.size(), 2u);
  EXPECT_NEAR(window[0], 0.4, 1e-15);
  EXPECT_NEAR(window[1], 0.6, 1e-15);
  const Expression e("sin(2*pi*(t - 1e-4)) > 1 - 1e-8", "t");
  const auto narrow = e.switch_points(0, 0.0, 1.0);
  ASSERT_EQ(narrow.size(), 2u);
  const double half = std::acos(1 - 1e-8) / (2 * std::numbers::pi);
  EXPECT_NEAR(narrow[0], 0.2501 - half, 1e-9);
  EXPECT_NEAR(narrow[1], 0.2501 + half, 1e-9);
  for (double b : narrow) EXPECT_NE(e(b), e(std::nextafter(b, 0.0)));  // each the first double on the new side
  EXPECT_TRUE(points("step(t - 2)", 0.0, 1.0).empty());  // outside the interval
  const Expression g("step(x - 1) + (t < 2) + min(x, t)", std::vector<std::string>{"t", "x"});
  EXPECT_EQ(g.switch_points(0, 0.0, 5.0), std::vector<double>{2.0});
}

// Claim: refuse_switches throws at the first switch that depends on the variable, with the
// caller's reason; kinks (min, max) only when asked; switches of other variables pass.
TEST(ExpressionSwitch, RefusedSwitchesNameThePlace) {
  const Expression f("3*t + max(v, 0) + 2*step(v - 1)", std::vector<std::string>{"t", "x", "v"});
  EXPECT_NO_THROW(f.refuse_switches(1, true, "x"));
  try {
    f.refuse_switches(2, false, "a jump");
    ADD_FAILURE() << "accepted";
  } catch (const ExpressionError& e) {
    EXPECT_EQ(e.column(), 21);
    EXPECT_EQ(std::string(e.what()), "at character 21: step of v: a jump");
  }
  try {
    f.refuse_switches(2, true, "a kink");
    ADD_FAILURE() << "accepted";
  } catch (const ExpressionError& e) {
    EXPECT_EQ(e.column(), 7);
  }
  EXPECT_NO_THROW(Expression("if(t < 1, v, 2*v)", std::vector<std::string>{"t", "v"}).refuse_switches(1, true, ""));
}


}  // namespace
}  // namespace machdyn
