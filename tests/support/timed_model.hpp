#pragma once
// A model from YAML text with its run appended: `simulation: {t_end, dt_out, rtol: 1e-10, atol: 1e-12}`
// on the given integrator (the element tests that build their models as text).
#include <string>

#include <fmt/format.h>

#include "support/support.hpp"

namespace machdyn::test {

/// x with all 17 significant digits, for model text.
inline std::string num(double x) { return fmt::format("{:.17g}", x); }

inline Model timed_model(const std::string& yaml, double t_end, double dt_out, IntegratorChoice integ,
                         const std::string& file = "test.yaml") {
  Model m = model_text(yaml + "simulation: {t_end: " + num(t_end) + " s, dt_out: " + num(dt_out) +
                           " s, rtol: 1e-10, atol: 1e-12}\n",
                       file);
  m.simulation.integrator = integ;
  return m;
}

}  // namespace machdyn::test
