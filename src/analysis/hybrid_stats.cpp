#include "machdyn/analysis/hybrid_stats.hpp"

#include <algorithm>
#include <limits>
#include <string>

namespace machdyn {

const std::vector<std::string>& counted_event_kinds() {
  static const std::vector<std::string> kinds = {"gap_closed", "gap_opened", "stick", "slip", "reversal"};
  return kinds;
}

std::vector<long> event_counts(const HybridReport& h) {
  const auto& kinds = counted_event_kinds();
  std::vector<long> n(kinds.size(), 0);
  for (const auto& e : h.events) {
    const auto it = std::find(kinds.begin(), kinds.end(), e.kind);
    if (it != kinds.end()) ++n[static_cast<size_t>(it - kinds.begin())];
  }
  return n;
}

std::vector<ContactStatistics> contact_statistics(const Model& m, const SimulationResult& r) {
  std::vector<ContactStatistics> out;
  for (const auto& c : m.contacts) {
    if (c.joint) continue;  // a gear joint never slips and has no limit
    ContactStatistics s;
    s.name = c.name;
    std::vector<double> late;  // slip starts in the second half of the run
    for (const auto& p : r.hybrid.slip_phases) {
      if (p.contact != c.name) continue;
      ++s.slips;
      if (p.t_start >= 0.5 * m.simulation.t_end) late.push_back(p.t_start);
    }
    s.period_s = late.size() >= 2 ? (late.back() - late.front()) / static_cast<double>(late.size() - 1)
                                  : std::numeric_limits<double>::quiet_NaN();
    // A ratio of like quantities only: a force in N over a brake torque in N·m is no F_max/F_sc.
    const std::string unit = load_unit(m.bodies[static_cast<size_t>(c.a)].kind);
    for (size_t l = 0; l < m.links.size() && l < r.links.size(); ++l)
      s.link_max_over_static_limit.push_back(unit == link_load_unit(m, m.links[l])
                                                 ? r.links[l].max / c.static_limit
                                                 : std::numeric_limits<double>::quiet_NaN());
    out.push_back(std::move(s));
  }
  return out;
}

}  // namespace machdyn
