#include "analysis/impact.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "machdyn/model/machine.hpp"

namespace machdyn::detail {

void impact_jump(const DriveSystem& sys, int k, double u_out, double t, double* y, const std::vector<char>& tie) {
  const Model& m = sys.model();
  const int n = sys.dof(), nc = static_cast<int>(m.contacts.size());
  double* v = y + n;
  // I⁻¹ per body: 0 for a prescribed motion (infinitely heavy), I(q)⁻¹ for a machine.
  std::vector<double> im(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    const Body& b = m.bodies[static_cast<size_t>(i)];
    double I = sys.inertia(i), dI = 0.0;
    if (b.machine) b.machine->inertia(y[i], &I, &dI);
    im[static_cast<size_t>(i)] = b.motion != MotionKind::free ? 0.0 : 1.0 / I;
  }
  // The rows: the stop first, then the ties (stuck joints, freewheels and stops a body rests on).
  std::vector<int> rows{k};
  for (int j = 0; j < nc; ++j) {
    const ContactLaw& c = sys.contact(j);
    if (j != k && tie[static_cast<size_t>(j)] && !c.kinematic && (c.joint || c.lock != 0) &&
        sys.contact_mode(j) == ContactMode::stuck)
      rows.push_back(j);
  }
  const std::vector<double> v0(v, v + n);
  for (int round = 0; round <= 2 * nc; ++round) {
    // (G M⁻¹ Gᵀ) Λ = G v⁻ − u*, least norm; v⁺ = v⁻ − M⁻¹ Gᵀ Λ.
    const auto r = static_cast<Eigen::Index>(rows.size());
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(r, n);
    Eigen::VectorXd rhs(r);
    for (Eigen::Index i = 0; i < r; ++i) {
      const ContactLaw& c = sys.contact(rows[static_cast<size_t>(i)]);
      for (int p = 0; p < c.row.terms; ++p)
        if (c.row.body[p] >= 0) G(i, c.row.body[p]) += c.row.w[p];
      rhs(i) = c.sliding_velocity(t, v0.data()) - (i == 0 ? u_out : 0.0);
    }
    const Eigen::MatrixXd GM = G * Eigen::Map<const Eigen::VectorXd>(im.data(), n).asDiagonal();
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
    cod.setThreshold(1e-12);
    cod.compute(GM * G.transpose());
    const Eigen::VectorXd Lambda = cod.solve(rhs);
    const Eigen::VectorXd dv = GM.transpose() * Lambda;
    for (int i = 0; i < n; ++i) v[i] = v0[static_cast<size_t>(i)] - dv(i);
    // A one-sided tie pulled against its lock lets go (the most pulled first); a freewheel turned into
    // its locked direction engages. Scale of the impulses: the stop's.
    const double scale = std::abs(Lambda(0));
    int drop = -1, add = -1;
    double worst = 0.0;
    for (Eigen::Index i = 1; i < r; ++i) {
      const ContactLaw& c = sys.contact(rows[static_cast<size_t>(i)]);
      if (c.lock == 0) continue;
      const double pull = -c.lock * Lambda(i);
      if (pull > 1e-12 * scale && pull > worst) worst = pull, drop = static_cast<int>(i);
    }
    if (drop < 0)
      for (int j = 0; j < nc && add < 0; ++j) {
        const ContactLaw& c = sys.contact(j);
        if (j == k || !tie[static_cast<size_t>(j)] || c.lock == 0 || c.stop || c.kinematic ||
            std::find(rows.begin(), rows.end(), j) != rows.end())
          continue;
        const double u = c.sliding_velocity(t, v), u0 = c.sliding_velocity(t, v0.data());
        // Its relative velocity now runs into the lock, beyond the rounding of the jump.
        if (c.lock * u > 1e-12 * (std::abs(u0) + std::abs(u_out) + std::abs(rhs(0)))) add = j;
      }
    if (drop >= 0) rows.erase(rows.begin() + drop);
    else if (add >= 0) rows.push_back(add);
    else break;
  }
  if (rows.size() == 1 && !sys.contact(k).general) {
    // The stop's body alone: exactly v⁺ = u*, the other bodies untouched.
    std::copy(v0.begin(), v0.end(), v);
    v[sys.contact(k).a] = u_out;
  }
}

}  // namespace machdyn::detail
