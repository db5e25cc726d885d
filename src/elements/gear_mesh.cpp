#include "machdyn/elements/gear_mesh.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "machdyn/elements/linear_model.hpp"

namespace machdyn {

namespace {
/// The sign a speed has just after the instant: its own, or its acceleration's at 0 (else `keep`).
int sign_after(double v, double a, int keep) {
  if (v != 0.0) return v > 0.0 ? 1 : -1;
  if (a != 0.0) return a > 0.0 ? 1 : -1;
  return keep;
}
}  // namespace

LinkLaw GearMesh::flanks() const {
  LinkLaw L;
  L.c = c, L.d = d;
  L.gap = b > 0.0;
  L.capped = L.gap;  // elasto-backlash (elements/link.hpp)
  L.hi = 0.5 * b, L.lo = -0.5 * b;
  return L;
}

int GearMesh::direction(int mode) {
  const int g = static_cast<int>(flank_of(mode));  // the sign of τ on a flank, 0 in the free play
  const int s1 = g * sign1(mode), s2 = g * sign2(mode);
  return s1 > 0 && s2 > 0 ? 1 : s1 < 0 && s2 < 0 ? -1 : 0;
}

double GearMesh::tooth_moment(const ElementMotion& m, int mode) const {
  return flanks().load(deflection(m), deflection_rate(m), flank_of(mode));
}

void GearMesh::forces(double, const ElementMotion& m, const double*, int mode, double* M) const {
  const double tau = tooth_moment(m, mode);
  const int dir = direction(mode);
  M[0] = -(dir < 0 ? eta : 1.0) * tau;
  M[1] = (dir > 0 ? eta : 1.0) * i * tau;
}

ElementJacobian GearMesh::jacobian(double, const ElementMotion& m, const double*, int mode) const {
  ElementJacobian J;
  const LinkLaw L = flanks();
  const GapMode g = flank_of(mode);
  if (!L.transmits(g)) return J;
  const double D = deflection(m), Dr = deflection_rate(m);
  const bool cap = L.on_cap(D, Dr, g);  // τ = 2 c e: ∂τ/∂Δ = 2c, ∂τ/∂Δ' = 0
  const double tD = cap ? 2.0 * c : c, tR = cap ? 0.0 : d;
  const int dir = direction(mode);
  const double k[2] = {-(dir < 0 ? eta : 1.0), (dir > 0 ? eta : 1.0) * i};  // M_p = k_p τ
  const double j[2] = {1.0, -i};                                            // ∂Δ/∂q_r
  for (int p = 0; p < 2; ++p)
    for (int r = 0; r < 2; ++r) {
      J.dM_dq[p][r] = k[p] * tD * j[r];
      J.dM_dv[p][r] = k[p] * tR * j[r];
    }
  return J;
}

double GearMesh::heat_power(double, const ElementMotion& m, const double*, int mode) const {
  const LinkLaw L = flanks();
  const GapMode g = flank_of(mode);
  if (!L.transmits(g)) return 0.0;
  const double damp = L.dissipation(deflection(m), deflection_rate(m), g);
  const int dir = direction(mode);
  if (dir == 0) return damp;
  const double tau = tooth_moment(m, mode);
  return damp + (1.0 - eta) * (dir > 0 ? tau * i * m.v[1] : -tau * m.v[0]);
}

double GearMesh::energy(const ElementMotion& m, const double*, int mode) const {
  return flanks().elastic_energy(deflection(m), flank_of(mode));
}

double GearMesh::stored_power(double, const ElementMotion& m, const double*, int mode) const {
  const LinkLaw L = flanks();
  const GapMode g = flank_of(mode);
  if (!L.transmits(g)) return 0.0;
  return c * (deflection(m) - L.flank(g)) * deflection_rate(m);
}

void GearMesh::events(double, const ElementMotion& m, const double*, int mode, double* ev) const {
  const LinkLaw L = flanks();
  const GapMode g = flank_of(mode);
  const double D = deflection(m), Dr = deflection_rate(m);
  if (!L.transmits(g)) {  // the free play: it reaches a flank
    L.events(D, Dr, g, ev);
    return;
  }
  ev[0] = static_cast<int>(g) * L.pressing(D - L.flank(g), Dr, L.u0);
  ev[1] = std::min(sign1(mode) * m.v[0], sign2(mode) * i * m.v[1]);
}

int GearMesh::mode_after(int mode, int slot) const {
  const int m = mode % 16;
  const GapMode g = flank_of(m);
  if (g == GapMode::open) return mode_of(LinkLaw::mode_after(g, slot), sign1(m), sign2(m)) + 16;
  if (slot == 1) return m + 16;  // a body reverses: settle() flips its sign
  // The contact ends (free play), or without backlash τ changes sign.
  return mode_of(b > 0.0 ? GapMode::open : GapMode(-static_cast<int>(g)), sign1(m), sign2(m));
}

int GearMesh::settle(double, const ElementMotion& m, const double*, int old, int now) const {
  const int n = now % 16;
  int s1 = sign1(old % 16), s2 = sign2(old % 16);
  if (flank_of(old % 16) == GapMode::open) {  // closing on a flank: the speeds' signs now
    s1 = sign_after(m.v[0], m.a[0], s1);
    s2 = sign_after(m.v[1], m.a[1], s2);
  } else {  // a body reverses: the one at its reversal takes its sign after the instant
    const double f1 = s1 * m.v[0], f2 = s2 * i * m.v[1];
    if (f1 <= f2) {
      if (f1 < 0.0 || s1 * m.a[0] < 0.0) s1 = -s1;
    } else if (f2 < 0.0 || s2 * m.a[1] < 0.0) {
      s2 = -s2;
    }
  }
  return mode_of(flank_of(n), s1, s2);
}

int GearMesh::natural_mode(double, const ElementMotion& m, const double*, int current) const {
  const LinkLaw L = flanks();
  const double D = deflection(m), Dr = deflection_rate(m);
  const int cur = current % 16;
  GapMode g;
  if (L.gap) {
    g = L.natural_mode(D, Dr);
    // In the free play the signs act on nothing and a contact reads them again (settle): kept, so a
    // decision at a breakpoint after a body reversed there changes no mode (no `free play` event).
    if (g == GapMode::open) return mode_of(g, sign1(cur), sign2(cur));
  } else {
    const double p = L.pressing(D, Dr, L.u0);
    // τ at 0 reads as + (a speed at 0 does too): a mesh at rest starts on the + flank, so a load
    // turning τ negative is an event (the start's mode 0, the − flank, hid it; campaign gear-mesh).
    g = p < 0.0 ? GapMode::closed_neg : GapMode::closed_pos;
  }
  const int s1 = m.v[0] > 0.0 ? 1 : m.v[0] < 0.0 ? -1 : sign1(cur);
  const int s2 = m.v[1] > 0.0 ? 1 : m.v[1] < 0.0 ? -1 : sign2(cur);
  return mode_of(g, s1, s2);
}

const char* GearMesh::mode_name(int mode) const {
  static const char* const kNames[3][3] = {
      {"flank-/wheel drives", "flank-/no transmission", "flank-/pinion drives"},
      {"free play", "free play", "free play"},
      {"flank+/wheel drives", "flank+/no transmission", "flank+/pinion drives"}};
  return kNames[static_cast<int>(flank_of(mode)) + 1][direction(mode) + 1];
}

const char* GearMesh::switch_kind(int now) const {
  return flank_of(now % 16) == GapMode::open ? "free play" : "mesh";
}

void GearMesh::add_linear(const int* body, int mode, LinearModel& lin) const {
  if (!flanks().transmits(flank_of(mode))) return;
  const double j[2] = {1.0, -i};
  LinearModel::add_outer(lin.K, body, j, 2, c);
  if (d > 0.0) LinearModel::add_outer(lin.D, body, j, 2, d);
}

std::vector<std::string> GearMesh::output_names(BodyKind) const {
  return {"deflection_rad", "wheel_torque_" + unit_suffix(load_unit(BodyKind::rotational)), "heat_power_W", "mode"};
}

void GearMesh::outputs(double t, const ElementMotion& m, const double* x, int mode, double* out) const {
  double M[2];
  forces(t, m, x, mode, M);
  out[0] = deflection(m);
  out[1] = M[1];
  out[2] = heat_power(t, m, x, mode);
  out[3] = static_cast<double>(mode % 16);
}

std::string GearMesh::describe(BodyKind) const {
  auto num = [](double v) { return fmt::format("{:.6g}", v); };
  std::string s = "i = " + num(i) + ", c = " + num(c) + " N·m/rad, d = " + num(d) + " N·m·s/rad, backlash " + num(b) +
                  " rad, η = " + num(eta) + " (at the pinion";
  if (r_p > 0.0) s += ", base radius " + num(r_p) + " m";
  return s + ")";
}

std::string GearMesh::violated(double, const ElementMotion& m, const double*, int mode, const double* M, double heat,
                               double resolution) const {
  // Inside the free play, |Δ| < b/2 (by more than Δ's resolution), no force acts.
  const double D = m.q[0] - i * m.q[1], Dr = m.v[0] - i * m.v[1];
  const double res = (1.0 + i) * resolution;
  if (b > 0.0 && std::abs(D) < 0.5 * b - res && (M[0] != 0.0 || M[1] != 0.0))
    return fmt::format("mesh.free_play|Δ = {:.17g} rad inside the backlash ±{:.17g} rad, but M = ({:.17g}, {:.17g})",
                       D, 0.5 * b, M[0], M[1]);
  // The loss is never negative: the heat (damping and the efficiency's loss) ≥ 0, and the mesh gives
  // its bodies no more than its teeth release, M₁ ω₁ + M₂ ω₂ ≤ −dV/dt.
  const double scale = (std::abs(M[0]) + std::abs(M[1])) * (std::abs(m.v[0]) + std::abs(m.v[1]) + res);
  const double tol = 1e-12 * scale + (std::abs(M[0]) + std::abs(M[1])) * res;
  if (heat < -tol) return fmt::format("mesh.loss|heat power {:.17g} W < 0 in mode {}", heat, mode_name(mode));
  const GapMode g = flank_of(mode);
  const double e = g == GapMode::open ? 0.0 : b > 0.0 ? D - static_cast<int>(g) * 0.5 * b : D;
  const double P = M[0] * m.v[0] + M[1] * m.v[1], dV = c * e * Dr;
  if (P > -dV + tol + 1e-12 * std::abs(dV))
    return fmt::format("mesh.loss|the bodies gain {:.17g} W, the teeth release {:.17g} W", P, -dV);
  return {};
}

}  // namespace machdyn
