#include "machdyn/elements/spatial_rope.hpp"

#include <cmath>
#include <fmt/format.h>

#include "machdyn/elements/linear_model.hpp"

namespace machdyn {

SpatialRope::Geometry SpatialRope::geometry(const ElementMotion& b) const {
  Geometry g{};
  double x = at(b, Role::load_x), y = at(b, Role::load_y), z = at(b, Role::load_z);
  double px = at(b, Role::trolley), py = at(b, Role::bridge);
  // A planar load: its horizontal axis (x, or y for a yz load) carries the offset and a rigid load's
  // attach point r = c + R(ψ) a.
  const bool on_y = !has(Role::load_x) && has(Role::load_y);
  (on_y ? py : px) += offset;
  const double psi = at(b, Role::load_psi), cp = std::cos(psi), sp = std::sin(psi);
  const double ra_h = attach[0] * cp - attach[1] * sp, ra_z = attach[0] * sp + attach[1] * cp;  // R(ψ) a
  (on_y ? y : x) += ra_h;
  z += ra_z;
  const bool jib = has(Role::jib);
  const double th = at(b, Role::jib), r = at(b, Role::radius, r0), ct = std::cos(th), st = std::sin(th);
  if (jib) px += r * ct, py += r * st;
  g.p[0] = px, g.p[1] = py, g.p[2] = h;
  g.w[0] = px - x, g.w[1] = py - y, g.w[2] = h - z;
  g.l = std::sqrt(g.w[0] * g.w[0] + g.w[1] * g.w[1] + g.w[2] * g.w[2]);
  if (g.l > 0.0) {
    for (int i = 0; i < 3; ++i) g.u[i] = g.w[i] / g.l;
  } else {
    g.u[0] = g.u[1] = 0.0, g.u[2] = 1.0;
  }
  const double s = has(Role::drum) ? law.inv_ratio : 0.0;
  g.qa = has(Role::drum) ? at(b, Role::drum) : law.u0;
  g.e = g.l - law.L0 + s * (g.qa - law.u0);
  g.rate = 0.0;
  for (int k = 0; k < n_ports; ++k) {
    double* d = g.dw[k];
    d[0] = d[1] = d[2] = 0.0;
    switch (role[k]) {
      case Role::load_x: d[0] = -1.0; break;
      case Role::load_y: d[1] = -1.0; break;
      case Role::load_z: d[2] = -1.0; break;
      case Role::trolley: d[0] = 1.0; break;
      case Role::bridge: d[1] = 1.0; break;
      case Role::jib: d[0] = -r * st, d[1] = r * ct; break;
      case Role::radius: d[0] = ct, d[1] = st; break;
      case Role::drum: break;
      case Role::load_psi: d[on_y ? 1 : 0] = ra_z, d[2] = -ra_h; break;  // −∂(R a)/∂ψ = (a_h sψ + a_z cψ, −(R a)_h)
    }
    g.a[k] = g.u[0] * d[0] + g.u[1] * d[1] + g.u[2] * d[2] + (role[k] == Role::drum ? s : 0.0);
    g.rate += g.a[k] * b.v[k];
  }
  return g;
}

void SpatialRope::hessian(const ElementMotion& b, const Geometry& g, double* H) const {
  const int n = n_ports;
  const double inv = g.l > 0.0 ? 1.0 / g.l : 0.0;
  double gl[ElementMotion::kMax];  // ∂ℓ/∂q_k = u · ∂w/∂q_k
  for (int k = 0; k < n; ++k) gl[k] = g.u[0] * g.dw[k][0] + g.u[1] * g.dw[k][1] + g.u[2] * g.dw[k][2];
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j) {
      const double dd = g.dw[k][0] * g.dw[j][0] + g.dw[k][1] * g.dw[j][1] + g.dw[k][2] * g.dw[j][2];
      H[k * n + j] = (dd - gl[k] * gl[j]) * inv;
    }
  // u · ∂²w/∂q_k∂q_j: a rigid load's ψψ term (∂²w/∂ψ² = R(ψ) a) and the jib's (∂²p/∂θ² = −r (cos θ, sin θ), ∂²p/∂θ∂r = (−sin θ, cos θ)).
  if (has(Role::load_psi)) {
    const int P = port_of[static_cast<int>(Role::load_psi)];
    const bool on_y = !has(Role::load_x);
    const double psi = at(b, Role::load_psi), cp = std::cos(psi), sp = std::sin(psi);
    const double ra_h = attach[0] * cp - attach[1] * sp, ra_z = attach[0] * sp + attach[1] * cp;
    H[P * n + P] += g.u[on_y ? 1 : 0] * ra_h + g.u[2] * ra_z;
  }
  if (has(Role::jib)) {
    const int J = port_of[static_cast<int>(Role::jib)], R = port_of[static_cast<int>(Role::radius)];
    const double th = at(b, Role::jib), r = at(b, Role::radius, r0), ct = std::cos(th), st = std::sin(th);
    H[J * n + J] += -r * (g.u[0] * ct + g.u[1] * st);
    if (R >= 0) {
      const double m = -g.u[0] * st + g.u[1] * ct;
      H[J * n + R] += m, H[R * n + J] += m;
    }
  }
}

