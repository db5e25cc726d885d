#include "analysis/gear_split.hpp"

#include <cmath>

#include "machdyn/analysis/bounded_split.hpp"

namespace machdyn::detail {
namespace {

/// The rolling mode of direction s with side b driving (b) or a.
GearMode gear_split_mode(int s, bool b) {
  return s > 0 ? (b ? GearMode::forward_b : GearMode::forward) : (b ? GearMode::backward_b : GearMode::backward);
}

}  // namespace

bool gear_holds(const LossyGearLaw& g, double X, double Y, double tol) {
  // X_−(Y) ≤ X ≤ X_+(Y): each side a union over the two driving sides (header).
  bool fwd = false, bwd = false;
  for (int s : {+1, -1})
    for (bool b : {false, true}) {
      const LossyGearLaw::Relation rl = g.relation(gear_split_mode(s, b), 0.0);
      const bool ok = s * (rl.p * X - rl.q * Y - rl.c) <= tol;
      (s > 0 ? fwd : bwd) = (s > 0 ? fwd : bwd) || ok;
    }
  return fwd && bwd;
}

std::optional<Eigen::VectorXd> gear_friction_split(const LossyGearLaw& g, double Fa, double Fb, const Eigen::VectorXd& ea,
                                                   const Eigen::VectorXd& eb, const Eigen::VectorXd& w,
                                                   const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  const Eigen::Index n = ea.size();
  if (gear_holds(g, Fa, -Fb / g.i, 0.0)) return Eigen::VectorXd::Zero(n);
  // No row of the dynamics: one zero row (rank 0), the split's null space every λ.
  const Eigen::MatrixXd A = Eigen::MatrixXd::Zero(1, n);
  const Eigen::VectorXd r = Eigen::VectorXd::Zero(1);
  Eigen::MatrixXd D(2, n);
  Eigen::VectorXd e(2);
  std::optional<Eigen::VectorXd> best;
  double best_cost = HUGE_VAL;
  for (int code = 0; code < 4; ++code) {
    for (int k = 0; k < 2; ++k) {  // k = 0: s = +1 on side σ₊; k = 1: s = −1 on side σ₋
      const int s = k == 0 ? 1 : -1;
      const LossyGearLaw::Relation rl = g.relation(gear_split_mode(s, ((code >> k) & 1) != 0), 0.0);
      // s (p X − q Y − c) ≤ 0 with X = F_a + e_a·λ, Y = −(F_b + e_b·λ)/i:
      //   (−s p e_a − s q e_b / i)·λ ≥ −s c + s p F_a + s q F_b / i.
      D.row(k) = (-s * rl.p) * ea.transpose() - (s * rl.q / g.i) * eb.transpose();
      e(k) = -s * rl.c + s * rl.p * Fa + s * rl.q * Fb / g.i;
    }
    const auto lam = bounded_split(A, r, w, lo, hi, D, e);
    if (!lam) continue;
    const double cost = (lam->array() / w.array()).square().sum();
    if (cost < best_cost) best_cost = cost, best = lam;
  }
  return best;
}

std::optional<Eigen::VectorXd> gear_bounded_split(const Eigen::MatrixXd& A, const Eigen::VectorXd& r, const Eigen::VectorXd& w,
                                                  const Eigen::VectorXd& lo, const Eigen::VectorXd& hi,
                                                  const std::vector<const LossyGearLaw*>& gears) {
  const auto ng = static_cast<Eigen::Index>(gears.size());
  const Eigen::Index n = A.cols(), first = n - 2 * ng;
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(2 * ng, n);
  Eigen::VectorXd e(2 * ng);
  std::optional<Eigen::VectorXd> best;
  double best_cost = HUGE_VAL;
  long pieces = 1;
  for (Eigen::Index g = 0; g < ng; ++g) pieces *= 4;
  for (long code = 0; code < pieces; ++code) {
    long c = code;
    for (Eigen::Index g = 0; g < ng; ++g, c /= 4) {
      const Eigen::Index jx = first + 2 * g, jr = jx + 1;
      for (int k = 0; k < 2; ++k) {  // k = 0: s = +1 on side σ₊; k = 1: s = −1 on side σ₋
        const int s = k == 0 ? 1 : -1;
        const bool b = ((c >> k) & 1) != 0;
        const LossyGearLaw::Relation rl = gears[static_cast<size_t>(g)]->relation(gear_split_mode(s, b), 0.0);
        // s (p X − q Y − c) ≤ 0 with X = λ_X, Y = −λ_ρ:  −s p λ_X − s q λ_ρ ≥ −s c.
        const Eigen::Index m = 2 * g + k;
        D(m, jx) = -s * rl.p;
        D(m, jr) = -s * rl.q;
        e(m) = -s * rl.c;
      }
    }
    const auto lam = bounded_split(A, r, w, lo, hi, D, e);
    if (!lam) continue;
    const double cost = (lam->array() / w.array()).square().sum();
    if (cost < best_cost) best_cost = cost, best = lam;
  }
  return best;
}

}  // namespace machdyn::detail
