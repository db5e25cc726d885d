#pragma once
/// @file
/// The law of a link (spring, damper, spring–damper, with or without a gap), stated once and used
/// by every consumer: the drive system's right-hand side and Jacobian, its event functions, the
/// mode decision, energies, peaks, quasi-static loads and linear models.
///
/// Kinematics (model/model.hpp): deflection δ = p_a(q_a)/i − p_b(q_b), rad or m in b's coordinate,
/// p(q) = q for a plain end or a machine's output point (model/machine.hpp); δ̇ = j_a v_a − j_b v_b
/// with j_a = p_a′/i, j_b = p_b′. The load F acts on b with +F and on a with −F j_a (a: −F/i).
/// An end on a joint's member without inertia X (a massless flange, q_X = Σ c_j q_j over the other
/// members, model/compile_joint.hpp) makes δ a linear form over up to three bodies:
///   δ = q_a/i − w_b q_b + w_e q_e,   δ̇ likewise,   j_a = 1/i, j_b = w_b, j_e = w_e,
/// and by virtual work (F δ(δq) = Σ Q_j δq_j with the signs above) the load acts on a with −F/i, on
/// b with +F w_b and on e with −F w_e. Every law below holds with this δ unchanged: the stiffness and
/// damping terms become c j jᵀ and d j jᵀ over the three bodies (j = (1/i, −w_b, w_e)).
///
/// Law (N·m or N; positive = tension, as the paper's M12 = c1 (φ1 − φ2)):
///   no gap:        F = c (δ − δ₀) + d δ̇          (δ₀: the free length's deflection, Link::delta0; 0 by default)
///   gap, open:     F = 0                         (δ₋ < δ < δ₊)
///   closed+:       F = c (δ − δ₊) + d δ̇ ≥ 0      (positive flank δ₊ = Δ − gap_start)
///   closed−:       F = c (δ − δ₋) + d δ̇ ≤ 0      (δ₋ = −gap_start; one-sided links: δ₋ = −∞, δ₊ any sign)
/// Flank law `elasto-backlash` (capped = true; Modelica's ElastoBacklash/ElastoGap): the damping
/// force on a flank is capped at the spring force, e = δ − flank:
///   closed+:       F = c e + min(c e, d δ̇)       closed−:  F = c e + max(c e, d δ̇)
/// so F rises from 0 at first contact (no jump d δ̇) and never exceeds 2 c e. The mode still ends
/// when c e + d δ̇ reaches 0 (F and c e + d δ̇ vanish together there), so the events below hold for
/// both laws. The cap's kink (d δ̇ = c e) is a continuous law, not an event: the load is continuous
/// there and the integrator's error control resolves it, as for any other continuous nonlinearity.
/// δ₀ is the flank of a link without a gap (flank() below), so every consumer of the law (force,
/// elastic energy ½ c (δ − δ₀)², Jacobian, linear terms, equilibrium) measures from it; the load's
/// constant part −c δ₀ at δ = 0 is rest_forces() (the affine and dense paths, static loads).
/// Events (each ≥ 0 while the mode holds): closed+ ends when F reaches 0 (F ≥ 0); closed− when
/// −F reaches 0; open ends when δ reaches a flank while pressing (δ₊ − δ ≥ 0, δ − δ₋ ≥ 0; beyond the
/// flank, the pressing force −F₊ or F₋ decides).
/// Valid for c ≥ 0, d ≥ 0, i ≠ 0, Δ ≥ 0. Nothing is thrown.
///
/// Rope wound on a drum (`winding`; Link::EA > 0 with a body a, model/model.hpp). Geometry: body a
/// is the drum (angle q_a, radius R), body b the hook (x, m); n falls carry the hook over frictionless
/// sheaves, so every fall has the same tension T and the hook moves 1/n of the rope speed at the
/// drum: i = n/R, s = 1/i = R/n. Turning the drum by Δq_a winds in R Δq_a of rope, so each fall's
/// free (unstretched) length is L_f(q_a) = L_f0 − s (q_a − q_a0): positive q_a hoists. The total
/// elongation of the n falls is n e with e = δ − δ₊ (δ = s q_a − x in the hook's metres, δ₊ the
/// slack), the strain ε = n e / (n L_f) = e / L_f, so
///   T = E A e / L_f (N, per fall),  F = n T = c(q_a) e  (N, the hook load),  c(q_a) = n E A / L_f(q_a).
/// Stored energy (the strain energy of the n falls, n · E A ε² L_f / 2):
///   V(q_a, x) = ½ c(q_a) e² = n E A e² / (2 L_f).
/// The law is conservative: the generalized forces are −∂V/∂q plus the damper, so the energy books
/// balance with V. With c′ = dc/dq_a = c s / L_f (> 0: winding in stiffens) and the damper part F_d:
///   on b:  +F,                                F = c e + F_d (capped as above for elasto-backlash)
///   on a:  −F s − W,                          W = ½ c′ e² = ½ T ε R  (the winding term)
/// W is the strain energy the rope's stretch carries per radian wound in; it is O(ε) beside the
/// torque T R (ε = T/(E A) ≲ 1e-2 for steel wire rope) and makes ∂V/∂q_a exact. The damping d is
/// the hook's (N·s/m), constant. Events and modes are those above with c = c(q_a). The Jacobian
/// (second derivatives of V, c″ = 2 c s² / L_f²):
///   ∂²V/∂q_a² = c s² + 2 c′ e s + ½ c″ e²,  ∂²V/∂q_a∂x = −(c s + c′ e),  ∂²V/∂x² = c.
/// Buffer characteristics (`shaped`: Link::characteristic other than linear, model/model.hpp). A
/// buffer has one flank δ₊; with the stroke e = δ − δ₊ and its rate δ̇ the law is
///   F = F_e(e) + F_v(δ̇)                          (closed+, N or N·m; F ≥ 0 pushes the body back)
///   progressive:  F_e = c sgn(e) |e|ⁿ, n > 1      V = c |e|ⁿ⁺¹/(n + 1)
///   hydraulic:    F_e = c e (return spring ≥ 0)   V = ½ c e²;  F_v = d δ̇ + k δ̇|δ̇|
///   table:        F_e = the table (s_j, F_j) interpolated linearly (s₀ = F₀ = 0), its first slope
///                 below 0 and its last slope beyond the last point; V = ∫₀ᵉ F_e ds (exact, per piece)
/// and F_v = d δ̇ for progressive and table. The hydraulic term is signed: it resists compression
/// with k δ̇² and the return stroke with −k δ̇² (a throttle both ways), so its power k |δ̇|³ ≥ 0 is
/// always dissipated and F crosses 0 (the contact ends) where the body starts to leave the buffer.
/// Contact starts at the buffer's position (e = 0, the open mode's event) and ends where F reaches 0
/// (the closed mode's event), as for the linear law. V is the elastic energy, F_v δ̇ the dissipated
/// power. Jacobian: ∂F/∂e = F_e′(e), ∂F/∂δ̇ = d + 2 k |δ̇|. These laws are nonlinear in the state: the
/// drive system takes its general path (not the affine one) and reads the state for dF/dt.
/// Valid for L_f > 0: below L_min = 1e-3 L_f0 (the hook at the drum, outside the model) L_f is held
/// at L_min, where c′ = c″ = 0.

