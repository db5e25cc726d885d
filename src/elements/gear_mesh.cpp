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

void GearMesh::hold_range(double tau, int p, double* lo, double* hi) const {
  const double T = p == 0 ? -tau : i * tau;
  *lo = std::min(eta * T, T), *hi = std::max(eta * T, T);
}

double GearMesh::hold_margin(double tau, int p, double R) const {
  double lo, hi;
  hold_range(tau, p, &lo, &hi);
  return std::min(-R - lo, hi + R) + 1e-12 * (std::abs(lo) + std::abs(hi) + std::abs(R));
}

void GearMesh::forces(double, const ElementMotion& m, const double*, int mode, double* M) const {
  const double tau = tooth_moment(m, mode);
  if (const int p = held(mode) - 1; p >= 0) {  // held: the other its ideal torque, p the clamp
    M[0] = -tau, M[1] = i * tau;
    double lo, hi;
    hold_range(tau, p, &lo, &hi);
    M[p] = std::clamp(-m.load[p], lo, hi);
    return;
  }
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
  const int dir = held(mode) ? 0 : direction(mode);
  double k[2] = {-(dir < 0 ? eta : 1.0), (dir > 0 ? eta : 1.0) * i};  // M_p = k_p τ
  if (held(mode)) k[held(mode) - 1] = 0.0;  // the held torque answers the other loads, not Δ
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
  if (dir == 0 || held(mode)) return damp;  // held: a body at rest passes no power
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
  if (const int p = held(mode) - 1; p >= 0) {
    // Held: the other body drives, and −R_p (with the stuck set's loads) within the range.
    const int o = 1 - p;
    const double w_o = o == 0 ? m.v[0] : i * m.v[1];
    ev[1] = std::min((p == 1 ? 1.0 : -1.0) * static_cast<int>(g) * w_o, hold_margin(tooth_moment(m, mode), p, m.load[p]));
    return;
  }
  ev[1] = std::min(sign1(mode) * m.v[0], sign2(mode) * i * m.v[1]);
}

int GearMesh::mode_after(int mode, int slot) const {
  const int m = mode % 16;
  const GapMode g = flank_of(m);
  if (g == GapMode::open) return mode_of(LinkLaw::mode_after(g, slot), sign1(m), sign2(m)) + 16;
  if (slot == 1) return (mode & ~16) | 16;  // a body reverses (or a hold ends): settle() decides
  // The contact ends (free play), or without backlash τ changes sign.
  return mode_of(b > 0.0 ? GapMode::open : GapMode(-static_cast<int>(g)), sign1(m), sign2(m));
}

int GearMesh::settle(double, const ElementMotion& m, const double*, int old, int now) const {
  const int n = now % 16;
  const GapMode gm = flank_of(n);
  const int g = static_cast<int>(gm);
  int s[2] = {sign1(old % 16), sign2(old % 16)};
  const double w[2] = {m.v[0], i * m.v[1]};
  const double tau = tooth_moment(m, n);
  // Whether port p at rest is held: the other drives and −R_p lies in the locking range.
  // Whether port p at rest is held: the other drives (its margin, judged in the held mode by the
  // drive system, ends the hold at once where the loads lie outside the range: settle from it).
  auto holds = [&](int p) { return eta < 1.0 && g != 0 && w[1 - p] != 0.0 && other_drives(g, p, s[1 - p]); };
  if (const int p = held(old) - 1; p >= 0) {  // a hold ends
    const int o = 1 - p;
    const double T = p == 0 ? -tau : i * tau;
    double lo, hi;
    hold_range(tau, p, &lo, &hi);
    const double R = m.load[p];
    if (!other_drives(g, p, w[o] > 0.0 ? 1 : w[o] < 0.0 ? -1 : s[o]) || w[o] == 0.0) {
      // The other stopped driving (it reverses): p takes T_p on both sides of rest.
      if (w[o] != 0.0) s[o] = w[o] > 0.0 ? 1 : -1;
      else s[o] = -s[o];
      if (R + T != 0.0) s[p] = R + T > 0.0 ? 1 : -1;
    } else {  // its load left the range: it starts the way the bound it reached pushes it
      const double net = R + std::clamp(-R, lo, hi);
      if (net != 0.0) s[p] = net > 0.0 ? 1 : -1;
    }
    return mode_of(gm, s[0], s[1]);
  }
  if (flank_of(old % 16) == GapMode::open) {  // closing on a flank: the speeds' signs now
    s[0] = sign_after(m.v[0], m.a[0], s[0]);
    s[1] = sign_after(m.v[1], m.a[1], s[1]);
    // A body at rest when the teeth meet while the other drives: held where its other loads lie in
    // the range (τ is 0 at the instant: a body a stuck contact holds, its range then growing from 0
    // with τ and the contact carrying the rest).
    for (int p = 0; p < 2; ++p)
      if (m.v[p] == 0.0 && w[1 - p] != 0.0 && holds(p)) return mode_of(gm, s[0], s[1]) + 32 * (p + 1);
    // A body exactly at rest (a stuck contact holds it, ω = ω' = 0) passes no power: its sign is
    // the one under which it does not drive, sign T_p (−g on the pinion, +g on the wheel), not its
    // acceleration's rounding.
    for (int p = 0; p < 2 && eta < 1.0; ++p)
      if (m.v[p] == 0.0 && m.a[p] == 0.0 && g != 0) s[p] = p == 0 ? -g : g;
    return mode_of(gm, s[0], s[1]);
  }
  // A body reverses: the one at its reversal is held, or takes its sign after the instant.
  const int p = s[0] * w[0] <= s[1] * w[1] ? 0 : 1;
  if (holds(p)) return mode_of(gm, s[0], s[1]) + 32 * (p + 1);
  if (s[p] * w[p] < 0.0 || s[p] * m.a[p] < 0.0) s[p] = -s[p];
  // The other body exactly at rest (a stuck contact holds it) is held once p drives.
  if (const int q = 1 - p; m.v[q] == 0.0 && w[p] != 0.0 && holds(q)) return mode_of(gm, s[0], s[1]) + 32 * (q + 1);
  return mode_of(gm, s[0], s[1]);
}

int GearMesh::natural_mode(double, const ElementMotion& m, const double*, int current) const {
  const LinkLaw L = flanks();
  const double D = deflection(m), Dr = deflection_rate(m);
  // A held body stays held while at rest: its margin, an event function, ends the hold (settle).
  if (const int p = held(current) - 1; p >= 0 && m.v[p] == 0.0) return current & ~16;
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
  // A body exactly at rest while the other drives is held where its other loads lie in the range.
  const int s[2] = {s1, s2};
  for (int p = 0; p < 2 && eta < 1.0; ++p)
    if (m.v[p] == 0.0 && m.v[1 - p] != 0.0 && other_drives(static_cast<int>(g), p, s[1 - p]))
      return mode_of(g, s1, s2) + 32 * (p + 1);
  return mode_of(g, s1, s2);
}

const char* GearMesh::mode_name(int mode) const {
  static const char* const kNames[3][3] = {
      {"flank-/wheel drives", "flank-/no transmission", "flank-/pinion drives"},
      {"free play", "free play", "free play"},
      {"flank+/wheel drives", "flank+/no transmission", "flank+/pinion drives"}};
  if (const int h = held(mode))
    return flank_of(mode) == GapMode::closed_pos ? (h == 1 ? "flank+/pinion held" : "flank+/wheel held")
                                                 : (h == 1 ? "flank-/pinion held" : "flank-/wheel held");
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
  out[3] = static_cast<double>(mode & ~16);  // mode_of(), + 32 the pinion held, + 64 the wheel held
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
