#pragma once
// Velocity jumps of machines (stepwise gears, model/machine.hpp) as events of the smooth chain
// simulation, and the samples of their motion behind MachineRunReport (analysis/simulate.hpp).

#include <string>
#include <vector>

#include "machdyn/analysis/chain_system.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/model/machine.hpp"
#include "machdyn/solve/driver.hpp"
#include "machdyn/solve/event_system.hpp"

namespace machdyn::detail {

/// The chain system with the velocity jumps of its machines as events: for each stepwise gear the
/// next jump positions above and below q are event functions g = q_up − q ≥ 0, g = q − q_down ≥ 0;
/// at a crossing the speed jumps (Machine::velocity_after_jump). Also samples the traced bodies for
/// their MachineRunReport.
class MachineRun final : public EventSystem {
 public:
  /// Sets the evaluation windows of `sys` (ChainSystem::set_evaluation_window) as it arms jumps.
  MachineRun(const Model& m, ChainSystem& sys);
  /// Whether any body has velocity jumps (then simulate() integrates this system, else `sys`).
  [[nodiscard]] bool has_jumps() const { return !jumpers_.empty(); }
  /// Whether there is anything to report (jumps or a point-speed report).
  [[nodiscard]] bool active() const { return !traces_.empty(); }
  [[nodiscard]] long jumps() const { return jumps_; }

  /// Samples the traced bodies at four points of the piece [ta, tb] of the stepper's last step.
  void on_segment(const Stepper& s, double ta, double tb);
  /// The first sample, at the start; arms the first jumps.
  void start(double t0, const double* y0);

  [[nodiscard]] int size() const override { return sys_.size(); }
  void rhs(double t, const double* y, double* dydt) override { sys_.rhs(t, y, dydt); }
  [[nodiscard]] bool has_jacobian() const override { return true; }
  void jacobian(double t, const double* y, Eigen::Ref<Eigen::MatrixXd> J) override { sys_.jacobian(t, y, J); }
  [[nodiscard]] std::string state_name(int i) const override { return sys_.state_name(i); }
  [[nodiscard]] int event_count() const override { return 2 * static_cast<int>(jumpers_.size()); }
  void event_functions(double t, const double* y, double* g) override;
  [[nodiscard]] std::vector<double> breakpoints(double t0, double t_end) const override {
    return sys_.breakpoints(t0, t_end);
  }
  bool handle_events(double t, double* y, const std::vector<int>& fired) override;

  [[nodiscard]] std::vector<MachineRunReport> reports() const;

 private:
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
  void arm(double t, const double* y);

  ChainSystem& sys_;
  int n_ = 0;
  std::vector<Trace> traces_;
  std::vector<Jumper> jumpers_;
  std::vector<double> y_;  ///< scratch, size 2n
  long jumps_ = 0;
};

}  // namespace machdyn::detail
