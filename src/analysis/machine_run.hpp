#pragma once
// Velocity jumps of machines (stepwise gears, model/machine.hpp) as events of the smooth chain
// simulation, and the samples of their motion behind MachineRunReport (analysis/simulate.hpp).

#include <string>
#include <vector>

#include "machdyn/analysis/chain_system.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/model/machine.hpp"
#include "machdyn/solve/driver.hpp"

namespace machdyn::detail {

class MachineRun final : public StepEvents {
 public:
  /// Sets the evaluation windows of `sys` (ChainSystem::set_evaluation_window) as it arms jumps.
  MachineRun(const Model& m, ChainSystem& sys);
  /// Whether any body has velocity jumps (then simulate() passes this object to integrate()).
  [[nodiscard]] bool has_jumps() const { return !jumpers_.empty(); }
  /// Whether there is anything to report (jumps or a point-speed report).
  [[nodiscard]] bool active() const { return !traces_.empty(); }
  [[nodiscard]] long jumps() const { return jumps_; }

  /// Samples the traced bodies at four points of the stepper's last step (its end included).
  void on_step(const Stepper& s);
  /// The first sample, at the start.
  void start(double t0, const double* y0);

  void arm(double t, const double* y) override;
  double locate(const Stepper& s) override;
  void apply(double t, double* y) override;

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

  ChainSystem& sys_;
  int n_ = 0;
  std::vector<Trace> traces_;
  std::vector<Jumper> jumpers_;
  std::vector<double> y_;  ///< scratch, size 2n
  // The event found by locate(), applied by apply().
  int pending_ = -1, pending_dir_ = 0;
  double pending_q_ = 0.0;
  long jumps_ = 0;
};

}  // namespace machdyn::detail
