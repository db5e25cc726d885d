#include "machdyn/model/machine.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Dense>

namespace machdyn {

void Machine::inertia(double q, double* I, double* dI) const {
  *I = *dI = 0.0;
  for (int k = 0; k < parts(); ++k) {
    double Ik = 0, dIk = 0;
    part_inertia(k, q, &Ik, &dIk);
    *I += Ik;
    *dI += dIk;
  }
}

// ---------------------------------------------------------------------------------------------
// Tables

namespace {
/// x reduced into [x0, x0 + P).
double wrap(double x, double x0, double P) {
  double t = std::fmod(x - x0, P);
  if (t < 0) t += P;
  return x0 + t;
}
}  // namespace

double LinearTable::operator()(double xq) const {
  if (x.size() == 1) return y[0];
  if (period > 0.0) {
    // Periodic: the table covers [x0, x0 + P]; the segment from the last point to x0 + P joins
    // the last value to the first.
    xq = wrap(xq, x.front(), period);
    if (xq >= x.back()) {
      const double span = x.front() + period - x.back();
      return span > 0 ? y.back() + (y.front() - y.back()) * (xq - x.back()) / span : y.back();
    }
  }
  if (xq <= x.front()) return y.front();
  if (xq >= x.back()) return y.back();
  const auto it = std::upper_bound(x.begin(), x.end(), xq);
  const size_t k = static_cast<size_t>(it - x.begin());
  const double w = (xq - x[k - 1]) / (x[k] - x[k - 1]);
  return y[k - 1] + w * (y[k] - y[k - 1]);
}

CubicSpline::CubicSpline(std::vector<double> x, std::vector<double> y, bool periodic)
    : x_(std::move(x)), y_(std::move(y)), periodic_(periodic) {
  const int n = static_cast<int>(x_.size()) - 1;  // intervals
  m_.assign(x_.size(), 0.0);
  if (n < 1) return;
  auto h = [&](int j) { return x_[static_cast<size_t>(j + 1)] - x_[static_cast<size_t>(j)]; };
  auto yv = [&](int j) { return y_[static_cast<size_t>(j)]; };
  // Continuity of y′ at knot j: h_{j−1}/6 M_{j−1} + (h_{j−1}+h_j)/3 M_j + h_j/6 M_{j+1}
  //                             = (y_{j+1}−y_j)/h_j − (y_j−y_{j−1})/h_{j−1}.
  if (periodic_) {
    // Unknowns M_0..M_{n−1}, M_n = M_0; knot 0 borrows interval n−1 from the previous period.
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n, n);
    Eigen::VectorXd b(n);
    for (int j = 0; j < n; ++j) {
      const int jm = (j + n - 1) % n, jp = (j + 1) % n;
      const double hm = h(jm), hj = h(j);
      A(j, jm) += hm / 6;
      A(j, j) += (hm + hj) / 3;
      A(j, jp) += hj / 6;
      const double ym = j == 0 ? yv(n - 1) : yv(j - 1);
      b(j) = (yv(j + 1) - yv(j)) / hj - (yv(j) - ym) / hm;
    }
    const Eigen::VectorXd M = A.partialPivLu().solve(b);
    for (int j = 0; j < n; ++j) m_[static_cast<size_t>(j)] = M(j);
    m_[static_cast<size_t>(n)] = M(0);
  } else {
    // Clamped with y′ = 0 at both ends.
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + 1, n + 1);
    Eigen::VectorXd b(n + 1);
    A(0, 0) = h(0) / 3;
    A(0, 1) = h(0) / 6;
    b(0) = (yv(1) - yv(0)) / h(0);
    for (int j = 1; j < n; ++j) {
      A(j, j - 1) = h(j - 1) / 6;
      A(j, j) = (h(j - 1) + h(j)) / 3;
      A(j, j + 1) = h(j) / 6;
      b(j) = (yv(j + 1) - yv(j)) / h(j) - (yv(j) - yv(j - 1)) / h(j - 1);
    }
    A(n, n - 1) = h(n - 1) / 6;
    A(n, n) = h(n - 1) / 3;
    b(n) = -(yv(n) - yv(n - 1)) / h(n - 1);
    const Eigen::VectorXd M = A.partialPivLu().solve(b);
    for (int j = 0; j <= n; ++j) m_[static_cast<size_t>(j)] = M(j);
  }
}

