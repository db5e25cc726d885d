#pragma once
/// @file
/// A figure as data — series with names, axes with quantity and unit, a legend, horizontal reference
/// lines (e.g. the particular solution M* of a link load) — and two renderers for it:
///   - gnuplot (this file): a static SVG + PNG for papers, readable at print size;
///   - uPlot (io/report.hpp): an interactive chart in the self-contained HTML report.
/// A kind of plot is one small function that fills a Figure (io/figures.hpp); both renderers then
/// draw it. The library never writes into a result folder: render() returns the file contents and
/// the caller writes them (atomically) next to its other results.

#include <filesystem>
#include <functional>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace machdyn::plot {

/// One axis: "quantity, unit" as an engineer writes it (e.g. "link load M, N·m").
struct Axis {
  std::string quantity;              ///< e.g. "time t", "angular velocity ω"
  std::string unit;                  ///< e.g. "s", "N·m", "rad/s"; empty for dimensionless
  std::optional<double> min, max;    ///< fixed range; autoscale when empty
  /// Tick labels at given positions (e.g. body names on the x axis of a mode shape); empty: numbers.
  std::vector<std::pair<double, std::string>> ticks;
  bool log = false;                  ///< logarithmic scale (a log-spaced sweep design); values > 0
  [[nodiscard]] std::string label() const;  ///< "quantity, unit" or "quantity"
  [[nodiscard]] bool used() const { return !quantity.empty(); }
};

enum class Style {
  line,        ///< straight segments through the points
  steps,       ///< piecewise-constant: horizontal from each point to the next x (gnuplot `steps`)
  linepoints,  ///< segments and a marker at every point (few points: mode shapes)
  thin,        ///< a thin grey construction line, not in the legend (sector boundaries, rays)
  points,      ///< markers only (events on a curve: the slip starts of a cyclogram)
};

/// One curve. x and y have the same size; a NaN in either breaks the curve (a new segment begins).
struct Series {
  std::string name;             ///< legend entry; also the hover name in the report
  std::vector<double> x, y;
  Style style = Style::line;
  int y_axis = 1;               ///< 1: left axis `y`, 2: right axis `y2`
  bool dashed = false;
  bool in_legend = true;        ///< false: drawn, but no legend entry (construction lines, centres)
};

/// A horizontal line at y = value across the plot, in the colour of series `series` (index into
/// Figure::series, or -1 for black), dashed, labelled at its right end.
struct RefLine {
  double value = 0.0;
  std::string label;            ///< e.g. "M₁₂* = 354 N·m"
  int series = -1;
  int y_axis = 1;
};

/// A shaded interval of x across the whole plot height, behind the curves (e.g. the slip phases
/// of a friction contact in a load cyclogram).
struct Band {
  double x0 = 0.0, x1 = 0.0;
};

/// A vertical dotted line at x (an event: breakaway, stick, brake applied, gap closed), its label
/// written upwards at the top of the plot.
struct EventMark {
  double x = 0.0;
  std::string label;            ///< e.g. "adhesion slips", "T applied"
};

/// A marked point with a text beside it (the peak of a curve), in the colour of series `series`.
struct Annotation {
  double x = 0.0, y = 0.0;
  std::string text;             ///< e.g. "peak −204 N·m at 0.254 s"
  int series = -1;
  int y_axis = 1;
};

struct Figure {
  std::string id;               ///< file stem and HTML id: letters, digits, '_' and '-' (e.g. "link_loads")
  std::string title;            ///< one line above the plot; may be empty for a paper figure
  Axis x, y, y2;                ///< y2 used when a series has y_axis = 2
  std::vector<Series> series;
  std::vector<RefLine> ref_lines;
  std::vector<Band> bands;      ///< shaded light grey, behind everything
  std::string bands_label;      ///< legend entry of the bands (e.g. "adhesion slips"); empty: none
  bool equal_aspect = false;    ///< one unit on x as long as one on y (pitch curves, geometry)
  bool zero_line = false;       ///< a thin line at y = 0 (with a right axis: both axes' zeros aligned)
  std::vector<EventMark> events;     ///< vertical event lines (gnuplot; the report lists events in a table)
  std::vector<Annotation> notes;     ///< annotated points (the peak)
  enum class Legend { top_right, top_left, bottom_right, bottom_left, below } legend = Legend::top_right;
};

/// Shorthands for the figure functions (aggregate braces with designated fields warn in GCC 12).
Axis make_axis(std::string quantity, std::string unit);
Series make_series(std::string name, std::vector<double> x, std::vector<double> y, Style style = Style::line,
                   int y_axis = 1);
RefLine make_ref_line(double value, std::string label, int series, int y_axis = 1);

/// The colour of series k (Okabe–Ito palette: distinct for colour-blind readers and in greyscale
/// by line width/dash), as "#rrggbb". The same colours in SVG, PNG and the report.
std::string series_color(std::size_t k);

/// The fill of Figure::bands, in both renderers.
inline constexpr const char* kBandColor = "#e3e3e3";

/// "N*m" → "N·m", "kg*m^2" → "kg·m²", "rad/s" stays: machdyn's unit strings as they are printed.
std::string pretty_unit(const std::string& unit);

/// Throws std::invalid_argument when a series' x and y sizes differ, the id is not a file stem,
/// or a series or reference line names an axis that does not exist.
void validate(const Figure& fig);

// ---- gnuplot -------------------------------------------------------------------------------------

enum class Format { svg, png };

/// The data file: one block per series ("# name" line, then "x y" rows, NaN as a blank line that
/// breaks the curve), blocks separated by two blank lines so that `index k` selects series k.
std::string gnuplot_data(const Figure& fig);

/// The gnuplot script that draws `fig` from `data_path` into `output_path`. Print size: 16 cm × 10 cm
/// (SVG 800 × 500 at 12 pt; PNG 1600 × 1000 at 24 pt, i.e. 250 dpi at 16 cm).
std::string gnuplot_script(const Figure& fig, Format format, const std::string& data_path,
                           const std::string& output_path);

/// The gnuplot executable: $MACHDYN_GNUPLOT if set, else `gnuplot` on PATH. Throws
/// std::runtime_error with the install hint (Debian package gnuplot-nox) when there is none.
std::filesystem::path find_gnuplot();

struct Rendered {
  std::string svg;  ///< the SVG document
  std::string png;  ///< the PNG bytes
};

/// Runs gnuplot (a subprocess; data and script through a fresh temporary folder, removed after) and
/// returns both files. Throws std::runtime_error with gnuplot's message when it fails.
Rendered render(const Figure& fig);

/// The same machinery for a figure that a Figure cannot describe (the sweep's heat map): `data` is
/// written to a file, `script(format, data_path, output_path)` gives the gnuplot commands for one
/// format; `what` names the figure in error messages.
using ScriptFor = std::function<std::string(Format format, const std::string& data_path, const std::string& output_path)>;
Rendered render_script(const std::string& data, const ScriptFor& script, const std::string& what);

/// A gnuplot single-quoted string: only ' needs doubling; no escapes, no enhanced-text markup.
std::string quote(const std::string& s);

}  // namespace machdyn::plot
