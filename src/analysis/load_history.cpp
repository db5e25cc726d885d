#include "machdyn/analysis/load_history.hpp"

#include <stdexcept>
#include <string>

namespace machdyn {
namespace {

/// One run with a rainflow counter on each chosen link (`residue` their rule); returns the counters
/// (not finished) and the chosen links' indices.
struct CountedRun {
  std::vector<int> links;
  std::vector<std::vector<RainflowCycle>> cycles;
  std::vector<RainflowCounter> counters;
};

void count_run(const Model& m, const SimulateOptions& options, const LinkCycleOptions& count, RainflowResidue residue,
               CountedRun& run, SimulationResult* result) {
  const int nl = static_cast<int>(m.links.size());
  run.links = count.links;
  if (run.links.empty())
    for (int l = 0; l < nl; ++l) run.links.push_back(l);
  for (const int l : run.links)
    if (l < 0 || l >= nl) throw std::invalid_argument("count_link_cycles: no link " + std::to_string(l));
  const std::size_t n = run.links.size();
  if (count.gates.size() > 1 && count.gates.size() != n)
    throw std::invalid_argument("count_link_cycles: " + std::to_string(count.gates.size()) + " gates for " +
                                std::to_string(n) + " links");
  run.cycles.resize(n);
  run.counters.reserve(n);
  std::vector<int> slot(static_cast<std::size_t>(nl), -1);  // link → its counter, −1 when not counted
  for (std::size_t k = 0; k < n; ++k) {
    const double gate = count.gates.empty() ? 0.0 : count.gates.size() == 1 ? count.gates[0] : count.gates[k];
    std::vector<RainflowCycle>* cycles = &run.cycles[k];
    run.counters.emplace_back([cycles](const RainflowCycle& c) { cycles->push_back(c); }, gate, residue);
    slot[static_cast<std::size_t>(run.links[k])] = static_cast<int>(k);
  }
  SimulationResult r = simulate(m, options, [&](int l, double, double v) {
    const int k = slot[static_cast<std::size_t>(l)];
    if (k >= 0) run.counters[static_cast<std::size_t>(k)].add(v);
  });
  if (result) *result = std::move(r);
}

}  // namespace

std::vector<LinkCycles> count_link_cycles(const Model& m, const SimulateOptions& options,
                                          const LinkCycleOptions& count, SimulationResult* result) {
  CountedRun run;
  count_run(m, options, count, count.residue, run, result);
  std::vector<LinkCycles> out(run.links.size());
  for (std::size_t k = 0; k < run.links.size(); ++k) {
    run.counters[k].finish();
    out[k].link = m.links[static_cast<std::size_t>(run.links[k])].name;
    out[k].cycles = std::move(run.cycles[k]);
    out[k].turning_points = run.counters[k].turning_points();
    out[k].max_held = run.counters[k].max_held();
  }
  return out;
}

std::vector<RainflowPart> link_parts(const Model& m, const SimulateOptions& options, const LinkCycleOptions& count,
                                     SimulationResult* result) {
  CountedRun run;
  count_run(m, options, count, RainflowResidue::repeat, run, result);  // the four-point rule: no halves
  std::vector<RainflowPart> out(run.links.size());
  for (std::size_t k = 0; k < run.links.size(); ++k) {
    run.counters[k].flush();
    out[k].residue = run.counters[k].residue();
    out[k].cycles = std::move(run.cycles[k]);
  }
  return out;
}

}  // namespace machdyn
