#pragma once
/// @file
/// The law of a link (spring, damper, spring–damper, with or without a gap), stated once and used
/// by every consumer: the drive system's right-hand side and Jacobian, its event functions, the
/// mode decision, energies, peaks, quasi-static loads and linear models.
///
/// Kinematics (model/model.hpp): deflection δ = p_a(q_a)/i − p_b(q_b), rad or m in b's coordinate,
/// p(q) = q for a plain end or a machine's output point (model/machine.hpp); δ̇ = j_a v_a − j_b v_b
/// with j_a = p_a′/i, j_b = p_b′. The load F acts on b with +F and on a with −F j_a (a: −F/i).
///
/// Law (N·m or N; positive = tension, as the paper's M12 = c1 (φ1 − φ2)):
///   no gap:        F = c δ + d δ̇
///   gap, open:     F = 0                         (δ₋ < δ < δ₊)
///   closed+:       F = c (δ − δ₊) + d δ̇ ≥ 0      (positive flank δ₊ = Δ − gap_start)
///   closed−:       F = c (δ − δ₋) + d δ̇ ≤ 0      (negative flank δ₋ = −gap_start)
/// Flank law `elasto-backlash` (capped = true; Modelica's ElastoBacklash/ElastoGap): the damping
/// force on a flank is capped at the spring force, e = δ − flank:
///   closed+:       F = c e + min(c e, d δ̇)       closed−:  F = c e + max(c e, d δ̇)
/// so F rises from 0 at first contact (no jump d δ̇) and never exceeds 2 c e. The mode still ends
/// when c e + d δ̇ reaches 0 (F and c e + d δ̇ vanish together there), so the events below hold for
/// both laws. The cap's kink (d δ̇ = c e) is a continuous law, not an event: the load is continuous
/// there and the integrator's error control resolves it, as for any other continuous nonlinearity.
/// Events (each ≥ 0 while the mode holds): closed+ ends when F reaches 0 (F ≥ 0); closed− when
/// −F reaches 0; open ends when δ reaches a flank while pressing (δ₊ − δ ≥ 0, δ − δ₋ ≥ 0; beyond the
/// flank, the pressing force −F₊ or F₋ decides).
/// Valid for c ≥ 0, d ≥ 0, i ≠ 0, Δ ≥ 0. Nothing is thrown.

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
  bool point = false;           ///< an end is a machine's output point (nonlinear kinematics)
  double lo = 0.0, hi = 0.0;    ///< flanks δ₋, δ₊
  const Machine* pa = nullptr;  ///< a's output point, or null (q_a itself)
  const Machine* pb = nullptr;

  /// The law of `link` of model `m` (machines resolved from its bodies).
  static LinkLaw of(const Model& m, const Link& link);

  /// δ, δ̇ and the weights j_a = ∂δ/∂q_a, j_b = −∂δ/∂q_b.
  struct Kinematics {
    double delta, rate, ja, jb;
  };
  /// General kinematics (machine output points included) from positions q and velocities v.
  [[nodiscard]] Kinematics kinematics(const double* q, const double* v) const {
    if (point) [[unlikely]] {
      const LinkDeflection s = link_deflection(a, b, inv_ratio, pa, pb, a >= 0 ? q[a] : 0.0, b >= 0 ? q[b] : 0.0,
                                               a >= 0 ? v[a] : 0.0, b >= 0 ? v[b] : 0.0);
      return {s.delta, s.rate, s.ja, s.jb};
    }
    return {linear(q), linear(v), inv_ratio, 1.0};
  }
  /// δ = q_a/i − q_b of a plain link (also δ̇ from the velocities, δ̈ from the accelerations).
  [[nodiscard]] double linear(const double* x) const {
    double s = 0.0;
    if (a >= 0) s += x[a] * inv_ratio;
    if (b >= 0) s -= x[b];
    return s;
  }

  /// The flank the load is measured from in mode g (0 without a gap).
  [[nodiscard]] double flank(GapMode g) const {
    return !gap ? 0.0 : g == GapMode::closed_pos ? hi : g == GapMode::closed_neg ? lo : 0.0;
  }
  /// Whether the link transmits load in mode g.
  [[nodiscard]] bool transmits(GapMode g) const { return !gap || g != GapMode::open; }
  /// F in mode g for deflection δ and rate δ̇.
  [[nodiscard]] double load(double delta, double rate, GapMode g) const {
    if (!transmits(g)) return 0.0;
    const double Fc = c * (delta - flank(g));
    return Fc + damping_force(Fc, rate, g);
  }
  /// The damper's part of the load for spring part Fc = c e: d δ̇, or with the cap min(Fc, d δ̇) on
  /// the positive flank and max(Fc, d δ̇) on the negative one.
  [[nodiscard]] double damping_force(double Fc, double rate, GapMode g) const {
    const double Fd = d * rate;
    if (!capped || !gap) return Fd;
    return g == GapMode::closed_pos ? std::min(Fc, Fd) : g == GapMode::closed_neg ? std::max(Fc, Fd) : Fd;
  }
  /// Whether the capped law is on its cap (F = 2 c e: the damper acts as a second spring) at (δ, δ̇).
  [[nodiscard]] bool on_cap(double delta, double rate, GapMode g) const {
    return capped && gap && transmits(g) && damping_force(c * (delta - flank(g)), rate, g) != d * rate;
  }
  /// The spring part of the law, c e, for a deflection e measured from the flank (quasi-static loads).
  [[nodiscard]] double spring_load(double e) const { return c * e; }
  /// Elastic energy ½ c (δ − flank)² in mode g, J.
  [[nodiscard]] double elastic_energy(double delta, GapMode g) const {
    if (!transmits(g)) return 0.0;
    const double e = delta - flank(g);
    return 0.5 * c * e * e;
  }
  /// Power dissipated by the damper, F_d δ̇ (W; d δ̇² without the cap), in mode g.
  [[nodiscard]] double dissipation(double delta, double rate, GapMode g) const {
    if (!transmits(g)) return 0.0;
    if (!capped) return d * rate * rate;
    return damping_force(c * (delta - flank(g)), rate, g) * rate;
  }

  /// The two event functions of mode g (both ≥ 0 while g holds; 1 for a link without a gap).
  void events(double delta, double rate, GapMode g, double* ev) const {
    ev[0] = ev[1] = 1.0;
    if (!gap) return;
    const double Fp = c * (delta - hi) + d * rate, Fn = c * (delta - lo) + d * rate;
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
  [[nodiscard]] GapMode natural_mode(double delta, double rate) const {
    if (!gap) return GapMode::open;
    const double Fp = c * (delta - hi) + d * rate, Fn = c * (delta - lo) + d * rate;
    if ((delta > hi && Fp > 0) || (delta == hi && rate > 0)) return GapMode::closed_pos;
    if ((delta < lo && Fn < 0) || (delta == lo && rate < 0)) return GapMode::closed_neg;
    return GapMode::open;
  }

  /// Adds the generalized forces of load F to f (n): −F j_a on a, +F j_b on b.
  void apply(double F, const Kinematics& k, double* f) const {
    if (a >= 0) f[a] -= F * k.ja;
    if (b >= 0) f[b] += F * k.jb;
  }
  /// The load's weights over y = [q; v] (2n states) for a plain link in a transmitting mode:
  /// F = Σ w_k y_k − c·flank. Calls add(index, weight) at most four times.
  template <class Add>
  void load_weights(int n, Add&& add) const {
    if (a >= 0) add(a, c * inv_ratio), add(n + a, d * inv_ratio);
    if (b >= 0) add(b, -c), add(n + b, -d);
  }
  /// The rate dF/dt from the state (q, v) and its derivative (v, acc), mode g (on the cap: 2 c δ̇).
  [[nodiscard]] double load_rate(const double* q, const double* v, const double* acc, GapMode g) const {
    if (!transmits(g)) return 0.0;
    if (point) [[unlikely]] return point_load_rate(q, v, acc, g);
    if (capped && on_cap(linear(q), linear(v), g)) return 2.0 * c * linear(v);
    return c * linear(v) + d * linear(acc);
  }
  /// load_rate of a link with a machine's output point at an end (p′, p″ of the point).
  [[nodiscard]] double point_load_rate(const double* q, const double* v, const double* acc, GapMode g) const;
  /// The terms of ∂(acceleration)/∂(q, v) before the division by the inertias: for a plain link
  /// calls add(row, column, value) with columns < n for q and ≥ n for v. Mode g, off the cap of the
  /// elasto-backlash law (its Jacobian on the cap is 2c, 0: jacobian(n, g, on_cap, add)).
  template <class Add>
  void jacobian(int n, GapMode g, Add&& add) const {
    jacobian(n, g, false, add);
  }
  template <class Add>
  void jacobian(int n, GapMode g, bool cap, Add&& add) const {
    if (!transmits(g)) return;
    const double cs = cap ? 2.0 * c : c, ds = cap ? 0.0 : d;
    const int idx[2] = {a, b};
    const double w[2] = {inv_ratio, -1.0};
    for (int r = 0; r < 2; ++r) {
      if (idx[r] < 0) continue;
      for (int s = 0; s < 2; ++s) {
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
