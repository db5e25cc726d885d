#include "machdyn/common/expression.hpp"

#include <cctype>
#include <cmath>
#include <algorithm>
#include <cstdlib>
#include <numbers>
#include <utility>

namespace machdyn {

Jet operator+(const Jet& a, const Jet& b) { return {a.v + b.v, a.d + b.d, a.dd + b.dd}; }
Jet operator-(const Jet& a, const Jet& b) { return {a.v - b.v, a.d - b.d, a.dd - b.dd}; }
Jet operator-(const Jet& a) { return {-a.v, -a.d, -a.dd}; }
Jet operator*(const Jet& a, const Jet& b) {
  return {a.v * b.v, a.d * b.v + a.v * b.d, a.dd * b.v + 2.0 * a.d * b.d + a.v * b.dd};
}
Jet operator*(double c, const Jet& a) { return {c * a.v, c * a.d, c * a.dd}; }
Jet chain(const Jet& a, double f, double f1, double f2) {
  return {f, f1 * a.d, f2 * a.d * a.d + f1 * a.dd};
}
Jet operator/(const Jet& a, const Jet& b) {
  const double x = b.v;  // 1/x: f' = -1/x², f'' = 2/x³
  return a * chain(b, 1.0 / x, -1.0 / (x * x), 2.0 / (x * x * x));
}

namespace {
Jet jet_pow(const Jet& a, const Jet& b) {
  if (b.d == 0.0 && b.dd == 0.0) {  // constant exponent n: f = x^n
    const double n = b.v, x = a.v;
    if (n == 0.0) return Jet::constant(1.0);
    return chain(a, std::pow(x, n), n * std::pow(x, n - 1.0), n * (n - 1.0) * std::pow(x, n - 2.0));
  }
  // a^b = exp(b log a)
  Jet l = chain(a, std::log(a.v), 1.0 / a.v, -1.0 / (a.v * a.v));
  Jet e = b * l;
  const double ex = std::exp(e.v);
  return chain(e, ex, ex, ex);
}
}  // namespace

ExpressionError::ExpressionError(int column, const std::string& message)
    : std::invalid_argument("at character " + std::to_string(column) + ": " + message), column_(column) {}

/// Recursive descent over the grammar in the header; builds the node array of an Expression.
class ExpressionParser {
 public:
  ExpressionParser(Expression& e, std::string_view s, const std::vector<std::string>& vars) : e_(e), s_(s), vars_(vars) {}

  int parse() {
    int r = expr();
    skip();
    if (p_ < s_.size()) fail(std::string("unexpected '") + s_[p_] + "'");
    return r;
  }

