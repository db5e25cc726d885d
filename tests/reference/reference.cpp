// The brute-force reference simulator (reference.hpp): fixed-step RK4, bisected switching functions,
// modes by enumeration. Independent of the engine: only the docs' laws, written again here.
#include "reference/reference.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <numbers>
#include <stdexcept>

#include <Eigen/Dense>

#include "machdyn/elements/hold_allowance.hpp"

namespace machdyn::reference {

double Signal::at(double t) const {
  switch (kind) {
    case Kind::constant: return value;
    case Kind::step: return t < t0 ? before : value;
    case Kind::ramp:
      if (t <= t0) return before;
      if (t >= t1) return value;
      return before + (value - before) * (t - t0) / (t1 - t0);
    case Kind::sine:
      return t < t0 ? offset : offset + amplitude * std::sin(2 * std::numbers::pi * frequency_hz * (t - t0) + phase);
    case Kind::table: {
      const size_t n = points.size();
      if (n == 0) return 0.0;
      auto line = [&](size_t i, size_t j) {  // the line through points i and j at t
        const auto [ta, sa] = points[i];
        const auto [tb, sb] = points[j];
        return tb == ta ? sb : sa + (sb - sa) * (t - ta) / (tb - ta);
      };
      if (t < points.front().first) return extrapolate && n > 1 ? line(0, 1) : points.front().second;
      if (t >= points.back().first) return extrapolate && n > 1 ? line(n - 2, n - 1) : points.back().second;
      // The last point at or before t (of two at one time, the second: the value after the jump).
      size_t i = 0;
      while (i + 1 < n && points[i + 1].first <= t) ++i;
      return line(i, i + 1);
    }
    case Kind::pulse: {
      if (t < t0) return before;
      // The period index k with t0 + kP ≤ t < t0 + (k+1)P, the edges computed as the breakpoints
      // are (the quotient alone can round an edge into the period before).
      double k = std::floor((t - t0) / period);
      if (t >= t0 + (k + 1) * period) k += 1;
      else if (t < t0 + k * period) k -= 1;
      if (count >= 0 && k >= static_cast<double>(count)) return before;
      return t < t0 + k * period + width ? value : before;  // the falling edge as its breakpoint
    }
    case Kind::expression:
      return offset + slope * t + amplitude * std::sin(2 * std::numbers::pi * frequency_hz * t + phase) + decay * std::exp(-t / tau);
  }
  return 0.0;
}

double Signal::slope_at(double t) const {
  const double w = 2 * std::numbers::pi * frequency_hz;
  switch (kind) {
    case Kind::constant:
    case Kind::step:
    case Kind::pulse: return 0.0;
    case Kind::ramp: return t >= t0 && t < t1 ? (value - before) / (t1 - t0) : 0.0;
    case Kind::sine: return t < t0 ? 0.0 : amplitude * w * std::cos(w * (t - t0) + phase);
    case Kind::table: {
      const size_t n = points.size();
      if (n < 2) return 0.0;
      auto seg = [&](size_t i) { return (points[i + 1].second - points[i].second) / (points[i + 1].first - points[i].first); };
      if (t < points.front().first) return extrapolate ? seg(0) : 0.0;
      if (t >= points.back().first) return extrapolate ? seg(n - 2) : 0.0;
      size_t i = 0;
      while (i + 1 < n && points[i + 1].first <= t) ++i;
      return seg(i);
    }
    case Kind::expression: return slope + amplitude * w * std::cos(w * t + phase) - decay / tau * std::exp(-t / tau);
  }
  return 0.0;
}

void Signal::breakpoints(std::vector<double>& out, double t_end, bool zeros) const {
  switch (kind) {
    case Kind::constant:
    case Kind::expression: break;
    case Kind::step: out.push_back(t0); break;
    case Kind::ramp: out.push_back(t0), out.push_back(t1); break;
    case Kind::sine: out.push_back(t0); break;
    case Kind::table:
      for (const auto& p : points) out.push_back(p.first);
      break;
    case Kind::pulse:
      for (long k = 0; (count < 0 || k < count) && t0 + static_cast<double>(k) * period <= t_end; ++k)
        out.push_back(t0 + static_cast<double>(k) * period), out.push_back(t0 + static_cast<double>(k) * period + width);
      break;
  }
  if (!zeros) return;
  // Zero crossings inside the pieces: a ramp's and a table's segments (linear), a sine's (closed form).
  auto segment = [&](double ta, double sa, double tb, double sb) {
    if (tb > ta && ((sa < 0 && sb > 0) || (sa > 0 && sb < 0))) out.push_back(ta + (tb - ta) * sa / (sa - sb));
  };
  if (kind == Kind::ramp) segment(t0, before, t1, value);
  if (kind == Kind::table)
    for (size_t i = 0; i + 1 < points.size(); ++i) segment(points[i].first, points[i].second, points[i + 1].first, points[i + 1].second);
  if (kind == Kind::sine && amplitude != 0.0 && std::abs(offset) < std::abs(amplitude)) {
    // offset + A sin(x) = 0, x = ω (t − t0) + phase: x = asin(c) + 2πk or π − asin(c) + 2πk, c = −offset/A.
    const double w = 2 * std::numbers::pi * frequency_hz, c = std::asin(-offset / amplitude);
    for (double x0 : {c, std::numbers::pi - c})
      for (double k = std::floor((phase - x0) / (2 * std::numbers::pi)); ; k += 1.0) {
        const double t = t0 + (x0 + 2 * std::numbers::pi * k - phase) / w;
        if (t > t_end) break;
        if (t > t0) out.push_back(t);
      }
  }
}

namespace {
double ramp01(double t, double t0, double dt) {
  if (t < t0) return 0.0;
  if (dt <= 0.0 || t >= t0 + dt) return 1.0;
  return (t - t0) / dt;
}
}  // namespace

double Friction::static_limit(double t) const {
  switch (kind) {
    case Kind::contact: return via_mu ? normal_at(t) * mu_s : Fs;
    case Kind::brake: return application_at(t) * Fs;
    case Kind::clutch: return std::max(0.0, fN.at(t)) * mu_s;
    default: return HUGE_VAL;
  }
}

double Friction::kinetic_level(double t, double speed) const {
  switch (kind) {
    case Kind::contact:
      if (via_mu) return normal_at(t) * mu_k;
      if (!kinetic_table.empty()) {  // linear in the sliding speed, the end values held
        const auto& T = kinetic_table;
        if (speed <= T.front().first) return T.front().second;
        if (speed >= T.back().first) return T.back().second;
        size_t i = 0;
        while (T[i + 1].first <= speed) ++i;
        return T[i].second + (T[i + 1].second - T[i].second) * (speed - T[i].first) / (T[i + 1].first - T[i].first);
      }
      if (stribeck_speed > 0.0) return Fk + (Fs - Fk) * std::exp(-std::pow(speed / stribeck_speed, stribeck_exponent));  // Stribeck
      return Fk;
    case Kind::brake: return application_at(t) * Fk;
    case Kind::clutch: return std::max(0.0, fN.at(t)) * mu_k;
    case Kind::freewheel: return drag;
    case Kind::stop: return 0.0;
  }
  return 0.0;
}

// r(t) = max(0, s(t)): an application below 0 is released (docs/model-files.md, Brakes).
double Friction::application_at(double t) const { return with_application ? std::max(0.0, application.at(t)) : ramp01(t, time, ramp); }

bool Friction::engaged(double t) const {
  // Engaged where the level is positive just after t (a step or ramp starting at t engages at t;
  // the engine decides its levels on the right of a breakpoint, docs/hybrid.md).
  const double tr = t + 1e-9 * std::max(1.0, t);
  if (kind == Kind::brake) return with_application ? application.at(tr) > 0.0 : t >= time;
  if (kind == Kind::clutch) return fN.at(tr) > 0.0;
  return true;
}

void Friction::breakpoints(std::vector<double>& out, double t_end) const {
  if (kind == Kind::brake && with_application) application.breakpoints(out, t_end, true);
  else if (kind == Kind::brake) out.push_back(time), out.push_back(time + ramp);
  if (kind == Kind::clutch) fN.breakpoints(out, t_end, true);
  if (kind == Kind::contact && via_mu) fN.breakpoints(out, t_end);
}

namespace {

enum class FMode { released, stuck, slip_pos, slip_neg, off };  // off: a stop not touching its body
enum class GMode { open, closed_pos, closed_neg };

int sign_of(FMode md) { return md == FMode::slip_pos ? 1 : md == FMode::slip_neg ? -1 : 0; }
bool sliding(FMode md) { return md == FMode::slip_pos || md == FMode::slip_neg; }

/// A gear mesh's mode: the flank g (+1, −1; 0 the free play; without backlash the sign of τ) and
/// the assumed signs of the pinion's and the wheel's speeds; `held` the body at rest it holds on a
/// lossy flank (1 the pinion, 2 the wheel, 0 none: docs/model-files.md, "Elastic gear mesh").
struct MeshMode {
  int g = 0, s1 = 1, s2 = 1, held = 0;
};

/// A two-stage lossy train's mode: s = 0 stuck, else rolling in s with each stage's driving side
/// (true: side b drives).
struct TrainMode {
  int s = 0;
  bool b1 = false, b2 = false;
  bool operator==(const TrainMode&) const = default;
};

struct Modes {
  std::vector<TrainMode> train;
  std::vector<GMode> gap;
  std::vector<FMode> fr;
  std::vector<MeshMode> mesh;
  std::vector<int> sway;  ///< per spatial rope: 0 taut, 1 slack
};

class Sim {
 public:
  Sim(const RefModel& m, const RefOptions& o) : m_(m), o_(o), n_(static_cast<int>(m.bodies.size())) {
    for (const auto& b : m.bodies) mass_.push_back(b.m);
    build_P();
    md_.gap.assign(m.links.size(), GMode::open);
    md_.fr.assign(m.frictions.size(), FMode::released);
    md_.mesh.assign(m.meshes.size(), MeshMode{});
    md_.sway.assign(m.sway.size(), 1);
    md_.train.assign(m.trains.size(), TrainMode{});
    series_v_.assign(m.frictions.size(), 0.0);
    // A lock's hold allowance ε_h = hold_allowance(k, atol): k = Σ (c + d·1 s⁻¹) of the links on its
    // bodies, atol the engine's (λ is known only to k atol: elements/hold_allowance.hpp).
    for (const auto& f : m.frictions) {
      double k = 0.0;
      for (const auto& l : m.links)
        if ((l.a >= 0 && (l.a == f.a || l.a == f.b)) || (l.b >= 0 && (l.b == f.a || l.b == f.b))) k += l.c + l.d;
      hold_.push_back(hold_allowance(k, kCampaignAtol));
    }
    // The force scale of the model (the thresholds of the switching functions are relative to it).
    // (sampled over the run: every signal kind, its largest magnitude up to a sample's spacing).
    for (int i = 0; i <= 2000; ++i) {
      const double t = m.t_end * i / 2000.0;
      for (const auto& l : m.loads) fscale_ = std::max(fscale_, std::abs(l.s.at(t)));
      for (const auto& f : m.frictions)
        if (!f.one_sided()) fscale_ = std::max(fscale_, f.static_limit(t));
    }
    // The fastest rate: √(c/m) and d/m of every link over its lighter body.
    double w = 0.0;
    for (const auto& l : m.links) {
      double mm = HUGE_VAL;
      if (l.a >= 0) mm = std::min(mm, m.bodies[l.a].m - released_from(l.a));
      if (l.b >= 0) mm = std::min(mm, m.bodies[l.b].m - released_from(l.b));
      const double meff = (l.a >= 0 && l.b >= 0) ? mm / 2 : mm;
      w = std::max({w, std::sqrt(l.c / meff), l.d / meff});
    }
    // A gear mesh: Δ'' = −(c Δ + d Δ') (1/J_a + i²/J_b) on a flank; twice that rate: its contacts
    // through the backlash and its efficiency's switches restart the step often (at the rate alone a
    // model's event times moved by 1.4e-9 s between h and h/2, beyond the self-convergence test's 1e-9).
    for (const auto& G : m.meshes) {
      const double k = 1.0 / (m.bodies[static_cast<size_t>(G.a)].m - released_from(G.a)) +
                       G.i * G.i / (m.bodies[static_cast<size_t>(G.b)].m - released_from(G.b));
      w = std::max({w, 2.0 * std::sqrt(G.c * k), 2.0 * G.d * k});
    }
    // A kinetic level falling or rising with the sliding speed is a damper of rate |dF_k/ds|/m: the
    // Stribeck law's steepest slope (F_s − F_k)/w_s (at s = 0 for δ = 1, below it for δ > 1), a
    // table's steepest segment.
    for (const auto& f : m.frictions) {
      double slope = f.stribeck_speed > 0.0 ? (f.Fs - f.Fk) / f.stribeck_speed : 0.0;
      for (size_t j = 1; j < f.kinetic_table.size(); ++j)
        slope = std::max(slope, std::abs(f.kinetic_table[j].second - f.kinetic_table[j - 1].second) /
                                    (f.kinetic_table[j].first - f.kinetic_table[j - 1].first));
      double mm = HUGE_VAL;
      if (f.a >= 0) mm = std::min(mm, m.bodies[static_cast<size_t>(f.a)].m);
      if (f.b >= 0) mm = std::min(mm, m.bodies[static_cast<size_t>(f.b)].m);
      if (slope > 0.0) w = std::max(w, slope / ((f.a >= 0 && f.b >= 0) ? mm / 2 : mm));
    }
    // A spatial rope: its stretch √(c/m) at its shortest free length and d/m on the load; the drum's
    // √(c s²/J) and d s²/J.
    for (const auto& R : m.sway) {
      const double ml = m.bodies[static_cast<size_t>(R.z)].m, c = R.falls * R.EA / (0.5 * R.L0);
      w = std::max({w, std::sqrt(c / ml), R.d / ml});
      if (R.drum >= 0) {
        const double s = R.R / R.falls, J = m.bodies[static_cast<size_t>(R.drum)].m;
        w = std::max({w, std::sqrt(c * s * s / J), R.d * s * s / J});
      }
      if (R.psi >= 0) {  // a rigid load's rotation on the rope: √(c |a|²/J), d |a|²/J
        const double a2 = R.attach[0] * R.attach[0] + R.attach[1] * R.attach[1], J = m.bodies[static_cast<size_t>(R.psi)].m;
        w = std::max({w, std::sqrt(c * a2 / J), R.d * a2 / J});
      }
    }
    // A DC motor's electrical rates: R/L and the coupling k/√(L m).
    for (const auto& M : m.motors)
      w = std::max({w, M.R / M.L, M.k / std::sqrt(M.L * (m.bodies[static_cast<size_t>(M.body)].m - released_from(M.body)))});
    h_ = w > 0 ? std::min(o.h_max, o.omega_h / w) : o.h_max;
  }

