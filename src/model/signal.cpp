#include "machdyn/model/signal.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>
#include <utility>
#include <fmt/format.h>

#include "machdyn/common/expression.hpp"

namespace machdyn {

Signal Signal::constant(double c) {
  Signal s;
  s.a_ = c;
  return s;
}

Signal Signal::step(double before, double after, double t0) {
  Signal s;
  s.kind_ = Kind::step, s.a_ = before, s.b_ = after, s.t0_ = t0;
  return s;
}

Signal Signal::ramp(double before, double after, double t0, double t1) {
  if (!(t1 > t0)) throw std::invalid_argument("a ramp must end after it starts");
  Signal s;
  s.kind_ = Kind::ramp, s.a_ = before, s.b_ = after, s.t0_ = t0, s.t1_ = t1;
  return s;
}

Signal Signal::table(std::vector<double> times, std::vector<double> values, bool extrapolate) {
  if (times.empty() || times.size() != values.size())
    throw std::invalid_argument("a table needs as many values as times, at least one");
  for (std::size_t k = 1; k < times.size(); ++k) {
    if (times[k] < times[k - 1]) throw std::invalid_argument("the times of a table must not decrease");
    if (k >= 2 && times[k] == times[k - 2]) throw std::invalid_argument("at most two points of a table at one time");
  }
  const std::size_t n = times.size();
  if (extrapolate && (n < 2 || times[1] == times[0] || times[n - 1] == times[n - 2]))
    throw std::invalid_argument("extrapolating a table needs a first and a last segment of positive length");
  Signal s;
  s.kind_ = Kind::table, s.x_ = std::move(times), s.y_ = std::move(values), s.extrapolate_ = extrapolate;
  return s;
}

Signal Signal::sine(double amplitude, double omega, double phase, double offset, double start) {
  Signal s;
  s.kind_ = Kind::sine, s.a_ = amplitude, s.b_ = omega, s.c_ = phase, s.d_ = offset, s.t0_ = start;
  return s;
}

Signal Signal::pulse(double low, double high, double period, double width, double start, long count) {
  if (!(period > 0.0) || !(width > 0.0) || !(width < period))
    throw std::invalid_argument("a pulse needs a period > 0 and a width between 0 and the period");
  Signal s;
  s.kind_ = Kind::pulse, s.a_ = low, s.b_ = high, s.c_ = period, s.d_ = width, s.t0_ = start, s.count_ = count;
  return s;
}

Signal Signal::expression(std::shared_ptr<const Expression> f) {
  Signal s;
  s.kind_ = Kind::expression, s.f_ = std::move(f);
  return s;
}

Signal Signal::sum(std::vector<Signal> terms) {
  Signal s;
  s.kind_ = Kind::sum, s.terms_ = std::move(terms);
  return s;
}

namespace {

/// The period index k of t for a pulse: start + kP ≤ t < start + (k+1)P, with the edges computed
/// as breakpoints() computes them (so that at an edge the value is the one after it).
long pulse_period(double t, double start, double period) {
  // A period index beyond any count (a 1e-300 s period over seconds) must not overflow the cast.
  const double f = std::floor((t - start) / period);
  if (!(f < 1e15)) return 1'000'000'000'000'000L;
  if (!(f > -1e15)) return -1'000'000'000'000'000L;
  auto k = static_cast<long>(f);
  if (t >= start + static_cast<double>(k + 1) * period) ++k;
  if (t < start + static_cast<double>(k) * period) --k;
  return k;
}

}  // namespace

const char* Signal::kind_name(Kind k) {
  switch (k) {
    case Kind::constant: return "constant";
    case Kind::step: return "step";
    case Kind::ramp: return "ramp";
    case Kind::table: return "table";
    case Kind::sine: return "sine";
    case Kind::pulse: return "pulse";
    case Kind::expression: return "expression";
    case Kind::sum: return "sum";
  }
  return "?";
}

double Signal::value(double t) const {
  switch (kind_) {
    case Kind::constant: return a_;
    case Kind::step: return t < t0_ ? a_ : b_;
    case Kind::ramp:
      if (t <= t0_) return a_;
      if (t >= t1_) return b_;
      return a_ + (b_ - a_) * (t - t0_) / (t1_ - t0_);
    case Kind::table: {
      const std::size_t n = x_.size();
      if (n == 1) return y_[0];
      if (t < x_.front())
        return extrapolate_ ? y_[0] + (y_[1] - y_[0]) * (t - x_[0]) / (x_[1] - x_[0]) : y_.front();
      if (t >= x_.back())
        return extrapolate_ ? y_[n - 1] + (y_[n - 1] - y_[n - 2]) * (t - x_[n - 1]) / (x_[n - 1] - x_[n - 2])
                            : y_.back();
      // x[k-1] ≤ t < x[k]: at a jump (two equal times) the second point is x[k-1], the value after it.
      const auto k = static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), t) - x_.begin());
      return y_[k - 1] + (y_[k] - y_[k - 1]) * (t - x_[k - 1]) / (x_[k] - x_[k - 1]);
    }
    case Kind::sine: return t < t0_ ? d_ : d_ + a_ * std::sin(b_ * (t - t0_) + c_);
    case Kind::pulse: {
      if (t < t0_) return a_;
      const long k = pulse_period(t, t0_, c_);
      if (count_ >= 0 && k >= count_) return a_;
      return t < t0_ + static_cast<double>(k) * c_ + d_ ? b_ : a_;
    }
    case Kind::expression: return (*f_)(t);
    case Kind::sum: {
      double s = 0.0;
      for (const Signal& term : terms_) s += term.value(t);
      return s;
    }
  }
  return 0.0;
}

