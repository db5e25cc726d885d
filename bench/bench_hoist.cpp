// The three-mass hoist for 10 s at rtol 1e-8, side by side: machdyn (model file → simulate) and a
// hand-written Dormand–Prince loop for the same equations, the same step control and the same
// results — every state and link load on the 1 ms output grid, and the link-load peaks located
// where the load rate changes sign (the limit for this job). Then chains of N masses (10, 100, 1000) for the cost per simulated second.
// Prints one line per case: name, wall time (median of repeats), steps.
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fmt/format.h>
#include <string>
#include <vector>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"

using namespace machdyn;

namespace {

template <class F>
double median_seconds(F&& f, int repeats) {
  std::vector<double> t;
  for (int r = 0; r < repeats; ++r) {
    const auto a = std::chrono::steady_clock::now();
    f();
    t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
  }
  std::sort(t.begin(), t.end());
  return t[t.size() / 2];
}

// ---- Hand-written Dormand–Prince 5(4) for the hoist, fixed size 6, outputs M12, M23 on the grid.
struct Hoist {
  double I1, I2, I3, c1, c2, Msp, MB;
  void f(const double* y, double* d) const {
    const double M12 = c1 * (y[0] - y[2]), M23 = c2 * (y[2] - y[4]);
    d[0] = y[1];
    d[1] = (Msp - M12) / I1;
    d[2] = y[3];
    d[3] = (M12 - M23 - MB) / I2;
    d[4] = y[5];
    d[5] = M23 / I3;
  }
};

struct HandResult {
  long steps = 0;
  std::vector<std::vector<double>> cols;  // t, q1, v1, q2, v2, q3, v3, M12, M23 — what machdyn writes
  double max[2] = {-1e300, -1e300}, min[2] = {1e300, 1e300}, t_max[2] = {0, 0};
};

HandResult hand_dopri(const Hoist& h, const double* y0in, double T, double dt_out, double rtol, double atol) {
  constexpr int n = 6;
  using V = std::array<double, n>;
  constexpr double a21 = 1.0 / 5, a31 = 3.0 / 40, a32 = 9.0 / 40, a41 = 44.0 / 45, a42 = -56.0 / 15,
                   a43 = 32.0 / 9, a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561,
                   a54 = -212.0 / 729, a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247,
                   a64 = 49.0 / 176, a65 = -5103.0 / 18656, a71 = 35.0 / 384, a73 = 500.0 / 1113,
                   a74 = 125.0 / 192, a75 = -2187.0 / 6784, a76 = 11.0 / 84, e1 = 71.0 / 57600,
                   e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200, e6 = 22.0 / 525,
                   e7 = -1.0 / 40, d1 = -12715105075.0 / 11282082432, d3 = 87487479700.0 / 32700410799,
                   d4 = -10690763975.0 / 1880347072, d5 = 701980252875.0 / 199316789632,
                   d6 = -1453857185.0 / 822651844, d7 = 69997945.0 / 29380423;
  V y, y1, k1, k2, k3, k4, k5, k6, k7, yt, r1, r2, r3, r4, r5;
  std::copy(y0in, y0in + n, y.begin());
  h.f(y.data(), k1.data());
  // Initial step as Hairer's HINIT.
  double dnf = 0, dny = 0;
  for (int i = 0; i < n; ++i) {
    const double sk = atol + rtol * std::abs(y[i]);
    dnf += (k1[i] / sk) * (k1[i] / sk), dny += (y[i] / sk) * (y[i] / sk);
  }
  double hs = (dnf <= 1e-10 || dny <= 1e-10) ? 1e-6 : std::sqrt(dny / dnf) * 0.01;
  for (int i = 0; i < n; ++i) yt[i] = y[i] + hs * k1[i];
  h.f(yt.data(), k2.data());
  double der2 = 0;
  for (int i = 0; i < n; ++i) {
    const double sk = atol + rtol * std::abs(y[i]);
    der2 += ((k2[i] - k1[i]) / sk) * ((k2[i] - k1[i]) / sk);
  }
  der2 = std::sqrt(der2) / hs;
  const double der12 = std::max(der2, std::sqrt(dnf));
  hs = std::min(100 * hs, der12 <= 1e-15 ? std::max(1e-6, hs * 1e-3) : std::pow(0.01 / der12, 0.2));

  HandResult res;
  const long n_out = std::lround(T / dt_out);
  res.cols.assign(9, {});
  for (auto& col : res.cols) col.reserve(static_cast<size_t>(n_out + 1));
  auto record = [&](double tk, const double* s) {
    res.cols[0].push_back(tk);
    for (int i = 0; i < n; ++i) res.cols[static_cast<size_t>(1 + i)].push_back(s[i]);
    res.cols[7].push_back(h.c1 * (s[0] - s[2]));
    res.cols[8].push_back(h.c2 * (s[2] - s[4]));
  };
  // Link loads M12 = c1 (q1 − q2), M23 = c2 (q2 − q3); rates from the velocities.
  auto load = [&](int j, const double* s) { return j == 0 ? h.c1 * (s[0] - s[2]) : h.c2 * (s[2] - s[4]); };
  auto rate = [&](int j, const double* ds) { return j == 0 ? h.c1 * (ds[0] - ds[2]) : h.c2 * (ds[2] - ds[4]); };
  auto consider = [&](int j, double tt, const double* s) {
    const double v = load(j, s);
    if (v > res.max[j]) res.max[j] = v, res.t_max[j] = tt;
    if (v < res.min[j]) res.min[j] = v;
  };
  record(0.0, y.data());
  double rate_prev[2] = {rate(0, k1.data()), rate(1, k1.data())};
  consider(0, 0.0, y.data());
  consider(1, 0.0, y.data());
  long k = 1;
  double t = 0, facold = 1e-4;
  bool rejected = false;
  while (t < T) {
    double step = hs;
    bool last = false;
    if (t + 1.01 * step >= T) step = T - t, last = true;
    for (int i = 0; i < n; ++i) yt[i] = y[i] + step * a21 * k1[i];
    h.f(yt.data(), k2.data());
    for (int i = 0; i < n; ++i) yt[i] = y[i] + step * (a31 * k1[i] + a32 * k2[i]);
    h.f(yt.data(), k3.data());
    for (int i = 0; i < n; ++i) yt[i] = y[i] + step * (a41 * k1[i] + a42 * k2[i] + a43 * k3[i]);
    h.f(yt.data(), k4.data());
    for (int i = 0; i < n; ++i) yt[i] = y[i] + step * (a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i]);
    h.f(yt.data(), k5.data());
    for (int i = 0; i < n; ++i)
      yt[i] = y[i] + step * (a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i]);
    h.f(yt.data(), k6.data());
    for (int i = 0; i < n; ++i)
      y1[i] = y[i] + step * (a71 * k1[i] + a73 * k3[i] + a74 * k4[i] + a75 * k5[i] + a76 * k6[i]);
    h.f(y1.data(), k7.data());
    double err = 0;
    for (int i = 0; i < n; ++i) {
      const double e = step * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]);
      const double sk = atol + rtol * std::max(std::abs(y[i]), std::abs(y1[i]));
      err += (e / sk) * (e / sk);
    }
    err = std::sqrt(err / n);
    const double fac11 = std::pow(err, 0.17);
    double fac = std::max(0.1, std::min(5.0, fac11 / std::pow(facold, 0.04) / 0.9));
    double hnew = step / fac;
    if (err <= 1.0) {
      facold = std::max(err, 1e-4);
      for (int i = 0; i < n; ++i) {
        const double ydiff = y1[i] - y[i], bspl = step * k1[i] - ydiff;
        r1[i] = y[i], r2[i] = ydiff, r3[i] = bspl, r4[i] = ydiff - step * k7[i] - bspl;
        r5[i] = step * (d1 * k1[i] + d3 * k3[i] + d4 * k4[i] + d5 * k5[i] + d6 * k6[i] + d7 * k7[i]);
      }
      const double t_old = t;
      t = last ? T : t + step;
      auto dense = [&](double tt, double* q) {
        const double th = (tt - t_old) / step, th1 = 1 - th;
        for (int i = 0; i < n; ++i) q[i] = r1[i] + th * (r2[i] + th1 * (r3[i] + th * (r4[i] + th1 * r5[i])));
      };
      auto dense_rate = [&](int j, double tt) {
        const double th = (tt - t_old) / step, g3 = 1 - 2 * th, g4 = th * (2 - 3 * th),
                     g5 = 2 * th * (1 - th) * (1 - 2 * th);
        double d[n];
        for (int i = 0; i < n; ++i) d[i] = (r2[i] + g3 * r3[i] + g4 * r4[i] + g5 * r5[i]) / step;
        return rate(j, d);
      };
      for (; k <= n_out && (k == n_out ? T : k * dt_out) <= t; ++k) {
        const double tk = k == n_out ? T : k * dt_out;
        double q[n];
        dense(tk, q);
        record(tk, q);
      }
      // Peaks: an interior extremum where the rate changes sign, by the Illinois method.
      for (int j = 0; j < 2; ++j) {
        const double r1j = rate(j, k7.data());
        if ((rate_prev[j] > 0 && r1j < 0) || (rate_prev[j] < 0 && r1j > 0)) {
          double a = t_old, b = t, ra = rate_prev[j], rb = r1j;
          int side = 0;
          for (int it = 0; it < 100 && b - a > 1e-15 * std::max(1.0, std::abs(b)); ++it) {
            double tm = (a * rb - b * ra) / (rb - ra);
            if (!(tm > a && tm < b)) tm = 0.5 * (a + b);
            const double rm = dense_rate(j, tm);
            if (rm == 0.0) { a = b = tm; break; }
            if ((rm > 0) == (ra > 0)) { a = tm, ra = rm; if (side == -1) rb *= 0.5; side = -1; }
            else { b = tm, rb = rm; if (side == 1) ra *= 0.5; side = 1; }
          }
          double q[n];
          dense(0.5 * (a + b), q);
          consider(j, 0.5 * (a + b), q);
        }
        consider(j, t, y1.data());
        rate_prev[j] = r1j;
      }
      y = y1;
      k1 = k7;
      if (rejected) hnew = std::min(hnew, step);
      hs = last ? std::max(hnew, hs) : hnew;
      rejected = false;
      ++res.steps;
    } else {
      hs = step / std::min(5.0, fac11 / 0.9);
      rejected = true;
    }
  }
  return res;
}

