#include "machdyn/analysis/modes.hpp"

#include <Eigen/Eigenvalues>

#include "machdyn/model/machine.hpp"

namespace machdyn {

namespace {
/// dp/dq and d²p/dq² of a link end at the initial position: 1 and 0 for q itself, p′(q0) and
/// p″(q0) for a machine's output point. The model is linearized at the initial position.
void end_slope(const Model& m, int body, bool point, double* dp, double* ddp) {
  *dp = 1.0;
  *ddp = 0.0;
  if (!point) return;
  const Body& b = m.bodies[static_cast<size_t>(body)];
  double p;
  b.machine->point(b.q0, &p, dp, ddp);
}
}  // namespace

Eigen::VectorXd mass_diagonal(const Model& m) {
  Eigen::VectorXd M(m.dof());
  for (int i = 0; i < m.dof(); ++i) M(i) = m.bodies[static_cast<size_t>(i)].inertia;
  return M;
}

Eigen::MatrixXd deflection_matrix(const Model& m) {
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(m.links.size()), m.dof());
  for (size_t l = 0; l < m.links.size(); ++l) {
    const Link& k = m.links[l];
    const auto r = static_cast<Eigen::Index>(l);
    double dp, ddp;
    if (k.a >= 0) end_slope(m, k.a, k.a_point, &dp, &ddp), B(r, k.a) += dp / k.ratio;
    if (k.b >= 0) end_slope(m, k.b, k.b_point, &dp, &ddp), B(r, k.b) -= dp;
  }
  return B;
}

namespace {
Eigen::MatrixXd weighted_gram(const Model& m, bool stiffness) {
  Eigen::MatrixXd B = deflection_matrix(m);
  Eigen::VectorXd w(static_cast<Eigen::Index>(m.links.size()));
  for (size_t l = 0; l < m.links.size(); ++l)
    w(static_cast<Eigen::Index>(l)) = stiffness ? m.links[l].c : m.links[l].d;
  return B.transpose() * w.asDiagonal() * B;
}
}  // namespace

Eigen::MatrixXd stiffness_matrix(const Model& m) {
  Eigen::MatrixXd K = weighted_gram(m, true);
  // A link to a machine's output point: V = ½ c δ(q)², so ∂²V/∂q² = c ∇δ ∇δᵀ + c δ ∇²δ; the
  // second (geometric) term is c δ0 p″(q0) on the diagonal, with δ0 the initial deflection.
  for (const Link& k : m.links) {
    if (!k.a_point && !k.b_point) continue;
    double delta0 = 0.0, pa = 0.0, pb = 0.0, d1, d2a = 0.0, d2b = 0.0;
    if (k.a >= 0) {
      const Body& b = m.bodies[static_cast<size_t>(k.a)];
      if (k.a_point) b.machine->point(b.q0, &pa, &d1, &d2a);
      else pa = b.q0;
      delta0 += pa / k.ratio;
    }
    if (k.b >= 0) {
      const Body& b = m.bodies[static_cast<size_t>(k.b)];
      if (k.b_point) b.machine->point(b.q0, &pb, &d1, &d2b);
      else pb = b.q0;
      delta0 -= pb;
    }
    if (k.a >= 0) K(k.a, k.a) += k.c * delta0 * d2a / k.ratio;
    if (k.b >= 0) K(k.b, k.b) -= k.c * delta0 * d2b;
  }
  return K;
}
Eigen::MatrixXd damping_matrix(const Model& m) { return weighted_gram(m, false); }

Modes compute_modes(const Model& m) {
  const Eigen::MatrixXd K = stiffness_matrix(m);
  const Eigen::VectorXd Md = mass_diagonal(m);
  const Eigen::MatrixXd M = Md.asDiagonal();
  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(K, M, Eigen::ComputeEigenvectors | Eigen::Ax_lBx);
  const Eigen::VectorXd lambda = es.eigenvalues();  // ascending
  const Eigen::MatrixXd V = es.eigenvectors();      // Vᵀ M V = 1
  const double lmax = lambda.size() ? lambda.cwiseAbs().maxCoeff() : 0.0;
  int rigid = 0;
  while (rigid < lambda.size() && (lmax == 0.0 || lambda(rigid) <= 1e-10 * lmax)) ++rigid;
  Modes out;
  out.rigid_body_modes = rigid;
  const Eigen::Index ne = lambda.size() - rigid;
  out.omega = lambda.tail(ne).cwiseSqrt();
  out.shapes = V.rightCols(ne);
  out.rigid_shapes = V.leftCols(rigid);
  for (auto* S : {&out.shapes, &out.rigid_shapes})
    for (Eigen::Index k = 0; k < S->cols(); ++k) {
      Eigen::Index imax = 0;
      S->col(k).cwiseAbs().maxCoeff(&imax);
      if ((*S)(imax, k) < 0) S->col(k) *= -1.0;
    }
  return out;
}

Eigen::VectorXd static_link_loads(const Model& m, const Modes& modes, const Eigen::VectorXd& f) {
  const Eigen::VectorXd eta = (modes.shapes.transpose() * f).cwiseQuotient(modes.omega.cwiseAbs2());
  const Eigen::VectorXd q_e = modes.shapes * eta;
  const Eigen::VectorXd delta = deflection_matrix(m) * q_e;
  Eigen::VectorXd F(static_cast<Eigen::Index>(m.links.size()));
  for (size_t l = 0; l < m.links.size(); ++l)
    F(static_cast<Eigen::Index>(l)) = m.links[l].c * delta(static_cast<Eigen::Index>(l));
  return F;
}

}  // namespace machdyn
