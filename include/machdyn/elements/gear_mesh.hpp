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
  [[nodiscard]] bool settles(int, int now) const override { return now >= 16; }
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
