// libFuzzer harness: an expression of one variable (gear laws, I(q)) and of three (a load in t, x,
// v). Parsing either succeeds or throws ExpressionError; evaluation of what parses never crashes
// (NaN is allowed: callers check), and neither do the switches' breakpoints or refusals.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "machdyn/common/expression.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const machdyn::Expression e(text, "phi");
    double f = 0.0, df = 0.0;
    for (double x : {-1.0, 0.0, 0.5, 3.0}) e.evaluate(x, &f, &df);
    if (size < 256) (void)e.switch_points(0, -1.0, 3.0);
    e.refuse_switches(0, true, "fuzz");
  } catch (const machdyn::ExpressionError&) {
  }
  try {
    const machdyn::Expression e(text, std::vector<std::string>{"t", "x", "v"});
    const double at[3] = {0.5, -0.25, 2.0};
    for (int k = -1; k < 3; ++k) (void)e.eval_at(at, k);
    e.refuse_switches(2, false, "fuzz");
  } catch (const machdyn::ExpressionError&) {
  }
  return 0;
}