void CubicSpline::evaluate(double xq, double* y, double* dy) const {
  if (x_.size() == 1) {
    *y = y_[0];
    *dy = 0.0;
    return;
  }
  if (periodic_) xq = wrap(xq, x_.front(), x_.back() - x_.front());
  if (!periodic_ && (xq <= x_.front() || xq >= x_.back())) {
    *y = xq <= x_.front() ? y_.front() : y_.back();
    *dy = 0.0;
    return;
  }
  auto it = std::upper_bound(x_.begin(), x_.end(), xq);
  size_t k = std::clamp<size_t>(static_cast<size_t>(it - x_.begin()), 1, x_.size() - 1);
  const double h = x_[k] - x_[k - 1];
  const double A = (x_[k] - xq) / h, B = 1.0 - A;
  *y = A * y_[k - 1] + B * y_[k] + ((A * A * A - A) * m_[k - 1] + (B * B * B - B) * m_[k]) * h * h / 6.0;
  *dy = (y_[k] - y_[k - 1]) / h - (3 * A * A - 1) / 6.0 * h * m_[k - 1] + (3 * B * B - 1) / 6.0 * h * m_[k];
}

// ---------------------------------------------------------------------------------------------
// Crank-slider

CrankSlider::CrankSlider(Params p, ForceAgainst against, LinearTable force)
    : p_(p), against_(against), force_(std::move(force)) {}

std::string CrankSlider::part_name(int k) const {
  static const char* names[] = {"crank", "rod", "piston"};
  return names[k];
}


CrankSlider::Kinematics CrankSlider::kinematics(double q) const {
  Kinematics K;
  const double r = p_.r, l = p_.l, a = p_.a, lam = r / l;
  const double s = std::sin(q), co = std::cos(q);
  K.I[0] = p_.J_c;
  K.dI[0] = 0.0;
  if (p_.approximate) {
    // S = sin φ + (λ/2) sin 2φ ≈ −(dx_B/dφ)/r,  S′ = cos φ + λ cos 2φ;
    // x = r(1 − cos φ) + (λ r/4)(1 − cos 2φ), so x′ = r S exactly.
    const double s2 = 2.0 * s * co, c2 = co * co - s * s;
    const double S = s + 0.5 * lam * s2, dS = co + lam * c2;
    for (int k = 1; k <= 2; ++k) {
      const double mB = k == 1 ? p_.m_rod * a / l : p_.m_p;
      K.I[k] = mB * r * r * S * S + (k == 1 ? p_.m_rod * (1.0 - a / l) * r * r : 0.0);
      K.dI[k] = 2.0 * mB * r * r * S * dS;
    }
    K.x = r * (1 - co) + 0.25 * lam * r * (1 - c2);
    K.dx = r * S;
    K.ddx = r * dS;
    return K;
  }
  // Exact: u = sin ψ = λ sin φ, c = cos ψ; ψ′ = λ cos φ / c, ψ″ = −λ sin φ / c + λ³ sin φ cos²φ / c³;
  // a point at distance d from the crank pin along the rod: P_x′ = −r sin φ − d u ψ′,
  // P_x″ = −r cos φ − d (λ cos φ ψ′ + u ψ″); the rod's centre P_y = r sin φ (1 − a/l).
  const double u = lam * s, c = std::sqrt(1.0 - u * u), dpsi = lam * co / c;
  const double ddpsi = -lam * s / c + lam * lam * lam * s * co * co / (c * c * c);
  auto px = [&](double d, double* d1, double* d2) {
    *d1 = -r * s - d * u * dpsi;
    *d2 = -r * co - d * (lam * co * dpsi + u * ddpsi);
  };
  double gx1, gx2, bx1, bx2;
  px(a, &gx1, &gx2);
  px(l, &bx1, &bx2);
  const double gy1 = r * co * (1.0 - a / l), gy2 = -r * s * (1.0 - a / l);
  K.I[1] = p_.m_rod * (gx1 * gx1 + gy1 * gy1) + p_.J_rod * dpsi * dpsi;
  K.dI[1] = 2.0 * p_.m_rod * (gx1 * gx2 + gy1 * gy2) + 2.0 * p_.J_rod * dpsi * ddpsi;
  K.I[2] = p_.m_p * bx1 * bx1;
  K.dI[2] = 2.0 * p_.m_p * bx1 * bx2;
  K.x = r + l - (r * co + l * c);  // from the outer dead centre
  K.dx = -bx1;
  K.ddx = -bx2;
  return K;
}

