#pragma once
/// @file
/// Rainflow cycle counting of a load history (ASTM E1049-85 (2017), section 5.4.4), streaming: the
/// memory is the residue (a stack of turning points), not the history's length.
///
/// 1. Turning points with a hysteresis gate h ≥ 0 (a range filter applied while the turning points
///    are extracted, before counting): the first sample is a turning point; after it, a reversal is
///    accepted only once the signal has come back from the running extreme by MORE than h. So every
///    range between consecutive turning points exceeds h, smaller excursions vanish before counting
///    (they do not merely drop out of the counts: the larger cycles form as if they were not there),
///    and h = 0 merges plateaus only. The last sample's running extreme closes the history.
/// 2. Counting (ASTM 5.4.4): turning points are pushed on a stack; with X the range of the newest two
///    and Y the range of the two before, while X ≥ Y: if Y contains the history's first point, Y is
///    half a cycle and the first point is dropped, else Y is a cycle and both its points are dropped.
///    At the end each range of what is left (the residue) is half a cycle.
/// 3. Residue closed by repetition (RainflowResidue::repeat, fatigue practice for a history that
///    repeats: ASTM 5.4.5): counting never takes the first point as half a cycle — a range Y is a
///    cycle when both neighbours X and Z are at least as large (the four-point rule) — so the residue
///    R is a diverging-then-converging sequence; at the end R followed by R is counted on, which
///    yields R's cycles, all whole (R·R leaves R again). The counts are then those of one period of
///    the infinitely repeated history: the four-point count of the history three times in a row
///    minus that of twice in a row, cycle for cycle.
/// With equal ranges (ties) ASTM's X ≥ Y takes a run of them at the starting point as halves where
/// the four-point rule takes pairs as whole cycles; the count per (range, mean) is the same.
///
/// A cycle is reported with its points from → to (the half cycle's direction; a whole cycle's first
/// reversal), range |to − from| and mean (from + to)/2. The largest range counted is always
/// max − min of the history (those two points are never the inner pair of a smaller loop).

#include <cstddef>
#include <functional>
#include <span>
#include <vector>

namespace machdyn {

/// One counted cycle: count 1 (whole) or 0.5 (half, a residue range in ASTM 5.4.4); merged parts
/// (merge_parts) carry the number of repetitions.
struct RainflowCycle {
  double from = 0.0, to = 0.0;  ///< the reversals, in the load's unit
  double count = 1.0;           ///< 1 or 0.5 (a multiple of them in merged parts)
  [[nodiscard]] double range() const { return to > from ? to - from : from - to; }
  [[nodiscard]] double mean() const { return 0.5 * (from + to); }
};

/// What becomes of the residue at the end.
enum class RainflowResidue {
  half_cycles,  ///< ASTM 5.4.4: each residue range is half a cycle
  repeat,       ///< closed by repeating the history: all cycles whole (see the file comment)
};

/// The streaming counter: add() samples (or turning points) one by one, finish() at the end. Each
/// cycle is handed to the sink as soon as it is known. The memory is the residue's size.
class RainflowCounter {
 public:
  using Sink = std::function<void(const RainflowCycle&)>;
  /// `gate` h ≥ 0 in the load's unit (std::invalid_argument when negative or not finite).
  RainflowCounter(Sink sink, double gate = 0.0, RainflowResidue residue = RainflowResidue::half_cycles);
  /// The next sample; std::invalid_argument when it is not finite.
  void add(double x);
  /// Ends the history: the last turning point and the residue are counted. Further add() calls start
  /// a new history (turning_points() and max_held() then count on).
  void finish();
  /// Turning points of the history so far (after the gate; the running extreme counts as one).
  [[nodiscard]] std::size_t turning_points() const { return turning_points_ + (dir_ != 0 ? 1 : 0); }
  /// Turning points held now: the residue so far and the running extreme.
  [[nodiscard]] std::size_t held() const { return stack_.size() + (dir_ != 0 ? 1 : 0); }
  /// Takes the running extreme as a turning point now (the end of a part of the history) without
  /// ending the history: what the counter holds is then an irreducible residue (residue()), and
  /// further samples continue the history.
  void flush();
  /// The residue so far: the turning points held (the stack and the running extreme), in order.
  [[nodiscard]] std::vector<double> residue() const;
  /// The most turning points held at once (the memory bound, in points).
  [[nodiscard]] std::size_t max_held() const { return max_held_; }