  RefResult run();

  /// The mass all releases of body i take away.
  double released_from(int i) const {
    double dm = 0.0;
    for (const auto& r : m_.releases)
      if (r.body == i) dm += r.dm;
    return dm;
  }

 private:
  const RefModel& m_;
  const RefOptions& o_;
  int n_;
  std::vector<double> im_;
  Eigen::MatrixXd P_;  // the inverse mass under the gears' rows (M⁻¹ without gears)

  std::vector<double> mass_;  // the bodies' current masses (releases lower them)

  /// M⁻¹ and P from the current masses (at the start and after every release; the stuck sets' A,
  /// formed from P, are formed again).
  void build_P() {
    im_.clear();
    for (double mi : mass_) im_.push_back(1.0 / mi);
    // The inverse mass under the ideal gears' rows J (q_a = i q_b: the row e_a − i e_b, held in
    // every mode): P = M⁻¹ − M⁻¹Jᵀ(J M⁻¹ Jᵀ)⁻¹J M⁻¹, so a = P f is the motion the gears allow and
    // the gears' forces never need to be known. Without gears P = M⁻¹.
    // A prescribed body weighs nothing here: its acceleration is the signal's (set in accel).
    for (int i = 0; i < n_; ++i)
      if (m_.bodies[static_cast<size_t>(i)].motion != Body::Motion::free) im_[static_cast<size_t>(i)] = 0.0;
    P_ = Eigen::VectorXd(Eigen::Map<const Eigen::VectorXd>(im_.data(), n_)).asDiagonal();
    if (!m_.gears.empty()) {
      Eigen::MatrixXd J = Eigen::MatrixXd::Zero(static_cast<long>(m_.gears.size()), n_);
      for (size_t g = 0; g < m_.gears.size(); ++g) {
        const Gear& G = m_.gears[g];
        const auto r = static_cast<long>(g);
        if (G.planetary) J(r, G.a) += 1.0, J(r, G.b) += G.ratio, J(r, G.c) -= 1.0 + G.ratio;  // Willis
        else J(r, G.a) += 1.0, J(r, G.b) -= G.ratio;                                          // q_a = i q_b
      }
      const Eigen::MatrixXd Mi = P_;
      P_ = Mi - Mi * J.transpose() * (J * Mi * J.transpose()).inverse() * J * Mi;
    }
    sets_.clear();
  }

  /// Slaved bodies follow their gear exactly: x_b = x_a / i (the rounding of P's projection).
  void follow_gears(double* x) const {
    for (const auto& g : m_.gears)
      if (!g.planetary) x[g.b] = x[g.a] / g.ratio;
  }
  Modes md_;
  double fscale_ = 1.0, h_ = 1e-3;
  RefResult res_;
  std::vector<double> series_v_;  ///< per stop: |v⁻| of the first impact of its current series of bounces (0: none)

  // ---- kinematics --------------------------------------------------------------------------------
  double qa(const double* y, int i) const { return i < 0 ? 0.0 : y[i]; }
  double va(const double* y, int i) const { return i < 0 ? 0.0 : y[n_ + i]; }
  double rel_u(const Friction& f, const double* y) const { return va(y, f.a) - va(y, f.b); }
  /// The hold rule's sign of a one-sided element: it holds while lock·λ ≥ 0 (λ: the force on b).
  static int lock(const Friction& f) {
    if (f.kind == Friction::Kind::freewheel) return 1;
    return f.stop_max ? 1 : -1;  // a stop is the row e_a (b = ground): it pushes a with −λ
  }
  static bool stop_row(const Friction& f) { return f.kind == Friction::Kind::stop; }

  double link_force(const Link& L, GMode gm, double dl, double ddl) const {
    if (!L.has_flanks()) return L.c * dl + L.d * ddl;
    if (gm == GMode::open) return 0.0;
    const double e = dl - (gm == GMode::closed_pos ? L.hi() : L.lo());
    const double ce = L.c * e, dd = L.d * ddl;
    if (!L.elasto) return ce + dd;
    return gm == GMode::closed_pos ? ce + std::min(ce, dd) : ce + std::max(ce, dd);
  }

  /// A spatial rope at the state y (docs/sway.md): its stretch e, ė, the unit vector u from the load
  /// to the suspension point, c(φ), dc/dφ, s and the force F in `mode` (0 taut, 1 slack).
  struct RopeAt {
    double e = 0, rate = 0, u[3] = {0, 0, 1}, c = 0, dc = 0, s = 0, F = 0;
  };
  /// A rigid load's rope point relative to its centre, R(ψ) a, and its derivative ∂(R(ψ) a)/∂ψ, in (h, z).
  static void attach_at(const SwayRope& R, double psi, double ra[2], double dra[2]) {
    const double c = std::cos(psi), s = std::sin(psi);
    ra[0] = R.attach[0] * c - R.attach[1] * s, ra[1] = R.attach[0] * s + R.attach[1] * c;
    dra[0] = -R.attach[0] * s - R.attach[1] * c, dra[1] = R.attach[0] * c - R.attach[1] * s;
  }
  RopeAt rope_at(const SwayRope& R, const double* y, int mode) const {
    RopeAt o;
    double ra[2] = {0, 0}, dra[2] = {0, 0};
    const double psi_dot = R.psi >= 0 ? y[n_ + R.psi] : 0.0;
    if (R.psi >= 0) attach_at(R, y[R.psi], ra, dra);
    const double w[3] = {qa(y, R.trolley) + R.offset - qa(y, R.x) - ra[0], qa(y, R.bridge) - qa(y, R.y), R.h - y[R.z] - ra[1]};
    const double wd[3] = {va(y, R.trolley) - va(y, R.x) - dra[0] * psi_dot, va(y, R.bridge) - va(y, R.y),
                          -y[n_ + R.z] - dra[1] * psi_dot};
    const double l = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    if (l > 0.0)
      for (int i = 0; i < 3; ++i) o.u[i] = w[i] / l;
    o.s = R.drum >= 0 ? R.R / R.falls : 0.0;
    const double phi = R.drum >= 0 ? y[R.drum] - m_.bodies[static_cast<size_t>(R.drum)].q0 : 0.0;
    const double L = R.L0 - o.s * phi, K = R.falls * R.EA;
    o.c = K / L, o.dc = K * o.s / (L * L);
    o.e = l - L;
    o.rate = o.u[0] * wd[0] + o.u[1] * wd[1] + o.u[2] * wd[2] + (R.drum >= 0 ? o.s * y[n_ + R.drum] : 0.0);
    o.F = mode == 0 ? o.c * o.e + R.d * o.rate : 0.0;
    return o;
  }

  /// A gear mesh's Δ = φ_a − i φ_b and Δ' (docs/model-files.md, "Elastic gear mesh").
  double mesh_D(const Mesh& G, const double* y) const { return y[G.a] - G.i * y[G.b]; }
  double mesh_Dr(const Mesh& G, const double* y) const { return y[n_ + G.a] - G.i * y[n_ + G.b]; }
  /// Its tooth moment in flank g: the elasto-backlash law of a gap with flanks ±b/2, 0 in the free
  /// play; without backlash c Δ + d Δ'.
  static double mesh_tau(const Mesh& G, int g, double D, double Dr) {
    if (!(G.backlash > 0.0)) return G.c * D + G.d * Dr;
    if (g == 0) return 0.0;
    const double ce = G.c * (D - g * 0.5 * G.backlash), dd = G.d * Dr;
    return g > 0 ? ce + std::min(ce, dd) : ce + std::max(ce, dd);
  }
  /// The held flank (docs/model-files.md): body p (0 the pinion, 1 the wheel) at rest while the other
  /// drives — its ideal torque T_p (−τ, i τ) and the other's speed ω_o feed the teeth, T_o ω_o < 0 —
  /// takes any torque between η T_p and T_p: [lo, hi].
  static void hold_range(const Mesh& G, double tau, int p, double* lo, double* hi) {
    const double T = p == 0 ? -tau : G.i * tau;
    *lo = std::min(G.eta * T, T), *hi = std::max(G.eta * T, T);
  }
  /// Whether the other body than p feeds the teeth on flank g with its speed's sign s_o: T_o has the
  /// sign −g on the pinion, +g on the wheel.
  static bool other_drives(int g, int p, int s_o) { return (p == 0 ? -g : g) * s_o > 0; }
  /// −R in the range, as a margin ≥ 0 (R the other loads on p, the stuck ones' included).
  static double hold_margin(const Mesh& G, double tau, int p, double R) {
    double lo, hi;
    hold_range(G, tau, p, &lo, &hi);
    return std::min(-R - lo, hi + R) + 1e-12 * (std::abs(lo) + std::abs(hi) + std::abs(R));
  }
  std::vector<double> mesh_M_;  // accel_core(): a held mesh's torque on its held body
  /// The sign of a speed just after an instant: its own, at 0 its acceleration's, else `keep`.
  static int sign_after(double v, double a, int keep) {
    if (v != 0.0) return v > 0.0 ? 1 : -1;
    if (a != 0.0) return a > 0.0 ? 1 : -1;
    return keep;
  }

  // ---- right-hand side of a mode -----------------------------------------------------------------
  struct StuckSet {
    std::vector<int> rows;   // the stuck elements
    Eigen::MatrixXd G, A;    // rows e_a − e_b; A = G M⁻¹ Gᵀ
    bool full = false;       // A regular
    Eigen::MatrixXd Ainv;
    // The bounded split's candidates (each row free 0, at its lower bound 1 or upper bound 2),
    // fewest bounds first, and the one that solved the last evaluation (tried first).
    std::vector<std::vector<int>> choices;
    std::vector<int> last;
  };
  std::map<unsigned, StuckSet> sets_;
  double t_left_ = -1.0;  // the end of the current step (its signals' left limits)
  // The start of the step before the current one in this piece (no event or breakpoint since; else
  // the piece's start), for event_window; the window of the events being recorded (0: exact).
  double t_back_ = 0.0, window_ = 0.0;
  // The initial state, and whether the run is still in its first piece (event_window).
  std::vector<double> y0_;
  bool from_start_ = true;
  std::vector<double> y_back_;
  std::vector<int> applied_at_rest_;  // brakes and clutches applied at rest now (engage → decide)
  std::vector<double> f_, lamv_, bv_;
  std::vector<double> hold_;  // each friction element's hold allowance ε_h (locks)

  StuckSet& stuck_set(unsigned mask) {
    auto it = sets_.find(mask);
    if (it != sets_.end()) return it->second;
    StuckSet S;
    for (size_t k = 0; k < m_.frictions.size(); ++k)
      if ((mask >> k & 1u) != 0) S.rows.push_back(static_cast<int>(k));
    const int s = static_cast<int>(S.rows.size());
    S.G = Eigen::MatrixXd::Zero(s, n_);
    for (int r = 0; r < s; ++r) {
      const Friction& fr = m_.frictions[static_cast<size_t>(S.rows[static_cast<size_t>(r)])];
      if (fr.a >= 0) S.G(r, fr.a) += 1.0;
      if (fr.b >= 0) S.G(r, fr.b) -= 1.0;
    }
    S.A = S.G * P_ * S.G.transpose();
    Eigen::FullPivLU<Eigen::MatrixXd> lu(S.A);
    lu.setThreshold(1e-12);
    S.full = lu.rank() == s;
    if (S.full) S.Ainv = S.A.inverse();
    return sets_.emplace(mask, std::move(S)).first->second;
  }

