#include "machdyn/analysis/load_history.hpp"

#include <stdexcept>
#include <string>

namespace machdyn {

std::vector<LinkCycles> count_link_cycles(const Model& m, const SimulateOptions& options,
                                          const LinkCycleOptions& count, SimulationResult* result) {
  const int nl = static_cast<int>(m.links.size());
  std::vector<int> links = count.links;
  if (links.empty())
    for (int l = 0; l < nl; ++l) links.push_back(l);
  for (const int l : links)
    if (l < 0 || l >= nl) throw std::invalid_argument("count_link_cycles: no link " + std::to_string(l));
  if (count.gates.size() > 1 && count.gates.size() != links.size())
    throw std::invalid_argument("count_link_cycles: " + std::to_string(count.gates.size()) + " gates for " +
                                std::to_string(links.size()) + " links");
  std::vector<LinkCycles> out(links.size());
  std::vector<RainflowCounter> counters;
  std::vector<int> slot(static_cast<std::size_t>(nl), -1);  // link → its counter, −1 when not counted
  counters.reserve(links.size());
  for (std::size_t k = 0; k < links.size(); ++k) {
    out[k].link = m.links[static_cast<std::size_t>(links[k])].name;
    const double gate = count.gates.empty() ? 0.0 : count.gates.size() == 1 ? count.gates[0] : count.gates[k];
    std::vector<RainflowCycle>* cycles = &out[k].cycles;
    counters.emplace_back([cycles](const RainflowCycle& c) { cycles->push_back(c); }, gate, count.residue);
    slot[static_cast<std::size_t>(links[k])] = static_cast<int>(k);
  }
  SimulationResult r = simulate(m, options, [&](int l, double, double v) {
    const int k = slot[static_cast<std::size_t>(l)];
    if (k >= 0) counters[static_cast<std::size_t>(k)].add(v);
  });
  for (std::size_t k = 0; k < links.size(); ++k) {
    counters[k].finish();
    out[k].turning_points = counters[k].turning_points();
    out[k].max_held = counters[k].max_held();
  }
  if (result) *result = std::move(r);
  return out;
}

}  // namespace machdyn
