#pragma once
// The report's table of the brakes' stops in one run (analysis/brake_summary.hpp), for
// io/report_model.cpp: one row per stop of each brake, the same numbers as summary.json's `brakes`.
#include <optional>

#include "machdyn/analysis/brake_summary.hpp"
#include "machdyn/io/report.hpp"

namespace machdyn::report {

/// "Brakes: stops, energy, temperature" for the run r of m; none when m has no brake.
std::optional<Table> brake_stops_table(const Model& m, const SimulationResult& r);

}  // namespace machdyn::report
