#pragma once
/// @file
/// The law of a lossy gear (model/model.hpp LossyGear; Modelica's Rotational.Components.LossyGear),
/// stated once and used by the drive system (right-hand side, event functions, torques), the mode
/// decision of the run, the outputs and the linear models.
///
/// Kinematics: v_a = i v_b (an ideal gear, rigid; i in the two bodies' coordinates).
/// Torques, in a's coordinate (positive along +q_a):
///   X   the torque side a delivers into the gear (MSL's flange_a.tau): body a receives −X;
///   Y   the torque the gear delivers to side b:                        body b receives +i Y
///       (power Y v_a = (i Y) v_b).
/// The loss torque is X − Y, its power (X − Y) v_a ≥ 0 the heat.
///
/// Mesh and bearings (MSL's documentation, Pelchen et al. 2002): bearing friction τ_bf,a before the
/// mesh on a's side and τ_bf,b after it on b's side (in a's coordinate), a mesh of efficiency
/// η_mf1 while a drives and η_mf2 while b drives. With s = sign(v_a) and the mesh torques
/// X̃ = X − s τ_bf,a (into the mesh) and Ỹ = Y + s τ_bf,b (out of it):
///   a drives (s X̃ > 0):  Ỹ = η_mf1 X̃      ⇔  Y = η_mf1 X − s τ_bf1
///   b drives (s X̃ < 0):  X̃ = η_mf2 Ỹ      ⇔  X = η_mf2 (Y + s τ_bf2)
/// with the resultant bearing torques of MSL's lossTable τ_bf1 = η_mf1 τ_bf,a + τ_bf,b and
/// τ_bf2 = τ_bf,a/η_mf2 + τ_bf,b; so τ_bf,a = η_mf2 (τ_bf1 − τ_bf2)/(η_mf1 η_mf2 − 1) (= τ_bf1/2 when
/// η_mf1 = η_mf2 = 1, then τ_bf1 = τ_bf2), τ_bf,b = τ_bf1 − η_mf1 τ_bf,a. These are MSL's quadrant
/// losses X − Y = (1 − η_mf1) X + s τ_bf1 and (1 − 1/η_mf2) X + s τ_bf2, written so that η_mf2 = 0
/// (self-locking: b cannot drive a, X = 0) needs no division.
///
/// Equation of motion in a mode. Let F_a, F_b be the generalized forces of everything else on the two
/// bodies, I_a, I_b their inertias, and in a's coordinate J_b = I_b/i², F_b' = F_b/i (a = v_a'):
///   side a:  I_a a = F_a − X        side b:  J_b a = F_b' + Y
/// Eliminating X and Y with the mode's relation gives one equation, linear in a:
///   a drives:  (η_mf1 I_a + J_b) a = η_mf1 F_a + F_b' − s τ_bf1
///   b drives:  (I_a + η_mf2 J_b) a = F_a + η_mf2 F_b' − s η_mf2 τ_bf2
///   stuck:     a = 0, X = F_a, Y = −F_b'       (held while the torques lie in the locking range)
/// and then X = F_a − I_a a, Y = J_b a − F_b'. The driving side in a rolling direction is unique:
/// with F̃_a = F_a − s τ_bf,a, F̃_b = F_b' − s τ_bf,b both modes give X̃ the sign of
/// D = F̃_a J_b − I_a F̃_b (X̃ = D/(η_mf1 I_a + J_b), resp. η_mf2 Ỹ with Ỹ = D/(I_a + η_mf2 J_b)), so the
/// switch between them is continuous in a (an event, no jump).
///
/// Stuck mode (v_a = 0): the gear holds the torque X − Y = F_a + F_b' (MSL's sa) while it lies in
/// [τ_loss,min, τ_loss,max], the losses at v = 0⁻ and 0⁺ with the quadrant of F̃_a (MSL's
/// tauLossMax_p, tauLossMin_m). Equivalently it starts in direction s exactly when the numerator N_s of
/// that direction's equation above has s N_s > 0 (the side chosen by s F̃_a > 0: a drives, else b):
///   start margin m_s = −s N_s  (a drives)   or   −s N_s / η_mf2  (b drives; −s N_s when η_mf2 = 0)
/// which is MSL's τ_loss,max − τ_h (s = +1) and τ_h − τ_loss,min (s = −1), continuous where F̃_a
/// passes 0. At most one direction can start (the locking range is never empty for η ≤ 1).
///
/// Events (≥ 0 while the mode holds): stuck: m_{+1}, m_{−1}; rolling in s: s v_a (comes to rest)
/// and s X̃ (a drives) or −s Ỹ (b drives): the driving side changes. Mode decision: rolling when
/// v_a ≠ 0, in the direction of v_a, with the driving side of sign(D); at v_a = 0 a start in the
/// direction whose margin is negative (beyond a rounding allowance unless its event fired), else stuck.
///
/// Prescribed side (a body with `motion:`, elements/prescribed_motion.hpp, on one side; compile refuses
/// both): a = v_a' is given (i a_b when b is), so the gear's kinematics make the other side prescribed
/// too, and only the torques and the mode remain. The free side's own equation gives its torque, the
/// mode's relation the prescribed side's (whose source force R closes its equation and carries X or
/// −i Y with everything else on it):
///   a prescribed:  Y = J_b a − F_b',  Ỹ = Y + s τ_bf,b;  a drives: X̃ = Ỹ/η_mf1, b drives: X̃ = η_mf2 Ỹ
///   b prescribed:  X = F_a − I_a a,   X̃ = X − s τ_bf,a;  a drives: Ỹ = η_mf1 X̃, b drives: Ỹ = X̃/η_mf2
/// (X = X̃ + s τ_bf,a, Y = Ỹ − s τ_bf,b). s = sign(v_a), at v_a = 0 sign(a) (the motion leaves rest at
/// once); a drives while s X̃ > 0, which is s Ỹ > 0 (the known one decides: no acceleration depends
/// on the side, the switch is continuous in X and Y). b prescribed with b driving needs η_mf2 > 0
/// (compile refuses a prescribed b with η_mf2 = 0: a self-locking gear cannot be back-driven).
/// Stuck (v_a = 0 and a = 0): the gear holds X − Y in its locking range, X_−(Y) ≤ X ≤ X_+(Y) with X_s
/// the rolling relation of direction s at v = 0 (increasing in Y, X_− ≤ X_+); of the holding torques
/// the source delivers the least force: a prescribed: X = clamp(F_a − I_a a, X_−(Y), X_+(Y)); b
/// prescribed: Y = clamp(J_b a − F_b', Y_+(X), Y_−(X)), Y_s = X_s⁻¹. So a self-locking gear (η_mf2 = 0)
/// prescribed on a holds an overhauling load at rest with X = 0 (X_− ≤ 0 ≤ X_+): no source force when
/// nothing else acts on a.
/// Mode law: the gear has no degree of freedom, so its mode is a function of t alone, decided at every
/// evaluation (decide_given): s = sign(v_a(t)), at rest sign(a(t)), stuck when both are 0 (v_a: the
/// motion's speed, a prescribed speed's state snapped onto its signal, so a hold is exactly at rest;
/// |v_a| and |a| both within a rounding allowance count as rest: 1e-12 of a prescribed speed's largest
/// |v_a|, per second for a, so a signal at rest only up to its rounding, ±1e-29, does not chatter);
/// the driving side from the known torque. A motion that leaves rest or comes to rest smoothly (v = t²,
/// a = 0 there) thus changes mode where it happens. The run's mode (the events' reference, the event
/// list) follows it: events_given is ≥ 0 while the evaluation's mode agrees with it — rolling s v_a and
/// the driving side as above (they locate the switches precisely), −1 in the slot whose part (the
/// direction, resp. the driving side) disagrees — so the integrator stops at every switch (the heat's
/// integrand has a kink there) and the run records it.
///
/// Speed tables (MSL's lossTable): η_mf1, η_mf2, τ_bf1, τ_bf2 over |v_A| (the file's body A),
/// interpolated linearly and held constant outside; their values at 0 decide the start.
/// Valid range (compile checks): η_mf1 ∈ (0, 1], η_mf2 ∈ [0, 1], τ_bf1, τ_bf2 ≥ 0, i ≠ 0.

