// libFuzzer harness: the values of `--set NAME.FIELD=VALUE` and `--vary NAME.FIELD=SPEC` on a fixed
// model (the three-mass hoist with a friction brake and a signal load), as `machdyn simulate --set`
// and `machdyn sweep --vary` read them. The input is a list of lines: a line starting with `~` is a
// --vary (without the `~`), any other line a --set. Each --set is applied to the model and the model
// compiled; then the sweep plan is made from all of them (sweep/plan.hpp), which parses and probes
// every axis and lists the runs. The only acceptable failure is InputError; anything else (a crash,
// a sanitizer report, another exception, a hang, memory exhaustion) is a bug.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "machdyn/sweep/plan.hpp"

namespace {

constexpr const char* kModel =
    "name: fuzzed hoist\n"
    "bodies:\n"
    "  I1: {type: rotational, inertia: 0.80 kg*m^2, position: 0.01125 rad}\n"
    "  I2: {type: rotational, inertia: 0.45 kg*m^2}\n"
    "  I3: {type: rotational, inertia: 0.25 kg*m^2}\n"
    "links:\n"
    "  c1: {type: spring, between: [I1, I2], stiffness: 2.4e4 N*m/rad}\n"
    "  c2: {type: spring-damper, between: [I2, I3], stiffness: 9.0e3 N*m/rad, damping: 5 N*m*s/rad}\n"
    "loads:\n"
    "  Msp: {type: constant, body: I1, value: 450 N*m}\n"
    "  MB: {type: sine, body: I2, amplitude: 20 N*m, frequency: 3 Hz}\n"
    "brakes:\n"
    "  B: {body: I3, holding: 120 N*m, braking: 100 N*m, time: 0.2 s, ramp: 10 ms}\n"
    "simulation: {t_end: 0.5 s, dt_out: 1 ms}\n";

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  machdyn::SweepRequest request;
  request.model_path = "fuzz.yaml";
  request.model_text = kModel;
  for (size_t start = 0; start <= text.size();) {
    size_t end = text.find('\n', start);
    if (end == std::string::npos) end = text.size();
    const std::string line = text.substr(start, end - start);
    if (!line.empty() && line[0] == '~') request.vary.push_back(line.substr(1));
    else if (!line.empty()) request.sets.push_back(line);
    start = end + 1;
  }
  try {
    machdyn::SpecNode root = machdyn::parse_yaml_string(kModel, "fuzz.yaml");
    for (const auto& s : request.sets) machdyn::apply_set(root, s);
    (void)machdyn::compile_model(root, "fuzz.yaml");
  } catch (const machdyn::InputError&) {
  }
  try {
    (void)machdyn::make_sweep_plan(request);
  } catch (const machdyn::InputError&) {
  }
  return 0;
}
