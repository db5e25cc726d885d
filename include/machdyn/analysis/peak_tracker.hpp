#pragma once
/// @file
/// Tracks the extremes of a signal s = wᵀ y that is linear in the state (a link load), on the
/// continuous solution: an interior extremum of a step is where the rate s' = wᵀ y' changes sign,
/// located by the Illinois method on the stepper's dense output.

#include <vector>

#include "machdyn/solve/stepper.hpp"

namespace machdyn {

class PeakTracker {
 public:
  explicit PeakTracker(const std::vector<double>& w);
  /// After each accepted step.
  void on_step(const Stepper& s);

  [[nodiscard]] double max() const { return max_; }
  [[nodiscard]] double min() const { return min_; }
  [[nodiscard]] double t_max() const { return t_max_; }
  [[nodiscard]] double t_min() const { return t_min_; }
  /// The state at t_max.
  [[nodiscard]] const std::vector<double>& y_at_max() const { return y_max_; }

 private:
  [[nodiscard]] double dot(const std::vector<double>& y) const;
  void consider(double t, const std::vector<double>& y);
  double locate_extremum(const Stepper& s, double t0, double r0, double t1, double r1);

  std::vector<int> idx_;
  std::vector<double> w_;
  bool started_ = false;
  double rate_prev_ = 0.0;
  double max_ = 0.0, min_ = 0.0, t_max_ = 0.0, t_min_ = 0.0;
  std::vector<double> y_max_, buf_, dbuf_;
};

}  // namespace machdyn
