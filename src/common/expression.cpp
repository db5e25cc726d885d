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
    int r = cmp();
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
  int add(Op op, int a = -1, int b = -1, double v = 0.0, int c = -1, int column = 0) {
    int h = 1;
    for (int k : {a, b, c})
      if (k >= 0) h = std::max(h, 1 + height_[static_cast<std::size_t>(k)]);
    if (h > Expression::kMaxDepth)
      fail("the expression is nested deeper than " + std::to_string(Expression::kMaxDepth) +
           " operations; split it or simplify it");
    e_.nodes_.push_back({op, v, a, b, c, column});
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
  /// The comparison operator at the current character (after blanks), its length in `len`.
  Op comparison(std::size_t* len) {
    skip();
    *len = 0;
    if (p_ >= s_.size() || (s_[p_] != '<' && s_[p_] != '>')) return Op::Num;
    const bool eq = p_ + 1 < s_.size() && s_[p_ + 1] == '=';
    *len = eq ? 2 : 1;
    return s_[p_] == '<' ? (eq ? Op::Le : Op::Lt) : (eq ? Op::Ge : Op::Gt);
  }
  int cmp() {
    int l = expr();
    std::size_t len = 0;
    const Op op = comparison(&len);
    if (len == 0) {
      skip();
      if (p_ < s_.size() && s_[p_] == '=')
        fail("'=' is not an operator here; compare with <, >, <= or >=");
      return l;
    }
    const int column = static_cast<int>(p_) + 1;
    p_ += len;
    const int r = add(op, l, expr(), 0.0, -1, column);
    if (comparison(&len) != Op::Num)
      fail("comparisons do not chain: write if(a < b, ...) or (a < b)*(b < c)");
    return r;
  }
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
      int r = cmp();
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
          {"log", Op::Log},   {"sqrt", Op::Sqrt}, {"abs", Op::Abs},   {"step", Op::Step}, {"min", Op::Min},
          {"max", Op::Max},   {"if", Op::If}};
      const int column = static_cast<int>(start) + 1;
      for (const auto& [fname, op] : funcs) {
        if (name == fname) {
          if (!eat('(')) fail("expected '(' after " + name);
          Nest nest(*this);
          const int args = op == Op::If ? 3 : op == Op::Min || op == Op::Max ? 2 : 1;
          int arg[3] = {-1, -1, -1};
          for (int k = 0; k < args; ++k) {
            if (k > 0 && !eat(','))
              fail(fmt_args(name, args) + ": expected ',' before argument " + std::to_string(k + 1));
            skip();
            const std::size_t at = p_;
            arg[k] = cmp();
            const Op got = e_.nodes_[static_cast<std::size_t>(arg[k])].op;
            if (op == Op::If && k == 0 && got != Op::Lt && got != Op::Gt && got != Op::Le && got != Op::Ge) {
              p_ = at;
              fail("the condition of if must be a comparison (<, >, <= or >=)");
            }
          }
          if (!eat(')')) {
            if (args > 1 && eat(',')) {
              skip();
              fail(fmt_args(name, args) + ": too many arguments");
            }
            fail("expected ')'");
          }
          return add(op, arg[0], arg[1], 0.0, arg[2], column);
        }
      }
      p_ = start;
      std::string known;
      for (const auto& v : vars_) known += v + ", ";
      fail("unknown name '" + name + "'; known: " + known +
           "pi, e, sin, cos, tan, asin, acos, atan, sinh, cosh, tanh, exp, log, sqrt, abs, step, min, max, if");
    }
    fail(std::string("unexpected '") + c + "'");
  }

  static std::string fmt_args(const std::string& name, int n) {
    return name + (n == 3 ? "(c, a, b)" : n == 2 ? "(a, b)" : "(x)");
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
    case Op::If: {  // only the branch taken is evaluated (if(x > 0, sqrt(x), 0) is defined everywhere)
      const double c = eval_node(n.a, x).v;
      if (std::isnan(c)) return Jet::constant(c);
      return eval_node(c != 0.0 ? n.b : n.c, x);
    }
    case Op::Step:
    case Op::Lt:
    case Op::Gt:
    case Op::Le:
    case Op::Ge: {
      const int sd = side(i, x);
      return Jet::constant(sd < 0 ? std::nan("") : static_cast<double>(sd));
    }
    case Op::Min:
    case Op::Max: {
      const Jet a = eval_node(n.a, x), b = eval_node(n.b, x);
      if (std::isnan(a.v) || std::isnan(b.v)) return Jet::constant(std::nan(""));
      // The smaller (larger) value; at a tie the one that stays smaller (larger) to the right: the
      // right derivative, as a signal's slope at its breakpoint.
      const double sg = n.op == Op::Min ? 1.0 : -1.0;
      const bool first = sg * a.v < sg * b.v ||
                         (a.v == b.v && (sg * a.d < sg * b.d || (a.d == b.d && sg * a.dd <= sg * b.dd)));
      return first ? a : b;
    }
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

int Expression::side(int i, const Jet* x) const {
  const Node& n = nodes_[static_cast<std::size_t>(i)];
  const double a = eval_node(n.a, x).v;
  if (n.op == Op::Step) return std::isnan(a) ? -1 : a >= 0.0;
  const double b = eval_node(n.b, x).v;
  if (std::isnan(a) || std::isnan(b)) return -1;
  switch (n.op) {
    case Op::Lt: return a < b;
    case Op::Gt: return a > b;
    case Op::Le:
    case Op::Min: return a <= b;
    case Op::Ge:
    case Op::Max: return a >= b;
    default: return -1;
  }
}

bool Expression::subtree_uses(int i, int k) const {
  if (i < 0) return false;
  const Node& n = nodes_[static_cast<std::size_t>(i)];
  if (n.op == Op::Var) return n.a == k;
  return subtree_uses(n.a, k) || subtree_uses(n.b, k) || subtree_uses(n.c, k);
}

bool Expression::subtree_uses_only(int i, int k) const {
  if (i < 0) return true;
  const Node& n = nodes_[static_cast<std::size_t>(i)];
  if (n.op == Op::Var) return n.a == k;
  return subtree_uses_only(n.a, k) && subtree_uses_only(n.b, k) && subtree_uses_only(n.c, k);
}

std::vector<double> Expression::switch_points(int k, double lo, double hi) const {
  std::vector<double> out;
  if (!(hi > lo) || k < 0 || k >= static_cast<int>(variables_.size())) return out;
  Jet x[8];
  for (int i = 0; i < static_cast<int>(nodes_.size()); ++i) {
    const Node& n = nodes_[static_cast<std::size_t>(i)];
    const bool sw = n.op == Op::Step || n.op == Op::Lt || n.op == Op::Gt || n.op == Op::Le || n.op == Op::Ge ||
                    n.op == Op::Min || n.op == Op::Max;
    if (!sw || !subtree_uses(i, k) || !subtree_uses_only(i, k)) continue;
    // The argument g (step: x; the others: a − b) and its derivative in variable k.
    auto g = [&](double t) {
      x[k] = Jet::variable(t);
      Jet v = eval_node(n.a, x);
      if (n.op != Op::Step) v = v - eval_node(n.b, x);
      return v;
    };
    auto sd = [&](double t) {
      x[k] = Jet::constant(t);
      return side(i, x);
    };
    // The first double on the side of b from a pair (a, b) on different sides.
    auto refine = [&](double a, double b) {
      const int s0 = sd(a);
      for (int it = 0; it < 2200; ++it) {
        const double mid = a + 0.5 * (b - a);
        if (!(mid > std::min(a, b) && mid < std::max(a, b))) break;
        (sd(mid) == s0 ? a : b) = mid;
      }
      if (b > lo && b < hi) out.push_back(b);
    };
    constexpr int kSamples = 4096;
    double ta = lo, da = g(lo).d;
    int sa = sd(lo);
    for (int j = 1; j <= kSamples; ++j) {
      const double tb = j == kSamples ? hi : lo + (hi - lo) * j / kSamples;
      const double db = g(tb).d;
      const int sb = sd(tb);
      double tm = tb;
      if (da * db < 0.0) {  // an extremum of g inside: bisect g' to it and look at g's side there
        double a = ta, b = tb;
        for (int it = 0; it < 200 && std::nextafter(a, b) < b; ++it) {
          const double mid = 0.5 * (a + b);
          (g(mid).d * da > 0.0 ? a : b) = mid;
        }
        tm = a;
      }
      const int sm = tm < tb ? sd(tm) : sb;
      if (tm < tb && sm >= 0 && sa >= 0 && sm != sa) refine(ta, tm);
      if (tm < tb && sm >= 0 && sb >= 0 && sm != sb) refine(tm, tb);
      if (tm == tb && sa >= 0 && sb >= 0 && sa != sb) refine(ta, tb);
      ta = tb, da = db, sa = sb;
    }
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void Expression::refuse_switches(int k, bool kinks_too, const std::string& why) const {
  const Node* first = nullptr;
  for (const Node& n : nodes_) {
    const bool jump = n.op == Op::Step || n.op == Op::Lt || n.op == Op::Gt || n.op == Op::Le || n.op == Op::Ge;
    const bool kink = n.op == Op::Min || n.op == Op::Max;
    if (!(jump || (kinks_too && kink))) continue;
    const int i = static_cast<int>(&n - nodes_.data());
    if (!subtree_uses(i, k)) continue;
    if (!first || n.column < first->column) first = &n;
  }
  if (!first) return;
  static const std::pair<Op, const char*> names[] = {{Op::Step, "step"}, {Op::Min, "min"}, {Op::Max, "max"},
                                                     {Op::Lt, "'<'"},    {Op::Gt, "'>'"},   {Op::Le, "'<='"},
                                                     {Op::Ge, "'>='"}};
  const char* what = "a switch";
  for (const auto& [op, nm] : names)
    if (op == first->op) what = nm;
  throw ExpressionError(first->column, std::string(what) + " of " + variables_[static_cast<std::size_t>(k)] + ": " + why);
}

}  // namespace machdyn
