#pragma once
/// @file
/// JSON of the energy-integral and steady-running analyses (analysis/energy.hpp); keys are listed
/// in docs/variable-inertia.md.

#include <nlohmann/json.hpp>

#include "machdyn/analysis/energy.hpp"

namespace machdyn {

nlohmann::json energy_json(const Model& m, const EnergyResult& r);
nlohmann::json steady_json(const SteadyResult& s);

}  // namespace machdyn
