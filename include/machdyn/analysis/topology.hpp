#pragma once
/// @file
/// Topologies of a drive by name: the `--topology` syntax, every topology a model can be in, and
/// the topologies a simulation passed through (with their time intervals).
///
/// Syntax: a comma-separated list of ELEMENT=MODE (spaces allowed around the words):
///   link with a gap:   open | closed (= closed+) | closed+ | closed-
///   contact or brake:  stuck (a brake: also `applied`, holding) | slip+ | slip- | sliding (= slip+; a
///                      freewheel: its free direction)
///                      | released (acts with no force: a released brake, an opened clutch)
/// Elements not named keep the mode of the initial state (elements/linearize.hpp initial_topology).
/// A stuck contact is a constraint of the linear model, a closed gap a spring, a sliding contact
/// its kinetic slope dF_k/du (0 for a constant kinetic level), an open gap or a released contact
/// nothing.

#include <string>
#include <vector>

#include "machdyn/analysis/hybrid_report.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/elements/linear_model.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// Applies `text` to `topo` (which starts as the initial topology or any other). Throws InputError
/// with every problem at once (unknown element, a link without a gap, a wrong mode word), each at
/// its column in `text`, the file of `where` naming the option (e.g. "--topology").
void apply_topology_text(const Model& m, const std::string& text, const Location& where, Topology& topo);

/// `m`'s topology from the text (initial_topology(m, t), then apply_topology_text).
Topology parse_topology(const Model& m, const std::string& text, const Location& where, double t = 0.0);

/// The topology in the same syntax, every gap link and contact named in model order (empty for a
/// model without switching elements): e.g. "backlash=closed+, adhesion=stuck, W=slip+".
std::string topology_label(const Model& m, const Topology& topo);

/// Number of switching elements (links with a gap, contacts and brakes).
int switching_elements(const Model& m);

/// Every topology that matters for the linear model: each gap closed+ or open, each contact and
/// brake stuck or sliding (slip+; a freewheel or stop in its free direction). A released brake or
/// an opened clutch is linearly the same as a sliding one with a constant kinetic level, so it is
/// not listed again. 2^k topologies for k switching elements; throws InputError (at m.source) for
/// k > max_elements — name the modes then.
std::vector<Topology> all_topologies(const Model& m, int max_elements = 12);

/// A topology and the time intervals a simulation spent in it.
struct TopologyInterval {
  Topology topology;
  std::vector<std::pair<double, double>> intervals;  ///< [t_start, t_end], s, in time order
};

/// The topologies of a run from its mode events (HybridReport::events; `initial` entries give the
/// modes at 0) and each brake's application time, grouped: one entry per distinct topology in
/// order of first appearance. Intervals of zero length (several switches at one instant) are
/// dropped. A smooth run (no switching elements) gives one topology over [0, t_end].
std::vector<TopologyInterval> run_topologies(const Model& m, const HybridReport& report, double t_end);

}  // namespace machdyn
