#pragma once
/// @file
/// Tracks the extremes of signals s_j(y) (link loads) on the continuous solution: an interior
/// extremum of a step is where the rate s_j' changes sign, located by the Illinois method on the
/// stepper's dense output. One dense derivative per step serves all signals, so the cost per step
/// is O(n + the signals' own cost).
///
/// An interior extremum that cannot be a new extreme is not located: a signal whose rate reads only
/// the derivative is affine in the state, so on a step it is a polynomial of degree ≤ 6 in t (the
/// dense output, solve/stepper.hpp), and the Bernstein coefficients of that polynomial on the piece
/// (from seven samples) bound it. Inside the extremes so far by a margin, nothing the tracker
/// reports could change, and the located value would be thrown away. A stepper whose dense output
/// has a lower degree d (dopri5: 4) is bounded from d + 1 samples (set_dense_degree).

#include <algorithm>
#include <functional>
#include <vector>

#include "machdyn/solve/stepper.hpp"

namespace machdyn {

/// The signals a PeakTracker follows: their values and rates from the state and its derivative.
class PeakSignals {
 public:
  virtual ~PeakSignals() = default;
  [[nodiscard]] virtual int count() const = 0;
  /// s_j at state y.
  [[nodiscard]] virtual double value(int j, const double* y) const = 0;
  /// ds_j/dt at state y with derivative dy.
  [[nodiscard]] virtual double rate(int j, const double* y, const double* dy) const = 0;
  /// Whether rate(j, …) reads y. False says the rate is linear in dy alone, so s_j is affine in the
  /// state: the tracker then skips interpolating y and bounds s_j by its dense-output polynomial.
  [[nodiscard]] virtual bool rate_reads_state(int /*j*/) const { return false; }
  /// All values s_j(y) into out and all rates into rate_out (count() each): one call per step
  /// instead of one per signal and quantity (the per-step path of the tracker). The default loops
  /// over value() and rate(); a system overrides it to keep its loop free of virtual calls.
  virtual void values_and_rates(const double* y, const double* dy, double* out, double* rate_out) const {
    for (int j = 0; j < count(); ++j) out[j] = value(j, y), rate_out[j] = rate(j, y, dy);
  }
};

/// The nonzero weights of a signal s = Σ_k w[k] y[idx[k]].
struct SparseWeights {
  std::vector<int> idx;
  std::vector<double> w;
};

/// Signals linear in the state, s_j = w_jᵀ y (rate w_jᵀ y').
class LinearSignals final : public PeakSignals {
 public:
  explicit LinearSignals(std::vector<SparseWeights> weights) : w_(std::move(weights)) {}
  [[nodiscard]] int count() const override { return static_cast<int>(w_.size()); }
  [[nodiscard]] double value(int j, const double* y) const override { return dot(j, y); }
  [[nodiscard]] double rate(int j, const double*, const double* dy) const override { return dot(j, dy); }

 private:
  [[nodiscard]] double dot(int j, const double* y) const {
    const SparseWeights& s = w_[static_cast<size_t>(j)];
    double v = 0;
    for (size_t k = 0; k < s.idx.size(); ++k) v += s.w[k] * y[s.idx[k]];
    return v;
  }
  std::vector<SparseWeights> w_;
};

class PeakTracker {
 public:
  /// Follows every signal of `signals` (kept by reference) over a state of `state_size`.
  PeakTracker(int state_size, const PeakSignals& signals);
  /// Called when signal j reaches a new maximum (is_max) or minimum at time t with state y.
  using NewMax = std::function<void(int j, bool is_max, double t, const double* y)>;
  /// The solution on [ta, tb] ⊂ [s.t_prev(), s.t()] (a driver piece, solve/driver.hpp). A piece
  /// that starts where the last one ended continues it (its start was seen, its rate is known).
  void on_segment(const Stepper& s, double ta, double tb, const NewMax& on_new_max);
  /// After an event or a restart: the next piece starts afresh (the state or the rate may jump).
  void restart() { last_end_ = -1.0; }
  /// The degree of the stepper's dense output in t, 4 (dopri5) or 6 (the default: any stepper of
  /// solve/stepper.hpp); other values throw std::invalid_argument.
  void set_dense_degree(int degree);
  [[nodiscard]] double max(int j) const { return sig_[static_cast<size_t>(j)].max; }
  [[nodiscard]] double min(int j) const { return sig_[static_cast<size_t>(j)].min; }
  [[nodiscard]] double t_max(int j) const { return sig_[static_cast<size_t>(j)].t_max; }
  [[nodiscard]] double t_min(int j) const { return sig_[static_cast<size_t>(j)].t_min; }
  /// Whether any value was seen (a run of zero length has none).
  [[nodiscard]] bool started() const { return started_; }