#include <algorithm>
#include <cmath>

#include "machdyn/elements/linear_model.hpp"
#include "machdyn/elements/modes.hpp"
#include "machdyn/model/machine.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

struct LinkLaw {
  int a = kGround, b = kGround;
  double inv_ratio = 1.0, c = 0.0, d = 0.0;
  bool gap = false;
  bool capped = false;          ///< flank law elasto-backlash (see above)
  /// The general path: an end is a machine's output point (nonlinear kinematics) or on a massless
  /// member (w_b ≠ 1 or a third body e; compile never combines the two).
  bool point = false;
  double wb = 1.0;              ///< w_b (1 except on a massless member)
  int third = kGround;          ///< the third body e, or kGround
  double w3 = 0.0;              ///< w_e
  double lo = 0.0, hi = 0.0;    ///< flanks δ₋, δ₊
  double rest = 0.0;            ///< δ₀ of a link without a gap (Link::delta0)
  const Machine* pa = nullptr;  ///< a's output point, or null (q_a itself)
  const Machine* pb = nullptr;
  bool winding = false;         ///< a rope wound on drum a: c(q_a) = K / L_f(q_a) (see above)
  double K = 0.0;               ///< n E A, N
  double L0 = 0.0;              ///< L_f0, m
  double u0 = 0.0;              ///< q_a0, where L_f = L_f0
  int falls = 1;                ///< n
  bool shaped = false;          ///< a buffer with a nonlinear characteristic (see above)
  Link::Characteristic shape = Link::Characteristic::linear;
  double cn = 0.0;              ///< progressive: c, N/mⁿ; hydraulic: the return spring c, N/m
  double expo = 1.0;            ///< progressive: n
  double kh = 0.0;              ///< hydraulic: k, N·s²/m²
  const double* ts = nullptr;   ///< table: strokes s_j (the model's Link::table_stroke)
  const double* tf = nullptr;   ///< table: forces F_j
  int tn = 0;                   ///< table: number of points