void CrankSlider::part_inertia(int k, double q, double* I, double* dI) const {
  const Kinematics K = kinematics(q);
  *I = K.I[k];
  *dI = K.dI[k];
}

void CrankSlider::inertia(double q, double* I, double* dI) const {
  const Kinematics K = kinematics(q);
  *I = K.I[0] + K.I[1] + K.I[2];
  *dI = K.dI[0] + K.dI[1] + K.dI[2];
}

void CrankSlider::point(double q, double* p, double* dp, double* ddp) const {
  const Kinematics K = kinematics(q);
  *p = K.x, *dp = K.dx, *ddp = K.ddx;
}

double CrankSlider::piston_force(double phi, double x) const {
  switch (against_) {
    case ForceAgainst::none: return 0.0;
    case ForceAgainst::angle: return force_(phi);
    case ForceAgainst::position: return force_(x);
  }
  return 0.0;
}

double CrankSlider::piston_force(double phi) const {
  return against_ == ForceAgainst::position ? piston_force(phi, kinematics(phi).x) : piston_force(phi, 0.0);
}

double CrankSlider::force(double q) const {
  if (against_ == ForceAgainst::none) return 0.0;
  const Kinematics K = kinematics(q);
  return piston_force(q, K.x) * K.dx;
}

void CrankSlider::dynamics(double q, double* I, double* dI, double* Q) const {
  const Kinematics K = kinematics(q);
  *I = K.I[0] + K.I[1] + K.I[2];
  *dI = K.dI[0] + K.dI[1] + K.dI[2];
  *Q = against_ == ForceAgainst::none ? 0.0 : piston_force(q, K.x) * K.dx;
}

std::vector<double> CrankSlider::kinks(double q_a, double q_b) const {
  std::vector<double> out;
  if (against_ == ForceAgainst::none || force_.x.empty()) return out;
  const double lo = std::min(q_a, q_b), hi = std::max(q_a, q_b);
  // Angles of the table's points within one period, then repeated over [lo, hi].
  std::vector<double> base;
  if (against_ == ForceAgainst::angle) {
    base = force_.x;
    base.push_back(force_.x.front() + force_.period);
  } else {
    // s(φ) rises monotonically on [0, π] and s(−φ) = s(φ): each table position s_j in (0, 2r) is
    // reached at ±φ_j, found by bisection.
    for (double sj : force_.x) {
      double a = 0, b = std::numbers::pi, p, dp, ddp;
      point(b, &p, &dp, &ddp);
      if (!(sj > 0 && sj < p)) continue;
      for (int it = 0; it < 200 && b - a > 1e-15; ++it) {
        const double c = 0.5 * (a + b);
        point(c, &p, &dp, &ddp);
        (p < sj ? a : b) = c;
      }
      base.push_back(0.5 * (a + b));
      base.push_back(2 * std::numbers::pi - 0.5 * (a + b));
    }
  }
  const double P = period();
  for (double x0 : base) {
    const double k0 = std::floor((lo - x0) / P);
    for (double k = k0; x0 + k * P < hi; k += 1.0) {
      const double x = x0 + k * P;
      if (x > lo && x < hi) out.push_back(x);
    }
  }
  std::sort(out.begin(), out.end());
  return out;
}

double CrankSlider::period() const {
  return against_ == ForceAgainst::angle && force_.period > 0 ? force_.period : 2.0 * std::numbers::pi;
}

// ---------------------------------------------------------------------------------------------
// Rolling wheel

RollingWheel::RollingWheel(Params p) : p_(p) {
  Rt_ = p.scheme == 2 ? p.r1 : p.R1;
  Rr_ = p.scheme == 3 ? p.r1 : p.R1;
}

double RollingWheel::x_of_beta(double b) const {
  return p_.H * (1.0 / std::tan(p_.beta0) - 1.0 / std::tan(b)) +
         (Rt_ - p_.r2) * (1.0 / std::sin(p_.beta0) - 1.0 / std::sin(b));
}

