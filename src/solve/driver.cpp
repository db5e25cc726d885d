#include "machdyn/solve/driver.hpp"

#include <chrono>
#include <cmath>
#include <vector>

namespace machdyn {

RunStats integrate(Stepper& stepper, double t0, const double* y0, double t_end, double dt_out,
                   StepObserver& observer) {
  const auto start = std::chrono::steady_clock::now();
  stepper.reset(t0, y0);
  const long n_out = std::max(1L, std::lround(std::ceil((t_end - t0) / dt_out - 1e-9)));
  auto out_time = [&](long k) { return k >= n_out ? t_end : t0 + static_cast<double>(k) * dt_out; };
  observer.on_output(t0, y0);
  long k = 1;
  std::vector<double> y(static_cast<size_t>(stepper.size()));
  while (stepper.t() < t_end) {
    stepper.step(t_end);
    observer.on_step(stepper);
    for (; k <= n_out && out_time(k) <= stepper.t(); ++k) {
      const double tk = out_time(k);
      if (tk == stepper.t()) {
        observer.on_output(tk, stepper.y());
      } else {
        stepper.interpolate(tk, y.data());
        observer.on_output(tk, y.data());
      }
    }
  }
  RunStats s;
  s.stepper = stepper.stats();
  s.method = stepper.name();
  s.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

}  // namespace machdyn
