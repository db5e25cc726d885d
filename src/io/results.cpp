#include "machdyn/io/results.hpp"

#include <cmath>
#include <numbers>
#include <fmt/format.h>

namespace machdyn {

std::string timeseries_csv(const SimulationResult& r) {
  std::string s;
  for (size_t c = 0; c < r.column_names.size(); ++c) {
    if (c) s += ',';
    s += r.column_names[c];
  }
  s += '\n';
  const size_t rows = r.columns.empty() ? 0 : r.columns[0].size();
  s.reserve(s.size() + rows * r.columns.size() * 24);
  for (size_t i = 0; i < rows; ++i) {
    for (size_t c = 0; c < r.columns.size(); ++c) {
      if (c) s += ',';
      fmt::format_to(std::back_inserter(s), "{:.17g}", r.columns[c][i]);
    }
    s += '\n';
  }
  return s;
}

namespace {
nlohmann::json number_or_null(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

const char* method_name(IntegratorChoice c) {
  switch (c) {
    case IntegratorChoice::dopri5: return "dopri5";
    case IntegratorChoice::bdf: return "bdf";
    default: return "auto";
  }
}
}  // namespace

nlohmann::json simulation_summary(const Model& m, const SimulationResult& r) {
  nlohmann::json j;
  j["model"] = m.name;
  j["source"] = m.source;
  const auto& s = m.simulation;
  j["settings"] = {{"t_end_s", s.t_end}, {"dt_out_s", s.dt_out}, {"rtol", s.rtol}, {"atol", s.atol},
                   {"integrator", method_name(s.integrator)}};
  nlohmann::json links = nlohmann::json::object();
  for (size_t l = 0; l < m.links.size(); ++l) {
    const auto& L = r.links[l];
    links[m.links[l].name] = {{"max", L.max},
                              {"min", L.min},
                              {"t_max", L.t_max},
                              {"t_min", L.t_min},
                              {"static", L.static_load},
                              {"dynamic_factor", number_or_null(L.dynamic_factor)},
                              {"unit", link_load_unit(m, m.links[l])}};
  }
  j["links"] = links;
  j["solver"] = {{"method", r.stats.method},
                 {"reason", r.method_reason},
                 {"steps", r.stats.stepper.steps},
                 {"rejected_steps", r.stats.stepper.rejected},
                 {"rhs_evals", r.stats.stepper.rhs_evals},
                 {"jac_evals", r.stats.stepper.jac_evals},
                 {"wall_time_s", r.stats.wall_time_s},
                 {"output_rows", r.columns.empty() ? 0 : r.columns[0].size()}};
  return j;
}

nlohmann::json modes_summary(const Model& m, const Modes& modes) {
  nlohmann::json j;
  j["model"] = m.name;
  j["rigid_body_modes"] = modes.rigid_body_modes;
  std::vector<double> w(modes.omega.data(), modes.omega.data() + modes.omega.size()), hz;
  for (double x : w) hz.push_back(x / (2.0 * std::numbers::pi));
  j["frequencies_rad_s"] = w;
  j["frequencies_hz"] = hz;
  nlohmann::json bodies = nlohmann::json::array();
  for (const auto& b : m.bodies) bodies.push_back(b.name);
  j["bodies"] = bodies;
  nlohmann::json shapes = nlohmann::json::array();
  for (Eigen::Index k = 0; k < modes.shapes.cols(); ++k) {
    nlohmann::json amp = nlohmann::json::object();
    for (int i = 0; i < m.dof(); ++i) amp[m.bodies[static_cast<size_t>(i)].name] = modes.shapes(i, k);
    shapes.push_back({{"mode", k + 1}, {"frequency_rad_s", w[static_cast<size_t>(k)]},
                      {"frequency_hz", hz[static_cast<size_t>(k)]}, {"amplitudes", amp}});
  }
  j["shapes"] = shapes;
  return j;
}

}  // namespace machdyn
