#pragma once
// Velocity jumps of machines (stepwise gears, model/machine.hpp) as event functions of the one run,
// and the samples of their motion behind MachineRunReport (analysis/simulate.hpp).

#include <string>
#include <vector>

#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/model/machine.hpp"
#include "machdyn/solve/stepper.hpp"

namespace machdyn::detail {

/// For each stepwise gear the next jump positions above and below q are event functions
/// g = q_up − q ≥ 0, g = q − q_down ≥ 0; at a crossing the speed jumps (Machine::velocity_after_jump).
/// Also samples the traced bodies (jumps or a point-speed report) for their MachineRunReport.
class MachineJumps {
 public:
  /// Sets the evaluation windows of `sys` (DriveSystem::set_evaluation_window) as it arms jumps.
  MachineJumps(const Model& m, DriveSystem& sys);
  /// Number of event functions (two per jumping machine).
  [[nodiscard]] int count() const { return 2 * static_cast<int>(jumpers_.size()); }
  [[nodiscard]] long jumps() const { return jumps_; }

  /// The first sample, at the start; arms the first jumps.
  void start(double t0, const double* y0);
  /// Samples the traced bodies at four points of the piece [ta, tb] of the stepper's last step
  /// (inline: most runs trace none).
  void on_segment(const Stepper& s, double ta, double tb) {
    if (!traces_.empty()) sample_piece(s, ta, tb);
  }
  /// Whether on_segment() samples anything (a machine with jumps or a reported point speed).
  [[nodiscard]] bool samples_pieces() const { return !traces_.empty(); }
  void event_functions(const double* y, double* g) const;
  /// The jump of event function `which` at t: maps y across it and re-arms.
  void jump(double t, double* y, int which);

  [[nodiscard]] std::vector<MachineRunReport> reports() const;

 private:
  void sample_piece(const Stepper& s, double ta, double tb);
  struct Trace {
    int body = 0;
    std::string name;
    const Machine* machine = nullptr;
    std::vector<double> t, q, v;
    std::vector<double> jump_t, jump_loss;
  };
  struct Jumper {
    int body = 0;
    const Machine* machine = nullptr;
    int trace = -1;  ///< index in traces_
    double up = 0.0, down = 0.0;  ///< the next jump positions above and below q
    int last_dir = 0;             ///< direction of the last jump (0: none yet)
    double last_q = 0.0;          ///< its position: the boundary behind the motion right after it
  };
  void sample(Trace& tr, double t, double q, double v);
  void arm(const double* y);

  DriveSystem& sys_;
  int n_ = 0;
  std::vector<Trace> traces_;
  std::vector<Jumper> jumpers_;
  std::vector<double> y_;  ///< scratch
  long jumps_ = 0;
};

}  // namespace machdyn::detail