 private:
  using Op = Expression::Op;
  [[noreturn]] void fail(const std::string& m) const { throw ExpressionError(static_cast<int>(p_) + 1, m); }
  void skip() {
    while (p_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[p_]))) ++p_;
  }
  bool eat(char c) {
    skip();
    if (p_ < s_.size() && s_[p_] == c) {
      ++p_;
      return true;
    }
    return false;
  }
  // Evaluation recurses over the tree and parsing over the nesting, so both are bounded: a
  // hostile or runaway text (20 000 parentheses, a chain of 10^5 '^') is an error, not a stack overflow.
  int add(Op op, int a = -1, int b = -1, double v = 0.0) {
    int h = 1;
    for (int k : {a, b})
      if (k >= 0) h = std::max(h, 1 + height_[static_cast<std::size_t>(k)]);
    if (h > Expression::kMaxDepth)
      fail("the expression is nested deeper than " + std::to_string(Expression::kMaxDepth) +
           " operations; split it or simplify it");
    e_.nodes_.push_back({op, v, a, b});
    height_.push_back(h);
    return static_cast<int>(e_.nodes_.size()) - 1;
  }
  /// Counts one level of parser recursion for the lifetime of a nested call.
  struct Nest {
    explicit Nest(ExpressionParser& p) : p_(p) {
      if (++p_.nesting_ > Expression::kMaxDepth)
        p_.fail("the expression is nested deeper than " + std::to_string(Expression::kMaxDepth) +
                " levels (parentheses, signs or powers)");
    }
    ~Nest() { --p_.nesting_; }
    Nest(const Nest&) = delete;
    Nest& operator=(const Nest&) = delete;
    ExpressionParser& p_;
  };
  int expr() {
    int l = term();
    for (;;) {
      if (eat('+')) l = add(Op::Add, l, term());
      else if (eat('-')) l = add(Op::Sub, l, term());
      else return l;
    }
  }
  int term() {
    int l = unary();
    for (;;) {
      if (eat('*')) l = add(Op::Mul, l, unary());
      else if (eat('/')) l = add(Op::Div, l, unary());
      else return l;
    }
  }
  int unary() {
    if (eat('-')) {
      Nest nest(*this);
      return add(Op::Neg, unary());
    }
    if (eat('+')) {
      Nest nest(*this);
      return unary();
    }
    return power();
  }
  int power() {
    int b = primary();
    if (eat('^')) {
      Nest nest(*this);
      return add(Op::Pow, b, unary());
    }
    return b;
  }
  int primary() {
    skip();
    if (p_ >= s_.size()) fail("expected a number, a name or '(' but the expression ended");
    const char c = s_[p_];
    if (c == '(') {
      ++p_;
      Nest nest(*this);
      int r = expr();
      if (!eat(')')) fail("expected ')'");
      return r;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      std::string rest(s_.substr(p_));
      char* end = nullptr;
      double v = std::strtod(rest.c_str(), &end);
      if (end == rest.c_str()) fail("bad number");
      p_ += static_cast<std::size_t>(end - rest.c_str());
      return add(Op::Num, -1, -1, v);
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      const std::size_t start = p_;
      while (p_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[p_])) || s_[p_] == '_')) ++p_;
      const std::string name(s_.substr(start, p_ - start));
      for (std::size_t k = 0; k < vars_.size(); ++k)
        if (name == vars_[k]) {
          const int node = add(Op::Var);
          e_.nodes_.back().a = static_cast<int>(k);  // the variable's index, not a child node
          return node;
        }
      if (name == "pi") return add(Op::Num, -1, -1, std::numbers::pi);
      if (name == "e") return add(Op::Num, -1, -1, std::numbers::e);
      static const std::pair<const char*, Op> funcs[] = {
          {"sin", Op::Sin},   {"cos", Op::Cos},   {"tan", Op::Tan},   {"asin", Op::Asin}, {"acos", Op::Acos},
          {"atan", Op::Atan}, {"sinh", Op::Sinh}, {"cosh", Op::Cosh}, {"tanh", Op::Tanh}, {"exp", Op::Exp},
          {"log", Op::Log},   {"sqrt", Op::Sqrt}, {"abs", Op::Abs}};
      for (const auto& [fname, op] : funcs) {
        if (name == fname) {
          if (!eat('(')) fail("expected '(' after " + name);
          Nest nest(*this);
          int a = expr();
          if (!eat(')')) fail("expected ')'");
          return add(op, a);
        }
      }
      p_ = start;
      std::string known;
      for (const auto& v : vars_) known += v + ", ";
      fail("unknown name '" + name + "'; known: " + known +
           "pi, e, sin, cos, tan, asin, acos, atan, sinh, cosh, tanh, exp, log, sqrt, abs");
    }
    fail(std::string("unexpected '") + c + "'");
  }

  Expression& e_;
  std::string_view s_;
  const std::vector<std::string>& vars_;
  std::size_t p_ = 0;
  int nesting_ = 0;
  std::vector<int> height_;  ///< height of each node's subtree
};

Expression::Expression(std::string_view text, std::string variable)
    : Expression(text, std::vector<std::string>{std::move(variable)}) {}

