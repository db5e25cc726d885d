#pragma once
/// @file
/// Results as text users load anywhere: the time-series CSV and the JSON summaries of `simulate`
/// and `modes`. Numbers are SI; column and key names carry the unit.

#include <string>

#include <nlohmann/json.hpp>

#include "machdyn/analysis/brake_summary.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/analysis/sway_summary.hpp"
#include "machdyn/io/output_file.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// CSV: a header of column names (`t_s`, `I1.position_rad`, …, `c1.load_N_m`), then one row per
/// output time, 17 significant digits.
std::string timeseries_csv(const SimulationResult& r);
/// The same CSV handed to `sink` in pieces of about 1 MB.
void timeseries_csv(const SimulationResult& r, const ChunkSink& sink);
/// Writes the CSV to `path` atomically, in pieces (io/output_file.hpp); throws OutputError.
void write_timeseries_csv(const std::filesystem::path& path, const SimulationResult& r);

/// `{model, integrator, settings, links: {NAME: {max, min, t_max, t_min, static_at_max,
/// static_at_min, peak, t_peak, static, dynamic_factor, unit}}, solver: {method, reason, steps,
/// rejected_steps, rhs_evals, jac_evals, wall_time_s}}`. `static` is the quasi-static load at the
/// peak and dynamic_factor = peak / static (LinkSummary), null when the static load is ~0.
/// A model with brakes adds `brakes: {NAME: {unit, energy_J, peak_power_W, t_peak_power_s[,
/// temperature_max_degC, t_temperature_max_s, temperature_end_degC], stops: [{applied_at_s,
/// start (applied, overcome, initial), ended_at_s, end (stuck, released, t_end), stopped, stopping_time_s, travel: {BODY: {value, unit}},
/// energy_J, peak_power_W, t_peak_power_s[, temperature_applied_degC, temperature_end_degC,
/// temperature_rise_K]}, …]}}` (analysis/brake_summary.hpp; null where not reached).
nlohmann::json simulation_summary(const Model& m, const SimulationResult& r);

/// The `brakes` object of the summary, and the lines `simulate` prints for it (per brake, one line
/// for the run and one per stop).
nlohmann::json brake_stops_json(const std::vector<BrakeSummary>& brakes);
std::string brake_stops_text(const std::vector<BrakeSummary>& brakes);

/// The lines `simulate` prints for the spatial ropes' sway (analysis/sway_summary.hpp), one per
/// rope: the largest sway, the residual after `sway_after`, the largest horizontal force and the
/// horizontal dynamic factor; empty without a spatial rope.
std::string sway_text(const std::vector<SwaySummary>& sway);

// `modes` writes its JSON with io/linear_results.hpp (every topology).

}  // namespace machdyn
