#pragma once
/// @file
/// Tracks the extremes of signals s_j = w_jᵀ y that are linear in the state (link loads), on the
/// continuous solution: an interior extremum of a step is where the rate s_j' = w_jᵀ y' changes
/// sign, located by the Illinois method on the stepper's dense output. One dense derivative per
/// step serves all signals, so the cost per step is O(n + nonzeros of the weights).

#include <functional>
#include <vector>

#include "machdyn/solve/stepper.hpp"

namespace machdyn {

/// The nonzero weights of a signal s = Σ_k w[k] y[idx[k]].
struct SparseWeights {
  std::vector<int> idx;
  std::vector<double> w;
};

class PeakTracker {
 public:
  /// One signal per entry of `weights`, over a state of `state_size`.
  PeakTracker(int state_size, const std::vector<SparseWeights>& weights);

  /// Called when signal j reaches a new maximum (is_max) or minimum at time t with state y.
  using NewMax = std::function<void(int j, bool is_max, double t, const double* y)>;
  /// The solution on [ta, tb] ⊂ [s.t_prev(), s.t()] (a driver piece, solve/driver.hpp). A piece
  /// that starts where the last one ended continues it (its start was seen, its rate is known).
  void on_segment(const Stepper& s, double ta, double tb, const NewMax& on_new_max);
  /// After an event or a restart: the next piece starts afresh (the state or the rate may jump).
  void restart() { last_end_ = -1.0; }

  [[nodiscard]] double max(int j) const { return sig_[static_cast<size_t>(j)].max; }
  [[nodiscard]] double min(int j) const { return sig_[static_cast<size_t>(j)].min; }
  [[nodiscard]] double t_max(int j) const { return sig_[static_cast<size_t>(j)].t_max; }
  [[nodiscard]] double t_min(int j) const { return sig_[static_cast<size_t>(j)].t_min; }

 private:
  struct Signal {
    std::vector<int> idx;
    std::vector<double> w;
    double rate_prev = 0.0, max = 0.0, min = 0.0, t_max = 0.0, t_min = 0.0;
    [[nodiscard]] double dot(const double* y) const;
  };
  void consider(int j, double t, const double* y, const NewMax& on_new_max);
  double locate_extremum(const Stepper& s, const Signal& g, double t0, double r0, double t1, double r1);

  std::vector<Signal> sig_;
  bool started_ = false;
  double last_end_ = -1.0;  // end of the last piece when it ended its step, else −1
  std::vector<double> y_, dy_, yb_, db_;
};

}  // namespace machdyn
