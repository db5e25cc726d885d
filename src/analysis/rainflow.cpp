#include "machdyn/analysis/rainflow.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace machdyn {

RainflowCounter::RainflowCounter(Sink sink, double gate, RainflowResidue residue)
    : sink_(std::move(sink)), gate_(gate), residue_(residue) {
  if (!(gate >= 0.0) || !std::isfinite(gate))
    throw std::invalid_argument("rainflow: the hysteresis gate must be finite and ≥ 0, got " + std::to_string(gate));
  if (!sink_) throw std::invalid_argument("rainflow: no sink for the counted cycles");
}

void RainflowCounter::add(double x) {
  if (!std::isfinite(x)) throw std::invalid_argument("rainflow: a sample is not finite");
  // 1. Turning points through the gate: a reversal once the signal is back from the running
  // extreme by more than the gate.
  if (!started_) {
    started_ = true, first_ = x, extreme_ = x, dir_ = 0;
    push(x);  // the history's first point is a turning point (the ASTM starting point)
    return;
  }
  if (dir_ == 0) {
    const int d = x - first_ > gate_ ? 1 : first_ - x > gate_ ? -1 : 0;
    if (d == 0) return;
    const std::size_t n = stack_.size();
    if (n >= 2 && (stack_[n - 1] - stack_[n - 2]) * d > 0) {
      // After flush(): the history goes on past the last turning point, which was none.
      stack_.pop_back();
      --turning_points_;
    }
    dir_ = d, extreme_ = x;
  } else if (dir_ > 0) {
    if (x >= extreme_) extreme_ = x;
    else if (extreme_ - x > gate_) push(extreme_), dir_ = -1, extreme_ = x;
  } else {
    if (x <= extreme_) extreme_ = x;
    else if (x - extreme_ > gate_) push(extreme_), dir_ = 1, extreme_ = x;
  }
}

void RainflowCounter::push(double p) {
  stack_.push_back(p);
  ++turning_points_;
  max_held_ = std::max(max_held_, stack_.size() + 1);
  // 2. Count on the stack s: X = |s[n-1] − s[n-2]| the newest range, Y = |s[n-2] − s[n-3]| before it.
  if (residue_ == RainflowResidue::half_cycles) {
    // ASTM 5.4.4: X ≥ Y counts Y — half a cycle when Y holds the starting point s[0] (dropped), else
    // a whole cycle (both points dropped).
    while (stack_.size() >= 3) {
      const std::size_t n = stack_.size();
      const double X = std::abs(stack_[n - 1] - stack_[n - 2]);
      const double Y = std::abs(stack_[n - 2] - stack_[n - 3]);
      if (X < Y) break;
      if (n == 3) {
        emit(stack_[0], stack_[1], 0.5);
        stack_.erase(stack_.begin());
      } else {
        emit(stack_[n - 3], stack_[n - 2], 1.0);
        stack_[n - 3] = stack_[n - 1];
        stack_.resize(n - 2);
      }
    }
  } else {
    // The four-point rule: Y is a cycle when both its neighbours X and Z = |s[n-3] − s[n-4]| are at
    // least as large; the starting point is never taken as half a cycle.
    while (stack_.size() >= 4) {
      const std::size_t n = stack_.size();
      const double X = std::abs(stack_[n - 1] - stack_[n - 2]);
      const double Y = std::abs(stack_[n - 2] - stack_[n - 3]);
      const double Z = std::abs(stack_[n - 3] - stack_[n - 4]);
      if (Y > X || Y > Z) break;
      emit(stack_[n - 3], stack_[n - 2], 1.0);
      stack_[n - 3] = stack_[n - 1];
      stack_.resize(n - 2);
    }
  }
}

