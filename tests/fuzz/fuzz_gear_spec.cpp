// libFuzzer harness: a gear spec file, as `machdyn gears` reads it (YAML → spec → compile_gears).
// The only acceptable failure is InputError.
#include <cstddef>
#include <cstdint>
#include <string>

#include "machdyn/gears/gear_model.hpp"
#include "machdyn/io/yaml_reader.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const machdyn::SpecNode root = machdyn::parse_yaml_string(text, "fuzz-gears.yaml");
    (void)machdyn::gears::compile_gears(root);
  } catch (const machdyn::InputError&) {
  }
  return 0;
}
