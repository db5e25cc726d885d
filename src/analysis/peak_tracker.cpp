#include "machdyn/analysis/peak_tracker.hpp"

#include <cmath>

#include "machdyn/solve/roots.hpp"

namespace machdyn {

PeakTracker::PeakTracker(int state_size, const std::vector<SparseWeights>& weights)
    : y_(static_cast<size_t>(state_size)), dy_(static_cast<size_t>(state_size)) {
  for (const auto& w : weights) {
    Signal g;
    for (size_t i = 0; i < w.idx.size(); ++i)
      if (w.w[i] != 0.0) g.idx.push_back(w.idx[i]), g.w.push_back(w.w[i]);
    sig_.push_back(std::move(g));
  }
}

double PeakTracker::Signal::dot(const double* y) const {
  double s = 0;
  for (size_t k = 0; k < idx.size(); ++k) s += w[k] * y[idx[k]];
  return s;
}

void PeakTracker::consider(int j, double t, const double* y, const NewMax& on_new_max) {
  Signal& g = sig_[static_cast<size_t>(j)];
  const double v = g.dot(y);
  if (!started_ || v > g.max) {
    g.max = v, g.t_max = t;
    if (on_new_max) on_new_max(j, true, t, y);
  }
  if (!started_ || v < g.min) {
    g.min = v, g.t_min = t;
    if (on_new_max) on_new_max(j, false, t, y);
  }
}

double PeakTracker::locate_extremum(const Stepper& s, const Signal& g, double t0, double r0, double t1, double r1) {
  // dy_ is free here: the end-of-step derivative comes from s.dydt().
  const Bracket br = illinois(
      [&](double t) {
        s.derivative(t, dy_.data());
        return g.dot(dy_.data());
      },
      t0, r0, t1, r1, 1e-15 * std::max(1.0, std::abs(t1)), 100, /*bisect_every=*/0);  // a smooth rate
  return 0.5 * (br.lo + br.hi);
}

void PeakTracker::on_segment(const Stepper& s, double ta, double tb, const NewMax& on_new_max) {
  const int n = static_cast<int>(sig_.size());
  if (n == 0) return;  // a model without links has nothing to track
  if (ta != last_end_) {  // a fresh start: the state and the rates at ta
    s.interpolate(ta, y_.data());
    s.derivative(ta, dy_.data());
    for (int j = 0; j < n; ++j) {
      sig_[static_cast<size_t>(j)].rate_prev = sig_[static_cast<size_t>(j)].dot(dy_.data());
      consider(j, ta, y_.data(), on_new_max);
    }
    started_ = true;
  }
  const double* y1 = s.y();
  const double* dy1 = s.dydt();
  std::vector<double>& yb = yb_;
  if (tb != s.t()) {
    yb.resize(y_.size());
    db_.resize(y_.size());
    s.interpolate(tb, yb.data());
    s.derivative(tb, db_.data());
    y1 = yb.data(), dy1 = db_.data();
  }
  for (int j = 0; j < n; ++j) {
    Signal& g = sig_[static_cast<size_t>(j)];
    const double r1 = g.dot(dy1);
    if ((g.rate_prev > 0 && r1 < 0) || (g.rate_prev < 0 && r1 > 0)) {
      const double te = locate_extremum(s, g, ta, g.rate_prev, tb, r1);
      s.interpolate(te, y_.data());
      consider(j, te, y_.data(), on_new_max);
    }
    consider(j, tb, y1, on_new_max);
    g.rate_prev = r1;
  }
  last_end_ = tb == s.t() ? tb : -1.0;
}

}  // namespace machdyn
