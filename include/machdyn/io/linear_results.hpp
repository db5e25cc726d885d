#pragma once
/// @file
/// Text and figures of the linear analyses (analysis/linear_analysis.hpp,
/// analysis/frequency_response.hpp): JSON for programs, CSV tables, gnuplot/uPlot figures (a Bode
/// plot, frequencies over a machine's position, a Campbell diagram). Plain functions of the
/// results; the CLI writes the strings (atomically).

#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "machdyn/analysis/frequency_response.hpp"
#include "machdyn/analysis/linear_analysis.hpp"
#include "machdyn/io/plot.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// One topology: label, intervals, counts, frequencies (rad/s and Hz), mass-normalized shapes by
/// body name, and with damping the damped modes (ω_n, ω_d, ζ, decay rate, complex shape as
/// magnitude and phase in degrees). With a spatial rope each shape also has its `kind` ("pendulum",
/// "rope stretch", "drive line") and `energy_shares` (analysis/mode_kinds.hpp), and "kinds" lists them.
nlohmann::json topology_modes_json(const Model& m, const TopologyModes& t);

/// Every topology analysed, under "topologies"; the first one's frequencies, shapes and rigid-body
/// count (and "kinds") also at the top level (the fields `modes --json` always had).
nlohmann::json linear_modes_json(const Model& m, const std::vector<TopologyModes>& list);

/// CSV, one row per mode: topology,mode,omega_rad_s,f_Hz,zeta,omega_d_rad_s (ζ empty when undamped).
std::string linear_modes_csv(const std::vector<TopologyModes>& list);

/// FRF: "omega_rad_s,f_Hz", then per output "OUT.mag_UNIT_per_IN_UNIT,OUT.phase_deg".
std::string frequency_response_csv(const FrequencyResponse& r);
/// The same as JSON, with the resonance peaks.
nlohmann::json frequency_response_json(const FrequencyResponse& r);
/// Bode plot: |H| (log) over frequency in Hz (log), one curve per output (the phases on the
/// right axis would crowd it; they are in the CSV and in `bode_phase`).
plot::Figure bode_magnitude_figure(const Model& m, const FrequencyResponse& r, const std::string& topology);
plot::Figure bode_phase_figure(const Model& m, const FrequencyResponse& r, const std::string& topology);

/// "position,omega_1_rad_s,..." — the frequencies over a body's position.
std::string position_frequencies_csv(const Model& m, const PositionFrequencies& p);
plot::Figure position_frequencies_figure(const Model& m, const PositionFrequencies& p, const std::string& topology);

/// Natural frequencies (horizontal lines) and excitation lines over the shaft speed (rpm on x,
/// Hz on y), the crossings marked.
plot::Figure campbell_figure(const Model& m, const Eigen::VectorXd& omega, const std::vector<ExcitationOrder>& orders,
                             double speed_lo, double speed_hi, const std::vector<CampbellCrossing>& crossings,
                             const std::string& shaft);
nlohmann::json campbell_json(const std::vector<CampbellCrossing>& crossings, const std::string& shaft);

}  // namespace machdyn
