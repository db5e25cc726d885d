// The drive system's side of gears with clutches on their bodies (analysis/gear_clutch.hpp): the stuck
// contacts solved with the compliance C of the bodies, whose gear blocks come from the gears' law.
// Nothing here decides a mode: for the modes set, solve_coupled forms the stuck set's loads by the
// decision rule's step 3 (docs/hybrid.md "Modes"): the weighted share with the one-sided rule, and where
// it leaves a row beyond its bounds the bounded split with the stuck gears as rows
// (split_stuck_gears, analysis/gear_split.hpp); enforce_coupled projects onto the stuck rows. The modes
// are decided by analysis/contact_decision.hpp and decide_gear_at_rest, which read these loads.
#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "analysis/bounded_share.hpp"
#include "analysis/gear_split.hpp"
#include "machdyn/analysis/drive_system.hpp"

namespace machdyn {
namespace {

/// λ = D (S D)⁺ r, the weighted least-norm solution of S λ = r (docs/hybrid.md); empty when `same_rank`
/// and the weighted matrix loses rank (the masked contacts are needed).
Eigen::MatrixXd weighted_solution(const Eigen::MatrixXd& S, const Eigen::VectorXd& w, bool same_rank) {
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  cod.setThreshold(1e-12);
  cod.compute(S * w.asDiagonal());
  if (same_rank) {
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> full;
    full.setThreshold(1e-12);
    full.compute(S);
    if (full.rank() != cod.rank()) return {};
  }
  return w.asDiagonal() * cod.pseudoInverse();
}

}  // namespace

void DriveSystem::solve_coupled(double t, const double* y, double* acc, double* fc, const double* im, double* src,
                                double* fric) {
  // Each gear's block of C: a = k_a F_a + k_b F_b + k_0 from its law at F = 0 and the unit forces.
  CoupledSplit& cs = coupled_split_;
  std::vector<double>& ka = cs.ka;
  std::vector<double>& kb = cs.kb;
  ka.assign(static_cast<size_t>(ng_), 0.0);
  kb.assign(static_cast<size_t>(ng_), 0.0);
  for (int g = 0; g < ng_; ++g) {
    const auto gi = static_cast<size_t>(g);
    if (gear_mode_[gi] == GearMode::stuck) continue;
    const LossyGearLaw& k = gears_[gi];
    const double Ia = inertia_[static_cast<size_t>(k.a)], Ib = inertia_[static_cast<size_t>(k.b)], va = y[n_ + k.a];
    const double a0 = k.solve(gear_mode_[gi], 0.0, 0.0, Ia, Ib, va).acc;
    ka[gi] = k.solve(gear_mode_[gi], 1.0, 0.0, Ia, Ib, va).acc - a0;
    kb[gi] = k.solve(gear_mode_[gi], 0.0, 1.0, Ia, Ib, va).acc - a0;
  }
  auto C = [&](int x, int z) {  // ∂acc_x / ∂f_z
    const int g = gear_of_body_[static_cast<size_t>(x)];
    if (g < 0) return x == z ? im[x] : 0.0;
    const LossyGearLaw& k = gears_[static_cast<size_t>(g)];
    if (z != k.a && z != k.b) return 0.0;
    const double kz = z == k.a ? ka[static_cast<size_t>(g)] : kb[static_cast<size_t>(g)];
    return x == k.a ? kz : kz / k.i;
  };
  const auto ns = static_cast<Eigen::Index>(stuck_.size());
  Eigen::MatrixXd& S = cs.S_now;
  Eigen::VectorXd& w = cs.w_now;
  S.setZero(ns, ns);
  w.resize(ns);
  for (Eigen::Index i = 0; i < ns; ++i) {
    const ContactLaw& ci = contacts_[static_cast<size_t>(stuck_[static_cast<size_t>(i)])];
    w(i) = share_weight(stuck_[static_cast<size_t>(i)], t);
    r_(i) = ci.sliding_acceleration(t, acc);  // acc = C f + c_0: the gears already solved without λ
    for (Eigen::Index j = 0; j < ns; ++j) {
      const VelocityRow& rj = contacts_[static_cast<size_t>(stuck_[static_cast<size_t>(j)])].row;
      for (int p = 0; p < ci.row.terms; ++p)
        for (int q = 0; q < rj.terms; ++q) S(i, j) += ci.row.w[p] * C(ci.row.body[p], rj.body[q]) * rj.w[q];
    }
  }
  if (S.rows() != cs.S.rows() || S != cs.S || w != cs.w) {
    cs.P = weighted_solution(S, w, false);
    cs.S = S;
    cs.w = w;
  }
  lam_.noalias() = cs.P * r_;
  // The one-sided rule (docs/hybrid.md): a freewheel loaded against its lock takes no share while
  // the others carry every load alone.
  bool masked = false;
  if (ns >= 2)
    for (Eigen::Index j = 0; j < ns; ++j) {
      const ContactLaw& c = contacts_[static_cast<size_t>(stuck_[static_cast<size_t>(j)])];
      if (c.lock != 0 && c.lock * lam_(j) < 0.0) w(j) = 0.0, masked = true;
    }
  if (masked)
    if (const Eigen::MatrixXd P = weighted_solution(S, w, true); P.size() > 0) lam_ = P * r_;
  // A stuck gear whose locking range this split breaks (or a contact beyond its limit beside it): the
  // gear as bounded rows of the split (analysis/gear_split.hpp).
  std::fill(gear_joint_.begin(), gear_joint_.end(), 0);
  split_stuck_gears(t, acc, im, ka, kb);
  // The loads on the bodies: the gears' sides through their law, the others through 1/I.
  std::vector<double>& df = cs.df;
  df.assign(static_cast<size_t>(n_), 0.0);
  for (Eigen::Index j = 0; j < ns; ++j) {
    const ContactLaw& c = contacts_[static_cast<size_t>(stuck_[static_cast<size_t>(j)])];
    fc[stuck_[static_cast<size_t>(j)]] = lam_(j);
    for (int p = 0; p < c.row.terms; ++p) df[static_cast<size_t>(c.row.body[p])] -= c.row.w[p] * lam_(j);
    if (c.grounded) *src -= lam_(j) * c.surface_velocity(t);
  }
  for (int x = 0; x < n_; ++x)
    if (gear_of_body_[static_cast<size_t>(x)] < 0) acc[x] += im[x] * df[static_cast<size_t>(x)];
  for (int g = 0; g < ng_; ++g) {
    const auto gi = static_cast<size_t>(g);
    const LossyGearLaw& k = gears_[gi];
    const double va = y[n_ + k.a];
    *fric -= LossyGearLaw::loss_power(gear_t_[gi], va);
    gear_fa_[gi] += df[static_cast<size_t>(k.a)];
    gear_fb_[gi] += df[static_cast<size_t>(k.b)];
    gear_t_[gi] = k.solve(gear_mode_[gi], gear_fa_[gi], gear_fb_[gi], inertia_[static_cast<size_t>(k.a)],
                          inertia_[static_cast<size_t>(k.b)], va);
    *fric += LossyGearLaw::loss_power(gear_t_[gi], va);
    acc[k.a] = gear_mode_[gi] == GearMode::stuck ? 0.0 : gear_t_[gi].acc;
    acc[k.b] = acc[k.a] / k.i;
  }
  enforce_coupled(t, acc, im, false);
  if (!locks_.empty()) share_locks(t, fc);
}

bool DriveSystem::split_stuck_gears(double t, const double* acc, const double* im, const std::vector<double>& ka,
                                    const std::vector<double>& kb) {
  // The stuck coupled gears the split can take as rows: both sides with inertia, no prescribed side.
  std::vector<int> J;
  for (int g = 0; g < ng_; ++g) {
    const auto gi = static_cast<size_t>(g);
    const LossyGearLaw& k = gears_[gi];
    if (gear_mode_[gi] != GearMode::stuck || !coupled_gear(g) || gear_motion_[gi] >= 0 || !std::isfinite(im[k.a]) ||
        !std::isfinite(im[k.b]) || im[k.a] <= 0.0 || im[k.b] <= 0.0)
      continue;
    J.push_back(g);
  }
  if (J.empty()) return false;
  const auto ns = static_cast<Eigen::Index>(stuck_.size());
  auto lock_owned = [&](Eigen::Index j) { return locks_.owner[static_cast<size_t>(stuck_[static_cast<size_t>(j)])] >= 0; };
  // 1. Does the split as it stands hold? Every contact within its limits, every gear of J with its
  //    friction to the ground at its limits within its locking range (gear_lock.hpp's pair events).
  bool holds = true;
  for (Eigen::Index j = 0; j < ns && holds; ++j)
    holds = lock_owned(j) || contacts_[static_cast<size_t>(stuck_[static_cast<size_t>(j)])].holds(lam_(j), t, true);
  for (size_t q = 0; q < J.size() && holds; ++q) {
    const auto gi = static_cast<size_t>(J[q]);
    const LossyGearLaw& k = gears_[gi];
    double F[2] = {gear_fa_[gi], gear_fb_[gi]};
    for (Eigen::Index j = 0; j < ns; ++j) {
      if (lock_owned(j)) continue;
      const VelocityRow& row = contacts_[static_cast<size_t>(stuck_[static_cast<size_t>(j)])].row;
      for (int p = 0; p < row.terms; ++p)
        if (row.body[p] == k.a || row.body[p] == k.b) F[row.body[p] == k.a ? 0 : 1] -= row.w[p] * lam_(j);
    }
    if (const int li = locks_.of_gear[gi]; li >= 0)
      holds = locks_.locks[static_cast<size_t>(li)].start(k, contacts_.data(), t, F[0], F[1], 0.0) == 0;
    else
      holds = k.start_margin(+1, F[0], F[1]) >= 0.0 && k.start_margin(-1, F[0], F[1]) >= 0.0;
  }
  if (holds) return false;
  // 2. The split with the gears' rows: e_a and i e_b per gear of J, their bodies with their own 1/I.
  std::vector<int> in_j(static_cast<size_t>(ng_), 0);
  for (int g : J) in_j[static_cast<size_t>(g)] = 1;
  auto C = [&](int x, int z) {  // ∂acc_x / ∂f_z (solve_coupled's C, J's gears free)
    const int g = gear_of_body_[static_cast<size_t>(x)];
    if (g < 0 || in_j[static_cast<size_t>(g)] != 0) return x == z ? im[x] : 0.0;
    const LossyGearLaw& k = gears_[static_cast<size_t>(g)];
    if (z != k.a && z != k.b) return 0.0;
    const double kz = z == k.a ? ka[static_cast<size_t>(g)] : kb[static_cast<size_t>(g)];
    return x == k.a ? kz : kz / k.i;
  };
  std::vector<double> acc0(acc, acc + n_);  // the accelerations without λ, J's gears not holding
  std::vector<VelocityRow> rows;
  std::vector<const LossyGearLaw*> laws;
  for (int k : stuck_) rows.push_back(contacts_[static_cast<size_t>(k)].row);
  for (int g : J) {
    const LossyGearLaw& k = gears_[static_cast<size_t>(g)];
    acc0[static_cast<size_t>(k.a)] = gear_fa_[static_cast<size_t>(g)] * im[k.a];
    acc0[static_cast<size_t>(k.b)] = gear_fb_[static_cast<size_t>(g)] * im[k.b];
    VelocityRow ra, rb;
    ra.terms = rb.terms = 1;
    ra.body[0] = k.a, ra.w[0] = 1.0;
    rb.body[0] = k.b, rb.w[0] = k.i;
    rows.push_back(ra), rows.push_back(rb);
    laws.push_back(&k);
  }
  const auto nr = static_cast<Eigen::Index>(rows.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(nr, nr);
  Eigen::VectorXd r(nr), w(nr), lo(nr), hi(nr);
  for (Eigen::Index i = 0; i < nr; ++i) {
    const VelocityRow& ri = rows[static_cast<size_t>(i)];
    if (i < ns) {
      const int k = stuck_[static_cast<size_t>(i)];
      r(i) = contacts_[static_cast<size_t>(k)].sliding_acceleration(t, acc0.data());
      w(i) = share_weight(k, t);
      detail::stuck_bounds(contacts_[static_cast<size_t>(k)], t, &lo(i), &hi(i));
    } else {
      r(i) = ri.w[0] * acc0[static_cast<size_t>(ri.body[0])];
      w(i) = detail::kGearSplitWeight;
      lo(i) = -HUGE_VAL, hi(i) = HUGE_VAL;
    }
    for (Eigen::Index j = 0; j < nr; ++j) {
      const VelocityRow& rj = rows[static_cast<size_t>(j)];
      for (int p = 0; p < ri.terms; ++p)
        for (int q = 0; q < rj.terms; ++q) A(i, j) += ri.w[p] * C(ri.body[p], rj.body[q]) * rj.w[q];
    }
  }
  const auto split = detail::gear_bounded_split(A, r, w, lo, hi, laws);
  if (!split) return false;  // no split within the bounds: the decision releases what is overloaded
  // The contacts' loads; the gears' friction to the ground is split by share_locks at these forces
  // (a split within its limits exists: the one above).
  for (Eigen::Index j = 0; j < ns; ++j) lam_(j) = lock_owned(j) ? 0.0 : (*split)(j);
  for (int g : J) gear_joint_[static_cast<size_t>(g)] = 1;
  return true;
}

void DriveSystem::enforce_coupled(double t, double* x, const double* im, bool velocities) const {
  // Bodies held: the gears' (their law holds them on x_a = i x_b), then along the stuck contacts.
  std::vector<char> held(static_cast<size_t>(n_), 0);
  for (int i = 0; i < n_; ++i) held[static_cast<size_t>(i)] = gear_of_body_[static_cast<size_t>(i)] >= 0;
  for (size_t pass = 0; pass <= stuck_.size(); ++pass) {
    bool changed = false;
    for (int k : stuck_) {
      const ContactLaw& c = contacts_[static_cast<size_t>(k)];
      if (c.general) continue;
      const auto a = static_cast<size_t>(c.a);
      if (c.b < 0) {
        if (!held[a]) x[c.a] = velocities ? c.surface_velocity(t) : c.surface_acceleration(t), held[a] = 1, changed = true;
        continue;
      }
      const auto b = static_cast<size_t>(c.b);
      if (held[a] && !held[b]) x[c.b] = x[c.a], held[b] = 1, changed = true;
      else if (held[b] && !held[a]) x[c.a] = x[c.b], held[a] = 1, changed = true;
    }
    if (!changed) break;
  }
  // The rest: the momentum-weighted mean of each stuck pair (enforce_stuck); general rows (gear joints)
  // keep the rounding of λ.
  for (int k : stuck_) {
    const ContactLaw& c = contacts_[static_cast<size_t>(k)];
    if (c.general || c.b < 0 || held[static_cast<size_t>(c.a)] || held[static_cast<size_t>(c.b)]) continue;
    const double ia = im[c.a], ib = im[c.b];
    x[c.a] = x[c.b] = (ib * x[c.a] + ia * x[c.b]) / (ia + ib);
  }
}

}  // namespace machdyn
