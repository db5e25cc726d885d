// The rigid load (`type: rigid-load` under `bodies:`, model/compile_point_mass.hpp): a long load or a
// spreader in a vertical plane with x, z and its angle ψ, hung by spatial ropes (elements/
// spatial_rope.hpp) at points of its own (`attach`) from points of the suspension (`offset`): the
// compound pendulum's two modes, a spreader on two parallel ropes, the energy books, the rope's
// Jacobian and stored power against differences with ψ, and located errors — each against an
// independent answer, event-driven runs on both integrators.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <string>
#include <vector>
#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <fmt/format.h>
#include <gtest/gtest.h>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/elements/linear_model.hpp"
#include "machdyn/elements/linearize.hpp"
#include "machdyn/model/element.hpp"
#include "support/support.hpp"
#include "support/timed_model.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

using test::num;
using test::series;
constexpr double kG = 9.80665;

class RigidLoad : public ::testing::TestWithParam<IntegratorChoice> {};
INSTANTIATE_TEST_SUITE_P(Integrators, RigidLoad, ::testing::Values(IntegratorChoice::dopri5, IntegratorChoice::bdf),
                         test::IntegratorName{});

// The compound pendulum: a body of mass m and inertia J about its centre on a rope of length L
// attached a above the centre, hung from a fixed point. With the rope's angle θ and the body's ψ
// (small), the attach point is at (L θ, −L) and the centre at (L θ + a ψ, −L − a), so
//   T = ½ m (L θ' + a ψ')² + ½ J ψ'²,  V = ½ m g (L θ² + a ψ²)  (from −m g (L cos θ + a cos ψ)),
//   M = [[m L², m L a], [m L a, m a² + J]],  K = diag(m g L, m g a),
// and det(K − λ M) = 0 is, divided by m L,
//   L J λ² − g (m a² + J + m a L) λ + m g² a = 0,
// whose two roots are the squared frequencies of the two modes; (K − λ M) v = 0 gives their shapes
// θ/ψ = λ a/(g − λ L).
struct Compound {
  double m = 1000, J = 2000, a = 1.0, L0 = 6, EA = 1e10;
  double c() const { return EA / L0; }
  double l() const { return L0 + m * kG / c(); }  // the hanging length under m g
  double lambda(int k) const {
    const double A = l() * J, B = kG * (m * a * a + J + m * a * l()), C = m * kG * kG * a;
    return (B + (k == 0 ? -1 : 1) * std::sqrt(B * B - 4 * A * C)) / (2 * A);
  }
  std::string yaml(double theta0, double psi0) const {
    // The rope's point at (ℓ sin θ, h − ℓ cos θ), h = ℓ + a: the centre at R(ψ)(0, a) below it.
    const double h = l() + a, xa = l() * std::sin(theta0), za = h - l() * std::cos(theta0);
    const double xc = xa + a * std::sin(psi0), zc = za - a * std::cos(psi0);
    return "bodies:\n  beam: {type: rigid-load, mass: " + num(m) + " kg, inertia: " + num(J) + " kg*m^2, position: [" +
           num(xc) + " m, " + num(zc) + " m], angle: " + num(psi0) + "}\n"
           "links:\n  rope: {type: spatial-rope, load: beam, attach: [0 m, " + num(a) + " m], length: " + num(L0) +
           " m, EA: " + num(EA) + " N, height: " + num(h) + " m}\n";
  }
};

// Claim: linearized about the hanging body, the rigid load's two pendulum modes are the compound
// pendulum's roots above (within 1e-5: the rope's elasticity shifts them by ≈ λ/(c/m) ≈ 1e-6), and
// its third mode is the rope's stretch c/m (the rope along z: exactly the spring). The mass matrix
// is diagonal in (x, z, ψ): m, m, J.
TEST(RigidLoadLinear, CompoundPendulumModes) {
  const Compound p;
  const Model md = test::model_text(p.yaml(0.0, 0.0));
  const LinearModel lin = linearize(md, initial_topology(md));
  ASSERT_EQ(lin.M.size(), 3);
  std::vector<double> mass(lin.M.data(), lin.M.data() + 3);
  std::sort(mass.begin(), mass.end());
  EXPECT_DOUBLE_EQ(mass[0], p.m);
  EXPECT_DOUBLE_EQ(mass[1], p.m);
  EXPECT_DOUBLE_EQ(mass[2], p.J);
  const Eigen::MatrixXd K(lin.stiffness());
  const Eigen::MatrixXd A = lin.M.cwiseInverse().asDiagonal() * K;
  Eigen::EigenSolver<Eigen::MatrixXd> es(A);
  std::vector<double> ev;
  for (int i = 0; i < 3; ++i) ev.push_back(es.eigenvalues()[i].real());
  std::sort(ev.begin(), ev.end());
  EXPECT_NEAR(ev[0], p.lambda(0), 1e-5 * p.lambda(0));
  EXPECT_NEAR(ev[1], p.lambda(1), 1e-5 * p.lambda(1));
  EXPECT_NEAR(ev[2], p.c() / p.m, 1e-6 * p.c() / p.m);
}