#include <cmath>
#include <utility>
#include <vector>

#include "machdyn/elements/linear_model.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// The mode of a lossy gear: at rest (stuck) or rolling forward/backward (sign of v_a) with side a or
/// side b driving. The output column `NAME.mode` is the direction −1, 0, +1 (MSL's gear.mode).
enum class GearMode : int { backward_b = -2, backward = -1, stuck = 0, forward = 1, forward_b = 2 };

/// −1, 0, +1: the rolling direction s.
[[nodiscard]] inline int direction(GearMode md) {
  const int k = static_cast<int>(md);
  return (k > 0) - (k < 0);
}
/// Whether side b drives (power flows from b to a).
[[nodiscard]] inline bool b_drives(GearMode md) { return md == GearMode::backward_b || md == GearMode::forward_b; }
const char* to_string(GearMode md);

struct LossyGearLaw {
  const LossyGear* spec = nullptr;
  int a = 0, b = 0;
  double i = 1.0;        ///< v_a = i v_b
  double speed_scale = 1.0;  ///< |ρ_A|: |v_A| = |ρ_A| |v_a|; torques in A's coordinate × |ρ_A| are in a's

  /// The loss coefficients at one speed, bearing torques in a's coordinate.
  struct Coefficients {
    double eta1 = 1.0, eta2 = 1.0;  ///< η_mf1, η_mf2
    double bf1 = 0.0, bf2 = 0.0;    ///< τ_bf1, τ_bf2
    double bf_a = 0.0, bf_b = 0.0;  ///< τ_bf,a, τ_bf,b (the split, header)
  };
  /// The gear's torques in a mode and the acceleration a of body a.
  struct Torques {
    double X = 0.0, Y = 0.0, acc = 0.0;
  };

