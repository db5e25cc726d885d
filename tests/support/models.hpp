#pragma once
// Helpers shared by the tests: a model from YAML text, and the integrator names of parameterized tests.
#include <string>

#include <gtest/gtest.h>

#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn::test {

/// The model of `yaml` (errors located in "test.yaml").
inline Model model_of(const std::string& yaml) { return compile_model(parse_yaml_string(yaml, "test.yaml"), "test.yaml"); }

/// `m` to be run on integrator `ic`.
inline Model with_integrator(Model m, IntegratorChoice ic) {
  m.simulation.integrator = ic;
  return m;
}

/// "dopri5" / "bdf": the integrator's word (the reference campaign's `compare` takes it).
inline std::string integrator_word(IntegratorChoice ic) { return ic == IntegratorChoice::bdf ? "bdf" : "dopri5"; }

/// "dopri5" / "bdf": the suffix of a test parameterized over the integrators.
inline std::string integrator_name(const ::testing::TestParamInfo<IntegratorChoice>& p) {
  return p.param == IntegratorChoice::bdf ? "bdf" : "dopri5";
}

}  // namespace machdyn::test
