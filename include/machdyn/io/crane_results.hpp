#pragma once
/// @file
/// The crane table (analysis/crane.hpp) as JSON, CSV and a terminal table — one column set:
/// factor | case | simulated | standard (value or lo–hi) | clause | margin | note. NaN is JSON null
/// and an empty CSV cell.

#include <string>
#include <nlohmann/json.hpp>

#include "machdyn/analysis/crane.hpp"
#include "machdyn/io/plot.hpp"

namespace machdyn {

/// {"model": NAME, "load_case": CASE (with a case only), "rows": [{"factor", "case", "simulated",
/// "standard_lo", "standard_hi", "clause", "margin", "note", "extreme", "t_extreme_s", "reference",
/// "vh_m_s", "xi_b", "stroke", "contact_speed", "t_contact_s", "warning"}, ...]} — the numbers of the
/// note as fields (CraneFactorRow), null where the row has none.
nlohmann::json crane_json(const CraneReport& r);
/// factor,case,simulated,standard_lo,standard_hi,clause,margin,note (text quoted, numbers %.17g).
std::string crane_csv(const CraneReport& r);
/// The table for the terminal: numbers to 4 digits, the standard as "1.44" or "1.0-1.5"; the notes,
/// then a line "warning: ..." per row with a warning.
std::string crane_table(const CraneReport& r);
/// One figure per simulated row (id "crane_FACTOR_K", K its row index): the factor's time history
/// with the standard's value (both ends of a range) as dashed lines.
std::vector<plot::Figure> crane_figures(const CraneReport& r);
/// φ2 over the hoisting speed (`--phi2-speeds`, analysis/crane.hpp phi2_sweep), id "crane_phi2_sweep":
/// the simulated φ2 at each speed (series 0, "simulated", line with markers) and the standard's
/// straight line φ2,min + β2 vh at the same speeds (series 1, dashed), against vh in m/s.
/// Throws std::invalid_argument for an empty sweep.
plot::Figure phi2_sweep_figure(const std::vector<Phi2Point>& pts);

}  // namespace machdyn
