#include "machdyn/analysis/crane.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <Eigen/Core>
#include <fmt/format.h>
#include "common/constants.hpp"

#include "machdyn/analysis/crane_standard.hpp"
#include "machdyn/analysis/equilibrium.hpp"
#include "machdyn/analysis/static_loads.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/elements/linear_model.hpp"
#include "machdyn/elements/link.hpp"
#include "machdyn/elements/lossy_gear.hpp"
#include "machdyn/model/element.hpp"
#include "machdyn/model/sheaves.hpp"

namespace machdyn {
namespace {


[[noreturn]] void case_error(const Model& m, const std::string& element, const std::string& message) {
  throw InputError(m.where(element), "crane: " + message);
}

/// A warning when the extreme `what` of a case's run lies at its end, t = t_end: the run may have
/// stopped before the case's extreme (a longer run may find a more extreme value). Empty otherwise.
std::string end_warning(const Model& m, double t, const std::string& what) {
  const double T = m.simulation.t_end;
  if (!(t >= T - 1e-9 * std::max(1.0, T))) return "";
  return fmt::format("the {} lies at the end of the run (t = t_end = {:.6g} s): the case may not have reached its "
                     "extreme; raise simulation.t_end", what, T);
}

/// The rigid motion of the free group of `body` through the links of `m` other than those `skip`
/// says and through its lossy gears (column of rigid_motions), or an empty vector when the body is
/// tied to the ground. A lossy gear keeps the ratio of an ideal one, v_a = i v_b, in every mode
/// (its row, elements/lossy_gear.hpp add_linear): the group runs through it as through a gear.
/// With `prescribed_free` a body with prescribed motion joins the walk as a free body (the φ2 case
/// sets the motion of such a hoist drive itself); otherwise it is a support, as in rigid_motions.
template <class Skip>
Eigen::VectorXd group_motion(const Model& m, int body, Skip&& skip, bool prescribed_free = false) {
  Model tied;
  tied.bodies = m.bodies;
  if (prescribed_free)
    for (Body& b : tied.bodies) b.motion = MotionKind::free;
  for (const Link& l : m.links)
    if (!skip(l)) tied.links.push_back(l);
  LinearModel gears(m.dof());
  for (const LossyGear& g : m.lossy_gears) LossyGearLaw::of(g).add_linear(gears);
  const Eigen::MatrixXd R = rigid_motions(tied, gears.G);
  for (Eigen::Index k = 0; k < R.cols(); ++k)
    if (R(body, k) != 0.0) return R.col(k);
  return {};
}

/// The load of link `k` on the output grid divided by `reference`: the row's time history.
void set_history(const Model& m, const SimulationResult& res, int k, double reference, CraneFactorRow& r) {
  const std::string name = m.links[static_cast<size_t>(k)].name + ".load_";
  for (size_t c = 0; c < res.column_names.size(); ++c)
    if (res.column_names[c].rfind(name, 0) == 0 && !res.columns.empty()) {
      r.t = res.columns[0];
      r.history = res.columns[c];
      for (double& x : r.history) x /= reference;
      return;
    }
}

const Body& load_body(const Model& m) { return m.bodies[static_cast<size_t>(m.crane.load)]; }
double load_weight(const Model& m) { return load_body(m).inertia * m.gravity; }

/// The φ2 case's run `s` (the rope's summary) must lift the load: a rope that never carries its
/// weight m g before t_end leaves it on the ground, and φ2 is not reached — an input error (located
/// at the load) instead of a factor below 1 with a "safe" margin. `which` names the case.
void require_lift_off(const Model& m, const LinkSummary& s, const std::string& which) {
  const double W = load_weight(m);
  if (s.max >= W * (1.0 - 1e-9)) return;
  case_error(m, load_body(m).name,
             fmt::format("the phi2 case ({}) does not lift the load '{}' off the ground before t_end = {:.6g} s: the "
                         "rope's largest force {:.6g} N stays below the weight m g = {:.6g} N, so phi2 is not reached; "
                         "raise simulation.t_end (or check the hoist drive)",
                         which, load_body(m).name, m.simulation.t_end, s.max, W));
}

CraneFactorRow phi2_row(const Model& m) {
  using namespace crane;
  const CraneSpec& c = m.crane;
  const auto hc = static_cast<HoistingClass>(c.hoisting_class);
  const auto hd = static_cast<HoistDriveClass>(c.drive_class);
  const double vh = characteristic_hoisting_speed(hd, c.hoist_speed, c.creep_speed);
  CraneFactorRow r;
  r.factor = "phi2";
  r.case_name = fmt::format("hoisting a grounded load, {}/{}, vh = {:.4g} m/s", to_string(hc), to_string(hd), vh);
  // φ2,min depends on both classes (HC1…HC4 for HD1, HD2, HD4; 1.05 in every class for HD3, HD5): name both.
  r.clause = fmt::format("EN 13001-2 phi2 = phi2,min + beta2 vh ({}: beta2 = {:.2f} s/m; {}/{}: phi2,min = {:.2f}{})",
                         to_string(hc), beta2(hc), to_string(hc), to_string(hd), phi2_min(hc, hd),
                         hd == HoistDriveClass::HD3 || hd == HoistDriveClass::HD5 ? ", the same in every class" : "");
  if ((hd == HoistDriveClass::HD2 || hd == HoistDriveClass::HD3) && !(c.creep_speed > 0.0)) {
    // Neither number exists without the creep speed: the standard's φ2 is φ2,min + β2 vh,CS too.
    r.case_name = fmt::format("hoisting a grounded load, {}/{}, vh = creep speed (not given)", to_string(hc),
                              to_string(hd));
    r.simulated = r.margin = r.standard_lo = r.standard_hi = kNaN;
    r.note = fmt::format("{} hoists at the creep speed: give 'creep_speed' in the crane section (the standard's phi2 "
                         "= phi2,min + beta2 vh,CS needs it too)", to_string(hd));
    return r;
  }
  r.standard_lo = r.standard_hi = phi2(hc, hd, vh);
  r.vh = vh;
  // HD5 (vh = 0): the stepless drive starts from zero speed — the model's own drive from its own start.
  const SimulationResult res = simulate(phi2_case_model(m, vh));
  const LinkSummary& s = res.links[static_cast<size_t>(c.rope)];
  const double W = load_weight(m);
  require_lift_off(m, s, fmt::format("{}/{}, {}", to_string(hc), to_string(hd),
                                     vh > 0.0 ? fmt::format("vh = {:.4g} m/s", vh) : std::string("the model's own drive")));
  r.simulated = s.max / W;
  r.margin = r.standard_hi - r.simulated;
  r.extreme = s.max, r.t_extreme = s.t_max, r.reference = W;
  r.warning = end_warning(m, s.t_max, "rope's largest force");
  set_history(m, res, c.rope, W, r);
  r.note = fmt::format("max rope force {:.6g} N at t = {:.6g} s; weight m g = {:.6g} N{}", s.max, s.t_max, W,
                       vh > 0.0 ? "" : "; the model's own drive (HD5: it starts from zero speed)");
  return r;
}

CraneFactorRow phi3_row(const Model& m) {
  using namespace crane;
  const CraneSpec& c = m.crane;
  const ReleaseKind kind = c.rapid_release ? ReleaseKind::rapid : ReleaseKind::slow;
  const double mass = load_body(m).inertia;
  CraneFactorRow r;
  r.factor = "phi3";
  r.case_name = fmt::format("sudden release of {:.6g} kg of {:.6g} kg ({})", c.release_mass, mass,
                            c.rapid_release ? "rapid" : "slow");
  r.standard_lo = r.standard_hi = phi3(c.release_mass, mass, kind);
  r.clause = fmt::format("EN 13001-2 phi3 = 1 - (dm/m)(1 + beta3), beta3 = {:.1f} ({} release)", beta3(kind),
                         c.rapid_release ? "rapid" : "slow");
  if (c.release_time < 0.0) {  // at once from the hanging equilibrium
    const SimulationResult res = simulate(phi3_case_model(m, c.release_mass));
    const LinkSummary& s = res.links[static_cast<size_t>(c.rope)];
    r.simulated = s.min / load_weight(m);
    r.margin = r.simulated - r.standard_lo;
    r.extreme = s.min, r.t_extreme = s.t_min, r.reference = load_weight(m);
    r.warning = end_warning(m, s.t_min, "rope's smallest force");
    set_history(m, res, c.rope, load_weight(m), r);
    r.note = fmt::format("min rope force {:.6g} N at t = {:.6g} s after the release; m g = {:.6g} N", s.min, s.t_min,
                         load_weight(m));
    return r;
  }
  // Released at t_r of a run: the rope's minimum from t_r on (before it the rope may be slack).
  r.case_name += fmt::format(" at t = {:.6g} s {}", c.release_time, c.release_hoisting ? "while hoisting" : "hanging");
  SimulateOptions opt;
  opt.extremes_from = c.release_time;
  const SimulationResult res = simulate(phi3_release_case_model(m, c.release_mass, c.release_time), opt);
  const LinkSummary& s = res.links[static_cast<size_t>(c.rope)];
  r.simulated = s.min / load_weight(m);
  r.margin = r.simulated - r.standard_lo;
  r.extreme = s.min, r.t_extreme = s.t_min, r.reference = load_weight(m);
  r.warning = end_warning(m, s.t_min, "rope's smallest force");
  set_history(m, res, c.rope, load_weight(m), r);
  r.note = fmt::format("min rope force {:.6g} N at t = {:.6g} s, after the release at {:.6g} s; m g = {:.6g} N", s.min,
                       s.t_min, c.release_time, load_weight(m));
  return r;
}

void phi5_rows(const Model& m, const SimulationResult& res, CraneReport& out) {
  using namespace crane;
  const auto change = static_cast<DriveForceChange>(m.crane.force_change);
  const Range range = phi5_range(change);
  for (int k : m.crane.drive_links) {
    const LinkSummary& s = res.links[static_cast<size_t>(k)];
    CraneFactorRow r;
    r.factor = "phi5";
    r.case_name = fmt::format("drive link {} ({} force changes)", m.links[static_cast<size_t>(k)].name, to_string(change));
    r.simulated = s.dynamic_factor;
    r.standard_lo = range.lo;
    r.standard_hi = range.hi;
    r.clause = fmt::format("EN 13001-2 phi5, {} force changes (one source)", to_string(change));
    r.margin = r.standard_hi - r.simulated;
    r.extreme = s.peak, r.t_extreme = s.t_peak, r.reference = s.static_load;
    r.warning = end_warning(m, s.t_peak, "peak");
    if (std::isfinite(s.dynamic_factor)) set_history(m, res, k, s.static_load, r);
    r.note = fmt::format("peak {:.6g} {} at t = {:.6g} s; quasi-static load there {:.6g}", s.peak,
                         link_load_unit(m, m.links[static_cast<size_t>(k)]), s.t_peak, s.static_load);
    out.rows.push_back(r);
  }
}

/// The velocities of the bodies of `m` at time t of its run: the model's own start at t = 0, else
/// the end state of the same run stopped at t (exact, not interpolated on the output grid).
std::vector<double> velocities_at(const Model& m, double t) {
  std::vector<double> v;
  for (const Body& b : m.bodies) v.push_back(b.v0);
  if (!(t > 0.0)) return v;
  Model upto = m;
  upto.simulation.t_end = t;
  const SimulationResult res = simulate(upto);
  for (size_t i = 0; i < m.bodies.size(); ++i) {
    const std::string name = m.bodies[i].name + ".velocity_";
    for (size_t c = 0; c < res.column_names.size() && c < res.columns.size(); ++c)
      if (res.column_names[c].rfind(name, 0) == 0 && !res.columns[c].empty()) v[i] = res.columns[c].back();
  }
  return v;
}

/// The rigid-body reference of buffer link k: the free group of its body (through springs and gears;
/// not through ropes or other buffers) lumped into one mass M = Σ m_i (r_i / r_b)², moving at the
/// group's momentum speed at the first contact with the buffer (`res`: the model's own run; its
/// first "gap_closed" event of the buffer), into the same buffer, without other loads. Returns its
/// peak force; sets the row's contact speed and time and says in `note` how the group was counted.
double rigid_buffer_force(const Model& m, const SimulationResult& res, int k, CraneFactorRow& r, std::string* note) {
  const Link& l = m.links[static_cast<size_t>(k)];
  const int body = l.a >= 0 ? l.a : l.b;
  const Eigen::VectorXd R = group_motion(m, body, [](const Link& x) { return x.buffer || x.tension_only; });
  if (R.size() == 0) {
    *note = "the buffer's body is tied to the ground by a spring: no rigid-body reference";
    return kNaN;
  }
  double t_c = 0.0;  // first contact: the buffer's first closing (none: in contact from the start)
  for (const ModeEvent& e : res.hybrid.events)
    if (e.element == l.name && e.kind == "gap_closed") {
      t_c = e.t;
      break;
    }
  const std::vector<double> v = velocities_at(m, t_c);
  const double rb = R(body);
  double RMR = 0.0, RMv = 0.0;
  std::string lumped;
  for (int i = 0; i < m.dof(); ++i) {
    const Body& b = m.bodies[static_cast<size_t>(i)];
    RMR += R(i) * b.inertia * R(i);
    RMv += R(i) * b.inertia * v[static_cast<size_t>(i)];
    if (R(i) != 0.0)
      lumped += fmt::format("{}{} {:.6g}", lumped.empty() ? "" : " + ", b.name, b.inertia * (R(i) / rb) * (R(i) / rb));
  }
  Model rigid;
  rigid.name = m.name + " (rigid)";
  rigid.source = m.source;
  rigid.simulation = m.simulation;
  rigid.simulation.initial = InitialState::given;
  Body b = m.bodies[static_cast<size_t>(body)];
  b.inertia = RMR / (rb * rb);  // M = Σ m_i (r_i / r_b)²
  b.v0 = rb * RMv / RMR;        // the group's momentum speed at the buffer's body, at first contact
  b.vertical = 0;
  b.motion = MotionKind::free;
  rigid.bodies.push_back(b);
  rigid.index_bodies();
  Link lb = l;
  lb.a = l.a >= 0 ? 0 : kGround;
  lb.b = l.b >= 0 ? 0 : kGround;
  rigid.links.push_back(lb);
  // It starts where the body starts and reaches the buffer (its flank at q = ±gap) at its constant
  // speed: the run lasts that long plus the model's own duration for the compression.
  const double flank = l.a >= 0 ? l.gap : -l.gap;
  if (b.v0 != 0.0) rigid.simulation.t_end += std::abs(flank - b.q0) / std::abs(b.v0);
  const SimulationResult rr = simulate(rigid);
  r.contact_speed = b.v0;
  r.t_contact = t_c;
  *note = fmt::format("rigid body {:.6g} kg ({}; lumped rigidly through springs and gears, bodies behind ropes and "
                      "friction contacts not counted) at {:.6g} {}, the group's momentum speed at first contact, "
                      "t = {:.6g} s", b.inertia, lumped, b.v0, velocity_unit(b.kind), t_c);
  return rr.links[0].max;
}

/// A column of the run by its name's start ("trolley.position_"), or null.
const std::vector<double>* column_starting_with(const SimulationResult& res, const std::string& start) {
  for (size_t c = 0; c < res.column_names.size() && c < res.columns.size(); ++c)
    if (res.column_names[c].rfind(start, 0) == 0) return &res.columns[c];
  return nullptr;
}

/// ξb of buffer link k (EN 13001-2: the energy absorbed over the stroke reached, ∫F ds, over the
/// rectangle F_max s_max) and how it was found. s_max is the largest stroke of the run. Elastic
/// characteristics (linear, progressive, table) give ξb from their force–stroke law F_e over
/// [0, s_max] (linear 1/2, progressive 1/(n + 1), a table exact per piece); the hydraulic buffer's
/// force depends on the speed, so its ξb comes from the run's own force–stroke curve (the output
/// samples of the compression, up to s_max). 1/2 when the buffer was not reached.
double buffer_xi(const Model& m, const SimulationResult& res, int k, std::string* how, double* stroke) {
  const Link& l = m.links[static_cast<size_t>(k)];
  const int body = l.a >= 0 ? l.a : l.b;
  const std::vector<double>* q = column_starting_with(res, m.bodies[static_cast<size_t>(body)].name + ".position_");
  const std::vector<double>* F = column_starting_with(res, l.name + ".load_");
  *how = "xi_b = 1/2: the buffer was not reached";
  if (!q || !F || q->empty()) return 0.5;
  std::vector<double> e(q->size());  // the stroke e = δ − δ₊ (model/model.hpp: Link::buffer)
  for (size_t j = 0; j < q->size(); ++j) e[j] = (l.a >= 0 ? (*q)[j] : -(*q)[j]) - l.gap;
  const size_t jmax = static_cast<size_t>(std::max_element(e.begin(), e.end()) - e.begin());
  const double s_max = e[jmax];
  if (!(s_max > 0.0)) return 0.5;
  *stroke = s_max;
  const LinkLaw law = LinkLaw::of(m, l);
  std::vector<double> s{0.0}, f{0.0};
  if (l.characteristic == Link::Characteristic::hydraulic) {
    for (size_t j = 0; j <= jmax; ++j)
      if (e[j] > s.back()) s.push_back(e[j]), f.push_back(std::max((*F)[j], 0.0));
    // The force jumps to k v² at first contact: F(0) from the first two samples, extrapolated.
    if (s.size() >= 3) f[0] = std::max(f[1] - (f[2] - f[1]) / (s[2] - s[1]) * s[1], 0.0);
  } else {
    if (l.characteristic == Link::Characteristic::table)  // the table's points below s_max, then s_max
      for (size_t j = 1; j < l.table_stroke.size() && l.table_stroke[j] < s_max; ++j)
        s.push_back(l.table_stroke[j]), f.push_back(l.table_force[j]);
    if (l.characteristic == Link::Characteristic::progressive) {  // ∫ exact: V(s_max) over F(s_max) s_max
      const double xi = law.shaped_energy(s_max) / (law.shaped_force(s_max) * s_max);
      *how = fmt::format("xi_b = {:.4g} = 1/(n + 1) of the progressive characteristic (n = {:.4g}) over the stroke "
                         "{:.4g}", xi, l.exponent, s_max);
      return xi;
    }
    s.push_back(s_max), f.push_back(law.spring_load(s_max));
  }
  if (s.size() < 2) return 0.5;
  const double xi = crane::buffer_energy_ratio(s, f);
  if (l.characteristic == Link::Characteristic::hydraulic)
    *how = fmt::format("xi_b = {:.4g} from the run's force-stroke curve (hydraulic buffer, {} samples up to the "
                       "stroke {:.4g})", xi, s.size(), s_max);
  else
    *how = fmt::format("xi_b = {:.4g} of the {} characteristic over the stroke {:.4g}", xi,
                       l.characteristic == Link::Characteristic::table ? "table" : "linear", s_max);
  return xi;
}

void phi7_rows(const Model& m, const SimulationResult& res, CraneReport& out) {
  for (int k : m.crane.buffers) {
    const Link& l = m.links[static_cast<size_t>(k)];
    const LinkSummary& s = res.links[static_cast<size_t>(k)];
    CraneFactorRow r;
    r.factor = "phi7";
    r.case_name = fmt::format("buffer {}", l.name);
    if (!(s.max > 0.0))
      case_error(m, l.name, fmt::format("the phi7 case: the run does not reach the buffer '{}' before t_end = {:.6g} s "
                                        "(its force stays 0), so phi7 is not reached; raise simulation.t_end or start "
                                        "nearer the buffer", l.name, m.simulation.t_end));
    std::string rigid_note;
    const double F_rigid = rigid_buffer_force(m, res, k, r, &rigid_note);
    std::string how;
    double s_max = 0.0;
    const double xi = buffer_xi(m, res, k, &how, &s_max);
    r.standard_lo = r.standard_hi = crane::phi7(xi);
    r.clause = fmt::format("EN 13001-2 phi7 = 1.25 (xi_b <= 0.5), 1.25 + 0.7 (xi_b - 0.5) above; {}", how);
    r.simulated = s.max / F_rigid;
    r.margin = r.standard_hi - r.simulated;
    r.extreme = s.max, r.t_extreme = s.t_max, r.reference = F_rigid, r.xi_b = xi, r.stroke = s_max;
    r.warning = end_warning(m, s.t_max, "peak buffer force");
    if (std::isfinite(F_rigid)) set_history(m, res, k, F_rigid, r);
    r.note = fmt::format("peak buffer force {:.6g} N at t = {:.6g} s; rigid-body force {:.6g} N ({}); {}", s.max, s.t_max,
                         F_rigid, rigid_note, how);
    out.rows.push_back(r);
  }
}

}  // namespace

Model phi2_case_model(const Model& m, double vh) {
  const CraneSpec& c = m.crane;
  if (c.rope < 0) case_error(m, m.name, "the phi2 case needs 'load' and 'rope'");
  const Link& rope = m.links[static_cast<size_t>(c.rope)];
  if (rope.a < 0) case_error(m, rope.name, fmt::format("the rope '{}' hangs from the ground: no hoist drive to start", rope.name));
  bool on_ground = false;
  for (const auto& s : m.contacts)
    on_ground = on_ground || (s.stop && s.a == c.load && s.lock == -1 && m.bodies[static_cast<size_t>(c.load)].q0 == s.stop_position);
  if (!on_ground)
    case_error(m, load_body(m).name, fmt::format("the phi2 case lifts the load '{}' from the ground: give it a lower stop "
                                                 "(stops: {{ground: {{body: {}, min: X}}}}) and start it there",
                                                 load_body(m).name, load_body(m).name));
  // vh = 0 (HD5, the stepless drive starting from zero speed): the model's own drive from its own start.
  if (vh == 0.0) return m;
  // The hoist drive: the free group behind the rope's first end (a body with prescribed motion in it
  // counts as part of the group: its motion is set below). Its rope end moves at vh:
  // δ̇ = v_a / i − v_load = vh with v = R β  ⇒  β = vh i / R_a.
  const int rope_index = c.rope;
  const Eigen::VectorXd R = group_motion(
      m, rope.a, [&](const Link& l) { return &l == &m.links[static_cast<size_t>(rope_index)]; }, true);
  if (R.size() == 0)
    case_error(m, rope.name, fmt::format("the hoist drive behind the rope '{}' is tied to the ground by a spring: it cannot "
                                         "hoist", rope.name));
  const double beta = vh * rope.ratio / R(rope.a);
  Model out = m;
  out.simulation.initial = InitialState::given;
  for (int i = 0; i < m.dof(); ++i) {
    if (R(i) == 0.0) continue;
    Body& b = out.bodies[static_cast<size_t>(i)];
    b.v0 = R(i) * beta;
    // A prescribed drive (`motion:`, the rigid drive of the standard's own assumption) runs at the
    // class's speed from the start: its motion becomes that constant speed.
    if (b.motion != MotionKind::free) b.motion = MotionKind::speed, b.motion_signal = Signal::constant(b.v0);
  }
  // A speed-controlled drive of the hoist runs at that steady speed: its reference holds it (its
  // own ramp would start from rest and brake the drive that the case starts at vh).
  for (auto& d : out.drives)  // its own speed ω_X = Drive::own over the bodies' speeds R β
    if (const double w = d.own(R.data()); w != 0.0)
      if (auto held = d.law->at_steady_speed(w * beta)) d.law = std::move(held);
  return out;
}

namespace {

/// The φ3 case's start: the load hanging at rest in static equilibrium, its stop removed, the rope's
/// first body held by a brake that never slips.
Model hanging_start(const Model& m, double released_mass) {
  const CraneSpec& c = m.crane;
  if (c.rope < 0) case_error(m, m.name, "the phi3 case needs 'load' and 'rope'");
  const Body& load = load_body(m);
  if (!(released_mass > 0.0 && released_mass < load.inertia))
    case_error(m, load.name, fmt::format("the released mass {} kg must lie between 0 and the load's mass {} kg",
                                         released_mass, load.inertia));
  // The load hangs: no ground under it, at rest, the rope on its flank (δ = δ₊) to start the search.
  Model hang = m;
  hang.releases.clear();  // the case's release is its own: the model's `releases:` do not act in it
  hang.simulation.initial = InitialState::equilibrium;
  std::erase_if(hang.contacts, [&](const FrictionContact& s) { return s.stop && s.a == c.load; });
  for (auto& b : hang.bodies) b.v0 = 0.0;
  const Link& rope = m.links[static_cast<size_t>(c.rope)];
  if (rope.a >= 0) {  // the hoist is stopped: a holding brake (never slipping) on the rope's first body
    FrictionContact hold;
    hold.name = "crane_holding_brake";
    hold.brake = true;
    hold.a = rope_drum(m, rope);  // the drum, also behind the rope's sheave losses (model/sheaves.hpp)
    hold.b = kGround;
    hold.static_limit = 1e30;
    hold.kinetic = {1e30};
    hang.contacts.push_back(hold);
  }
  const double qa = rope.a >= 0 ? hang.bodies[static_cast<size_t>(rope.a)].q0 : 0.0;
  hang.bodies[static_cast<size_t>(c.load)].q0 = qa / rope.ratio - rope.gap;
  return with_equilibrium_start(hang);
}

}  // namespace

Model phi3_case_model(const Model& m, double released_mass) {
  const CraneSpec& c = m.crane;
  Model out = hanging_start(m, released_mass);
  // At t = 0 the load loses Δm: its mass and weight drop, position and velocity are continuous.
  Body& b = out.bodies[static_cast<size_t>(c.load)];
  b.inertia -= released_mass;
  for (Load& ld : out.loads)
    if (ld.name == b.name + ".weight") {
      ld.value = -b.vertical * b.inertia * out.gravity;
      ld.signal = Signal::constant(ld.value);
    }
  return out;
}

Model phi3_release_case_model(const Model& m, double released_mass, double release_time) {
  const CraneSpec& c = m.crane;
  if (!(release_time < m.simulation.t_end))
    case_error(m, m.name, fmt::format("the phi3 release time {} s is not before the end of the run, t_end = {} s",
                                      release_time, m.simulation.t_end));
  Model out = c.release_hoisting ? phi2_case_model(m, c.hoist_speed) : hanging_start(m, released_mass);
  out.releases.clear();  // the case's release is its own: the model's `releases:` do not act in it
  const Body& load = out.bodies[static_cast<size_t>(c.load)];
  if (!(released_mass > 0.0 && released_mass < load.inertia))
    case_error(m, load.name, fmt::format("the released mass {} kg must lie between 0 and the load's mass {} kg",
                                         released_mass, load.inertia));
  out.releases.push_back(body_release(out, "crane_release", c.load, released_mass, release_time));
  return out;
}

std::vector<Phi2Point> phi2_sweep(const Model& m, const std::vector<double>& speeds) {
  const auto hc = static_cast<crane::HoistingClass>(m.crane.hoisting_class);
  const auto hd = static_cast<crane::HoistDriveClass>(m.crane.drive_class);
  if (m.crane.rope < 0) case_error(m, m.name, "the phi2 sweep needs 'load' and 'rope' in the 'crane:' section");
  std::vector<Phi2Point> out;
  for (double vh : speeds) {
    if (!(vh > 0.0)) throw std::invalid_argument(fmt::format("a hoisting speed of the phi2 sweep must be > 0, got {}", vh));
    const SimulationResult res = simulate(phi2_case_model(m, vh));
    const LinkSummary& s = res.links[static_cast<size_t>(m.crane.rope)];
    require_lift_off(m, s, fmt::format("sweep point vh = {:.4g} m/s", vh));
    out.push_back({vh, s.max / load_weight(m), crane::phi2(hc, hd, vh)});
  }
  return out;
}

CraneReport crane_analysis(const Model& m) { return crane_analysis(m, {}); }

namespace {

CraneReport crane_cases(const Model& m, const std::vector<int>& drive_classes);

}  // namespace

CraneReport crane_analysis(const Model& m, const std::vector<int>& drive_classes) {
  if (!m.crane.given)
    throw InputError(Location{m.source, 0, 0},
                     m.load_case.empty() ? std::string("the model has no 'crane:' section (docs/crane-factors.md)")
                                         : fmt::format("load case '{}': the model has no 'crane:' section (the case "
                                                       "drops it, or the file has none; docs/crane-factors.md)",
                                                       m.load_case));
  for (int k : drive_classes)
    if (k < 1 || k > 5) throw std::invalid_argument(fmt::format("hoist drive class HD{} does not exist (HD1…HD5)", k));
  if (m.load_case.empty()) return crane_cases(m, drive_classes);
  try {  // every error of a load case's crane analysis names the case
    return crane_cases(m, drive_classes);
  } catch (const InputError& e) {
    std::vector<Diagnostic> named = e.diagnostics();
    for (Diagnostic& d : named) d.message = fmt::format("load case '{}': {}", m.load_case, d.message);
    throw InputError(std::move(named));
  }
}

namespace {

CraneReport crane_cases(const Model& m, const std::vector<int>& drive_classes) {
  CraneReport out;
  out.model = m.name;
  out.load_case = m.load_case;
  const CraneSpec& c = m.crane;
  if (c.rope >= 0 && c.hoist_speed > 0.0) {
    if (drive_classes.empty()) out.rows.push_back(phi2_row(m));
    for (int k : drive_classes) {
      Model mk = m;
      mk.crane.drive_class = k;
      out.rows.push_back(phi2_row(mk));
    }
  }
  if (c.rope >= 0 && c.release_mass > 0.0) out.rows.push_back(phi3_row(m));
  if (!c.drive_links.empty() || !c.buffers.empty()) {
    const SimulationResult res = simulate(m);  // the model's own run
    phi5_rows(m, res, out);
    phi7_rows(m, res, out);
  }
  return out;
}

}  // namespace

}  // namespace machdyn
