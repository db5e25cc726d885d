// Two lossy gears on one body (a two-stage lossy gearbox): the joint law (header).
#include "machdyn/analysis/gear_train.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

namespace machdyn {
namespace train_detail {

int local_of(const GearTrain& tr, int body) {
  for (int j = 0; j < 3; ++j)
    if (tr.bodies[static_cast<size_t>(j)] == body) return j;
  return -1;
}

GearMode rolling_mode(int s, bool b_side) {
  return s > 0 ? (b_side ? GearMode::forward_b : GearMode::forward) : (b_side ? GearMode::backward_b : GearMode::backward);
}

int sign_of(double x) { return (x > 0.0) - (x < 0.0); }

}  // namespace train_detail

std::vector<GearTrain> find_gear_trains(const std::vector<LossyGearLaw>& gears, const std::vector<double>& inertia) {
  std::vector<GearTrain> out;
  const auto ng = static_cast<int>(gears.size());
  for (int g = 0; g < ng; ++g)
    for (int h = g + 1; h < ng; ++h) {
      const LossyGearLaw& a = gears[static_cast<size_t>(g)];
      const LossyGearLaw& b = gears[static_cast<size_t>(h)];
      int m = -1;
      for (int x : {a.a, a.b})
        if (x == b.a || x == b.b) m = x;
      if (m < 0) continue;
      GearTrain tr;
      tr.gears = {g, h};
      const int r = a.a == m ? a.b : a.a, c = b.a == m ? b.b : b.a;
      tr.bodies = {r, m, c};
      // ρ across a gear: v_a = i v_b.
      auto across = [](const LossyGearLaw& k, int from, double rho_from) { return from == k.a ? rho_from / k.i : rho_from * k.i; };
      tr.rho[0] = 1.0;
      tr.rho[1] = across(a, r, 1.0);
      tr.rho[2] = across(b, m, tr.rho[1]);
      for (int j = 0; j < 3; ++j)
        tr.inertia += inertia[static_cast<size_t>(tr.bodies[static_cast<size_t>(j)])] * tr.rho[static_cast<size_t>(j)] *
                      tr.rho[static_cast<size_t>(j)];
      out.push_back(tr);
    }
  return out;
}

TrainSolution train_roll(const GearTrain& tr, const std::vector<LossyGearLaw>& gears, int s, std::array<bool, 2> b_side,
                         const std::array<double, 3>& F, const std::array<double, 3>& I, double v_r) {
  using train_detail::local_of;
  Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
  Eigen::Vector3d rhs(F[0], F[1], F[2]);
  for (int j = 0; j < 3; ++j) A(j, 0) = I[static_cast<size_t>(j)] * tr.rho[static_cast<size_t>(j)];
  std::array<LossyGearLaw::Relation, 2> rel{};
  std::array<int, 2> sg{}, ja{};
  TrainSolution sol;
  for (int k = 0; k < 2; ++k) {
    const LossyGearLaw& law = gears[static_cast<size_t>(tr.gears[static_cast<size_t>(k)])];
    const int a = local_of(tr, law.a), b = local_of(tr, law.b);
    ja[static_cast<size_t>(k)] = a;
    sg[static_cast<size_t>(k)] = s * train_detail::sign_of(tr.rho[static_cast<size_t>(a)]);
    const GearMode md = train_detail::rolling_mode(sg[static_cast<size_t>(k)], b_side[static_cast<size_t>(k)]);
    sol.modes[static_cast<size_t>(k)] = md;
    const LossyGearLaw::Relation r = law.relation(md, tr.rho[static_cast<size_t>(a)] * v_r);
    rel[static_cast<size_t>(k)] = r;
    // −X on a (X = q μ + c/p), +i Y on b (Y = p μ).
    A(a, 1 + k) += r.q;
    rhs(a) -= r.c / r.p;
    A(b, 1 + k) -= law.i * r.p;
  }
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(A);
  if (!lu.isInvertible()) return sol;
  const Eigen::Vector3d x = lu.solve(rhs);
  sol.ok = true;
  sol.acc = x(0);
  for (int k = 0; k < 2; ++k) {
    const auto u = static_cast<size_t>(k);
    const LossyGearLaw& law = gears[static_cast<size_t>(tr.gears[u])];
    LossyGearLaw::Torques& T = sol.T[u];
    const double rho_a = tr.rho[static_cast<size_t>(ja[u])];
    T.X = rel[u].q * x(1 + k) + rel[u].c / rel[u].p;
    T.Y = rel[u].p * x(1 + k);
    T.acc = rho_a * sol.acc;
    // The power flow (header): side a drives while s X̃ ≥ 0, side b while −s Ỹ ≥ 0.
    const LossyGearLaw::Coefficients c = law.at(rho_a * v_r);
    const double Xt = T.X - sg[u] * c.bf_a, Yt = T.Y + sg[u] * c.bf_b;
    const double v = b_side[u] ? std::max(0.0, sg[u] * Yt) : std::max(0.0, -sg[u] * Xt);
    sol.violation += std::abs(rho_a) * v;
  }
  return sol;
}

TrainSolution train_rolling(const GearTrain& tr, const std::vector<LossyGearLaw>& gears, int s,
                            const std::array<double, 3>& F, const std::array<double, 3>& I, double v_r,
                            std::array<bool, 2> prefer) {
  TrainSolution best = train_roll(tr, gears, s, prefer, F, I, v_r);
  if (best.ok && best.violation == 0.0) return best;
  for (int combo = 0; combo < 4; ++combo) {
    const std::array<bool, 2> sides{(combo & 1) != 0, (combo & 2) != 0};
    if (sides == prefer) continue;
    const TrainSolution x = train_roll(tr, gears, s, sides, F, I, v_r);
    if (x.ok && (!best.ok || x.violation < best.violation)) best = x;
  }
  return best;
}

double train_start_margin(const GearTrain& tr, const std::vector<LossyGearLaw>& gears, int s,
                          const std::array<double, 3>& F, const std::array<double, 3>& I) {
  const TrainSolution x = train_rolling(tr, gears, s, F, I, 0.0);
  const double tol = train_allowance(tr, gears, F);
  // No side combination consistent: a massless shaft (I_m = 0) whose stages cannot drive it back
  // (self-locking) takes only a bounded torque from them in s, so its own load pushing against s
  // leaves its equation without a solution (the header's uniqueness needs I_m > 0 there). The train
  // cannot start in s; the margin is the least violation, > 0, 0 where a consistent solution appears
  // (docs/hybrid.md step 5).
  if (!x.ok || x.violation > tol) return x.ok ? x.violation : 0.0;
  // The solve's rounding of a margin that is 0 exactly (a self-locking stage holding the load alone:
  // α = 0) is no start: below 1e-14 of the torques it reads 0.
  const double m = -s * x.acc * tr.inertia;
  return std::abs(m) <= 1e-2 * tol ? 0.0 : m;
}

double train_allowance(const GearTrain& tr, const std::vector<LossyGearLaw>& gears, const std::array<double, 3>& F) {
  double scale = 0.0;
  for (int j = 0; j < 3; ++j) scale += std::abs(tr.rho[static_cast<size_t>(j)] * F[static_cast<size_t>(j)]);
  for (int k = 0; k < 2; ++k) {
    const LossyGearLaw& law = gears[static_cast<size_t>(tr.gears[static_cast<size_t>(k)])];
    const LossyGearLaw::Coefficients c = law.at(0.0);
    scale += std::abs(tr.rho[static_cast<size_t>(train_detail::local_of(tr, law.a))]) * (c.bf1 + c.bf2);
  }
  return 1e-12 * scale;
}

std::array<GearMode, 2> decide_train(const GearTrain& tr, const std::vector<LossyGearLaw>& gears,
                                     const std::array<double, 3>& F, const std::array<double, 3>& I, double v_r,
                                     double tol, std::array<GearMode, 2> now) {
  int s = train_detail::sign_of(v_r);
  if (s == 0) {
    if (train_start_margin(tr, gears, +1, F, I) < -tol) s = 1;
    else if (train_start_margin(tr, gears, -1, F, I) < -tol) s = -1;
    else return {GearMode::stuck, GearMode::stuck};
  }
  return train_rolling(tr, gears, s, F, I, v_r, {b_drives(now[0]), b_drives(now[1])}).modes;
}

namespace train_detail {

/// The stuck train's torques as affine functions of τ (gear 1's torque on m): X_k = X0 + τ dX, Y_k likewise.
struct Affine {
  double X0 = 0.0, dX = 0.0, Y0 = 0.0, dY = 0.0;
};

std::array<Affine, 2> stuck_affine(const GearTrain& tr, const std::vector<LossyGearLaw>& gears,
                                   const std::array<double, 3>& F) {
  std::array<Affine, 2> out{};
  const int m = tr.bodies[1];
  for (int k = 0; k < 2; ++k) {
    const LossyGearLaw& law = gears[static_cast<size_t>(tr.gears[static_cast<size_t>(k)])];
    const double Fo = F[k == 0 ? 0 : 2];
    // Gear k's torque on m: gear 1's is τ, gear 2's −F_m − τ (m at rest).
    const double on0 = k == 0 ? 0.0 : -F[1], d_on = k == 0 ? 1.0 : -1.0;
    Affine& A = out[static_cast<size_t>(k)];
    if (law.a == m) {  // −X on m; the outer body b at rest: F_o + i Y = 0
      A.X0 = -on0, A.dX = -d_on;
      A.Y0 = -Fo / law.i;
    } else {  // +i Y on m; the outer body a at rest: F_o − X = 0
      A.Y0 = on0 / law.i, A.dY = d_on / law.i;
      A.X0 = Fo;
    }
  }
  return out;
}

}  // namespace train_detail

std::array<LossyGearLaw::Torques, 2> stuck_train_torques(const GearTrain& tr, const std::vector<LossyGearLaw>& gears,
                                                         const std::array<double, 3>& F, std::array<double, 2>* interval) {
  const std::array<train_detail::Affine, 2> A = train_detail::stuck_affine(tr, gears, F);
  // The least Σ ℓ_k², ℓ_k = ρ_a,k (X_k − Y_k) = u_k + v_k τ.
  double uv = 0.0, vv = 0.0, scale = 0.0;
  for (int k = 0; k < 2; ++k) {
    const LossyGearLaw& law = gears[static_cast<size_t>(tr.gears[static_cast<size_t>(k)])];
    const double rho = tr.rho[static_cast<size_t>(train_detail::local_of(tr, law.a))];
    const train_detail::Affine& a = A[static_cast<size_t>(k)];
    const double u = rho * (a.X0 - a.Y0), v = rho * (a.dX - a.dY);
    uv += u * v, vv += v * v;
    scale += std::abs(a.X0) + std::abs(a.Y0) + std::abs(F[1]);
  }
  const double tau0 = vv > 0.0 ? -uv / vv : 0.0;
  scale = std::max(scale + std::abs(tau0), 1e-300);
  // Each gear holds while both its start margins are ≥ 0; each margin is monotone in τ (one of X, −i Y
  // varies with it): a half-line (or all, or nothing) per margin, bracketed by doubling.
  double lo = -HUGE_VAL, hi = HUGE_VAL;
  for (int k = 0; k < 2; ++k) {
    const LossyGearLaw& law = gears[static_cast<size_t>(tr.gears[static_cast<size_t>(k)])];
    const train_detail::Affine& a = A[static_cast<size_t>(k)];
    const double Fa0 = a.X0, dFa = a.dX, Fb0 = -law.i * a.Y0, dFb = -law.i * a.dY;
    for (int s : {+1, -1}) {
      auto mg = [&](double th) { return law.start_margin(s, Fa0 + th * dFa, Fb0 + th * dFb); };
      const double m0 = mg(tau0);
      // The direction in which the margin falls (it never rises on one side and falls on the other).
      const double up = mg(tau0 + scale), down = mg(tau0 - scale);
      const int fall = up < m0 || (up == m0 && down > m0) ? +1 : down < m0 ? -1 : 0;
      if (fall == 0) {  // constant
        if (m0 < 0.0) lo = HUGE_VAL, hi = -HUGE_VAL;
        continue;
      }
      // Bracket the root: from τ0 along the fall (m0 ≥ 0) or against it (m0 < 0).
      const int dir = m0 >= 0.0 ? fall : -fall;
      double step = scale, t1 = tau0 + dir * step;
      int n = 0;
      while ((mg(t1) >= 0.0) == (m0 >= 0.0) && n < 200) step *= 2.0, t1 = tau0 + dir * step, ++n;
      if (n == 200) {  // no root: the margin keeps its sign
        if (m0 < 0.0) lo = HUGE_VAL, hi = -HUGE_VAL;
        continue;
      }
      // The boundary of {m ≥ 0} by bisection: a self-locking gear's margin (η_mf2 = 0) jumps at its
      // kink (elements/lossy_gear.hpp start_margin), so no root of a continuous piece is assumed.
      double in = m0 >= 0.0 ? tau0 : t1, out = m0 >= 0.0 ? t1 : tau0;
      for (int it = 0; it < 200 && in != out; ++it) {
        const double mid = 0.5 * (in + out);
        if (mid == in || mid == out) break;
        (mg(mid) >= 0.0 ? in : out) = mid;
      }
      const double root = in;
      if (fall > 0) hi = std::min(hi, root);  // holds for τ ≤ root
      else lo = std::max(lo, root);
    }
  }
  if (interval) *interval = {lo, hi};
  const double tau = lo <= hi ? std::clamp(tau0, lo, hi) : std::isfinite(lo + hi) ? 0.5 * (lo + hi) : tau0;
  std::array<LossyGearLaw::Torques, 2> T{};
  for (int k = 0; k < 2; ++k) {
    const train_detail::Affine& a = A[static_cast<size_t>(k)];
    T[static_cast<size_t>(k)].X = a.X0 + tau * a.dX;
    T[static_cast<size_t>(k)].Y = a.Y0 + tau * a.dY;
  }
  return T;
}

}  // namespace machdyn
