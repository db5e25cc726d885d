#pragma once
/// @file
/// Input shaping of a reference signal against a lightly damped oscillation (a load swinging on its
/// rope, ω² = g/L for a trolley that follows its speed reference): the shaped reference is the
/// convolution of the reference with a few impulses whose vibrations cancel,
///
///   s_shaped(t) = Σ_i A_i s(t − t_i),   Σ_i A_i = 1,
///
/// with ω_d = ω √(1 − ζ²), K = exp(−ζ π / √(1 − ζ²)) (ω in rad/s, ζ the damping ratio, 0 ≤ ζ < 1):
///   ZV   (zero vibration):                  A = [1, K] / (1 + K),            t = [0, π/ω_d]
///   ZVD  (zero vibration and derivative):   A = [1, 2K, K²] / (1 + K)²,      t = [0, π/ω_d, 2π/ω_d]
/// A second-order oscillator x'' + 2ζω x' + ω² x = ω² s(t) driven by a shaped s is left at rest
/// once the last impulse's copy of a move is over (ZV exactly at ω; ZVD also with zero slope of the
/// residual in ω, so it tolerates an error in the frequency). Each shaper delays the move by its
/// last t_i (half a damped period for ZV, one for ZVD).
///
/// The two-step acceleration with coasting (crane drives): a speed ramp from `before` to `after`
/// over [t0, t1] (acceleration a) becomes two ramps at the same acceleration a, each of half the
/// change and half the time, from t0 and from t0 + π/ω, coasting between them. For an undamped
/// oscillator the two acceleration pulses' vibrations cancel (the second starts half a period
/// after the first, with the same shape); with damping the halves would differ in length and no
/// longer cancel exactly, so it is for ζ = 0 only (use ZV or ZVD for a damped one).
///
/// Only piecewise-linear references can be shaped (constant, step, ramp, table, a pulse of finite
/// count, sums of those): their shaped signal is again piecewise linear, returned exactly as a
/// table (breakpoints where any copy has one). Throws std::invalid_argument otherwise, for ω ≤ 0,
/// ζ outside [0, 1), and a two-step whose first half-ramp lasts beyond the second's start.

#include <vector>

#include "machdyn/model/signal.hpp"

namespace machdyn {

enum class ShaperKind { zv, zvd };

struct ShaperImpulse {
  double time;       ///< t_i, s after the reference's own times
  double amplitude;  ///< A_i, Σ A_i = 1
};

/// The impulses of a ZV or ZVD shaper for ω (rad/s) and ζ.
std::vector<ShaperImpulse> shaper_impulses(ShaperKind kind, double omega, double zeta);

/// Σ A_i s(t − t_i) of a piecewise-linear s, exactly, as a table (a constant stays a constant).
Signal shaped_signal(const Signal& s, const std::vector<ShaperImpulse>& impulses);

/// The two-step acceleration with coasting of a ramp (kind ramp only) for ω (rad/s): two ramps.
Signal two_step_signal(const Signal& ramp, double omega);

}  // namespace machdyn