std::string chain_model(int N) {
  std::string s = fmt::format("name: chain of {} masses\nbodies:\n", N);
  for (int i = 0; i < N; ++i) s += fmt::format("  b{}: {{inertia: {}}}\n", i, 1.0 + 0.1 * (i % 7));
  s += "links:\n";
  for (int i = 0; i + 1 < N; ++i)
    s += fmt::format("  k{}: {{type: spring-damper, between: [b{}, b{}], stiffness: 1e4, damping: 0.5}}\n", i, i, i + 1);
  s += "loads:\n  M: {type: constant, body: b0, value: 100}\n";
  s += "simulation: {t_end: 1, dt_out: 1e-3, rtol: 1e-8, atol: 1e-10, integrator: dopri5}\n";
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  const bool hoist_only = argc > 1 && std::string(argv[1]) == "hoist";
  const std::vector<std::string> sets = {"simulation.t_end=10", "simulation.rtol=1e-8", "simulation.atol=1e-10",
                                         "simulation.dt_out=1e-3", "simulation.integrator=dopri5"};
  const Model m = load_model(std::string(MACHDYN_SOURCE_DIR) + "/examples/hoist-3mass.yaml", sets);
  SimulationResult r;
  const double t_md = median_seconds([&] { r = simulate(m); }, 15);
  const Hoist h{m.bodies[0].inertia, m.bodies[1].inertia, m.bodies[2].inertia, m.links[0].c, m.links[1].c,
                m.loads[0].value, -m.loads[1].value};
  const double y0[6] = {m.bodies[0].q0, 0, m.bodies[1].q0, 0, m.bodies[2].q0, 0};
  HandResult hr;
  const double t_hand = median_seconds([&] { hr = hand_dopri(h, y0, 10.0, 1e-3, 1e-8, 1e-10); }, 15);
  double maxdiff = 0;
  for (size_t i = 0; i < hr.cols[7].size(); ++i) maxdiff = std::max(maxdiff, std::abs(hr.cols[7][i] - r.columns[7][i]));
  std::printf("hoist machdyn  %.6f s  steps %ld  max M12 %.9g at %.9g s\n", t_md, r.stats.stepper.steps, r.links[0].max,
              r.links[0].t_max);
  std::printf("hoist hand     %.6f s  steps %ld  max M12 %.9g at %.9g s  max|dM12| vs machdyn %.3g N*m\n", t_hand,
              hr.steps, hr.max[0], hr.t_max[0], maxdiff);
  if (hoist_only) return 0;
  for (int N : {10, 100, 1000}) {
    SpecNode root = parse_yaml_string(chain_model(N), fmt::format("chain{}", N));
    const Model cm = compile_model(root, fmt::format("chain{}", N));
    SimulationResult cr;
    const double t = median_seconds([&] { cr = simulate(cm); }, N >= 1000 ? 3 : 7);
    std::printf("chain N=%-5d  %.6f s per simulated s  steps %ld  %.3g us per step per mass\n", N, t,
                cr.stats.stepper.steps, 1e6 * t / static_cast<double>(cr.stats.stepper.steps) / N);
  }
  return 0;
}
