#pragma once
/// @file
/// The mode events a run recorded for one element (the tests' view of SimulationResult::hybrid).

#include <string>
#include <vector>

#include "machdyn/analysis/simulate.hpp"

namespace machdyn::test {

/// The events of `element` in time order, without the "initial" record; only those of `kind`
/// ("stick", "slip", "gap_closed", …) when it is given.
inline std::vector<ModeEvent> events_of(const SimulationResult& r, const std::string& element,
                                        const std::string& kind = "") {
  std::vector<ModeEvent> out;
  for (const auto& e : r.hybrid.events)
    if (e.element == element && e.kind != "initial" && (kind.empty() || e.kind == kind)) out.push_back(e);
  return out;
}

}  // namespace machdyn::test