// Claim: started in the shape of one mode (ψ0 = ε = 1e-3, θ0 = ε λ a/(g − λ L), at rest) the body
// swings in that mode alone: ψ = ε cos(√λ t) within 1e-3 ε over three periods of the slow mode, for
// each of the two modes (the nonlinear terms are O(ε²), the rope's elasticity shifts ω by 1e-6).
TEST_P(RigidLoad, CompoundPendulumSwingsInItsModes) {
  const Compound p;
  const double eps = 1e-3, T1 = 2 * std::numbers::pi / std::sqrt(p.lambda(0));
  for (int k = 0; k < 2; ++k) {
    const double lam = p.lambda(k), w = std::sqrt(lam), theta0 = eps * lam * p.a / (kG - lam * p.l());
    const Model md = test::timed_model(p.yaml(theta0, eps), 3 * T1, 1e-2, GetParam());
    const SimulationResult r = simulate(md);
    const double err = test::max_error(r, "beam.psi.position_rad", [&](double t) { return eps * std::cos(w * t); });
    EXPECT_LT(err, 1e-3 * eps) << "mode " << k << ": " << test::sci(err / eps);
  }
}

// Claim: a spreader hung on two parallel ropes of equal length (suspension offsets ±d equal to the
// attach points ±d) is a parallelogram linkage: it stays level (ψ ≡ 0) and its centre swings as a
// point pendulum of the rope's length, whatever its inertia: x = x0 cos(√(g/ℓ) t), ℓ = L0 + (m g/2)/c
// (each rope carries half the weight), within 1e-3 x0 over two periods. ψ stays 0 but for the ropes'
// elasticity: the ropes' horizontal pull m g θ acts a_z above the centre, a moment a_z m g θ that the
// ropes' axial stiffness resists with 2 c d² ψ (c = EA/L0 each, at ±d); applied at once at the start
// it turns the spreader by at most twice its static ψ (the suddenly applied load), so
// |ψ| ≤ 2 a_z m g (x0/ℓ)/(2 c d²) (within 10 %).
TEST_P(RigidLoad, SpreaderOnParallelRopesStaysLevel) {
  const double m = 20000, L0 = 8, EA = 2e10, c = EA / L0, l = L0 + 0.5 * m * kG / c, x0 = 0.05, h = l + 0.4;
  const double z0 = h - 0.4 - std::sqrt(l * l - x0 * x0), w = std::sqrt(kG / l);
  const std::string rope = "type: spatial-rope, load: spreader, length: 8 m, EA: 2e10 N, height: " + num(h) + " m";
  const Model md = test::timed_model("bodies:\n  spreader: {type: rigid-load, mass: 20 t, inertia: 9e4 kg*m^2, position: [" +
                                   num(x0) + " m, " + num(z0) + " m]}\n"
                                   "links:\n  left: {" + rope + ", attach: [-3 m, 0.4 m], offset: -3 m}\n"
                                   "  right: {" + rope + ", attach: [3 m, 0.4 m], offset: 3 m}\n",
                               2 * 2 * std::numbers::pi / w, 1e-2, GetParam());
  const SimulationResult r = simulate(md);
  const double ex = test::max_error(r, "spreader.x.position_m", [&](double t) { return x0 * std::cos(w * t); });
  const double epsi = test::max_error(r, "spreader.psi.position_rad", [](double) { return 0.0; });
  EXPECT_LT(ex, 1e-3 * x0) << test::sci(ex / x0);
  const double psi_bound = 2 * 0.4 * m * kG * (x0 / l) / (2 * c * 3.0 * 3.0);
  EXPECT_LT(epsi, 1.1 * psi_bound) << test::sci(epsi) << " of " << test::sci(psi_bound);
}

