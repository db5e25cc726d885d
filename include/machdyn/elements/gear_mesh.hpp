#pragma once
/// @file
/// The law of an elastic gear mesh with backlash and efficiency (`type: gear-mesh` under `links:`,
/// `between: [pinion, wheel]`; Simscape's Simple Gear with meshing losses and a compliant mesh, MSL's
/// ElastoBacklash in series with a LossyGear's meshing efficiency), stated once as an Element between
/// two rotational bodies (model/element.hpp):
///
///   kinematics   ideal mesh φ₁ = i φ₂ (i = r_w/r_p > 0; the project's gear convention q_a = i q_b,
///                the sense reversal of an external mesh taken into the wheel's coordinate)
///   deflection   Δ = φ₁ − i φ₂ (rad at the pinion; s = r_p Δ along the line of action)
///   tooth moment τ(Δ, Δ') at the pinion (N·m), the flank law of a gap link (elements/link.hpp,
///                `elasto-backlash`, MSL's ElastoBacklash), backlash b total, centred on Δ = 0:
///                  |Δ| < b/2 (free play):  τ = 0
///                  + flank, e = Δ − b/2:   τ = c e + min(c e, d Δ') ≥ 0 (contact ends where it reaches 0)
///                  − flank, e = Δ + b/2:   τ = c e + max(c e, d Δ') ≤ 0
///                b = 0: τ = c Δ + d Δ' (both flanks in contact, no free play)
///   torques      ideal:               M₁ = −τ,    M₂ = i τ        (virtual work: −τ δΔ)
///                pinion drives (P₁ = τ ω₁ > 0 and P₂ = τ i ω₂ > 0):  M₁ = −τ,   M₂ = η i τ
///                wheel drives  (P₁ < 0 and P₂ < 0):                  M₁ = −η τ, M₂ = i τ
///                neither (P₁, P₂ of opposite signs: both bodies feed the teeth or both draw from
///                them; no power passes through the mesh): the ideal torques
///   loss         P_loss = (1 − η) P₂ (pinion drives), −(1 − η) P₁ (wheel drives), 0 (neither): the
///                efficiency applied in the direction of the power flow, (1 − η)·|transmitted power|
///                ≥ 0 with the transmitted power the driven side's ideal power
///   energy       V = ½ c e² on a flank (0 in the free play), dV/dt = c e Δ'
///   heat         P_heat = (damping part of τ)·Δ' + P_loss ≥ 0
/// so that M₁ ω₁ + M₂ ω₂ = −dV/dt − P_heat exactly (0 = P_source).
/// c > 0 the mesh stiffness (N·m/rad at the pinion; c_lin r_p² from N/m along the line of action),
/// d ≥ 0 its damping (N·m·s/rad; d_lin r_p²), b ≥ 0 (rad at the pinion; b_lin/r_p), 0 < η ≤ 1.
///
/// Modes (an int): the flank g ∈ {−1, 0, +1} (GapMode: − flank, free play, + flank; without
/// backlash the sign of τ) and the assumed signs of ω₁ and ω₂ (σ₁, σ₂), which with the sign of τ
/// fix the power direction above. Events (each ≥ 0 while the mode holds):
///   free play:  g₀ = the gap's (reaches the + flank), g₁ = (reaches the − flank)
///   on a flank: g₀ = σ_τ (c e + d Δ') (contact ends; without backlash: τ changes sign),
///               g₁ = min(σ₁ ω₁, σ₂ i ω₂) (a body reverses: the power direction changes)
/// Rule at a switch: closing on a flank or a body reversing, the new signs σ are the bodies' speed
/// signs after the instant (a speed at 0 takes the sign of its acceleration); at the start every sign
/// is read from the state (a speed at 0, and without backlash τ at 0: +). A run at rest (ω₁ = ω₂ =
/// 0) keeps its mode. In the free play the signs are kept (they act on nothing there; the contact
/// reads them again).
///
/// Held flank (η < 1): body j at rest (ω_j = 0) passes no power, so while the other body o drives
/// (T_o ω_o < 0: it feeds the teeth; T_j the ideal torque on j, −τ on the pinion, i τ on the wheel)
/// j's torque is any value in [η T_j, T_j] (mirrored for T_j < 0) — those of its two neighbouring
/// modes, j driven and j driving. j is *held* there: its torque is clamp(−R_j, η T_j, T_j), R_j
/// everything else on j but the stuck set's loads (ElementMotion::load, Element::held_port), o gets
/// its ideal torque T_o, no loss. Inside the range ω_j stays 0; at a bound the clamp is the torque of
/// the mode j leaves rest into (η T_j where it is driven, T_j where it drives), and a contact stuck on
/// j carries what the mesh does not (the mesh holds what its range allows, the friction the rest).
/// Entered where a body reaches rest (or is at rest when the teeth meet, or at the start) with
/// −R_j in the range while o drives; events while held: g₀ as on a flank (τ reaching 0), g₁ =
/// min(the other's driving σ ω_o, the range's margin min(−R_j − lo, hi + R_j) with R_j now
/// including the stuck set's loads, so a stuck contact carrying the rest keeps it ≥ 0, + 1e-12 of
/// its scale). Leaving: the margin → j starts in sign(R_j + clamp); o stops driving → o reverses
/// and j takes T_j on both sides of rest (sign(R_j + T_j)). Modes: bits 5–6 the held body (1 pinion,
/// 2 wheel), bit 4 a switch to be settled, bits 0–3 mode_of().
/// Valid for two rotational bodies; nothing is thrown.

