#include "machdyn/gears/synthesis.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
#include <numbers>

namespace machdyn::gears {

namespace {

[[noreturn]] void fail(const Location& at, const std::string& msg) { throw InputError(at, "gears: " + msg); }

/// Wheel split: returns Δφ_1..Δφ_n (eqs. 21–31).
std::vector<double> split_wheel(const GearModel& m, GearSynthesis& out, std::vector<double>& rH_law) {
  const int n = m.n;
  const double T = m.T(), tol = m.tolerance;
  std::vector<double> d(static_cast<std::size_t>(n));
  rH_law.assign(static_cast<std::size_t>(n), 0.0);
  double d1 = T / n;  // eq. 27
  double relax = 0.5, prev = std::numeric_limits<double>::infinity();
  for (int cycle = 1; cycle <= m.max_iterations; ++cycle) {
    double phi = 0.5 * T;  // eq. 21
    d[0] = d1;
    rH_law[0] = m.rH(phi - 0.5 * d1);
    const double arc = rH_law[0] * d1;
    double sum = d1;
    for (std::size_t j = 1; j < d.size(); ++j) {
      phi -= d[j - 1];  // eqs. 22–23
      double x = d[j - 1];
      bool converged = false;
      for (int it = 0; it < 100 && !converged; ++it) {  // eq. 25: Δφ_j = r_H1 Δφ_1 / r_H(φ_j − Δφ_j/2)
        const double nx = arc / m.rH(phi - 0.5 * x);
        converged = std::abs(nx - x) <= 1e-3 * tol;
        x = nx;
        if (!std::isfinite(x) || x <= 0.0) break;
      }
      if (!converged) {  // steep law: the fixed point oscillates; bisect g(x) = x r_H(φ − x/2) − l instead
        auto g = [&](double y) { return y * m.rH(phi - 0.5 * y) - arc; };
        double lo = 0.0, hi = d[j - 1];
        for (int k = 0; g(hi) < 0.0; ++k) {
          hi *= 2.0;
          if (k > 60) fail(m.where.law, fmt::format("wheel sector {}: no angle gives the arc of sector 1", j + 1));
        }
        for (int k = 0; k < 200 && hi - lo > 1e-3 * tol; ++k) {
          const double mid = 0.5 * (lo + hi);
          (g(mid) < 0.0 ? lo : hi) = mid;
        }
        x = 0.5 * (lo + hi);
      }
      d[j] = x;
      rH_law[j] = m.rH(phi - 0.5 * x);
      sum += x;
    }
    const double defect = T - sum;  // eq. 28
    out.wheel_cycles = cycle;
    out.wheel_defect = defect;
    if (std::abs(defect) <= tol) return d;  // eq. 31
    if (std::abs(defect) >= std::abs(prev)) relax *= 0.5;
    prev = defect;
    d1 += relax * defect / n;  // eqs. 29–30
    if (d1 <= 0.0) d1 = 0.5 * (d1 - relax * defect / n);
  }
  fail(m.where.law, fmt::format("the wheel split did not converge in {} cycles (defect {:.3g} rad); raise "
                                "max_iterations or the tolerance", m.max_iterations, out.wheel_defect));
}

/// Pinion split: returns Δθ_1..Δθ_n (eqs. 39–51).
std::vector<double> split_pinion(const GearModel& m, const std::vector<double>& dphi, GearSynthesis& out) {
  const int n = m.n;
  const double Theta = m.Theta(), tol = m.tolerance;
  const double d1 = dphi[0], dmin = *std::min_element(dphi.begin(), dphi.end());
  // C = Δφ_1Δθ_1/(Δφ_1 + Δθ_1) must stay below min Δφ_j; Δθ_1 below this bound:
  const double bound = d1 > dmin ? dmin * d1 / (d1 - dmin) : std::numeric_limits<double>::infinity();
  std::vector<double> t(dphi.size());
  double t1 = std::min(Theta / n, 0.5 * bound);  // eq. 48
  double relax = 0.5, prev = std::numeric_limits<double>::infinity();
  for (int cycle = 1; cycle <= m.max_iterations; ++cycle) {
    const double C = d1 * t1 / (d1 + t1);
    double sum = 0.0;
    for (std::size_t j = 0; j < dphi.size(); ++j) {  // eqs. 39–40
      t[j] = C * dphi[j] / (dphi[j] - C);
      sum += t[j];
    }
    const double defect = Theta - sum;  // eq. 49
    out.pinion_cycles = cycle;
    out.pinion_defect = defect;
    if (std::abs(defect) <= tol) return t;  // eq. 51
    if (std::abs(defect) >= std::abs(prev)) relax *= 0.5;
    prev = defect;
    double next = t1 + relax * defect / n;  // eq. 50
    if (next >= bound) next = 0.5 * (t1 + bound);
    if (next <= 0.0) next = 0.5 * t1;
    t1 = next;
  }
  fail(m.where.law, fmt::format("the pinion split did not converge in {} cycles (defect {:.3g} rad)",
                                m.max_iterations, out.pinion_defect));
}

}  // namespace

GearSynthesis synthesize(const GearModel& m) {
  GearSynthesis s;
  std::vector<double> rH_law;
  const std::vector<double> dphi = split_wheel(m, s, rH_law);
  const std::vector<double> dtheta = split_pinion(m, dphi, s);

  const double T = m.T();
  double phi = 0.5 * T, theta = m.law.theta(0.5 * T);
  s.closure = m.law.theta(0.5 * T) - m.law.theta(-0.5 * T) - m.Theta();
  const double C = dphi[0] * dtheta[0] / (dphi[0] + dtheta[0]);
  s.arc = m.L * C;
  s.module = s.arc / std::numbers::pi;
  for (std::size_t j = 0; j < dphi.size(); ++j) {
    Sector row;
    row.i = static_cast<int>(j) + 1;
    row.phi = phi;
    row.dphi = dphi[j];
    row.theta = theta;
    row.dtheta = dtheta[j];
    row.rH = m.L * dtheta[j] / (dphi[j] + dtheta[j]);  // eqs. 41–42
    row.r = m.L - row.rH;                              // eqs. 43–44
    row.rH_law = rH_law[j];
    s.eq52_deviation = std::max({s.eq52_deviation, std::abs(row.rH * row.dphi - s.arc) / s.arc,
                                 std::abs(row.r * row.dtheta - s.arc) / s.arc});
    s.sectors.push_back(row);
    phi -= dphi[j];
    theta -= dtheta[j];  // eqs. 45–47
  }

  // feasibility of the teeth
  const double rmin =
      std::min_element(s.sectors.begin(), s.sectors.end(), [](auto& x, auto& y) { return x.r < y.r; })->r;
  const double hf = m.profile.dedendum * s.module;
  if (rmin - hf <= 0.0)
    fail(m.where.z, fmt::format("the pinion is too small for its teeth: smallest pitch radius {:.4g} mm, tooth "
                                "depth below the pitch curve {:.4g} mm (module {:.4g} mm); use fewer teeth or a "
                                "ratio law with a smaller range", rmin * 1e3, hf * 1e3, s.module * 1e3));
  const double gap = m.L_installed - m.L;
  if (gap >= m.profile.addendum * s.module)
    fail(m.where.L_installed, fmt::format("the installation distance exceeds the calculation distance by {:.4g} mm, "
                                          "not less than the addendum {:.4g} mm (module {:.4g} mm): the teeth "
                                          "would barely or not engage", gap * 1e3,
                                          m.profile.addendum * s.module * 1e3, s.module * 1e3));
  return s;
}

double stepwise_ratio(const GearModel& m, const GearSynthesis& s, double phi) {
  const double pw = m.law.wrap(phi);
  for (const auto& row : s.sectors)
    if (pw >= row.phi - row.dphi) return row.dtheta / row.dphi;
  return s.sectors.back().dtheta / s.sectors.back().dphi;
}

SpeedUniformity speed_uniformity(const GearModel& m, const GearSynthesis& s) {
  SpeedUniformity u;
  if (!m.law.has_travel()) return u;
  u.available = true;
  u.omega = m.pinion_speed;
  const double T = m.T();
  const int K = 200 * m.n;
  // X_T = ∫ dX/dφ over the big sector (Simpson, K even)
  double X = 0.0;
  for (int q = 0; q <= K; ++q) {
    const double w = (q == 0 || q == K) ? 1.0 : (q % 2 ? 4.0 : 2.0);
    X += w * m.law.travel(-0.5 * T + T * q / K);
  }
  X *= T / K / 3.0;
  u.mean = u.omega * X / m.Theta();
  const double i_circ = static_cast<double>(m.zH) / m.z;
  double cmin = 1e300, cmax = -1e300, smin = 1e300, smax = -1e300, qmin = 1e300, qmax = -1e300;
  for (int q = 0; q <= K; ++q) {  // continuous law and circular gears, ends included
    const double phi = -0.5 * T + T * q / K;
    const double tr = m.law.travel(phi) * u.omega;
    const double vc = tr / m.law.ratio(phi).v, vq = tr / i_circ;
    cmin = std::min(cmin, vc), cmax = std::max(cmax, vc);
    qmin = std::min(qmin, vq), qmax = std::max(qmax, vq);
  }
  for (const auto& row : s.sectors) {  // stepwise: constant i_j over each closed sector
    const double ij = row.dtheta / row.dphi;
    for (int q = 0; q <= 200; ++q) {
      const double vs = m.law.travel(row.phi - row.dphi * q / 200.0) * u.omega / ij;
      smin = std::min(smin, vs), smax = std::max(smax, vs);
    }
  }
  u.continuous_min = cmin, u.continuous_max = cmax, u.continuous_delta = (cmax - cmin) / u.mean;
  u.stepwise_min = smin, u.stepwise_max = smax, u.stepwise_delta = (smax - smin) / u.mean;
  u.circular_delta = (qmax - qmin) / u.mean;
  return u;
}

PitchCurves sample_pitch_curves(const GearModel& m, int per) {
  PitchCurves c;
  const double T = m.T(), Theta = m.Theta();
  const int nw = per * m.N;
  for (int q = 0; q <= nw; ++q) {
    const double phi = -std::numbers::pi + 2.0 * std::numbers::pi * q / nw;
    const double r = m.rH(phi), beta = -phi;
    c.wheel_x.push_back(r * std::cos(beta));
    c.wheel_y.push_back(r * std::sin(beta));
  }
  const int big_pinion = static_cast<int>(std::lround(2.0 * std::numbers::pi / Theta));
  const int np = per * big_pinion;
  for (int q = 0; q <= np; ++q) {
    const double th = -std::numbers::pi + 2.0 * std::numbers::pi * q / np;
    const double phi = m.law.phi_of_theta(th);
    const double r = m.r(phi), beta = std::numbers::pi + th;
    c.pinion_x.push_back(r * std::cos(beta));
    c.pinion_y.push_back(r * std::sin(beta));
  }
  (void)T;
  return c;
}

}  // namespace machdyn::gears