  static LossyGearLaw of(const LossyGear& g);

  /// The coefficients at body a's speed v_a.
  [[nodiscard]] Coefficients at(double v_a) const;
  /// Mode md's torques and acceleration for the forces F_a, F_b (everything else on a and b), the
  /// inertias I_a, I_b and the speed v_a.
  [[nodiscard]] Torques solve(GearMode md, double Fa, double Fb, double Ia, double Ib, double va) const;
  /// The two event functions of mode md (header), ≥ 0 while it holds.
  void events(GearMode md, double Fa, double Fb, double Ia, double Ib, double va, const Torques& T, double* ev) const;
  /// The mode at this state: rolling in the direction of v_a ≠ 0 with its consistent driving side,
  /// at rest a start where a margin is below −`tol`, else stuck.
  [[nodiscard]] GearMode decide(double Fa, double Fb, double Ia, double Ib, double va, double tol) const;
  /// A rounding allowance for the start margins: 1e-12 of the torques involved.
  [[nodiscard]] double allowance(double Fa, double Fb) const;
  /// Adds the gear's torques to the generalized forces: −X on a, +i Y on b.
  void apply(const Torques& T, double* f) const {
    f[a] -= T.X;
    f[b] += i * T.Y;
  }
  /// The heat: the power of the loss torque, (X − Y) v_a (W).
  [[nodiscard]] static double loss_power(const Torques& T, double va) { return (T.X - T.Y) * va; }
  /// X at the file's body A, in A's own coordinate (MSL's flange_a.tau), N·m or N.
  [[nodiscard]] double torque_at_a(const Torques& T) const { return T.X / spec->rho_a; }
  /// The torque side b exerts on the gear, −i Y, at the file's body B in B's coordinate (MSL's
  /// flange_b.tau; at rest the holding torque of a self-locking gear), N·m or N.
  [[nodiscard]] double torque_at_b(const Torques& T) const { return -i * T.Y / spec->rho_b; }
  /// A prescribed side (header "Prescribed side"): mode md's torques when body a (`b_given` false) or
  /// body b follows a given motion; `acc` is a = v_a' (i a_b for b), returned as T.acc in every mode.
  [[nodiscard]] Torques solve_given(GearMode md, bool b_given, double acc, double Fa, double Fb, double Ia, double Ib,
                                    double va) const;
  /// The mode of a gear with a prescribed side at (a, v_a) (header "Mode law"): rolling in sign(v_a) (at
  /// rest sign(a)) on the side the known torque drives, stuck when both are 0, or both within the
  /// rounding allowances |v_a| ≤ rest_v, |a| ≤ rest_a.
  [[nodiscard]] GearMode decide_given(bool b_given, double acc, double Fa, double Fb, double Ia, double Ib, double va,
                                      double rest_v = 0.0, double rest_a = 0.0) const;
  /// Its two event functions (header "Mode law") for the run's mode md, the evaluation's mode `now`
  /// (decide_given), its torques T (solve_given in `now`) and v_a: ≥ 0 while now agrees with md.
  void events_given(GearMode md, GearMode now, double va, const Torques& T, double* ev) const;
  /// Linear terms: for modes a lossy gear is the ideal gear, the constraint row v_a − i v_b = 0.
  void add_linear(LinearModel& lin) const;
  /// The rows of mode md as constraints (the quasi-static load, analysis/static_loads.hpp; the
  /// equilibrium start): the ratio row v_a − i v_b = 0 in every mode and, stuck (a = 0), the rest row
  /// v_a = 0 (both sides at rest). A rolling gear's reaction is not along its row: see reaction().
  void add_linear(GearMode md, LinearModel& lin) const;

