#pragma once
/// @file
/// The linear analyses of a drive that knows its contact state, built on linearize()
/// (elements/linearize.hpp) and the modal solvers (analysis/modal.hpp):
///   - the modes of each topology (analyse_topology), with their time intervals from a run;
///   - the frequencies of a machine with I(q) over its position (frequencies_over_position);
///   - the resonance map of a speed range against excitation orders (campbell).

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include "machdyn/analysis/frequency_response.hpp"
#include "machdyn/analysis/hybrid_report.hpp"
#include "machdyn/analysis/modal.hpp"
#include "machdyn/analysis/topology.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// The undamped and damped modes of one topology at the initial state.
struct TopologyModes {
  Topology topology;
  std::string label;                                 ///< topology_label()
  std::vector<std::pair<double, double>> intervals;  ///< from a run (s); empty otherwise
  UndampedModes modes;
  bool damped = false;                               ///< D ≠ 0: `damped_modes` filled
  bool damped_skipped = false;                       ///< D ≠ 0 but too many coordinates
  DampedModes damped_modes;
};

/// The modes of `topo` (t: the time the brakes' ramps and kinetic slopes are evaluated at). The
/// damped eigenproblem is solved when the linear model has damping and at most `max_damped_dof`
/// independent coordinates (the dense 2r × 2r eigenproblem costs O(r³): 1.5 s for r = 300).
TopologyModes analyse_topology(const Model& m, const Topology& topo, double t = 0.0, int max_damped_dof = 400);

/// The modes of each topology a run passed through (run_topologies), with their intervals.
std::vector<TopologyModes> run_topology_modes(const Model& m, const HybridReport& report, double t_end);

/// What a report's frequency response shows (`machdyn report --frf-input/--frf-output/--frf-band`,
/// Python `report(frf_input=, frf_outputs=, frf_band_hz=)`); empty fields are chosen:
///   input:   the drive — the first motor load, else the body of the first drive (`drives:`), else the
///            first load that is not a body's weight, else the first body;
///   outputs: every link load (LINK.load; also BODY.position, BODY.speed);
///   band:    0.1 × the lowest natural frequency up to 2 × the highest resonance that shows in the
///            outputs (a peak of |H| above 1 % of the output's largest), so a stiff coupling's mode
///            that the input barely excites does not stretch the band to hundreds of Hz.
struct FrfChoice {
  std::string input;
  std::vector<std::string> outputs;
  double f_lo_hz = 0.0, f_hi_hz = 0.0;  ///< the band in Hz; 0, 0: chosen
  std::string option_prefix = "--frf-";  ///< errors are located at PREFIX input/output/band
};

/// The input FrfChoice chooses when none is named: a load's name or a body's name.
std::string default_frf_input(const Model& m);

/// The frequency response a report shows (FrfChoice) in the topology of `list` with the most elastic
/// modes (a hanging load rather than one resting on the floor; on a tie the longest in the run, then
/// the first), 400 log-spaced frequencies. Null when there is none (or no link and no output named).
/// *label gets that topology's label. A name that is no load, body or output is an InputError.
std::unique_ptr<FrequencyResponse> default_frequency_response(const Model& m, const std::vector<TopologyModes>& list,
                                                              std::string* label, const FrfChoice& choice = {});

/// Elastic frequencies (rad/s) with body `body` at each position in `positions` (rad or m), the
/// other bodies at their initial positions, in topology `topo`: row p holds the ascending
/// frequencies at positions(p), NaN-padded to the largest count. For a machine with I(q) this
/// is the linearization at each point of its cycle (geometric stiffness included).
struct PositionFrequencies {
  std::string body;
  Eigen::VectorXd positions;
  Eigen::MatrixXd omega;
};
PositionFrequencies frequencies_over_position(const Model& m, const Topology& topo, int body,
                                              const Eigen::VectorXd& positions);

/// An excitation order: frequency = order × Ω (Ω the speed of the reference shaft, rad/s), e.g.
/// a gear mesh (teeth × shaft speed) or a motor's pole-pass frequency.
struct ExcitationOrder {
  std::string name;
  double order = 1.0;  ///< > 0
};
/// A crossing of an excitation line with a natural frequency: resonance at shaft speed Ω.
struct CampbellCrossing {
  std::string order_name;
  double order = 0.0;
  int mode = 0;        ///< 1-based elastic mode
  double omega = 0.0;  ///< natural frequency, rad/s
  double speed = 0.0;  ///< Ω = ω / order, rad/s (of the reference shaft)
};
/// The crossings of each order's line ω = order Ω, Ω ∈ [speed_lo, speed_hi], with the natural
/// frequencies `omega` (rad/s), ascending by speed. Throws std::invalid_argument for order ≤ 0
/// or speed_hi < speed_lo.
std::vector<CampbellCrossing> campbell(const Eigen::VectorXd& omega, const std::vector<ExcitationOrder>& orders,
                                       double speed_lo, double speed_hi);

}  // namespace machdyn
