#pragma once
/// @file
/// A small, safe expression language in one variable for laws written in input files: gear ratio
/// and travel laws (`1.25248*(1 + 0.9375*cos(2*phi))`), reduced inertias I(q) (`0.5 + 0.12*sin(q)^2`).
/// It is parsed once into a tree (nothing is executed) and evaluated on second-order jets, so the
/// first and second derivatives come out exactly (forward-mode differentiation): dI/dq needs no
/// finite difference, and the pitch-curve curvature needs i, di/dφ and d²i/dφ².
///
/// Grammar (usual precedence, `^` right-associative and above unary minus: `-2^2` = -4):
///   top := cmp;  cmp := expr [('<'|'>'|'<='|'>=') expr]      (comparisons do not chain)
///   expr := term (('+'|'-') term)*;  term := unary (('*'|'/') unary)*
///   unary := ('+'|'-') unary | power;  power := primary ['^' unary]
///   primary := number | 'pi' | 'e' | variable | func '(' cmp ')' | func2 '(' cmp ',' cmp ')'
///            | 'if' '(' comparison ',' cmp ',' cmp ')' | '(' cmp ')'
/// Functions: sin cos tan asin acos atan sinh cosh tanh exp log sqrt abs step; min max (two
/// arguments); if (three). Numbers are plain (no units, the value is SI); angles are in radians.
/// Switches (exact values and derivatives on each side; NaN in, NaN out):
///   a < b, a > b, a <= b, a >= b   1 where it holds, else 0 (derivative 0)
///   step(x)                        1 for x ≥ 0, 0 for x < 0
///   min(a, b), max(a, b)           the smaller (larger) argument with its derivatives; at a tie the
///                                  one that stays smaller (larger) to the right (the right derivative)
///   if(c, a, b)                    a where the comparison c holds, else b (only that branch is evaluated)
/// A switch jumps (step, comparisons, if) or has a kink (min, max) where its argument changes side:
/// switch_points() lists those places for the callers that must stop there (a signal in t: its
/// breakpoints), refuse_switches() refuses them where no such stop exists (a law of the state).
/// abs has a kink at 0 but is not a switch (its kink is the caller's, as before).
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

  /// The values of variable k in the open interval (lo, hi), increasing without repeats, where a
  /// switch whose argument depends on variable k alone changes side: each the first double on the
  /// new side, so the expression is on the old side everywhere before it and on the new one from it
  /// (a breakpoint a step can end at and restart from). Found from the argument g (step: x; a
  /// comparison, min, max: a − b) sampled at 4096 equal steps and at each extremum of g between two
  /// samples, each change of side refined by bisection to the last bit: exact for an argument with
  /// at most one extremum between samples (an affine one always); two extrema within one sample
  /// step can hide a pair of switches.
  [[nodiscard]] std::vector<double> switch_points(int k, double lo, double hi) const;
  /// Throws ExpressionError at the first switch whose argument depends on variable k: any switch
  /// (kinks_too) or only those that jump (step, comparisons, if). `why` ends the message.
  void refuse_switches(int k, bool kinks_too, const std::string& why) const;

 private:
  enum class Op {
    Num, Var, Add, Sub, Mul, Div, Pow, Neg, Sin, Cos, Tan, Asin, Acos, Atan, Sinh, Cosh, Tanh, Exp, Log, Sqrt, Abs,
    Step, Min, Max, If, Lt, Gt, Le, Ge
  };
  struct Node {
    Op op;
    double value = 0.0;  ///< Op::Num
    int a = -1, b = -1;  ///< operand node indices (Op::Var: a is the variable's index)
    int c = -1;          ///< Op::If: the else branch (a: the condition, b: the then branch)
    int column = 0;      ///< 1-based character of the operator or function name in the text
  };
  friend class ExpressionParser;
  [[nodiscard]] Jet eval_node(int i, const Jet* x) const;
  /// Whether the subtree at node i uses variable k; uses_only: no other variable.
  [[nodiscard]] bool subtree_uses(int i, int k) const;
  [[nodiscard]] bool subtree_uses_only(int i, int k) const;
  /// The side of switch node i with every variable at x[]: 1 or 0 (NaN: −1).
  [[nodiscard]] int side(int i, const Jet* x) const;
  std::string text_;
  std::vector<std::string> variables_;
  std::vector<Node> nodes_;
  int root_ = -1;
};

}  // namespace machdyn