  /// λ of a stuck set whose rows are dependent (two stuck elements lock one motion), into lamv_;
  /// bv_ holds G M⁻¹ f.
  void redundant_lambda(StuckSet& S, double t) {
    const int s = static_cast<int>(S.rows.size());
    // Two stuck elements lock one motion (docs/hybrid.md, "Redundant locks: the bounded split"):
    // the weighted least-norm λ = W A (A W A)⁺ b, min Σ λ²/W, W the static limits F_s(t) (a
    // one-sided element: 1); a one-sided element whose share would be against its lock takes none
    // if the others carry every load alone. Where that share leaves an element beyond its bounds
    // (a friction element |λ| ≤ F_s(t), a one-sided one lock·λ ≥ −F_drag), λ is the bounded
    // weighted least-norm split; only where no split within the bounds exists is the share kept (and
    // the element beyond its bound breaks away).
    const Eigen::VectorXd b = Eigen::Map<const Eigen::VectorXd>(bv_.data(), s);
    Eigen::VectorXd W(s), lo(s), hi(s);
    for (int r = 0; r < s; ++r) {
      const Friction& fr = m_.frictions[static_cast<size_t>(S.rows[static_cast<size_t>(r)])];
      if (fr.one_sided()) {
        W(r) = 1.0;
        const double d = fr.kinetic_level(t);
        lo(r) = lock(fr) > 0 ? -d : -HUGE_VAL;
        hi(r) = lock(fr) > 0 ? HUGE_VAL : d;
      } else {
        const double Fs = fr.static_limit(t);
        W(r) = std::max(Fs, 1e-300);
        lo(r) = -Fs, hi(r) = Fs;
      }
    }
    const double btol = 1e-9 * (b.norm() + 1e-300);
    // The weighted least-norm λ over the rows not `fixed`, those held at `val`; g = A μ, μ the
    // multipliers of A λ = b (the free rows have λ = W g).
    Eigen::VectorXd g(s);
    auto weighted = [&](const std::vector<bool>& fixed, const Eigen::VectorXd& val) {
      Eigen::VectorXd w = W, l = Eigen::VectorXd::Zero(s);
      for (int r = 0; r < s; ++r)
        if (fixed[static_cast<size_t>(r)]) w(r) = 0.0, l(r) = val(r);
      const Eigen::VectorXd rhs = b - S.A * l;
      g.setZero();  // every row fixed: μ = 0 (the pseudo-inverse of a zero matrix is not formed)
      if (w.cwiseAbs().maxCoeff() > 0.0) {
        const Eigen::MatrixXd AWA = S.A * w.asDiagonal() * S.A;
        Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(AWA);
        cod.setThreshold(1e-12);
        g = S.A * (cod.pseudoInverse() * rhs);
      }
      for (int r = 0; r < s; ++r)
        if (!fixed[static_cast<size_t>(r)]) l(r) = w(r) * g(r);
      return l;
    };
    // Within the bounds and solving A λ = b to rounding (a looser residual would hold a set a
    // little beyond its limits: 1e-9 ‖b‖ delayed a breakaway by 1e-8 N).
    const double anorm = S.A.cwiseAbs().rowwise().sum().maxCoeff();
    auto within = [&](const Eigen::VectorXd& l) {
      if (!l.allFinite()) return false;
      if ((S.A * l - b).norm() > 1e-11 * (b.norm() + anorm * l.cwiseAbs().maxCoeff()) + 1e-300) return false;
      for (int r = 0; r < s; ++r) {
        const double tol = 1e-12 * (std::abs(l(r)) + fscale_);
        if (l(r) < lo(r) - tol || l(r) > hi(r) + tol) return false;
      }
      return true;
    };
    const Eigen::VectorXd zero = Eigen::VectorXd::Zero(s);
    std::vector<bool> fixed(static_cast<size_t>(s), false);
    Eigen::VectorXd lv = weighted(fixed, zero);
    bool any = false;
    for (int r = 0; r < s; ++r) {
      const Friction& fr = m_.frictions[static_cast<size_t>(S.rows[static_cast<size_t>(r)])];
      if (fr.one_sided() && lock(fr) * lv(r) < 0.0) fixed[static_cast<size_t>(r)] = true, any = true;
    }
    if (any) {
      const Eigen::VectorXd l2 = weighted(fixed, zero);
      if ((S.A * l2 - b).norm() <= btol) lv = l2;
    }
    if (!within(lv) && s <= 10) {
      // The bounded split min Σ λ²/W, A λ = b, lo ≤ λ ≤ hi, by its active sets: every assignment of
      // each row to {free, at its lower bound, at its upper bound} (finite bounds only), the free
      // rows' weighted least-norm solution. A feasible candidate whose bound multipliers
      // ν = ±(g − λ/W) are ≥ 0 satisfies the KKT conditions: it is the optimum (strictly convex
      // objective, convex set). Failing that (rounding in g), the feasible candidate of least
      // Σ λ²/W is the optimum too: the optimum's own active set is among the candidates.
      if (S.choices.empty()) {
        std::vector<int> c(static_cast<size_t>(s), 0);
        for (;;) {
          S.choices.push_back(c);
          int r = 0;
          while (r < s && ++c[static_cast<size_t>(r)] == 3) c[static_cast<size_t>(r++)] = 0;
          if (r == s) break;
        }
        auto nfix = [](const std::vector<int>& v) { return std::count_if(v.begin(), v.end(), [](int x) { return x != 0; }); };
        std::stable_sort(S.choices.begin(), S.choices.end(), [&](const auto& x, const auto& y) { return nfix(x) < nfix(y); });
      }
      Eigen::VectorXd best = lv, val(s);
      double best_obj = HUGE_VAL;
      auto try_choice = [&](const std::vector<int>& choice) {  // true: the optimum
        for (int r = 0; r < s; ++r) {
          const int c = choice[static_cast<size_t>(r)];
          fixed[static_cast<size_t>(r)] = c != 0;
          val(r) = c == 1 ? lo(r) : c == 2 ? hi(r) : 0.0;
          if (!std::isfinite(val(r))) return false;
        }
        const Eigen::VectorXd l = weighted(fixed, val);
        if (!within(l) || !g.allFinite()) return false;
        double obj = 0.0;
        bool kkt = true;
        for (int r = 0; r < s; ++r) {
          obj += l(r) * l(r) / W(r);
          const int c = choice[static_cast<size_t>(r)];
          const double nu = c == 2 ? g(r) - l(r) / W(r) : c == 1 ? l(r) / W(r) - g(r) : 0.0;
          if (nu < -1e-9 * (std::abs(g(r)) + std::abs(l(r) / W(r)) + 1e-300)) kkt = false;
        }
        if (obj < best_obj) best_obj = obj, best = l;
        if (kkt) best = l;
        return kkt;
      };
      bool done = !S.last.empty() && try_choice(S.last);
      for (size_t k = 0; k < S.choices.size() && !done; ++k)
        if (try_choice(S.choices[k])) done = true, S.last = S.choices[k];
      lv = best;
    }
    for (int r = 0; r < s; ++r) lamv_[static_cast<size_t>(r)] = lv(r);
  }

  /// Accelerations a (n) and the stuck loads λ (per friction element, 0 if not stuck) at (t, y).
  /// The accelerations in mode md; a two-stage lossy train's bodies by its own law (train_solve).
  void accel(double t_in, const double* y, const Modes& md, double* a, double* lam) {
    accel_core(t_in, y, md, a, lam);
    for (size_t k = 0; k < m_.trains.size(); ++k) {
      const LossyTrain& T = m_.trains[k];
      const TrainMode& tm = md.train[k];
      const double al = tm.s == 0 ? 0.0 : train_solve(T, tm.b1, tm.b2, f_.data()).alpha;
      a[T.a] = al, a[T.m] = al / T.i1, a[T.c] = al / (T.i1 * T.i2);
    }
  }

  // ---- two-stage lossy trains --------------------------------------------------------------------
  struct TrainSol {
    double alpha = 0.0, X1 = 0.0, Y1 = 0.0, X2 = 0.0, Y2 = 0.0;
  };
  /// Rolling with the sides b1, b2 (true: side b drives) under the forces f: reduced from the last
  /// body inward, every torque affine in α = a_a (k0 + k1 α):
  ///   c: J_c α/(i1 i2) = f_c + i2 Y2;  m: J_m α/i1 = f_m + i1 Y1 − X2;  a: J_a α = f_a − X1,
  /// each stage's X from its Y by its side (a drives: X = Y/e, b drives: X = r Y).
  TrainSol train_solve(const LossyTrain& T, bool b1, bool b2, const double* f) const {
    const double Ja = mass_[static_cast<size_t>(T.a)], Jm = mass_[static_cast<size_t>(T.m)], Jc = mass_[static_cast<size_t>(T.c)];
    const double Y2_0 = -f[T.c] / T.i2, Y2_1 = Jc / (T.i1 * T.i2 * T.i2);
    const double w2 = b2 ? T.r2 : 1.0 / T.e2;
    const double X2_0 = w2 * Y2_0, X2_1 = w2 * Y2_1;
    const double Y1_0 = (X2_0 - f[T.m]) / T.i1, Y1_1 = (Jm / T.i1 + X2_1) / T.i1;
    const double w1 = b1 ? T.r1 : 1.0 / T.e1;
    const double X1_0 = w1 * Y1_0, X1_1 = w1 * Y1_1;
    TrainSol x;
    x.alpha = (f[T.a] - X1_0) / (Ja + X1_1);
    x.X1 = X1_0 + X1_1 * x.alpha, x.Y1 = Y1_0 + Y1_1 * x.alpha;
    x.X2 = X2_0 + X2_1 * x.alpha, x.Y2 = Y2_0 + Y2_1 * x.alpha;
    return x;
  }
  /// How far the sides disagree with the power flow in direction s (0: consistent).
  static double train_violation(const TrainSol& x, int s, bool b1, bool b2) {
    const double v1 = b1 ? std::max(0.0, s * x.Y1) : std::max(0.0, -s * x.X1);
    const double v2 = b2 ? std::max(0.0, s * x.Y2) : std::max(0.0, -s * x.X2);
    return v1 + v2;
  }
  /// The consistent sides rolling in s (the least violation of the four).
  TrainMode train_sides(const LossyTrain& T, int s, const double* f) const {
    TrainMode best{s, false, false};
    double worst = HUGE_VAL;
    for (int combo = 0; combo < 4; ++combo) {
      const bool b1 = (combo & 1) != 0, b2 = (combo & 2) != 0;
      const double v = train_violation(train_solve(T, b1, b2, f), s, b1, b2);
      if (v < worst) worst = v, best = TrainMode{s, b1, b2};
    }
    return best;
  }
  /// The stuck train's function of a start in s: −s α_s (J_a + J_m/i1² + J_c/(i1 i2)²), α_s rolling in s.
  double train_margin(const LossyTrain& T, int s, const double* f) const {
    const TrainMode x = train_sides(T, s, f);
    const double I = mass_[static_cast<size_t>(T.a)] + mass_[static_cast<size_t>(T.m)] / (T.i1 * T.i1) +
                     mass_[static_cast<size_t>(T.c)] / (T.i1 * T.i1 * T.i2 * T.i2);
    return -s * train_solve(T, x.b1, x.b2, f).alpha * I;
  }
  std::vector<int> fired_trains_;  ///< trains whose function fired (decided strictly)
  /// Decides every train (docs/hybrid.md step 5): rolling, the consistent sides in sign(v_a); at rest
  /// a start in the s whose function is negative (beyond 1e-13 of the force scale unless it fired),
  /// else stuck. Records each stage's change as the engine names it.
  void decide_trains(double t, const std::vector<double>& y, bool initial) {
    for (size_t k = 0; k < m_.trains.size(); ++k) {
      const LossyTrain& T = m_.trains[k];
      std::vector<double> a(static_cast<size_t>(n_)), lam(m_.frictions.size());
      accel(t, y.data(), md_, a.data(), lam.data());
      const std::vector<double> f = f_;
      const double v = y[static_cast<size_t>(n_ + T.a)];
      TrainMode now;
      if (v != 0.0) {
        now = train_sides(T, v > 0.0 ? 1 : -1, f.data());
      } else {
        const bool fired = std::find(fired_trains_.begin(), fired_trains_.end(), static_cast<int>(k)) != fired_trains_.end();
        const double eps = fired ? 0.0 : 1e-13 * fscale_;
        int found = 0;
        for (int s : {1, -1})
          if (train_margin(T, s, f.data()) < -eps) {
            if (found++ == 0) now = train_sides(T, s, f.data());
          }
        if (found > 1) res_.ambiguous_from = std::min(res_.ambiguous_from, t);
      }
      const TrainMode was = md_.train[k];
      md_.train[k] = now;
      if (initial) continue;
      auto log = [&](const std::string& name, bool bw, bool bn) {
        if (was.s == now.s && (now.s == 0 || bw == bn)) return;
        record(t, now.s == 0 ? "stick" : was.s == 0 ? "slip" : was.s != now.s ? "reversal" : "driving_side", name);
      };
      log(T.name1, was.b1, now.b1);
      log(T.name2, was.b2, now.b2);
    }
    fired_trains_.clear();
  }

