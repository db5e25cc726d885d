#include "machdyn/analysis/modes.hpp"

#include <Eigen/Eigenvalues>

namespace machdyn {

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
    if (k.a >= 0) B(r, k.a) += 1.0 / k.ratio;
    if (k.b >= 0) B(r, k.b) -= 1.0;
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

Eigen::MatrixXd stiffness_matrix(const Model& m) { return weighted_gram(m, true); }
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