#include "machdyn/elements/link.hpp"
#include "machdyn/model/element.hpp"

namespace machdyn {

class GearMesh final : public Element {
 public:
  double i = 1.0;    ///< ratio r_w/r_p, > 0
  double c = 0.0;    ///< mesh stiffness at the pinion, N·m/rad, > 0
  double d = 0.0;    ///< mesh damping at the pinion, N·m·s/rad, ≥ 0
  double b = 0.0;    ///< total backlash at the pinion, rad, ≥ 0
  double eta = 1.0;  ///< meshing efficiency η ∈ (0, 1]
  double r_p = 0.0;  ///< the pinion's base radius, m (0: given as a ratio; for the description only)

  /// The flank law (elements/link.hpp) with flanks ±b/2 (no gap for b = 0).
  [[nodiscard]] LinkLaw flanks() const;
  /// The mode from flank g and the signs σ₁, σ₂ (+1: ω ≥ 0 assumed, −1: ω ≤ 0).
  [[nodiscard]] static int mode_of(GapMode g, int s1, int s2) {
    return (static_cast<int>(g) + 1) + 3 * (s1 < 0 ? 1 : 0) + 6 * (s2 < 0 ? 1 : 0);
  }
  [[nodiscard]] static GapMode flank_of(int mode) { return GapMode((mode % 16) % 3 - 1); }
  /// The held body of `mode`: 0 none, 1 the pinion, 2 the wheel.
  [[nodiscard]] static int held(int mode) { return (mode >> 5) & 3; }
  [[nodiscard]] static int sign1(int mode) { return ((mode % 16) / 3) % 2 ? -1 : 1; }
  [[nodiscard]] static int sign2(int mode) { return (mode % 16) / 6 ? -1 : 1; }
  /// Δ and Δ' from the motion.
  [[nodiscard]] double deflection(const ElementMotion& m) const { return m.q[0] - i * m.q[1]; }
  [[nodiscard]] double deflection_rate(const ElementMotion& m) const { return m.v[0] - i * m.v[1]; }
  /// τ in `mode`.
  [[nodiscard]] double tooth_moment(const ElementMotion& m, int mode) const;
  /// The power direction of `mode`: +1 the pinion drives, −1 the wheel drives, 0 neither.
  [[nodiscard]] static int direction(int mode);

