#pragma once
/// @file
/// The report an engineer sends to a colleague: one self-contained HTML file (no network: the uPlot
/// charting library, its CSS, the data and the page's script are all inside it) with the model as
/// tables with units, the run settings, the results and interactive plots (zoom by dragging, pan
/// with Shift+drag or the wheel, hover read-out, series toggled from the legend).
///
/// A Document is generic — sections of tables, paragraphs and plot::Figures — so any command can
/// build one; simulation_report() builds the one of `machdyn report`. The page writes a status into
/// `<pre id="machdyn-status">` when it has drawn: `{"done": true, "errors": [...], "plots": [{"id",
/// "series", "drawn": [pixels of each series' colour], "points": [...], "ms"}]}` for browser tests.

#include <string>
#include <vector>

#include "machdyn/analysis/crane.hpp"
#include "machdyn/analysis/energy.hpp"
#include "machdyn/analysis/frequency_response.hpp"
#include "machdyn/analysis/linear_analysis.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/plot.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::report {

struct Table {
  std::string caption;
  std::vector<std::string> header;                ///< column titles, with the unit: "max, N·m"
  std::vector<std::vector<std::string>> rows;     ///< cells as text (already formatted)
  std::string note;                               ///< a line under the table
  bool text_values = false;                       ///< left-align every cell (settings), not only words
  /// Long tables (events, slip phases): shown folded under their caption and row count, opened by a
  /// click, so that the plots after them stay near the top.
  bool collapsed = false;
};

struct Section {
  std::string title;
  std::vector<std::string> paragraphs;            ///< plain text, escaped when written
  std::vector<Table> tables;
  std::vector<plot::Figure> figures;              ///< each series' x must be non-decreasing
};

struct Document {
  std::string title, subtitle;
  std::vector<Section> sections;
};

/// True when this build embeds uPlot (CMake option MACHDYN_REPORT, on by default).
bool assets_available();
/// The embedded uPlot version, e.g. "1.6.32" (empty when !assets_available()).
std::string uplot_version();

/// The HTML page. Throws std::runtime_error when !assets_available(), std::invalid_argument for a
/// figure the charts cannot draw (see plot::validate; x must be non-decreasing in each series).
std::string to_html(const Document& doc);

/// The data of one figure as the page's chart script reads it (JSON text: labels, colours,
/// reference lines and the columns [x, y_1, ..., y_n] on one shared x grid, NaN → null).
/// `dom_id` replaces fig.id as the chart's id in the page (unique per page); empty: fig.id.
std::string figure_json(const plot::Figure& fig, const std::string& dom_id = "");

/// The model as tables: bodies, links (with their gaps), friction contacts and brakes, and loads,
/// each quantity with its unit.
std::vector<Table> model_tables(const Model& m);

/// One run in a report. `name` is empty for the model as written; a named case (issue 3's
/// `--case NAME`, `--all-cases`) gets its own section of settings, results and plots.
struct Case {
  std::string name;
  const Model* model = nullptr;
  const SimulationResult* result = nullptr;
  const Modes* modes = nullptr;   ///< optional: natural frequencies and the mode-shape plot
  std::string description;        ///< the case's description (cases: NAME: description:)
  /// Optional, for a 1-DOF machine: the energy integral, drawn as ω against distance or angle (and
  /// the crank's inertia moments), io/figures.hpp energy_figures().
  const EnergyResult* energy = nullptr;
  /// Optional: the modes of each topology the run passed through (analysis/linear_analysis.hpp),
  /// shown instead of `modes`' table, and a frequency response drawn as a Bode plot.
  const std::vector<TopologyModes>* topologies = nullptr;
  const FrequencyResponse* frf = nullptr;
  std::string frf_topology;  ///< the topology label of `frf`
  /// Optional: the crane analysis of a model with a `crane:` section (analysis/crane.hpp), shown as
  /// its own section: the factor table beside EN 13001-2 and each factor's time history.
  const CraneReport* crane = nullptr;
  /// The links whose loads are drawn (`--links`); empty: every link, in panels by unit and size.
  std::vector<std::string> links;
};

/// The natural frequencies (Hz) and damping ratios of each topology, with its time intervals.
Table topology_modes_table(const Model& m, const std::vector<TopologyModes>& list);

/// Rows of the events table at most; a longer run says how many were left out.
inline constexpr std::size_t kMaxEventRows = 400;

/// The mode events of a hybrid run: t, kind, element, from, to (the `initial` modes first).
Table events_table(const SimulationResult& r);
/// The slip phases: contact, direction, start, end, and per link the load at breakaway and the
/// extremes inside the phase.
Table slip_phases_table(const Model& m, const SimulationResult& r);
/// One table over several cases: per case and link the maximum, minimum, peak (extreme of larger
/// magnitude) with its time, the quasi-static load there, the dynamic factor and the mode events.
Table cases_table(const std::vector<Case>& cases);

/// The document of `machdyn report`: the model (of the first case), then for each case its run
/// settings and solver statistics, the results table (peaks, static values, dynamic factors,
/// events), the natural frequencies, and the plots (link loads with the static values marked, body
/// speeds, mode shapes; the load cyclogram and contacts of a hybrid run; ω against distance or
/// angle of a machine; the crane factors of a case that has them). With more than one case a
/// comparison table (cases_table) follows the model.
/// `command` is the command line, printed under the title.
Document simulation_report(const std::vector<Case>& cases, const std::string& command);

}  // namespace machdyn::report