 private:
  void push(double p);                  // counts on the stack after pushing turning point p
  void emit(double from, double to, double count) { sink_(RainflowCycle{from, to, count}); }
  Sink sink_;
  double gate_;
  RainflowResidue residue_;
  std::vector<double> stack_;       // the residue: turning points not yet counted
  bool started_ = false;            // a first sample was seen
  int dir_ = 0;                     // +1 rising, −1 falling, 0 no reversal beyond the gate yet
  double first_ = 0.0;              // the first sample (while dir_ == 0)
  double extreme_ = 0.0;            // the running extreme since the last turning point
  std::size_t turning_points_ = 0, max_held_ = 0;
};

/// Appends sample x to `points`, keeping only where the history turns: a point inside a monotone run
/// (the last point when x goes on in its direction) is replaced by x, a value equal to the last is
/// dropped, the first sample always stays. Lossless for counting: the turning points through any
/// gate h >= 0 (RainflowCounter), hence every count and residue, are the same over `points` as over
/// all the samples — the gate looks only at the running extreme and at how far the signal came back
/// from it, and both are reached at the ends of a monotone run. Holds the reversals, not the samples:
/// a history can be kept while its range (and so a gate given as a fraction of it) is not yet known.
void append_turning_point(std::vector<double>& points, double x);

/// One part of a longer history (an operation of a duty): its whole cycles by the four-point rule
/// (never a half) and its residue, the turning points left. Parts merge exactly: counting A·B equals
/// A's cycles + B's cycles + the count of R_A·R_B (the residues' concatenation), and the residue of
/// A·B is that of R_A·R_B.
struct RainflowPart {
  std::vector<RainflowCycle> cycles;
  std::vector<double> residue;
};

/// The part of a series (gate h ≥ 0 in the load's unit, as RainflowCounter).
RainflowPart rainflow_part(std::span<const double> series, double gate = 0.0);

/// The count of the history part 0 repeated n_0 times back to back, then part 1 repeated n_1 times, …
/// (n_i whole numbers ≥ 0), the residue at the end treated by `residue`. Exact, without building the
/// history: part i gives n_i times its cycles; its residue R_i enters the sequence of residues
/// min(n_i, 2) times, and each repetition beyond the second adds the cycles of R_i·R_i (R_i^n leaves
/// the same stack as R_i·R_i after any prefix, each further R_i closing those cycles once more).
/// Counts are multiplied (a cycle record of count n_i), not repeated. Throws std::invalid_argument on
/// a negative or fractional repetition or a count list of the wrong length.
std::vector<RainflowCycle> merge_parts(std::span<const RainflowPart> parts, std::span<const double> repeats,
                                       RainflowResidue residue = RainflowResidue::half_cycles);

/// Options of the whole-series count.
struct RainflowOptions {
  /// The gate as a fraction of the largest range, max − min of the series (the largest range counted):
  /// h = gate_fraction · (max − min). Must lie in [0, 1).
  double gate_fraction = 0.0;
  RainflowResidue residue = RainflowResidue::half_cycles;
};

/// Counts a whole series (one pass for max − min when gated, one for the count). Throws
/// std::invalid_argument on a non-finite sample or a gate fraction outside [0, 1).
std::vector<RainflowCycle> rainflow(std::span<const double> series, const RainflowOptions& options = {});

/// A counted matrix: counts[i * cols + j]. Bin k of an axis over [lo, hi] with n bins of width
/// w = (hi − lo)/n holds lo + k w ≤ x < lo + (k+1) w; x = hi falls in the last bin; values outside
/// [lo, hi] are clamped into the first or last bin (the axes are normally the counted data's extent).
struct RainflowMatrix {
  int rows = 0, cols = 0;
  double row_lo = 0.0, row_hi = 0.0, col_lo = 0.0, col_hi = 0.0;
  std::vector<double> counts;  ///< cycles (halves count 0.5)
  [[nodiscard]] double at(int i, int j) const { return counts[static_cast<std::size_t>(i * cols + j)]; }
  [[nodiscard]] double total() const;
};

/// The bin of x on an axis [lo, hi] of n bins (the rule above); n ≥ 1, hi ≥ lo.
int rainflow_bin(double x, double lo, double hi, int n);

/// Range–mean matrix: rows are ranges over [0, max range], columns means over [min mean, max mean]
/// of the cycles (an empty axis, lo = hi, is one bin wide in effect: everything in bin 0).
RainflowMatrix range_mean_matrix(std::span<const RainflowCycle> cycles, int range_bins, int mean_bins);
/// From–to matrix: rows are `from`, columns `to`, both over [lo, hi] = the cycles' extent, n bins each.
RainflowMatrix from_to_matrix(std::span<const RainflowCycle> cycles, int bins);

}  // namespace machdyn