  void accel_core(double t_in, const double* y, const Modes& md, double* a, double* lam) {
    // A step that ends on a breakpoint sees the signals' left limits there (the next step starts
    // with the new values), as every step of the engine does.
    const double t = t_in == t_left_ ? std::nextafter(t_in, -HUGE_VAL) : t_in;
    f_.assign(static_cast<size_t>(n_), 0.0);
    auto& f = f_;
    for (const auto& l : m_.loads) f[static_cast<size_t>(l.body)] += l.s.at(t);
    for (size_t d = 0; d < m_.motors.size(); ++d) f[static_cast<size_t>(m_.motors[d].body)] += m_.motors[d].k * y[2 * n_ + static_cast<int>(d)];
    for (size_t k = 0; k < m_.links.size(); ++k) {
      const Link& L = m_.links[k];
      const double F = link_force(L, md.gap[k], qa(y, L.a) - qa(y, L.b), va(y, L.a) - va(y, L.b));
      if (L.b >= 0) f[static_cast<size_t>(L.b)] += F;
      if (L.a >= 0) f[static_cast<size_t>(L.a)] -= F;
    }
    // Gear meshes: −τ on the pinion, i τ on the wheel, η on the driven side (the power flows from
    // the pinion where τ σ_a > 0 and τ σ_b > 0, from the wheel where both are < 0).
    for (size_t k = 0; k < m_.meshes.size(); ++k) {
      const Mesh& G = m_.meshes[k];
      const MeshMode& mm = md.mesh[k];
      const double tau = mesh_tau(G, mm.g, mesh_D(G, y), mesh_Dr(G, y));
      if (mm.held == 1) {  // the wheel its ideal torque; the pinion's below, after every other force
        f[static_cast<size_t>(G.b)] += G.i * tau;
        continue;
      }
      if (mm.held == 2) {
        f[static_cast<size_t>(G.a)] -= tau;
        continue;
      }
      const bool pinion_drives = mm.g * mm.s1 > 0 && mm.g * mm.s2 > 0, wheel_drives = mm.g * mm.s1 < 0 && mm.g * mm.s2 < 0;
      f[static_cast<size_t>(G.a)] -= (wheel_drives ? G.eta : 1.0) * tau;
      f[static_cast<size_t>(G.b)] += (pinion_drives ? G.eta : 1.0) * G.i * tau;
    }
    // A point-mass load's weight on its z body (LOAD.z); spatial ropes: the rope's pull F u on the
    // load, −F u_x on the trolley, −F u_y on the bridge, −F s − ½ (dc/dφ) e² on the drum.
    for (int i = 0; i < n_; ++i) {
      const Body& b = m_.bodies[static_cast<size_t>(i)];
      if (b.load_coordinate && b.name.size() > 2 && b.name.compare(b.name.size() - 2, 2, ".z") == 0)
        f[static_cast<size_t>(i)] -= mass_[static_cast<size_t>(i)] * m_.g;
    }
    for (size_t k = 0; k < m_.sway.size(); ++k) {
      const SwayRope& R = m_.sway[k];
      if (md.sway[k] != 0) continue;
      const RopeAt o = rope_at(R, y, 0);
      if (R.x >= 0) f[static_cast<size_t>(R.x)] += o.F * o.u[0];
      if (R.y >= 0) f[static_cast<size_t>(R.y)] += o.F * o.u[1];
      f[static_cast<size_t>(R.z)] += o.F * o.u[2];
      if (R.trolley >= 0) f[static_cast<size_t>(R.trolley)] -= o.F * o.u[0];
      if (R.bridge >= 0) f[static_cast<size_t>(R.bridge)] -= o.F * o.u[1];
      if (R.drum >= 0) f[static_cast<size_t>(R.drum)] -= o.F * o.s + 0.5 * o.dc * o.e * o.e;
      if (R.psi >= 0) {  // the pull F u at the rope point r = c + R(ψ) a: its moment F u · ∂r/∂ψ
        double ra[2], dra[2];
        attach_at(R, y[R.psi], ra, dra);
        f[static_cast<size_t>(R.psi)] += o.F * (o.u[0] * dra[0] + o.u[2] * dra[1]);
      }
    }
    unsigned mask = 0;
    for (size_t k = 0; k < m_.frictions.size(); ++k) {
      const Friction& fr = m_.frictions[k];
      lam[k] = 0.0;
      if (sliding(md.fr[k])) {
        const double F = sign_of(md.fr[k]) * fr.kinetic_level(t, std::abs(rel_u(fr, y)));
        if (fr.b >= 0) f[static_cast<size_t>(fr.b)] += F;
        if (fr.a >= 0) f[static_cast<size_t>(fr.a)] -= F;
      } else if (md.fr[k] == FMode::stuck) {
        mask |= 1u << k;
      }
    }
    // A held body: the mesh's torque clamp(−R, lo, hi) against every other force R on it but the
    // stuck elements' (those, solved below, carry the rest).
    mesh_M_.assign(m_.meshes.size(), 0.0);
    for (size_t k = 0; k < m_.meshes.size(); ++k) {
      const Mesh& G = m_.meshes[k];
      const MeshMode& mm = md.mesh[k];
      if (mm.held == 0) continue;
      const int p = mm.held - 1, j = p == 0 ? G.a : G.b;
      double lo, hi;
      hold_range(G, mesh_tau(G, mm.g, mesh_D(G, y), mesh_Dr(G, y)), p, &lo, &hi);
      const double R = f[static_cast<size_t>(j)];
      mesh_M_[k] = std::clamp(-R, lo, hi);
      f[static_cast<size_t>(j)] += mesh_M_[k];
    }
    Eigen::Map<Eigen::VectorXd>(a, n_) = P_ * Eigen::Map<const Eigen::VectorXd>(f.data(), n_);
    for (int i = 0; i < n_; ++i)  // P has no row for a prescribed body: its motion is the signal's
      if (m_.bodies[static_cast<size_t>(i)].motion != Body::Motion::free) a[i] = m_.bodies[static_cast<size_t>(i)].prescribed_acceleration(t);
    if (mask == 0) return follow_gears(a);
    StuckSet& S = stuck_set(mask);
    const int s = static_cast<int>(S.rows.size());
    // b = G M⁻¹ f (the free accelerations' row differences); G M⁻¹ Gᵀ λ = b.
    bv_.assign(static_cast<size_t>(s), 0.0);
    for (int r = 0; r < s; ++r) {
      const Friction& fr = m_.frictions[static_cast<size_t>(S.rows[static_cast<size_t>(r)])];
      bv_[static_cast<size_t>(r)] = (fr.a >= 0 ? a[fr.a] : 0.0) - (fr.b >= 0 ? a[fr.b] : 0.0);
    }
    lamv_.assign(static_cast<size_t>(s), 0.0);
    if (S.full) {
      for (int r = 0; r < s; ++r)
        for (int c = 0; c < s; ++c) lamv_[static_cast<size_t>(r)] += S.Ainv(r, c) * bv_[static_cast<size_t>(c)];
    } else {
      redundant_lambda(S, t);
    }
    // a = M⁻¹ (f − Gᵀ λ)
    for (int r = 0; r < s; ++r) {
      const int k = S.rows[static_cast<size_t>(r)];
      const Friction& fr = m_.frictions[static_cast<size_t>(k)];
      const double l = lamv_[static_cast<size_t>(r)];
      for (int i = 0; i < n_; ++i) a[i] -= l * ((fr.a >= 0 ? P_(i, fr.a) : 0.0) - (fr.b >= 0 ? P_(i, fr.b) : 0.0));
      lam[k] = l;
    }
    // Bodies held together get exactly equal accelerations (a stuck pair's rounding).
    for (int r = 0; r < s; ++r) {
      const Friction& fr = m_.frictions[static_cast<size_t>(S.rows[static_cast<size_t>(r)])];
      if (fr.a >= 0 && fr.b < 0) a[fr.a] = 0.0;
      else if (fr.b >= 0 && fr.a < 0) a[fr.b] = 0.0;
    }
    follow_gears(a);
  }

  void deriv(double t, const std::vector<double>& y, const Modes& md, std::vector<double>& dy) {
    lam_d_.resize(m_.frictions.size());
    for (int i = 0; i < n_; ++i) dy[static_cast<size_t>(i)] = y[static_cast<size_t>(n_ + i)];
    accel(t, y.data(), md, dy.data() + n_, lam_d_.data());
    // DC motors: L di/dt = u(t) − R i − k v (the voltage's left limit at a step's end, as the loads).
    const double tl = t == t_left_ ? std::nextafter(t, -HUGE_VAL) : t;
    for (size_t d = 0; d < m_.motors.size(); ++d) {
      const DcMotor& M = m_.motors[d];
      const size_t s = static_cast<size_t>(2 * n_) + d;
      dy[s] = (M.u.at(tl) - M.R * y[s] - M.k * y[static_cast<size_t>(n_ + M.body)]) / M.L;
    }
  }

  std::vector<double> k1, k2, k3, k4, tmp, lam_d_;
  std::vector<double> rk4(double t, const std::vector<double>& y, double h) {
    const size_t N = y.size();
    k1.resize(N), k2.resize(N), k3.resize(N), k4.resize(N), tmp.resize(N);
    deriv(t, y, md_, k1);
    for (size_t i = 0; i < N; ++i) tmp[i] = y[i] + 0.5 * h * k1[i];
    deriv(t + 0.5 * h, tmp, md_, k2);
    for (size_t i = 0; i < N; ++i) tmp[i] = y[i] + 0.5 * h * k2[i];
    deriv(t + 0.5 * h, tmp, md_, k3);
    for (size_t i = 0; i < N; ++i) tmp[i] = y[i] + h * k3[i];
    deriv(t + h, tmp, md_, k4);
    std::vector<double> out(N);
    for (size_t i = 0; i < N; ++i) out[i] = y[i] + h / 6.0 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    return out;
  }

  // ---- switching functions -----------------------------------------------------------------------
  struct Fn {
    double g, eps;
    int gap = -1, fr = -1;  // which element (kinks: gap ≥ 0 with kink = true)
    bool kink = false;
    int mesh = -1, slot = 0;  // a gear mesh: 0 its flank (or τ's sign), 1 and 2 its bodies' speeds
    double res = 0.0;  // its resolution δ (> 0: the events it fires get a resolution window)
    int sway = -1;     // a spatial rope
    int train = -1, tslot = 0;  // a two-stage lossy train: 0, 1 its margins (stuck), 2 its rest, 3, 4 its stages' sides
  };

  std::vector<char> held_;        // functions(): bodies held at rest by a stuck element to the ground
  std::vector<char> sliding_on_;  // functions(): bodies a sliding friction element acts on

