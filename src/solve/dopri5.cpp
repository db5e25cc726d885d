#include "dopri5.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <fmt/format.h>

#include "machdyn/common/diagnostics.hpp"
#include <memory>

namespace machdyn {
namespace {
// Butcher tableau of Dormand–Prince 5(4).
constexpr double c2 = 1.0 / 5, c3 = 3.0 / 10, c4 = 4.0 / 5, c5 = 8.0 / 9;
constexpr double a21 = 1.0 / 5;
constexpr double a31 = 3.0 / 40, a32 = 9.0 / 40;
constexpr double a41 = 44.0 / 45, a42 = -56.0 / 15, a43 = 32.0 / 9;
constexpr double a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561, a54 = -212.0 / 729;
constexpr double a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247, a64 = 49.0 / 176,
                 a65 = -5103.0 / 18656;
constexpr double a71 = 35.0 / 384, a73 = 500.0 / 1113, a74 = 125.0 / 192, a75 = -2187.0 / 6784,
                 a76 = 11.0 / 84;
// Error estimate y5 − y4.
constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                 e6 = 22.0 / 525, e7 = -1.0 / 40;
// Continuous extension (Hairer's dopri5, CONTD5).
constexpr double d1 = -12715105075.0 / 11282082432, d3 = 87487479700.0 / 32700410799,
                 d4 = -10690763975.0 / 1880347072, d5 = 701980252875.0 / 199316789632,
                 d6 = -1453857185.0 / 822651844, d7 = 69997945.0 / 29380423;
// Step-size control (Hairer): safety, bounds of the factor, PI exponent β.
constexpr double safe = 0.9, facc1 = 5.0, facc2 = 0.1, beta = 0.04, expo1 = 0.2 - beta * 0.75;
constexpr double uround = std::numeric_limits<double>::epsilon();
}  // namespace

template <int N>
Dopri5<N>::Dopri5(OdeSystem& system, const StepperOptions& options)
    : sys_(system), opt_(options), n_(system.size()) {
  if constexpr (N == 0) {
    for (auto* v : {&y_, &y1_, &k1_, &k2_, &k3_, &k4_, &k5_, &k6_, &k7_, &ytmp_, &err_, &r1_, &r2_, &r3_,
                    &r4_, &r5_})
      v->assign(static_cast<size_t>(n_), 0.0);
  }
}

template <int N>
void Dopri5<N>::fail(const char* what, int component) const {
  throw SolverError(component >= 0 ? sys_.state_name(component) : "integrator", t_, what);
}

template <int N>
void Dopri5<N>::reset(double t0, const double* y0) {
  t_ = t_old_ = t0;
  std::copy(y0, y0 + n(), y_.begin());
  sys_.rhs(t_, y_.data(), k1_.data());
  ++stats_.rhs_evals;
  for (int i = 0; i < n(); ++i)
    if (!std::isfinite(k1_[static_cast<size_t>(i)])) fail("the right-hand side is not finite at the start", i);
  r1_ = y_;
  h_old_ = 0.0;
  std::fill(r2_.begin(), r2_.end(), 0.0);
  std::fill(r3_.begin(), r3_.end(), 0.0);
  std::fill(r4_.begin(), r4_.end(), 0.0);
  std::fill(r5_.begin(), r5_.end(), 0.0);
  h_ = initial_step();
  facold_ = 1e-4;
  last_rejected_ = false;
}

template <int N>
double Dopri5<N>::initial_step() {
  // Hairer's HINIT: an explicit Euler step of size h0 estimates the second derivative.
  const size_t n = static_cast<size_t>(this->n());
  double dnf = 0, dny = 0;
  for (size_t i = 0; i < n; ++i) {
    double sk = opt_.atol + opt_.rtol * std::abs(y_[i]);
    dnf += (k1_[i] / sk) * (k1_[i] / sk);
    dny += (y_[i] / sk) * (y_[i] / sk);
  }
  // Never below what the step loop resolves at t (it fails at 0.1 h ≤ |t| uround): a state at rest near
  // the origin (|y| ~ 1e-17 against atol 1e-12, the rounding left on bodies held by stuck contacts) made
  // ‖y‖/‖f‖ ~ 1e-18 at a breakaway at t = 0.12 s, and the run ended with "step size too small" before its
  // first step (issue 27, class F: it depended on the rounding before the event, so a breakpoint later
  // in the run decided it). The error control takes the step from there.
  const double h_min = 100.0 * std::abs(t_) * uround;
  double h = (dnf <= 1e-10 || dny <= 1e-10) ? 1e-6 : std::max(std::sqrt(dny / dnf) * 0.01, h_min);
  if (opt_.h_max > 0) h = std::min(h, opt_.h_max);
  for (size_t i = 0; i < n; ++i) ytmp_[i] = y_[i] + h * k1_[i];
  sys_.rhs(t_ + h, ytmp_.data(), k2_.data());
  ++stats_.rhs_evals;
  double der2 = 0;
  for (size_t i = 0; i < n; ++i) {
    double sk = opt_.atol + opt_.rtol * std::abs(y_[i]);
    double d = (k2_[i] - k1_[i]) / sk;
    der2 += d * d;
  }
  der2 = std::sqrt(der2) / h;
  double der12 = std::max(std::abs(der2), std::sqrt(dnf));
  double h1 = der12 <= 1e-15 ? std::max(1e-6, h * 1e-3) : std::pow(0.01 / der12, 0.2);
  h = std::max(std::min(100 * h, h1), h_min);
  if (opt_.h_max > 0) h = std::min(h, opt_.h_max);
  return h;
}

template <int N>
void Dopri5<N>::step(double t_limit) {
  const size_t n = static_cast<size_t>(this->n());
  double* y = y_.data();
  // The component with the largest error of the last attempt: what holds the step size down.
  auto worst_component = [&] {
    int worst = -1;
    double worst_v = -1;
    for (size_t i = 0; i < n; ++i)
      if (!(std::abs(err_[i]) <= worst_v)) worst_v = std::abs(err_[i]), worst = static_cast<int>(i);
    return worst;
  };
  for (;;) {
    if (stats_.steps + stats_.rejected >= opt_.max_steps) {
      // Name the part that held the steps short (a stiff DC motor's current), not "integrator".
      const int worst = stats_.steps + stats_.rejected > 0 ? worst_component() : -1;
      fail(fmt::format("the maximum number of steps was reached (step size {:.3g} s, held down by this state; "
                       "if it is a fast, strongly damped part, try integrator: bdf)", h_).c_str(), worst);
    }
    if (0.1 * std::abs(h_) <= std::abs(t_) * uround || h_ <= 0.0)
      fail("the step size became too small (the solution is singular or very stiff there)", worst_component());
    double h = h_;
    bool last = false;
    if (t_ + 1.01 * h >= t_limit) {
      h = t_limit - t_;
      last = true;
    }
    for (size_t i = 0; i < n; ++i) ytmp_[i] = y[i] + h * a21 * k1_[i];
    sys_.rhs(t_ + c2 * h, ytmp_.data(), k2_.data());
    for (size_t i = 0; i < n; ++i) ytmp_[i] = y[i] + h * (a31 * k1_[i] + a32 * k2_[i]);
    sys_.rhs(t_ + c3 * h, ytmp_.data(), k3_.data());
    for (size_t i = 0; i < n; ++i) ytmp_[i] = y[i] + h * (a41 * k1_[i] + a42 * k2_[i] + a43 * k3_[i]);
    sys_.rhs(t_ + c4 * h, ytmp_.data(), k4_.data());
    for (size_t i = 0; i < n; ++i)
      ytmp_[i] = y[i] + h * (a51 * k1_[i] + a52 * k2_[i] + a53 * k3_[i] + a54 * k4_[i]);
    sys_.rhs(t_ + c5 * h, ytmp_.data(), k5_.data());
    for (size_t i = 0; i < n; ++i)
      ytmp_[i] = y[i] + h * (a61 * k1_[i] + a62 * k2_[i] + a63 * k3_[i] + a64 * k4_[i] + a65 * k5_[i]);
    sys_.rhs(t_ + h, ytmp_.data(), k6_.data());
    for (size_t i = 0; i < n; ++i)
      y1_[i] = y[i] + h * (a71 * k1_[i] + a73 * k3_[i] + a74 * k4_[i] + a75 * k5_[i] + a76 * k6_[i]);
    sys_.rhs(t_ + h, y1_.data(), k7_.data());
    stats_.rhs_evals += 6;

    double err = 0;
    for (size_t i = 0; i < n; ++i) {
      err_[i] = h * (e1 * k1_[i] + e3 * k3_[i] + e4 * k4_[i] + e5 * k5_[i] + e6 * k6_[i] + e7 * k7_[i]);
      double sk = opt_.atol + opt_.rtol * std::max(std::abs(y[i]), std::abs(y1_[i]));
      double r = err_[i] / sk;
      err += r * r;
    }
    err = std::sqrt(err / static_cast<double>(n));
    if (!std::isfinite(err)) {  // f blew up inside the step: shrink hard and retry
      for (size_t i = 0; i < n; ++i)
        if (!std::isfinite(y1_[i]) || !std::isfinite(k7_[i])) err_[i] = std::numeric_limits<double>::max();
      ++stats_.rejected;
      h_ = h * facc2;
      last_rejected_ = true;
      continue;
    }
    double fac11 = std::pow(err, expo1);
    double fac = fac11 / std::pow(facold_, beta);
    fac = std::max(facc2, std::min(facc1, fac / safe));
    double h_new = h / fac;
    if (err <= 1.0) {
      facold_ = std::max(err, 1e-4);
      for (size_t i = 0; i < n; ++i) {
        double ydiff = y1_[i] - y[i];
        double bspl = h * k1_[i] - ydiff;
        r1_[i] = y[i];
        r2_[i] = ydiff;
        r3_[i] = bspl;
        r4_[i] = ydiff - h * k7_[i] - bspl;
        r5_[i] = h * (d1 * k1_[i] + d3 * k3_[i] + d4 * k4_[i] + d5 * k5_[i] + d6 * k6_[i] + d7 * k7_[i]);
      }
      std::swap(k1_, k7_);
      std::swap(y_, y1_);
      t_old_ = t_;
      h_old_ = h;
      t_ = last ? t_limit : t_ + h;
      ++stats_.steps;
      if (opt_.h_max > 0) h_new = std::min(h_new, opt_.h_max);
      if (last_rejected_) h_new = std::min(h_new, h);
      // A step cut short by t_limit says nothing about the natural step size.
      h_ = last ? std::max(h_new, h_) : h_new;
      last_rejected_ = false;
      return;
    }
    ++stats_.rejected;
    h_ = h / std::min(facc1, fac11 / safe);
    last_rejected_ = true;
  }
}

template <int N>
void Dopri5<N>::interpolate(double t, double* y_out) const {
  if (h_old_ == 0.0) {
    std::copy(y_.begin(), y_.end(), y_out);
    return;
  }
  const double th = (t - t_old_) / h_old_, th1 = 1.0 - th;
  for (int i = 0; i < n(); ++i) {
    size_t k = static_cast<size_t>(i);
    y_out[i] = r1_[k] + th * (r2_[k] + th1 * (r3_[k] + th * (r4_[k] + th1 * r5_[k])));
  }
}

}  // namespace machdyn

