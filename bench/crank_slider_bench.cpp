// Benchmark (not a test): the crank-slider of examples/crank-slider.yaml running 100 revolutions,
//   (1) machdyn: load_model + simulate (DOPRI5, the library's stepper, DriveSystem with a machine),
//   (2) a hand-written DOPRI5 loop (Hairer's step control with the same PI constants) on the same
//       equation I(φ) φ'' + ½ I′(φ) φ'² = M + F(φ) s′(φ), written out inline.
// Prints one line per variant: name, wall time per run (best of N), steps, final φ and ω.
// Build and run: bench/run-issue4.sh BUILD_DIR
#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/model/compile.hpp"

namespace {

constexpr double kPi = std::numbers::pi;
// The example's data (SI).
constexpr double r = 0.04, l = 0.16, m_rod = 1.2, a = l / 3, J_rod = m_rod * a * (l - a), m_p = 1.6, J_c = 0.08,
                 M_drive = 24.66;
const std::array<double, 8> tab_x = {0, 20, 40, 180, 240, 290, 320, 335};
const std::array<double, 8> tab_F = {6000, 2500, 0, 0, 600, 2000, 4500, 6000};

double gas_force(double phi) {
  double d = std::fmod(phi * 180 / kPi, 360.0);
  if (d < 0) d += 360;
  if (d >= 335) return 6000;
  size_t k = 1;
  while (tab_x[k] < d) ++k;
  return tab_F[k - 1] + (tab_F[k] - tab_F[k - 1]) * (d - tab_x[k - 1]) / (tab_x[k] - tab_x[k - 1]);
}

/// y = [φ, ω] → [ω, ε].
void rhs(const double* y, double* f) {
  const double phi = y[0], w = y[1], lam = r / l, s = std::sin(phi), c = std::cos(phi);
  const double u = lam * s, cp = std::sqrt(1 - u * u), dpsi = lam * c / cp;
  const double ddpsi = -lam * s / cp + lam * lam * lam * s * c * c / (cp * cp * cp);
  auto px = [&](double d, double* d1, double* d2) {
    *d1 = -r * s - d * u * dpsi;
    *d2 = -r * c - d * (lam * c * dpsi + u * ddpsi);
  };
  double gx1, gx2, bx1, bx2;
  px(a, &gx1, &gx2);
  px(l, &bx1, &bx2);
  const double gy1 = r * c * (1 - a / l), gy2 = -r * s * (1 - a / l);
  const double I = J_c + m_rod * (gx1 * gx1 + gy1 * gy1) + J_rod * dpsi * dpsi + m_p * bx1 * bx1;
  const double dI = 2 * m_rod * (gx1 * gx2 + gy1 * gy2) + 2 * J_rod * dpsi * ddpsi + 2 * m_p * bx1 * bx2;
  const double Q = M_drive + gas_force(phi) * (-bx1);  // s′ = −dx_B/dφ
  f[0] = w;
  f[1] = (Q - 0.5 * dI * w * w) / I;
}

struct LoopResult {
  long steps;
  double phi, w;
};

LoopResult hand_dopri5(double t_end, double rtol, double atol) {
  static const double c2 = 1. / 5, c3 = 3. / 10, c4 = 4. / 5, c5 = 8. / 9;
  static const double a21 = 1. / 5, a31 = 3. / 40, a32 = 9. / 40, a41 = 44. / 45, a42 = -56. / 15, a43 = 32. / 9,
                      a51 = 19372. / 6561, a52 = -25360. / 2187, a53 = 64448. / 6561, a54 = -212. / 729,
                      a61 = 9017. / 3168, a62 = -355. / 33, a63 = 46732. / 5247, a64 = 49. / 176,
                      a65 = -5103. / 18656, a71 = 35. / 384, a73 = 500. / 1113, a74 = 125. / 192,
                      a75 = -2187. / 6784, a76 = 11. / 84;
  static const double e1 = 71. / 57600, e3 = -71. / 16695, e4 = 71. / 1920, e5 = -17253. / 339200, e6 = 22. / 525,
                      e7 = -1. / 40;
  (void)c2, (void)c3, (void)c4, (void)c5;
  double y[2] = {0.0, 150.0}, k1[2], k2[2], k3[2], k4[2], k5[2], k6[2], k7[2], yt[2], y1[2];
  double t = 0, h = 1e-5, facold = 1e-4;
  long steps = 0;
  rhs(y, k1);
  while (t < t_end) {
    if (t + h > t_end) h = t_end - t;
    for (int i = 0; i < 2; ++i) yt[i] = y[i] + h * a21 * k1[i];
    rhs(yt, k2);
    for (int i = 0; i < 2; ++i) yt[i] = y[i] + h * (a31 * k1[i] + a32 * k2[i]);
    rhs(yt, k3);
    for (int i = 0; i < 2; ++i) yt[i] = y[i] + h * (a41 * k1[i] + a42 * k2[i] + a43 * k3[i]);
    rhs(yt, k4);
    for (int i = 0; i < 2; ++i) yt[i] = y[i] + h * (a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i]);
    rhs(yt, k5);
    for (int i = 0; i < 2; ++i)
      yt[i] = y[i] + h * (a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i]);
    rhs(yt, k6);
    for (int i = 0; i < 2; ++i) y1[i] = y[i] + h * (a71 * k1[i] + a73 * k3[i] + a74 * k4[i] + a75 * k5[i] + a76 * k6[i]);
    rhs(y1, k7);
    double err = 0;
    for (int i = 0; i < 2; ++i) {
      const double e = h * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]);
      const double sk = atol + rtol * std::max(std::abs(y[i]), std::abs(y1[i]));
      err += (e / sk) * (e / sk);
    }
    err = std::sqrt(err / 2);
    // Hairer's PI control: safe 0.9, factor bounds [0.1, 5]... as written in DOPRI5.
    const double beta = 0.04, expo1 = 0.2 - beta * 0.75;
    const double fac11 = std::pow(std::max(err, 1e-300), expo1);
    double fac = fac11 / std::pow(facold, beta) / 0.9;
    fac = std::max(1.0 / 5.0, std::min(1.0 / 0.1, fac));
    if (err <= 1.0) {
      facold = std::max(err, 1e-4);
      t += h;
      y[0] = y1[0], y[1] = y1[1];
      k1[0] = k7[0], k1[1] = k7[1];
      ++steps;
      h = h / fac;
    } else {
      h = h / std::min(1.0 / 0.1, fac11 / 0.9);
    }
  }
  return {steps, y[0], y[1]};
}

