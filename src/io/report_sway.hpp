#pragma once
// The report's sway section of one run (analysis/sway_summary.hpp, docs/sway.md), for
// io/report_model.cpp: the spatial ropes' summary table (the same numbers as summary.json's `sway`
// and `simulate`'s printout) and a figure of the sway angles and the horizontal force over time.
#include <optional>
#include <string>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/report.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::report {

/// "Sway" (or "Sway — case NAME") for the run r of m; none when m has no spatial rope.
std::optional<Section> sway_section(const Model& m, const SimulationResult& r, const std::string& case_name);

}  // namespace machdyn::report