namespace machdyn {

template <int N>
void Dopri5<N>::derivative(double t, double* dy_out) const {
  if (h_old_ == 0.0) {
    std::copy(k1_.begin(), k1_.end(), dy_out);
    return;
  }
  // d/dθ of r1 + θ r2 + θ(1−θ) r3 + θ²(1−θ) r4 + θ²(1−θ)² r5, divided by h.
  const double th = (t - t_old_) / h_old_, th1 = 1.0 - th;
  const double inv_h = 1.0 / h_old_;
  const double g3 = (1.0 - 2.0 * th) * inv_h, g4 = th * (2.0 - 3.0 * th) * inv_h,
               g5 = 2.0 * th * th1 * (1.0 - 2.0 * th) * inv_h;
  for (int i = 0; i < n(); ++i) {
    size_t k = static_cast<size_t>(i);
    dy_out[i] = r2_[k] * inv_h + g3 * r3_[k] + g4 * r4_[k] + g5 * r5_[k];
  }
}

}  // namespace machdyn

namespace machdyn {

// Explicit instantiations: the general size and the fixed sizes make_dopri5() picks.
template class Dopri5<0>;
template class Dopri5<1>;
template class Dopri5<2>;
template class Dopri5<3>;
template class Dopri5<4>;
template class Dopri5<5>;
template class Dopri5<6>;
template class Dopri5<7>;
template class Dopri5<8>;
template class Dopri5<9>;
template class Dopri5<10>;
template class Dopri5<11>;
template class Dopri5<12>;
template class Dopri5<13>;
template class Dopri5<14>;
template class Dopri5<15>;
template class Dopri5<16>;

namespace {
template <int... Ns>
std::unique_ptr<Stepper> make_fixed(int n, OdeSystem& system, const StepperOptions& options,
                                    std::integer_sequence<int, Ns...>) {
  std::unique_ptr<Stepper> s;
  ((n == Ns + 1 ? (s = std::make_unique<Dopri5<Ns + 1>>(system, options), 0) : 0), ...);
  return s;
}
}  // namespace

std::unique_ptr<Stepper> make_dopri5(OdeSystem& system, const StepperOptions& options) {
  // Fixed sizes up to 16 states: an 8-body chain, or a hybrid model with its energy states.
  auto s = make_fixed(system.size(), system, options, std::make_integer_sequence<int, 16>{});
  return s ? std::move(s) : std::make_unique<Dopri5<0>>(system, options);
}

}  // namespace machdyn