// Claim: the energy books balance with a rigid load on two damped ropes of a free trolley pushed by
// a sine force (the ropes not parallel: the load swings and turns), within 1e-6 of the work turned
// over; the ropes' damping is the only loss.
TEST_P(RigidLoad, EnergyBooksBalance) {
  // The ropes from (±1 m, 6.5 m) to (±2.5 m, 0.5 m) of the level beam at z = 0: 1 mm shorter than that.
  const std::string rope = "type: spatial-rope, load: beam, trolley: trolley, length: " + num(std::hypot(1.5, 6.0) - 1e-3) +
                           " m, EA: 5e8 N, damping: 2e4 N*s/m, height: 6.5 m";
  Model md = test::timed_model("bodies:\n  trolley: {type: translational, mass: 4 t}\n"
                         "  beam: {type: rigid-load, mass: 10 t, inertia: 3e4 kg*m^2, angular_velocity: 0.1}\n"
                         "links:\n  left: {" + rope + ", attach: [-2.5 m, 0.5 m], offset: -1 m}\n"
                         "  right: {" + rope + ", attach: [2.5 m, 0.5 m], offset: 1 m}\n"
                         "loads:\n  push: {type: sine, body: trolley, amplitude: 20 kN, frequency: 0.4 Hz}\n",
                         5.0, 1e-3, GetParam());
  SimulateOptions o;
  o.event_driven = true;
  const SimulationResult r = simulate(md, o);
  const EnergyBalance& e = r.hybrid.energy;
  EXPECT_GT(e.source_work, 1e3);
  EXPECT_GT(e.damping_loss, 0.0);
  EXPECT_LT(std::abs(e.residual()), 1e-6 * (std::abs(e.source_work) + e.damping_loss)) << e.residual();
  double psi_max = 0.0;
  for (double psi : series(r, "beam.psi.position_rad")) psi_max = std::max(psi_max, std::abs(psi));
  EXPECT_GT(psi_max, 0.01) << "the beam turns";
}

// Claim: the rope's Jacobian with a rigid load's ψ (and a trolley, a drum) equals central
// differences of its forces (within 1e-6 of the force scale), and its stored power the difference of
// its energy along the motion — the ψ terms of ∂e/∂q and of the Hessian are right.
TEST(RigidLoadRope, JacobianAndStoredPowerMatchDifferences) {
  const Model md = test::model_text(
      "bodies:\n  trolley: {type: translational, mass: 2 t}\n  drum: {inertia: 20 kg*m^2}\n"
      "  beam: {type: rigid-load, mass: 3 t, inertia: 5e3 kg*m^2, axes: [y, z], position: [0.3 m, -0.2 m], angle: 0.2}\n"
      "links:\n  rope: {type: spatial-rope, load: beam, bridge: trolley, drum: drum, drum_radius: 0.25 m, falls: 2, "
      "length: 5 m, EA: 1e7 N, damping: 3e3 N*s/m, attach: [1.5 m, 0.3 m], offset: 0.4 m}\n");
  const Drive* d = nullptr;
  for (const Drive& x : md.drives)
    if (x.name == "rope") d = &x;
  ASSERT_NE(d, nullptr);
  const Element& el = *d->law;
  const int n = el.bodies();
  ASSERT_EQ(n, 5);  // z, y, ψ, bridge, drum
  ElementMotion b;
  std::vector<int> body = {d->body};
  body.insert(body.end(), d->others.begin(), d->others.end());
  const double dq[5] = {-0.01, 0.02, 0.05, -0.03, 0.1}, v[5] = {0.3, -0.2, 0.4, 0.5, -1.2};
  for (int k = 0; k < n; ++k) b.q[k] = md.bodies[static_cast<size_t>(body[static_cast<size_t>(k)])].q0 + dq[k], b.v[k] = v[k];
  double M0[ElementMotion::kMax];
  el.forces(0.0, b, nullptr, 0, M0);
  double scale = 0.0;
  for (int k = 0; k < n; ++k) scale = std::max(scale, std::abs(M0[k]));
  ASSERT_GT(scale, 1e3) << "the rope is taut there";
  const ElementJacobian J = el.jacobian(0.0, b, nullptr, 0);
  const double h = 1e-6;
  for (int j = 0; j < n; ++j)
    for (int which = 0; which < 2; ++which) {
      ElementMotion bp = b, bm = b;
      (which == 0 ? bp.q : bp.v)[j] += h, (which == 0 ? bm.q : bm.v)[j] -= h;
      double Mp[ElementMotion::kMax], Mm[ElementMotion::kMax];
      el.forces(0.0, bp, nullptr, 0, Mp), el.forces(0.0, bm, nullptr, 0, Mm);
      for (int k = 0; k < n; ++k) {
        const double fd = (Mp[k] - Mm[k]) / (2 * h), an = which == 0 ? J.dM_dq[k][j] : J.dM_dv[k][j];
        EXPECT_NEAR(an, fd, 1e-6 * scale) << (which == 0 ? "dM/dq" : "dM/dv") << " k " << k << " j " << j;
      }
    }
  ElementMotion bp = b, bm = b;
  for (int k = 0; k < n; ++k) bp.q[k] += h * v[k], bm.q[k] -= h * v[k];
  const double dV = (el.energy(bp, nullptr, 0) - el.energy(bm, nullptr, 0)) / (2 * h);
  EXPECT_NEAR(el.stored_power(0.0, b, nullptr, 0), dV, 1e-6 * std::abs(dV) + 1e-6);
  // The virtual work: Σ M_k v_k = −dV/dt − the damper's heat.
  double P = 0.0;
  for (int k = 0; k < n; ++k) P += M0[k] * v[k];
  EXPECT_NEAR(P, -dV - el.heat_power(0.0, b, nullptr, 0), 1e-6 * std::abs(dV) + 1e-6);
}

