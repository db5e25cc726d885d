#include "machdyn/analysis/simulate.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <fmt/format.h>

#include "machdyn/elements/contact.hpp"
#include "machdyn/elements/linear_model.hpp"
#include "machdyn/elements/linearize.hpp"
#include "machdyn/elements/link.hpp"
#include "machdyn/model/element.hpp"


namespace machdyn {

Method choose_method(const Model& m, std::string* reason) {
  const auto& s = m.simulation;
  if (s.integrator == IntegratorChoice::dopri5) {
    if (reason) *reason = "chosen in the model file";
    return Method::dopri5;
  }
  if (s.integrator == IntegratorChoice::bdf) {
    if (reason) *reason = "chosen in the model file";
    return Method::bdf;
  }
  // Gershgorin bounds from the links' own Jacobian terms (elements/link.hpp), O(n): ρ_D ≥ every
  // damping rate of M⁻¹D, ω_K ≥ ω_max.
  const int n = m.dof();
  std::vector<double> rowD(static_cast<size_t>(n), 0.0), rowK(rowD);
  // A massless side x of a lossy gear moves with its other side y, q_x = w q_y (a rope's end at the
  // drum behind its sheave losses, model/sheaves.hpp): its rows and columns fold onto y's (the bounds
  // of Tᵀ K T over the coordinates that carry mass).
  std::vector<int> onto(static_cast<size_t>(n));
  std::vector<double> weight(static_cast<size_t>(n), 1.0);
  for (int i = 0; i < n; ++i) onto[static_cast<size_t>(i)] = i;
  for (const LossyGear& g : m.lossy_gears) {
    if (m.bodies[static_cast<size_t>(g.b)].inertia == 0.0) onto[static_cast<size_t>(g.b)] = g.a, weight[static_cast<size_t>(g.b)] = 1.0 / g.ratio;
    else if (m.bodies[static_cast<size_t>(g.a)].inertia == 0.0) onto[static_cast<size_t>(g.a)] = g.b, weight[static_cast<size_t>(g.a)] = g.ratio;
  }
  auto add = [&](std::vector<double>& row, int r, int c, double v) {
    const auto rr = static_cast<size_t>(r), cc = static_cast<size_t>(c);
    row[static_cast<size_t>(onto[rr])] += std::abs(v * weight[rr] * weight[cc]);
  };
  for (const auto& l : m.links)
    LinkLaw::of(m, l).jacobian(n, GapMode::closed_pos, [&](int r, int c, double v) {
      if (c < n) add(rowK, r, c, v);
      else add(rowD, r, c - n, v);
    });
  // A kinetic friction table rising with the sliding speed acts as a damper of its steepest rising
  // slope while the contact slides (dF_k/du: 7e9 N·s/m for 0.2 → 0.9 of 10 N over 1e-9 m/s).
  for (const auto& c : m.contacts) {
    const ContactLaw law = ContactLaw::of(c);
    const double slope = law.steepest_kinetic_slope();
    for (int r = 0; r < law.row.terms; ++r)
      for (int k = 0; k < law.row.terms; ++k) add(rowD, law.row.body[r], law.row.body[k], slope * law.row.w[r] * law.row.w[k]);
  }
  double rho_D = 0.0, omega_K = 0.0;
  // An element's linear terms in its mode 0 (model/element.hpp: a speed drive's K_p and a DC
  // motor's k²/R as dampers, K_p/T_i as a spring) and its own rates (R/L of the armature, 1/T_m of
  // the torque lag).
  for (const auto& d : m.drives) {
    LinearModel lin(n);
    add_drive_linear(d, 0, lin);
    for (const auto& e : lin.D) add(rowD, static_cast<int>(e.row()), static_cast<int>(e.col()), e.value());
    for (const auto& e : lin.K) add(rowK, static_cast<int>(e.row()), static_cast<int>(e.col()), e.value());
    rho_D = std::max(rho_D, d.law->rate_bound());
  }
  // The smallest masses of the run (after every release) give the largest rates.
  std::vector<double> released(static_cast<size_t>(n), 0.0);
  for (const Release& r : m.releases) released[static_cast<size_t>(r.body)] += r.amount;
  for (int i = 0; i < m.dof(); ++i) {
    if (onto[static_cast<size_t>(i)] != i) continue;  // folded onto its gear's other side
    const double I = m.bodies[static_cast<size_t>(i)].inertia - released[static_cast<size_t>(i)];
    rho_D = std::max(rho_D, rowD[static_cast<size_t>(i)] / I);
    omega_K = std::max(omega_K, std::sqrt(rowK[static_cast<size_t>(i)] / I));
  }
  // Stiff: the fastest motion is damping-dominated (ρ_D ≥ ω_K, i.e. ζ ≳ 0.5) and so fast that an
  // explicit method would spend > 2e4 steps on stability alone.
  const double fastest = rho_D >= omega_K ? rho_D : 0.0;
  const double stiffness_index = fastest * s.t_end;
  if (stiffness_index > 2e4) {
    if (reason) *reason = fmt::format("auto: strongly damped fast motion, |Re λ|·t_end = {:.3g} > 2e4", stiffness_index);
    return Method::bdf;
  }
  if (reason) *reason = fmt::format("auto: non-stiff, |Re λ|·t_end = {:.3g} <= 2e4", stiffness_index);
  return Method::dopri5;
}

void set_peak(LinkSummary& s) {
  // An extreme below 1e-12 of the link's largest magnitude is zero to the run's tolerance (rtol ≥
  // 1e-14 cannot resolve it): a rope that never pushes has min = 0, not −4.6e−29.
  const double scale = std::max(std::abs(s.max), std::abs(s.min));
  for (double* v : {&s.max, &s.min})
    if (std::abs(*v) <= 1e-12 * scale) *v = 0.0;
  const bool neg = std::abs(s.min) > std::abs(s.max);
  s.peak = neg ? s.min : s.max;
  s.t_peak = neg ? s.t_min : s.t_max;
  s.static_load = neg ? s.static_at_min : s.static_at_max;
  s.dynamic_factor = std::abs(s.static_load) > 1e-9 * std::abs(s.peak) ? s.peak / s.static_load
                                                                       : std::numeric_limits<double>::quiet_NaN();
}

}  // namespace machdyn