bool SpatialRope::hang(ElementMotion& b, double gravity) const {
  if (has(Role::load_psi)) return false;
  const Geometry g = geometry(b);  // p does not depend on a point-mass load's coordinates
  const double s = has(Role::drum) ? law.inv_ratio : 0.0;
  // e = ℓ − L0 + s (φ − φ0) at the tension c(φ) e = m g
  const double l = law.L0 - s * (g.qa - law.u0) + mass * gravity / law.stiffness(g.qa);
  if (has(Role::load_x)) b.q[port_of[static_cast<int>(Role::load_x)]] = g.p[0];
  if (has(Role::load_y)) b.q[port_of[static_cast<int>(Role::load_y)]] = g.p[1];
  b.q[port_of[static_cast<int>(Role::load_z)]] = h - l;
  return true;
}

double SpatialRope::tension(const Geometry& g, int mode) const {
  return mode == 0 ? law.load(g.e, g.rate, GapMode::closed_pos, g.qa) : 0.0;
}

void SpatialRope::forces(double, const ElementMotion& b, const double*, int mode, double* M) const {
  for (int k = 0; k < n_ports; ++k) M[k] = 0.0;
  if (mode != 0) return;
  const Geometry g = geometry(b);
  const double F = tension(g, mode);
  for (int k = 0; k < n_ports; ++k) M[k] = -F * g.a[k];
  if (has(Role::drum)) M[port_of[static_cast<int>(Role::drum)]] -= law.winding_force(g.e, g.qa, GapMode::closed_pos);
}

ElementJacobian SpatialRope::jacobian(double, const ElementMotion& b, const double*, int mode) const {
  ElementJacobian J;
  if (mode != 0) return J;
  const int n = n_ports;
  const Geometry g = geometry(b);
  double H[ElementMotion::kMax * ElementMotion::kMax];
  hessian(b, g, H);
  const double F = tension(g, mode), c = law.stiffness(g.qa), c1 = law.stiffness_slope(g.qa);
  const double c2 = law.stiffness_curvature(g.qa), d = law.d, e = g.e;
  const int D = port_of[static_cast<int>(Role::drum)];
  // ∂F/∂q_j = c a_j + c′ e [j drum] + d Σ_k H_kj v_k; ∂W/∂q_j = ½ c″ e² [j drum] + c′ e a_j (W = ½ c′ e²).
  double Fq[ElementMotion::kMax], Wq[ElementMotion::kMax];
  for (int j = 0; j < n; ++j) {
    double Hv = 0.0;
    for (int k = 0; k < n; ++k) Hv += H[k * n + j] * b.v[k];
    Fq[j] = c * g.a[j] + d * Hv + (j == D ? c1 * e : 0.0);
    Wq[j] = c1 * e * g.a[j] + (j == D ? 0.5 * c2 * e * e : 0.0);
  }
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j) {
      J.dM_dq[k][j] = -Fq[j] * g.a[k] - F * H[k * n + j] - (k == D ? Wq[j] : 0.0);
      J.dM_dv[k][j] = -d * g.a[j] * g.a[k];
    }
  return J;
}

double SpatialRope::heat_power(double, const ElementMotion& b, const double*, int mode) const {
  if (mode != 0) return 0.0;
  const Geometry g = geometry(b);
  return law.dissipation(g.e, g.rate, GapMode::closed_pos, g.qa);
}

double SpatialRope::energy(const ElementMotion& b, const double*, int mode) const {
  if (mode != 0) return 0.0;
  const Geometry g = geometry(b);
  return law.elastic_energy(g.e, GapMode::closed_pos, g.qa);
}