// Claim: every bad input of a rigid load or its rope's attach point and offset is an error at its
// place naming it (inertia missing, a rigid load in space, `attach` on a point mass or not two
// lengths, an `offset` of a load in space).
TEST(RigidLoadCompile, BadInputIsLocated) {
  struct Case {
    std::string yaml, want;
  };
  const std::string ok_bodies = "bodies:\n  B: {type: rigid-load, mass: 1 t, inertia: 100 kg*m^2}\n"
                                "  P: {type: point-mass, mass: 1 t, axes: [x, z]}\n  S: {type: point-mass, mass: 1 t}\n";
  EXPECT_EQ(test::compile_errors(ok_bodies + "links:\n  r: {type: spatial-rope, load: B, attach: [1 m, 0 m], offset: 1 m, "
                                             "length: 5 m, EA: 1e8 N}\n"),
            "");
  const Case cases[] = {
      {"bodies:\n  B: {type: rigid-load, mass: 1 t}\n", "test.yaml:2:6: error: body 'B': missing field 'inertia'"},
      {"bodies:\n  B: {type: rigid-load, mass: 1 t, inertia: 1, axes: [x, y, z]}\n",
       "test.yaml:2:54: error: body 'B': a rigid load moves in a vertical plane"},
      {ok_bodies + "links:\n  r: {type: spatial-rope, load: P, attach: [1 m, 0 m], length: 5 m, EA: 1e8 N}\n",
       "test.yaml:6:44: error: link 'r': 'attach' is a point on a rigid load; 'P' is a point mass"},
      {ok_bodies + "links:\n  r: {type: spatial-rope, load: B, attach: [1 m], length: 5 m, EA: 1e8 N}\n",
       "test.yaml:6:44: error: link 'r': 'attach' expected the rope's point on the load"},
      {ok_bodies + "links:\n  r: {type: spatial-rope, load: S, offset: 1 m, length: 5 m, EA: 1e8 N}\n",
       "test.yaml:6:44: error: link 'r': an 'offset' of the suspension point"},
  };
  for (const Case& c : cases) {
    const std::string got = test::compile_errors(c.yaml);
    EXPECT_NE(got.find(c.want), std::string::npos) << c.yaml << "\n--- want: " << c.want << "\n--- got:\n" << got;
  }
}

}  // namespace MACHDYN_UNITY_ID
}  // namespace machdyn
