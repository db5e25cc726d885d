#include "machdyn/sweep/plot_data.hpp"

#include <algorithm>
#include <fstream>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/sweep/table.hpp"

namespace machdyn {

SweepPlotSpec parse_plot_spec(const std::string& text, const SweepPlan& plan, const std::string& header) {
  const Location where{"--plot " + text, 0, 0};
  const auto columns = split_csv_line(header);
  std::vector<std::string> parts;
  size_t start = 0;
  for (;;) {
    const auto p = text.find(':', start);
    parts.push_back(text.substr(start, p == std::string::npos ? std::string::npos : p - start));
    if (p == std::string::npos) break;
    start = p + 1;
  }
  if (parts.size() > 3 || parts[0].empty()) throw InputError(where, "expected OUTPUT, OUTPUT:X or OUTPUT:X:Y");
  SweepPlotSpec spec;
  spec.output = parts[0];
  if (std::find(columns.begin(), columns.end(), spec.output) == columns.end() || spec.output == "run" ||
      spec.output == "status" || spec.output == "message")
    throw InputError(where, fmt::format("no output column '{}'; the table has: {}", spec.output,
                                        fmt::join(columns.begin() + 1, columns.end() - 2, ", ")));
  std::vector<std::string> targets;
  for (const auto& a : plan.axes) targets.push_back(a.target);
  if (parts.size() == 1) {
    for (size_t d = 0; d < std::min<size_t>(2, targets.size()); ++d) spec.inputs.push_back(targets[d]);
  } else {
    for (size_t k = 1; k < parts.size(); ++k) {
      if (std::find(targets.begin(), targets.end(), parts[k]) == targets.end())
        throw InputError(where, fmt::format("'{}' is not varied; the varied fields are: {}", parts[k], fmt::join(targets, ", ")));
      spec.inputs.push_back(parts[k]);
    }
  }
  return spec;
}

std::string sweep_plot_csv(const std::string& table_path, const SweepPlotSpec& spec) {
  std::ifstream in(table_path);
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error("cannot read " + table_path);
  const auto header = split_csv_line(line);
  auto col = [&](const std::string& name) {
    return static_cast<size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  std::vector<size_t> pick;
  for (const auto& x : spec.inputs) pick.push_back(col(x));
  pick.push_back(col(spec.output));
  const size_t status = col("status");
  std::string out;
  auto add = [&out](size_t k, const std::string& field) {
    if (k > 0) out += ',';
    out += csv_field(field);
  };
  for (size_t k = 0; k < pick.size(); ++k) add(k, header.at(pick[k]));
  out += '\n';
  while (std::getline(in, line)) {
    const auto f = split_csv_line(line);
    if (f.size() != header.size() || f[status] != "ok") continue;
    for (size_t k = 0; k < pick.size(); ++k) add(k, f[pick[k]]);
    out += '\n';
  }
  return out;
}

bool render_sweep_plot(const std::string& /*data_csv*/, const SweepPlotSpec& /*spec*/, const std::string& /*image_path*/) {
  return false;  // issue 6 (report machinery, gnuplot) draws here
}

}  // namespace machdyn