  std::vector<Fn> functions(double t_in, const std::vector<double>& y) {
    const double t = t_in == t_left_ ? std::nextafter(t_in, -HUGE_VAL) : t_in;
    std::vector<Fn> out;
    std::vector<double> a(static_cast<size_t>(n_)), lam(m_.frictions.size());
    accel(t_in, y.data(), md_, a.data(), lam.data());
    const double eps_x = 0.0, eps_v = 1e-12, eps_f = 1e-13 * fscale_;
    held_.assign(static_cast<size_t>(n_), 0);  // bodies a stuck element holds to the ground (at rest)
    sliding_on_.assign(static_cast<size_t>(n_), 0);  // bodies a sliding element acts on
    for (size_t k = 0; k < m_.frictions.size(); ++k) {
      const Friction& f = m_.frictions[k];
      if (sliding(md_.fr[k])) {
        if (f.a >= 0) sliding_on_[static_cast<size_t>(f.a)] = 1;
        if (f.b >= 0) sliding_on_[static_cast<size_t>(f.b)] = 1;
      }
      if (md_.fr[k] != FMode::stuck || (f.a >= 0 && f.b >= 0)) continue;
      held_[static_cast<size_t>(f.a >= 0 ? f.a : f.b)] = 1;
    }
    for (size_t k = 0; k < m_.links.size(); ++k) {
      const Link& L = m_.links[k];
      if (!L.has_flanks()) continue;
      const double dl = qa(y.data(), L.a) - qa(y.data(), L.b), ddl = va(y.data(), L.a) - va(y.data(), L.b);
      const int gi = static_cast<int>(k);
      const double gp = L.c * (dl - L.hi()) + L.d * ddl;  // the flank's c e + d δ̇ (contact ends at 0)
      const double gn = L.c * (dl - L.lo()) + L.d * ddl;
      switch (md_.gap[k]) {
        case GMode::open:
          out.push_back({dl <= L.hi() ? L.hi() - dl : -gp, dl <= L.hi() ? eps_x : eps_f, gi});
          if (L.kind == Link::Kind::gap) out.push_back({dl >= L.lo() ? dl - L.lo() : gn, dl >= L.lo() ? eps_x : eps_f, gi});
          break;
        case GMode::closed_pos:
          out.push_back({gp, eps_f, gi});
          if (L.elasto) out.push_back({L.c * (dl - L.hi()) - L.d * ddl, eps_f, gi, -1, true});
          break;
        case GMode::closed_neg:
          out.push_back({-gn, eps_f, gi});
          if (L.elasto) out.push_back({L.d * ddl - L.c * (dl - L.lo()), eps_f, gi, -1, true});
          break;
      }
    }
    // Gear meshes: in the free play the flanks' distances (past a flank: its c e + d Δ'); on a flank
    // its c e + d Δ' (the contact ends; without backlash τ changes sign), the elasto-backlash kink, and
    // σ ω of each body (a body reverses: the power direction changes).
    for (size_t k = 0; k < m_.meshes.size(); ++k) {
      const Mesh& G = m_.meshes[k];
      const MeshMode& mm = md_.mesh[k];
      const int mi = static_cast<int>(k);
      const double D = mesh_D(G, y.data()), Dr = mesh_Dr(G, y.data()), h = 0.5 * G.backlash;
      if (mm.g == 0) {
        const double gp = G.c * (D - h) + G.d * Dr, gn = G.c * (D + h) + G.d * Dr;
        out.push_back({D <= h ? h - D : -gp, D <= h ? eps_x : eps_f, -1, -1, false, mi, 0});
        out.push_back({D >= -h ? D + h : gn, D >= -h ? eps_x : eps_f, -1, -1, false, mi, 1});
        continue;
      }
      const double ce = G.c * (D - mm.g * h);
      // Without backlash τ's sign (after a decision it is > 0 strictly: the bisection's side) fires
      // at any negative value too: from rest τ grows as c (t − t₀)^k (a root at t₀, as a speed's).
      out.push_back({mm.g * (ce + G.d * Dr), h > 0.0 ? eps_f : 0.0, -1, -1, false, mi, 0});
      if (h > 0.0 && G.d > 0.0) out.push_back({mm.g * (ce - G.d * Dr), eps_f, -1, -1, true, mi, 3});
      // A speed's sign fires at any negative value, as the engine's: a body starting from rest as
      // c (t − t₀)^k through k − 1 springs (after a load's step, or at the start) reaches −1e-12 only
      // (1e-12/c)^(1/k) later (3e-6 to 6e-5 s) — its sign is − from t₀ on, a reversal at t₀ on
      // both sides. A body held by a stuck element to the ground has ω = 0 by its mode (RK4 leaves
      // it rounding, ~1e-20, whose sign would fire over and over: campaign gear-mesh seed 2 #99).
      // A body a sliding element acts on reverses where that element's slide function fires (u past
      // ±1e-12: the same zero, located and decided together — its stick may hold the body): there
      // the sign takes the slide's threshold (seed 2 #99: at 0 the sign flipped alone, back and
      // forth inside the slide's threshold, the loss turning the body each time).
      auto speed = [&](int b) { return held_[static_cast<size_t>(b)] ? 0.0 : y[static_cast<size_t>(n_ + b)]; };
      auto eps_of = [&](int b) { return sliding_on_[static_cast<size_t>(b)] ? eps_v : 0.0; };
      if (mm.held != 0) {
        // Held: the other body's speed in the sign that feeds the teeth (it stops driving: slot 4)
        // and the range's margin with R = J a − M, the stuck elements' loads included (slot 5).
        const int p = mm.held - 1, o = p == 0 ? G.b : G.a, j = p == 0 ? G.a : G.b;
        out.push_back({(p == 0 ? -mm.g : mm.g) * speed(o), eps_of(o), -1, -1, false, mi, 4});
        const double R = mass_[static_cast<size_t>(j)] * a[static_cast<size_t>(j)] - mesh_M_[k];
        out.push_back({.g = hold_margin(G, mesh_tau(G, mm.g, D, Dr), p, R), .eps = eps_f, .mesh = mi, .slot = 5,
                       .res = kLoadResolution * fscale_});
        continue;
      }
      out.push_back({mm.s1 * speed(G.a), eps_of(G.a), -1, -1, false, mi, 1});
      out.push_back({mm.s2 * speed(G.b), eps_of(G.b), -1, -1, false, mi, 2});
    }
    // Spatial ropes: taut, F (slack where it reaches 0); slack, −e (taut where the load reaches the
    // rope's length) — past it (a damped rope gone slack while stretched, ė < 0) the flank's force
    // −(c e + d ė), as a gap's open side: taut where it pulls again.
    for (size_t k = 0; k < m_.sway.size(); ++k) {
      const RopeAt o = rope_at(m_.sway[k], y.data(), 0);
      if (md_.sway[k] == 0) out.push_back({.g = o.F, .eps = eps_f, .sway = static_cast<int>(k)});
      else out.push_back({.g = o.e <= 0.0 ? -o.e : -o.F, .eps = o.e <= 0.0 ? eps_x : eps_f, .sway = static_cast<int>(k)});
    }
    // Two-stage lossy trains: stuck, −s α_s for both s; rolling, s v_a and each stage's side function.
    const std::vector<double> ft = f_;
    const double res_f = kLoadResolution * fscale_;  // functions of loads: their resolution (event_window)
    for (size_t k = 0; k < m_.trains.size(); ++k) {
      const LossyTrain& T = m_.trains[k];
      const TrainMode& tm = md_.train[k];
      const int ti = static_cast<int>(k);
      if (tm.s == 0) {
        out.push_back({.g = train_margin(T, 1, ft.data()), .eps = eps_f, .res = res_f, .train = ti, .tslot = 0});
        out.push_back({.g = train_margin(T, -1, ft.data()), .eps = eps_f, .res = res_f, .train = ti, .tslot = 1});
        continue;
      }
      const TrainSol x = train_solve(T, tm.b1, tm.b2, ft.data());
      out.push_back({.g = tm.s * y[static_cast<size_t>(n_ + T.a)], .eps = 0.0, .train = ti, .tslot = 2});
      out.push_back({.g = tm.b1 ? -tm.s * x.Y1 : tm.s * x.X1, .eps = eps_f, .res = res_f, .train = ti, .tslot = 3});
      out.push_back({.g = tm.b2 ? -tm.s * x.Y2 : tm.s * x.X2, .eps = eps_f, .res = res_f, .train = ti, .tslot = 4});
    }
    for (size_t k = 0; k < m_.frictions.size(); ++k) {
      const Friction& f = m_.frictions[k];
      const int fi = static_cast<int>(k);
      const FMode md = md_.fr[k];
      if (md == FMode::released) continue;
      if (md == FMode::off) {
        const double x = y[static_cast<size_t>(f.a)];
        out.push_back({f.stop_max ? f.stop_pos - x : x - f.stop_pos, eps_x, -1, fi});
      } else if (md == FMode::stuck) {
        const double res = kLoadResolution * fscale_;  // a load's resolution (event_window)
        if (f.one_sided()) out.push_back({.g = lock(f) * lam[k] + f.kinetic_level(t) + hold_[k], .eps = eps_f, .fr = fi, .res = res});
        else out.push_back({.g = f.static_limit(t) - std::abs(lam[k]), .eps = stuck_allowance(f.static_limit(t)), .fr = fi, .res = res});
      } else {
        out.push_back({sign_of(md) * rel_u(f, y.data()), eps_v, -1, fi});
        // The kinks of a kinetic table over the sliding speed: located (no mode changes there), so
        // no fixed step runs across a change of slope of the friction force.
        for (size_t j = 1; j < f.kinetic_table.size(); ++j)
          out.push_back({std::abs(rel_u(f, y.data())) - f.kinetic_table[j].first, 0.0, -1, fi, true});
      }
    }
    return out;
  }

  /// A mode function fires going from ≥ −ε to < −ε (armed only while ≥ −ε); a kink on either side.
  static bool fires(const Fn& f0, const Fn& f1) {
    if (f0.kink) return (f0.g < 0) != (f1.g < 0);
    return f0.g >= -f0.eps && f1.g < -f1.eps;
  }
  static bool any_fired(const std::vector<Fn>& g0, const std::vector<Fn>& g1) {
    for (size_t i = 0; i < g1.size() && i < g0.size(); ++i)
      if (fires(g0[i], g1[i])) return true;
    return false;
  }

  // ---- decisions ---------------------------------------------------------------------------------
  /// Mesh k holds body p (at rest) if −R lies in its range, R = J a − M the other loads on it with
  /// the stuck elements' (its margin ≥ 0); else p leaves rest the way the held torque's bound
  /// pushes it (the sign of its acceleration in the held mode). Returns whether it holds.
  bool try_hold(size_t k, int p, double t, const std::vector<double>& y) {
    const Mesh& G = m_.meshes[k];
    MeshMode& mm = md_.mesh[k];
    const int j = p == 0 ? G.a : G.b;
    mm.held = p + 1;
    std::vector<double> a(static_cast<size_t>(n_)), lam(m_.frictions.size());
    accel(t, y.data(), md_, a.data(), lam.data());
    const double R = mass_[static_cast<size_t>(j)] * a[static_cast<size_t>(j)] - mesh_M_[k];
    if (hold_margin(G, mesh_tau(G, mm.g, mesh_D(G, y.data()), mesh_Dr(G, y.data())), p, R) >= 0.0) return true;
    int& s = p == 0 ? mm.s1 : mm.s2;
    s = sign_after(0.0, a[static_cast<size_t>(j)], s);
    mm.held = 0;
    return false;
  }
  /// The hold of mesh k ends: the other body stops driving (it reverses; the held one then takes its
  /// ideal torque on both sides of rest) or the loads leave the range (the bound's way).
  void leave_hold(size_t k, double t, const std::vector<double>& y, bool other_stopped) {
    const Mesh& G = m_.meshes[k];
    MeshMode& mm = md_.mesh[k];
    const int p = mm.held - 1, j = p == 0 ? G.a : G.b, o = p == 0 ? G.b : G.a;
    std::vector<double> a(static_cast<size_t>(n_)), lam(m_.frictions.size());
    accel(t, y.data(), md_, a.data(), lam.data());
    int& sp = p == 0 ? mm.s1 : mm.s2;
    int& so = p == 0 ? mm.s2 : mm.s1;
    if (other_stopped) {
      // The held body then takes its ideal torque T_p on both sides of rest: sign(R + T_p), R its
      // other loads with the stuck ones' (J a − M in the held mode).
      const double vo = y[static_cast<size_t>(n_ + o)];
      so = vo != 0.0 ? (vo > 0.0 ? 1 : -1) : -so;
      const double tau = mesh_tau(G, mm.g, mesh_D(G, y.data()), mesh_Dr(G, y.data()));
      const double T = p == 0 ? -tau : G.i * tau;
      const double R = mass_[static_cast<size_t>(j)] * a[static_cast<size_t>(j)] - mesh_M_[k];
      if (R + T != 0.0) sp = R + T > 0.0 ? 1 : -1;
      mm.held = 0;
      return;
    }
    sp = sign_after(0.0, a[static_cast<size_t>(j)], sp);
    mm.held = 0;
  }
  /// After a decision: a held body whose margin (or the other's drive) the decision left negative
  /// leaves the hold (a stuck contact beside it broke away); at the start and at a breakpoint a
  /// body exactly at rest on a lossy flank while the other drives is held where its loads allow.
  void settle_holds(double t, const std::vector<double>& y, bool entry, bool initial) {
    for (size_t k = 0; k < m_.meshes.size(); ++k) {
      const Mesh& G = m_.meshes[k];
      MeshMode& mm = md_.mesh[k];
      if (mm.g == 0 || !(G.eta < 1.0)) continue;
      if (mm.held != 0) {
        const std::vector<Fn> g = functions(t, y);
        for (const Fn& f : g)
          if (f.mesh == static_cast<int>(k) && (f.slot == 4 || f.slot == 5) && f.g < -f.eps) {
            leave_hold(k, t, y, f.slot == 4);
            if (!initial) record(t, "mesh", G.name);
            break;
          }
        continue;
      }
      if (!entry) continue;
      for (int p = 0; p < 2; ++p) {
        const double vp = y[static_cast<size_t>(n_ + (p == 0 ? G.a : G.b))], vo = y[static_cast<size_t>(n_ + (p == 0 ? G.b : G.a))];
        if (vp != 0.0 || vo == 0.0 || !other_drives(mm.g, p, vo > 0.0 ? 1 : -1)) continue;
        const MeshMode was = mm;
        if (try_hold(k, p, t, y)) {
          if (!initial) record(t, "mesh", G.name);
          break;
        }
        mm = was;
      }
    }
  }

  void record(double t, const char* kind, const std::string& el) { res_.events.push_back({t, kind, el, window_}); }

  /// The resolution window of an event located at te (RefEvent::window): for every function that
  /// fired with a resolution δ > 0, how far from te it stays within δ of its value there — before te
  /// (g(te − τ) − g(te) ≤ δ) and after it in the same mode's equations (g(te) − g(te + τ) ≤ δ), by
  /// doubling τ from 1e-7·max(1, te) s; the larger side. Each side reaches at most to the start of
  /// the step before te's (t_back_, y_back_: the same piece) and two steps past te, short of the
  /// next breakpoint `t_next` (a lower bound there). One function evaluation per side when the root
  /// is simple and steep (no window below 1e-7 s).
  double event_window(double te, double t_next, const std::vector<Fn>& g0, const std::vector<Fn>& ge) {
    double w = 0.0;
    const double t_far = std::min(t_next, te + 2.0 * h_);
    for (size_t i = 0; i < ge.size() && i < g0.size(); ++i) {
      if (!fires(g0[i], ge[i]) || ge[i].kink || !(ge[i].res > 0.0)) continue;
      for (const double side : {-1.0, 1.0}) {
        double within = 0.0;
        for (double tau = 1e-7 * std::max(1.0, te); side < 0 ? te - tau > t_back_ : te + tau < t_far; tau *= 2.0) {
          const double s = te + side * tau;
          std::vector<double> ys = y_back_;  // at s, in steps of at most h from t_back_
          const int pieces = static_cast<int>(std::ceil((s - t_back_) / h_));
          for (int p = 0; p < pieces; ++p) ys = rk4(t_back_ + (s - t_back_) * p / pieces, ys, (s - t_back_) / pieces);
          if (side * (ge[i].g - functions(s, ys)[i].g) > ge[i].res) break;
          within = tau;
        }
        // In the run's first piece (no event or breakpoint before te, the modes the start's), a
        // window that reaches the step before te goes on back towards t = 0 (from the initial
        // state), and where the function is within δ all the way, at 0 too, the root is known only
        // to [0, te]: the window is te, the instant is the start's decision (a train or a freewheel
        // starting from rest, its margin growing from 0 like c t^k: `gear` seed 2 #5, seed 7 #304).
        if (side < 0 && from_start_ && within > 0.0 && te - 2.0 * within <= t_back_) {
          bool all = true;
          for (double tau = 2.0 * within; all; tau *= 2.0) {
            const double s = std::max(0.0, te - tau);
            std::vector<double> ys = y0_;
            const int pieces = static_cast<int>(std::ceil(s / h_));
            for (int p = 0; p < pieces; ++p) ys = rk4(s * p / pieces, ys, s / pieces);
            all = side * (ge[i].g - functions(s, ys)[i].g) <= ge[i].res;
            if (s == 0.0) break;
          }
          if (all) within = te;
        }
        w = std::max(w, within);
      }
    }
    return w;
  }

