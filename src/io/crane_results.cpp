#include "machdyn/io/crane_results.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>
#include <fmt/format.h>
#include "machdyn/common/csv.hpp"
#include "io/number_text.hpp"

namespace machdyn {
namespace {

std::string csv_exact(double x) { return std::isfinite(x) ? fmt::format("{:.17g}", x) : ""; }
std::string quoted(const std::string& s) { return csv_field(s, true); }
std::string standard_text(const CraneFactorRow& r) {
  if (!std::isfinite(r.standard_lo)) return "-";  // not defined (e.g. HD2 without its creep speed)
  return r.standard_lo == r.standard_hi ? fmt::format("{:.4g}", r.standard_lo)
                                        : fmt::format("{:.4g}-{:.4g}", r.standard_lo, r.standard_hi);
}
std::string short_number(double x) { return std::isfinite(x) ? fmt::format("{:.4f}", x) : "-"; }

}  // namespace

nlohmann::json crane_json(const CraneReport& r) {
  nlohmann::json rows = nlohmann::json::array();
  for (const auto& x : r.rows)
    rows.push_back({{"factor", x.factor},
                    {"case", x.case_name},
                    {"simulated", json_number(x.simulated)},
                    {"standard_lo", json_number(x.standard_lo)},
                    {"standard_hi", json_number(x.standard_hi)},
                    {"clause", x.clause},
                    {"margin", json_number(x.margin)},
                    {"note", x.note},
                    {"extreme", json_number(x.extreme)},
                    {"t_extreme_s", json_number(x.t_extreme)},
                    {"reference", json_number(x.reference)},
                    {"vh_m_s", json_number(x.vh)},
                    {"xi_b", json_number(x.xi_b)},
                    {"stroke", json_number(x.stroke)},
                    {"contact_speed", json_number(x.contact_speed)},
                    {"t_contact_s", json_number(x.t_contact)},
                    {"warning", x.warning.empty() ? nlohmann::json(nullptr) : nlohmann::json(x.warning)}});
  nlohmann::json j = {{"model", r.model}, {"rows", rows}};
  if (!r.load_case.empty()) j["load_case"] = r.load_case;
  return j;
}

std::string crane_csv(const CraneReport& r) {
  std::string s = "factor,case,simulated,standard_lo,standard_hi,clause,margin,note\n";
  for (const auto& x : r.rows)
    s += fmt::format("{},{},{},{},{},{},{},{}\n", csv_field(x.factor), quoted(x.case_name), csv_exact(x.simulated),
                     csv_exact(x.standard_lo), csv_exact(x.standard_hi), quoted(x.clause), csv_exact(x.margin),
                     quoted(x.note));
  return s;
}

std::string crane_table(const CraneReport& r) {
  std::vector<std::vector<std::string>> cells = {{"factor", "case", "simulated", "standard", "margin", "clause/table"}};
  for (const auto& x : r.rows)
    cells.push_back({x.factor, x.case_name, short_number(x.simulated), standard_text(x), short_number(x.margin), x.clause});
  std::vector<size_t> width(cells[0].size(), 0);
  for (const auto& row : cells)
    for (size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  std::string s = fmt::format("crane factors of {}{}\n", r.model,
                              r.load_case.empty() || r.model.find("[" + r.load_case + "]") != std::string::npos
                                  ? std::string()
                                  : fmt::format(" (load case {})", r.load_case));
  for (size_t k = 0; k < cells.size(); ++k) {
    for (size_t c = 0; c < cells[k].size(); ++c)
      s += c + 1 < cells[k].size() ? fmt::format("{:<{}}  ", cells[k][c], width[c]) : cells[k][c];
    s += '\n';
    if (k == 0) {
      for (size_t c = 0; c < width.size(); ++c) s += std::string(width[c], '-') + (c + 1 < width.size() ? "  " : "");
      s += '\n';
    }
  }
  for (const auto& x : r.rows) s += fmt::format("{} ({}): {}\n", x.factor, x.case_name, x.note);
  for (const auto& x : r.rows)
    if (!x.warning.empty()) s += fmt::format("warning: {} ({}): {}\n", x.factor, x.case_name, x.warning);
  return s;
}

std::vector<plot::Figure> crane_figures(const CraneReport& r) {
  std::vector<plot::Figure> out;
  for (size_t k = 0; k < r.rows.size(); ++k) {
    const CraneFactorRow& x = r.rows[k];
    if (x.history.empty()) continue;
    plot::Figure f;
    f.id = fmt::format("crane_{}_{}", x.factor, k);
    f.title = fmt::format("{}: {}", x.factor, x.case_name);
    f.x = plot::make_axis("time t", "s");
    f.y = plot::make_axis(x.factor + " (load / reference)", "");
    f.series.push_back(plot::make_series("simulated", x.t, x.history));
    f.ref_lines.push_back(plot::make_ref_line(x.standard_hi, fmt::format("EN 13001-2: {}", standard_text(x)), -1));
    if (x.standard_lo != x.standard_hi)
      f.ref_lines.push_back(plot::make_ref_line(x.standard_lo, fmt::format("lower end {:.4g}", x.standard_lo), -1));
    out.push_back(std::move(f));
  }
  return out;
}

plot::Figure phi2_sweep_figure(const std::vector<Phi2Point>& pts) {
  if (pts.empty()) throw std::invalid_argument("phi2_sweep_figure: no sweep points");
  std::vector<double> vh, sim, std_line;
  for (const Phi2Point& p : pts) vh.push_back(p.vh), sim.push_back(p.simulated), std_line.push_back(p.standard);
  plot::Figure f;
  f.id = "crane_phi2_sweep";
  f.title = "phi2 over the hoisting speed, simulated beside EN 13001-2";
  f.x = plot::make_axis("hoisting speed vh", "m/s");
  f.y = plot::make_axis("phi2 (max rope force / m g)", "");
  f.series.push_back(plot::make_series("simulated", vh, std::move(sim), plot::Style::linepoints));
  plot::Series line = plot::make_series("EN 13001-2: phi2,min + beta2 vh", std::move(vh), std::move(std_line));
  line.dashed = true;
  f.series.push_back(std::move(line));
  f.legend = plot::Figure::Legend::top_left;
  return f;
}

}  // namespace machdyn
