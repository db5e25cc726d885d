#include "machdyn/gears/ratio_law.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace machdyn::gears {

// ---- periodic cubic spline ------------------------------------------------------------------------
// With h_k = x_{k+1} − x_k (cyclic, the last one wrapping over the period) and second derivatives M_k,
// continuity of y' at every knot gives the cyclic system
//   h_{k−1} M_{k−1} + 2 (h_{k−1} + h_k) M_k + h_k M_{k+1} = 6 [(y_{k+1} − y_k)/h_k − (y_k − y_{k−1})/h_{k−1}].
PeriodicSpline::PeriodicSpline(std::vector<double> x, std::vector<double> y, double period)
    : x_(std::move(x)), y_(std::move(y)), period_(period) {
  const std::size_t n = x_.size();
  if (n < 3 || y_.size() != n) throw std::invalid_argument("a ratio table needs at least 3 points");
  for (std::size_t k = 1; k < n; ++k)
    if (!(x_[k] > x_[k - 1])) throw std::invalid_argument("the angles of a ratio table must increase");
  if (!(x_.back() - x_.front() < period))
    throw std::invalid_argument("the angles of a ratio table must lie within one big sector (span < 2π/N)");
  auto h = [&](std::size_t k) { return k + 1 < n ? x_[k + 1] - x_[k] : x_[0] + period - x_[n - 1]; };
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(n), static_cast<Eigen::Index>(n));
  Eigen::VectorXd rhs(static_cast<Eigen::Index>(n));
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t km = (k + n - 1) % n, kp = (k + 1) % n;
    const double hm = h(km), hk = h(k);
    const auto K = static_cast<Eigen::Index>(k);
    A(K, static_cast<Eigen::Index>(km)) += hm;
    A(K, K) += 2.0 * (hm + hk);
    A(K, static_cast<Eigen::Index>(kp)) += hk;
    rhs(K) = 6.0 * ((y_[kp] - y_[k]) / hk - (y_[k] - y_[km]) / hm);
  }
  Eigen::VectorXd M = A.partialPivLu().solve(rhs);
  m_.assign(M.data(), M.data() + n);
}

Jet PeriodicSpline::eval(double x) const {
  const std::size_t n = x_.size();
  // bring x into [x0, x0 + period)
  double xx = x - period_ * std::floor((x - x_[0]) / period_);
  std::size_t k = static_cast<std::size_t>(std::upper_bound(x_.begin(), x_.end(), xx) - x_.begin()) - 1;
  const std::size_t kp = (k + 1) % n;
  const double x1 = x_[k] + (k + 1 < n ? x_[k + 1] - x_[k] : x_[0] + period_ - x_[k]);
  const double hk = x1 - x_[k];
  const double A = (x1 - xx) / hk, B = (xx - x_[k]) / hk;
  const double y0 = y_[k], y1 = y_[kp], m0 = m_[k], m1 = m_[kp];
  Jet j;
  j.v = A * y0 + B * y1 + ((A * A * A - A) * m0 + (B * B * B - B) * m1) * hk * hk / 6.0;
  j.d = (y1 - y0) / hk - (3.0 * A * A - 1.0) / 6.0 * hk * m0 + (3.0 * B * B - 1.0) / 6.0 * hk * m1;
  j.dd = A * m0 + B * m1;
  return j;
}

// ---- ratio law ------------------------------------------------------------------------------------
namespace {
// 8-point Gauss–Legendre nodes and weights on [−1, 1].
constexpr std::array<double, 8> kGLx{-0.9602898564975363, -0.7966664774136267, -0.5255324099163290,
                                     -0.1834346424956498, 0.1834346424956498,  0.5255324099163290,
                                     0.7966664774136267,  0.9602898564975363};
constexpr std::array<double, 8> kGLw{0.1012285362903763, 0.2223810344533745, 0.3137066458778873,
                                     0.3626837833783620, 0.3626837833783620, 0.3137066458778873,
                                     0.2223810344533745, 0.1012285362903763};
}  // namespace

RatioLaw RatioLaw::walking(double a, double b, double c, double T, double Theta) {
  RatioLaw L;
  L.kind_ = Kind::Walking;
  L.T_ = T;
  L.Theta_ = Theta;
  L.a_ = a;
  L.b_ = b;
  L.c_ = c;
  L.k_ = 3.0 * b / (a - b + c);
  // ∫_{−T/2}^{T/2} (1 + k cos 2φ) dφ = T + k sin T
  L.u_ = Theta / (T + L.k_ * std::sin(T));
  return L;
}