  /// Sets u = 0 exactly for every element in `rows` (friction rows e_a − e_b, stop rows e_a): the
  /// momentum-keeping projection v ← v − M⁻¹Gᵀ(G M⁻¹ Gᵀ)⁺ G v.
  void project(std::vector<double>& y, const std::vector<int>& rows) const {
    if (rows.empty()) return;
    const int s = static_cast<int>(rows.size());
    Eigen::MatrixXd G = Eigen::MatrixXd::Zero(s, n_);
    for (int r = 0; r < s; ++r) {
      const Friction& fr = m_.frictions[static_cast<size_t>(rows[static_cast<size_t>(r)])];
      if (fr.a >= 0) G(r, fr.a) += 1.0;
      if (fr.b >= 0) G(r, fr.b) -= 1.0;
    }
    Eigen::Map<Eigen::VectorXd> v(y.data() + n_, n_);
    const Eigen::MatrixXd A = G * P_ * G.transpose();
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod(A);
    cod.setThreshold(1e-12);
    const Eigen::VectorXd dv = P_ * (G.transpose() * (cod.pseudoInverse() * (G * v)));
    v -= dv;
    // Exactly equal speeds: the mean of each stuck pair (rounding of the projection).
    for (int r = 0; r < s; ++r) {
      const Friction& fr = m_.frictions[static_cast<size_t>(rows[static_cast<size_t>(r)])];
      if (fr.b < 0) v(fr.a) = 0.0;
      else if (fr.a < 0) v(fr.b) = 0.0;
    }
    for (int pass = 0; pass < 3; ++pass) {
      for (int r = 0; r < s; ++r) {
        const Friction& fr = m_.frictions[static_cast<size_t>(rows[static_cast<size_t>(r)])];
        if (fr.a >= 0 && fr.b >= 0) {
          if (im_[static_cast<size_t>(fr.a)] == 0.0) v(fr.b) = v(fr.a);  // a prescribed body leads
          else if (im_[static_cast<size_t>(fr.b)] == 0.0) v(fr.a) = v(fr.b);
          else {
            const double ma = 1.0 / im_[static_cast<size_t>(fr.a)], mb = 1.0 / im_[static_cast<size_t>(fr.b)];
            const double vm = (ma * v(fr.a) + mb * v(fr.b)) / (ma + mb);
            v(fr.a) = v(fr.b) = vm;
          }
        }
      }
      // A body held to the ground stays exactly at rest (the mean with a neighbour moved it by rounding).
      for (int r = 0; r < s; ++r) {
        const Friction& fr = m_.frictions[static_cast<size_t>(rows[static_cast<size_t>(r)])];
        if (fr.b < 0) v(fr.a) = 0.0;
        else if (fr.a < 0) v(fr.b) = 0.0;
      }
    }
    follow_gears(y.data() + n_);
  }

  /// Decides the friction elements at zero sliding speed (`zero`: their indices) by enumeration;
  /// `fired` are those whose switching function fired (judged strictly).
  void decide(double t, std::vector<double>& y, const std::vector<int>& fired, bool initial = false) {
    decide_trains(t, y, initial);
    std::vector<int> Z;
    for (size_t k = 0; k < m_.frictions.size(); ++k) {
      const Friction& f = m_.frictions[k];
      const FMode md = md_.fr[k];
      if (md == FMode::released || md == FMode::off) continue;
      const bool f_fired = std::find(fired.begin(), fired.end(), static_cast<int>(k)) != fired.end();
      if (md == FMode::stuck || rel_u(f, y.data()) == 0.0 || (f_fired && sliding(md))) Z.push_back(static_cast<int>(k));
    }
    const int z = static_cast<int>(Z.size());
    auto is_fired = [&](int k) { return std::find(fired.begin(), fired.end(), k) != fired.end(); };
    std::vector<double> a(static_cast<size_t>(n_)), lam(m_.frictions.size());
    // A slide whose u reached 0 (its function s u fired): u̇ there in the mode it ends, for its
    // event's sensitivity (RefEvent: δu/|u̇|).
    std::vector<double> du_end(m_.frictions.size(), 0.0);
    if (std::any_of(fired.begin(), fired.end(), [&](int k) { return sliding(md_.fr[static_cast<size_t>(k)]); })) {
      accel(t, y.data(), md_, a.data(), lam.data());
      for (int k : fired) {
        const Friction& f = m_.frictions[static_cast<size_t>(k)];
        if (sliding(md_.fr[static_cast<size_t>(k)]))
          du_end[static_cast<size_t>(k)] = (f.a >= 0 ? a[static_cast<size_t>(f.a)] : 0.0) - (f.b >= 0 ? a[static_cast<size_t>(f.b)] : 0.0);
      }
    }
    // Stops just come to rest (set by the impact) are in Z as stuck already.
    project(y, Z);
    if (z == 0) return;

    // A two-sided friction element (contact, brake, clutch) sliding while the stuck ones tie its two
    // bodies together (both in one component of their graph, the ground a node) would slide at
    // u ≡ 0: no slide, it is stuck with that set (docs/hybrid.md, the decision at an event). A stuck
    // freewheel or resting stop ties too (stuck, it is a constraint; campaign `mixed` seed 1 #61, #67:
    // a contact slid at u ≡ 0 on a body two stuck freewheels tied to the ground). Not one whose static
    // limit is below a load's resolution (a clutch at the zero of its normal force, breaking away
    // there as it opens: it holds nothing, sliding or stuck, and its loop of a clutch and a stuck
    // freewheel would have it slide the other clutch with it; `mixed` seed 2 #68).
    auto two_sided = [](const Friction& f) { return f.kind != Friction::Kind::freewheel && f.kind != Friction::Kind::stop; };
    auto locked = [&](const Modes& tr, int k) { return tied_by_stuck(tr, k); };
    // Consistency of a trial (Modes tr): stuck within limits, sliding accelerating its way.
    auto consistent = [&](const Modes& tr) {
      accel(t, y.data(), tr, a.data(), lam.data());
      for (int k : Z) {
        const Friction& f = m_.frictions[static_cast<size_t>(k)];
        const FMode md = tr.fr[static_cast<size_t>(k)];
        const double aa = f.a >= 0 ? a[static_cast<size_t>(f.a)] : 0.0, ab = f.b >= 0 ? a[static_cast<size_t>(f.b)] : 0.0;
        const double du = aa - ab, tol_a = 1e-12 * (std::abs(aa) + std::abs(ab)) + 1e-14;
        if (md == FMode::stuck) {
          if (f.one_sided()) {
            if (lock(f) * lam[static_cast<size_t>(k)] + f.kinetic_level(t) < -hold_[static_cast<size_t>(k)]) return false;
          } else {
            // The stuck switching function's own allowance, 1e-13 (F_s + the force scale) (one limit:
            // the decision and the function read one; at 1e-14 a clutch applied at the zero of its
            // normal force in a loop of stuck elements, F_s = 3e-15 N, was overloaded by its split's
            // rounding, 4e-13 N of a 120 N loop, and let slide at u ≡ 0: `mixed` seed 2 #68).
            const double Fs = f.static_limit(t);
            const double allow = is_fired(k) ? 0.0 : stuck_allowance(Fs);
            if (std::abs(lam[static_cast<size_t>(k)]) > Fs + allow) return false;
          }
        } else if (md == FMode::off) {  // a resting stop left: the body moves off it
          if ((f.stop_max ? -aa : aa) < -tol_a) return false;
        } else if (sign_of(md) * du < -tol_a || (two_sided(f) && f.static_limit(t) > kLoadResolution * fscale_ && locked(tr, k))) {
          return false;
        }
      }
      return true;
    };
    auto options = [&](int k) {
      const Friction& f = m_.frictions[static_cast<size_t>(k)];
      if (f.kind == Friction::Kind::stop) return std::vector<FMode>{FMode::stuck, FMode::off};
      if (f.kind == Friction::Kind::freewheel) return std::vector<FMode>{FMode::stuck, FMode::slip_neg};
      return std::vector<FMode>{FMode::stuck, FMode::slip_pos, FMode::slip_neg};
    };
    // Every combination.
    struct Trial {
      Modes md;
      int slides;
      std::vector<double> a;
    };
    std::vector<Trial> ok;
    std::vector<int> idx(static_cast<size_t>(z), 0);
    for (;;) {
      Modes tr = md_;
      int slides = 0;
      for (int j = 0; j < z; ++j) {
        const FMode md = options(Z[static_cast<size_t>(j)])[static_cast<size_t>(idx[static_cast<size_t>(j)])];
        tr.fr[static_cast<size_t>(Z[static_cast<size_t>(j)])] = md;
        slides += md != FMode::stuck;
      }
      if (consistent(tr)) ok.push_back({tr, slides, a});
      int j = 0;
      while (j < z && ++idx[static_cast<size_t>(j)] == static_cast<int>(options(Z[static_cast<size_t>(j)]).size()))
        idx[static_cast<size_t>(j)] = 0, ++j;
      if (j == z) break;
    }
    if (ok.empty()) throw std::runtime_error("no consistent mode combination at t = " + std::to_string(t));
    // The documented rule: all stuck; else release the most overloaded one after the other; else
    // fewest sliding first.
    Modes chosen = md_;
    for (int k : Z) chosen.fr[static_cast<size_t>(k)] = FMode::stuck;
    bool found = consistent(chosen);
    for (int guard = 0; !found && guard <= z; ++guard) {
      accel(t, y.data(), chosen, a.data(), lam.data());
      int worst = -1;
      double worst_r = 0.0;
      for (int k : Z) {
        if (chosen.fr[static_cast<size_t>(k)] != FMode::stuck) continue;
        const Friction& f = m_.frictions[static_cast<size_t>(k)];
        const double l = lam[static_cast<size_t>(k)];
        double r = 0.0;
        if (f.one_sided()) {
          r = lock(f) * l + f.kinetic_level(t) < -hold_[static_cast<size_t>(k)] ? HUGE_VAL : 0.0;
        } else {
          const double Fs = f.static_limit(t), allow = is_fired(k) ? 0.0 : stuck_allowance(Fs);
          r = std::abs(l) > Fs + allow ? (Fs > 0 ? std::abs(l) / Fs : HUGE_VAL) : 0.0;
        }
        if (r > worst_r) worst_r = r, worst = k;
      }
      if (worst < 0) break;
      const Friction& f = m_.frictions[static_cast<size_t>(worst)];
      chosen.fr[static_cast<size_t>(worst)] = f.kind == Friction::Kind::stop        ? FMode::off
                                              : f.kind == Friction::Kind::freewheel ? FMode::slip_neg
                                              : lam[static_cast<size_t>(worst)] > 0 ? FMode::slip_pos
                                                                                    : FMode::slip_neg;
      found = consistent(chosen);
    }
    int min_slides = z + 1;
    for (const auto& tr : ok) min_slides = std::min(min_slides, tr.slides);
    if (!found) {
      for (const auto& tr : ok)
        if (tr.slides == min_slides) {
          chosen = tr.md;
          break;
        }
    }
    // Ambiguity: a consistent combination with the fewest slides that moves otherwise.
    accel(t, y.data(), chosen, a.data(), lam.data());
    double amax = 1e-12;
    for (double x : a) amax = std::max(amax, std::abs(x));
    for (const auto& tr : ok) {
      if (tr.slides != min_slides) continue;
      for (int i = 0; i < n_; ++i)
        if (std::abs(tr.a[static_cast<size_t>(i)] - a[static_cast<size_t>(i)]) > 1e-9 * amax) {
          res_.ambiguous_from = std::min(res_.ambiguous_from, t);
          break;
        }
    }
    // Log the changes and set the modes.
    for (int k : Z) {
      const FMode was = md_.fr[static_cast<size_t>(k)], now = chosen.fr[static_cast<size_t>(k)];
      const std::string& name = m_.frictions[static_cast<size_t>(k)].name;
      if (was == now || initial) continue;
      const bool applied = std::find(applied_at_rest_.begin(), applied_at_rest_.end(), k) != applied_at_rest_.end();
      if (now == FMode::stuck) record(t, "stick", name);
      else if (was == FMode::stuck) record(t, applied ? "applied" : "slip", name);
      else if (sliding(was) && sliding(now)) record(t, "reversal", name);
      // The stick or reversal of a slide whose u reached 0 is a zero of u = v_a − v_b: states within
      // δv_a, δv_b move it by (δv_a + δv_b)/|u̇| (RefEvent).
      const double du = du_end[static_cast<size_t>(k)];
      if (sliding(was) && du != 0.0 && (now == FMode::stuck || sliding(now))) {
        const Friction& f = m_.frictions[static_cast<size_t>(k)];
        RefEvent& ev = res_.events.back();
        ev.body = f.a >= 0 ? f.a : f.b, ev.body2 = f.a >= 0 ? f.b : -1, ev.dt_dv = 1.0 / std::abs(du);
      }
    }
    md_ = chosen;
    applied_at_rest_.clear();
    // Stuck ones: exactly equal speeds.
    std::vector<int> st;
    for (size_t k = 0; k < m_.frictions.size(); ++k)
      if (md_.fr[k] == FMode::stuck) st.push_back(static_cast<int>(k));
    project(y, st);
  }