  /// F_e(e), F_e′(e) and V(e) = ∫₀ᵉ F_e of a shaped buffer (see above).
  [[nodiscard]] double shaped_force(double e) const;
  [[nodiscard]] double shaped_slope(double e) const;
  [[nodiscard]] double shaped_energy(double e) const;
  /// F_v(δ̇) = d δ̇ + k δ̇|δ̇| and ∂F_v/∂δ̇ = d + 2 k |δ̇| (k = 0 except hydraulic).
  [[nodiscard]] double damper_force(double rate) const { return d * rate + kh * rate * std::abs(rate); }
  [[nodiscard]] double damper_slope(double rate) const { return d + 2.0 * kh * std::abs(rate); }
  /// The law's force before the mode's clamp, for stroke e and rate δ̇: c(q_a) e + d δ̇, or a shaped
  /// buffer's F_e(e) + F_v(δ̇). The events and the natural mode test its sign.
  [[nodiscard]] double pressing(double e, double rate, double qa) const {
    if (shaped) [[unlikely]] return shaped_force(e) + damper_force(rate);
    return stiffness(qa) * e + d * rate;
  }

  /// The drum's position q_a from positions q (0 for the ground).
  [[nodiscard]] double drum(const double* q) const { return a >= 0 ? q[a] : 0.0; }
  /// L_f(q_a), the free length of one fall, m (winding ropes; L0 otherwise).
  [[nodiscard]] double free_length(double qa) const {
    return winding ? std::max(L0 - inv_ratio * (qa - u0), 1e-3 * L0) : L0;
  }
  /// Whether L_f is held at L_min (c′ = c″ = 0 there).
  [[nodiscard]] bool at_min_length(double qa) const { return L0 - inv_ratio * (qa - u0) < 1e-3 * L0; }
  /// c(q_a): the stiffness at drum position q_a (c itself for every other link).
  [[nodiscard]] double stiffness(double qa) const { return winding ? K / free_length(qa) : c; }
  /// c′ = dc/dq_a and c″ (0 for every other link).
  [[nodiscard]] double stiffness_slope(double qa) const {
    return winding && !at_min_length(qa) ? stiffness(qa) * inv_ratio / free_length(qa) : 0.0;
  }
  [[nodiscard]] double stiffness_curvature(double qa) const {
    const double L = free_length(qa);
    return winding && !at_min_length(qa) ? 2.0 * stiffness(qa) * inv_ratio * inv_ratio / (L * L) : 0.0;
  }
  /// The winding term W = ½ c′ e² on the drum (acts on a with −W), mode g; 0 for every other link.
  [[nodiscard]] double winding_force(double delta, double qa, GapMode g) const {
    if (!winding || !transmits(g)) return 0.0;
    const double e = delta - flank(g);
    return 0.5 * stiffness_slope(qa) * e * e;
  }

