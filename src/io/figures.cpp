// The papers' plots as Figures (io/figures.hpp). Each function only selects and labels data.
#include "machdyn/io/figures.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

namespace machdyn {

namespace {

constexpr double kPi = std::numbers::pi;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The output column whose name starts with `prefix` (e.g. "c1.load_"); columns are found by name
/// so that commands adding columns (events, gaps) do not shift them.
const std::vector<double>& column(const SimulationResult& r, const std::string& prefix) {
  for (std::size_t c = 0; c < r.column_names.size(); ++c)
    if (r.column_names[c].rfind(prefix, 0) == 0) return r.columns[c];
  throw std::logic_error("simulation result has no column " + prefix);
}

std::string endpoint_name(const Model& m, int body) {
  return body == kGround ? std::string("ground") : m.bodies[static_cast<std::size_t>(body)].name;
}

std::string number(double v) { return fmt::format("{:.4g}", v); }

}  // namespace

plot::Figure link_loads_figure(const Model& m, const SimulationResult& r) {
  plot::Figure f;
  f.id = "link_loads";
  f.title = "Link loads; dashed: quasi-static load (particular solution)";
  f.x = plot::make_axis("time t", "s");
  const auto& t = column(r, "t_s");
  const bool any_torque = std::any_of(m.links.begin(), m.links.end(),
                                      [&](const Link& l) { return std::string(link_load_unit(m, l)) == "N*m"; });
  const bool any_force = std::any_of(m.links.begin(), m.links.end(),
                                     [&](const Link& l) { return std::string(link_load_unit(m, l)) == "N"; });
  f.y = any_torque ? plot::make_axis("link torque M", "N·m") : plot::make_axis("link force F", "N");
  if (any_torque && any_force) f.y2 = plot::make_axis("link force F", "N");
  for (std::size_t l = 0; l < m.links.size(); ++l) {
    const Link& L = m.links[l];
    const std::string unit = link_load_unit(m, L);
    const int axis = any_torque && unit == "N" ? 2 : 1;
    f.series.push_back(plot::make_series(fmt::format("{} ({}–{})", L.name, endpoint_name(m, L.a), endpoint_name(m, L.b)),
                                         t, column(r, L.name + ".load_"), plot::Style::line, axis));
    if (l < r.links.size() && std::isfinite(r.links[l].static_load))
      f.ref_lines.push_back(plot::make_ref_line(
          r.links[l].static_load, fmt::format("{}* = {} {}", L.name, number(r.links[l].static_load), plot::pretty_unit(unit)),
          static_cast<int>(l), axis));
  }
  f.zero_line = true;
  f.legend = plot::Figure::Legend::below;
  return f;
}

plot::Figure body_speeds_figure(const Model& m, const SimulationResult& r) {
  plot::Figure f;
  f.id = "body_speeds";
  f.title = "Body speeds";
  f.x = plot::make_axis("time t", "s");
  const auto& t = column(r, "t_s");
  const bool any_rot = std::any_of(m.bodies.begin(), m.bodies.end(), [](const Body& b) { return b.kind == BodyKind::rotational; });
  const bool any_tr = std::any_of(m.bodies.begin(), m.bodies.end(), [](const Body& b) { return b.kind == BodyKind::translational; });
  f.y = any_rot ? plot::make_axis("angular velocity ω", "rad/s") : plot::make_axis("velocity v", "m/s");
  if (any_rot && any_tr) f.y2 = plot::make_axis("velocity v", "m/s");
  for (const Body& b : m.bodies)
    f.series.push_back(plot::make_series(b.name, t, column(r, b.name + ".velocity_"), plot::Style::line,
                                         any_rot && b.kind == BodyKind::translational ? 2 : 1));
  f.legend = plot::Figure::Legend::below;
  return f;
}

std::vector<plot::Figure> simulation_figures(const Model& m, const SimulationResult& r) {
  std::vector<plot::Figure> figs;
  if (!m.links.empty()) figs.push_back(link_loads_figure(m, r));
  figs.push_back(body_speeds_figure(m, r));
  return figs;
}

plot::Figure mode_shapes_figure(const Model& m, const Modes& modes) {
  plot::Figure f;
  f.id = "mode_shapes";
  f.title = "Elastic mode shapes (each scaled to max |φ| = 1)";
  f.x = plot::make_axis("body", "");
  for (int i = 0; i < m.dof(); ++i) f.x.ticks.push_back({i + 1.0, m.bodies[static_cast<std::size_t>(i)].name});
  f.y = plot::make_axis("relative amplitude φ / max|φ|", "");
  for (Eigen::Index k = 0; k < modes.shapes.cols(); ++k) {
    const double scale = modes.shapes.col(k).cwiseAbs().maxCoeff();
    plot::Series s = plot::make_series(fmt::format("mode {}: {:.4g} Hz ({:.4g} rad/s)", k + 1,
                                                   modes.omega(k) / (2 * kPi), modes.omega(k)),
                                       {}, {}, plot::Style::linepoints);
    for (int i = 0; i < m.dof(); ++i) {
      s.x.push_back(i + 1.0);
      s.y.push_back(scale > 0 ? modes.shapes(i, k) / scale : 0.0);
    }
    f.series.push_back(std::move(s));
  }
  f.y.min = -1.1, f.y.max = 1.1;
  f.zero_line = true;
  f.legend = plot::Figure::Legend::below;
  return f;
}

plot::Figure gears_pitch_figure(const io::GearReport& r) {
  const auto& m = r.model;
  const double dx = m.L_installed * 1e3;  // pinion centre, mm
  plot::Figure f;
  f.id = "pitch_curves";
  f.title = fmt::format("Pitch curves and sector boundaries (L = {:.5g} mm)", dx);
  f.x = plot::make_axis("x", "mm");
  f.y = plot::make_axis("y", "mm");
  f.equal_aspect = true;
  // Sector boundaries: a ray from each centre through every sector start, a little beyond the curve.
  plot::Series rays = plot::make_series("sector boundaries", {}, {}, plot::Style::thin);
  auto ray = [&](double cx, double beta, double radius) {
    rays.x.insert(rays.x.end(), {cx, cx + radius * std::cos(beta), kNaN});
    rays.y.insert(rays.y.end(), {0.0, radius * std::sin(beta), kNaN});
  };
  const int pinion_big = static_cast<int>(std::lround(2 * kPi / m.Theta()));
  for (int q = 0; q < m.N; ++q)
    for (const auto& row : r.synthesis.sectors) ray(0.0, -row.phi + q * m.T(), row.rH * 1e3 * 1.06);
  for (int q = 0; q < pinion_big; ++q)
    for (const auto& row : r.synthesis.sectors) ray(dx, kPi + row.theta + q * m.Theta(), row.r * 1e3 * 1.08);
  f.series.push_back(std::move(rays));
  const auto c = gears::sample_pitch_curves(m, 360);
  plot::Series wheel = plot::make_series(fmt::format("wheel (H), z_H = {}: r_H(φ)", m.zH), {}, {});
  plot::Series pinion = plot::make_series(fmt::format("pinion, z = {}: r(θ)", m.z), {}, {});
  for (std::size_t k = 0; k < c.wheel_x.size(); ++k) wheel.x.push_back(c.wheel_x[k] * 1e3), wheel.y.push_back(c.wheel_y[k] * 1e3);
  for (std::size_t k = 0; k < c.pinion_x.size(); ++k)
    pinion.x.push_back(dx + c.pinion_x[k] * 1e3), pinion.y.push_back(c.pinion_y[k] * 1e3);
  f.series.push_back(std::move(wheel));
  f.series.push_back(std::move(pinion));
  plot::Series centres = plot::make_series("centres", {0.0, dx}, {0.0, 0.0}, plot::Style::linepoints);
  centres.dashed = true;
  centres.in_legend = false;
  f.series.push_back(std::move(centres));
  f.legend = plot::Figure::Legend::below;
  return f;
}

plot::Figure gears_ratio_figure(const io::GearReport& r) {
  const auto& m = r.model;
  const double T = m.T(), deg = 180.0 / kPi;
  plot::Figure f;
  f.id = "ratio";
  f.title = "Gear ratio over one big sector";
  f.x = plot::make_axis("wheel angle φ", "deg");
  f.x.min = -0.5 * T * deg, f.x.max = 0.5 * T * deg;
  f.y = plot::make_axis("ratio i = dθ/dφ", "");
  plot::Series law = plot::make_series("theoretical i(φ) of the law", {}, {});
  plot::Series step = plot::make_series("stepwise Δθ_j/Δφ_j of the sectors", {}, {});
  for (int q = 0; q <= 600; ++q) {
    const double phi = -0.5 * T + T * q / 600.0;
    law.x.push_back(phi * deg);
    law.y.push_back(m.law.ratio(phi).v);
  }
  // Sectors run from φ_j down to φ_j − Δφ_j; draw them from left to right as a staircase.
  auto rows = r.synthesis.sectors;
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.phi < b.phi; });
  for (const auto& row : rows) {
    const double i = row.dtheta / row.dphi;
    step.x.insert(step.x.end(), {(row.phi - row.dphi) * deg, row.phi * deg});
    step.y.insert(step.y.end(), {i, i});
  }
  f.series.push_back(std::move(law));
  f.series.push_back(std::move(step));
  f.legend = plot::Figure::Legend::below;
  return f;
}

}  // namespace machdyn
