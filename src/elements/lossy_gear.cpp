#include "machdyn/elements/lossy_gear.hpp"

#include <algorithm>

namespace machdyn {
namespace {

/// y(x) piecewise linear through (xs, ys), held constant outside; one value: constant.
double table(const std::vector<double>& xs, const std::vector<double>& ys, double x) {
  if (ys.size() == 1 || x <= xs.front()) return ys.front();
  if (x >= xs.back()) return ys.back();
  const auto k = static_cast<size_t>(std::upper_bound(xs.begin(), xs.end(), x) - xs.begin());
  const double w = (x - xs[k - 1]) / (xs[k] - xs[k - 1]);
  return ys[k - 1] + w * (ys[k] - ys[k - 1]);
}

}  // namespace

const char* to_string(GearMode md) {
  switch (md) {
    case GearMode::backward_b: return "backward_b_drives";
    case GearMode::backward: return "backward";
    case GearMode::stuck: return "stuck";
    case GearMode::forward: return "forward";
    case GearMode::forward_b: return "forward_b_drives";
  }
  return "?";
}

LossyGearLaw LossyGearLaw::of(const LossyGear& g) {
  LossyGearLaw k;
  k.spec = &g;
  k.a = g.a, k.b = g.b;
  k.i = g.ratio;
  k.speed_scale = std::abs(g.rho_a);
  return k;
}

LossyGearLaw::Coefficients LossyGearLaw::at(double v_a) const {
  const double s = std::abs(v_a) * speed_scale;
  const LossyGear& g = *spec;
  Coefficients c;
  c.eta1 = table(g.speeds, g.eta_forward, s);
  c.eta2 = table(g.speeds, g.eta_reverse, s);
  c.bf1 = speed_scale * table(g.speeds, g.bearing_forward, s);
  c.bf2 = speed_scale * table(g.speeds, g.bearing_reverse, s);
  // The split into the bearing before and after the mesh (header); MSL's tau_bf_a.
  if (c.eta1 == 1.0 && c.eta2 == 1.0) c.bf_a = 0.5 * c.bf1;
  else c.bf_a = c.eta2 * (c.bf1 - c.bf2) / (c.eta1 * c.eta2 - 1.0);
  c.bf_b = c.bf1 - c.eta1 * c.bf_a;
  return c;
}

bool LossyGearLaw::b_side_drives(int s, const Coefficients& c, double Fa, double Fb, double Ia, double Ib) const {
  // sign(X̃) = sign(D), D = F̃_a J_b − I_a F̃_b (header): a drives while s D ≥ 0.
  const double Jb = Ib / (i * i), Fbp = Fb / i;
  const double D = (Fa - s * c.bf_a) * Jb - Ia * (Fbp - s * c.bf_b);
  return s * D < 0.0;
}

namespace {
/// The relation p X − q Y = c of rolling in s with side b driving or not (LossyGearLaw::relation).
LossyGearLaw::Relation relation_of(int s, bool b_drive, const LossyGearLaw::Coefficients& c) {
  if (b_drive) return {1.0, c.eta2, s * c.eta2 * c.bf2};
  return {c.eta1, 1.0, s * c.bf1};
}
}  // namespace

LossyGearLaw::Relation LossyGearLaw::relation(GearMode md, double va) const {
  return relation_of(direction(md), b_drives(md), at(va));
}

LossyGearLaw::Reaction LossyGearLaw::reaction(GearMode md, double va) const {
  const Relation r = relation(md, va);
  return {{{a, -r.q}, {b, i * r.p}}, -r.c / r.p};
}

LossyGearLaw::Torques LossyGearLaw::solve(GearMode md, double Fa, double Fb, double Ia, double Ib, double va) const {
  const double Jb = Ib / (i * i), Fbp = Fb / i;
  Torques T;
  const int s = direction(md);
  if (s == 0) {  // stuck: a = 0, the gear holds both sides
    T.X = Fa;
    T.Y = -Fbp;
    return T;
  }
  // The relation p X − q Y = c with X = F_a − I_a a, Y = J_b a − F_b'.
  const Relation r = relation(md, va);
  T.acc = (r.p * Fa + r.q * Fbp - r.c) / (r.p * Ia + r.q * Jb);
  T.X = Fa - Ia * T.acc;
  T.Y = Jb * T.acc - Fbp;
  return T;
}

double LossyGearLaw::start_margin(int s, double Fa, double Fb) const {
  const Coefficients c = at(0.0);
  const double Fbp = Fb / i;
  const bool b_drive = s * (Fa - s * c.bf_a) <= 0.0;
  const Relation r = relation_of(s, b_drive, c);
  const double N = r.p * Fa + r.q * Fbp - r.c;  // the numerator of the mode's equation (header)
  if (!b_drive) return -s * N;                  // a would drive
  return c.eta2 > 0.0 ? -s * N / c.eta2 : -s * N;
}

void LossyGearLaw::events(GearMode md, double Fa, double Fb, double /*Ia*/, double /*Ib*/, double va, const Torques& T,
                          double* ev) const {
  const int s = direction(md);
  if (s == 0) {
    ev[0] = start_margin(+1, Fa, Fb);
    ev[1] = start_margin(-1, Fa, Fb);
    return;
  }
  const Coefficients c = at(va);
  ev[0] = s * va;  // comes to rest
  ev[1] = b_drives(md) ? -s * (T.Y + s * c.bf_b) : s * (T.X - s * c.bf_a);  // the driving side changes
}

double LossyGearLaw::margin_root(int s, double Fa, double Fb, double dFa, double dFb, double th0, double th1) const {
  // The kink: s (F_a + θ dF_a − s τ_bf,a) = 0 (start_margin's choice of the driving side).
  const double bf_a = at(0.0).bf_a;
  auto m = [&](double th) { return start_margin(s, Fa + th * dFa, Fb + th * dFb); };
  if (dFa != 0.0) {
    const double kink = (s * bf_a - Fa) / dFa;
    if (kink > th0 && kink < th1) {
      const double mk = m(kink);
      if (mk == 0.0) return kink;
      if ((mk > 0.0) == (m(th0) > 0.0)) th0 = kink;
      else th1 = kink;
    }
  }
  const double m0 = m(th0), m1 = m(th1);
  if (m0 == m1) return th0;
  return std::clamp(th0 - m0 * (th1 - th0) / (m1 - m0), std::min(th0, th1), std::max(th0, th1));
}

GearMode LossyGearLaw::rolling(int s, double Fa, double Fb, double Ia, double Ib, double va) const {
  const bool bd = b_side_drives(s, at(va), Fa, Fb, Ia, Ib);
  return s > 0 ? (bd ? GearMode::forward_b : GearMode::forward) : (bd ? GearMode::backward_b : GearMode::backward);
}

double LossyGearLaw::allowance(double Fa, double Fb) const {
  const Coefficients c = at(0.0);
  return 1e-12 * (std::abs(Fa) + std::abs(Fb / i) + c.bf1 + c.bf2);
}

GearMode LossyGearLaw::decide(double Fa, double Fb, double Ia, double Ib, double va, double tol) const {
  int s = va > 0.0 ? 1 : va < 0.0 ? -1 : 0;
  if (s == 0) {
    if (start_margin(+1, Fa, Fb) < -tol) s = 1;
    else if (start_margin(-1, Fa, Fb) < -tol) s = -1;
    else return GearMode::stuck;
  }
  return rolling(s, Fa, Fb, Ia, Ib, va);
}

namespace {

/// X̃ from Ỹ in direction s (header "Prescribed side"): a drives while s Ỹ > 0 (X̃ = Ỹ/η_mf1), else
/// b (X̃ = η_mf2 Ỹ). Increasing in Ỹ.
double mesh_in(int s, const LossyGearLaw::Coefficients& c, double Yt) {
  return s * Yt > 0.0 ? Yt / c.eta1 : c.eta2 * Yt;
}
/// Its inverse, Ỹ from X̃: a drives while s X̃ > 0 (Ỹ = η_mf1 X̃), else b (Ỹ = X̃/η_mf2; η_mf2 > 0).
double mesh_out(int s, const LossyGearLaw::Coefficients& c, double Xt) {
  return s * Xt > 0.0 ? c.eta1 * Xt : Xt / c.eta2;
}

}  // namespace

LossyGearLaw::Torques LossyGearLaw::solve_given(GearMode md, bool b_given, double acc, double Fa, double Fb, double Ia,
                                                double Ib, double va) const {
  const double Jb = Ib / (i * i), Fbp = Fb / i;
  const Coefficients c = at(va);
  Torques T;
  T.acc = acc;
  const int s = direction(md);
  if (!b_given) {  // a prescribed: b's equation gives Y, the mode (or the locking range) X
    T.Y = Jb * acc - Fbp;
    if (s != 0) {
      T.X = mesh_in(s, c, T.Y + s * c.bf_b) + s * c.bf_a;
    } else {  // X_s(Y) = X̃ + s τ_bf,a of the rolling relation in s; the source's least force
      const double lo = mesh_in(-1, c, T.Y - c.bf_b) - c.bf_a, hi = mesh_in(+1, c, T.Y + c.bf_b) + c.bf_a;
      T.X = std::clamp(Fa - Ia * acc, lo, hi);
    }
    return T;
  }
  T.X = Fa - Ia * acc;  // b prescribed: a's equation gives X, the mode (or the locking range) Y
  if (s != 0) {
    T.Y = mesh_out(s, c, T.X - s * c.bf_a) - s * c.bf_b;
  } else {  // Y_s(X) = X_s⁻¹(X): Y_+ ≤ Y_− (X_s increasing, X_− ≤ X_+)
    const double lo = mesh_out(+1, c, T.X - c.bf_a) - c.bf_b, hi = mesh_out(-1, c, T.X + c.bf_a) + c.bf_b;
    T.Y = std::clamp(Jb * acc - Fbp, lo, hi);
  }
  return T;
}

GearMode LossyGearLaw::decide_given(bool b_given, double acc, double Fa, double Fb, double Ia, double Ib, double va,
                                    double rest_v, double rest_a) const {
  // Rest only with both within the allowances: a speed that is tiny but falling to rest keeps its sign.
  if (std::abs(va) <= rest_v && std::abs(acc) <= rest_a) return GearMode::stuck;
  const int s = va > 0.0 ? 1 : va < 0.0 ? -1 : acc > 0.0 ? 1 : -1;
  const Coefficients c = at(va);
  // The known torque decides the side (header): s Ỹ, resp. s X̃, > 0: a drives.
  const double known = b_given ? Fa - Ia * acc - s * c.bf_a : Ib / (i * i) * acc - Fb / i + s * c.bf_b;
  const bool bd = s * known < 0.0;
  return s > 0 ? (bd ? GearMode::forward_b : GearMode::forward) : (bd ? GearMode::backward_b : GearMode::backward);
}

void LossyGearLaw::events_given(GearMode md, GearMode now, double va, const Torques& T, double* ev) const {
  if (direction(md) == 0) ev[0] = ev[1] = 1.0;
  else events(md, 0.0, 0.0, 0.0, 0.0, va, T, ev);  // rolling: its events read only v_a and the torques
  // The evaluation decided otherwise (header "Mode law"): the slot of the part that changed fires.
  if (direction(now) != direction(md)) ev[0] = -1.0;
  else if (now != md) ev[1] = -1.0;
}

void LossyGearLaw::add_linear(LinearModel& lin) const {
  lin.G.push_back({{a, 1.0}, {b, -i}});
  lin.constraint_names.push_back(spec->name);
}

void LossyGearLaw::add_linear(GearMode md, LinearModel& lin) const {
  add_linear(lin);
  if (md != GearMode::stuck) return;
  lin.G.push_back({{a, 1.0}});  // stuck: a = 0, so v_a = 0 (and v_b = v_a / i)
  lin.constraint_names.push_back(spec->name);
}

}  // namespace machdyn
