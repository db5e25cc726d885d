#pragma once
/// @file
/// A two-stage lossy gearbox: two lossy gears sharing one body (the intermediate shaft m, with or
/// without inertia), a –g1– m –g2– c in any orientation of either gear. The gears' law stays in
/// elements/lossy_gear.hpp; this file only joins the two (docs/hybrid.md "Modes", step 5).
///
/// Kinematics: one degree of freedom, v_j = ρ_j v_r for the three bodies, r the first gear's outer
/// body (ρ_r = 1, ρ_b = ρ_a / i across each gear).
///
/// Rolling (v_r ≠ 0, or a start from rest in direction s of r). Each gear g rolls in s_g = s sign(ρ_a,g)
/// with a driving side, its relation p_g X_g − q_g Y_g = c_g (LossyGearLaw::relation): X_g = q_g μ_g +
/// c_g/p_g, Y_g = p_g μ_g. With the bodies' equations I_j ρ_j α = F_j − Σ_{a_g = j} X_g + Σ_{b_g = j} i_g Y_g
/// (F_j everything else on body j) these are three linear equations in (α, μ_1, μ_2). The sides are
/// the flow of power through each gear: side a drives while s_g X̃_g ≥ 0, side b while −s_g Ỹ_g ≥ 0
/// (X̃ = X − s τ_bf,a, Ỹ = Y + s τ_bf,b; elements/lossy_gear.hpp). The four side combinations are
/// enumerated and the consistent one taken (the least violation; the current one on a tie). In a fixed
/// direction every gear's output is an increasing function of its input (concave for s = +1, convex
/// for s = −1), so the train's equation in α is monotone and its solution unique: at a change of one
/// gear's side both combinations give the same α (the switch is an event, no jump). A massless shaft
/// is the exception: a stage its far side cannot drive (self-locking) passes a bounded torque in s, so
/// the shaft's own load against s may leave no consistent combination — the train cannot move in s.
///
/// At rest (v_r = 0). The train starts in s exactly when the rolling solution in s (coefficients at 0)
/// has s α_s > 0 (with no consistent solution in s it cannot start there: m_s is then the least
/// violation, > 0; docs/hybrid.md step 5). The start margins m_s = −s α_s Ī (Ī = Σ I_j ρ_j², a torque in r's coordinate) are the
/// stuck train's event functions (below 1e-14 of the torques they read 0: a self-locking stage holding
/// the load alone has α = 0 exactly, which the solve rounds); α_+ ≤ α_− (the losses oppose either
/// start), so at most one direction starts. Cost: 2 directions × 4 combinations × one 3 × 3 solve per evaluation
/// of a stuck train, 4 solves to decide a rolling one.
///
/// Stuck, the shaft torque is not fixed by the dynamics (two locked gears in series: one unknown τ,
/// gear 1's torque on m). Gear 1's outer body and gear 2's outer body fix one torque of each gear,
/// τ the other two; each gear holds while its start margins are ≥ 0 (LossyGearLaw::start_margin with
/// X = F_a, F_b = −i Y), monotone in τ: an interval of τ per gear (its ends by bisection, since a
/// self-locking gear's margin jumps at its kink). Of the common interval the train takes the τ with
/// the least Σ_g (ρ_a,g (X_g − Y_g))², the losses in r's coordinate (the nearest to lossless holding).
/// The interval is not empty exactly when both margins m_± ≥ 0 (GearTrain.MarginsAndSplitAgree).
///
/// Supported (compile checks): exactly two gears per train; no friction element, end stop or
/// prescribed motion on its bodies; inertia on the two outer bodies.

#include <array>
#include <vector>

#include "machdyn/elements/lossy_gear.hpp"

namespace machdyn {

/// Two lossy gears on one body.
struct GearTrain {
  std::array<int, 2> gears{};     ///< indices of the two gears (model order)
  std::array<int, 3> bodies{};    ///< r (gear 1's outer body), the shared body m, gear 2's outer body
  std::array<double, 3> rho{};    ///< v_j = ρ_j v_r
  double inertia = 0.0;           ///< Ī = Σ I_j ρ_j²
  /// ρ of one of its bodies.
  [[nodiscard]] double rho_of(int body) const {
    return body == bodies[0] ? rho[0] : body == bodies[1] ? rho[1] : rho[2];
  }
};

/// One solution of the train: the gears' torques (T.acc = the acceleration of each gear's body a),
/// their modes and the acceleration of r.
struct TrainSolution {
  std::array<LossyGearLaw::Torques, 2> T{};
  std::array<GearMode, 2> modes{GearMode::stuck, GearMode::stuck};
  double acc = 0.0;
  double violation = 0.0;  ///< how far the sides disagree with the power flow (0: consistent)
  bool ok = false;         ///< the linear system was regular
};

/// The trains among the gears (pairs sharing a body; compile allows no more), inertias per body.
[[nodiscard]] std::vector<GearTrain> find_gear_trains(const std::vector<LossyGearLaw>& gears,
                                                      const std::vector<double>& inertia);

/// The rolling solution in direction s of r with the sides `b_side` (true: b drives) at v_r; F and I
/// per body of the train (r, m, other).
[[nodiscard]] TrainSolution train_roll(const GearTrain& tr, const std::vector<LossyGearLaw>& gears, int s,
                                       std::array<bool, 2> b_side, const std::array<double, 3>& F,
                                       const std::array<double, 3>& I, double v_r);

/// The consistent rolling solution in direction s (header): the least violation of the four side
/// combinations, `prefer` on a tie.
[[nodiscard]] TrainSolution train_rolling(const GearTrain& tr, const std::vector<LossyGearLaw>& gears, int s,
                                          const std::array<double, 3>& F, const std::array<double, 3>& I, double v_r,
                                          std::array<bool, 2> prefer = {false, false});

/// The start margin m_s = −s α_s Ī of the train at rest (header), ≥ 0 while it holds against a start in s.
[[nodiscard]] double train_start_margin(const GearTrain& tr, const std::vector<LossyGearLaw>& gears, int s,
                                        const std::array<double, 3>& F, const std::array<double, 3>& I);

/// A rounding allowance for the margins: 1e-12 of the torques involved in r's coordinate.
[[nodiscard]] double train_allowance(const GearTrain& tr, const std::vector<LossyGearLaw>& gears,
                                     const std::array<double, 3>& F);

/// The train's modes at this state: rolling in sign(v_r) on its consistent sides; at rest a start in
/// the s whose margin is below −tol, else stuck. `now`: the current modes (kept on a tie).
[[nodiscard]] std::array<GearMode, 2> decide_train(const GearTrain& tr, const std::vector<LossyGearLaw>& gears,
                                                   const std::array<double, 3>& F, const std::array<double, 3>& I,
                                                   double v_r, double tol, std::array<GearMode, 2> now);

/// The stuck train's torques (header: the split of the shaft torque); acc = 0. `interval` (if given)
/// receives the common interval of τ (lo > hi: none).
[[nodiscard]] std::array<LossyGearLaw::Torques, 2> stuck_train_torques(const GearTrain& tr,
                                                                       const std::vector<LossyGearLaw>& gears,
                                                                       const std::array<double, 3>& F,
                                                                       std::array<double, 2>* interval = nullptr);

}  // namespace machdyn
