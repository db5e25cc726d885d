// libFuzzer harness: the CSV of a `type: file` signal (io/signal_files.hpp), read as `machdyn
// simulate` reads it: the bytes become the signal file of a small model, the signal is resolved into
// its table and the model compiled. The only acceptable failure is InputError; anything else (a
// crash, a sanitizer report, another exception, a hang, memory exhaustion) is a bug. A table that
// compiles holds only finite, non-decreasing times (the reader's promise).
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "machdyn/io/signal_files.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

namespace {

/// A folder of this process's own (fuzzers may run side by side), holding model.yaml's data.csv.
const std::filesystem::path& folder() {
  static const std::filesystem::path dir = [] {
    auto d = std::filesystem::temp_directory_path() / ("machdyn_fuzz_csv_" + std::to_string(::getpid()));
    std::filesystem::create_directories(d);
    return d;
  }();
  return dir;
}

constexpr const char* kModel =
    "bodies:\n"
    "  I1: {type: rotational, inertia: 1 kg*m^2}\n"
    "links:\n"
    "  c1: {type: spring, between: [I1, ground], stiffness: 100 N*m/rad}\n"
    "loads:\n"
    "  M: {type: file, body: I1, path: data.csv, outside: hold}\n"
    "simulation: {t_end: 0.01 s}\n";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::filesystem::path csv = folder() / "data.csv";
  {
    std::ofstream out(csv, std::ios::binary | std::ios::trunc);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  const std::string model = (folder() / "model.yaml").string();
  try {
    machdyn::SpecNode root = machdyn::parse_yaml_string(kModel, model);
    machdyn::Diagnostics diag;
    machdyn::resolve_signal_files(root, diag);
    diag.throw_if_any();
    (void)machdyn::compile_model(root, model);
  } catch (const machdyn::InputError&) {
  }
  return 0;
}
