#include "machdyn/analysis/modes.hpp"

#include "machdyn/analysis/modal.hpp"
#include "machdyn/elements/link.hpp"
#include "machdyn/elements/linearize.hpp"

namespace machdyn {

// The chain these functions describe: every link transmitting (a gap taken as closed on its
// positive flank), no contact or brake acting. The laws are the elements' (linearize()).
namespace {
Topology chain_topology(const Model& m) {
  Topology t;
  t.gaps.assign(m.links.size(), GapMode::closed_pos);
  t.contacts.assign(m.contacts.size(), ContactMode::stuck);
  t.engaged.assign(m.contacts.size(), false);
  return t;
}
LinearModel chain(const Model& m) { return linearize(m, chain_topology(m)); }
}  // namespace

Eigen::VectorXd mass_diagonal(const Model& m) { return chain(m).M; }

Eigen::MatrixXd deflection_matrix(const Model& m) {
  Eigen::MatrixXd B = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(m.links.size()), m.dof());
  std::vector<double> q(static_cast<size_t>(m.dof())), v(q.size(), 0.0);
  for (int i = 0; i < m.dof(); ++i) q[static_cast<size_t>(i)] = m.bodies[static_cast<size_t>(i)].q0;
  for (size_t l = 0; l < m.links.size(); ++l) {
    const LinkLaw k = LinkLaw::of(m, m.links[l]);
    const LinkLaw::Kinematics s = k.kinematics(q.data(), v.data());
    const auto r = static_cast<Eigen::Index>(l);
    if (k.a >= 0) B(r, k.a) += s.ja;
    if (k.b >= 0) B(r, k.b) -= s.jb;
    if (k.third >= 0) B(r, k.third) += k.w3;  // a massless member's end (elements/link.hpp)
  }
  return B;
}

Eigen::MatrixXd stiffness_matrix(const Model& m) { return Eigen::MatrixXd(chain(m).stiffness()); }
Eigen::MatrixXd damping_matrix(const Model& m) { return Eigen::MatrixXd(chain(m).damping()); }

Modes compute_modes(const Model& m) {
  UndampedModes u = undamped_modes(chain(m));
  Modes out;
  out.rigid_body_modes = u.rigid_body_modes;
  out.omega = std::move(u.omega);
  out.shapes = std::move(u.shapes);
  out.rigid_shapes = std::move(u.rigid_shapes);
  return out;
}

Eigen::VectorXd static_link_loads(const Model& m, const Modes& modes, const Eigen::VectorXd& f) {
  // A spring's free length (elements/link.hpp): its constant part −c δ₀ joins the forces, and the
  // load is measured from δ₀.
  Eigen::VectorXd f0 = f;
  for (const Link& l : m.links) LinkLaw::of(m, l).rest_forces(f0.data());
  const Eigen::VectorXd eta = (modes.shapes.transpose() * f0).cwiseQuotient(modes.omega.cwiseAbs2());
  const Eigen::VectorXd q_e = modes.shapes * eta;
  const Eigen::VectorXd delta = deflection_matrix(m) * q_e;
  Eigen::VectorXd F(static_cast<Eigen::Index>(m.links.size()));
  for (size_t l = 0; l < m.links.size(); ++l)
    F(static_cast<Eigen::Index>(l)) = m.links[l].c * (delta(static_cast<Eigen::Index>(l)) - m.links[l].delta0);
  return F;
}

}  // namespace machdyn
