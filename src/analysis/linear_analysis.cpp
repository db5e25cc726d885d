#include "machdyn/analysis/linear_analysis.hpp"

#include <algorithm>
#include <numbers>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <fmt/format.h>

#include "machdyn/analysis/hanging_rest.hpp"
#include "machdyn/elements/linearize.hpp"

namespace machdyn {

TopologyModes analyse_topology(const Model& m, const Topology& topo, double t, int max_damped_dof) {
  TopologyModes out;
  out.topology = topo;
  out.label = topology_label(m, topo);
  const std::vector<double> y = linearization_state(m, topo);  // a load that starts on the floor hangs
  const LinearModel lin = linearize(m, topo, t, y.empty() ? nullptr : y.data());
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

std::string default_frf_input(const Model& m) {
  for (const Load& l : m.loads)
    if (l.kind == LoadKind::motor_linear || l.kind == LoadKind::motor_kloss || l.kind == LoadKind::motor_table) return l.name;
  if (!m.drives.empty()) return m.bodies[static_cast<size_t>(m.drives.front().body)].name;
  for (const Load& l : m.loads) {
    // compile's weight of a vertical body ("NAME.weight", model.hpp Body::vertical) excites nothing a drive does
    const Body& b = m.bodies[static_cast<size_t>(l.body)];
    if (!(b.vertical != 0 && l.name == b.name + ".weight")) return l.name;
  }
  return m.bodies.empty() ? std::string() : m.bodies.front().name;
}

std::unique_ptr<FrequencyResponse> default_frequency_response(const Model& m, const std::vector<TopologyModes>& list,
                                                              std::string* label, const FrfChoice& choice) {
  if (m.bodies.empty() || (m.links.empty() && choice.outputs.empty())) return nullptr;
  const Location at_input{choice.option_prefix + "input", 0, 0}, at_output{choice.option_prefix + "output", 0, 0},
      at_band{choice.option_prefix + "band", 0, 0};
  const bool band_given = choice.f_lo_hz > 0.0 || choice.f_hi_hz > 0.0;
  if (band_given && !(choice.f_lo_hz > 0.0 && choice.f_hi_hz > choice.f_lo_hz && std::isfinite(choice.f_hi_hz)))
    throw InputError(at_band, fmt::format("expected 0 < f_lo < f_hi in Hz, got {} … {}", choice.f_lo_hz, choice.f_hi_hz));
  const std::string input_name = choice.input.empty() ? default_frf_input(m) : choice.input;
  const LinearSignal input = linear_input(m, input_name, at_input);
  // The topology: the one with the most elastic modes (a hoist's hanging load, not the load resting
  // on the floor with its rope slack, where the rope force answers nothing); on a tie the longest
  // in the run, then the first.
  std::vector<const TopologyModes*> order;
  for (const TopologyModes& t : list) order.push_back(&t);
  auto time_in = [](const TopologyModes& t) {
    double s = 0.0;
    for (const auto& [a, b] : t.intervals) s += b - a;
    return s;
  };
  std::stable_sort(order.begin(), order.end(), [&](const TopologyModes* x, const TopologyModes* y) {
    if (x->modes.omega.size() != y->modes.omega.size()) return x->modes.omega.size() > y->modes.omega.size();
    return time_in(*x) > time_in(*y);
  });
  for (const TopologyModes* tp : order) {
    const TopologyModes& t = *tp;
    if (t.modes.omega.size() == 0) continue;
    std::vector<LinearSignal> outs;
    if (choice.outputs.empty())
      for (const Link& l : m.links) outs.push_back(linear_output(m, t.topology, l.name + ".load", at_output));
    else
      for (const auto& o : choice.outputs) outs.push_back(linear_output(m, t.topology, o, at_output));
    const std::vector<double> y = linearization_state(m, t.topology);
    const LinearModel lin = linearize(m, t.topology, 0.0, y.empty() ? nullptr : y.data());
    const double two_pi = 2.0 * std::numbers::pi;
    if (label) *label = t.label;
    if (band_given)
      return std::make_unique<FrequencyResponse>(frequency_response(
          lin, input, outs, frequency_grid(two_pi * choice.f_lo_hz, two_pi * choice.f_hi_hz, 400, true)));
    // The band: a first look over 0.1 × the lowest to 3 × the highest mode finds the resonances
    // that show in the outputs; the band ends at twice the highest of those.
    const double lo = 0.1 * t.modes.omega.minCoeff();
    auto wide = std::make_unique<FrequencyResponse>(
        frequency_response(lin, input, outs, frequency_grid(lo, 3.0 * t.modes.omega.maxCoeff(), 400, true)));
    const Eigen::MatrixXd mag = wide->magnitude();
    double top = 0.0;
    for (const ResonancePeak& p : resonance_peaks(*wide)) {
      double largest = 0.0;
      for (Eigen::Index f = 0; f < mag.rows(); ++f)
        if (std::isfinite(mag(f, p.output))) largest = std::max(largest, mag(f, p.output));
      if (p.magnitude >= 0.01 * largest) top = std::max(top, p.omega);
    }
    const double hi = top > 0.0 ? 2.0 * top : 3.0 * t.modes.omega.maxCoeff();
    if (!(hi < 3.0 * t.modes.omega.maxCoeff())) return wide;
    return std::make_unique<FrequencyResponse>(frequency_response(lin, input, outs, frequency_grid(lo, hi, 400, true)));
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
