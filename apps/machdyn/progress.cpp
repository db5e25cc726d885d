#include "progress.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <unistd.h>

#include <fmt/format.h>

namespace machdyn::cli {

ProgressBar::ProgressBar(bool quiet) {
  enabled_ = !quiet && ::isatty(STDERR_FILENO) == 1;
  if (const char* d = std::getenv("MACHDYN_PROGRESS_DELAY")) delay_s_ = std::atof(d);
}

ProgressBar::~ProgressBar() { clear(); }

void ProgressBar::clear() {
  if (!shown_) return;
  std::fputs("\r\033[K", stderr);
  std::fflush(stderr);
  shown_ = false;
}

std::string ProgressBar::line(const SimulationProgress& p, int width) {
  const double frac = p.t_end > 0 ? std::clamp(p.t / p.t_end, 0.0, 1.0) : 1.0;
  const int filled = static_cast<int>(std::lround(frac * width));
  const std::string bar = fmt::format("{:#<{}}{:.<{}}", "", filled, "", width - filled);
  std::string left = "estimating";
  if (frac > 1e-6) {
    const double rest = p.wall_s * (1.0 - frac) / frac;  // wall time per simulated second so far
    left = rest < 90 ? fmt::format("~{:.0f} s left", std::ceil(rest)) : fmt::format("~{:.0f} min left", std::ceil(rest / 60));
  }
  return fmt::format("[{}] {:3.0f}%  t = {:.4g}/{:.4g} s  events {}  {}", bar, frac * 100, p.t, p.t_end, p.events, left);
}

ProgressCallback ProgressBar::callback() {
  if (!enabled_) return {};
  return [this](const SimulationProgress& p) {
    if (p.finished) {
      clear();
      return;
    }
    if (p.wall_s < delay_s_) return;
    fmt::print(stderr, "\r{}\033[K", line(p, 30));
    std::fflush(stderr);
    shown_ = true;
  };
}

}  // namespace machdyn::cli
