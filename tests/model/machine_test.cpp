// Machines with position-dependent reduced inertia (model/machine.hpp): kinematics, dI/dq, the
// crank-slider's approximate formula, splines.
#include "machdyn/model/machine.hpp"

#include <cmath>
#include <memory>
#include <numbers>
#include <gtest/gtest.h>

namespace machdyn {
namespace MACHDYN_UNITY_ID {

constexpr double kPi = std::numbers::pi;

CrankSlider::Params crank(double r, double l, bool approximate = false) {
  CrankSlider::Params p;
  p.r = r;
  p.l = l;
  p.m_rod = 1.2;
  p.a = l / 3;
  p.J_rod = p.m_rod * p.a * (l - p.a);  // two-point-mass equivalent rod
  p.m_p = 1.6;
  p.J_c = 0.08;
  p.approximate = approximate;
  return p;
}

std::vector<std::shared_ptr<const Machine>> all_machines() {
  std::vector<std::shared_ptr<const Machine>> v;
  auto uniform_rod = crank(0.04, 0.16);
  uniform_rod.a = 0.08, uniform_rod.J_rod = 1.2 * 0.16 * 0.16 / 12;  // a uniform bar
  v.push_back(std::make_shared<CrankSlider>(uniform_rod));
  v.push_back(std::make_shared<CrankSlider>(crank(0.04, 0.16, true)));
  for (int scheme : {1, 2, 3}) {
    RollingWheel::Params w;
    w.scheme = scheme, w.R1 = 0.6, w.r1 = 0.3, w.r2 = 0.3, w.rho = 0.42, w.beta0 = kPi / 3;
    v.push_back(std::make_shared<RollingWheel>(w));
  }
  std::vector<double> q, I;
  for (int j = 0; j <= 12; ++j) q.push_back(2 * kPi * j / 12), I.push_back(2 + std::sin(q.back()) * std::sin(q.back()));
  v.push_back(std::make_shared<InertiaTable>(CubicSpline(q, I, true), std::nullopt));
  v.push_back(std::make_shared<InertiaTable>(CubicSpline(q, I, false), std::nullopt));
  v.push_back(std::make_shared<InertiaExpression>(Expression("2 + 0.3*cos(q)^3", "q"), std::nullopt, 0.0));
  return v;
}

// Claim: dI/dq of every part of every machine agrees with a central finite difference of I
// (h = 1e-6, error O(h²) + round-off ~1e-9 relative).
TEST(Machine, InertiaDerivativeMatchesFiniteDifference) {
  for (const auto& m : all_machines())
    for (int k = 0; k < m->parts(); ++k)
      for (double q : {0.0, 0.3, 1.1, 2.0, 2.9, 4.0, 5.5, 9.0}) {
        // The clamped table is C¹ but not C² at its end q = 0: a central difference there is O(h).
        if (q == 0.0 && m->type() == "inertia-table" && m->period() == 0.0) continue;
        double I, dI, Ip, Im, d;
        m->part_inertia(k, q, &I, &dI);
        const double h = 1e-6;
        m->part_inertia(k, q + h, &Ip, &d);
        m->part_inertia(k, q - h, &Im, &d);
        EXPECT_NEAR(dI, (Ip - Im) / (2 * h), 1e-8 * std::max(1.0, std::abs(I)))
            << m->type() << " part " << m->part_name(k) << " q " << q;
      }
}

// Claim: the output point's p′ and p″ agree with finite differences of p (piston, wheel travel).
TEST(Machine, PointDerivativesMatchFiniteDifference) {
  for (const auto& m : all_machines()) {
    if (m->point_name().empty()) continue;
    for (double q : {0.1, 1.0, 2.5, 4.4}) {
      double p, dp, ddp, pp, pm, d1p, d1m, x;
      const double h = 1e-5;
      m->point(q, &p, &dp, &ddp);
      m->point(q + h, &pp, &d1p, &x);
      m->point(q - h, &pm, &d1m, &x);
      EXPECT_NEAR(dp, (pp - pm) / (2 * h), 1e-9) << m->type();
      EXPECT_NEAR(ddp, (d1p - d1m) / (2 * h), 1e-8) << m->type();
    }
  }
}

// Claim: the exact crank-slider kinematics give the textbook values: stroke 2r (s(0) = 0,
// s(π) = 2r) and, at φ = π/2, piston speed s′ = r (the rod is at its largest angle, ψ′ = 0) and
// I = J_c + m_rod[(P_x′)² + (P_y′)²] + m_p r² with P′ = (−r, 0) for every rod point.
TEST(CrankSlider, ExactKinematicsAtDeadCentresAndQuarterTurn) {
  const CrankSlider c(crank(0.05, 0.2));
  double s, ds, dds;
  c.point(0, &s, &ds, &dds);
  EXPECT_NEAR(s, 0, 1e-15);
  c.point(kPi, &s, &ds, &dds);
  EXPECT_NEAR(s, 0.1, 1e-15);
  c.point(kPi / 2, &s, &ds, &dds);
  EXPECT_NEAR(ds, 0.05, 1e-15);
  double I, dI;
  c.inertia(kPi / 2, &I, &dI);
  EXPECT_NEAR(I, 0.08 + 1.2 * 0.05 * 0.05 + 1.6 * 0.05 * 0.05, 1e-15);
}

// Claim (paper 004): the approximate I = I1 + m_B r² (sin φ + (λ/2) sin 2φ)² agrees with the exact
// one to O(λ³). Derivation: with the two-point-mass rod (J_rod = m a (l − a)) the exact reduced
// inertia is I1 + m_B (dx_B/dφ)², and dx_B/dφ = −r[sin φ + λ sin φ cos φ/√(1 − λ² sin²φ)]
// = −r[sin φ + (λ/2) sin 2φ + O(λ³)]. So max|I_exact − I_approx|/(m_B r²) halves by 8 when λ halves.
TEST(CrankSlider, ApproximateFormulaErrorScalesAsLambdaCubed) {
  const double r = 0.04;
  std::vector<double> err;
  for (double lam : {0.2, 0.1, 0.05, 0.025}) {
    const CrankSlider exact(crank(r, r / lam)), approx(crank(r, r / lam, true));
    const double mB = 1.6 + 1.2 / 3;
    double e = 0;
    for (int j = 0; j <= 720; ++j) {
      const double q = 2 * kPi * j / 720;
      double Ie, Ia, d;
      exact.inertia(q, &Ie, &d);
      approx.inertia(q, &Ia, &d);
      e = std::max(e, std::abs(Ie - Ia) / (mB * r * r));
    }
    err.push_back(e);
  }
  for (size_t k = 1; k < err.size(); ++k) {
    const double ratio = err[k - 1] / err[k];
    EXPECT_GT(ratio, 7.0) << k;
    EXPECT_LT(ratio, 9.0) << k;
  }
  EXPECT_LT(err.back(), 0.025 * 0.025 * 0.025);  // a few λ³
}

// Claim: the rolling wheel's β(φ) inverts x(β) = Rr φ and dβ/dφ = Rr sin²β/(H + (Rt − r2) cos β)
// (paper 000), checked by a finite difference of β(φ).
TEST(RollingWheel, BetaInvertsTravelAndMatchesPaperDerivative) {
  RollingWheel::Params p;
  p.scheme = 3, p.R1 = 0.6, p.r1 = 0.3, p.r2 = 0.3, p.beta0 = kPi / 3;
  const RollingWheel w(p);
  for (double phi : {-1.0, 0.0, 0.5, 3.0, 50.0, 1000.0}) {
    const double b = w.beta(phi);
    EXPECT_NEAR(w.x_of_beta(b), w.Rr() * phi, 1e-12 * std::max(1.0, std::abs(w.Rr() * phi)));
    const double h = 1e-6 * std::max(1.0, phi);
    const double fd = (w.beta(phi + h) - w.beta(phi - h)) / (2 * h);
    const double paper = w.Rr() * std::sin(b) * std::sin(b) / (p.H + (w.Rt() - p.r2) * std::cos(b));
    EXPECT_NEAR(fd, paper, 1e-7 * std::abs(paper) + 1e-12) << phi;
  }
  EXPECT_NEAR(w.beta(0.0), kPi / 3, 1e-15);
}

// Claim: the periodic spline reproduces a smooth periodic I(q) to O(h⁴) and its derivative is
// continuous across the period; the clamped one has zero slope at and beyond its ends.
TEST(CubicSpline, PeriodicAccuracyAndContinuity) {
  auto err = [](int n) {
    std::vector<double> q, I;
    for (int j = 0; j <= n; ++j) q.push_back(2 * kPi * j / n), I.push_back(2 + std::sin(q.back()) * std::sin(q.back()));
    const CubicSpline s(q, I, true);
    double e = 0, y, dy;
    for (int j = 0; j < 1000; ++j) {
      const double x = 2 * kPi * (j + 0.37) / 1000;
      s.evaluate(x, &y, &dy);
      e = std::max(e, std::abs(y - (2 + std::sin(x) * std::sin(x))));
    }
    double y1, d1, y2, d2;
    s.evaluate(2 * kPi - 1e-12, &y1, &d1);
    s.evaluate(2 * kPi + 1e-12, &y2, &d2);
    EXPECT_NEAR(y1, y2, 1e-10);
    EXPECT_NEAR(d1, d2, 1e-9);
    return e;
  };
  const double e1 = err(24), e2 = err(48);
  EXPECT_GT(e1 / e2, 12.0);  // 16 for O(h⁴)
  EXPECT_LT(e2, 1e-5);
  const CubicSpline c({0, 1, 2}, {1, 2, 1.5}, false);
  double y, dy;
  c.evaluate(0, &y, &dy);
  EXPECT_NEAR(dy, 0, 1e-15);
  c.evaluate(5, &y, &dy);
  EXPECT_EQ(y, 1.5);
  EXPECT_EQ(dy, 0);
}

}  // namespace
}  // namespace machdyn
