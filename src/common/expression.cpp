#include "machdyn/common/expression.hpp"

#include <cctype>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <stdexcept>
#include <fmt/format.h>

namespace machdyn {

/// A value with its derivative: the arithmetic of forward-mode automatic differentiation.
struct Dual {
  double v, d;
};

struct Expression::Node {
  enum class Op { constant, variable, add, sub, mul, div, pow, neg, func };
  Op op = Op::constant;
  double value = 0.0;
  std::string func;
  std::shared_ptr<const Node> a, b;

  [[nodiscard]] Dual eval(double x) const {
    switch (op) {
      case Op::constant: return {value, 0.0};
      case Op::variable: return {x, 1.0};
      case Op::neg: {
        Dual u = a->eval(x);
        return {-u.v, -u.d};
      }
      case Op::add: {
        Dual u = a->eval(x), w = b->eval(x);
        return {u.v + w.v, u.d + w.d};
      }
      case Op::sub: {
        Dual u = a->eval(x), w = b->eval(x);
        return {u.v - w.v, u.d - w.d};
      }
      case Op::mul: {
        Dual u = a->eval(x), w = b->eval(x);
        return {u.v * w.v, u.d * w.v + u.v * w.d};
      }
      case Op::div: {
        Dual u = a->eval(x), w = b->eval(x);
        return {u.v / w.v, (u.d * w.v - u.v * w.d) / (w.v * w.v)};
      }
      case Op::pow: {
        Dual u = a->eval(x), w = b->eval(x);
        const double p = std::pow(u.v, w.v);
        // d(u^w) = w u^(w-1) u' + u^w ln(u) w'; the second term only when the exponent varies.
        double d = w.v == 0.0 ? 0.0 : w.v * std::pow(u.v, w.v - 1.0) * u.d;
        if (w.d != 0.0) d += p * std::log(u.v) * w.d;
        return {p, d};
      }
      case Op::func: {
        Dual u = a->eval(x);
        const double s = u.v;
        if (func == "sin") return {std::sin(s), std::cos(s) * u.d};
        if (func == "cos") return {std::cos(s), -std::sin(s) * u.d};
        if (func == "tan") {
          const double c = std::cos(s);
          return {std::tan(s), u.d / (c * c)};
        }
        if (func == "asin") return {std::asin(s), u.d / std::sqrt(1 - s * s)};
        if (func == "acos") return {std::acos(s), -u.d / std::sqrt(1 - s * s)};
        if (func == "atan") return {std::atan(s), u.d / (1 + s * s)};
        if (func == "sinh") return {std::sinh(s), std::cosh(s) * u.d};
        if (func == "cosh") return {std::cosh(s), std::sinh(s) * u.d};
        if (func == "tanh") {
          const double t = std::tanh(s);
          return {t, (1 - t * t) * u.d};
        }
        if (func == "exp") {
          const double e = std::exp(s);
          return {e, e * u.d};
        }
        if (func == "log") return {std::log(s), u.d / s};
        if (func == "sqrt") {
          const double r = std::sqrt(s);
          return {r, u.d / (2 * r)};
        }
        if (func == "abs") return {std::abs(s), s < 0 ? -u.d : u.d};
        return {std::nan(""), 0.0};
      }
    }
    return {0.0, 0.0};
  }
};

namespace {

using NodeP = std::shared_ptr<const Expression::Node>;
using Op = Expression::Node::Op;

class Parser {
 public:
  Parser(std::string_view s, const std::string& var) : s_(s), var_(var) {}

  NodeP parse() {
    NodeP n = expr();
    skip();
    if (i_ < s_.size()) fail(fmt::format("unexpected '{}'", s_[i_]));
    return n;
  }

 private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::invalid_argument(fmt::format("at character {}: {}", i_ + 1, what));
  }
  void skip() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  bool eat(char c) {
    skip();
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  static NodeP make(Op op, NodeP a = nullptr, NodeP b = nullptr, double v = 0.0, std::string f = {}) {
    auto n = std::make_shared<Expression::Node>();
    n->op = op;
    n->a = std::move(a);
    n->b = std::move(b);
    n->value = v;
    n->func = std::move(f);
    return n;
  }

  NodeP expr() {
    NodeP n = term();
    for (;;) {
      if (eat('+')) n = make(Op::add, n, term());
      else if (eat('-')) n = make(Op::sub, n, term());
      else return n;
    }
  }
  NodeP term() {
    NodeP n = unary();
    for (;;) {
      if (eat('*')) n = make(Op::mul, n, unary());
      else if (eat('/')) n = make(Op::div, n, unary());
      else return n;
    }
  }
  NodeP unary() {
    if (eat('-')) return make(Op::neg, unary());
    if (eat('+')) return unary();
    return power();
  }
  NodeP power() {
    NodeP n = atom();
    if (eat('^')) return make(Op::pow, n, unary());
    return n;
  }
  NodeP atom() {
    skip();
    if (i_ >= s_.size()) fail("expected a number, a name or '(' but the text ended");
    const char c = s_[i_];
    if (eat('(')) {
      NodeP n = expr();
      if (!eat(')')) fail("expected ')'");
      return n;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') {
      const std::string rest(s_.substr(i_));
      char* end = nullptr;
      const double v = std::strtod(rest.c_str(), &end);
      if (end == rest.c_str()) fail("expected a number");
      i_ += static_cast<size_t>(end - rest.c_str());
      return make(Op::constant, nullptr, nullptr, v);
    }
    if (std::isalpha(static_cast<unsigned char>(c)) || c == '_') {
      const size_t start = i_;
      while (i_ < s_.size() && (std::isalnum(static_cast<unsigned char>(s_[i_])) || s_[i_] == '_')) ++i_;
      const std::string name(s_.substr(start, i_ - start));
      if (name == var_) return make(Op::variable);
      if (name == "pi") return make(Op::constant, nullptr, nullptr, std::numbers::pi);
      if (name == "e") return make(Op::constant, nullptr, nullptr, std::numbers::e);
      static const char* kFuncs[] = {"sin", "cos", "tan", "asin", "acos", "atan", "sinh",
                                     "cosh", "tanh", "exp", "log", "sqrt", "abs"};
      for (const char* f : kFuncs)
        if (name == f) {
          if (!eat('(')) fail(fmt::format("expected '(' after function '{}'", name));
          NodeP arg = expr();
          if (!eat(')')) fail("expected ')'");
          return make(Op::func, arg, nullptr, 0.0, name);
        }
      i_ = start;
      fail(fmt::format("unknown name '{}'; the variable is '{}', constants pi and e, functions sin cos tan "
                       "asin acos atan sinh cosh tanh exp log sqrt abs",
                       name, var_));
    }
    fail(fmt::format("unexpected '{}'", c));
  }

  std::string_view s_;
  const std::string& var_;
  size_t i_ = 0;
};

}  // namespace

Expression::Expression(std::string_view text, std::string variable) : text_(text) {
  root_ = Parser(text, variable).parse();
}

double Expression::operator()(double x) const { return root_->eval(x).v; }

void Expression::evaluate(double x, double* f, double* df) const {
  const Dual r = root_->eval(x);
  *f = r.v;
  *df = r.d;
}

}  // namespace machdyn