void RainflowCounter::finish() {
  const std::size_t n = stack_.size();
  if (dir_ == 0 && n >= 2) {  // after flush(): the last turning point runs on as the extreme
    extreme_ = stack_[n - 1], dir_ = stack_[n - 1] > stack_[n - 2] ? 1 : -1;
    stack_.pop_back();
    --turning_points_;
  }
  if (started_) {
    if (residue_ == RainflowResidue::half_cycles) {
      if (dir_ != 0) push(extreme_);
      dir_ = 0;
      for (std::size_t i = 0; i + 1 < stack_.size(); ++i) emit(stack_[i], stack_[i + 1], 0.5);
    } else if (dir_ != 0) {
      // 3. The residue R followed by R again: continuing the extraction over R's points counts R·R;
      // what is held afterwards is R once more (dropped).
      // The history's last turning point first (it may close cycles of its own), then R = the stack.
      push(extreme_);
      const std::vector<double> residue = stack_;
      const std::size_t seen = turning_points_;
      stack_.pop_back();  // R without its last point is a residue too; extreme_ (R's last) runs on
      for (const double x : residue) add(x);
      push(extreme_);
      turning_points_ = seen;
    }
  }
  stack_.clear();
  started_ = false, dir_ = 0;
}

void RainflowCounter::flush() {
  if (dir_ == 0) return;
  push(extreme_);
  first_ = extreme_, dir_ = 0;  // the next reversal beyond the gate sets the direction again
}

std::vector<double> RainflowCounter::residue() const {
  std::vector<double> r = stack_;
  if (dir_ != 0) r.push_back(extreme_);
  return r;
}

void append_turning_point(std::vector<double>& points, double x) {
  const std::size_t n = points.size();
  if (n >= 1 && x == points[n - 1]) return;
  if (n >= 2 && (points[n - 1] - points[n - 2]) * (x - points[n - 1]) > 0.0) {
    points[n - 1] = x;  // the run goes on: its end moves
    return;
  }
  points.push_back(x);
}

RainflowPart rainflow_part(std::span<const double> series, double gate) {
  RainflowPart part;
  // The four-point counter (the repeat rule) never takes a half cycle while counting; flushed but not
  // finished, what it holds is the part's irreducible residue.
  RainflowCounter counter([&part](const RainflowCycle& c) { part.cycles.push_back(c); }, gate, RainflowResidue::repeat);
  for (const double x : series) counter.add(x);
  counter.flush();
  part.residue = counter.residue();
  return part;
}

std::vector<RainflowCycle> merge_parts(std::span<const RainflowPart> parts, std::span<const double> repeats,
                                       RainflowResidue residue) {
  if (parts.size() != repeats.size())
    throw std::invalid_argument("rainflow: " + std::to_string(repeats.size()) + " repetitions for " +
                                std::to_string(parts.size()) + " parts");
  std::vector<RainflowCycle> out;
  RainflowCounter residues([&out](const RainflowCycle& c) { out.push_back(c); }, 0.0, residue);
  for (std::size_t i = 0; i < parts.size(); ++i) {
    const double n = repeats[i];
    if (!(n >= 0.0) || !std::isfinite(n) || n != std::floor(n))
      throw std::invalid_argument("rainflow: the repetitions of a part must be a whole number >= 0, got " +
                                  std::to_string(n));
    if (n == 0.0) continue;
    for (RainflowCycle c : parts[i].cycles) out.push_back({c.from, c.to, c.count * n});
    const int feeds = n >= 2.0 ? 2 : 1;
    for (int k = 0; k < feeds; ++k)
      for (const double x : parts[i].residue) residues.add(x);
    if (n > 2.0) {  // each further repetition closes the cycles of R_i·R_i once more
      RainflowCounter closure([&out, n](const RainflowCycle& c) { out.push_back({c.from, c.to, c.count * (n - 2.0)}); },
                              0.0, RainflowResidue::repeat);
      for (int k = 0; k < 2; ++k)
        for (const double x : parts[i].residue) closure.add(x);
      closure.flush();  // R·R's last point closes cycles too
    }
  }
  residues.finish();
  return out;
}