  /// The law of `link` of model `m` (machines resolved from its bodies).
  static LinkLaw of(const Model& m, const Link& link);

  /// δ, δ̇ and the weights j_a = ∂δ/∂q_a, j_b = −∂δ/∂q_b.
  struct Kinematics {
    double delta, rate, ja, jb;
  };
  /// General kinematics (machine output points included) from positions q and velocities v.
  [[nodiscard]] Kinematics kinematics(const double* q, const double* v) const {
    if (point) [[unlikely]] {
      if (!pa && !pb) return {weighted(q), weighted(v), inv_ratio, wb};  // a massless member's end
      const LinkDeflection s = link_deflection(a, b, inv_ratio, pa, pb, a >= 0 ? q[a] : 0.0, b >= 0 ? q[b] : 0.0,
                                               a >= 0 ? v[a] : 0.0, b >= 0 ? v[b] : 0.0);
      return {s.delta, s.rate, s.ja, s.jb};
    }
    return {linear(q), linear(v), inv_ratio, 1.0};
  }
  /// δ = q_a/i − q_b of a plain link (also δ̇ from the velocities, δ̈ from the accelerations); not
  /// for a `point` link (the hot path of every other link stays two terms).
  [[nodiscard]] double linear(const double* x) const {
    double s = 0.0;
    if (a >= 0) s += x[a] * inv_ratio;
    if (b >= 0) s -= x[b];
    return s;
  }
  /// δ = q_a/i − w_b q_b + w_e q_e of any link without a machine's output point (likewise δ̇, δ̈).
  [[nodiscard]] double weighted(const double* x) const {
    double s = 0.0;
    if (a >= 0) s += x[a] * inv_ratio;
    if (b >= 0) s -= x[b] * wb;
    if (third >= 0) s += x[third] * w3;
    return s;
  }

