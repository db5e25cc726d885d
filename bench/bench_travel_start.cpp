// Travel start-up (paper 001), 2 s: machdyn's hybrid simulation against a hand-written event loop
// with the same method (the same Dopri5 stepper, Illinois on the dense output, restart at events)
// but the three-mass equations, modes and decisions written out for this one model. Both do the
// same job: the 15 output columns on the 0.5 ms grid (states, link force, contact forces, sliding
// speeds and modes, gap mode), the work and losses integrated as extra states, and the link-force
// maximum located where its rate changes sign.
//   bench_travel_start EXAMPLES/travel-start.yaml [repeats]
#include <chrono>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>
#include <Eigen/Dense>

#include "solve/dopri5.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/model/compile.hpp"

using namespace machdyn;

namespace {

struct Params {
  double m1, mk, m2, c, Delta, P, Fsc, Fd, W;
};

// Modes: gap (0 open, 1 closed), adhesion (0 stuck, 1 slipping forward), W (0 stuck, 1 sliding).
struct Hand final : OdeSystem {
  Params p;
  int gap = 0, adh = 0, res = 0;
  explicit Hand(const Params& q) : p(q) {}
  int size() const override { return 9; }  // + work of P, friction loss, damping loss
  // y = [x1, xk, x2, v1, vk, v2]; returns the link force, adhesion force, resistance force.
  void forces(const double* y, double* a, double* Fl, double* Fa, double* Fw) const {
    const double F = gap ? p.c * (y[0] - y[1] - p.Delta) : 0.0;
    a[0] = (p.P - F) / p.m1;
    if (adh == 0 && res == 0) {  // mk, m2 locked to the ground
      a[1] = a[2] = 0.0;
      *Fa = F;
      *Fw = F;
    } else if (adh == 0) {  // mk + m2 together against W
      const double acc = (F - p.W) / (p.mk + p.m2);
      a[1] = a[2] = acc;
      *Fa = F - p.mk * acc;
      *Fw = p.W;
    } else {
      a[1] = (F - p.Fd) / p.mk;
      if (res == 0) {
        a[2] = 0.0;
        *Fw = p.Fd;
      } else {
        a[2] = (p.Fd - p.W) / p.m2;
        *Fw = p.W;
      }
      *Fa = p.Fd;
    }
    *Fl = F;
  }
  void rhs(double, const double* y, double* dy) override {
    double Fl, Fa, Fw;
    dy[0] = y[3], dy[1] = y[4], dy[2] = y[5];
    forces(y, dy + 3, &Fl, &Fa, &Fw);
    dy[6] = p.P * y[3];
    dy[7] = (adh ? p.Fd * (y[4] - y[5]) : 0.0) + (res ? p.W * y[5] : 0.0);
    dy[8] = 0.0;
  }
  // Event functions, >= 0 while the mode holds.
  void events(const double* y, double* g) const {
    double a[3], Fl, Fa, Fw;
    forces(y, a, &Fl, &Fa, &Fw);
    g[0] = gap ? Fl : p.Delta - (y[0] - y[1]);
    g[1] = adh ? y[4] - y[5] : p.Fsc - Fa;
    g[2] = res ? y[5] : p.W - Fw;
  }
};

struct HandOut {
  std::vector<std::vector<double>> cols = std::vector<std::vector<double>>(15);
  double Fmax = 0, t_Fmax = 0;
};

__attribute__((noinline)) long hand_loop(const Params& p, double t_end, double dt_out, HandOut& out) {
  Hand sys(p);
  StepperOptions opt;
  opt.rtol = 1e-10, opt.atol = 1e-12;
  Dopri5<9> st(sys, opt);
  std::vector<double> y(9, 0.0), ym(9), dm(9);
  double g0[3], g1[3], gm[3];
  double t = 0;
  for (auto& col : out.cols) col.clear();
  out.Fmax = 0;
  const long n_out = std::lround(t_end / dt_out);
  long k_out = 0;
  auto record = [&](double tk, const double* s) {
    double a[3], Fl, Fa, Fw;
    sys.forces(s, a, &Fl, &Fa, &Fw);
    const double row[15] = {tk, s[0], s[3], s[1], s[4], s[2], s[5], Fl, Fa, s[4] - s[5], double(sys.adh), Fw, s[5],
                            double(sys.res), double(sys.gap)};
    for (int c = 0; c < 15; ++c) out.cols[static_cast<size_t>(c)].push_back(row[c]);
  };
  auto rate = [&](const double* d) { return sys.gap ? p.c * (d[0] - d[1]) : 0.0; };
  auto force = [&](const double* s) { return sys.gap ? p.c * (s[0] - s[1] - p.Delta) : 0.0; };
  // Outputs and the exact link-force maximum on [ta, tb] of the current step.
  auto segment = [&](double ta, double tb, double ra) {
    for (; k_out <= n_out && (k_out == n_out ? t_end : static_cast<double>(k_out) * dt_out) <= tb; ++k_out) {
      const double tk = k_out == n_out ? t_end : static_cast<double>(k_out) * dt_out;
      st.interpolate(tk, ym.data());
      record(tk, ym.data());
    }
    st.interpolate(tb, ym.data());
    st.derivative(tb, dm.data());
    const double Fb = force(ym.data()), rb = rate(dm.data());
    if (Fb > out.Fmax) out.Fmax = Fb, out.t_Fmax = tb;
    if (ra > 0 && rb < 0) {
      double a = ta, b = tb, r0 = ra, r1 = rb;
      int side = 0;
      for (int it = 0; it < 100 && b - a > 1e-15 * std::max(1.0, b); ++it) {
        double tm = (a * r1 - b * r0) / (r1 - r0);
        if (!(tm > a && tm < b)) tm = 0.5 * (a + b);
        st.derivative(tm, dm.data());
        const double r = rate(dm.data());
        if ((r > 0) == (r0 > 0)) { a = tm, r0 = r; if (side == -1) r1 *= 0.5; side = -1; }
        else { b = tm, r1 = r; if (side == 1) r0 *= 0.5; side = 1; }
      }
      st.interpolate(0.5 * (a + b), ym.data());
      const double F = force(ym.data());
      if (F > out.Fmax) out.Fmax = F, out.t_Fmax = 0.5 * (a + b);
    }
    return rb;
  };
  st.reset(0, y.data());
  sys.events(y.data(), g0);
  double r_prev = rate(st.dydt());
  long events = 0;
  while (t < t_end) {
    st.step(t_end);
    sys.events(st.y(), g1);
    int first = -1;
    double hi_b = 1e300;
    for (int k = 0; k < 3; ++k) {
      if (!(g0[k] >= 0 && g1[k] < 0)) continue;
      double lo = st.t_prev(), hi = st.t(), a = g0[k], b = g1[k];
      int side = 0;
      while (hi - lo > 1e-13 * std::max(1.0, hi)) {
        double tm = (lo * b - hi * a) / (b - a);
        if (!(tm > lo && tm < hi)) tm = 0.5 * (lo + hi);
        st.interpolate(tm, ym.data());
        sys.events(ym.data(), gm);
        if (gm[k] >= 0) { lo = tm, a = gm[k]; if (side == -1) b *= 0.5; side = -1; }
        else { hi = tm, b = gm[k]; if (side == 1) a *= 0.5; side = 1; }
      }
      if (hi < hi_b) hi_b = hi, first = k;
    }
    if (first < 0) {
      r_prev = segment(st.t_prev(), st.t(), r_prev);
      std::copy(g1, g1 + 3, g0);
      t = st.t();
      continue;
    }
    segment(st.t_prev(), hi_b, r_prev);
    t = hi_b;
    st.interpolate(t, y.data());
    ++events;
    if (first == 0) sys.gap = !sys.gap;
    if (first == 1) {
      if (sys.adh) {  // re-stick if the locked pair can hold
        sys.adh = 0;
        y[4] = y[5] = (p.mk * y[4] + p.m2 * y[5]) / (p.mk + p.m2);
        double a[3], Fl, Fa, Fw;
        sys.forces(y.data(), a, &Fl, &Fa, &Fw);
        if (Fa > p.Fsc) sys.adh = 1;
      } else {
        sys.adh = 1;
      }
    }
    if (first == 2) {
      if (sys.res) sys.res = 0, y[5] = 0;
      else sys.res = 1;
    }
    st.reset(t, y.data());
    sys.events(y.data(), g0);
    r_prev = rate(st.dydt());
  }
  return events;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_travel_start MODEL [repeats]\n");
    return 2;
  }
  const Model m = load_model(argv[1], {"simulation.t_end=2"});
  const int repeats = argc > 2 ? std::stoi(argv[2]) : 50;
  const Params p{m.bodies[0].inertia, m.bodies[1].inertia, m.bodies[2].inertia, m.links[0].c, m.links[0].gap,
                 m.loads[0].value, m.contacts[0].static_limit, m.contacts[0].kinetic[0], m.contacts[1].static_limit};
  auto best = [&](auto&& f) {
    double b = 1e300;
    for (int i = 0; i < repeats; ++i) {
      const auto t0 = std::chrono::steady_clock::now();
      f();
      b = std::min(b, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
    }
    return b;
  };
  SimulationResult r;
  const double t_md = best([&] { r = simulate(m); });
  long ev_md = 0;
  for (const auto& e : r.hybrid.events) ev_md += e.kind != "initial";
  HandOut ho;
  long ev_hand = 0;
  const double t_hand = best([&] { ev_hand = hand_loop(p, 2.0, m.simulation.dt_out, ho); });
  std::printf("machdyn simulate        : %8.3f ms  %ld events  %ld steps  F_max %.6g N (incl. CSV rows every %g s)\n",
              t_md * 1e3, ev_md, r.stats.stepper.steps, r.links[0].max, m.simulation.dt_out);
  std::printf("hand-written event loop : %8.3f ms  %ld events  F_max %.6g N at %.9g s (machdyn: at %.9g s)\n",
              t_hand * 1e3, ev_hand, ho.Fmax, ho.t_Fmax, r.links[0].t_max);
  std::printf("ratio machdyn / hand    : %8.2f\n", t_md / t_hand);
  // Cost per step and per event: summary-only runs to t_end = 0.25, 0.5, …, 2 s (events and steps
  // grow at different rates over the start-up), fitted by least squares as
  // wall = fixed + c_step · steps + c_event · events.
  SimulateOptions lean;
  lean.record_series = false;
  Eigen::MatrixXd X(8, 3);
  Eigen::VectorXd y(8);
  for (int i = 0; i < 8; ++i) {
    Model part = m;
    part.simulation.t_end = 0.25 * (i + 1);
    SimulationResult rp;
    y(i) = best([&] { rp = simulate(part, lean); });
    long ev = 0;
    for (const auto& e : rp.hybrid.events) ev += e.kind != "initial";
    X(i, 0) = 1.0, X(i, 1) = static_cast<double>(rp.stats.stepper.steps), X(i, 2) = static_cast<double>(ev);
  }
  const Eigen::Vector3d c = X.colPivHouseholderQr().solve(y);
  std::printf("cost per step           : %8.3f us   cost per event: %.3f us   fixed: %.3f ms (fit over 8 runs of 0.25..2 s, residual %.2g ms)\n",
              c(1) * 1e6, c(2) * 1e6, c(0) * 1e3, (X * c - y).norm() * 1e3);
  return 0;
}
