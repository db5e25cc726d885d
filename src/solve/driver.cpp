#include "machdyn/solve/driver.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <vector>

namespace machdyn {

RunStats integrate(Stepper& stepper, double t0, const double* y0, double t_end, double dt_out,
                   StepObserver& observer) {
  return integrate(stepper, t0, y0, t_end, dt_out, observer, nullptr);
}

RunStats integrate(Stepper& stepper, double t0, const double* y0, double t_end, double dt_out,
                   StepObserver& observer, StepEvents* events) {
  const auto start = std::chrono::steady_clock::now();
  stepper.reset(t0, y0);
  if (events) events->arm(t0, y0);
  const long n_out = std::max(1L, std::lround(std::ceil((t_end - t0) / dt_out - 1e-9)));
  auto out_time = [&](long k) { return k >= n_out ? t_end : t0 + static_cast<double>(k) * dt_out; };
  observer.on_output(t0, y0);
  long k = 1;
  const auto n = static_cast<size_t>(stepper.size());
  std::vector<double> y(n), y_prev(n);
  StepperStats done;  // counts before restarts of a stepper whose reset() clears them (CVODE)
  auto add = [](StepperStats& a, const StepperStats& b) {
    a.steps += b.steps, a.rejected += b.rejected, a.rhs_evals += b.rhs_evals, a.jac_evals += b.jac_evals;
  };
  auto restart = [&](double t, const double* yr) {
    const StepperStats before = stepper.stats();
    stepper.reset(t, yr);
    if (stepper.stats().steps < before.steps) add(done, before);
  };
  // Outputs inside the stepper's last step, up to t_limit.
  auto emit = [&](double t_limit) {
    for (; k <= n_out && out_time(k) <= t_limit; ++k) {
      const double tk = out_time(k);
      if (tk == stepper.t()) {
        observer.on_output(tk, stepper.y());
      } else {
        stepper.interpolate(tk, y.data());
        observer.on_output(tk, y.data());
      }
    }
  };
  while (stepper.t() < t_end) {
    const double t_prev = stepper.t();
    if (events) std::copy(stepper.y(), stepper.y() + n, y_prev.begin());
    stepper.step(t_end);
    const double te = events ? events->locate(stepper) : std::nan("");
    if (std::isnan(te)) {
      observer.on_step(stepper);
      emit(stepper.t());
      continue;
    }
    // An event at te in (t_prev, t]: integrate [t_prev, te] again, stopping exactly at te.
    if (te < stepper.t()) {
      restart(t_prev, y_prev.data());
      while (stepper.t() < te) {
        stepper.step(te);
        observer.on_step(stepper);
        emit(stepper.t());
      }
    } else {
      observer.on_step(stepper);
      emit(stepper.t());
    }
    std::copy(stepper.y(), stepper.y() + n, y.begin());
    events->apply(te, y.data());
    restart(te, y.data());
    events->arm(te, y.data());
  }
  RunStats s;
  add(done, stepper.stats());
  s.stepper = done;
  s.method = stepper.name();
  s.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

}  // namespace machdyn
