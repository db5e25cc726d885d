#pragma once
/// @file
/// The data of a sweep's summary plot: one output column of the table against one or two varied
/// inputs, as a small CSV (`x[,y],output`, rows with status ok, in run order). Drawing it (SVG/PNG)
/// is the job of the report machinery; render_sweep_plot() is the hook it fills.

#include <string>
#include <vector>

#include "machdyn/sweep/plan.hpp"

namespace machdyn {

struct SweepPlotSpec {
  std::string output;               ///< a column of the table, e.g. `c1.max_N_m`
  std::vector<std::string> inputs;  ///< one or two --vary targets (x, then y)
};

/// Parses `OUTPUT[:X[:Y]]` against the table header; without X the first one or two varied fields
/// are taken. Throws InputError naming the known columns when a name is not in the table.
SweepPlotSpec parse_plot_spec(const std::string& text, const SweepPlan& plan, const std::string& header);

/// The plot data from a finished table (sweep.csv): header `X[,Y],OUTPUT`, one line per ok run.
std::string sweep_plot_csv(const std::string& table_path, const SweepPlotSpec& spec);

/// HOOK for the report machinery (issue 6): draws `data_csv` (written by sweep_plot_csv) into
/// `image_path` (.svg or .png) — a line for one input, a map or family of lines for two. Returns
/// false when this build cannot draw (no renderer yet), so the caller says where the data is.
bool render_sweep_plot(const std::string& data_csv, const SweepPlotSpec& spec, const std::string& image_path);

}  // namespace machdyn
