// libFuzzer harness: a quantity with units (`1.2 kg m^2`, `1500 rpm`). Parsing never crashes,
// never overflows, and what it accepts is finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <string>

#include "machdyn/common/units.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  std::string err;
  if (auto q = machdyn::parse_quantity(text, &err)) {
    if (!std::isfinite(q->value)) std::abort();  // the header promises finite values
  } else if (err.empty()) {
    std::abort();  // a rejection always says why
  }
  (void)machdyn::parse_as(text, machdyn::dim::angular_velocity, &err);
  return 0;
}
