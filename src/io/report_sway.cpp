#include "io/report_sway.hpp"

#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/format.h>

#include "machdyn/analysis/sway_summary.hpp"

namespace machdyn::report {

namespace {

/// The column `name` of r, or null.
const std::vector<double>* report_sway_column(const SimulationResult& r, const std::string& name) {
  for (size_t k = 0; k < r.column_names.size(); ++k)
    if (r.column_names[k] == name) return &r.columns[k];
  return nullptr;
}

}  // namespace

std::optional<Section> sway_section(const Model&, const SimulationResult& r, const std::string& case_name) {
  const std::vector<SwaySummary>& sway = r.sway;
  if (sway.empty()) return std::nullopt;
  constexpr double deg_per_rad = 180.0 / std::numbers::pi;
  Section s;
  s.title = case_name.empty() ? "Sway" : "Sway — case " + case_name;
  Table t;
  t.caption = "Sway of the swinging load (spatial ropes)";
  t.header = {"rope", "largest sway, °", "at, s", "residual sway, °", "after, s", "largest horizontal force, N", "at, s",
              "m a, N", "horizontal dynamic factor", "largest tension, N"};
  auto num = [](double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : std::string("–"); };
  for (const SwaySummary& x : sway)
    t.rows.push_back({x.rope, num(x.max_sway_rad * deg_per_rad), num(x.t_max_sway),
                      x.residual_after ? num(x.residual_sway_rad * deg_per_rad) : "–",
                      x.residual_after ? num(*x.residual_after) : "–", num(x.max_horizontal_force_N),
                      num(x.t_max_horizontal_force), x.rigid_force_N ? num(*x.rigid_force_N) : "–",
                      x.dynamic_factor ? fmt::format("{:.4g}", *x.dynamic_factor) : "–", num(x.max_tension_N)});
  t.note = "Sway: the rope's angle from the vertical through the suspension point (docs/sway.md); residual: the largest "
           "sway from the rope's sway_after on; horizontal dynamic factor: the horizontal force's peak over m a, a the "
           "largest horizontal acceleration of the suspension point's travel (– with a jib or without travel).";
  s.tables.push_back(std::move(t));
  // The sway angles (left axis) and the horizontal force (right axis) of every rope over time.
  const std::vector<double>* time = report_sway_column(r, "t_s");
  if (!time) return s;
  plot::Figure f;
  f.id = "sway";
  f.title = "Sway angles and horizontal force on the suspension point";
  f.x.quantity = "time t", f.x.unit = "s";
  f.y.quantity = "sway angle θ", f.y.unit = "°";
  f.y2.quantity = "horizontal force H", f.y2.unit = "N";
  f.zero_line = true;
  f.legend = plot::Figure::Legend::below;
  for (const SwaySummary& x : sway) {
    for (const char* col : {"sway_x_rad", "sway_y_rad", "sway_radial_rad", "sway_tangential_rad"}) {
      const std::vector<double>* th = report_sway_column(r, x.rope + "." + col);
      if (!th) continue;
      plot::Series se;
      const std::string which(col + 5, std::string(col).size() - 9);  // x, y, radial, tangential
      se.name = fmt::format("{} θ {}", x.rope, which);
      se.x = *time;
      se.y.reserve(th->size());
      for (double v : *th) se.y.push_back(v * deg_per_rad);
      f.series.push_back(std::move(se));
    }
    if (const std::vector<double>* H = report_sway_column(r, x.rope + ".horizontal_force_N")) {
      plot::Series se;
      se.name = x.rope + " H";
      se.x = *time;
      se.y = *H;
      se.y_axis = 2;
      se.dashed = true;
      f.series.push_back(std::move(se));
    }
  }
  if (!f.series.empty()) s.figures.push_back(std::move(f));
  return s;
}

}  // namespace machdyn::report