  /// The flank the load is measured from in mode g (δ₀ without a gap).
  [[nodiscard]] double flank(GapMode g) const {
    return !gap ? rest : g == GapMode::closed_pos ? hi : g == GapMode::closed_neg ? lo : 0.0;
  }
  /// Adds the generalized forces of the load at δ = 0, δ̇ = 0 to f (n): the constant part of an
  /// affine law, F₀ = −c δ₀ (0 with a gap, which is open there, or without a free length).
  void rest_forces(double* f) const {
    if (gap || rest == 0.0) return;
    const double F0 = -c * rest;
    if (a >= 0) f[a] -= F0 * inv_ratio;
    if (b >= 0) f[b] += F0 * wb;
    if (third >= 0) f[third] -= F0 * w3;
  }
  /// Whether the link transmits load in mode g.
  [[nodiscard]] bool transmits(GapMode g) const { return !gap || g != GapMode::open; }
  /// F in mode g for deflection δ and rate δ̇, drum position q_a (the stiffness c(q_a)). The
  /// overloads without q_a use c (a winding rope's stiffness at q_a0): for constant-stiffness links.
  [[nodiscard]] double load(double delta, double rate, GapMode g, double qa) const {
    if (!transmits(g)) return 0.0;
    if (shaped) [[unlikely]] return pressing(delta - flank(g), rate, qa);
    const double Fc = stiffness(qa) * (delta - flank(g));
    return Fc + damping_force(Fc, rate, g);
  }
  [[nodiscard]] double load(double delta, double rate, GapMode g) const { return load(delta, rate, g, u0); }
  /// The damper's part of the load for spring part Fc = c e: d δ̇, or with the cap min(Fc, d δ̇) on
  /// the positive flank and max(Fc, d δ̇) on the negative one.
  [[nodiscard]] double damping_force(double Fc, double rate, GapMode g) const {
    const double Fd = d * rate;
    if (!capped || !gap) return Fd;
    return g == GapMode::closed_pos ? std::min(Fc, Fd) : g == GapMode::closed_neg ? std::max(Fc, Fd) : Fd;
  }
  /// Whether the capped law is on its cap (F = 2 c e: the damper acts as a second spring) at (δ, δ̇).
  [[nodiscard]] bool on_cap(double delta, double rate, GapMode g, double qa) const {
    return capped && !shaped && gap && transmits(g) && damping_force(stiffness(qa) * (delta - flank(g)), rate, g) != d * rate;
  }
  [[nodiscard]] bool on_cap(double delta, double rate, GapMode g) const { return on_cap(delta, rate, g, u0); }
  /// The spring part of the law, c e, for a deflection e measured from the flank (quasi-static loads).
  [[nodiscard]] double spring_load(double e) const { return shaped ? shaped_force(e) : c * e; }
  /// Elastic energy ½ c(q_a) (δ − flank)² in mode g, J.
  [[nodiscard]] double elastic_energy(double delta, GapMode g, double qa) const {
    if (!transmits(g)) return 0.0;
    const double e = delta - flank(g);
    if (shaped) [[unlikely]] return shaped_energy(e);
    return 0.5 * stiffness(qa) * e * e;
  }
  [[nodiscard]] double elastic_energy(double delta, GapMode g) const { return elastic_energy(delta, g, u0); }
  /// Power dissipated by the damper, F_d δ̇ (W; d δ̇² without the cap), in mode g.
  [[nodiscard]] double dissipation(double delta, double rate, GapMode g, double qa) const {
    if (!transmits(g)) return 0.0;
    if (!capped || shaped) return damper_force(rate) * rate;
    return damping_force(stiffness(qa) * (delta - flank(g)), rate, g) * rate;
  }
  [[nodiscard]] double dissipation(double delta, double rate, GapMode g) const { return dissipation(delta, rate, g, u0); }

  /// The two event functions of mode g (both ≥ 0 while g holds; 1 for a link without a gap).
  void events(double delta, double rate, GapMode g, double* ev) const { events(delta, rate, g, u0, ev); }
  void events(double delta, double rate, GapMode g, double qa, double* ev) const {
    ev[0] = ev[1] = 1.0;
    if (!gap) return;
    const double Fp = pressing(delta - hi, rate, qa), Fn = pressing(delta - lo, rate, qa);
    switch (g) {
      case GapMode::closed_pos: ev[0] = Fp; break;
      case GapMode::closed_neg: ev[1] = -Fn; break;
      case GapMode::open:
        ev[0] = delta < hi ? hi - delta : -Fp;  // reaches the positive flank, pressing
        ev[1] = delta > lo ? delta - lo : Fn;   // reaches the negative flank, pressing
        break;
    }
  }
  /// The mode after event function `which` (0 or 1) of mode `old` crossed zero: a closed flank
  /// opens; an open gap closes on the flank it reached.
  [[nodiscard]] static GapMode mode_after(GapMode old, int which) {
    if (old != GapMode::open) return GapMode::open;
    return which == 0 ? GapMode::closed_pos : GapMode::closed_neg;
  }
  /// The mode a state implies on its own (the initial state): closed on a flank it presses.
  [[nodiscard]] GapMode natural_mode(double delta, double rate) const { return natural_mode(delta, rate, u0); }
  [[nodiscard]] GapMode natural_mode(double delta, double rate, double qa) const {
    if (!gap) return GapMode::open;
    const double Fp = pressing(delta - hi, rate, qa), Fn = pressing(delta - lo, rate, qa);
    if ((delta > hi && Fp > 0) || (delta == hi && rate > 0)) return GapMode::closed_pos;
    if ((delta < lo && Fn < 0) || (delta == lo && rate < 0)) return GapMode::closed_neg;
    return GapMode::open;
  }