Expression::Expression(std::string_view text, std::vector<std::string> variables)
    : text_(text), variables_(std::move(variables)) {
  if (variables_.size() > 8) throw std::invalid_argument("an expression has at most 8 variables");
  ExpressionParser p(*this, text_, variables_);
  root_ = p.parse();
}

Jet Expression::eval(const Jet& x) const { return eval_node(root_, &x); }

Jet Expression::eval_at(const double* x, int wrt) const {
  // At most a handful of variables (t, q, v): a small array of jets on the stack.
  Jet j[8];
  const std::size_t n = std::min<std::size_t>(variables_.size(), 8);
  for (std::size_t k = 0; k < n; ++k)
    j[k] = static_cast<int>(k) == wrt ? Jet::variable(x[k]) : Jet::constant(x[k]);
  return eval_node(root_, j);
}

bool Expression::uses(int k) const {
  for (const Node& n : nodes_)
    if (n.op == Op::Var && n.a == k) return true;
  return false;
}

Jet Expression::eval_node(int i, const Jet* x) const {
  const Node& n = nodes_[static_cast<std::size_t>(i)];
  switch (n.op) {
    case Op::Num: return Jet::constant(n.value);
    case Op::Var: return x[n.a];
    case Op::Add: return eval_node(n.a, x) + eval_node(n.b, x);
    case Op::Sub: return eval_node(n.a, x) - eval_node(n.b, x);
    case Op::Mul: return eval_node(n.a, x) * eval_node(n.b, x);
    case Op::Div: return eval_node(n.a, x) / eval_node(n.b, x);
    case Op::Pow: return jet_pow(eval_node(n.a, x), eval_node(n.b, x));
    case Op::Neg: return -eval_node(n.a, x);
    default: break;
  }
  const Jet a = eval_node(n.a, x);
  const double v = a.v;
  switch (n.op) {
    case Op::Sin: return chain(a, std::sin(v), std::cos(v), -std::sin(v));
    case Op::Cos: return chain(a, std::cos(v), -std::sin(v), -std::cos(v));
    case Op::Tan: {
      const double t = std::tan(v);
      return chain(a, t, 1.0 + t * t, 2.0 * t * (1.0 + t * t));
    }
    case Op::Exp: {
      const double ex = std::exp(v);
      return chain(a, ex, ex, ex);
    }
    case Op::Log: return chain(a, std::log(v), 1.0 / v, -1.0 / (v * v));
    case Op::Asin: {  // (1 − v²)^(−1/2), v (1 − v²)^(−3/2)
      const double s = 1.0 - v * v;
      return chain(a, std::asin(v), 1.0 / std::sqrt(s), v / (s * std::sqrt(s)));
    }
    case Op::Acos: {
      const double s = 1.0 - v * v;
      return chain(a, std::acos(v), -1.0 / std::sqrt(s), -v / (s * std::sqrt(s)));
    }
    case Op::Atan: {  // 1/(1 + v²), −2v/(1 + v²)²
      const double s = 1.0 + v * v;
      return chain(a, std::atan(v), 1.0 / s, -2.0 * v / (s * s));
    }
    case Op::Sinh: return chain(a, std::sinh(v), std::cosh(v), std::sinh(v));
    case Op::Cosh: return chain(a, std::cosh(v), std::sinh(v), std::cosh(v));
    case Op::Tanh: {  // sech² v, −2 tanh v sech² v
      const double th = std::tanh(v), s2 = 1.0 - th * th;
      return chain(a, th, s2, -2.0 * th * s2);
    }
    case Op::Sqrt: {
      const double r = std::sqrt(v);
      return chain(a, r, 0.5 / r, -0.25 / (r * v));
    }
    case Op::Abs: return chain(a, std::abs(v), v < 0.0 ? -1.0 : 1.0, 0.0);
    default: return Jet::constant(std::nan(""));
  }
}

}  // namespace machdyn
