#include "machdyn/analysis/peak_tracker.hpp"

#include <cmath>

namespace machdyn {

PeakTracker::PeakTracker(const std::vector<double>& w) {
  for (size_t i = 0; i < w.size(); ++i)
    if (w[i] != 0.0) idx_.push_back(static_cast<int>(i)), w_.push_back(w[i]);
  buf_.resize(w.size());
  dbuf_.resize(w.size());
}

double PeakTracker::dot(const std::vector<double>& y) const {
  double s = 0;
  for (size_t k = 0; k < idx_.size(); ++k) s += w_[k] * y[static_cast<size_t>(idx_[k])];
  return s;
}

void PeakTracker::consider(double t, const std::vector<double>& y) {
  const double v = dot(y);
  if (!started_ || v > max_) max_ = v, t_max_ = t, y_max_ = y;
  if (!started_ || v < min_) min_ = v, t_min_ = t;
  started_ = true;
}

double PeakTracker::locate_extremum(const Stepper& s, double t0, double r0, double t1, double r1) {
  // Illinois (modified regula falsi) on the rate; r0 and r1 have opposite signs.
  int side = 0;
  for (int it = 0; it < 100 && t1 - t0 > 1e-15 * std::max(1.0, std::abs(t1)); ++it) {
    double t = (t0 * r1 - t1 * r0) / (r1 - r0);
    if (!(t > t0 && t < t1)) t = 0.5 * (t0 + t1);
    s.derivative(t, dbuf_.data());
    const double r = dot(dbuf_);
    if (r == 0.0) return t;
    if ((r > 0) == (r0 > 0)) {
      t0 = t, r0 = r;
      if (side == -1) r1 *= 0.5;
      side = -1;
    } else {
      t1 = t, r1 = r;
      if (side == 1) r0 *= 0.5;
      side = 1;
    }
  }
  return 0.5 * (t0 + t1);
}

void PeakTracker::on_step(const Stepper& s) {
  const double t0 = s.t_prev(), t1 = s.t();
  if (!started_) {
    s.interpolate(t0, buf_.data());
    consider(t0, buf_);
    s.derivative(t0, dbuf_.data());
    rate_prev_ = dot(dbuf_);
  }
  s.derivative(t1, dbuf_.data());
  const double r1 = dot(dbuf_);
  if ((rate_prev_ > 0 && r1 < 0) || (rate_prev_ < 0 && r1 > 0)) {
    const double te = locate_extremum(s, t0, rate_prev_, t1, r1);
    s.interpolate(te, buf_.data());
    consider(te, buf_);
  }
  buf_.assign(s.y(), s.y() + buf_.size());
  consider(t1, buf_);
  rate_prev_ = r1;
}

}  // namespace machdyn