  /// Adds the generalized forces of load F to f (n): −F j_a on a, +F j_b on b, −F w_e on e.
  void apply(double F, const Kinematics& k, double* f) const {
    if (a >= 0) f[a] -= F * k.ja;
    if (b >= 0) f[b] += F * k.jb;
    if (third >= 0) f[third] -= F * w3;
  }
  /// Adds all generalized forces of the link at positions q (velocities v) in mode g to f (n):
  /// the load F (returned) and a winding rope's W. Links without a machine point (a third body e, the
  /// frame a winding rope's drum hangs from, takes −F w_e).
  double apply_at(const double* q, const double* v, GapMode g, double* f) const {
    const double qa = drum(q), delta = weighted(q), F = load(delta, weighted(v), g, qa);
    if (a >= 0) f[a] -= F * inv_ratio + winding_force(delta, qa, g);
    if (b >= 0) f[b] += F * wb;
    if (third >= 0) f[third] -= F * w3;
    return F;
  }
  /// The load's weights over y = [q; v] (2n states) for a plain link in a transmitting mode:
  /// F = Σ w_k y_k − c·flank. Calls add(index, weight) at most six times.
  template <class Add>
  void load_weights(int n, Add&& add) const {
    if (a >= 0) add(a, c * inv_ratio), add(n + a, d * inv_ratio);
    if (b >= 0) add(b, -c * wb), add(n + b, -d * wb);
    if (third >= 0) add(third, c * w3), add(n + third, d * w3);
  }
  /// The rate dF/dt from the state (q, v) and its derivative (v, acc), mode g (on the cap: 2 c δ̇).
  [[nodiscard]] double load_rate(const double* q, const double* v, const double* acc, GapMode g) const {
    if (!transmits(g)) return 0.0;
    if (point || winding || shaped) [[unlikely]] return general_load_rate(q, v, acc, g);
    if (capped && on_cap(linear(q), linear(v), g)) return 2.0 * c * linear(v);
    return c * linear(v) + d * linear(acc);
  }
  /// load_rate of a rope wound on a drum (c(q_a)), of a shaped buffer (F_e′ δ̇ + F_v′ δ̈) or of a link
  /// with a machine's output point at an end (p′, p″ of the point), in a transmitting mode.
  [[nodiscard]] double general_load_rate(const double* q, const double* v, const double* acc, GapMode g) const;
  /// The terms of ∂(acceleration)/∂(q, v) before the division by the inertias: for a plain link
  /// calls add(row, column, value) with columns < n for q and ≥ n for v. Mode g, off the cap of the
  /// elasto-backlash law (its Jacobian on the cap is 2c, 0: jacobian(n, g, on_cap, add)).
  template <class Add>
  void jacobian(int n, GapMode g, Add&& add) const {
    jacobian(n, g, false, add);
  }
  /// The same at positions q for every plain link: a winding rope adds the terms of c(q_a) (the
  /// second derivatives of V above, and ∂F_d/∂q_a of the cap).
  /// The same at positions q and velocities v (null: at rest) for every plain link: a shaped buffer
  /// adds F_e′(e) and F_v′(δ̇) (see above).
  template <class Add>
  void jacobian(int n, GapMode g, bool cap, const double* q, const double* v, Add&& add) const {
    if (!shaped) return jacobian(n, g, cap, q, add);
    if (!transmits(g)) return;
    jacobian_cd(n, shaped_slope(linear(q) - flank(g)), damper_slope(v ? linear(v) : 0.0), add);
  }
  template <class Add>
  void jacobian(int n, GapMode g, bool cap, const double* q, Add&& add) const {
    if (shaped) return jacobian(n, g, cap, q, nullptr, add);
    if (!winding) return jacobian(n, g, cap, add);
    if (!transmits(g)) return;
    // e = s q_a − x_b + w_e x_e − flank (the frame e: a third body with w_e = 1, or none).
    const double qa = drum(q), e = weighted(q) - flank(g), s = inv_ratio;
    const double cq = stiffness(qa), c1 = stiffness_slope(qa), c2 = stiffness_curvature(qa);
    const double k = cap ? 2.0 : 1.0, ds = cap ? 0.0 : d;
    // F = k (c e) + F_d: ∂F/∂q_a, ∂F/∂x_b, ∂F/∂x_e and the same over the speeds.
    const double Fa = k * (cq * s + c1 * e), Fb = -k * cq, Fe = k * cq * w3, Fva = ds * s, Fvb = -ds, Fve = ds * w3;
    if (b >= 0) {  // f_b = +F
      if (a >= 0) add(b, a, Fa), add(b, n + a, Fva);
      add(b, b, Fb), add(b, n + b, Fvb);
      if (third >= 0) add(b, third, Fe), add(b, n + third, Fve);
    }
    if (third >= 0) {  // f_e = −F w_e
      if (a >= 0) add(third, a, -w3 * Fa), add(third, n + a, -w3 * Fva);
      if (b >= 0) add(third, b, -w3 * Fb), add(third, n + b, -w3 * Fvb);
      add(third, third, -w3 * Fe), add(third, n + third, -w3 * Fve);
    }
    if (a >= 0) {  // f_a = −F s − ½ c′ e²
      add(a, a, -(Fa * s + c1 * e * s + 0.5 * c2 * e * e));
      add(a, n + a, -Fva * s);
      if (b >= 0) add(a, b, -(Fb * s - c1 * e)), add(a, n + b, -Fvb * s);
      if (third >= 0) add(a, third, -(Fe * s + c1 * e * w3)), add(a, n + third, -Fve * s);
    }
  }
  template <class Add>
  void jacobian(int n, GapMode g, bool cap, Add&& add) const {
    if (!transmits(g)) return;
    jacobian_cd(n, cap ? 2.0 * c : c, cap ? 0.0 : d, add);
  }
  /// The Jacobian terms of a load with ∂F/∂δ = cs and ∂F/∂δ̇ = ds (over j = (1/i, −w_b, w_e)).
  template <class Add>
  void jacobian_cd(int n, double cs, double ds, Add&& add) const {
    const int idx[3] = {a, b, third};
    const double w[3] = {inv_ratio, -wb, w3};
    for (int r = 0; r < 3; ++r) {
      if (idx[r] < 0) continue;
      for (int s = 0; s < 3; ++s) {
        if (idx[s] < 0) continue;
        add(idx[r], idx[s], -cs * w[r] * w[s]);
        add(idx[r], n + idx[s], -ds * w[r] * w[s]);
      }
    }
  }
  /// K and D terms at positions q (machines' output points linearized there, with the geometric
  /// stiffness c (δ − flank) p″ of a point end), mode g.
  void add_linear(const double* q, GapMode g, LinearModel& lin) const;
  /// The load's linearization at (q, v) in mode g, the output row of a linear model: adds
  /// ∂F/∂q_i to dFdq[i] and ∂F/∂v_i to dFdv[i] (arrays of n). F = c (δ − flank) + d δ̇ gives
  /// ∂F/∂v = d j and ∂F/∂q = c j + d ∂δ̇/∂q (the last nonzero only for a machine's point end in
  /// motion: d p″ v). Adds nothing when the gap is open.
  void add_load_gradient(const double* q, const double* v, GapMode g, double* dFdq, double* dFdv) const;
};

}  // namespace machdyn