  /// The gaps after a velocity jump: each whose switching function is now negative toggles.
  void settle_gaps(double t, const std::vector<double>& y) {
    for (size_t k = 0; k < m_.links.size(); ++k) {
      const Link& L = m_.links[k];
      if (!L.has_flanks()) continue;
      const double dl = qa(y.data(), L.a) - qa(y.data(), L.b), ddl = va(y.data(), L.a) - va(y.data(), L.b);
      const double gp = L.c * (dl - L.hi()) + L.d * ddl, gn = L.c * (dl - L.lo()) + L.d * ddl;
      const GMode md = md_.gap[k];
      if (md == GMode::closed_pos && gp < 0.0) md_.gap[k] = GMode::open, record(t, "gap_opened", L.name);
      else if (md == GMode::closed_neg && gn > 0.0) md_.gap[k] = GMode::open, record(t, "gap_opened", L.name);
      else if (md == GMode::open && dl > L.hi() && gp > 0.0) md_.gap[k] = GMode::closed_pos, record(t, "gap_closed", L.name);
      else if (md == GMode::open && dl < L.lo() && gn < 0.0) md_.gap[k] = GMode::closed_neg, record(t, "gap_closed", L.name);
    }
    // A taut spatial rope whose F turns negative with the jump goes slack (a slack one's e is continuous).
    for (size_t k = 0; k < m_.sway.size(); ++k)
      if (md_.sway[k] == 0 && rope_at(m_.sway[k], y.data(), 0).F < 0.0) md_.sway[k] = 1, record(t, "slack", m_.sway[k].name);
  }

  /// A stuck friction element's allowance beyond its static limit F_s: its switching function's ε,
  /// 1e-13 (F_s + the model's force scale), which the decision reads too.
  double stuck_allowance(double Fs) const { return 1e-13 * (Fs + fscale_); }

  /// Whether the stuck friction elements other than k (freewheels and resting stops among them) tie
  /// k's two bodies together: both in one component of their graph, the ground a node.
  bool tied_by_stuck(const Modes& md, int k) const {
    std::vector<int> comp(static_cast<size_t>(n_) + 1);
    for (size_t i = 0; i < comp.size(); ++i) comp[i] = static_cast<int>(i);
    auto node = [&](int b) { return b < 0 ? n_ : b; };
    auto find = [&](int x) {
      while (comp[static_cast<size_t>(x)] != x) x = comp[static_cast<size_t>(x)];
      return x;
    };
    for (size_t j = 0; j < m_.frictions.size(); ++j)
      if (static_cast<int>(j) != k && md.fr[j] == FMode::stuck)
        comp[static_cast<size_t>(find(node(m_.frictions[j].a)))] = find(node(m_.frictions[j].b));
    const Friction& f = m_.frictions[static_cast<size_t>(k)];
    return find(node(f.a)) == find(node(f.b));
  }

  /// Engagement changes of brakes and clutches at t (a breakpoint or the start).
  void engage(double t, const std::vector<double>& y, bool initial) {
    applied_at_rest_.clear();
    for (size_t k = 0; k < m_.frictions.size(); ++k) {
      const Friction& f = m_.frictions[k];
      const bool on = f.engaged(t);
      if (md_.fr[k] == FMode::released && on) {
        // At rest where u is 0 within the resolution of the sliding functions, 1e-12 (1 + |v_a| +
        // |v_b|): the projection of a stuck chain leaves its bodies 1e-19 m/s apart (and the engine's
        // integration, its rounding, applied_at_rest in analysis/run.cpp).
        // A clutch whose two bodies the stuck elements tie (one component of their graph, the
        // ground a node) is at rest whatever u's rounding reads: its bodies move as one (the tie
        // rule of decide(); `mixed` seed 2 #68: a loop of a stuck clutch and a stuck freewheel
        // left the pair 1e-12 m/s apart after 0.1 s of RK4 and the reference logged `applied`).
        const double S = std::abs(va(y.data(), f.a)) + std::abs(va(y.data(), f.b)), u0 = rel_u(f, y.data());
        const double u = std::abs(u0) <= 1e-12 * (1.0 + S) || tied_by_stuck(md_, static_cast<int>(k)) ? 0.0 : u0;
        md_.fr[k] = u > 0 ? FMode::slip_pos : u < 0 ? FMode::slip_neg : FMode::stuck;
        // An `applied` event where it is applied while its bodies move (docs/hybrid.md); applied at
        // rest it simply holds, or slips at once (decided with the rest: its slide is `applied`).
        if (!initial && u == 0.0) applied_at_rest_.push_back(static_cast<int>(k));
        if (!initial && u != 0.0) record(t, "applied", f.name);
      } else if (md_.fr[k] != FMode::released && !on) {
        md_.fr[k] = FMode::released;
        if (!initial) record(t, "released", f.name);
      }
    }
  }

  /// The switching functions at a restart: every one must hold (≥ −ε) in the modes just decided —
  /// a negative one would never be armed, so a decision that leaves one is an error, not a disarm.
  void restart(double t, const std::vector<double>& y, std::vector<Fn>& g) {
    g = functions(t, y);
    for (const auto& f : g)
      if (!f.kink && f.g < -f.eps)
        throw std::runtime_error("the decision at t = " + std::to_string(t) + " leaves a switching function negative (" +
                                 (f.gap >= 0    ? m_.links[static_cast<size_t>(f.gap)].name
                                  : f.sway >= 0 ? m_.sway[static_cast<size_t>(f.sway)].name
                                  : f.mesh >= 0 ? m_.meshes[static_cast<size_t>(f.mesh)].name
                                  : f.train >= 0 ? m_.trains[static_cast<size_t>(f.train)].name1
                                                : m_.frictions[static_cast<size_t>(f.fr)].name) +
                                 ": " + std::to_string(f.g) + ")");
  }

