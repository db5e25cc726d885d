#include "machdyn/elements/linear_model.hpp"

#include <algorithm>
#include <stdexcept>

#include "machdyn/elements/contact.hpp"
#include "machdyn/model/element.hpp"
#include "machdyn/elements/link.hpp"
#include "machdyn/elements/linearize.hpp"
#include "machdyn/elements/lossy_gear.hpp"
#include "machdyn/elements/prescribed_motion.hpp"

namespace machdyn {

void LinearModel::add_outer(std::vector<Eigen::Triplet<double>>& to, const int* idx, const double* j, int count,
                            double w) {
  if (w == 0.0) return;
  for (int r = 0; r < count; ++r)
    for (int s = 0; s < count; ++s) to.emplace_back(idx[r], idx[s], w * j[r] * j[s]);
}

namespace {
Eigen::SparseMatrix<double> assemble(int rows, int cols, const std::vector<Eigen::Triplet<double>>& t) {
  Eigen::SparseMatrix<double> A(rows, cols);
  A.setFromTriplets(t.begin(), t.end());
  A.makeCompressed();
  return A;
}
}  // namespace

Eigen::SparseMatrix<double> LinearModel::stiffness() const { return assemble(n, n, K); }
Eigen::SparseMatrix<double> LinearModel::damping() const { return assemble(n, n, D); }
Eigen::SparseMatrix<double> LinearModel::constraints() const {
  std::vector<Eigen::Triplet<double>> t;
  for (size_t r = 0; r < G.size(); ++r)
    for (const auto& [col, w] : G[r]) t.emplace_back(static_cast<int>(r), col, w);
  return assemble(static_cast<int>(G.size()), n, t);
}

void add_drive_linear(const Drive& d, int mode, LinearModel& lin, const double* q, const double* x) {
  const int np = d.ports();
  ElementMotion b;  // the configuration q (at rest) the terms are taken about
  b.n = np;
  if (q)
    for (int p = 0; p < np; ++p) b.q[p] = d.at(q, p);
  std::vector<double> x0;
  if (!x) {  // the element's initial states
    x0.assign(static_cast<size_t>(std::max(d.law->states(), 1)), 0.0);
    d.law->initial_states(x0.data());
    x = x0.data();
  }
  auto add = [&](const int* at, LinearModel& to) {
    if (q) d.law->add_linear_at(at, b, x, mode, to);
    else d.law->add_linear(at, mode, to);
  };
  if (np == 1 && d.body2 < 0 && d.ratio == 1.0) return add(&d.body, lin);
  // The element's terms at its own points X_p (a scratch model of one coordinate per port), spread
  // by δq_X = Σ ρ_i δq_i: an entry c at (X_r, X_s) is ρ_i ρ_j c at (i, j) over the terms i of port r
  // and j of port s (model.hpp: Drive; ports ≥ 1 are plain bodies).
  LinearModel own(np);
  int at[ElementMotion::kMax];
  for (int p = 0; p < np; ++p) at[p] = p;
  add(at, own);
  int b_[ElementMotion::kMax][2];
  double w[ElementMotion::kMax][2];
  int nt[ElementMotion::kMax];
  nt[0] = d.terms(b_[0], w[0]);
  for (int p = 1; p < np; ++p) nt[p] = 1, b_[p][0] = d.others[static_cast<size_t>(p - 1)], w[p][0] = 1.0;
  auto spread = [&](const std::vector<Eigen::Triplet<double>>& from, std::vector<Eigen::Triplet<double>>& to) {
    for (const auto& e : from) {
      const int r = static_cast<int>(e.row()), c = static_cast<int>(e.col());
      for (int i = 0; i < nt[r]; ++i)
        for (int j = 0; j < nt[c]; ++j) to.emplace_back(b_[r][i], b_[c][j], w[r][i] * w[c][j] * e.value());
    }
  };
  spread(own.K, lin.K);
  spread(own.D, lin.D);
}

LinearModel linearize(const Model& m, const Topology& topo, double t, const double* y) {
  const int n = m.dof();
  if (topo.gaps.size() != m.links.size() || topo.contacts.size() != m.contacts.size() ||
      (!topo.engaged.empty() && topo.engaged.size() != m.contacts.size()))
    throw std::invalid_argument("linearize: the topology does not match the model's links and contacts");
  std::vector<double> state(static_cast<size_t>(2 * n));
  for (int i = 0; i < n; ++i) {
    state[static_cast<size_t>(i)] = y ? y[i] : m.bodies[static_cast<size_t>(i)].q0;
    state[static_cast<size_t>(n + i)] = y ? y[n + i] : m.bodies[static_cast<size_t>(i)].v0;
  }
  const double* q = state.data();
  const double* v = q + n;
  LinearModel lin(n);
  for (int i = 0; i < n; ++i) {
    const Body& b = m.bodies[static_cast<size_t>(i)];
    double I = b.inertia, dI;
    if (b.machine) b.machine->inertia(q[i], &I, &dI);
    lin.M(i) = I;
  }
  for (size_t l = 0; l < m.links.size(); ++l) LinkLaw::of(m, m.links[l]).add_linear(q, topo.gaps[l], lin);
  for (size_t k = 0; k < m.contacts.size(); ++k) {
    const ContactLaw c = ContactLaw::of(m.contacts[k], m);  // a kinematic one: no row (its bodies are supports)
    const bool engaged = topo.engaged.empty() || topo.engaged[k];
    c.add_linear(topo.contacts[k], engaged, t, c.sliding_velocity(t, v), lin);
  }
  // Elements with states of their own in their mode 0 (model/element.hpp; a limited speed drive
  // is a constant torque and adds nothing): a DC motor its quasi-static slope k²/R, a speed drive its
  // PI law as damper K_p and spring K_p/T_i.
  for (const Drive& d : m.drives) add_drive_linear(d, 0, lin, q);  // about the configuration q
  // Lossy gears: for modes the ideal gear, v_a − i v_b = 0 (elements/lossy_gear.hpp).
  for (const LossyGear& g : m.lossy_gears) LossyGearLaw::of(g).add_linear(lin);
  // Prescribed motions: fixed supports (elements/prescribed_motion.hpp).
  for (int i = 0; i < n; ++i)
    if (m.bodies[static_cast<size_t>(i)].motion != MotionKind::free)
      PrescribedMotionLaw::of(m, i).add_linear(m.bodies[static_cast<size_t>(i)].name + ".motion", lin);
  return lin;
}

Topology initial_topology(const Model& m, double t) {
  const int n = m.dof();
  std::vector<double> q(static_cast<size_t>(n)), v(q);
  for (int i = 0; i < n; ++i) q[static_cast<size_t>(i)] = m.bodies[static_cast<size_t>(i)].q0, v[static_cast<size_t>(i)] = m.bodies[static_cast<size_t>(i)].v0;
  Topology topo;
  for (const Link& l : m.links) {
    const LinkLaw k = LinkLaw::of(m, l);
    const LinkLaw::Kinematics s = k.kinematics(q.data(), v.data());
    topo.gaps.push_back(k.natural_mode(s.delta, s.rate, k.drum(q.data())));
  }
  for (const FrictionContact& fc : m.contacts) {
    const ContactLaw c = ContactLaw::of(fc);
    const double u = c.sliding_velocity(t, v.data());
    topo.contacts.push_back(u == 0.0 ? ContactMode::stuck : u > 0 ? ContactMode::slip_pos : ContactMode::slip_neg);
    topo.engaged.push_back(!c.released(t) && c.static_limit(t) > 0.0);
  }
  return topo;
}

}  // namespace machdyn