std::vector<RainflowCycle> rainflow(std::span<const double> series, const RainflowOptions& options) {
  if (!(options.gate_fraction >= 0.0 && options.gate_fraction < 1.0))
    throw std::invalid_argument("rainflow: the gate fraction must lie in [0, 1), got " +
                                std::to_string(options.gate_fraction));
  double gate = 0.0;
  if (options.gate_fraction > 0.0 && !series.empty()) {
    const auto [lo, hi] = std::minmax_element(series.begin(), series.end());
    gate = options.gate_fraction * (*hi - *lo);
    if (!std::isfinite(gate)) throw std::invalid_argument("rainflow: a sample is not finite");
  }
  std::vector<RainflowCycle> cycles;
  RainflowCounter counter([&cycles](const RainflowCycle& c) { cycles.push_back(c); }, gate, options.residue);
  for (const double x : series) counter.add(x);
  counter.finish();
  return cycles;
}

double RainflowMatrix::total() const {
  double s = 0.0;
  for (const double c : counts) s += c;
  return s;
}

int rainflow_bin(double x, double lo, double hi, int n) {
  if (n < 1) throw std::invalid_argument("rainflow: a matrix axis needs at least one bin");
  if (!(hi > lo)) return 0;
  const double k = std::floor((x - lo) / (hi - lo) * n);
  return static_cast<int>(std::clamp(k, 0.0, static_cast<double>(n - 1)));
}

namespace {

RainflowMatrix make_matrix(int rows, int cols, double row_lo, double row_hi, double col_lo, double col_hi) {
  if (rows < 1 || cols < 1) throw std::invalid_argument("rainflow: a matrix axis needs at least one bin");
  RainflowMatrix M;
  M.rows = rows, M.cols = cols, M.row_lo = row_lo, M.row_hi = row_hi, M.col_lo = col_lo, M.col_hi = col_hi;
  M.counts.assign(static_cast<std::size_t>(rows) * static_cast<std::size_t>(cols), 0.0);
  return M;
}

}  // namespace

RainflowMatrix range_mean_matrix(std::span<const RainflowCycle> cycles, int range_bins, int mean_bins) {
  double r_hi = 0.0, m_lo = 0.0, m_hi = 0.0;
  for (std::size_t k = 0; k < cycles.size(); ++k) {
    const double r = cycles[k].range(), m = cycles[k].mean();
    r_hi = std::max(r_hi, r);
    m_lo = k == 0 ? m : std::min(m_lo, m);
    m_hi = k == 0 ? m : std::max(m_hi, m);
  }
  RainflowMatrix M = make_matrix(range_bins, mean_bins, 0.0, r_hi, m_lo, m_hi);
  for (const RainflowCycle& c : cycles)
    M.counts[static_cast<std::size_t>(rainflow_bin(c.range(), 0.0, r_hi, range_bins) * mean_bins +
                                      rainflow_bin(c.mean(), m_lo, m_hi, mean_bins))] += c.count;
  return M;
}

RainflowMatrix from_to_matrix(std::span<const RainflowCycle> cycles, int bins) {
  double lo = 0.0, hi = 0.0;
  for (std::size_t k = 0; k < cycles.size(); ++k) {
    const double a = std::min(cycles[k].from, cycles[k].to), b = std::max(cycles[k].from, cycles[k].to);
    lo = k == 0 ? a : std::min(lo, a);
    hi = k == 0 ? b : std::max(hi, b);
  }
  RainflowMatrix M = make_matrix(bins, bins, lo, hi, lo, hi);
  for (const RainflowCycle& c : cycles)
    M.counts[static_cast<std::size_t>(rainflow_bin(c.from, lo, hi, bins) * bins + rainflow_bin(c.to, lo, hi, bins))] +=
        c.count;
  return M;
}

}  // namespace machdyn