template <class F>
double best_of(int n, F&& f) {
  double best = 1e300;
  for (int i = 0; i < n; ++i) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string model = argc > 1 ? argv[1] : "examples/crank-slider.yaml";
  const double rtol = 1e-10, atol = 1e-12;
  const double t_end = 100 * 2 * kPi / 150.0;  // about 100 revolutions at the mean speed
  const std::vector<std::string> sets = {"simulation.t_end=" + std::to_string(t_end),
                                         "simulation.dt_out=" + std::to_string(t_end / 10),
                                         "simulation.rtol=1e-10", "simulation.atol=1e-12",
                                         "simulation.integrator=dopri5"};
  machdyn::SimulationResult res;
  const machdyn::Model m = machdyn::load_model(model, sets);  // reading the file is not timed
  const double t_lib = best_of(5, [&] { res = machdyn::simulate(m); });
  LoopResult hand{};
  const double t_hand = best_of(5, [&] { hand = hand_dopri5(res.columns[0].back(), rtol, atol); });
  std::printf("t_end %.9g s, %.3f revolutions, rtol %g, atol %g\n", res.columns[0].back(),
              res.columns[1].back() / (2 * kPi), rtol, atol);
  std::printf("%-22s %10.3f ms %8ld steps %8ld f-evals  phi_end %.12g  omega_end %.12g\n", "machdyn (simulate)",
              t_lib * 1e3, res.stats.stepper.steps, res.stats.stepper.rhs_evals, res.columns[1].back(),
              res.columns[2].back());
  std::printf("%-22s %10.3f ms %8ld steps %8s f-evals  phi_end %.12g  omega_end %.12g\n", "hand-written DOPRI5",
              t_hand * 1e3, hand.steps, "-", hand.phi, hand.w);
  return 0;
}
