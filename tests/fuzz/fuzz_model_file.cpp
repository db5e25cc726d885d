// libFuzzer harness: a model file, as `machdyn simulate` reads it (YAML → spec → compile, every
// case checked, a `--set` override applied). The only acceptable failure is InputError; anything
// else (a crash, a sanitizer report, another exception, a hang, memory exhaustion) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>

#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    machdyn::SpecNode root = machdyn::parse_yaml_string(text, "fuzz.yaml");
    (void)machdyn::compile_model(root, "fuzz.yaml");
    machdyn::apply_set(root, "simulation.t_end=0.5 s");
    (void)machdyn::compile_model(root, "fuzz.yaml");
  } catch (const machdyn::InputError&) {
  }
  return 0;
}
