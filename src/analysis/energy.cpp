#include "machdyn/analysis/energy.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <fmt/format.h>

#include "machdyn/analysis/machine_outputs.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/model/element.hpp"
#include "machdyn/model/machine.hpp"
#include "machdyn/solve/roots.hpp"

namespace machdyn {

// ---------------------------------------------------------------------------------------------
// Adaptive Gauss–Kronrod 7–15 (nodes and weights of QUADPACK's qk15).

namespace {
constexpr double kXgk[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                            0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                            0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                            0.207784955007898467600689403773245, 0.0};
constexpr double kWgk[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                            0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                            0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                            0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kWg[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                           0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

void gk15(const std::function<double(double)>& f, double a, double b, double* k, double* err) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  const double fc = f(c);
  double rk = fc * kWgk[7], rg = fc * kWg[3];
  for (int j = 0; j < 7; ++j) {
    const double dx = h * kXgk[j];
    const double s = f(c - dx) + f(c + dx);
    rk += kWgk[j] * s;
    if (j % 2 == 1) rg += kWg[j / 2] * s;
  }
  *k = rk * h;
  *err = std::abs((rk - rg) * h);
}

double integrate_abs15(const std::function<double(double)>& f, double a, double b) {
  const double c = 0.5 * (a + b), h = 0.5 * (b - a);
  double r = std::abs(f(c)) * kWgk[7];
  for (int j = 0; j < 7; ++j) r += kWgk[j] * (std::abs(f(c - h * kXgk[j])) + std::abs(f(c + h * kXgk[j])));
  return r * h;
}

/// Globally adaptive: bisect the panel with the largest error estimate until the total error is
/// within tolerance, the panels reach round-off, or 4000 panels (QUADPACK's QAG strategy).
double adapt(const std::function<double(double)>& f, double a, double b, double rel, double abs_tol) {
  struct Panel {
    double a, b, k, err;
    bool operator<(const Panel& o) const { return err < o.err; }
  };
  std::vector<Panel> heap;
  Panel p{a, b, 0, 0};
  gk15(f, a, b, &p.k, &p.err);
  heap.push_back(p);
  double total = p.k, err = p.err;
  // Scale of the integrand: ∫|f| by the 15-point rule, so a nearly cancelling integral (a balanced
  // cycle) is judged against the size of its parts, not against its small sum.
  const double scale = std::abs(integrate_abs15(f, a, b));
  for (int it = 0; it < 20000; ++it) {
    if (err <= std::max(abs_tol, rel * std::max(std::abs(total), scale))) break;
    std::pop_heap(heap.begin(), heap.end());
    const Panel w = heap.back();
    const double c = 0.5 * (w.a + w.b);
    if (!(std::abs(w.b - w.a) > 1e-13 * std::max(1.0, std::abs(c)))) break;  // round-off
    heap.pop_back();
    Panel l{w.a, c, 0, 0}, r{c, w.b, 0, 0};
    gk15(f, l.a, l.b, &l.k, &l.err);
    gk15(f, r.a, r.b, &r.k, &r.err);
    total += l.k + r.k - w.k;
    err += l.err + r.err - w.err;
    heap.push_back(l);
    std::push_heap(heap.begin(), heap.end());
    heap.push_back(r);
    std::push_heap(heap.begin(), heap.end());
  }
  double sum = 0;  // re-add to avoid drift from the running updates
  for (const auto& h : heap) sum += h.k;
  return sum;
}

double sign(double x) { return x > 0 ? 1.0 : (x < 0 ? -1.0 : 0.0); }
}  // namespace

double integrate_gk15(const std::function<double(double)>& f, double a, double b, double rel_tol, double abs_tol) {
  if (a == b) return 0.0;
  return adapt(f, a, b, rel_tol, abs_tol);
}

// ---------------------------------------------------------------------------------------------
// EnergyIntegral

EnergyIntegral::EnergyIntegral(const Model& m, double added_inertia, double extra_torque)
    : added_(added_inertia), constant_torque_(extra_torque) {
  Diagnostics diag;
  // Each problem at the element that causes it (the second body, the first link, the contact...).
  const Location where = m.dof() > 1  ? m.where(m.bodies[1].name)
                         : !m.links.empty() ? m.where(m.links.front().name)
                         : m.dof() == 1     ? m.where(m.bodies[0].name)
                                            : Location{m.source, 0, 0};
  if (m.dof() != 1 || !m.links.empty())
    diag.error(where, fmt::format("the energy integral needs a model with one body and no links; '{}' has {} "
                                  "bodies and {} links",
                                  m.name, m.dof(), m.links.size()));
  if (!m.contacts.empty())
    diag.error(m.where(m.contacts.front().name), fmt::format("'{}' has friction contacts or brakes ('{}'), whose modes switch, so the motion has "
                                  "no single energy integral; simulate it instead",
                                  m.name, m.contacts.front().name));
  for (const auto& ld : m.loads) {
    if (ld.kind == LoadKind::constant) constant_torque_ += ld.value;
    else
      diag.error(m.where(ld.name), fmt::format("load '{}' depends on time or speed, so the motion has no energy integral; "
                                    "only constant loads and the machine's own forces can be used",
                                    ld.name));
  }
  for (const auto& d : m.drives)
    diag.error(m.where(d.name),
               d.states() > 0 ? fmt::format("drive '{}' has states of its own (current, controller), so the motion has "
                                            "no energy integral; simulate it instead",
                                            d.name)
                              : fmt::format("'{}' ({}) is not part of the energy integral; simulate it instead", d.name,
                                            d.law->type()));
  if (m.dof() == 1 && m.bodies[0].machine && m.bodies[0].machine->has_jumps())
    diag.error(m.where(m.bodies[0].name), fmt::format("body '{}' has velocity jumps (a stepwise gear ratio): kinetic energy is lost at "
                                  "every jump, so the energy integral does not hold; use `simulate`",
                                  m.bodies[0].name));
  diag.throw_if_any();
  body_ = &m.bodies[0];
  q0_ = body_->q0;
  omega0_ = body_->v0;
  s0_ = s_of_q(q0_);
}

double EnergyIntegral::q_of_s(double s) const {
  double d;
  return body_->machine ? body_->machine->q_of_s(s, &d) : s;
}
double EnergyIntegral::s_of_q(double q) const { return body_->machine ? body_->machine->s_of_q(q) : q; }

double EnergyIntegral::force_s(double s) const {
  return (body_->machine ? body_->machine->force_of_s(s) : 0.0) + constant_torque_;
}

double EnergyIntegral::inertia_s(double s) const {
  return (body_->machine ? body_->machine->inertia_of_s(s) : body_->inertia) + added_;
}

double EnergyIntegral::work_s(double s_a, double s_b) const {
  const Machine* mach = body_->machine.get();
  auto integrand = [&](double s) {
    double dq = 1.0;
    if (mach) (void)mach->q_of_s(s, &dq);
    return force_s(s) * dq;
  };
  // Split at the kinks of piecewise-linear force tables (s = q for such machines), so that every
  // panel is smooth and Gauss–Kronrod converges fast.
  std::vector<double> cuts = mach && mach->s_name() == "q" ? mach->kinks(s_a, s_b) : std::vector<double>{};
  if (s_b < s_a) std::reverse(cuts.begin(), cuts.end());
  double sum = 0, from = s_a;
  for (double c : cuts) {
    sum += integrate_gk15(integrand, from, c);
    from = c;
  }
  return sum + integrate_gk15(integrand, from, s_b);
}

double EnergyIntegral::work(double q) const { return work_s(s0_, s_of_q(q)); }

double EnergyIntegral::omega_squared(double q) const {
  const double s = s_of_q(q);
  return (inertia_s(s0_) * omega0_ * omega0_ + 2.0 * work_s(s0_, s)) / inertia_s(s);
}

double EnergyIntegral::omega(double q) const {
  const double w2 = omega_squared(q);
  return w2 >= 0 ? std::sqrt(w2) : std::numeric_limits<double>::quiet_NaN();
}

// ---------------------------------------------------------------------------------------------
// The scan

namespace {

/// Golden-section search for the maximum of f on [a, b].
double golden_max(const std::function<double(double)>& f, double a, double b) {
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double x1 = b - g * (b - a), x2 = a + g * (b - a), f1 = f(x1), f2 = f(x2);
  for (int it = 0; it < 100 && std::abs(b - a) > 1e-15 * std::max(1.0, std::abs(a)); ++it) {
    if (f1 < f2) {
      a = x1, x1 = x2, f1 = f2, x2 = a + g * (b - a), f2 = f(x2);
    } else {
      b = x2, x2 = x1, f2 = f1, x1 = b - g * (b - a), f1 = f(x1);
    }
  }
  return 0.5 * (a + b);
}

/// A root of f in [a, b] with f(a) f(b) <= 0 (solve/roots.hpp).
double root(const std::function<double(double)>& f, double a, double b) {
  const double fa = f(a), fb = f(b);
  if (fa == 0) return a;
  if (fb == 0) return b;
  const Bracket br = illinois(f, a, fa, b, fb, 4e-16 * std::max({1.0, std::abs(a), std::abs(b)}));
  return 0.5 * (br.lo + br.hi);
}

}  // namespace

EnergyResult energy_analysis(const Model& m, const EnergyOptions& opt) {
  const EnergyIntegral E(m);
  const Body& b = E.body();
  const Machine* mach = b.machine.get();
  EnergyResult r;
  r.body = b.name;
  r.machine = mach ? mach->type() : "constant inertia";
  r.s_name = mach ? mach->s_name() : "q";
  r.point_name = mach ? mach->point_name() : "";
  r.q0 = E.q0();
  r.omega0 = E.omega0();
  const double s0 = E.s0();
  const double I0 = E.inertia_s(s0), E0 = I0 * r.omega0 * r.omega0;
  const double period = mach ? mach->period() : 0.0;
  if (period > 0) r.work_per_period = E.work_s(s0, s0 + period);

  const double Q0 = E.force_s(s0);
  r.direction = r.omega0 != 0 ? sign(r.omega0) : sign(Q0);
  auto row = [&](double s, double A) {
    const double I = E.inertia_s(s), w2 = (E0 + 2 * A) / I;
    return EnergyRow{s, E.q_of_s(s), std::sqrt(std::max(0.0, w2)), I, A};
  };
  if (r.direction == 0) {  // at rest where no force acts: an equilibrium
    r.turning_points = {r.q0};
    r.limit_kind = "none";
    r.table = {row(s0, 0.0)};
    r.q_at_omega_max = r.q_at_omega_min = r.q0;
    return r;
  }
  // The range of the scan.
  std::optional<double> open_end;  // s where the range ends without a turning point (β → π)
  double s_hi;
  if (opt.s_to) {
    s_hi = *opt.s_to;
    if ((s_hi - s0) * r.direction <= 0)
      throw InputError(Location{"--to", 0, 0},
                       fmt::format("the scan must go from {} = {:.6g} in the direction of motion ({})", r.s_name, s0,
                                   r.direction > 0 ? "increasing" : "decreasing"));
    // Bounds: a range with an end (the wheel's β < π) ends there; an open one is scanned over at
    // most kMaxScanPeriods periods (or turns of 2π rad): beyond, even 10^6 rows (--points) would
    // skip whole periods, and the coordinate loses the digits that tell its phase.
    constexpr double kMaxScanPeriods = 1e6;
    const double unit = period > 0 ? period : 2 * std::numbers::pi;
    if (mach && mach->s_end() && s_hi >= *mach->s_end())
      throw InputError(Location{"--to", 0, 0},
                       fmt::format("the range of {} ends at {:.6g}; give --to below it", r.s_name, *mach->s_end()));
    if (std::abs(s_hi - s0) > kMaxScanPeriods * unit)
      throw InputError(Location{"--to", 0, 0},
                       fmt::format("{} = {:.6g} is {:.3g} {} from the start, more than {:.0e}: the table could not "
                                   "resolve them; scan a nearer range", r.s_name, s_hi, std::abs(s_hi - s0) / unit,
                                   period > 0 ? "periods" : "turns of 2 pi rad", kMaxScanPeriods));
  } else if (mach && mach->s_end() && r.direction > 0) {
    open_end = *mach->s_end();
    s_hi = *open_end - 1e-3 * (*open_end - s0);
  } else if (mach && mach->s_end() && r.direction < 0) {
    s_hi = 1e-3 * s0;  // the wheel rolling back: β → 0
  } else {
    s_hi = s0 + r.direction * (period > 0 ? period : 2 * std::numbers::pi);
  }
  const int n = std::max(3, opt.points);
  std::vector<double> sk(static_cast<size_t>(n));
  for (int k = 0; k < n; ++k) sk[static_cast<size_t>(k)] = s0 + (s_hi - s0) * k / (n - 1);

  r.table.push_back(row(s0, 0.0));
  if (r.omega0 == 0) r.turning_points.push_back(r.q0);
  double A = 0.0;
  bool turned = false;
  auto energy_from = [&](double s_a, double A_a) {
    return [&E, s_a, A_a, E0](double s) { return E0 + 2.0 * (A_a + E.work_s(s_a, s)); };
  };
  for (int k = 1; k < n && !turned; ++k) {
    const double sa = sk[static_cast<size_t>(k - 1)], sb = sk[static_cast<size_t>(k)];
    const double Ab = A + E.work_s(sa, sb);
    if (E0 + 2 * Ab < 0) {
      const double st = root(energy_from(sa, A), sa, sb);
      const double At = A + E.work_s(sa, st);
      r.table.push_back(row(st, At));
      r.table.back().omega = 0.0;
      r.turning_points.push_back(E.q_of_s(st));
      turned = true;
    } else {
      r.table.push_back(row(sb, Ab));
    }
    A = Ab;
  }
  // The end of the open range: finite limit, unbounded speed, or a turning point close to it.
  if (!turned && open_end) {
    double scale = 0;
    for (const auto& rw : r.table) scale = std::max(scale, std::abs(E.force_s(rw.s)));
    const double Qend = E.force_s(*open_end);
    const double s_last = r.table.back().s, A_last = r.table.back().work;
    if (std::abs(Qend) <= 1e-12 * std::max(scale, 1e-300)) {
      const double A_end = A_last + E.work_s(s_last, *open_end);
      r.omega_limit = std::sqrt(std::max(0.0, (E0 + 2 * A_end) / E.inertia_s(*open_end)));
      r.limit_kind = "finite";
    } else if (Qend > 0) {
      r.limit_kind = "unbounded";
      // q'' = (Q − ½ I′ ω²)/I with I′ω² → 0 at the end of the range (I′ vanishes faster than ω²
      // grows), so the acceleration tends to Q/I there: paper 000 eq. 30 for the rolling wheel.
      r.epsilon_limit = Qend / E.inertia_s(*open_end);
    } else {
      auto En = energy_from(s_last, A_last);
      for (int j = 4; j <= 14; ++j) {
        const double s = *open_end - std::pow(10.0, -j) * (*open_end - s0);
        if (En(s) < 0) {
          const double st = root(En, s_last, s);
          r.table.push_back(row(st, A_last + E.work_s(s_last, st)));
          r.table.back().omega = 0.0;
          r.turning_points.push_back(E.q_of_s(st));
          turned = true;
          break;
        }
      }
      r.limit_kind = turned ? "turning point" : "none";
    }
  } else {
    r.limit_kind = turned ? "turning point" : "none";
  }
  // Extremes of ω: the table, refined by golden-section search on ω²(s) around the best rows.
  size_t imax = 0, imin = 0;
  for (size_t i = 0; i < r.table.size(); ++i) {
    if (r.table[i].omega > r.table[imax].omega) imax = i;
    if (r.table[i].omega < r.table[imin].omega) imin = i;
  }
  auto refine = [&](size_t i, double sgn, double* w_out, double* q_out) {
    *w_out = r.table[i].omega;
    *q_out = r.table[i].q;
    if (i == 0 || i + 1 >= r.table.size()) return;
    const double sa = r.table[i - 1].s, sb = r.table[i + 1].s, Aa = r.table[i - 1].work;
    auto w2 = [&](double s) { return sgn * (E0 + 2.0 * (Aa + E.work_s(sa, s))) / E.inertia_s(s); };
    const double s = golden_max(w2, std::min(sa, sb), std::max(sa, sb));
    const double v = sgn * w2(s);
    if (sgn * v >= sgn * (*w_out) * (*w_out)) {
      *w_out = std::sqrt(std::max(0.0, v));
      *q_out = E.q_of_s(s);
    }
  };
  refine(imax, 1.0, &r.omega_max, &r.q_at_omega_max);
  refine(imin, -1.0, &r.omega_min, &r.q_at_omega_min);
  return r;
}

// ---------------------------------------------------------------------------------------------
// Steady running and flywheel sizing

namespace {

struct Extremes {
  double wmax, wmin;
};

/// ω extremes over one period for start speed w_s at q0, on a grid then refined.
Extremes periodic_extremes(const EnergyIntegral& E, const std::vector<double>& s, const std::vector<double>& A,
                           double w_s) {
  const double E0 = E.inertia_s(s.front()) * w_s * w_s;
  auto w2 = [&](size_t k) { return (E0 + 2 * A[k]) / E.inertia_s(s[k]); };
  size_t imax = 0, imin = 0;
  std::vector<double> v(s.size());
  for (size_t k = 0; k < s.size(); ++k) {
    v[k] = w2(k);
    if (v[k] > v[imax]) imax = k;
    if (v[k] < v[imin]) imin = k;
  }
  auto refine = [&](size_t i, double sgn) {
    // Periodic: neighbours wrap around (the last node equals the first one period later).
    const size_t n = s.size() - 1;
    size_t ia = i == 0 ? n - 1 : i - 1;
    double sa = s[ia], Aa = A[ia];
    if (i == 0) sa -= s[n] - s[0], Aa -= A[n];
    const double sb = i == n ? s[1] + (s[n] - s[0]) : s[i + 1];
    auto f = [&](double x) { return sgn * (E0 + 2.0 * (Aa + E.work_s(sa, x))) / E.inertia_s(x); };
    const double x = golden_max(f, sa, sb);
    return std::max(sgn * v[i], f(x)) * sgn;
  };
  const double vmax = refine(imax, 1.0), vmin = refine(imin, -1.0);
  if (vmin < 0) throw InputError(Location{"--mean-speed", 0, 0}, "the mean speed is too low: the machine stops within a period");
  return {std::sqrt(vmax), std::sqrt(vmin)};
}

}  // namespace

SteadyResult steady_running(const Model& m, double omega_mean, double delta_target) {
  const EnergyIntegral base(m);
  const Machine* mach = base.body().machine.get();
  const double P = mach ? mach->period() : 0.0;
  if (P <= 0)
    throw InputError(m.dof() > 0 ? m.where(m.bodies[0].name) : Location{m.source, 0, 0},
                     "steady running needs a periodic machine (crank-slider, periodic table, or an expression with "
                     "a period)");
  if (!(omega_mean > 0)) throw InputError(Location{"--mean-speed", 0, 0}, "the mean speed must be positive");
  if (!(delta_target > 0)) throw InputError(Location{"--delta", 0, 0}, "the target δ must be positive");
  SteadyResult r;
  r.omega_mean = omega_mean;
  r.delta_target = delta_target;
  const double s0 = base.s0();
  r.work_per_period = base.work_s(s0, s0 + P);
  r.balancing_torque = -r.work_per_period / P;

  const int n = 720;
  std::vector<double> s(n + 1), A(n + 1);
  double w_start = omega_mean;
  auto analyse = [&](double J, double* wmax, double* wmin) {
    const EnergyIntegral E(m, J, r.balancing_torque);
    if (J == 0.0) {
      for (int k = 0; k <= n; ++k) s[static_cast<size_t>(k)] = s0 + P * k / n;
      A[0] = 0;
      for (int k = 1; k <= n; ++k)
        A[static_cast<size_t>(k)] = A[static_cast<size_t>(k - 1)] + E.work_s(s[static_cast<size_t>(k - 1)], s[static_cast<size_t>(k)]);
    }
    // The start speed whose (ωmax + ωmin)/2 is the target: ω_mean scales nearly like w_s.
    double w_s = omega_mean;
    Extremes x{};
    for (int it = 0; it < 60; ++it) {
      x = periodic_extremes(E, s, A, w_s);
      const double mean = 0.5 * (x.wmax + x.wmin);
      if (std::abs(mean - omega_mean) <= 1e-13 * omega_mean) break;
      w_s *= omega_mean / mean;
    }
    *wmax = x.wmax;
    *wmin = x.wmin;
    w_start = w_s;
    return (x.wmax - x.wmin) / omega_mean;
  };
  r.delta = analyse(0.0, &r.omega_max, &r.omega_min);
  double Imean = 0, Amax = A[0], Amin = A[0];
  for (int k = 0; k < n; ++k) Imean += base.inertia_s(s[static_cast<size_t>(k)]) / n;
  for (double a : A) Amax = std::max(Amax, a), Amin = std::min(Amin, a);
  r.mean_inertia = Imean;
  r.flywheel_estimate = std::max(0.0, (Amax - Amin) / (delta_target * omega_mean * omega_mean) - Imean);
  if (r.delta <= delta_target) {
    r.flywheel_inertia = 0;
    r.delta_with_flywheel = r.delta;
    r.omega_max_fw = r.omega_max;
    r.omega_min_fw = r.omega_min;
    r.omega_start_fw = w_start;
    return r;
  }
  // 1/δ grows nearly linearly with the total inertia: secant iteration on g(J) = 1/δ(J) − 1/δ_target.
  double wmax = 0, wmin = 0;
  double J0 = 0.0, g0 = 1.0 / r.delta - 1.0 / delta_target;
  double J1 = std::max(r.flywheel_estimate, 1e-6 * Imean);
  double g1 = 1.0 / analyse(J1, &wmax, &wmin) - 1.0 / delta_target;
  for (int it = 0; it < 60 && std::abs(g1) > 1e-12 / delta_target; ++it) {
    double J2 = J1 - g1 * (J1 - J0) / (g1 - g0);
    if (!(J2 > 0)) J2 = 0.5 * J1;
    J0 = J1, g0 = g1;
    J1 = J2;
    g1 = 1.0 / analyse(J1, &wmax, &wmin) - 1.0 / delta_target;
  }
  r.flywheel_inertia = J1;
  r.delta_with_flywheel = analyse(J1, &r.omega_max_fw, &r.omega_min_fw);
  r.omega_start_fw = w_start;
  return r;
}

std::optional<EnergyResult> machine_energy(const Model& m) {
  if (m.dof() != 1 || !m.links.empty() || !has_machines(m) || m.is_hybrid()) return std::nullopt;
  try {
    return energy_analysis(m);
  } catch (const InputError&) {
    return std::nullopt;
  }
}

}  // namespace machdyn