  void project_stuck(std::vector<double>& y) const {
    std::vector<int> st;
    for (size_t k = 0; k < m_.frictions.size(); ++k)
      if (md_.fr[k] == FMode::stuck) st.push_back(static_cast<int>(k));
    project(y, st);
  }
};

RefResult Sim::run() {
  std::vector<double> y(static_cast<size_t>(2 * n_) + m_.motors.size());
  for (size_t d = 0; d < m_.motors.size(); ++d) y[static_cast<size_t>(2 * n_) + d] = m_.motors[d].i0;
  for (int i = 0; i < n_; ++i) {
    const Body& b = m_.bodies[static_cast<size_t>(i)];
    y[static_cast<size_t>(i)] = b.q0, y[static_cast<size_t>(n_ + i)] = b.motion == Body::Motion::speed ? b.prescribed.at(0.0) : b.v0;
  }
  // Initial modes: gaps by δ(0), stops off unless on the stop, friction by u(0) (zero: decided).
  for (size_t k = 0; k < m_.links.size(); ++k) {
    const Link& L = m_.links[k];
    if (!L.has_flanks()) continue;
    const double dl = qa(y.data(), L.a) - qa(y.data(), L.b);
    md_.gap[k] = dl > L.hi() ? GMode::closed_pos : dl < L.lo() ? GMode::closed_neg : GMode::open;
    // Past a flank whose force c e + d δ̇ pulls (a damped flank the bodies leave faster than its
    // spring presses): open, as settle_gaps decides it after a jump (`mixed` seed 7 #428, #436: the
    // start left the closed flank's function negative, a reference error).
    const double ddl = va(y.data(), L.a) - va(y.data(), L.b);
    if (md_.gap[k] == GMode::closed_pos && L.c * (dl - L.hi()) + L.d * ddl < 0.0) md_.gap[k] = GMode::open;
    if (md_.gap[k] == GMode::closed_neg && L.c * (dl - L.lo()) + L.d * ddl > 0.0) md_.gap[k] = GMode::open;
  }
  // Gear meshes: the flank by Δ(0) (without backlash the sign of τ, + at 0), the speeds' signs
  // from the state (+ at 0).
  for (size_t k = 0; k < m_.meshes.size(); ++k) {
    const Mesh& G = m_.meshes[k];
    const double D = mesh_D(G, y.data()), h = 0.5 * G.backlash;
    MeshMode& mm = md_.mesh[k];
    if (h > 0.0) mm.g = D > h ? 1 : D < -h ? -1 : 0;
    else mm.g = G.c * D + G.d * mesh_Dr(G, y.data()) < 0.0 ? -1 : 1;
    mm.s1 = y[static_cast<size_t>(n_ + G.a)] < 0.0 ? -1 : 1;
    mm.s2 = y[static_cast<size_t>(n_ + G.b)] < 0.0 ? -1 : 1;
  }
  // Spatial ropes: taut where the load is beyond the rope's length (at it: where it moves away).
  for (size_t k = 0; k < m_.sway.size(); ++k) {
    const RopeAt o = rope_at(m_.sway[k], y.data(), 0);
    md_.sway[k] = (o.e > 0.0 && o.F > 0.0) || (o.e == 0.0 && o.rate > 0.0) ? 0 : 1;
  }
  for (size_t k = 0; k < m_.frictions.size(); ++k) {
    const Friction& f = m_.frictions[k];
    if (f.kind == Friction::Kind::stop) {
      const double x = y[static_cast<size_t>(f.a)];
      md_.fr[k] = x == f.stop_pos ? FMode::stuck : FMode::off;
    }
  }
  engage(0.0, y, true);
  decide(0.0, y, {}, true);
  settle_holds(0.0, y, true, true);
  std::vector<Fn> g0;
  restart(0.0, y, g0);
  bool g0_valid = true;
  t_back_ = 0.0, y_back_ = y, y0_ = y, from_start_ = true;

  std::vector<double> bps;
  for (const auto& l : m_.loads) l.s.breakpoints(bps, m_.t_end);
  for (const auto& b : m_.bodies)
    if (b.motion != Body::Motion::free) b.prescribed.breakpoints(bps, m_.t_end);
  for (const auto& r : m_.releases) bps.push_back(r.t);
  for (const auto& M : m_.motors) M.u.breakpoints(bps, m_.t_end);
  for (const auto& f : m_.frictions) f.breakpoints(bps, m_.t_end);
  std::sort(bps.begin(), bps.end());
  bps.erase(std::remove_if(bps.begin(), bps.end(), [&](double b) { return !(b > 0.0 && b < m_.t_end); }), bps.end());
  bps.erase(std::unique(bps.begin(), bps.end()), bps.end());
  size_t ib = 0;
  const long rows = std::lround(m_.t_end / m_.dt_out);
  long next_row = 0;
  auto row = [&](double t) {
    res_.t.push_back(t);
    res_.q.emplace_back(y.begin(), y.begin() + n_);
    res_.v.emplace_back(y.begin() + n_, y.begin() + 2 * n_);
    std::vector<double> acc(static_cast<size_t>(n_)), lam(m_.frictions.size());
    accel(t, y.data(), md_, acc.data(), lam.data());
    res_.lam.push_back(std::move(lam));
  };
  double t = 0.0;
  row(0.0), next_row = 1;
  long events_here = 0;
  double last_event_t = -1.0;
  while (next_row <= rows) {
    const double t_row = next_row == rows ? m_.t_end : static_cast<double>(next_row) * m_.dt_out;
    double t_to = std::min(t + h_, t_row);
    if (ib < bps.size()) t_to = std::min(t_to, bps[ib]);
    const double dt = t_to - t;
    if (!g0_valid) g0 = functions(t, y), g0_valid = true;
    t_left_ = t_to;
    auto y1 = rk4(t, y, dt);
    ++res_.steps;
    auto g1 = functions(t_to, y1);
    if (any_fired(g0, g1)) {
      double lo = 0.0, hi = dt;
      const double res = 1e-13 * std::max(1.0, t);
      while (hi - lo > res) {
        const double mid = 0.5 * (lo + hi);
        if (any_fired(g0, functions(t + mid, rk4(t, y, mid)))) hi = mid;
        else lo = mid;
      }
      const double te = t + hi;
      y = rk4(t, y, hi);
      const auto ge = functions(te, y);
      window_ = event_window(te, ib < bps.size() ? bps[ib] : m_.t_end, g0, ge);
      t = te;
      t_left_ = -1.0;
      if (t - last_event_t < 1e-9 * std::max(1.0, t)) {
        if (++events_here > 200) {
          std::string last;  // the events that repeat
          for (size_t j = res_.events.size() >= 4 ? res_.events.size() - 4 : 0; j < res_.events.size(); ++j)
            last += (last.empty() ? "" : ", ") + res_.events[j].kind + " " + res_.events[j].element;
          throw std::runtime_error("chattering at t = " + std::to_string(t) + " (last: " + last + ")");
        }
      } else {
        events_here = 0, last_event_t = t;
      }
      if (static_cast<long>(res_.events.size()) > o_.max_events) throw std::runtime_error("too many events");
      std::vector<int> fired_fr;
      std::vector<size_t> rested;  // stops the impact brought to rest
      std::vector<double> rested_v;  // their |v⁻|
      for (size_t i = 0; i < ge.size() && i < g0.size(); ++i) {
        if (!fires(g0[i], ge[i]) || ge[i].kink) continue;
        if (ge[i].gap >= 0) {
          const size_t k = static_cast<size_t>(ge[i].gap);
          const Link& L = m_.links[k];
          const double dl = qa(y.data(), L.a) - qa(y.data(), L.b);
          const double ddl = std::abs(va(y.data(), L.a) - va(y.data(), L.b));
          const bool by_position = md_.gap[k] == GMode::open || L.d == 0.0;  // g a distance (RefEvent)
          // A damped flank opening at g = c e + d δ̇ = 0: δg = c δq + d δv moves it by δg/|ġ|, ġ = c δ̇ + d δ̈
          // in the closed mode (RefEvent: dt_dq = c/|ġ|, dt_dv = d/|ġ|).
          double gdot = 0.0;
          if (!by_position) {
            std::vector<double> a(static_cast<size_t>(n_)), lam(m_.frictions.size());
            accel(t, y.data(), md_, a.data(), lam.data());
            const double dda = (L.a >= 0 ? a[static_cast<size_t>(L.a)] : 0.0) - (L.b >= 0 ? a[static_cast<size_t>(L.b)] : 0.0);
            gdot = std::abs(L.c * (va(y.data(), L.a) - va(y.data(), L.b)) + L.d * dda);
          }
          if (md_.gap[k] == GMode::open) {
            md_.gap[k] = std::abs(dl - L.hi()) <= std::abs(dl - L.lo()) ? GMode::closed_pos : GMode::closed_neg;
            record(t, "gap_closed", L.name);
          } else {
            md_.gap[k] = GMode::open;
            record(t, "gap_opened", L.name);
          }
          if (by_position && ddl > 0.0) {
            RefEvent& ev = res_.events.back();
            ev.body = L.a >= 0 ? L.a : L.b, ev.body2 = L.a >= 0 ? L.b : -1, ev.dt_dq = 1.0 / ddl;
          } else if (!by_position && gdot > 0.0) {
            RefEvent& ev = res_.events.back();
            ev.body = L.a >= 0 ? L.a : L.b, ev.body2 = L.a >= 0 ? L.b : -1, ev.dt_dq = L.c / gdot, ev.dt_dv = L.d / gdot;
          }
        } else if (ge[i].train >= 0) {
          // A train: at its rest every speed of its bodies is 0 (the bisection's side), then decided.
          const LossyTrain& T = m_.trains[static_cast<size_t>(ge[i].train)];
          if (ge[i].tslot == 2) y[static_cast<size_t>(n_ + T.a)] = y[static_cast<size_t>(n_ + T.m)] = y[static_cast<size_t>(n_ + T.c)] = 0.0;
          fired_trains_.push_back(ge[i].train);
        } else if (ge[i].sway >= 0) {
          // A spatial rope goes slack (F reaches 0) or taut (e reaches 0).
          const size_t k = static_cast<size_t>(ge[i].sway);
          const SwayRope& R = m_.sway[k];
          const RopeAt o = rope_at(R, y.data(), 0);
          const bool by_position = (md_.sway[k] == 1 && o.e <= 0.0) || R.d == 0.0;  // g = −e or c e: a distance
          md_.sway[k] = 1 - md_.sway[k];
          record(t, md_.sway[k] == 0 ? "taut" : "slack", R.name);
          if (by_position && o.rate != 0.0) {
            RefEvent& ev = res_.events.back();
            ev.body = R.z, ev.body2 = R.x >= 0 ? R.x : R.y, ev.dt_dq = 1.0 / std::abs(o.rate);
          }
        } else if (ge[i].mesh >= 0) {
          // A gear mesh: the free play reaches a flank (the speeds' signs read again), the contact
          // ends, τ changes sign (no backlash), or a body on a flank reverses.
          const size_t k = static_cast<size_t>(ge[i].mesh);
          const Mesh& G = m_.meshes[k];
          MeshMode& mm = md_.mesh[k];
          std::vector<double> a(static_cast<size_t>(n_)), lam(m_.frictions.size());
          auto signs = [&](bool first, bool second) {
            accel(t, y.data(), md_, a.data(), lam.data());
            if (first) mm.s1 = sign_after(y[static_cast<size_t>(n_ + G.a)], a[static_cast<size_t>(G.a)], mm.s1);
            if (second) mm.s2 = sign_after(y[static_cast<size_t>(n_ + G.b)], a[static_cast<size_t>(G.b)], mm.s2);
          };
          // Reaching a flank (g its distance) or ending an undamped contact (g = c e): a zero of a
          // function of Δ, moved by δΔ/|Δ'| = (δq_a + i δq_b)/|Δ'| (RefEvent), as a gap's.
          const double Dr = std::abs(mesh_Dr(G, y.data()));
          auto by_position = [&]() {
            if (!(Dr > 0.0)) return;
            RefEvent& ev = res_.events.back();
            ev.body = G.a, ev.body2 = G.b, ev.w2 = G.i, ev.dt_dq = 1.0 / Dr;
          };
          if (mm.g == 0) {
            mm.g = ge[i].slot == 0 ? 1 : -1;
            signs(true, true);
            // A body at rest (its acceleration 0: a stuck element holds it) passes no power: the sign
            // under which it does not drive, that of its ideal torque (−g the pinion, +g the wheel).
            if (G.eta < 1.0) {
              if (y[static_cast<size_t>(n_ + G.a)] == 0.0 && a[static_cast<size_t>(G.a)] == 0.0) mm.s1 = -mm.g;
              if (y[static_cast<size_t>(n_ + G.b)] == 0.0 && a[static_cast<size_t>(G.b)] == 0.0) mm.s2 = mm.g;
            }
            // A body at rest when the teeth meet while the other drives: held where its loads allow.
            for (int p = 0; p < 2 && mm.held == 0; ++p)
              if (y[static_cast<size_t>(n_ + (p == 0 ? G.a : G.b))] == 0.0 && y[static_cast<size_t>(n_ + (p == 0 ? G.b : G.a))] != 0.0 &&
                  G.eta < 1.0 && other_drives(mm.g, p, p == 0 ? mm.s2 : mm.s1))
                (void)try_hold(k, p, t, y);
            record(t, "mesh", G.name);
            by_position();
          } else if (ge[i].slot == 4 || ge[i].slot == 5) {
            leave_hold(k, t, y, ge[i].slot == 4);
            record(t, "mesh", G.name);
          } else if (ge[i].slot == 0) {
            mm.held = 0;  // the contact ends, or τ changes sign: the hold with it
            // Damped: g = c e + d Δ' moved by (c δΔ + d δΔ')/|ġ|, ġ = c Δ' + d Δ'' in the contact's mode.
            double gdot = 0.0;
            if (G.d > 0.0) {
              accel(t, y.data(), md_, a.data(), lam.data());
              gdot = std::abs(G.c * mesh_Dr(G, y.data()) + G.d * (a[static_cast<size_t>(G.a)] - G.i * a[static_cast<size_t>(G.b)]));
            }
            if (G.backlash > 0.0) mm.g = 0, record(t, "free play", G.name);
            else mm.g = -mm.g, record(t, "mesh", G.name);
            if (G.d == 0.0) {
              by_position();
            } else if (gdot > 0.0) {
              RefEvent& ev = res_.events.back();
              ev.body = G.a, ev.body2 = G.b, ev.w2 = G.i, ev.dt_dq = G.c / gdot, ev.dt_dv = G.d / gdot;
            }
          } else {
            // A body reaches rest: on a lossy flank while the other drives it is held where its
            // loads lie in the range, else it leaves rest the way the bound pushes it.
            const int p = ge[i].slot - 1;
            if (G.eta < 1.0 && y[static_cast<size_t>(n_ + (p == 0 ? G.b : G.a))] != 0.0 && other_drives(mm.g, p, p == 0 ? mm.s2 : mm.s1)) {
              y[static_cast<size_t>(n_ + (p == 0 ? G.a : G.b))] = 0.0;
              (void)try_hold(k, p, t, y);
            } else {
              signs(ge[i].slot == 1, ge[i].slot == 2);
              // The other body exactly at rest (a stuck element holds it) is held once p drives.
              const int q = 1 - p;
              if (y[static_cast<size_t>(n_ + (q == 0 ? G.a : G.b))] == 0.0 && y[static_cast<size_t>(n_ + (p == 0 ? G.a : G.b))] != 0.0 &&
                  G.eta < 1.0 && other_drives(mm.g, q, p == 0 ? mm.s1 : mm.s2))
                (void)try_hold(k, q, t, y);
            }
            record(t, "mesh", G.name);
          }
        } else if (ge[i].fr >= 0) {
          const size_t k = static_cast<size_t>(ge[i].fr);
          const Friction& f = m_.frictions[k];
          if (md_.fr[k] == FMode::off) {
            // The impact: v⁺ = −e v⁻ at the stop; rest for e = 0 or a flight below the resolution.
            const size_t b = static_cast<size_t>(f.a);
            y[b] = f.stop_pos;
            const double vm = std::abs(y[static_cast<size_t>(n_) + b]);
            if (series_v_[k] == 0.0) series_v_[k] = vm;  // the first impact of a series of bounces
            const double vp = -f.e * y[static_cast<size_t>(n_) + b];
            y[static_cast<size_t>(n_) + b] = vp;
            std::vector<double> a(static_cast<size_t>(n_)), lam(m_.frictions.size());
            accel(t, y.data(), md_, a.data(), lam.data());
            const double back = f.stop_max ? a[b] : -a[b];
            // Rest: e = 0, or a flight 2|v⁺|/|a| below 1e-9·max(1, t) s, or a rebound height v⁺²/(2|a|)
            // of a few ulps of the position (below that the bounces only pump rounding).
            const bool rest = vp == 0.0 || (back > 0.0 && (2.0 * std::abs(vp) <= 1e-9 * std::max(1.0, t) * back ||
                                                          vp * vp <= 2.0 * back * 16.0 * (std::nextafter(std::abs(f.stop_pos), HUGE_VAL) - std::abs(f.stop_pos))));
            if (rest) {
              y[static_cast<size_t>(n_) + b] = 0.0;
              md_.fr[k] = FMode::stuck;
              record(t, "stick", f.name);
              // The rest is the series' accumulation instant (RefEvent): its sensitivity.
              RefEvent& ev = res_.events.back();
              ev.body = f.a, ev.dt_dq = series_v_[k] > 0.0 ? 1.0 / series_v_[k] : 0.0;
              if (f.e > 0.0 && f.e < 1.0 && back > 0.0) {
                ev.dt_dsqrtq = (1.0 + f.e) / ((1.0 - f.e) * std::sqrt(2.0 * back));
                ev.dt_dv = 2.0 * f.e / (back * (1.0 - f.e));
              }
              series_v_[k] = 0.0;
              rested.push_back(k), rested_v.push_back(vm);
            } else {
              record(t, "impact", f.name);
              RefEvent& ev = res_.events.back();
              ev.body = f.a, ev.dt_dq = vm > 0.0 ? 1.0 / vm : 0.0;
            }
            // The velocity jump changes δ̇ of the links on the body: a closed damped flank whose
            // c e + d δ̇ turns negative opens at the impact, an open one past its flank whose force
            // turns positive closes (the flanks are decided again, as the friction below).
            settle_gaps(t, y);
            // Friction on the body slides the other way now, or is decided at zero speed.
            for (size_t j = 0; j < m_.frictions.size(); ++j) {
              if (!sliding(md_.fr[j])) continue;
              const double u = rel_u(m_.frictions[j], y.data());
              if (u != 0.0 && (u > 0) != (md_.fr[j] == FMode::slip_pos)) {
                md_.fr[j] = u > 0 ? FMode::slip_pos : FMode::slip_neg;
                record(t, "reversal", m_.frictions[j].name);
              }
            }
          } else {
            fired_fr.push_back(static_cast<int>(k));
          }
        }
      }
      decide(t, y, fired_fr);
      settle_holds(t, y, false, false);
      // A plastic impact whose loads pull the body off the stop at once is one `impact` (docs/hybrid.md,
      // End stop), not a rest: its `stick` and the decision's `slip` at t become that impact.
      for (size_t r = 0; r < rested.size(); ++r) {
        const size_t k = rested[r];
        if (md_.fr[k] != FMode::off) continue;
        const std::string& name = m_.frictions[k].name;
        auto& ev = res_.events;
        ev.erase(std::remove_if(ev.begin(), ev.end(),
                                [&](const RefEvent& x) { return x.t == t && x.element == name && (x.kind == "stick" || x.kind == "slip"); }),
                 ev.end());
        record(t, "impact", name);
        RefEvent& imp = res_.events.back();
        imp.body = m_.frictions[k].a, imp.dt_dq = rested_v[r] > 0.0 ? 1.0 / rested_v[r] : 0.0;
      }
      restart(t, y, g0), g0_valid = true;
      window_ = 0.0, t_back_ = t, y_back_ = y, from_start_ = false;
    } else {
      t_back_ = t, y_back_ = y;  // this step's start: the next event's window may reach back to it
      y = std::move(y1);
      t = t_to;
      t_left_ = -1.0;
      g0 = std::move(g1);
      if (ib < bps.size() && t == bps[ib]) {
        ++ib;
        // Releases at t: the mass drops, position and velocity are continuous (the released part
        // leaves with the body's velocity); the stuck ones are decided again with the new masses.
        bool released = false;
        for (const auto& r : m_.releases)
          if (r.t == t) mass_[static_cast<size_t>(r.body)] -= r.dm, released = true, record(t, "release", r.name);
        if (released) build_P();
        engage(t, y, false);
        decide(t, y, {});
        settle_holds(t, y, true, false);
        restart(t, y, g0);
        t_back_ = t, y_back_ = y, from_start_ = false;
      }
      project_stuck(y);
      if (t == t_row) row(t), ++next_row;
    }
  }
  return std::move(res_);
}

}  // namespace

RefResult simulate_reference(const RefModel& m, const RefOptions& o) {
  try {
    Sim s(m, o);
    return s.run();
  } catch (const std::exception& e) {
    RefResult r;
    r.error = e.what();
    return r;
  }
}

}  // namespace machdyn::reference