RatioLaw RatioLaw::travel(Expression travel, double T, double Theta) {
  RatioLaw L;
  L.kind_ = Kind::Travel;
  L.T_ = T;
  L.Theta_ = Theta;
  L.expr_ = std::make_shared<const Expression>(std::move(travel));
  L.u_ = 1.0;
  L.u_ = Theta / L.sector_integral();
  return L;
}

RatioLaw RatioLaw::expression(Expression f, double T, double Theta, bool normalize) {
  RatioLaw L;
  L.kind_ = Kind::Expression;
  L.T_ = T;
  L.Theta_ = Theta;
  L.expr_ = std::make_shared<const Expression>(std::move(f));
  if (normalize) L.u_ = Theta / L.sector_integral();
  return L;
}

RatioLaw RatioLaw::table(PeriodicSpline f, double T, double Theta, bool normalize) {
  RatioLaw L;
  L.kind_ = Kind::Table;
  L.T_ = T;
  L.Theta_ = Theta;
  L.spline_ = std::move(f);
  if (normalize) L.u_ = Theta / L.sector_integral();
  return L;
}

double RatioLaw::wrap(double phi) const {
  const double h = 0.5 * T_;
  if (phi >= -h && phi <= h) return phi;
  return phi - T_ * std::floor((phi + h) / T_);
}

Jet RatioLaw::shape(double p) const {
  switch (kind_) {
    case Kind::Walking: {
      const double c2 = std::cos(2.0 * p), s2 = std::sin(2.0 * p);
      return {1.0 + k_ * c2, -2.0 * k_ * s2, -4.0 * k_ * c2};
    }
    case Kind::Travel:
    case Kind::Expression: return expr_->eval(Jet::variable(p));
    case Kind::Table: return spline_.eval(p);
  }
  return {};
}

Jet RatioLaw::ratio(double phi) const { return u_ * shape(wrap(phi)); }

double RatioLaw::travel(double phi) const {
  const double p = wrap(phi);
  if (kind_ == Kind::Walking) return a_ - b_ + c_ + 3.0 * b_ * std::cos(2.0 * p);
  if (kind_ == Kind::Travel) return (*expr_)(p);
  return 0.0;
}

double RatioLaw::integral_wrapped(double from, double to) const {
  if (from == to) return 0.0;
  if (kind_ == Kind::Walking)  // u ∫ (1 + k cos 2φ) dφ = u [φ + (k/2) sin 2φ]
    return u_ * ((to - from) + 0.5 * k_ * (std::sin(2.0 * to) - std::sin(2.0 * from)));
  double sign = 1.0;
  if (to < from) {
    std::swap(from, to);
    sign = -1.0;
  }
  std::vector<double> cuts{from, to};
  if (kind_ == Kind::Table)  // piecewise cubic: integrate knot to knot (exact with 8-point GL)
    for (double x : spline_.knots())
      for (double xs : {x - T_, x, x + T_})
        if (xs > from && xs < to) cuts.push_back(xs);
  std::sort(cuts.begin(), cuts.end());
  const double panel = T_ / 64.0;
  double sum = 0.0;
  for (std::size_t q = 0; q + 1 < cuts.size(); ++q) {
    const double lo = cuts[q], hi = cuts[q + 1];
    const int np = std::max(1, static_cast<int>(std::ceil((hi - lo) / panel)));
    const double w = (hi - lo) / np;
    for (int p = 0; p < np; ++p) {
      const double mid = lo + (p + 0.5) * w;
      for (std::size_t g = 0; g < kGLx.size(); ++g) sum += kGLw[g] * 0.5 * w * shape(mid + 0.5 * w * kGLx[g]).v;
    }
  }
  return sign * u_ * sum;
}

double RatioLaw::sector_integral() const { return integral_wrapped(-0.5 * T_, 0.5 * T_); }

double RatioLaw::theta(double phi) const {
  const double pw = wrap(phi);
  const double m = std::round((phi - pw) / T_);
  return m * sector_integral() + integral_wrapped(0.0, pw);
}

double RatioLaw::phi_of_theta(double th) const {
  const double S = sector_integral();
  double phi = th * T_ / S;
  for (int it = 0; it < 60; ++it) {
    const double step = (theta(phi) - th) / ratio(phi).v;
    phi -= step;
    if (std::abs(step) < 1e-14) break;
  }
  return phi;
}

}  // namespace machdyn::gears
