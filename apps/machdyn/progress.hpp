#pragma once
// The progress bar of long runs, drawn on stderr by the CLI from the library's progress callback
// (SimulateOptions::progress). Shown only when stderr is a terminal, not with --quiet, and only
// after the run has taken `delay` seconds (1 s; MACHDYN_PROGRESS_DELAY overrides it, for tests).
#include <string>

#include "machdyn/analysis/simulate.hpp"

namespace machdyn::cli {

class ProgressBar {
 public:
  explicit ProgressBar(bool quiet);
  ~ProgressBar();
  ProgressBar(const ProgressBar&) = delete;
  ProgressBar& operator=(const ProgressBar&) = delete;

  /// The callback to put into SimulateOptions::progress; empty when the bar is off.
  [[nodiscard]] ProgressCallback callback();
  /// Clears the bar's line (also done by the destructor and by the final progress report).
  void clear();

  /// One line of the bar, e.g. "[#####.....]  48%  t = 0.24/0.5 s  events 0  ~2 s left".
  static std::string line(const SimulationProgress& p, int width);

 private:
  bool enabled_ = false;
  bool shown_ = false;
  double delay_s_ = 1.0;
};

}  // namespace machdyn::cli