double Signal::slope(double t) const {
  switch (kind_) {
    case Kind::ramp: return t >= t0_ && t < t1_ ? (b_ - a_) / (t1_ - t0_) : 0.0;
    case Kind::table: {
      const std::size_t n = x_.size();
      if (n == 1) return 0.0;
      if (t < x_.front()) return extrapolate_ ? (y_[1] - y_[0]) / (x_[1] - x_[0]) : 0.0;
      if (t >= x_.back()) return extrapolate_ ? (y_[n - 1] - y_[n - 2]) / (x_[n - 1] - x_[n - 2]) : 0.0;
      const auto k = static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), t) - x_.begin());
      return (y_[k] - y_[k - 1]) / (x_[k] - x_[k - 1]);
    }
    case Kind::sine: return t < t0_ ? 0.0 : a_ * b_ * std::cos(b_ * (t - t0_) + c_);
    case Kind::expression: return f_->eval(Jet::variable(t)).d;
    case Kind::sum: {
      double s = 0.0;
      for (const Signal& term : terms_) s += term.slope(t);
      return s;
    }
    case Kind::constant:
    case Kind::step:
    case Kind::pulse: return 0.0;
  }
  return 0.0;
}

double Signal::curvature(double t) const {
  switch (kind_) {
    case Kind::sine: return t < t0_ ? 0.0 : -a_ * b_ * b_ * std::sin(b_ * (t - t0_) + c_);
    case Kind::expression: return f_->eval(Jet::variable(t)).dd;
    case Kind::sum: {
      double s = 0.0;
      for (const Signal& term : terms_) s += term.curvature(t);
      return s;
    }
    case Kind::constant:
    case Kind::step:
    case Kind::ramp:
    case Kind::table:
    case Kind::pulse: return 0.0;  // piecewise linear
  }
  return 0.0;
}

