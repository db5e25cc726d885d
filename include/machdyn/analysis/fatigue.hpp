#pragma once
/// @file
/// Fatigue figures of counted load cycles (analysis/rainflow.hpp), in the load's own unit (N·m, N):
/// a Basquin S–N curve with a knee and an optional second slope, Palmgren–Miner damage, the
/// equivalent constant range, and EN 13001's stress history parameter s. The mechanism classes of
/// ISO 4301-1 (k_m, L, T, M) are in analysis/duty_classes.hpp; EN 13001's S-classes are not
/// collected (docs/duty.md).
///
///   S–N curve (Basquin):  N(Δ) = N_ref (Δ_ref/Δ)^m                 for Δ ≥ Δ_knee,
///                         N(Δ) = N_knee (Δ_knee/Δ)^m₂              for Δ < Δ_knee,
///                         Δ_knee = Δ_ref (N_ref/N_knee)^(1/m)      (the range at N_knee cycles);
///   no knee (N_knee = 0): the first slope throughout; m₂ = ∞: no damage below the knee (endurance).
///   Miner:                D = Σ_i n_i / N(Δ_i)                     (n_i = the cycles' counts, halves 0.5)
///   Equivalent range:     Δ_eq = (Σ_i n_i Δ_i^m / N_eq)^(1/m)      (one slope m: the constant range that
///                                                                   does the damage of the spectrum in N_eq cycles)
///   EN 13001 (-1, -3-1):  s = ν k,  k = Σ_i (Δ_i/Δ̂)^m n_i / N_t,  ν = N_t / N_ref,  so s = Σ_i n_i (Δ_i/Δ̂)^m / N_ref,
///                         Δ̂ the largest range, N_t = Σ n_i, N_ref the reference number of cycles
///                         (2·10⁶ in EN 13001-3-1's S–N curves).

#include <limits>
#include <span>

#include "machdyn/analysis/rainflow.hpp"

namespace machdyn {

/// A Basquin S–N curve of load ranges. Checked by validate(): m > 0, Δ_ref > 0, N_ref > 0, N_knee ≥ 0
/// (0: no knee), m₂ > 0 (∞ allowed), all finite but m₂.
struct SNCurve {
  double m = 0.0;          ///< slope exponent (0: not given — invalid)
  double delta_ref = 0.0;  ///< Δ_ref: a range on the curve, load unit
  double n_ref = 0.0;      ///< N_ref: cycles to failure at Δ_ref
  double n_knee = 0.0;     ///< N_knee: cycles at the knee (0: no knee)
  double m2 = std::numeric_limits<double>::infinity();  ///< slope below the knee (∞: endurance limit)
  /// Throws std::invalid_argument naming the bad field.
  void validate() const;
  /// Δ_knee (0 without a knee).
  [[nodiscard]] double knee_range() const;
  /// N(Δ): ∞ for Δ = 0 and, with m₂ = ∞, below the knee.
  [[nodiscard]] double cycles_to_failure(double range) const;
};

/// Palmgren–Miner damage D = Σ repeat · n_i / N(Δ_i) of the cycles repeated `repeat` times.
double miner_damage(std::span<const RainflowCycle> cycles, const SNCurve& curve, double repeat = 1.0);

/// Δ_eq for N_eq cycles and exponent m (both > 0); 0 when there are no cycles.
double equivalent_range(std::span<const RainflowCycle> cycles, double m, double n_eq, double repeat = 1.0);

/// EN 13001's stress history parameter of the cycles (repeated `repeat` times).
struct StressHistory {
  double total_cycles = 0.0;  ///< N_t = Σ n_i
  double largest = 0.0;       ///< Δ̂
  double k = 0.0;             ///< spectrum ratio factor Σ (Δ_i/Δ̂)^m n_i / N_t (0 without cycles)
  double nu = 0.0;            ///< relative number of cycles N_t / N_ref
  double s = 0.0;             ///< ν k
};
StressHistory stress_history(std::span<const RainflowCycle> cycles, double m, double n_ref = 2e6, double repeat = 1.0);

}  // namespace machdyn
