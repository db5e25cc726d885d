// The report's table of the linear analysis: natural frequencies and damping per topology.
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "machdyn/analysis/mode_kinds.hpp"
#include "machdyn/io/report.hpp"

namespace machdyn::report {

Table topology_modes_table(const Model& m, const std::vector<TopologyModes>& list) {
  Table t;
  t.caption = "Natural frequencies per topology (linearized: stuck contacts as constraints, closed gaps as springs)";
  t.header = {"topology", "in the run, s", "rigid-body modes", "f, Hz", "ζ"};
  bool any_damped = false;
  // A swinging load's pendulum and rope-stretch modes are named beside their frequencies
  // (analysis/mode_kinds.hpp); the drive line's stay bare.
  const bool kinds = has_swinging_load(m);
  for (const TopologyModes& x : list) {
    const std::vector<ModeKind> kind = kinds ? mode_kinds(m, x.modes.shapes) : std::vector<ModeKind>{};
    std::string iv, hz, zeta;
    for (const auto& [a, b] : x.intervals) {
      if (iv.size() > 120) {
        iv += fmt::format(" … ({} intervals)", x.intervals.size());
        break;
      }
      iv += fmt::format("{}{:.4g}–{:.4g}", iv.empty() ? "" : ", ", a, b);
    }
    for (Eigen::Index k = 0; k < x.modes.omega.size() && k < 12; ++k)
    {
      hz += fmt::format("{}{:.5g}", hz.empty() ? "" : ", ", x.modes.omega(k) / (2 * std::numbers::pi));
      if (kinds && kind[static_cast<size_t>(k)] != ModeKind::drive_line) hz += fmt::format(" ({})", to_string(kind[static_cast<size_t>(k)]));
    }
    if (x.modes.omega.size() > 12) hz += fmt::format(" … ({} modes)", x.modes.omega.size());
    if (x.damped) {
      any_damped = true;
      int k = 0;
      for (const DampedMode& d : x.damped_modes.modes)
        if (d.oscillatory && ++k <= 12) zeta += fmt::format("{}{:.4g}", zeta.empty() ? "" : ", ", d.zeta);
    }
    t.rows.push_back({x.label.empty() ? "(no gap, contact or brake)" : x.label, iv.empty() ? "–" : iv,
                      fmt::format("{}", x.modes.rigid_body_modes), hz.empty() ? "none" : hz, zeta.empty() ? "–" : zeta});
  }
  t.text_values = true;
  t.note = any_damped ? "ζ: damping ratios of the oscillatory modes of the state-space eigenproblem, ascending in ω_n."
                      : "No damper acts: the modes are undamped.";
  if (kinds)
    t.note += " (pendulum), (rope stretch): the swinging load's modes — the loads' horizontal or vertical motion carries "
              "most of the mode's kinetic energy (docs/sway.md, \"Pendulum modes\"); the others are the drive line's.";
  return t;
}

}  // namespace machdyn::report
