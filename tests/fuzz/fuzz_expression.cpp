// libFuzzer harness: an expression of one variable (gear laws, I(q)). Parsing either succeeds or
// throws ExpressionError; evaluation of what parses never crashes (NaN is allowed: callers check).
#include <cstddef>
#include <cstdint>
#include <string>

#include "machdyn/common/expression.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const machdyn::Expression e(text, "phi");
    double f = 0.0, df = 0.0;
    for (double x : {-1.0, 0.0, 0.5, 3.0}) e.evaluate(x, &f, &df);
  } catch (const machdyn::ExpressionError&) {
  }
  return 0;
}