std::vector<double> Signal::breakpoints(double t0, double t1) const {
  std::vector<double> out;
  auto add = [&](double t) {
    if (t > t0 && t < t1) out.push_back(t);
  };
  switch (kind_) {
    case Kind::step: add(t0_); break;
    case Kind::ramp: add(t0_), add(t1_); break;
    case Kind::table:
      for (double t : x_) add(t);
      break;
    case Kind::sine: add(t0_); break;
    case Kind::pulse: {
      // The first period that can hold an edge after t0; edges as value() places them.
      long k = t0 <= t0_ ? 0 : std::max(0L, pulse_period(t0, t0_, c_));
      for (; count_ < 0 || k < count_; ++k) {
        const double rise = t0_ + static_cast<double>(k) * c_;
        if (rise >= t1) break;
        add(rise), add(rise + d_);
      }
      break;
    }
    case Kind::sum:
      for (const Signal& term : terms_) {
        auto b = term.breakpoints(t0, t1);
        out.insert(out.end(), b.begin(), b.end());
      }
      break;
    case Kind::expression: out = f_->switch_points(0, t0, t1); break;  // its switches (step, min, ...)
    case Kind::constant: break;
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

double Signal::breakpoint_count(double t0, double t1) const {
  switch (kind_) {
    case Kind::table: return static_cast<double>(x_.size());
    case Kind::pulse: {
      if (t1 <= t0_) return 0.0;
      double periods = std::ceil((t1 - std::max(t0, t0_)) / c_) + 1.0;
      if (count_ >= 0) periods = std::min(periods, static_cast<double>(count_));
      return 2.0 * periods;
    }
    case Kind::sum: {
      double n = 0.0;
      for (const Signal& term : terms_) n += term.breakpoint_count(t0, t1);
      return n;
    }
    default: return static_cast<double>(breakpoints(t0, t1).size());
  }
}

std::vector<double> Signal::crossings(double level, double t0, double t1) const {
  std::vector<double> out;
  auto add = [&](double t) {
    if (t > t0 && t < t1) out.push_back(t);
  };
  // A crossing of the segment from (xa, ya) to (xb, yb), both ends excluded (they are breakpoints).
  auto segment = [&](double xa, double ya, double xb, double yb) {
    if (xb > xa && (ya - level) * (yb - level) < 0.0) add(xa + (level - ya) * (xb - xa) / (yb - ya));
  };
  switch (kind_) {
    case Kind::ramp: segment(t0_, a_, t1_, b_); break;
    case Kind::table: {
      const std::size_t n = x_.size();
      for (std::size_t k = 1; k < n; ++k) segment(x_[k - 1], y_[k - 1], x_[k], y_[k]);
      if (extrapolate_ && n >= 2) {  // the first and last segments continued outside the table
        const double s0 = (y_[1] - y_[0]) / (x_[1] - x_[0]), s1 = (y_[n - 1] - y_[n - 2]) / (x_[n - 1] - x_[n - 2]);
        if (s0 != 0.0 && (y_[0] - level) * s0 > 0.0) add(x_[0] + (level - y_[0]) / s0);
        if (s1 != 0.0 && (level - y_[n - 1]) * s1 > 0.0) add(x_[n - 1] + (level - y_[n - 1]) / s1);
      }
      break;
    }
    case Kind::sine: {
      // d + A sin(θ) = level, θ = ω (t − t_s) + φ: θ = asin(r) + 2πk or π − asin(r) + 2πk, r = (level − d)/A;
      // |r| ≥ 1 only touches (no change of sign).
      if (a_ == 0.0 || b_ <= 0.0) break;
      const double r = (level - d_) / a_;
      if (!(std::abs(r) < 1.0)) break;
      const double lo = std::max(t0, t0_), two_pi = 2.0 * std::acos(-1.0);
      if (lo >= t1) break;
      const double th0 = b_ * (lo - t0_) + c_, th1 = b_ * (t1 - t0_) + c_, base[2] = {std::asin(r), two_pi / 2 - std::asin(r)};
      for (double b : base)
        for (double k = std::floor((th0 - b) / two_pi); b + k * two_pi <= th1; k += 1.0) {
          const double th = b + k * two_pi;
          if (th > th0) add(t0_ + (th - c_) / b_);
        }
      break;
    }
    case Kind::expression:
    case Kind::sum: {
      std::vector<double> nodes = breakpoints(t0, t1);
      constexpr int kSamples = 4096;
      for (int i = 0; i <= kSamples; ++i) nodes.push_back(t0 + (t1 - t0) * i / kSamples);
      std::sort(nodes.begin(), nodes.end());
      for (std::size_t i = 1; i < nodes.size(); ++i) {
        double a = nodes[i - 1], b = nodes[i];
        // Inside (a, b): the left value just after a (a jump at a is not a crossing), the right
        // value just before b.
        const double fa = value(a) - level, fb = value(std::nextafter(b, a)) - level;
        if (!(b > a) || !(fa * fb < 0.0)) continue;
        for (int it = 0; it < 200 && std::nextafter(a, b) < b; ++it) {
          const double mid = 0.5 * (a + b);
          if ((value(mid) - level) * fa > 0.0) a = mid;
          else b = mid;
        }
        add(b);
      }
      break;
    }
    case Kind::constant:
    case Kind::step:
    case Kind::pulse: break;
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

double Signal::magnitude_bound(double t0, double t1) const {
  switch (kind_) {
    case Kind::constant: return std::abs(a_);
    case Kind::step:
    case Kind::ramp:
    case Kind::pulse: return std::max(std::abs(a_), std::abs(b_));
    case Kind::table: {
      double m = 0.0;
      for (double y : y_) m = std::max(m, std::abs(y));
      if (extrapolate_) m = std::max({m, std::abs(value(t0)), std::abs(value(t1))});
      return m;
    }
    case Kind::sine: return std::abs(d_) + std::abs(a_);
    case Kind::expression: {
      double m = 0.0;
      for (int i = 0; i <= 1000; ++i) m = std::max(m, std::abs(value(t0 + (t1 - t0) * i / 1000.0)));
      return m;
    }
    case Kind::sum: {
      double m = 0.0;
      for (const Signal& term : terms_) m += term.magnitude_bound(t0, t1);
      return m;
    }
  }
  return 0.0;
}

std::vector<double> Signal::levels() const {
  std::vector<double> v;
  switch (kind_) {
    case Kind::constant: v = {a_}; break;
    case Kind::step: v = {a_, b_}; break;
    case Kind::ramp:
      if (a_ == b_) v = {a_};
      break;
    case Kind::pulse: v = count_ == 0 ? std::vector<double>{a_} : std::vector<double>{a_, b_}; break;
    case Kind::table: {
      for (std::size_t k = 1; k < x_.size(); ++k)
        if (x_[k] > x_[k - 1] && y_[k] != y_[k - 1]) return {};  // a sloped segment
      if (extrapolate_ && x_.size() >= 2 && (y_[1] != y_[0] || y_.back() != y_[y_.size() - 2])) return {};
      v = y_;
      break;
    }
    case Kind::sum: {
      v = {0.0};
      for (const Signal& term : terms_) {
        const auto l = term.levels();
        if (l.empty() || v.size() * l.size() > 4096) return {};
        std::vector<double> next;
        for (double a : v)
          for (double b : l) next.push_back(a + b);
        std::sort(next.begin(), next.end());
        next.erase(std::unique(next.begin(), next.end()), next.end());
        v = std::move(next);
      }
      break;
    }
    case Kind::sine:
      if (a_ == 0.0) v = {d_};
      break;
    case Kind::expression: break;
  }
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
  return v;
}

bool Signal::is_constant() const { return levels().size() == 1; }

std::string Signal::describe(const std::string& unit) const {
  const std::string u = unit.empty() ? "" : " " + unit;  // "5 N" or "5" for a dimensionless signal
  switch (kind_) {
    case Kind::constant: return fmt::format("{:g}{}", a_, u);
    case Kind::step: return fmt::format("step {:g}{} → {:g}{} at t = {:g} s", a_, u, b_, u, t0_);
    case Kind::ramp:
      return fmt::format("{:g}{} until t0 = {:g} s, linear to {:g}{} at t1 = {:g} s", a_, u, t0_, b_, u, t1_);
    case Kind::table: {
      std::string s = fmt::format("piecewise linear ({}, t [s], [{}]):", extrapolate_ ? "extrapolated" : "held",
                                  unit.empty() ? "1" : unit);
      for (std::size_t k = 0; k < x_.size() && k < 8; ++k) s += fmt::format(" ({:g}, {:g})", x_[k], y_[k]);
      if (x_.size() > 8) s += fmt::format(" … {} points", x_.size());
      return s;
    }
    case Kind::sine:
      return fmt::format("{:g} + {:g} sin({:g} rad/s (t − {:g} s) + {:g} rad){}", d_, a_, b_, t0_, c_, u);
    case Kind::pulse:
      return fmt::format("pulses {:g} → {:g}{}, period {:g} s, width {:g} s, from {:g} s{}", a_, b_, u, c_, d_, t0_,
                         count_ >= 0 ? fmt::format(", {} times", count_) : std::string());
    case Kind::expression: return fmt::format("f(t) = {}{}", f_->text(), unit.empty() ? "" : " [" + unit + "]");
    case Kind::sum: {
      std::string s;
      for (const Signal& term : terms_) s += fmt::format("{}({})", s.empty() ? "" : " + ", term.describe(unit));
      return s;
    }
  }
  return "";
}

}  // namespace machdyn
