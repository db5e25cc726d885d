#pragma once
/// @file
/// The classification of a crane mechanism by its duty (ISO 4301-1, FEM 1.001 section 1; the tables
/// as collected in docs/duty.md with their public sources):
///
///   load spectrum factor  k_m = Σ_i (t_i/T) (P_i/P_max)³       (t_i the running time at load P_i,
///                                                               T = Σ t_i, P_max the rated load)
///   continuous form       k_m = ∫ |P(t)|³ dt / (P_max³ T)       (the same sum over infinitely many levels)
///   spectrum class        L1: k_m ≤ 0.125, L2: ≤ 0.25, L3: ≤ 0.5, L4: ≤ 1     (nominal 0.125, 0.25, 0.5, 1)
///   class of utilization  T0…T9 by the total running time over the design life, upper limits
///                         200, 400, 800, 1600, 3200, 6300, 12500, 25000, 50000 h; T9 above 50000 h
///   mechanism group       M = T + L − 2 (the table's diagonals: T2·L1 = T1·L2 = T0·L3 = M1, each class
///                         up one group up), below M1 taken as M1, above M8 as M8 (the table's blanks)
///
/// and EN 13001-1's classes of the stress history parameter s (analysis/fatigue.hpp, s = ν k):
///   S0: s ≤ 0.008, S1: ≤ 0.016, S2: ≤ 0.032, S3: ≤ 0.063, S4: ≤ 0.125, S5: ≤ 0.25, S6: ≤ 0.5,
///   S7: ≤ 1, S8: ≤ 2, S9: ≤ 4 (4 · 2^(S−9), rounded to two digits as printed); above 4
///   outside the table. One public source, verify against the standard (docs/duty.md).
///
/// The classes depend on a class-boundary comparison only: a value on a boundary belongs to the lower
/// class (the tables give upper limits "≤").

#include <span>
#include <string>

namespace machdyn {

/// One level of a load spectrum: the load P (any unit, its magnitude counts) held for time t.
struct LoadLevel {
  double time = 0.0;
  double load = 0.0;
};

/// k_m of discrete levels; `p_max` > 0 the rated load, 0: the largest |P| of the levels. Throws
/// std::invalid_argument on a negative time, no running time at all, or no load.
double load_spectrum_factor(std::span<const LoadLevel> levels, double p_max = 0.0);

/// The continuous form over a load history sampled at (t, P) in time order: the trapezoidal rule of
/// |P|³ between neighbouring samples (exact for a piecewise-linear history, O(Δt²) otherwise), the
/// running time from the first to the last sample and the largest |P|.
class CubicLoadIntegral {
 public:
  void add(double t, double load);
  [[nodiscard]] double integral() const { return integral_; }  ///< ∫ |P|³ dt
  [[nodiscard]] double duration() const { return duration_; }  ///< T, the running time
  [[nodiscard]] double peak() const { return peak_; }          ///< max |P|
 private:
  bool started_ = false;
  double t_ = 0.0, cube_ = 0.0, integral_ = 0.0, duration_ = 0.0, peak_ = 0.0;
};

/// L1…L4 (returns 1…4) of a k_m ≥ 0; k_m above 1 (loads above the rated one) is L4 as well.
int spectrum_class(double k_m);
/// T0…T9 (returns 0…9) of a total running time in hours ≥ 0.
int utilization_class(double hours);
/// M1…M8 (returns 1…8) of a spectrum class L (1…4) and a class of utilization T (0…9).
int mechanism_group(int spectrum_class, int utilization_class);

/// EN 13001's S-class of a stress history parameter s ≥ 0: 0…9 for S0…S9, 10 above S9's limit (4).
int stress_history_class(double s);
/// "S0"…"S9", ">S9" for 10.
std::string stress_history_class_name(int stress_history_class);
/// The upper limit of s of class S0…S9.
double stress_history_class_limit(int stress_history_class);

/// The upper limit of k_m of class L (1…4) and of the running hours of class T (0…8; T9 has none).
double spectrum_class_limit(int spectrum_class);
double utilization_class_limit_hours(int utilization_class);

}  // namespace machdyn
