#pragma once
/// @file
/// A small, safe expression language in one variable for laws written in input files: gear ratio
/// and travel laws (`1.25248*(1 + 0.9375*cos(2*phi))`), reduced inertias I(q) (`0.5 + 0.12*sin(q)^2`).
/// It is parsed once into a tree (nothing is executed) and evaluated on second-order jets, so the
/// first and second derivatives come out exactly (forward-mode differentiation): dI/dq needs no
/// finite difference, and the pitch-curve curvature needs i, di/dφ and d²i/dφ².
///
/// Grammar (usual precedence, `^` right-associative and above unary minus: `-2^2` = -4):
///   expr := term (('+'|'-') term)*;  term := unary (('*'|'/') unary)*
///   unary := ('+'|'-') unary | power;  power := primary ['^' unary]
///   primary := number | 'pi' | 'e' | variable | func '(' expr ')' | '(' expr ')'
/// Functions: sin cos tan asin acos atan sinh cosh tanh exp log sqrt abs. Numbers are plain (no
/// units, the value is SI); angles are in radians.
/// Nothing else is accepted: no assignment, no other names, no I/O. Nesting and tree height are
/// bounded by Expression::kMaxDepth (200), so evaluation cannot exhaust the stack.

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace machdyn {

/// Value and first two derivatives of a function of one variable x: (f, df/dx, d²f/dx²).
struct Jet {
  double v = 0.0, d = 0.0, dd = 0.0;
  static Jet constant(double c) { return {c, 0.0, 0.0}; }
  static Jet variable(double x) { return {x, 1.0, 0.0}; }
};

Jet operator+(const Jet& a, const Jet& b);
Jet operator-(const Jet& a, const Jet& b);
Jet operator-(const Jet& a);
Jet operator*(const Jet& a, const Jet& b);
Jet operator/(const Jet& a, const Jet& b);
Jet operator*(double c, const Jet& a);
/// Chain rule for g = f(a), given f, f', f'' at a.v.
Jet chain(const Jet& a, double f, double f1, double f2);

/// A syntax error: `column` is the 1-based character of the expression where it was found; the
/// message reads "at character N: what was expected".
class ExpressionError : public std::invalid_argument {
 public:
  ExpressionError(int column, const std::string& message);
  [[nodiscard]] int column() const { return column_; }

 private:
  int column_;
};

/// A parsed expression of one variable. Immutable after parsing; evaluation does not throw
/// (domain errors give NaN, which the callers check).
class Expression {
 public:
  /// Bound on both the nesting of the text (parentheses, signs, powers) and the height of the
  /// parsed tree (a sum of n terms has height n); deeper texts throw ExpressionError.
  static constexpr int kMaxDepth = 200;
  /// Parses `text` with variable name `variable` (e.g. "phi", "q"). Throws ExpressionError.
  Expression(std::string_view text, std::string variable);
  /// Parses `text` in several variables (e.g. {"t", "phi", "omega"}); eval_at() takes their values
  /// in this order. Throws ExpressionError.
  Expression(std::string_view text, std::vector<std::string> variables);
  [[nodiscard]] Jet eval(const Jet& x) const;
  /// The value at x[0..n) (n = number of variables) and its derivatives with respect to x[wrt]
  /// (wrt < 0: none, the jet is constant).
  [[nodiscard]] Jet eval_at(const double* x, int wrt) const;
  /// Whether variable k occurs in the text.
  [[nodiscard]] bool uses(int k) const;
  [[nodiscard]] double operator()(double x) const { return eval(Jet::constant(x)).v; }
  /// The value f(x) and the derivative f'(x).
  void evaluate(double x, double* f, double* df) const {
    const Jet j = eval(Jet::variable(x));
    *f = j.v, *df = j.d;
  }
  [[nodiscard]] const std::string& text() const { return text_; }

 private:
  enum class Op { Num, Var, Add, Sub, Mul, Div, Pow, Neg, Sin, Cos, Tan, Asin, Acos, Atan, Sinh, Cosh, Tanh, Exp, Log, Sqrt, Abs };
  struct Node {
    Op op;
    double value = 0.0;  ///< Op::Num
    int a = -1, b = -1;  ///< operand node indices (Op::Var: a is the variable's index)
  };
  friend class ExpressionParser;
  [[nodiscard]] Jet eval_node(int i, const Jet* x) const;
  std::string text_;
  std::vector<std::string> variables_;
  std::vector<Node> nodes_;
  int root_ = -1;
};

}  // namespace machdyn
