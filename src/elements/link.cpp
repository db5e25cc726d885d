#include "machdyn/elements/link.hpp"

#include <algorithm>
#include <cmath>

namespace machdyn {

LinkLaw LinkLaw::of(const Model& m, const Link& l) {
  LinkLaw k;
  k.a = l.a, k.b = l.b;
  k.inv_ratio = 1.0 / l.ratio;
  k.c = l.c, k.d = l.d;
  k.gap = l.has_gap;
  k.capped = l.damping_capped;
  k.lo = l.tension_only ? -HUGE_VAL : -l.gap_start;
  k.hi = l.gap - l.gap_start;
  k.rest = l.has_gap ? 0.0 : l.delta0;
  if (l.a_point && l.a >= 0) k.pa = m.bodies[static_cast<size_t>(l.a)].machine.get();
  if (l.b_point && l.b >= 0) k.pb = m.bodies[static_cast<size_t>(l.b)].machine.get();
  k.wb = l.b_weight;
  k.third = l.third;
  k.w3 = l.third_weight;
  k.point = k.pa || k.pb || k.wb != 1.0 || k.third >= 0;
  k.falls = l.falls;
  k.winding = l.EA > 0.0 && l.a >= 0 && l.length > 0.0;
  k.K = l.falls * l.EA;
  k.L0 = l.length;
  k.u0 = l.drum_q0;
  k.shape = l.characteristic;
  k.shaped = l.buffer && l.characteristic != Link::Characteristic::linear;
  if (k.shaped) {
    k.cn = l.characteristic == Link::Characteristic::progressive ? l.coefficient : l.c;
    k.expo = l.exponent;
    k.kh = l.characteristic == Link::Characteristic::hydraulic ? l.hydraulic_k : 0.0;
    k.ts = l.table_stroke.data(), k.tf = l.table_force.data();
    k.tn = static_cast<int>(l.table_stroke.size());
  }
  return k;
}

namespace {
/// The table's piece j (0 ≤ j ≤ tn − 2) that holds e: the first below s₁, the last beyond s_{n−2}.
int piece(const double* s, int n, double e) {
  const int j = static_cast<int>(std::upper_bound(s, s + n, e) - s) - 1;
  return std::clamp(j, 0, n - 2);
}
}  // namespace

double LinkLaw::shaped_force(double e) const {
  switch (shape) {
    case Link::Characteristic::progressive: return std::copysign(cn * std::pow(std::abs(e), expo), e);
    case Link::Characteristic::table: {
      const int j = piece(ts, tn, e);
      return tf[j] + (tf[j + 1] - tf[j]) / (ts[j + 1] - ts[j]) * (e - ts[j]);
    }
    default: return cn * e;
  }
}

double LinkLaw::shaped_slope(double e) const {
  switch (shape) {
    case Link::Characteristic::progressive: return cn * expo * std::pow(std::abs(e), expo - 1.0);
    case Link::Characteristic::table: {
      const int j = piece(ts, tn, e);
      return (tf[j + 1] - tf[j]) / (ts[j + 1] - ts[j]);
    }
    default: return cn;
  }
}

double LinkLaw::shaped_energy(double e) const {
  switch (shape) {
    case Link::Characteristic::progressive: return cn * std::pow(std::abs(e), expo + 1.0) / (expo + 1.0);
    case Link::Characteristic::table: {
      // ∫₀ᵉ F ds: whole pieces by the trapezoid (exact for a linear piece), then the part of e's piece.
      if (e <= 0.0) return 0.5 * shaped_force(e) * e;  // the first piece continued below 0 (F₀ = 0)
      const int j = piece(ts, tn, e);
      double V = 0.0;
      for (int i = 0; i < j; ++i) V += 0.5 * (tf[i] + tf[i + 1]) * (ts[i + 1] - ts[i]);
      return V + 0.5 * (tf[j] + shaped_force(e)) * (e - ts[j]);
    }
    default: return 0.5 * cn * e * e;
  }
}

double LinkLaw::general_load_rate(const double* q, const double* v, const double* acc, GapMode g) const {
  if (shaped) return shaped_slope(linear(q) - flank(g)) * linear(v) + damper_slope(linear(v)) * linear(acc);
  // A winding rope hung from a frame (`frame:`, the third body e, w_e = 1: the girder the drum and
  // the upper sheaves hang from): δ = s q_a − x + w_e x_e, c(q_a) follows the drum alone (the wound
  // length), the load pulls e with −F w_e, and V gains the terms of x_e (elements/link.hpp jacobian):
  //   ∂²V/∂x_e² = c w_e²,  ∂²V/∂x_e∂x = −c w_e,  ∂²V/∂q_a∂x_e = (c s + c′ e) w_e.
  if (winding) {  // d(c e)/dt = c δ̇ + c′ e q̇_a (δ over the frame too: weighted)
    const double qa = drum(q), rate = weighted(v), Fc_rate = stiffness(qa) * rate + stiffness_slope(qa) * (weighted(q) - flank(g)) * v[a];
    if (capped && on_cap(weighted(q), rate, g, qa)) return 2.0 * Fc_rate;
    return Fc_rate + d * weighted(acc);
  }
  // δ̇ = Σ ± p′ v (/i), δ̈ = Σ ± (p″ v² + p′ acc) (/i); a massless member's end: the linear form.
  double delta = 0, rate = 0, dd = 0, p, dp, ddp;
  if (!pa && !pb) {
    delta = weighted(q), rate = weighted(v), dd = weighted(acc);
    if (on_cap(delta, rate, g)) return 2.0 * c * rate;
    return c * rate + d * dd;
  }
  if (a >= 0) {
    if (pa) pa->point(q[a], &p, &dp, &ddp);
    else p = q[a], dp = 1.0, ddp = 0.0;
    delta += p * inv_ratio;
    rate += dp * v[a] * inv_ratio;
    dd += (ddp * v[a] * v[a] + dp * acc[a]) * inv_ratio;
  }
  if (b >= 0) {
    if (pb) pb->point(q[b], &p, &dp, &ddp);
    else p = q[b], dp = 1.0, ddp = 0.0;
    delta -= p;
    rate -= dp * v[b];
    dd -= ddp * v[b] * v[b] + dp * acc[b];
  }
  if (on_cap(delta, rate, g)) return 2.0 * c * rate;
  return c * rate + d * dd;
}

void LinkLaw::add_linear(const double* q, GapMode g, LinearModel& lin) const {
  if (!transmits(g)) return;
  if (shaped) {  // K: F_e′(e) j jᵀ, D: F_v′(0) j jᵀ (about a state at rest)
    const int n = std::max(a, b) + 1;
    jacobian(n, g, false, q, nullptr, [&](int r, int col, double v) {
      if (col < n) lin.K.emplace_back(r, col, -v);
      else lin.D.emplace_back(r, col - n, -v);
    });
    return;
  }
  if (winding) {  // K: the Hessian of V (header), D: d j jᵀ
    const int n = std::max({a, b, third}) + 1;
    jacobian(n, g, false, q, [&](int r, int col, double v) {
      if (col < n) lin.K.emplace_back(r, col, -v);
      else lin.D.emplace_back(r, col - n, -v);
    });
    return;
  }
  // δ ≈ δ0 + jᵀ Δq: the spring adds c j jᵀ, the damper d j jᵀ. A machine's output point also adds
  // the geometric stiffness of V = ½ c (δ(q) − flank)²: ∂²V/∂q² ∋ c (δ0 − flank) ∂²δ/∂q².
  int idx[3];
  double j[3], curv[3];
  int cnt = 0;
  double delta0 = 0.0;
  auto end = [&](int body, const Machine* p_m, double sign, double scale) {
    if (body < 0) return;
    double p = q[body], dp = 1.0, ddp = 0.0;
    if (p_m) p_m->point(q[body], &p, &dp, &ddp);
    delta0 += sign * scale * p;
    idx[cnt] = body, j[cnt] = sign * scale * dp, curv[cnt] = sign * scale * ddp;
    ++cnt;
  };
  end(a, pa, 1.0, inv_ratio);
  end(b, pb, -1.0, wb);
  end(third, nullptr, 1.0, w3);
  LinearModel::add_outer(lin.K, idx, j, cnt, c);
  LinearModel::add_outer(lin.D, idx, j, cnt, d);
  for (int k = 0; k < cnt; ++k)
    if (curv[k] != 0.0) lin.K.emplace_back(idx[k], idx[k], c * (delta0 - flank(g)) * curv[k]);
}

void LinkLaw::add_load_gradient(const double* q, const double* v, GapMode g, double* dFdq, double* dFdv) const {
  if (!transmits(g)) return;
  if (shaped) {  // F = F_e(e) + F_v(δ̇): ∂F/∂q = F_e′ j, ∂F/∂v = F_v′ j
    const double Fq = shaped_slope(linear(q) - flank(g)), Fv = damper_slope(linear(v));
    if (a >= 0) dFdq[a] += Fq * inv_ratio, dFdv[a] += Fv * inv_ratio;
    if (b >= 0) dFdq[b] -= Fq, dFdv[b] -= Fv;
    return;
  }
  if (winding) {  // F = c(q_a) e + d δ̇: ∂F/∂q_a = c s + c′ e, ∂F/∂x = −c
    const double qa = drum(q);
    dFdq[a] += stiffness(qa) * inv_ratio + stiffness_slope(qa) * (weighted(q) - flank(g));
    dFdv[a] += d * inv_ratio;
    if (b >= 0) dFdq[b] -= stiffness(qa), dFdv[b] -= d;
    if (third >= 0) dFdq[third] += stiffness(qa) * w3, dFdv[third] += d * w3;  // the frame
    return;
  }
  auto end = [&](int body, const Machine* p_m, double sign) {
    if (body < 0) return;
    double p = q[body], dp = 1.0, ddp = 0.0;
    if (p_m) p_m->point(q[body], &p, &dp, &ddp);
    dFdq[body] += sign * (c * dp + d * ddp * v[body]);
    dFdv[body] += sign * d * dp;
  };
  end(a, pa, inv_ratio);
  end(b, pb, -wb);
  end(third, nullptr, w3);
}

}  // namespace machdyn