  [[nodiscard]] const char* type() const override { return "gear-mesh"; }
  [[nodiscard]] int bodies() const override { return 2; }
  [[nodiscard]] int states() const override { return 0; }
  void initial_states(double*) const override {}
  void forces(double t, const ElementMotion& m, const double* x, int mode, double* M) const override;
  void rates(double, const ElementMotion&, const double*, int, double*) const override {}
  [[nodiscard]] ElementJacobian jacobian(double t, const ElementMotion& m, const double* x, int mode) const override;
  [[nodiscard]] bool reads_positions() const override { return true; }
  [[nodiscard]] bool dissipates() const override { return d > 0.0 || eta < 1.0; }
  [[nodiscard]] double heat_power(double t, const ElementMotion& m, const double* x, int mode) const override;
  [[nodiscard]] double source_power(double, const ElementMotion&, const double*, int) const override { return 0.0; }
  [[nodiscard]] bool has_energy() const override { return true; }
  [[nodiscard]] double energy(const ElementMotion& m, const double* x, int mode) const override;
  [[nodiscard]] double stored_power(double t, const ElementMotion& m, const double* x, int mode) const override;

  [[nodiscard]] bool has_events() const override { return true; }
  void events(double t, const ElementMotion& m, const double* x, int mode, double* g) const override;
  [[nodiscard]] int mode_after(int mode, int slot) const override;
  [[nodiscard]] bool settles(int, int now) const override { return (now & 16) != 0; }
  [[nodiscard]] int held_port(int mode) const override { return held(mode) - 1; }
  /// On a lossy flank: the hold's entry and margin read the bodies' other loads (ElementMotion::load).
  [[nodiscard]] bool reads_acceleration(int mode) const override {
    return eta < 1.0 && flank_of(mode) != GapMode::open;
  }
  /// The locking range [lo, hi] of port p's torque at rest while the other drives: η T_p … T_p.
  void hold_range(double tau, int p, double* lo, double* hi) const;
  /// How far −R (R the other loads on port p's body) lies inside that range, min(−R − lo, hi + R),
  /// with 1e-12 of its scale for rounding (≥ 0: held).
  [[nodiscard]] double hold_margin(double tau, int p, double R) const;
  /// Whether the other body than port p feeds the teeth (T_o ω_o > 0 against it) on flank g with o's
  /// speed sign s_o.
  [[nodiscard]] static bool other_drives(int g, int p, int s_o) { return (p == 1 ? g : -g) * s_o > 0; }
  [[nodiscard]] int settle(double t, const ElementMotion& m, const double* x, int old, int now) const override;
  [[nodiscard]] int natural_mode(double t, const ElementMotion& m, const double* x, int current) const override;
  [[nodiscard]] const char* mode_name(int mode) const override;
  [[nodiscard]] const char* switch_kind(int now) const override;

  /// Linear model about the centred mesh on a flank (b = 0: always): the spring c and damper d over
  /// the deflection Δ = φ₁ − i φ₂ (gradient (1, −i)); in the free play nothing. η is left out.
  void add_linear(const int* body, int mode, LinearModel& lin) const override;
  [[nodiscard]] const char* state_name(int) const override { return ""; }
  [[nodiscard]] std::string state_unit(int, BodyKind) const override { return ""; }
  /// The deflection, the torque on the wheel, the heat power and the mode.
  [[nodiscard]] std::vector<std::string> output_names(BodyKind) const override;
  void outputs(double t, const ElementMotion& m, const double* x, int mode, double* out) const override;
  [[nodiscard]] std::string describe(BodyKind) const override;
  /// mesh.free_play: a force inside the backlash; mesh.loss: a negative loss.
  [[nodiscard]] std::string violated(double t, const ElementMotion& m, const double* x, int mode, const double* M,
                                     double heat, double resolution) const override;
};

}  // namespace machdyn