  /// The load history for cycle counting (analysis/load_history.hpp): when set, every value the
  /// tracker takes is handed to `every(j, t, s_j)` in time order — the start of each fresh piece,
  /// every interior extremum (then located on every piece, none skipped by the bounds), the end of
  /// each piece. A superset of the signal's turning points; unset (the default) it costs nothing.
  using EveryValue = std::function<void(int j, double t, double v)>;
  void set_every_value(EveryValue every) { every_ = std::move(every); }

  /// The extremes of every signal over a window of time (a slip phase): from open_window(t) on,
  /// every value the tracker takes (the ends of pieces, their located interior extrema) enters the
  /// open windows too, until close_window. A window that saw no value has max −∞, min +∞ and
  /// t_max = its opening time.
  struct Window {
    std::vector<double> max, t_max, min;  // per signal
  };
  /// Opens a window at t; returns its handle (valid until close_window).
  int open_window(double t);
  /// The window's extremes so far.
  [[nodiscard]] const Window& window(int w) const { return windows_[static_cast<size_t>(w)]; }
  /// Closes window w (its handle may be handed out again).
  void close_window(int w);

 private:
  struct Extremes {
    double rate_prev = 0.0, value_prev = 0.0, max = 0.0, min = 0.0, t_max = 0.0, t_min = 0.0;
  };
  void consider(int j, double t, const double* y, const NewMax& on_new_max);
  /// Inline: most values are no new extreme of the run (and no window is open).
  void consider_value(int j, double t, double v, const double* y, const NewMax& on_new_max) {
    if (every_) every_(j, t, v);
    const Extremes& g = sig_[static_cast<size_t>(j)];
    if (!(started_ && v <= g.max && v >= g.min)) new_value(j, t, v, y, on_new_max);
    for (const int w : open_) {
      Window& W = windows_[static_cast<size_t>(w)];
      const auto i = static_cast<size_t>(j);
      if (v > W.max[i]) W.max[i] = v, W.t_max[i] = t;
      W.min[i] = std::min(W.min[i], v);
    }
  }
  void new_value(int j, double t, double v, const double* y, const NewMax& on_new_max);
  /// A piece that does not continue the last: the state, values and rates at its start ta.
  void start_piece(const Stepper& s, double ta, const NewMax& on_new_max);
  /// A piece that ends inside its step: the state (returned) and its derivative (db_) at tb.
  const double* piece_end(const Stepper& s, double tb);
  /// Signal j's rate changes sign on [ta, tb] (r1, v1 at tb): its interior extremum, located where
  /// it could be a new extreme (inside_extremes).
  void interior(const Stepper& s, int j, double ta, double tb, double r1, double v1, const NewMax& on_new_max);
  double locate_extremum(const Stepper& s, int j, double t0, double r0, double t1, double r1);
  /// Whether signal j on the piece [ta, tb] (values v0, v1 at its ends) stays inside its extremes
  /// so far, and inside those of every open window, by a margin: then its interior extremum need
  /// not be located (it could change nothing the tracker reports).
  bool inside_extremes(const Stepper& s, int j, double ta, double tb, double v0, double v1);
  /// Whether [lo, hi] lies inside signal j's extremes so far and inside every open window's.
  [[nodiscard]] bool inside_so_far(int j, double lo, double hi) const;
  const PeakSignals& signals_;
  int count_;                  // signals_.count()
  std::vector<Extremes> sig_;
  bool started_ = false;
  double last_end_ = -1.0;  // end of the last piece when it ended its step, else −1
  std::vector<double> y_, dy_, yb_, db_, ym_;
  int degree_ = 6;                // of the dense output: degree_ + 1 samples bound a signal on a piece
  std::vector<double> samples_;  // the state at the piece's interior sample times (inside_extremes)
  bool sampled_ = false;         // samples_ holds the current piece's
  std::vector<double> vals_, rates_;  // the signals' values and rates at the end of a piece
  std::vector<Window> windows_;      // by handle, open or free
  std::vector<int> open_, free_;     // the open windows' handles; closed handles to reuse
  EveryValue every_;                 // set_every_value: the load history's sink, or empty
};

}  // namespace machdyn
