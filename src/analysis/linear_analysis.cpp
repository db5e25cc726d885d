#include "machdyn/analysis/linear_analysis.hpp"

#include <algorithm>
#include <limits>
#include <stdexcept>

#include "machdyn/elements/linearize.hpp"

namespace machdyn {

TopologyModes analyse_topology(const Model& m, const Topology& topo, double t, int max_damped_dof) {
  TopologyModes out;
  out.topology = topo;
  out.label = topology_label(m, topo);
  const LinearModel lin = linearize(m, topo, t);
  out.modes = undamped_modes(lin);
  bool has_damping = false;
  for (const auto& e : lin.D) has_damping = has_damping || e.value() != 0.0;
  if (has_damping && out.modes.dof <= max_damped_dof) {
    out.damped = true;
    out.damped_modes = damped_modes(lin);
  }
  out.damped_skipped = has_damping && !out.damped;
  return out;
}

std::vector<TopologyModes> run_topology_modes(const Model& m, const HybridReport& report, double t_end) {
  std::vector<TopologyModes> out;
  for (const TopologyInterval& ti : run_topologies(m, report, t_end)) {
    TopologyModes t = analyse_topology(m, ti.topology, ti.intervals.front().first);
    t.intervals = ti.intervals;
    out.push_back(std::move(t));
  }
  return out;
}

std::unique_ptr<FrequencyResponse> default_frequency_response(const Model& m, const std::vector<TopologyModes>& list,
                                                              std::string* label) {
  if (m.loads.empty() || m.links.empty()) return nullptr;
  for (const TopologyModes& t : list) {
    if (t.modes.omega.size() == 0) continue;
    const Location at{m.source, 0, 0};
    std::vector<LinearSignal> outs;
    for (const Link& l : m.links) outs.push_back(linear_output(m, t.topology, l.name + ".load", at));
    const Eigen::VectorXd w = frequency_grid(0.1 * t.modes.omega.minCoeff(), 3.0 * t.modes.omega.maxCoeff(), 400, true);
    if (label) *label = t.label;
    return std::make_unique<FrequencyResponse>(
        frequency_response(linearize(m, t.topology), linear_input(m, m.loads.front().name, at), outs, w));
  }
  return nullptr;
}

PositionFrequencies frequencies_over_position(const Model& m, const Topology& topo, int body,
                                              const Eigen::VectorXd& positions) {
  if (body < 0 || body >= m.dof()) throw std::invalid_argument("frequencies_over_position: no such body");
  const int n = m.dof();
  std::vector<double> y(static_cast<size_t>(2 * n));
  for (int i = 0; i < n; ++i)
    y[static_cast<size_t>(i)] = m.bodies[static_cast<size_t>(i)].q0, y[static_cast<size_t>(n + i)] = 0.0;
  std::vector<Eigen::VectorXd> rows;
  Eigen::Index width = 0;
  for (double q : positions) {
    y[static_cast<size_t>(body)] = q;
    rows.push_back(undamped_modes(linearize(m, topo, 0.0, y.data())).omega);
    width = std::max(width, rows.back().size());
  }
  PositionFrequencies out;
  out.body = m.bodies[static_cast<size_t>(body)].name;
  out.positions = positions;
  out.omega = Eigen::MatrixXd::Constant(positions.size(), width, std::numeric_limits<double>::quiet_NaN());
  for (size_t p = 0; p < rows.size(); ++p)
    out.omega.row(static_cast<Eigen::Index>(p)).head(rows[p].size()) = rows[p].transpose();
  return out;
}

std::vector<CampbellCrossing> campbell(const Eigen::VectorXd& omega, const std::vector<ExcitationOrder>& orders,
                                       double speed_lo, double speed_hi) {
  if (!(speed_hi >= speed_lo)) throw std::invalid_argument("campbell: the speed range is empty");
  std::vector<CampbellCrossing> out;
  for (const ExcitationOrder& o : orders) {
    if (!(o.order > 0.0)) throw std::invalid_argument("campbell: an excitation order must be positive");
    for (Eigen::Index k = 0; k < omega.size(); ++k) {
      const double speed = omega(k) / o.order;
      if (speed >= speed_lo && speed <= speed_hi)
        out.push_back({o.name, o.order, static_cast<int>(k) + 1, omega(k), speed});
    }
  }
  std::sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.speed < b.speed; });
  return out;
}

}  // namespace machdyn
