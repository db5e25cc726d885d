#pragma once
/// @file
/// A small, safe arithmetic expression in one variable, for user-given laws such as a reduced
/// inertia I(q) = "0.5 + 0.12*sin(q)^2". No code is executed: the text is parsed once into a tree,
/// then evaluated together with its exact derivative (forward-mode automatic differentiation), so
/// dI/dq needs no finite difference.
///
/// Grammar (usual precedence, `^` right-associative and above unary minus, so -q^2 = -(q^2)):
///   expr   := term (('+' | '-') term)*
///   term   := unary (('*' | '/') unary)*
///   unary  := ('-' | '+') unary | power
///   power  := atom ['^' unary]
///   atom   := number | VARIABLE | 'pi' | 'e' | FUNCTION '(' expr ')' | '(' expr ')'
/// Functions: sin cos tan asin acos atan sinh cosh tanh exp log sqrt abs.
/// Numbers are plain (no units): the value is in SI.

#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace machdyn {

class Expression {
 public:
  /// Parses `text` with variable `variable` (e.g. "q"). Throws std::invalid_argument with the
  /// 1-based character position and what was expected, e.g. "at character 7: expected ')'".
  Expression(std::string_view text, std::string variable);

  /// The value at x.
  [[nodiscard]] double operator()(double x) const;
  /// The value f(x) and the derivative f'(x).
  void evaluate(double x, double* f, double* df) const;
  [[nodiscard]] const std::string& text() const { return text_; }

  struct Node;

 private:
  std::string text_;
  std::shared_ptr<const Node> root_;
};

}  // namespace machdyn
