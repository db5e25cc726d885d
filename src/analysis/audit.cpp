// The invariant audit (analysis/audit.hpp): each check is one documented law, written here from the
// law and its parameters — never by calling the function that produced the value it checks.
#include "machdyn/analysis/audit.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <string_view>
#include <Eigen/Dense>
#include <fmt/format.h>

#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/analysis/simulate.hpp"

namespace machdyn {
namespace {
/// A state's global error in units of its local tolerance: the error control holds each step to
/// atol + rtol |state|, and the errors of the steps since the state was last exact add up.
constexpr double kGlobal = 1e3;
}  // namespace

AuditError::AuditError(std::string element, double t, std::string invariant, const std::string& values)
    : SolverError(element, t, fmt::format("invariant {} violated: {}", invariant, values)),
      invariant_(std::move(invariant)),
      values_(values),
      message_(fmt::format("invariant {} violated by '{}' at t = {:.17g} s: {}", invariant_, this->element(), t, values)) {}

bool audit_requested_by_environment() {
  const char* v = std::getenv("MACHDYN_CHECK");
  return v != nullptr && *v != '\0' && std::string_view(v) != "0";
}

namespace audit {
namespace {

[[noreturn]] void fail(const std::string& element, double t, const char* invariant, const std::string& values) {
  throw AuditError(element, t, invariant, values);
}

const char* mode_name(ContactMode m) { return to_string(m); }

}  // namespace

void check_contact(const ContactLaw& law, const std::string& name, double t, const ContactValues& x) {
  if (law.joint) return;  // a gear joint holds every load (elements/contact.hpp)
  const FrictionContact& c = *law.spec;
  // r(t) = max(0, g s(t)) and F_s = r F_s0 (model/model.hpp FrictionContact); released: r = 0.
  const bool released = law.applied && c.released(t);
  const double r = law.applied ? c.scale(t) : 1.0;
  if (law.stop && x.mode != ContactMode::stuck) {
    // Off its stop the body is free: it stays on its side of the stop, −lock (q − q_stop) ≥ 0.
    const double d = -static_cast<double>(law.lock) * (x.q - law.stop_position);
    if (d < -(1e-12 * std::max(1.0, std::abs(law.stop_position)) + x.position_resolution))
      fail(name, t, "stop.position",
           fmt::format("the body is at q = {:.17g}, {:.3g} beyond its stop at {:.17g} (lock {:+d}), mode {}", x.q, -d,
                       law.stop_position, law.lock, mode_name(x.mode)));
    return;
  }
  if (x.mode == ContactMode::stuck) {
    if (law.kinematic) {
      // Its bodies are held by their motions: it carries no load of its own (λ = 0).
      if (x.F != 0.0) fail(name, t, "contact.kinematic_load", fmt::format("stuck between prescribed motions with λ = {:.17g} ≠ 0", x.F));
      return;
    }
    if (law.lock != 0) {
      // A freewheel (or an end stop the body rests on) holds while lock·λ ≥ −F_d (allowance ε_h, the
      // resolution of λ: elements/hold_allowance.hpp): its drag at rest F_d = F_k0(0) is the static
      // limit of its free direction (0 for an end stop).
      const double Fd = law.stop ? 0.0 : c.kinetic_level(0.0);
      if (law.lock * x.F < -(Fd + x.hold_allowance))
        fail(name, t, law.stop ? "stop.hold" : "freewheel.hold",
             fmt::format("stuck with lock·λ = {:.17g} < −F_d = {:.17g} (λ = {:.17g}, lock {:+d}): it holds against "
                         "its free direction beyond its drag and its allowance {:.3g}",
                         law.lock * x.F, -Fd, x.F, law.lock, x.hold_allowance));
      return;
    }
    const double Fs = r * c.static_limit;
    if (std::abs(x.F) > Fs + 1e-12 * c.static_limit)
      fail(name, t, "contact.static_limit",
           fmt::format("stuck with |λ| = {:.17g} > F_s = {:.17g} ({:.6g} F_s; F_s0 = {:.17g}, application r = {:.6g}{})",
                       std::abs(x.F), Fs, Fs > 0 ? std::abs(x.F) / Fs : std::numeric_limits<double>::infinity(),
                       c.static_limit, r, released ? ", released" : ""));
    return;
  }
  // Sliding in s = ±1.
  const double s = static_cast<double>(static_cast<int>(x.mode));
  if (law.lock != 0 && static_cast<int>(x.mode) != -law.lock)
    fail(name, t, "freewheel.direction",
         fmt::format("slides in its locked direction (mode {}, lock {:+d}, u = {:.17g})", mode_name(x.mode), law.lock, x.u));
  // The kinetic law: F = s r F_k0(|u|) (a released one: r = 0, no force).
  const double level = c.kinetic_level(std::abs(x.u));
  const double expected = s * r * level;
  if (std::abs(x.F - expected) > 1e-9 * (r * level + c.static_limit))
    fail(name, t, "contact.kinetic_law",
         fmt::format("sliding ({}) at u = {:.17g} with F = {:.17g}, its law gives s r F_k(|u|) = {:.17g} (r = {:.6g}, "
                     "F_k = {:.17g})",
                     mode_name(x.mode), x.u, x.F, expected, r, level));
  // Its kept direction follows the bodies beside it: no event of its own while released, nor while r is
  // 0 up to rounding (ContactLaw::events: relabelled at the application's breakpoint).
  if (released || (law.applied && r <= ContactLaw::kApplicationRounding)) return;
  // Its direction is its motion's: s u ≥ 0 (u ≠ 0 against it is a missed stick or reversal).
  if (s * x.u < -(1e-12 * x.speed_scale + x.resolution))
    fail(name, t, "contact.sliding_direction",
         fmt::format("mode {} but the sliding velocity is u = {:.17g}: the friction force {:.17g} drives the motion",
                     mode_name(x.mode), x.u, x.F));
}

void check_locked_slide(const std::string& name, double t, ContactMode mode, double u,
                        const std::vector<std::vector<double>>& stuck_rows, const std::vector<double>& row) {
  if (mode == ContactMode::stuck || u != 0.0 || stuck_rows.empty()) return;
  const auto n = static_cast<Eigen::Index>(row.size()), s = static_cast<Eigen::Index>(stuck_rows.size());
  Eigen::MatrixXd G(s + 1, n);
  for (Eigen::Index i = 0; i <= s; ++i)
    for (Eigen::Index j = 0; j < n; ++j) G(i, j) = (i < s ? stuck_rows[static_cast<size_t>(i)] : row)[static_cast<size_t>(j)];
  Eigen::FullPivLU<Eigen::MatrixXd> with(G), without(G.topRows(s));
  with.setThreshold(1e-9);
  without.setThreshold(1e-9);
  if (with.rank() != without.rank()) return;  // its motion is free of the stuck set
  fail(name, t, "contact.locked_slide",
       fmt::format("labelled sliding ({}) at u = 0 while the stuck contacts beside it lock its motion (u ≡ 0): it is "
                   "stuck, its load within the limits of the set",
                   mode_name(mode)));
}

void check_link(const LinkLaw& law, const std::string& name, double t, const LinkValues& x) {
  if (!law.gap) return;
  // The law's parts before the mode's clamp: the spring part F_e(e) (c(q_a) e, or a buffer's
  // characteristic) and the damper F_v(δ̇) (elements/link.hpp); their magnitudes scale the rounding.
  auto spring = [&](double e) {
    return law.shaped ? law.shaped_force(e) : (law.winding ? law.K / law.free_length(x.qa) : law.c) * e;
  };
  const double Fv = law.d * x.rate + law.kh * x.rate * std::abs(x.rate);
  const bool one_sided = std::isinf(law.lo);
  // The rounding of the law's sum, and the force of a deflection and a rate within the integrator's
  // resolution (a flank reached to atol is reached).
  auto tolerance = [&](double e, double Fe) {
    const double dv = std::abs(x.rate) + x.resolution;
    return 1e-12 * (std::abs(Fe) + std::abs(Fv)) + std::abs(spring(e + x.resolution) - Fe) +
           law.d * x.resolution + law.kh * (dv * dv - x.rate * x.rate);
  };
  switch (x.mode) {
    case GapMode::closed_pos:
    case GapMode::closed_neg: {
      const double flank = x.mode == GapMode::closed_pos ? law.hi : law.lo;
      const double Fe = spring(x.delta - flank);
      const double sgn = x.mode == GapMode::closed_pos ? 1.0 : -1.0;
      if (sgn * x.F < -tolerance(x.delta - flank, Fe))
        fail(name, t, one_sided ? "rope.never_pushes" : "gap.flank_sign",
             fmt::format("closed on its {} flank with F = {:.17g} (δ = {:.17g}, flank {:.17g}, δ̇ = {:.17g}): a closed "
                         "flank {}",
                         sgn > 0 ? "positive" : "negative", x.F, x.delta, flank, x.rate,
                         one_sided ? "never pushes" : (sgn > 0 ? "never pulls" : "never pushes")));
      return;
    }
    case GapMode::open: {
      // Inside the gap it carries no load; beyond a flank the law's pressing force must not press
      // into that flank (else it passed the flank without closing).
      // Beyond a flank by more than the integrator's resolution (at the flank to atol is at it).
      if (x.delta - law.hi > x.resolution + 1e-12 * std::abs(law.hi)) {
        const double Fe = spring(x.delta - law.hi);
        if (Fe + Fv > tolerance(x.delta - law.hi, Fe))
          fail(name, t, "gap.inside",
               fmt::format("open at δ = {:.17g} beyond its positive flank {:.17g}, pressing with c e + d δ̇ = {:.17g}: it "
                           "passed the flank without closing",
                           x.delta, law.hi, Fe + Fv));
      }
      if (!one_sided && law.lo - x.delta > x.resolution + 1e-12 * std::abs(law.lo)) {
        const double Fe = spring(x.delta - law.lo);
        if (Fe + Fv < -tolerance(x.delta - law.lo, Fe))
          fail(name, t, "gap.inside",
               fmt::format("open at δ = {:.17g} beyond its negative flank {:.17g}, pressing with c e + d δ̇ = {:.17g}: it "
                           "passed the flank without closing",
                           x.delta, law.lo, Fe + Fv));
      }
      return;
    }
  }
}

void check_gear_loss(const std::string& name, double t, double X, double Y, double va, double force_scale,
                     double resolution) {
  const double P = (X - Y) * va;  // the heat of the mesh and bearing friction (elements/lossy_gear.hpp)
  const double T = std::abs(X) + std::abs(Y);
  if (P < -(1e-12 * (T + force_scale) * std::abs(va) + T * resolution))
    fail(name, t, "lossy_gear.loss",
         fmt::format("loss power (X − Y) v_a = {:.17g} W < 0 (X = {:.17g}, Y = {:.17g}, v_a = {:.17g}): the gear "
                     "delivers power",
                     P, X, Y, va));
}

void check_energy(double t, const EnergyValues& e, double tol, double& E_max, double abs_tol) {
  for (double v : {e.work, e.kinetic, e.kinetic_start, e.elastic, e.elastic_start, e.friction, e.damping, e.discrete})
    E_max = std::max(E_max, std::abs(v));
  const double res = e.residual();
  if (!(std::abs(res) <= tol * E_max + abs_tol))
    fail("energy books", t, "energy.balance",
         fmt::format("W − (ΔT + ΔV + losses) = {:.6g} J > {:.3g} × {:.6g} J + {:.3g} J (W = {:.9g}, ΔT = {:.9g}, ΔV = {:.9g}, "
                     "friction {:.9g}, damping {:.9g}, release/impact/released {:.9g})",
                     res, tol, E_max, abs_tol, e.work, e.kinetic - e.kinetic_start, e.elastic - e.elastic_start, e.friction,
                     e.damping, e.discrete));
}

void check_event_list(const Model& m, const SimulationResult& r) {
  if (r.columns.empty() || r.columns[0].empty()) return;  // no rows (record_series off)
  const std::vector<double>& time = r.columns[0];
  std::map<std::string, size_t> column;
  for (size_t j = 0; j < r.column_names.size(); ++j) column[r.column_names[j]] = j;
  // Per element: its mode column and the value each mode name stands for.
  struct Track {
    size_t col = 0;
    std::vector<const ModeEvent*> events;
  };
  std::map<std::string, Track> tracks;
  for (const auto& c : m.contacts)
    if (!c.joint)
      if (auto it = column.find(c.name + ".mode"); it != column.end()) tracks[c.name].col = it->second;
  for (const auto& l : m.links)
    if (auto it = column.find(l.name + ".gap_mode"); it != column.end()) tracks[l.name].col = it->second;
  for (const ModeEvent& ev : r.hybrid.events)
    if (auto it = tracks.find(ev.element); it != tracks.end()) it->second.events.push_back(&ev);
  auto value = [](const std::string& to) -> double {
    if (to == "stuck" || to == "open") return 0.0;
    if (to == "slip+" || to == "closed+") return 1.0;
    if (to == "slip-" || to == "closed-") return -1.0;
    return std::numeric_limits<double>::quiet_NaN();  // "released": its kept mode is no event
  };
  for (const auto& [name, tr] : tracks) {
    if (tr.events.empty()) continue;
    const std::vector<double>& col = r.columns[tr.col];
    size_t k = 0;
    double now = std::numeric_limits<double>::quiet_NaN();
    for (size_t row = 0; row < time.size() && row < col.size(); ++row) {
      // The events before the row (at t = 0 the initial ones: the first row shows them); a row at an
      // event's time shows the modes before it.
      while (k < tr.events.size() &&
             (tr.events[k]->t < time[row] || (tr.events[k]->kind == "initial" && tr.events[k]->t <= time[row]))) {
        if (tr.events[k]->kind != "impact") now = value(tr.events[k]->to);
        ++k;
      }
      if (std::isnan(now)) continue;
      if (col[row] != now)
        fail(name, time[row], "events.mode_columns",
             fmt::format("the mode column reads {:g} but the event list says {:g} (last event before: {} at t = {:.17g})",
                         col[row], now, k > 0 ? tr.events[k - 1]->kind : "none", k > 0 ? tr.events[k - 1]->t : 0.0));
    }
  }
}

}  // namespace audit

Audit::Audit(const Model& m, DriveSystem& sys, const EnergyBalance& E, const double& release_loss)
    : m_(m), sys_(sys), E_(E), release_loss_(release_loss) {
  fc_.assign(m.contacts.size(), 0.0);
  for (const FrictionContact& c : m.contacts)
    hold_.push_back(hold_allowance(ContactLaw::hold_stiffness(c, m), m.simulation.atol));
  // The books are quadrature states of the same integration: O(rtol) per unit energy, accumulated.
  tol_E_ = std::max(1e-6, kGlobal * m.simulation.rtol);
  // Their absolute part the same way: atol (J for these states) accumulated. BDF on
  // worm-hoist-s-curve.yaml is 1.45e-9 J off 3.6 ms after the start at 0.5 s (W = 3.6e-5 J).
  abs_E_ = std::max(1e-9, kGlobal * m.simulation.atol);
}

void Audit::in_mode(double t, const double* y) {
  try {
    // The laws at t⁻, the mode of the piece that ends at t; the first row (t = 0) ends no piece: the
    // run starts with the signals' values at 0 (their right limits — a step, pulse or table that
    // jumps at 0 s acts from the start), as its decision there took them.
    check(t > 0.0 ? std::nextafter(t, -std::numeric_limits<double>::infinity()) : t, t, y);
  } catch (const AuditError& e) {
    if (!pending_) pending_ = std::make_unique<AuditError>(e);
  }
}

void Audit::row(double t, const double* y) { in_mode(t, y); }

void Audit::piece_end(double tb, bool step_end, const double* y) {
  if (pending_ && pending_->time() < tb) settle();  // inside the piece: no event can excuse it
  if (step_end) in_mode(tb, y);
}

void Audit::after_event(double t, const double* y, bool located) {
  // The event's own crossing: a failure inside its location bracket, before the decision.
  if (pending_ && located && pending_->time() <= t && t - pending_->time() <= 2e-13 * std::max(1.0, std::abs(t)))
    pending_.reset();
  settle();
  check(t, t, y);
}

void Audit::settle() {
  if (!pending_) return;
  const AuditError e = *pending_;
  pending_.reset();
  throw e;
}

void Audit::check(double t_law, double t, const double* y) {
  try {
    check_at(t_law, y);
  } catch (const AuditError& e) {
    if (t_law == t) throw;
    throw AuditError(e.element(), t, e.invariant(), e.values());  // reported at t, the law taken at t⁻
  }
}

void Audit::check_at(double t, const double* y) {
  const int n = sys_.dof();
  const double* v = y + n;
  // Contacts: the engine's loads in the current modes (λ while stuck, the kinetic force sliding).
  const int nc = static_cast<int>(m_.contacts.size());
  if (nc > 0) {
    sys_.contact_forces(t, y, fc_.data());
    for (int k = 0; k < nc; ++k) {
      const ContactLaw& law = sys_.contact(k);
      audit::ContactValues x;
      x.mode = sys_.contact_mode(k);
      x.F = fc_[static_cast<size_t>(k)];
      x.u = law.sliding_velocity(t, v);
      for (int j = 0; j < law.row.terms; ++j) x.speed_scale += std::abs(law.row.w[j] * v[law.row.body[j]]);
      if (law.grounded) x.speed_scale += std::abs(law.surface_velocity(t));
      x.q = law.a >= 0 ? y[law.a] : 0.0;
      // The integrator's error control holds each step's local error to atol + rtol |state|; a speed's
      // global error is that accumulated over the steps since it was last exact (kGlobal, the factor
      // the energy books use): BDF on MSL OneWayClutch (rtol 1e-10) carries u off its closed form
      // −(10/6π)(1 + cos 6πt) by +7.7e-10 = 14 rtol S at every row of (7/6, 1.6) s, so at the tangency
      // u = 0 of t = 1.5 s it reads +7.7e-10 (test AuditTolerance.SpeedsAreResolvedToTheirGlobalError).
      x.resolution = kGlobal * (m_.simulation.atol + m_.simulation.rtol * x.speed_scale);
      x.position_resolution = m_.simulation.atol + m_.simulation.rtol * std::abs(x.q);
      x.hold_allowance = hold_[static_cast<size_t>(k)];
      audit::check_contact(law, m_.contacts[static_cast<size_t>(k)].name, t, x);
    }
    // A friction contact sliding at u = 0 exactly: is its motion locked by the stuck ones beside it?
    // Not a released one, nor one whose r is 0 up to rounding (its mode a label until the
    // application's breakpoint decides it: the left limit of a normal force's rising zero).
    for (int k = 0; k < nc; ++k) {
      const ContactLaw& law = sys_.contact(k);
      if (sys_.contact_mode(k) == ContactMode::stuck || law.lock != 0 || law.joint || law.kinematic ||
          (law.applied && (law.spec->released(t) || law.scale(t) <= ContactLaw::kApplicationRounding)) ||
          law.sliding_velocity(t, v) != 0.0)
        continue;
      auto dense = [&](const ContactLaw& c) {
        std::vector<double> r(static_cast<size_t>(n), 0.0);
        for (int j = 0; j < c.row.terms; ++j) r[static_cast<size_t>(c.row.body[j])] += c.row.w[j];
        return r;
      };
      std::vector<std::vector<double>> rows;
      for (int j = 0; j < nc; ++j) {
        const ContactLaw& c = sys_.contact(j);
        if (sys_.contact_mode(j) == ContactMode::stuck && c.lock == 0 && !c.joint && !c.kinematic) rows.push_back(dense(c));
      }
      audit::check_locked_slide(m_.contacts[static_cast<size_t>(k)].name, t, sys_.contact_mode(k), 0.0, rows, dense(law));
    }
  }
  // Gap links and ropes.
  for (int l = 0; l < static_cast<int>(m_.links.size()); ++l) {
    const LinkLaw& law = sys_.link(l);
    if (!law.gap) continue;
    const LinkLaw::Kinematics s = sys_.link_kinematics(l, y);
    audit::LinkValues x;
    x.mode = sys_.gap_mode(l);
    x.delta = s.delta, x.rate = s.rate, x.qa = law.drum(y);
    x.F = sys_.link_load(l, y);
    const double qs = (law.a >= 0 ? std::abs(y[law.a] * law.inv_ratio) : 0.0) + (law.b >= 0 ? std::abs(y[law.b]) : 0.0);
    x.resolution = m_.simulation.atol + m_.simulation.rtol * qs;
    audit::check_link(law, m_.links[static_cast<size_t>(l)].name, t, x);
  }
  // Lossy gears: the torques the engine solves in their modes.
  for (int g = 0; g < sys_.gear_count(); ++g) {
    const LossyGearLaw::Torques T = sys_.gear_torques(g, t, y);
    double Fa = 0.0, Fb = 0.0;
    sys_.gear_loads(g, t, y, &Fa, &Fb);
    const LossyGearLaw& k = sys_.lossy_gear(g);
    // v_a's resolution: the integrator's, and a prescribed side's speed within 1e-6 of its signal's
    // scale — the integral of the signal's slope, which the engine itself takes as the signal within
    // that bound (PrescribedMotionLaw::snapped_velocity; the gear's mode is decided on the signal):
    // worm-hoist-s-curve.yaml's motor state reads −3.2e-5 rad/s at 4.99955 s where its signal
    // 150 (1 − c)² (1 + 2c) is +9.1e-5 (8e-7 of its scale 150 rad/s at the default rtol 1e-8).
    double res = m_.simulation.atol + m_.simulation.rtol * std::abs(v[k.a]);
    for (int j = 0; j < sys_.motion_count(); ++j) {
      const PrescribedMotionLaw& mo = sys_.motion(j);
      if (mo.body == k.a) res += 1e-6 * mo.speed_scale;
      if (mo.body == k.b) res += 1e-6 * std::abs(k.i) * mo.speed_scale;
    }
    double scale = std::abs(Fa) + std::abs(Fb);
    if (const int tn = sys_.gear_train_of(g); tn >= 0) {
      // A gear of a two-stage train: X and Y come out of the train's solve, their rounding that of
      // every load on the train, Σ |ρ_j F_j| in its first body's coordinate, / |ρ_a| in the gear's
      // (the engine's side functions read that allowance: analysis/drive_system.cpp).
      const GearTrain& tr = sys_.gear_train(tn);
      double sum = 0.0;
      for (int h : tr.gears) {
        double Fha = 0.0, Fhb = 0.0;
        sys_.gear_loads(h, t, y, &Fha, &Fhb);
        const LossyGearLaw& kh = sys_.lossy_gear(h);
        sum += std::abs(tr.rho_of(kh.a) * Fha) + std::abs(tr.rho_of(kh.b) * Fhb);
      }
      scale += sum / std::abs(tr.rho_of(k.a));
    }
    audit::check_gear_loss(m_.lossy_gears[static_cast<size_t>(g)].name, t, T.X, T.Y, v[k.a], scale, res);
  }
  // Elements behind the interface: each checks its own law's invariants (Element::violated).
  for (int d = 0; d < sys_.drive_count(); ++d) {
    const Element& k = sys_.drive(d);
    const ElementMotion b = sys_.drive_motion_at(d, t, y);
    double M[ElementMotion::kMax] = {};
    const double* x = y + sys_.drive_offset(d);
    k.forces(t, b, x, sys_.drive_mode(d), M);
    double scale = 0.0;
    for (int p = 0; p < b.n; ++p) scale += std::abs(b.q[p]) + std::abs(b.v[p]);
    const std::string why = k.violated(t, b, x, sys_.drive_mode(d), M, k.heat_power(t, b, x, sys_.drive_mode(d)),
                                       m_.simulation.atol + m_.simulation.rtol * scale);
    if (!why.empty()) {
      const size_t bar = why.find('|');
      throw AuditError(m_.drives[static_cast<size_t>(d)].name, t, why.substr(0, bar),
                       bar == std::string::npos ? std::string() : why.substr(bar + 1));
    }
  }
  // The energy books.
  if (sys_.energy_books()) {
    const auto e = static_cast<size_t>(sys_.energy_index());
    audit::EnergyValues b;
    b.work = y[e], b.friction = y[e + 1], b.damping = y[e + 2];
    b.kinetic = sys_.kinetic_energy(y), b.kinetic_start = E_.kinetic_start;
    b.elastic = sys_.elastic_energy(y), b.elastic_start = E_.elastic_start;
    b.discrete = release_loss_ + E_.impact_loss + E_.released_kinetic;
    audit::check_energy(t, b, tol_E_, E_max_, abs_E_);
  }
}

}  // namespace machdyn