  /// The torque relation of a rolling mode md at v_a, p X − q Y = c (header "Mesh and bearings"):
  ///   a drives:  η_mf1 X − Y = s τ_bf1        (p = η_mf1, q = 1,      c = s τ_bf1)
  ///   b drives:  X − η_mf2 Y = s η_mf2 τ_bf2  (p = 1,     q = η_mf2,  c = s η_mf2 τ_bf2)
  /// p > 0 in both; with X = F_a − I_a a, Y = J_b a − F_b' it gives the mode's equation of motion
  /// (p I_a + q J_b) a = p F_a + q F_b' − c (solve, start_margin).
  struct Relation {
    double p = 1.0, q = 1.0, c = 0.0;
  };
  [[nodiscard]] Relation relation(GearMode md, double va) const;
  /// A rolling mode md at v_a as a constraint with its own reaction (the quasi-static load): the gear
  /// keeps its ratio (add_linear's row, G) and its torques satisfy relation(): X = q μ + c/p, Y = p μ
  /// for one reaction μ, so its forces on the bodies (apply: −X on a, +i Y on b) are H μ + f0 with
  /// H = {a: −q, b: i p} and f0 = −c/p on a. H ≠ G: the reaction does work (the loss (X − Y) v_a).
  struct Reaction {
    std::vector<std::pair<int, double>> H;  ///< (body, weight) pairs, as a row of LinearModel::G
    double f0_a = 0.0;                      ///< the constant force on body a (N·m or N)
  };
  [[nodiscard]] Reaction reaction(GearMode md, double va) const;

  /// The start margin m_s of direction s at rest (header), ≥ 0 while the gear holds against a start
  /// in s. Piecewise linear in (F_a, F_b/i) with one kink, where the driving side changes (s F̃_a = 0);
  /// m_{+1} never increases and m_{−1} never decreases as F_a or F_b/i grows (slopes −η_mf1 or
  /// −1/η_mf2 (−1 when η_mf2 = 0) in F_a, −1 in F_b/i; the opposite signs for s = −1).
  [[nodiscard]] double start_margin(int s, double Fa, double Fb) const;
  /// The θ in [θ0, θ1] where m_s(F_a + θ dF_a, F_b + θ dF_b) = 0, for a margin that changes sign on
  /// [θ0, θ1] and is monotone along it: solved linearly on the side of the kink that holds the root.
  [[nodiscard]] double margin_root(int s, double Fa, double Fb, double dFa, double dFb, double th0, double th1) const;
  /// The rolling mode in direction s = ±1 with its consistent driving side (sign of D, header) at v_a.
  [[nodiscard]] GearMode rolling(int s, double Fa, double Fb, double Ia, double Ib, double va) const;

 private:
  /// The driving side while rolling in s: true when b drives (sign of D, header).
  [[nodiscard]] bool b_side_drives(int s, const Coefficients& c, double Fa, double Fb, double Ia, double Ib) const;
};

}  // namespace machdyn
