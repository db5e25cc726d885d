#include "machdyn/analysis/peak_tracker.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include <Eigen/LU>

#include "machdyn/solve/roots.hpp"

namespace machdyn {
namespace {

constexpr int kDegree = 6;  // bounds the dense output's degree (solve/stepper.hpp)

/// The map from a polynomial's values at u_k = k/D (k = 0…D) to its Bernstein coefficients on
/// [0, 1]: the inverse of B_kl = C(D, l) u_k^l (1 − u_k)^(D−l).
template <int D>
const Eigen::Matrix<double, D + 1, D + 1>& bernstein_from_samples() {
  using SampleMap = Eigen::Matrix<double, D + 1, D + 1>;
  static const SampleMap T = [] {
    SampleMap B;
    for (int k = 0; k <= D; ++k)
      for (int l = 0; l <= D; ++l) {
        const double u = static_cast<double>(k) / D;
        double binom = 1;
        for (int i = 1; i <= l; ++i) binom = binom * (D - l + i) / i;
        B(k, l) = binom * std::pow(u, l) * std::pow(1.0 - u, D - l);
      }
    return SampleMap(B.inverse());
  }();
  return T;
}

/// The bounds [lo, hi] of the degree-D polynomial with values v(k) at u_k = k/D and the largest
/// |v(k)| (the scale of the margin).
template <int D>
void bernstein_bounds(const Eigen::Matrix<double, D + 1, 1>& v, double& lo, double& hi, double& scale) {
  const Eigen::Matrix<double, D + 1, 1> b = bernstein_from_samples<D>() * v;
  lo = b.minCoeff(), hi = b.maxCoeff(), scale = v.cwiseAbs().maxCoeff();
}

}  // namespace

PeakTracker::PeakTracker(int state_size, const PeakSignals& signals)
    : signals_(signals), count_(signals.count()), sig_(static_cast<size_t>(count_)), y_(static_cast<size_t>(state_size)),
      dy_(static_cast<size_t>(state_size)), samples_(static_cast<size_t>((kDegree - 1) * state_size)), vals_(static_cast<size_t>(signals.count())),
      rates_(static_cast<size_t>(signals.count())) {}

void PeakTracker::consider(int j, double t, const double* y, const NewMax& on_new_max) {
  consider_value(j, t, signals_.value(j, y), y, on_new_max);
}

int PeakTracker::open_window(double t) {
  int w;
  if (!free_.empty()) {
    w = free_.back();
    free_.pop_back();
  } else {
    w = static_cast<int>(windows_.size());
    windows_.emplace_back();
  }
  Window& W = windows_[static_cast<size_t>(w)];
  const size_t n = sig_.size();
  W.max.assign(n, -std::numeric_limits<double>::infinity());
  W.t_max.assign(n, t);
  W.min.assign(n, std::numeric_limits<double>::infinity());
  open_.push_back(w);
  return w;
}

void PeakTracker::close_window(int w) {
  const auto it = std::find(open_.begin(), open_.end(), w);
  if (it == open_.end()) return;
  open_.erase(it);
  free_.push_back(w);
}

void PeakTracker::new_value(int j, double t, double v, const double* y, const NewMax& on_new_max) {
  Extremes& g = sig_[static_cast<size_t>(j)];
  if (!started_ || v > g.max) {
    g.max = v, g.t_max = t;
    if (on_new_max) on_new_max(j, true, t, y);
  }
  if (!started_ || v < g.min) {
    g.min = v, g.t_min = t;
    if (on_new_max) on_new_max(j, false, t, y);
  }
}

double PeakTracker::locate_extremum(const Stepper& s, int j, double t0, double r0, double t1, double r1) {
  // dy_ is free here: the end-of-step derivative comes from s.dydt().
  const bool state = signals_.rate_reads_state(j);
  if (state) ym_.resize(y_.size());
  const Bracket br = illinois(
      [&](double t) {
        s.derivative(t, dy_.data());
        if (state) s.interpolate(t, ym_.data());
        return signals_.rate(j, ym_.data(), dy_.data());
      },
      t0, r0, t1, r1, 1e-15 * std::max(1.0, std::abs(t1)), 100, /*bisect_every=*/0);  // a smooth rate
  return 0.5 * (br.lo + br.hi);
}

void PeakTracker::set_dense_degree(int degree) {
  if (degree != 4 && degree != kDegree) throw std::invalid_argument("PeakTracker: dense-output degree 4 or 6");
  degree_ = degree;
  sampled_ = false;
}

bool PeakTracker::inside_extremes(const Stepper& s, int j, double ta, double tb, double v0, double v1) {
  if (!started_ || signals_.rate_reads_state(j)) return false;  // not affine in the state: no bound
  // The ends alone: the bound below contains them and its margin is at least this one, so an end
  // outside some extremes fails it too — without sampling (a window just opened has none).
  const double end_margin = 1e-6 * std::max(std::abs(v0), std::abs(v1));
  if (!inside_so_far(j, std::min(v0, v1) - end_margin, std::max(v0, v1) + end_margin)) return false;
  const size_t n = y_.size();
  const int D = degree_;
  if (!sampled_) {  // one set of samples serves every signal of the piece
    for (int k = 1; k < D; ++k)
      s.interpolate(ta + (tb - ta) * k / D, samples_.data() + static_cast<size_t>(k - 1) * n);
    sampled_ = true;
  }
  double lo, hi, scale;
  if (D == 4) {
    Eigen::Matrix<double, 5, 1> v;
    v(0) = v0, v(4) = v1;
    for (int k = 1; k < 4; ++k) v(k) = signals_.value(j, samples_.data() + static_cast<size_t>(k - 1) * n);
    bernstein_bounds<4>(v, lo, hi, scale);
  } else {
    Eigen::Matrix<double, kDegree + 1, 1> v;
    v(0) = v0, v(kDegree) = v1;
    for (int k = 1; k < kDegree; ++k) v(k) = signals_.value(j, samples_.data() + static_cast<size_t>(k - 1) * n);
    bernstein_bounds<kDegree>(v, lo, hi, scale);
  }
  // The margin covers the rounding of the samples, of the coefficients and of a located value.
  const double margin = 1e-6 * scale;
  return inside_so_far(j, lo - margin, hi + margin);
}

bool PeakTracker::inside_so_far(int j, double lo, double hi) const {
  const auto i = static_cast<size_t>(j);
  if (!(hi <= sig_[i].max && lo >= sig_[i].min)) return false;
  for (const int w : open_) {
    const Window& W = windows_[static_cast<size_t>(w)];
    if (!(hi <= W.max[i] && lo >= W.min[i])) return false;
  }
  return true;
}

void PeakTracker::start_piece(const Stepper& s, double ta, const NewMax& on_new_max) {
  s.interpolate(ta, y_.data());
  s.derivative(ta, dy_.data());
  for (int j = 0; j < count_; ++j) {
    Extremes& g = sig_[static_cast<size_t>(j)];
    g.rate_prev = signals_.rate(j, y_.data(), dy_.data());
    g.value_prev = signals_.value(j, y_.data());
    consider_value(j, ta, g.value_prev, y_.data(), on_new_max);
  }
  started_ = true;
}

const double* PeakTracker::piece_end(const Stepper& s, double tb) {
  yb_.resize(y_.size());
  db_.resize(y_.size());
  s.interpolate(tb, yb_.data());
  s.derivative(tb, db_.data());
  return yb_.data();
}

void PeakTracker::interior(const Stepper& s, int j, double ta, double tb, double r1, double v1,
                           const NewMax& on_new_max) {
  const Extremes& g = sig_[static_cast<size_t>(j)];
  if (!every_ && inside_extremes(s, j, ta, tb, g.value_prev, v1)) return;
  const double te = locate_extremum(s, j, ta, g.rate_prev, tb, r1);
  s.interpolate(te, y_.data());
  consider(j, te, y_.data(), on_new_max);
}

void PeakTracker::on_segment(const Stepper& s, double ta, double tb, const NewMax& on_new_max) {
  const int n = count_;
  if (n == 0) return;  // a model without links has nothing to track
  if (ta != last_end_) start_piece(s, ta, on_new_max);  // a fresh start: the state and the rates at ta
  const bool step_end = tb == s.t();  // read once: t() is virtual
  const double* y1 = step_end ? s.y() : piece_end(s, tb);
  const double* dy1 = step_end ? s.dydt() : db_.data();
  signals_.values_and_rates(y1, dy1, vals_.data(), rates_.data());
  sampled_ = false;
  for (int j = 0; j < n; ++j) {
    Extremes& g = sig_[static_cast<size_t>(j)];
    const double r1 = rates_[static_cast<size_t>(j)], v1 = vals_[static_cast<size_t>(j)];
    // The rate changes sign: an interior extremum (out of line: a few steps in ten).
    if ((g.rate_prev > 0 && r1 < 0) || (g.rate_prev < 0 && r1 > 0)) [[unlikely]]
      interior(s, j, ta, tb, r1, v1, on_new_max);
    consider_value(j, tb, v1, y1, on_new_max);
    g.rate_prev = r1, g.value_prev = v1;
  }
  last_end_ = step_end ? tb : -1.0;
}

}  // namespace machdyn