double SpatialRope::stored_power(double, const ElementMotion& b, const double*, int mode) const {
  if (mode != 0) return 0.0;
  const Geometry g = geometry(b);
  const double drum_speed = has(Role::drum) ? b.v[port_of[static_cast<int>(Role::drum)]] : 0.0;
  return law.stiffness(g.qa) * g.e * g.rate + 0.5 * law.stiffness_slope(g.qa) * g.e * g.e * drum_speed;
}

void SpatialRope::events(double, const ElementMotion& b, const double*, int mode, double* ev) const {
  const Geometry g = geometry(b);
  law.events(g.e, g.rate, mode == 0 ? GapMode::closed_pos : GapMode::open, g.qa, ev);
  ev[1] = 1.0;  // one flank: nothing on the other side
}

int SpatialRope::natural_mode(double, const ElementMotion& b, const double*, int) const {
  const Geometry g = geometry(b);
  return law.natural_mode(g.e, g.rate, g.qa) == GapMode::closed_pos ? 0 : 1;
}

void SpatialRope::add_linear_at(const int* body, const ElementMotion& b, const double* x, int mode,
                                LinearModel& lin) const {
  if (mode != 0) return;
  ElementMotion rest = b;  // about the configuration at rest
  for (int k = 0; k < n_ports; ++k) rest.v[k] = rest.a[k] = 0.0;
  const ElementJacobian J = jacobian(0.0, rest, x, mode);
  for (int k = 0; k < n_ports; ++k)
    for (int j = 0; j < n_ports; ++j) {
      if (J.dM_dq[k][j] != 0.0) lin.K.emplace_back(body[k], body[j], -J.dM_dq[k][j]);
      if (J.dM_dv[k][j] != 0.0) lin.D.emplace_back(body[k], body[j], -J.dM_dv[k][j]);
    }
}

std::vector<std::string> SpatialRope::output_names(BodyKind) const {
  std::vector<std::string> names = {"tension_N", "length_m", "free_length_m"};
  if (has(Role::load_x)) names.emplace_back("sway_x_rad");
  if (has(Role::load_y)) names.emplace_back("sway_y_rad");
  if (has(Role::jib)) names.emplace_back("sway_radial_rad"), names.emplace_back("sway_tangential_rad");
  names.emplace_back("horizontal_force_N");
  names.emplace_back("mode");
  return names;
}

void SpatialRope::outputs(double, const ElementMotion& b, const double*, int mode, double* out) const {
  const Geometry g = geometry(b);
  const double F = tension(g, mode);
  int k = 0;
  out[k++] = F;
  out[k++] = g.l;
  out[k++] = law.free_length(g.qa);
  // Sway: the load's offset from the point below the suspension point over the drop h − z.
  if (has(Role::load_x)) out[k++] = std::atan2(-g.w[0], g.w[2]);
  if (has(Role::load_y)) out[k++] = std::atan2(-g.w[1], g.w[2]);
  if (has(Role::jib)) {
    const double th = at(b, Role::jib), ct = std::cos(th), st = std::sin(th);
    out[k++] = std::atan2(-(g.w[0] * ct + g.w[1] * st), g.w[2]);
    out[k++] = std::atan2(-(-g.w[0] * st + g.w[1] * ct), g.w[2]);
  }
  out[k++] = F * std::hypot(g.u[0], g.u[1]);
  out[k++] = static_cast<double>(mode);
}

std::string SpatialRope::describe(BodyKind) const {
  auto num = [](double v) { return fmt::format("{:.6g}", v); };
  std::string s = "L0 = " + num(law.L0) + " m, " + num(law.falls) + " fall(s), n E A = " + num(law.K) +
                  " N (c = " + num(law.c) + " N/m at L0), d = " + num(law.d) + " N·s/m, height " + num(h) + " m";
  if (has(Role::jib) && !has(Role::radius)) s += ", radius " + num(r0) + " m";
  if (has(Role::load_psi)) s += ", attached at (" + num(attach[0]) + ", " + num(attach[1]) + ") m";
  if (offset != 0.0) s += ", offset " + num(offset) + " m";
  if (has(Role::drum)) s += ", drum radius " + num(law.inv_ratio * law.falls) + " m";
  return s;
}

}  // namespace machdyn