double RollingWheel::beta(double phi) const {
  // x(β) increases from −∞ (β → 0) to +∞ (β → π) since x′(β) = (H + (Rt − r2) cos β)/sin²β > 0.
  const double target = Rr_ * phi;
  double lo = 0.0, hi = std::numbers::pi, b = p_.beta0;
  for (int it = 0; it < 200; ++it) {
    const double f = x_of_beta(b) - target;
    if (f == 0.0) return b;
    (f > 0 ? hi : lo) = b;
    const double sb = std::sin(b);
    const double dx = (p_.H + (Rt_ - p_.r2) * std::cos(b)) / (sb * sb);
    double next = b - f / dx;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - b) <= 1e-16 * std::max(1.0, std::abs(b)) || hi - lo < 1e-16) return next;
    b = next;
  }
  return b;
}

void RollingWheel::inertia_beta(double b, double* I, double* dI_dbeta) const {
  const double gb = g(b);
  *I = p_.m1 * (p_.rho * p_.rho + Rr_ * Rr_) + 0.5 * p_.m2 * gb * gb;
  *dI_dbeta = -p_.m2 * gb * Rr_ * std::sin(b);
}

void RollingWheel::part_inertia(int k, double q, double* I, double* dI) const {
  if (k == 0) {
    *I = p_.m1 * (p_.rho * p_.rho + Rr_ * Rr_);
    *dI = 0.0;
    return;
  }
  const double b = beta(q), sb = std::sin(b), cb = std::cos(b);
  const double gb = g(b);
  const double dbeta = Rr_ * sb * sb / (p_.H + (Rt_ - p_.r2) * cb);  // dβ/dφ
  *I = 0.5 * p_.m2 * gb * gb;
  *dI = -p_.m2 * gb * Rr_ * sb * dbeta;
}

double RollingWheel::force(double q) const { return p_.F * g(beta(q)); }

void RollingWheel::point(double q, double* p, double* dp, double* ddp) const {
  *p = Rr_ * q;
  *dp = Rr_;
  *ddp = 0.0;
}

double RollingWheel::q_of_s(double s, double* dq_ds) const {
  const double sb = std::sin(s);
  *dq_ds = (p_.H + (Rt_ - p_.r2) * std::cos(s)) / (sb * sb) / Rr_;
  return x_of_beta(s) / Rr_;
}

std::optional<double> RollingWheel::s_end() const { return std::numbers::pi; }

// ---------------------------------------------------------------------------------------------
// Table and expression

InertiaTable::InertiaTable(CubicSpline spline, std::optional<Expression> torque)
    : spline_(std::move(spline)), torque_(std::move(torque)) {}

void InertiaTable::part_inertia(int, double q, double* I, double* dI) const { spline_.evaluate(q, I, dI); }

InertiaExpression::InertiaExpression(Expression inertia, std::optional<Expression> torque, double period)
    : inertia_(std::move(inertia)), torque_(std::move(torque)), period_(period) {}

void InertiaExpression::part_inertia(int, double q, double* I, double* dI) const { inertia_.evaluate(q, I, dI); }

LinkDeflection link_deflection(int a, int b, double inv_ratio, const Machine* pa, const Machine* pb, double qa,
                               double qb, double va, double vb) {
  LinkDeflection s{0.0, 0.0, inv_ratio, 1.0};
  double p, dp, ddp;
  if (a >= 0) {
    if (pa) {
      pa->point(qa, &p, &dp, &ddp);
      s.ja = dp * inv_ratio;
      s.delta += p * inv_ratio;
    } else {
      s.delta += qa * inv_ratio;
    }
    s.rate += va * s.ja;
  }
  if (b >= 0) {
    if (pb) {
      pb->point(qb, &p, &dp, &ddp);
      s.jb = dp;
      s.delta -= p;
    } else {
      s.delta -= qb;
    }
    s.rate -= vb * s.jb;
  }
  return s;
}

bool has_velocity_jumps(const Model& m) {
  for (const auto& b : m.bodies)
    if (b.machine && b.machine->has_jumps()) return true;
  return false;
}

}  // namespace machdyn
