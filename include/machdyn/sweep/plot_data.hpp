#pragma once
/// @file
/// A sweep's summary plot: one output column of the table against one or two varied inputs.
/// The data is a small CSV (`x[,y],output`, rows with status ok, in run order); the figure is a
/// plot::Figure drawn by gnuplot (io/plot.hpp, SVG + PNG at print size):
///   one input:   the output against x, points joined in x order;
///   two inputs:  one curve per value of the second input (a family), when it takes at most
///                kMaxCurves values (a grid); otherwise (lhs, random, a fine grid) a heat map:
///                a coloured cell per point for a full grid, a coloured dot per point for scattered
///                samples, the output on the colour scale.
/// With load cases, `case` is an input like a varied field (`--plot c1.dynamic_factor:MB.value:case`:
/// one curve per case, however many); without X and Y a case sweep plots against the first varied
/// field with one curve per case.
/// Axes carry the quantity and its SI unit (the table holds SI values).

#include <string>
#include <vector>

#include "machdyn/io/plot.hpp"
#include "machdyn/sweep/plan.hpp"

namespace machdyn {

struct SweepPlotSpec {
  std::string output;               ///< a column of the table, e.g. `c1.max_N_m`
  std::vector<std::string> inputs;  ///< one or two --vary targets (x, then y)
  /// Axis labels (parse_plot_spec fills them): quantity and SI unit of each input and the output,
  /// e.g. {"c1.stiffness", "N·m/rad"}, {"peak load of c1", "N·m"}.
  std::vector<plot::Axis> input_axes;  ///< log = true for a log-spaced or log-sampled input (`:log`)
  plot::Axis output_axis;
  /// "MODEL: OUTPUT against X[ and Y]" (parse_plot_spec fills it); the figure's title.
  std::string title;
};

/// At most this many values of the second input are drawn as a family of curves; more: a heat map.
inline constexpr int kMaxCurves = 10;

/// "quantity" and SI unit of a table column: `c1.max_N_m` → {"peak load of c1", "N·m"},
/// `adhesion.period_s` → {"self-oscillation period of adhesion", "s"}, ...
plot::Axis column_axis(const std::string& column);

/// The SI unit of a varied field `NAME.FIELD` of model `m` (e.g. `c1.stiffness` of a rotational
/// link: "N·m/rad", `P.value` of a force: "N", `adhesion.mu_k`: ""); "" when not known.
std::string field_unit(const Model& m, const std::string& target);

/// Parses `OUTPUT[:X[:Y]]` against the table header; without X the first one or two varied fields
/// are taken (with cases: the first varied field and `case`). Throws InputError naming the known columns when a name is not in the table.
SweepPlotSpec parse_plot_spec(const std::string& text, const SweepPlan& plan, const std::string& header);

/// The plot data from a finished table (sweep.csv): header `X[,Y],OUTPUT`, one line per ok run.
std::string sweep_plot_csv(const std::string& table_path, const SweepPlotSpec& spec);

/// The figure of one input, or of two as a family of curves (id `sweep_plot`, series named after the
/// output, or `Y = value unit` per curve). Throws std::invalid_argument when the data has two
/// inputs with more than kMaxCurves values of the second (that is a heat map: render_sweep_plot).
plot::Figure sweep_plot_figure(const std::string& data_csv, const SweepPlotSpec& spec);

/// Draws the plot of `data_csv` (the text sweep_plot_csv() returns) with gnuplot: the SVG and PNG
/// contents (the caller writes them). Throws std::runtime_error when gnuplot is missing or fails.
plot::Rendered render_sweep_plot(const std::string& data_csv, const SweepPlotSpec& spec);

}  // namespace machdyn
