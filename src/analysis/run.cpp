// The one run of every model: the drive system (analysis/drive_system.hpp) as an event system of the
// one driver (solve/driver.hpp) — its event functions (gaps, contacts, machines' velocity jumps) and
// breakpoints, the decision of the new modes of all elements together at an event — and the
// observers (outputs, peaks, quasi-static loads, slip phases, energy books, progress).
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/analysis/extra_outputs.hpp"
#include "machdyn/analysis/equilibrium.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <tuple>
#include <memory>
#include <utility>
#include <fmt/format.h>

#include "machdyn/analysis/audit.hpp"
#include "machdyn/analysis/contact_decision.hpp"
#include "machdyn/analysis/drive_system.hpp"
#include "machdyn/analysis/gear_clutch.hpp"
#include "machdyn/analysis/gear_lock.hpp"
#include "machdyn/analysis/machine_outputs.hpp"
#include "machdyn/analysis/load_history.hpp"
#include "machdyn/analysis/peak_tracker.hpp"
#include "machdyn/analysis/static_loads.hpp"
#include "machdyn/analysis/sway_summary.hpp"
#include "machdyn/model/reeving.hpp"
#include "analysis/heat.hpp"
#include "analysis/impact.hpp"
#include "analysis/machine_jumps.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/units.hpp"
#include "machdyn/model/signal_sampling.hpp"
#include "machdyn/solve/driver.hpp"
#include "machdyn/solve/roots.hpp"

namespace machdyn {
namespace {

class DriveRun final : public EventSystem, public StepObserver, public PeakSignals {
 public:
  DriveRun(const Model& m, const SimulateOptions& opt, SimulationResult& out, const OutputSelection& extra = {})
      : m_(m), opt_(opt), extra_(extra), out_(out), sys_(m, m.is_hybrid() || opt.event_driven), jumps_(m, sys_), heat_(m, sys_), n_(m.dof()),
        N_(sys_.size()), nl_(static_cast<int>(m.links.size())), nc_(static_cast<int>(m.contacts.size())),
        nd_(static_cast<int>(m.drives.size())), ng_(static_cast<int>(m.lossy_gears.size())), peaks_(sys_.size(), *this) {
    y_.assign(static_cast<size_t>(N_), 0.0);
    acc_.assign(static_cast<size_t>(n_), 0.0);
    fc_.assign(static_cast<size_t>(nc_), 0.0);
    open_phase_.assign(static_cast<size_t>(nc_), -1);
    phase_window_.assign(static_cast<size_t>(nc_), -1);
    for (int k = 0; k < nc_; ++k) was_released_.push_back(m_.contacts[static_cast<size_t>(k)].released(0.0));
    switches_.resize(static_cast<size_t>(nl_ + nc_ + nd_ + ng_));
    impact_times_.resize(static_cast<size_t>(nc_));
    for (int k = 0; k < nc_; ++k) impact_ties_.push_back(!gear_owned(k));
    at_max_.resize(static_cast<size_t>(nl_));
    at_min_.resize(static_cast<size_t>(nl_));
    for (size_t k = 0; k < m.loads.size(); ++k)
      if (m.loads[k].kind != LoadKind::constant) varying_.push_back(k);
    for (int i = 0; i < n_; ++i)
      if (m.bodies[static_cast<size_t>(i)].machine) machine_bodies_.push_back(i);
    jump_events_ = jumps_.count() > 0;
    has_events_ = nc_ > 0 || ng_ > 0 || jump_events_;
    for (int l = 0; l < nl_; ++l)
      if (sys_.link(l).gap) flank_links_.push_back(l);
    has_events_ = has_events_ || !flank_links_.empty();
    for (int d = 0; d < nd_; ++d) has_events_ = has_events_ || sys_.drive(d).has_events();
    on_new_max_ = [this](int l, bool is_max, double t, const double* y) {
      ingredients(t, y, (is_max ? at_max_ : at_min_)[static_cast<size_t>(l)]);
    };
    setup_columns();
  }

  void run() {
    const auto start = std::chrono::steady_clock::now();
    const auto& s = m_.simulation;
    out_.hybrid.active = sys_.energy_books();
    out_.hybrid.breakpoints = m_.breakpoints(s.t_end);
    next_breakpoint(0.0);
    const Method method = choose_method(m_, &out_.method_reason);
    if (method == Method::dopri5) peaks_.set_dense_degree(4);  // its dense output (solve/stepper.hpp)
    sys_.initial_state(y_.data());
    jumps_.start(0.0, y_.data());
    apply_releases(0.0);  // a release at t = 0 acts at 0⁺: the start state is the full bodies'
    initial_modes();
    initial_events_ = static_cast<long>(out_.hybrid.events.size());
    auto& E = out_.hybrid.energy;
    if (sys_.energy_books()) {
      // The bodies' kinetic energy before a release at t = 0 (its part is in released_kinetic).
      E.kinetic_start = sys_.kinetic_energy(y_.data()) + E.released_kinetic;
      E.elastic_start = sys_.elastic_energy(y_.data());
    }
    // The invariant audit (analysis/audit.hpp): an observer only when asked for.
    if (opt_.check || audit_requested_by_environment()) {
      audit_ = std::make_unique<Audit>(m_, sys_, E, release_loss_);
      audit_->after_event(0.0, y_.data(), false);
    }
    // The sway summary of the spatial ropes (analysis/sway_summary.hpp): an observer of the output
    // rows, which the run visits for it even when it keeps no series.
    if (SwayObserver sway(m_); !sway.empty()) sway_ = std::make_unique<SwayObserver>(std::move(sway));
    observed_rows_ = audit_ || sway_;
    step_watch_ = audit_ || opt_.progress;
    row_fast_end_ = observed_rows_ ? 0 : row_cap_;
    StepperOptions so;
    so.rtol = s.rtol;
    so.atol = s.atol;
    so.max_steps = s.max_steps;
    // A stuck lossy gear holds its bodies at rest: the error control sees a constant state and would grow
    // the step across a start margin that dips below 0 and back within one step (a double sign change
    // the event check cannot see). The output step bounds the step while the model has lossy gears.
    if (ng_ > 0) so.h_max = s.dt_out;
    auto stepper = make_stepper(method, *this, so);
    Stepper& st = *stepper;
    DriveOptions drive;
    drive.dt_out = s.dt_out;
    drive.outputs = opt_.record_series || sway_;
    if (jumps_.count() > 0) drive.event_tol = 4e-16;  // jump positions of stepwise gears: to the last bits of t
    start_ = start;
    extremes_only_ = winding_links_.empty() && !(extra_.heat || heat_.any_thermal()) && !jumps_.samples_pieces() && !audit_;
    out_.stats = integrate(st, *this, 0.0, y_.data(), s.t_end, drive, *this);
    if (opt_.record_series)
      for (auto& col : out_.columns) col.resize(row_);
    if (audit_) {
      audit_->settle();
      audit::check_event_list(m_, out_);
    }
    std::copy(st.y(), st.y() + N_, y_.begin());
    // Close the books.
    for (int k = 0; k < nc_; ++k) close_phase(k, s.t_end);
    if (sys_.energy_books()) {
      E.kinetic_end = sys_.kinetic_energy(y_.data());
      E.elastic_end = sys_.elastic_energy(y_.data());
      const auto e = static_cast<size_t>(sys_.energy_index());
      E.source_work = y_[e];
      E.friction_loss = y_[e + 1];
      E.damping_loss = y_[e + 2];
      E.release_loss = release_loss_;
    }
    summarize_links();
    out_.machines = jumps_.reports();
    if (sway_) out_.sway = sway_->summaries();
    if (sys_.has_machines())  // I(q), ε, inertia moments, output points (analysis/machine_outputs.hpp)
      append_machine_outputs(
          m_, out_,
          [&](size_t row, const double*, double* acc) {
            std::copy_n(acc_rows_.begin() + static_cast<long>(row) * n_, n_, acc);
          });
    out_.stats.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report_progress(st, start, true);
  }

  // ---- the event system the driver integrates: the drive system in its current modes ----
  [[nodiscard]] int size() const override { return sys_.size(); }
  void rhs(double t, const double* y, double* dydt) override {
    // A step never crosses a breakpoint; one that ends on it sees the signals' left limits there (a
    // load, a brake's application or a surface that jumps at t_b has its old value on the whole
    // step): the stages of the step at its end (dopri5's c = 1, BDF's implicit t_n) used to take the
    // value after the jump, an error of O(h ΔF) in the state the next piece starts from — a brake
    // applied on a body at rest set it sliding at 1e-11 m/s, BDF's stops and rests came 1e-6 s off.
    if (t == bp_next_) [[unlikely]] return rhs_left_limit(t, y, dydt);  // out of line: no frame here
    last_t_ = t, last_y_ = y;  // the integrator's own buffer: where a failure was met (state_name)
    sys_.rhs(t, y, dydt);
  }
  __attribute__((noinline)) void rhs_left_limit(double t, const double* y, double* dydt) {
    t = std::nextafter(t, -std::numeric_limits<double>::infinity());
    last_t_ = t, last_y_ = y;
    sys_.rhs(t, y, dydt);
  }
  [[nodiscard]] bool has_jacobian() const override { return sys_.has_jacobian(); }
  void jacobian(double t, const double* y, Eigen::Ref<Eigen::MatrixXd> J) override { sys_.jacobian(t, y, J); }
  [[nodiscard]] bool has_sparse_jacobian() const override { return sys_.has_sparse_jacobian(); }
  void sparse_jacobian(double t, const double* y, Eigen::SparseMatrix<double>& J) override {
    sys_.sparse_jacobian(t, y, J);
  }
  /// What failed: a body's acceleration that is not finite at the integrator's last evaluation is
  /// the fault of the load whose law is not finite there (an expression dividing by zero), so that
  /// load is named; otherwise the state itself (a drive's current, a body's velocity).
  [[nodiscard]] std::string state_name(int i) const override {
    if (last_y_ && i >= n_ && i < 2 * n_) {
      const int b = i - n_;
      for (const Load& ld : m_.loads)
        if ((ld.body == b || ld.body2 == b) && !std::isfinite(ld.at(last_t_, last_y_, last_y_ + n_)))
          return fmt::format("load '{}'", ld.name);
    }
    return sys_.state_name(i);
  }
  /// None when no element has an event function (a chain of springs and loads): the driver then
  /// evaluates none.
  [[nodiscard]] int event_count() const override { return has_events_ ? sys_.event_slots() + jumps_.count() : 0; }
  void event_functions(double t, const double* y, double* g) override {
    // Without stepwise gears the drive system's functions are all: its call is a tail call.
    if (jump_events_) [[unlikely]] return event_functions_with_jumps(t, y, g);
    sys_.event_functions(t, y, g);
  }
  __attribute__((noinline)) void event_functions_with_jumps(double t, const double* y, double* g) {
    sys_.event_functions(t, y, g);
    jumps_.event_functions(y, g + sys_.event_slots());
  }
  [[nodiscard]] std::vector<double> breakpoints(double, double) const override { return out_.hybrid.breakpoints; }
  [[nodiscard]] double sampling_step(double, double t_end) const override { return machdyn::sampling_step(m_, t_end); }
  bool handle_events(double t, double* y, const std::vector<int>& fired) override {
    next_breakpoint(t);
    // The driver hands back every event function a decision left negative and asks again at the
    // same instant (solve/driver.cpp): decisions that keep contradicting their own event functions
    // there mean no consistent mode exists — an error naming the element, never a disarmed event.
    if (t == decided_at_ && !fired.empty()) {
      // Contacts, end stops, flanks, ropes, lossy gears (their stuck margins and the contacts beside
      // them from one split, analysis/gear_split.hpp; a fired margin is judged strictly) and elements
      // with states (a speed drive: its switch puts its state on the surface, Element::on_switch) are
      // decided again. A stepwise gear's jump is no decision: its function waits until it is ≥ 0 at a
      // step end (handed back, it would jump again).
      if (std::all_of(fired.begin(), fired.end(), [&](int f) { return f >= sys_.event_slots(); })) return false;
      if (++redecisions_ > kMaxRedecisions)
        throw SolverError(slot_name(fired.front()), t,
                          fmt::format("no consistent mode: its event function stays negative after {} decisions at "
                                      "this instant",
                                      kMaxRedecisions));
    } else {
      decided_at_ = t, redecisions_ = 0;
    }
    std::copy(y, y + N_, y_.begin());
    apply_releases(t);  // at its breakpoint, or at an event located on it
    // Prescribed speeds exactly on their signals (the integrated slope's error off): a kinematic
    // contact at a prescribed rest is then at u = 0 exactly (elements/prescribed_motion.hpp).
    for (int j = 0; j < sys_.motion_count(); ++j) {
      const PrescribedMotionLaw& k = sys_.motion(j);
      y_[static_cast<size_t>(n_ + k.body)] = k.snapped_velocity(t, y_[static_cast<size_t>(n_ + k.body)]);
    }
    // A lossy gear's free side exactly on v_a = i v_b of its prescribed side (the same rounding off).
    for (int g = 0; g < ng_ && sys_.motion_count() > 0; ++g) {
      const LossyGearLaw& k = sys_.lossy_gear(g);
      double* v = y_.data() + n_;
      if (m_.bodies[static_cast<size_t>(k.a)].motion != MotionKind::free) v[k.b] = v[k.a] / k.i;
      else if (m_.bodies[static_cast<size_t>(k.b)].motion != MotionKind::free) v[k.a] = k.i * v[k.b];
    }
    std::vector<int>& own = own_;  // kept: no allocation per event
    own.clear();
    int jump = -1;
    for (int f : fired) {
      if (f < sys_.event_slots()) own.push_back(f);
      else if (jump < 0) jump = f - sys_.event_slots();  // one jump at a time: the earliest
    }
    if (jump >= 0) jumps_.jump(t, y_.data(), jump);
    // A re-decision (the driver hands back functions this instant's decision left negative) reports
    // whether it changed anything: the same modes and state again are the decision's last word.
    const bool again = redecisions_ > 0;
    if (again) remember_decision(y);
    if (fired.empty()) time_event(t);
    else if (!own.empty()) {
      // An event located on a breakpoint (within the span that merges breakpoints into it): the
      // breakpoint's applications and releases too.
      const auto& bps = out_.hybrid.breakpoints;
      const auto bp = std::lower_bound(bps.begin(), bps.end(), t);
      if (bp != bps.end() && *bp - t <= 1e-12 * m_.simulation.t_end) log_applications(t);
      handle_event(t, own);
    }
    std::copy(y_.begin(), y_.end(), y);
    return !again || !same_decision(y);
  }

  // ---- the link loads as the peak tracker's signals (elements/link.hpp, in the current modes) ----
  [[nodiscard]] int count() const override { return nl_; }
  [[nodiscard]] double value(int l, const double* y) const override { return sys_.link_load(l, y); }
  [[nodiscard]] double rate(int l, const double* y, const double* dy) const override {
    return sys_.link_load_rate(l, y, dy);
  }
  [[nodiscard]] bool rate_reads_state(int l) const override { return sys_.link_rate_reads_state(l); }
  void values_and_rates(const double* y, const double* dy, double* out, double* rate_out) const override {
    sys_.link_loads_and_rates(y, dy, out, rate_out);
  }

  // ---- the observer of the driver ----
  void on_step(const Stepper& st) override {
    step_ = &st;
    // No breakpoint ahead (bp_next_ = ∞), no audit and no progress report (step_watch_): nothing more,
    // and no call of t() (virtual) per step.
    if (step_watch_ || bp_next_ != std::numeric_limits<double>::infinity()) [[unlikely]] return on_step_rest(st);
  }
  __attribute__((noinline)) void on_step_rest(const Stepper& st) {
    if (bp_next_ != std::numeric_limits<double>::infinity() && st.t() >= bp_next_) next_breakpoint(st.t());
    if (audit_) [[unlikely]] audit_->settle();
    if (opt_.progress) report_progress(st, start_, false);
  }
  void on_segment(const Stepper& st, double ta, double tb) override {
    if (!extremes_only_) [[unlikely]] return on_piece(st, ta, tb);
    // Only the extremes follow the piece: the peak tracker by a tail call (no frame here).
    if (tb >= opt_.extremes_from) return peaks_.on_segment(st, std::max(ta, opt_.extremes_from), tb, on_new_max_);
  }
  /// A piece with more to follow than the extremes: rope ends, heat, machine traces, the audit.
  __attribute__((noinline)) void on_piece(const Stepper& st, double ta, double tb) {
    if (!winding_links_.empty()) check_rope_ends(st, ta, tb);
    if (extra_.heat || heat_.any_thermal()) heat_.close_piece(st, ta, tb);  // heat, temperatures over the piece
    // The extremes over [extremes_from, t_end] (SimulateOptions): the part of the piece from there.
    if (tb >= opt_.extremes_from)
      peaks_.on_segment(st, std::max(ta, opt_.extremes_from), tb, on_new_max_);
    jumps_.on_segment(st, ta, tb);
    // A step's end in its mode (a piece an event truncates is checked after the event's decision).
    if (audit_) [[unlikely]] audit_->piece_end(tb, tb == st.t(), st.y());
  }
  /// A rope wound on its drum until one fall is shorter than L_min = 1e-3 L_f0 (elements/link.hpp): the
  /// hook has reached the drum (two-blocking), where the model ends — the law would hold L_f at L_min
  /// and let the hook rise on. The run stops there (the first such time in the piece, by bisection on
  /// the dense output) naming the rope.
  void check_rope_ends(const Stepper& st, double ta, double tb) {
    auto short_at = [&](int l, double t) {
      st.interpolate(t, rope_q_.data());
      const LinkLaw& k = sys_.link(l);
      return k.at_min_length(k.drum(rope_q_.data()));
    };
    rope_q_.resize(static_cast<size_t>(N_));
    for (const int l : winding_links_) {
      if (!short_at(l, tb)) continue;
      double lo = ta, hi = tb;  // long at lo (the previous piece ended long), short at hi
      for (int it = 0; it < 60 && hi - lo > 1e-15 * std::max(1.0, std::abs(hi)); ++it) {
        const double mid = 0.5 * (lo + hi);
        (short_at(l, mid) ? hi : lo) = mid;
      }
      const LinkLaw& k = sys_.link(l);
      throw SolverError(m_.links[static_cast<size_t>(l)].name, hi,
                        fmt::format("the rope is wound in to its end: one fall is {:.3g} m long, 1/1000 of its "
                                    "free length {:.6g} m (the hook at the drum); the model ends there: "
                                    "shorten t_end or give the rope a longer 'length'",
                                    1e-3 * k.L0, k.L0));
    }
  }

  void on_output(double t, const double* y) override {
    // One test for every rare row: observers of the rows, or columns without room (row_fast_end_).
    if (row_ >= row_fast_end_) [[unlikely]] return output_rare(t, y);
    const size_t row = row_++;
    // Tail calls: the row's writer returns to the driver (no frame here, nothing kept across).
    if (plain_rows_) return output_head(row, t, y);
    if (contact_rows_) return output_contacts(row, t, y);
    output(row, t, y);
  }
  /// A row with observers of the rows, or one the columns have no room for yet.
  __attribute__((noinline)) void output_rare(double t, const double* y) {
    if (observed_rows_) return output_observed(t, y);
    write_row(next_row(), t, y);
  }
  /// A row with observers of the rows: the row (when the series is kept) and the audit's check of it
  /// (audit.hpp), the sway summary (sway_summary.hpp).
  void output_observed(double t, const double* y) {
    if (opt_.record_series) {
      write_row(next_row(), t, y);
      if (audit_) audit_->row(t, y);
    }
    if (sway_) sway_->row(sys_, t, y);
  }
  /// Row `row` by the writer of the model's columns.
  void write_row(size_t row, double t, const double* y) {
    if (plain_rows_) output_head(row, t, y);
    else if (contact_rows_) output_contacts(row, t, y);
    else output(row, t, y);
  }
  void on_event(double t, const double* y, const std::vector<int>& fired) override {
    peaks_.restart();
    if (audit_) [[unlikely]] audit_->after_event(t, y, !fired.empty());
  }
  /// The load history (analysis/load_history.hpp): every value the link loads take, to `f`.
  void set_link_values(PeakTracker::EveryValue f) { peaks_.set_every_value(std::move(f)); }

 private:
  // ---- output ----
  void setup_columns() {
    auto& names = out_.column_names;
    names = chain_column_names(m_);
    for (const auto& c : m_.contacts) {
      const BodyKind k = m_.bodies[static_cast<size_t>(c.a)].kind;
      if (c.joint) {  // a gear joint: the torque it puts on each member, −w_j λ (elements/contact.hpp)
        for (int j = 0; j < c.row.terms; ++j)
          names.push_back(c.name + ".torque_" + m_.bodies[static_cast<size_t>(c.row.body[j])].name + "_" +
                          unit_suffix(load_unit(k)));
        continue;
      }
      names.push_back(c.name + ".force_" + unit_suffix(load_unit(k)));
      names.push_back(c.name + ".sliding_velocity_" + unit_suffix(velocity_unit(k)));
      names.push_back(c.name + ".mode");
    }
    // Gear joints with a member without inertia (model.hpp: EliminatedJoint): the torque on each member.
    for (const auto& e : m_.eliminated_joints)
      for (const auto& nm : e.members) names.push_back(e.name + ".torque_" + nm + "_" + unit_suffix(load_unit(e.kind)));
    for (int l = 0; l < nl_; ++l)
      if (m_.links[static_cast<size_t>(l)].has_gap) {
        names.push_back(m_.links[static_cast<size_t>(l)].name + ".gap_mode");
        gap_links_.push_back(l);
      }
    loads_.assign(static_cast<size_t>(nl_), 0.0);
    // Elements with states of their own: the torque on the body, then the element's own columns
    // (Element::output_names: a DC motor's current, a speed drive's reference speed, a mode).
    for (const auto& d : m_.drives) {
      const BodyKind k = m_.bodies[static_cast<size_t>(d.body)].kind;
      names.push_back(d.name + ".torque_" + unit_suffix(load_unit(k)));
      const std::vector<std::string> own = d.law->output_names(k);
      for (const auto& o : own) names.push_back(d.name + "." + o);
      drive_cols_.push_back(own.size());
      drive_vals_.resize(std::max(drive_vals_.size(), own.size()));
    }
    // Lossy gears (elements/lossy_gear.hpp): the direction −1, 0, +1 (MSL's gear.mode), the torques
    // at its two bodies (MSL's flange_a.tau, flange_b.tau) and the heat (X − Y) v_a.
    for (const auto& g : m_.lossy_gears) {
      const BodyKind k = m_.bodies[static_cast<size_t>(g.a)].kind;
      names.push_back(g.name + ".mode");
      names.push_back(g.name + ".torque_a_" + unit_suffix(load_unit(k)));
      names.push_back(g.name + ".torque_b_" + unit_suffix(load_unit(m_.bodies[static_cast<size_t>(g.b)].kind)));
      names.push_back(g.name + ".loss_power_W");
    }
    // Ropes with falls or a free length (elements/link.hpp): the tension of one fall T = F/n (the
    // link's load F is the hook load) and, wound on a drum, the free length of one fall L_f.
    for (int k = 0; k < nl_; ++k) {
      const Link& l = m_.links[static_cast<size_t>(k)];
      if (!is_rope_with_falls(l)) continue;
      names.push_back(l.name + ".fall_tension_N");
      if (l.EA > 0.0) names.push_back(l.name + ".fall_length_m");
      if (has_reeving(l)) names.push_back(l.name + ".rope_force_N");  // the part at the drum (model/reeving.hpp)
      rope_links_.push_back(k);
    }
    for (int k = 0; k < nl_; ++k)
      if (sys_.link(k).winding) winding_links_.push_back(k);
    // Bodies slaved by ideal gears (model.hpp: RigidSlave): q = ρ q_master, v = ρ v_master.
    for (const auto& sl : m_.slaves) {
      names.push_back(sl.name + ".position_" + unit_suffix(position_unit(sl.kind)));
      names.push_back(sl.name + ".velocity_" + unit_suffix(velocity_unit(sl.kind)));
    }
    // Ideal gears merged at compile (model.hpp: MergedGear): the torque each passes to its B side.
    for (const auto& g : m_.merged_gears)
      names.push_back(g.name + (g.kind_b == BodyKind::translational ? ".force_" : ".torque_") + unit_suffix(load_unit(g.kind_b)));
    // Friction elements with a thermal model (elements/thermal.hpp): the temperature, in °C.
    for (const auto& c : m_.contacts)
      if (c.thermal) names.push_back(c.name + ".temperature_degC");
    temperature_.assign(static_cast<size_t>(std::count_if(m_.contacts.begin(), m_.contacts.end(),
                                                          [](const FrictionContact& c) { return c.thermal.has_value(); })),
                        0.0);
    // Bodies that release mass (model.hpp: Release): their current mass or inertia.
    for (int b : released_bodies_) {
      const Body& bd = m_.bodies[static_cast<size_t>(b)];
      names.push_back(bd.name + (bd.kind == BodyKind::translational ? ".mass_kg" : ".inertia_kg_m2"));
    }
    // Bodies with a prescribed motion (elements/prescribed_motion.hpp): the force of the motion source.
    for (int j = 0; j < sys_.motion_count(); ++j) {
      const Body& bd = m_.bodies[static_cast<size_t>(sys_.motion(j).body)];
      names.push_back(bd.name + (bd.kind == BodyKind::translational ? ".motion_force_N" : ".motion_torque_N_m"));
    }
    if (extra_.any()) extra_columns(names);
    // Rows of only t, states and link loads (and no machine, whose accelerations are kept per row).
    plain_rows_ = names.size() == 1 + 2 * m_.bodies.size() + m_.links.size() && !sys_.has_machines();
    // Every column group output() writes after the gap modes (a new one must be added here).
    tail_groups_ = nd_ > 0 || ng_ > 0 || !rope_links_.empty() || !m_.slaves.empty() || !m_.merged_gears.empty() ||
                   heat_.any_thermal() || !released_bodies_.empty() || sys_.motion_count() > 0 || extra_.any();
    // Rows that end with the contacts and gap modes: output_contacts().
    contact_rows_ = !plain_rows_ && nc_ > 0 && !sys_.has_machines() && m_.eliminated_joints.empty() && !tail_groups_;
    out_.columns.resize(names.size());
    if (!opt_.record_series) return;
    // Sized once (compile bounded the bytes); rows are written in place and the columns cut to
    // the rows written at the end: no capacity check per value on the output path.
    row_cap_ = static_cast<size_t>(m_.simulation.t_end / m_.simulation.dt_out) + 2;
    for (auto& col : out_.columns) col.resize(row_cap_);
    point_columns();
  }
  /// col_[j] = out_.columns[j].data(): a row writes each value through one pointer, not through a
  /// column's vector (refreshed whenever the columns are resized).
  void point_columns() {
    col_.resize(out_.columns.size());
    for (size_t j = 0; j < col_.size(); ++j) col_[j] = out_.columns[j].data();
  }
  /// The index of the next output row (more room if the grid ever outgrows its bound).
  size_t next_row() {
    if (row_ == row_cap_) [[unlikely]] grow_rows();
    return row_++;
  }
  /// Out of line: inlined, its loop gave on_output() a stack frame and six saved registers per row.
  __attribute__((noinline)) void grow_rows() {
    row_cap_ = 2 * row_cap_ + 16;
    row_fast_end_ = observed_rows_ ? 0 : row_cap_;
    for (auto& col : out_.columns) col.resize(row_cap_);
    point_columns();
  }

  /// A plain chain's rows (t, the states, the link loads) by a small function of their own (the
  /// hoist's rows without output()'s frame and group checks).
  __attribute__((noinline)) void output_head(size_t row, double t, const double* y) { head(row, t, y); }
  /// The first columns of every row: t, the states, the link loads (into loads_ as well).
  __attribute__((always_inline)) void head(size_t row, double t, const double* y) {
    double* const* col = col_.data();
    (*col++)[row] = t;
    for (int i = 0; i < n_; ++i, col += 2) {
      col[0][row] = y[i];
      col[1][row] = y[n_ + i];
    }
    double* F = loads_.data();
    sys_.link_loads(y, F);
    for (int l = 0; l < nl_; ++l) col[l][row] = F[l];
  }

  /// Row `row` of a model whose rows end with its contacts and gap modes (no machine, eliminated
  /// joint or later group: contact_rows_, the travel start-up): output()'s columns without its checks.
  __attribute__((noinline)) void output_contacts(size_t row, double t, const double* y) {
    double* const* col = col_.data();
    (*col++)[row] = t;
    for (int i = 0; i < n_; ++i, col += 2) {
      col[0][row] = y[i];
      col[1][row] = y[n_ + i];
    }
    // The link loads by their law inline, straight into their columns (head()'s loads_ serve the
    // rope columns of output() alone).
    for (int l = 0; l < nl_; ++l) (*col++)[row] = sys_.link_load(l, y);
    sys_.contact_forces(t, y, fc_.data());
    col = contact_columns(row, t, y, col);
    gap_columns(row, col);
  }
  /// The contacts' columns from fc_ (a gear joint: the torques −w_j λ; else F, u and the mode),
  /// written through `col`; returns the column after them.
  __attribute__((always_inline)) double* const* contact_columns(size_t row, double t, const double* y,
                                                                double* const* col) const {
    const double* fc = fc_.data();  // locals: the stores into the columns make no member reload
    const double* v = y + n_;
    const ContactMode* mode = sys_.contact_modes().data();
    for (int k = 0; k < nc_; ++k) {
      const ContactLaw& law = sys_.contact(k);
      if (law.joint) {
        for (int j = 0; j < law.row.terms; ++j) (*col++)[row] = -law.row.w[j] * fc[k];
        continue;
      }
      (*col++)[row] = fc[k];
      (*col++)[row] = law.sliding_velocity(t, v);  // = sys_.sliding_velocity(k, t, y)
      (*col++)[row] = static_cast<double>(static_cast<int>(mode[k]));
    }
    return col;
  }
  /// The gap links' modes, written through `col`; returns the column after them.
  __attribute__((always_inline)) double* const* gap_columns(size_t row, double* const* col) const {
    for (const int l : gap_links_) (*col++)[row] = static_cast<double>(static_cast<int>(sys_.gap_mode(l)));
    return col;
  }

  /// Row `row` of every other model: head()'s columns, then the contacts, gaps and the groups after.
  __attribute__((noinline)) void output(size_t row, double t, const double* y) {
    head(row, t, y);
    double* const* col = col_.data() + 1 + 2 * n_ + nl_;
    auto put = [&](double v) { (*col++)[row] = v; };
    if (sys_.has_machines()) sys_.evaluate(t, y, acc_.data(), fc_.data());
    else if (nc_ > 0) sys_.contact_forces(t, y, fc_.data());
    if (sys_.has_machines()) acc_rows_.insert(acc_rows_.end(), acc_.begin(), acc_.end());  // for the machine series
    col = contact_columns(row, t, y, col);
    for (const auto& e : m_.eliminated_joints) {
      const double lambda = eliminated_joint_load(e, t, y);
      for (const double w : e.w) put(-w * lambda);
    }
    col = gap_columns(row, col);
    if (!tail_groups_) return;  // no drive, gear, rope, slave, thermal, release, motion or extra columns
    for (int d = 0; d < nd_; ++d) {
      put(sys_.drive_torque(d, t, y));
      sys_.drive_outputs(d, t, y, drive_vals_.data());
      for (size_t j = 0; j < drive_cols_[static_cast<size_t>(d)]; ++j) put(drive_vals_[j]);
    }
    for (int g = 0; g < ng_; ++g) {
      const LossyGearLaw& k = sys_.lossy_gear(g);
      const LossyGearLaw::Torques T = sys_.gear_torques(g, t, y);
      put(static_cast<double>(direction(sys_.gear_mode_now(g))));
      put(k.torque_at_a(T));
      put(k.torque_at_b(T));
      put(LossyGearLaw::loss_power(T, y[n_ + k.a]));
    }
    for (const int l : rope_links_) {
      const Link& lk = m_.links[static_cast<size_t>(l)];
      put(loads_[static_cast<size_t>(l)] / lk.falls);
      if (lk.EA > 0.0) put(sys_.link(l).free_length(sys_.link(l).drum(y)));
      if (has_reeving(lk))  // the drum's rope speed: q̇_a / i > 0 winds in (hoists)
        put(Reeving{lk.falls, lk.rope_ends, lk.sheave_efficiency}
                .drum_part_force(loads_[static_cast<size_t>(l)], sys_.link(l).drum(y + n_) * sys_.link(l).inv_ratio));
    }
    for (const auto& sl : m_.slaves) {  // slaved bodies: q = ρ q_master (+ ρ₂ q_master2), likewise v
      put(sl.ratio * y[sl.master] + (sl.master2 >= 0 ? sl.ratio2 * y[sl.master2] : 0.0));
      put(sl.ratio * y[n_ + sl.master] + (sl.master2 >= 0 ? sl.ratio2 * y[n_ + sl.master2] : 0.0));
    }
    if (!m_.merged_gears.empty()) {
      if (!sys_.has_machines()) sys_.evaluate(t, y, acc_.data(), fc_.data());
      for (size_t k = 0; k < m_.merged_gears.size(); ++k) put(merged_gear_torque(k, t, y));
    }
    if (heat_.any_thermal()) {
      heat_.at(step_, t, y, nullptr, nullptr, temperature_.data());
      for (double T : temperature_) put(T - kZeroCelsius);
    }
    for (int b : released_bodies_) put(sys_.inertia(b));
    if (sys_.motion_count() > 0) {
      sys_.evaluate(t, y, acc_.data(), fc_.data());
      for (int j = 0; j < sys_.motion_count(); ++j) put(sys_.motion_force(j));
    }
    if (extra_.any()) {
      size_t c = static_cast<size_t>(col - col_.data());
      extra_output(t, y, row, c);
    }
  }

  // ---- the optional columns (analysis/extra_outputs.hpp) ----
  void extra_columns(std::vector<std::string>& names) {
    auto rate_unit = [](const std::string& pos) { return pos == "rad" ? std::string("rad_s") : std::string("m_s"); };
    if (extra_.deflection)
      for (const auto& l : m_.links) {
        const std::string u = link_deflection_unit(l);
        names.push_back(l.name + ".deflection_" + u);
        names.push_back(l.name + ".deflection_rate_" + rate_unit(u));
      }
    if (extra_.acceleration)  // a machine body has its acceleration column already (machine_outputs.hpp)
      for (const auto& b : m_.bodies)
        if (!b.machine) names.push_back(b.name + ".acceleration_" + (b.kind == BodyKind::rotational ? "rad_s2" : "m_s2"));
    if (extra_.power) {
      for (const auto& ld : m_.loads) names.push_back(ld.name + ".power_W");
      for (const auto& d : m_.drives) names.push_back(d.name + ".power_W");
      for (const auto& l : m_.links)
        if (l.d > 0.0) names.push_back(l.name + ".damping_power_W");
    }
    if (extra_.heat) {  // every dissipative element (analysis/heat.hpp), then the model's total
      for (int j = 0; j < heat_.count(); ++j) {
        if (!heat_.own_power_column(j)) names.push_back(heat_.name(j) + ".heat_power_W");
        names.push_back(heat_.name(j) + ".heat_J");
      }
      names.emplace_back("heat_power_W");
      names.emplace_back("heat_J");
      p_.assign(static_cast<size_t>(heat_.count()) + 1, 0.0);
      q_.assign(static_cast<size_t>(heat_.count()) + 1, 0.0);
    }
  }
  /// τ_B of merged ideal gear g (model.hpp: MergedGear) from its side S's equation of motion:
  /// ρ_E τ_E = I_S q̈_M − f_S, f_S the loads on S and the first ends of S's links (−F j_a and a winding
  /// rope's −W, as the drive system applies them), in the master's coordinate; acc_ holds q̈.
  double merged_gear_torque(size_t gi, double t, const double* y) const {
    const MergedGear& g = m_.merged_gears[gi];
    const int M = g.body;
    double f = 0.0;
    for (const int d : merged_drives_[gi]) {  // drives on S's slaves: their share ρ M on the master
      int b[2];
      double w[2];
      const double Md = sys_.drive_torque(d, t, y);
      for (int i = 0, nt = sys_.drive_place(d).terms(b, w); i < nt; ++i)
        if (b[i] == M) f += w[i] * Md;
    }
    for (const int k : g.loads) {  // the load's share on M (model.hpp: Load::terms)
      const Load& ld = now().loads[static_cast<size_t>(k)];
      int b[2];
      double w[2];
      const double Mx = ld.at(t, y, y + n_);
      for (int i = 0, nt = ld.terms(b, w); i < nt; ++i)
        if (b[i] == M) f += w[i] * Mx;
    }
    for (const int l : g.links) {
      const LinkLaw& law = sys_.link(l);
      const LinkLaw::Kinematics s = sys_.link_kinematics(l, y);
      f -= loads_[static_cast<size_t>(l)] * s.ja + law.winding_force(s.delta, law.drum(y), sys_.gap_mode(l));
    }
    const double tau_e = (g.inertia * acc_[static_cast<size_t>(M)] - f) / g.rho;
    return g.side_b ? tau_e : -g.ratio * tau_e;
  }
  /// λ of a gear joint whose member X has no inertia, from X's torque balance (model.hpp:
  /// EliminatedJoint): λ = f_X / w_X; loads_ and fc_ hold the link loads and contact forces at t.
  double eliminated_joint_load(const EliminatedJoint& e, double t, const double* y) const {
    double f = 0.0;
    for (size_t k = 0; k < e.loads.size(); ++k)
      f += e.load_weight[k] * now().loads[static_cast<size_t>(e.loads[k])].at(t, y, y + n_);
    for (size_t k = 0; k < e.links.size(); ++k) f -= e.link_weight[k] * loads_[static_cast<size_t>(e.links[k])];
    for (size_t k = 0; k < e.contacts.size(); ++k) f -= e.contact_weight[k] * fc_[static_cast<size_t>(e.contacts[k])];
    for (size_t k = 0; k < e.drives.size(); ++k) f += e.drive_weight[k] * sys_.drive_torque(e.drives[k], t, y);
    return f / e.wx;
  }
  /// δ is in b's coordinate (a's for a link to the ground), in m at a machine's output point.
  std::string link_deflection_unit(const Link& l) const {
    return std::string(link_load_unit(m_, l)) == "N*m" ? "rad" : "m";
  }

  void extra_output(double t, const double* y, size_t row, size_t& c) {
    auto& cols = out_.columns;
    auto put = [&](double v) { cols[c++][row] = v; };
    if (extra_.deflection)
      for (int l = 0; l < nl_; ++l) {
        const LinkLaw::Kinematics s = sys_.link_kinematics(l, y);
        put(s.delta);
        put(s.rate);
      }
    if (extra_.acceleration) sys_.evaluate(t, y, acc_.data(), fc_.data());
    if (extra_.acceleration)
      for (int i = 0; i < n_; ++i)
        if (!m_.bodies[static_cast<size_t>(i)].machine) put(acc_[static_cast<size_t>(i)]);
    if (extra_.power) {
      for (const Load& ld : now().loads)  // the weights as the releases so far left them
        put(ld.at(t, y, y + n_) * ld.own(y + n_));  // M v_X (model.hpp: Load)
      for (int d = 0; d < nd_; ++d)
        put(sys_.drive_power(d, t, y));  // Σ M_p v_p, M ω_X on one body (model.hpp: Drive)
      for (int l = 0; l < nl_; ++l)
        if (m_.links[static_cast<size_t>(l)].d > 0.0) {
          const LinkLaw::Kinematics s = sys_.link_kinematics(l, y);
          put(sys_.link(l).dissipation(s.delta, s.rate, sys_.gap_mode(l), sys_.link(l).drum(y)));  // c(q_a) of a winding rope
        }
    }
    if (extra_.heat) {
      heat_.at(step_, t, y, p_.data(), q_.data(), nullptr);
      for (size_t j = 0; j < p_.size(); ++j) {
        if (j + 1 == p_.size() || !heat_.own_power_column(static_cast<int>(j))) put(p_[j]);
        put(q_[j]);
      }
    }
  }
  // ---- quasi-static loads at the extremes ----
  /// What the generalized forces at (t, y) are made of beyond the constant loads: the values of the
  /// time- or speed-dependent loads, the machines' forces Q(q), the drives' torques and the contacts'
  /// forces, with the contact and gear modes that decide what is held — O(loads + machines + drives +
  /// contacts + gears), not O(n), per new extreme and in memory.
  struct Extreme {
    std::vector<double> vals;
    double t = 0.0;
    std::vector<ContactMode> modes;
    std::vector<GearMode> gears;  // the lossy gears' modes: a stuck one is held (held())
    std::vector<double> gear_v;   // their speeds v_a: a rolling one's relation (rolling())
    size_t stage = 0;  // releases applied at its instant: the masses and weights it belongs to
    // The links off their flank at the instant (an open gap, a slack rope, a one-sided link off its
    // flank), ascending: no coupling of the quasi-static problem (uncoupled()). O(links with a gap).
    std::vector<int> off;
  };
  void ingredients(double t, const double* y, Extreme& out) {
    out.vals.clear();
    out.stage = released_;
    for (size_t k : varying_) {
      const Load& ld = m_.loads[k];
      out.vals.push_back(ld.at(t, y, y + n_));  // M at the load's point, spread in forces()
    }
    for (int i : machine_bodies_) out.vals.push_back(m_.bodies[static_cast<size_t>(i)].machine->force(y[i]));
    for (int d = 0; d < nd_; ++d) {  // the element's forces at t, one per body it acts on
      double M[ElementMotion::kMax] = {};
      sys_.drive_forces_of(d, t, y, M);
      for (int p = 0; p < sys_.drive_place(d).ports(); ++p) out.vals.push_back(M[p]);
    }
    out.off.clear();
    for (int l : flank_links_)
      if (!sys_.link(l).transmits(sys_.gap_mode(l))) out.off.push_back(l);
    out.gears.resize(static_cast<size_t>(ng_));
    out.gear_v.resize(static_cast<size_t>(ng_));
    for (int g = 0; g < ng_; ++g) {
      out.gears[static_cast<size_t>(g)] = sys_.gear_mode_now(g);
      out.gear_v[static_cast<size_t>(g)] = y[n_ + sys_.lossy_gear(g).a];
    }
    if (nc_ == 0) return;
    out.t = t;
    out.modes = sys_.contact_modes();
    contact_forces(y, out);
  }
  /// Appends the contact forces of an extreme (in its modes) to its ingredients: a sliding contact's
  /// friction force from its law at (t, v) (elements/contact.hpp kinetic_force); a held one's is a
  /// reaction, which the quasi-static problem solves for (0 here); a kinematic one stuck carries
  /// nothing (its bodies are supports). A released brake the dynamics keep stuck is no constraint of
  /// the quasi-static problem (held()): its force is the dynamics' λ at (t, y) — the one case that
  /// evaluates the system (O(n)), only while such a brake is stuck.
  void contact_forces(const double* y, Extreme& e) {
    // held_contact per contact, not held(): no vector per new extreme.
    bool reaction = false;
    for (int c = 0; c < nc_; ++c)
      reaction = reaction || (e.modes[static_cast<size_t>(c)] == ContactMode::stuck && !held_contact(e, c) &&
                              !sys_.contact(c).kinematic);
    if (reaction) {
      extreme_acc_.resize(static_cast<size_t>(n_));
      extreme_fc_.resize(static_cast<size_t>(nc_));
      sys_.evaluate(e.t, y, extreme_acc_.data(), extreme_fc_.data());
    }
    for (int c = 0; c < nc_; ++c) {
      const ContactMode md = e.modes[static_cast<size_t>(c)];
      const ContactLaw& law = sys_.contact(c);
      if (md != ContactMode::stuck) e.vals.push_back(law.kinetic_force(md, e.t, law.sliding_velocity(e.t, y + n_)));
      else if (held_contact(e, c) || law.kinematic) e.vals.push_back(0.0);
      else e.vals.push_back(extreme_fc_[static_cast<size_t>(c)]);
    }
  }
  /// The elements an extreme holds, per contact then per lossy gear: constraints of its quasi-static
  /// problem (static_loads.hpp), not forces. A contact held stuck and engaged (a joint always; a
  /// kinematic one adds no row: its bodies are supports), a lossy gear at rest.
  std::vector<char> held(const Extreme& e) const {
    std::vector<char> h(static_cast<size_t>(nc_ + ng_), 0);
    for (int c = 0; c < nc_ && !e.modes.empty(); ++c) h[static_cast<size_t>(c)] = held_contact(e, c);
    for (int g = 0; g < ng_ && !e.gears.empty(); ++g)
      h[static_cast<size_t>(nc_ + g)] = e.gears[static_cast<size_t>(g)] == GearMode::stuck;
    return h;
  }
  /// Whether an extreme holds contact c (its modes set): a joint always, else stuck and engaged
  /// (a kinematic one adds no row: its bodies are supports).
  bool held_contact(const Extreme& e, int c) const {
    const ContactLaw& law = sys_.contact(c);
    return law.joint ||
           (e.modes[static_cast<size_t>(c)] == ContactMode::stuck && !law.released(e.t) && !law.kinematic);
  }
  /// The lossy gears an extreme finds rolling: constraints with their own reaction (LossyGearLaw::
  /// reaction), per gear g its number, the weights of H on a and b and the constant force on a.
  std::vector<double> rolling(const Extreme& e) const {
    std::vector<double> r;
    for (int g = 0; g < ng_ && !e.gears.empty(); ++g) {
      const GearMode md = e.gears[static_cast<size_t>(g)];
      if (md == GearMode::stuck) continue;
      const LossyGearLaw::Reaction x = sys_.lossy_gear(g).reaction(md, e.gear_v[static_cast<size_t>(g)]);
      r.insert(r.end(), {static_cast<double>(g), x.H[0].second, x.H[1].second, x.f0_a});
    }
    return r;
  }
  /// The rows G of the held elements and their reactions H (empty: along the row): a contact's stuck
  /// row u = 0 (elements/contact.hpp add_linear), a stuck gear's ratio and rest rows (elements/
  /// lossy_gear.hpp add_linear: a = 0, both sides at rest), a rolling gear's ratio row with its mode's
  /// reaction (`roll`, rolling()).
  std::pair<ConstraintRows, ConstraintRows> held_rows(const std::vector<char>& h, const std::vector<double>& roll) const {
    LinearModel lin(n_);
    for (int c = 0; c < nc_; ++c)
      if (h[static_cast<size_t>(c)]) sys_.contact(c).add_linear(ContactMode::stuck, true, 0.0, 0.0, lin);
    for (int g = 0; g < ng_; ++g)
      if (h[static_cast<size_t>(nc_ + g)]) sys_.lossy_gear(g).add_linear(GearMode::stuck, lin);
    ConstraintRows H(lin.G.size());
    for (size_t k = 0; k < roll.size(); k += 4) {
      const LossyGearLaw& law = sys_.lossy_gear(static_cast<int>(roll[k]));
      law.add_linear(lin);
      H.push_back({{law.a, roll[k + 1]}, {law.b, roll[k + 2]}});
    }
    return {lin.G, H};
  }
  /// The generalized forces f (n) of a set of ingredients, with the constant loads of `mm` (the
  /// model after the releases of the extreme's instant).
  Eigen::VectorXd forces(const std::vector<double>& vals, const Model& mm) const {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(n_);
    size_t v = 0, k = 0;
    for (size_t j = 0; j < mm.loads.size(); ++j) {
      const Load& ld = mm.loads[j];
      const bool varies = k < varying_.size() && varying_[k] == j;
      ld.spread(varies ? (v < vals.size() ? vals[v] : 0.0) : ld.value, f.data());
      if (varies) ++k, ++v;
    }
    for (int i : machine_bodies_) f(i) += v < vals.size() ? vals[v++] : 0.0;
    for (int d = 0; d < nd_; ++d) {
      double M[ElementMotion::kMax] = {};
      for (int p = 0; p < sys_.drive_place(d).ports(); ++p) M[p] = v < vals.size() ? vals[v++] : 0.0;
      sys_.drive_place(d).spread_all(M, f.data());
    }
    for (int c = 0; c < nc_; ++c) sys_.contact(c).apply(v < vals.size() ? vals[v++] : 0.0, f.data());
    return f;
  }

  /// `mm` without the links `off` marks as coupling (stiffness 0): a link off its flank transmits no
  /// load, so the rigid acceleration and the elastic solution of the quasi-static problem must not
  /// see it (a slack rope leaves the drum to accelerate with the motor alone; its own load is 0).
  static Model uncoupled(const Model& mm, const std::vector<int>& off) {
    Model out = mm;
    for (int l : off) out.links[static_cast<size_t>(l)].c = 0.0;
    return out;
  }

  void summarize_links() {
    // One sparse factorization, one solve per distinct force vector (constant loads: one solve).
    if (nl_ == 0) return;
    // One solver per set of masses (the model's, and after each release an extreme falls behind) and
    // of held elements (constraints, not forces: an extreme's stuck brake holds its drum).
    // A rolling lossy gear keeps its ratio, its reaction follows its mode's efficiency (rolling()).
    // A link off its flank at the extreme's instant carries nothing and couples nothing: the problem
    // is that of the model without it (uncoupled()), one copy per set of such links.
    using Solver = std::tuple<size_t, std::vector<char>, std::vector<double>, std::vector<int>>;
    std::map<Solver, std::unique_ptr<ParticularSolver>> particular;
    std::map<std::pair<size_t, std::vector<int>>, std::unique_ptr<Model>> uncoupled_models;
    auto model_of = [&](size_t st, const std::vector<int>& off) -> const Model& {
      if (off.empty()) return stage(st);
      auto& mm = uncoupled_models[{st, off}];
      if (!mm) mm = std::make_unique<Model>(uncoupled(stage(st), off));
      return *mm;
    };
    std::map<std::pair<Solver, std::vector<double>>, Eigen::VectorXd> solved;
    auto static_loads = [&](const Extreme& e) -> const Eigen::VectorXd& {
      Solver which{e.stage, held(e), rolling(e), e.off};
      const auto key = std::make_pair(which, e.vals);
      auto it = solved.find(key);
      if (it == solved.end()) {
        const auto& [st, h, roll, off] = which;
        auto& p = particular[which];
        if (!p) {
          const auto [G, H] = held_rows(h, roll);
          p = std::make_unique<ParticularSolver>(model_of(st, off), G, H);
        }
        Eigen::VectorXd f = forces(e.vals, stage(st));
        for (size_t k = 0; k < roll.size(); k += 4) f(sys_.lossy_gear(static_cast<int>(roll[k])).a) += roll[k + 3];
        Eigen::VectorXd F = p->solve(f);
        for (int l : off) F(l) = 0.0;  // off its flank: no load, whatever its law
        it = solved.emplace(key, std::move(F)).first;
      }
      return it->second;
    };
    // Link l off its flank at the extreme's instant carries 0 whatever the solution (static_loads
    // sets it so): no solver for that extreme's problem (a gap link's minimum, open at 0).
    auto static_load = [&](const Extreme& e, int l) {
      return std::binary_search(e.off.begin(), e.off.end(), l) ? 0.0 : static_loads(e)(l);
    };
    for (int l = 0; l < nl_; ++l) {
      LinkSummary s;
      s.max = peaks_.max(l), s.min = peaks_.min(l), s.t_max = peaks_.t_max(l), s.t_min = peaks_.t_min(l);
      s.static_at_max = static_load(at_max_[static_cast<size_t>(l)], l);
      s.static_at_min = static_load(at_min_[static_cast<size_t>(l)], l);
      set_peak(s);
      // A buffer's force has no quasi-static counterpart (it is zero until the impact, and the
      // impact's reference is the rigid-body peak of φ7, analysis/crane.hpp): no dynamic factor.
      if (m_.links[static_cast<size_t>(l)].buffer) s.dynamic_factor = std::numeric_limits<double>::quiet_NaN();
      out_.links.push_back(s);
    }
  }

  // ---- progress ----
  /// The clock is read every 32 steps only; a report at most every progress_interval_s.
  __attribute__((noinline)) void report_progress(const Stepper& st, std::chrono::steady_clock::time_point start,
                                                 bool finished) {
    if (!opt_.progress) return;
    ++progress_steps_;
    if (!finished && (progress_steps_ & 31) != 0) return;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    if (!finished && wall < next_progress_) return;
    next_progress_ = wall + opt_.progress_interval_s;
    SimulationProgress p;
    p.t = finished ? m_.simulation.t_end : st.t();
    p.t_end = m_.simulation.t_end;
    p.steps = st.stats().steps;
    p.events = static_cast<long>(out_.hybrid.events.size()) - initial_events_ + jumps_.jumps();
    p.wall_s = wall;
    p.finished = finished;
    opt_.progress(p);
  }

  /// bp_next_ = the first breakpoint after t (rhs() takes the signals' left limits there).
  void next_breakpoint(double t) {
    const std::vector<double>& b = out_.hybrid.breakpoints;
    const auto it = std::upper_bound(b.begin(), b.end(), t);
    bp_next_ = it == b.end() ? std::numeric_limits<double>::infinity() : *it;
  }
  double bp_next_ = std::numeric_limits<double>::infinity();

  // ---- re-decisions at one instant ----
  /// The modes of every element and the state, before a re-decision.
  void remember_decision(const double* y) {
    decision_modes_ = decision_signature();
    decision_y_.assign(y, y + N_);
  }
  /// Whether the re-decision left modes and state as remember_decision saw them.
  bool same_decision(const double* y) const {
    return decision_signature() == decision_modes_ && std::equal(decision_y_.begin(), decision_y_.end(), y);
  }
  std::vector<int> decision_signature() const {
    std::vector<int> s;
    for (ContactMode md : sys_.contact_modes()) s.push_back(static_cast<int>(md));
    for (int l = 0; l < nl_; ++l) s.push_back(static_cast<int>(sys_.gap_mode(l)));
    for (int d = 0; d < nd_; ++d) s.push_back(sys_.drive_mode(d));
    for (int g = 0; g < ng_; ++g) s.push_back(static_cast<int>(sys_.gear_mode(g)));
    return s;
  }
  std::vector<int> decision_modes_;
  std::vector<double> decision_y_;

  // ---- events and slip phases ----
  /// The element of event function `slot` (the drive system's slots, then the stepwise gears' jumps).
  std::string slot_name(int slot) const {
    if (slot >= sys_.event_slots()) return "stepwise gear jump " + std::to_string(slot - sys_.event_slots());
    const int e = sys_.slot_element(slot);
    return element_name(sys_.slot_is_link(slot)    ? e
                        : sys_.slot_is_gear(slot)  ? nl_ + nc_ + nd_ + e
                        : sys_.slot_is_drive(slot) ? nl_ + nc_ + e
                                                   : nl_ + e);
  }
  /// Element e of the events: links, then contacts, then drives, then lossy gears.
  const std::string& element_name(int e) const {
    return e < nl_               ? m_.links[static_cast<size_t>(e)].name
           : e < nl_ + nc_       ? m_.contacts[static_cast<size_t>(e - nl_)].name
           : e < nl_ + nc_ + nd_ ? m_.drives[static_cast<size_t>(e - nl_ - nc_)].name
                                 : m_.lossy_gears[static_cast<size_t>(e - nl_ - nc_ - nd_)].name;
  }
  /// Decides every lossy gear at (t, y_) with the other elements in their new modes (the gears decide
  /// independently, but for the two gears of a two-stage train: analysis/gear_train.hpp); a gear at rest with friction elements to the
  /// ground on its bodies is decided together with them (analysis/gear_lock.hpp), their changes
  /// recorded as contact events. `fired`: gears whose event fired, judged without the rounding
  /// allowance. Records the changes (`initial`: all).
  void decide_gears(double t, const std::vector<int>& fired, bool initial, const std::vector<int>& broke = {}) {
    for (int g = 0; g < ng_; ++g) {
      bool strict = std::find(fired.begin(), fired.end(), g) != fired.end();
      if (const int tr = sys_.gear_train_of(g); tr >= 0)  // a two-stage train is decided as one (gear_train.hpp)
        for (int h : sys_.gear_train(tr).gears) strict = strict || std::find(fired.begin(), fired.end(), h) != fired.end();
      // The contact decision may have settled a coupled gear's driving side already: its mode before.
      const GearMode old = gear_before_.empty() ? sys_.gear_mode(g) : gear_before_[static_cast<size_t>(g)];
      GearMode now;
      const double va = y_[static_cast<size_t>(n_ + sys_.lossy_gear(g).a)];
      if (sys_.coupled_gear(g) && va != 0.0) {  // rolling with the clutches on its bodies (analysis/gear_clutch.hpp)
        now = settle_rolling_side(sys_, g, va > 0.0 ? 1 : -1, t, y_.data());
      } else if (decided_at_rest(g)) {  // with its friction and clutches (analysis/gear_clutch.hpp)
        const std::vector<ContactMode> before = sys_.contact_modes();
        now = decide_gear_at_rest(sys_, g, t, y_.data(), strict, broke);
        if (!initial) apply_contact_modes(t, before, sys_.contact_modes(), false);
      } else {
        now = sys_.natural_gear_mode(g, t, y_.data(), strict);
      }
      if (!initial && now == old) continue;
      sys_.set_gear_mode(g, now);
      const char* kind = initial ? "initial"
                         : now == GearMode::stuck ? "stick"
                         : old == GearMode::stuck ? "slip"
                         : direction(old) != direction(now) ? "reversal"
                                                            : "driving_side";
      record(t, kind, nl_ + nc_ + nd_ + g, initial ? "" : to_string(old), to_string(now));
    }
    gear_before_.clear();
  }
  /// The gears' modes before an event's contact decision (which settles coupled gears' sides).
  void remember_gears() {
    if (!sys_.has_coupled_gears()) return;
    gear_before_.resize(static_cast<size_t>(ng_));
    for (int g = 0; g < ng_; ++g) gear_before_[static_cast<size_t>(g)] = sys_.gear_mode(g);
  }
  std::vector<GearMode> gear_before_;
  /// Whether gear g stands still with friction elements or clutches on its bodies: decided together
  /// with them (analysis/gear_clutch.hpp decide_gear_at_rest).
  bool decided_at_rest(int g) const {
    return (sys_.coupled_gear(g) || sys_.gear_locks().of_gear[static_cast<size_t>(g)] >= 0) &&
           y_[static_cast<size_t>(n_ + sys_.lossy_gear(g).a)] == 0.0;
  }
  /// Whether contact k is decided again at any event: a stuck one (not a joint or a gear's), a
  /// kinematic one exactly at u = 0 (a prescribed speed that reached its rest at a kink), and one
  /// sliding at exactly u = 0 (a clutch at its limit beside a stuck freewheel that holds u ≡ 0): its
  /// sliding direction is only a label there, decided again with the others (else a freewheel
  /// overrunning beside it leaves it sliding against its motion).
  bool decided_at_event(int k, double t) const {
    const ContactLaw& c = sys_.contact(k);
    if (c.kinematic && sys_.sliding_velocity(k, t, y_.data()) == 0.0) return true;
    if (c.joint || gear_owned(k)) return false;
    if (sys_.contact_mode(k) == ContactMode::stuck) return true;
    return !c.stop && !released(k, t) && sys_.sliding_velocity(k, t, y_.data()) == 0.0;
  }
  /// Whether contact k belongs to a gear lock (decided with its gear, not by decide_contacts).
  bool gear_owned(int k) const { return sys_.gear_locks().owner[static_cast<size_t>(k)] >= 0; }
  /// Sets the mode of element d (with states of its own) and records the switch in its words.
  /// `located`: the switch of one of its own event functions (else its natural mode): its states are
  /// put on the switching surface, on the new mode's side (Element::on_switch).
  void set_drive_mode(int d, double t, int now, bool initial, bool located = false) {
    const int old = sys_.drive_mode(d);
    if (!initial && now == old) return;
    const Element& e = sys_.drive(d);
    // An element that stores energy may release some at a switch (a gear mesh leaving a flank off it,
    // at zero force with its damper pulling): a loss, as a damped gap's release.
    auto stored = [&] { return e.energy(sys_.drive_motion(d, y_.data()), y_.data() + sys_.drive_offset(d), sys_.drive_mode(d)); };
    const double V_old = !initial && e.has_energy() ? stored() : 0.0;
    sys_.set_drive_mode(d, now);
    // A body the element now holds is at rest exactly (its reversal was located a rounding past 0).
    if (const int p = e.held_port(now); p >= 0 && e.held_port(old) != p)
      y_[static_cast<size_t>(n_ + sys_.port_body(d, p))] = 0.0;
    if (!initial) sys_.drive(d).on_switch(t, sys_.drive_motion(d, y_.data()), y_.data() + sys_.drive_offset(d), old, now, located);
    if (!initial && e.has_energy()) {
      const double released = V_old - stored();
      release_loss_ += released, drive_released_ += released;
      heat_.add_drive_release(d, released);
    }
    record(t, initial ? "initial" : e.switch_kind(now), nl_ + nc_ + d, initial ? "" : e.mode_name(old),
           e.mode_name(now));
  }

  void record(double t, const char* kind, int element, const char* from, const char* to) {
    out_.hybrid.events.push_back({t, kind, element_name(element), from, to});
    if (std::string_view(kind) == "initial") return;
    if (static_cast<long>(out_.hybrid.events.size()) > opt_.max_events)
      throw SolverError(element_name(element), t,
                        fmt::format("more than {} mode events; raise max_events or check the model", opt_.max_events));
    // Impacts are not mode switches: a bouncing body's impacts are bounded by the accumulation rule of
    // impact(), not by the chatter guard.
    if (std::string_view(kind) == "impact") return;
    auto& sw = switches_[static_cast<size_t>(element)];
    sw.push_back(t);
    const size_t K = static_cast<size_t>(opt_.chatter_count);
    if (sw.size() >= K) {
      const double window = opt_.chatter_window * std::max(1.0, m_.simulation.t_end);
      const double span = t - sw[sw.size() - K];
      if (span < window)
        throw SolverError(element_name(element), t,
                          fmt::format("chattering: {} mode switches within {:.3g} s (last: {} -> {})", K, span, from, to));
      if (sw.size() > 4 * K) sw.erase(sw.begin(), sw.end() - static_cast<long>(K));
    }
  }

  /// A brake before its application time is released, not slipping: no slip phase.
  bool released(int k, double t) const { return sys_.contact(k).released(t); }

  void open_phase(int k, double t, ContactMode md) {
    if (released(k, t)) return;
    SlipPhase p;
    p.contact = m_.contacts[static_cast<size_t>(k)].name;
    p.direction = static_cast<int>(md);
    p.t_start = p.t_end = t;
    for (int l = 0; l < nl_; ++l) p.link_start.push_back(sys_.link_load(l, y_.data()));
    out_.hybrid.slip_phases.push_back(std::move(p));
    open_phase_[static_cast<size_t>(k)] = static_cast<int>(out_.hybrid.slip_phases.size()) - 1;
    phase_window_[static_cast<size_t>(k)] = peaks_.open_window(t);  // the link extremes over the phase
  }

  void close_phase(int k, double t) {
    int& ph = open_phase_[static_cast<size_t>(k)];
    if (ph < 0) return;
    SlipPhase& p = out_.hybrid.slip_phases[static_cast<size_t>(ph)];
    p.t_end = t;
    const int w = phase_window_[static_cast<size_t>(k)];
    const PeakTracker::Window& W = peaks_.window(w);
    p.link_max = W.max, p.link_t_max = W.t_max, p.link_min = W.min;
    peaks_.close_window(w);
    // A phase of zero length saw no solution: report the loads at its instant.
    for (int l = 0; l < nl_; ++l) {
      const size_t li = static_cast<size_t>(l);
      if (!std::isfinite(p.link_max[li])) {
        p.link_max[li] = p.link_min[li] = sys_.link_load(l, y_.data());
        p.link_t_max[li] = t;
      }
    }
    ph = -1;
  }

  void apply_contact_modes(double t, const std::vector<ContactMode>& old_modes, const std::vector<ContactMode>& modes,
                           bool initial) {
    // The decision leaves the drive system in the modes it returns: formed once, not again.
    if (sys_.contact_modes() != modes) sys_.set_contact_modes(modes);
    for (int k = 0; k < nc_; ++k) {
      const ContactMode a = old_modes[static_cast<size_t>(k)], b = modes[static_cast<size_t>(k)];
      if (!applied_at_rest_.empty() && applied_at_rest_[static_cast<size_t>(k)] != 0) {
        applied_at_rest_[static_cast<size_t>(k)] = 0;
        if (b != ContactMode::stuck) {
          record(t, "applied", nl_ + k, "released", to_string(b));
          open_phase(k, t, b);
        }
        continue;
      }
      if (!initial && a == b) continue;
      // A released element transmits nothing: the mode it is kept in (stuck at zero load, or the
      // direction it would slide) follows the bodies beside it and is no event of its own. Its
      // release and its application are logged by time_event.
      if (!initial && released(k, t)) {
        close_phase(k, t);
        continue;
      }
      const char* kind = initial ? "initial" : b == ContactMode::stuck ? "stick" : a == ContactMode::stuck ? "slip" : "reversal";
      record(t, kind, nl_ + k, initial ? "" : to_string(a), released(k, t) ? "released" : to_string(b));
      close_phase(k, t);
      if (b != ContactMode::stuck) open_phase(k, t, b);
    }
    // A slide that starts at rest starts at u = 0 exactly: the projection of the stuck set beside
    // it may move its bodies by rounding (a general row's step — a planetary gear's joint — touches
    // every member), and a ring brake breaking away beside the joint started at u = −2e-29, its
    // sliding event negative, decided again and again at the same instant.
    std::vector<int>& from_rest = from_rest_;  // kept: no allocation per event
    from_rest.clear();
    for (int k = 0; k < nc_; ++k)
      if (modes[static_cast<size_t>(k)] != ContactMode::stuck && !sys_.contact(k).kinematic && !released(k, t) &&
          sys_.sliding_velocity(k, t, y_.data()) == 0.0)
        from_rest.push_back(k);
    sys_.project_velocities(t, y_.data());
    for (int k : from_rest)
      if (sys_.sliding_velocity(k, t, y_.data()) != 0.0) sys_.zero_sliding_velocity(k, t, y_.data());
  }

  /// The impact of end stop k's body at t, by the stop's law (elements/contact.hpp: rebound, landing):
  /// on the stop exactly, then the velocity jump of the body and of everything tied to it
  /// (analysis/impact.hpp) to the rebound, or to rest (true: the stop is then decided like a contact
  /// at zero speed). Bounces that accumulate (Zeno: by the stop's law, or `chatter_count` impacts
  /// within the chatter window) end at rest with a warning. The kinetic energy lost, of every body
  /// the jump changes, goes to the impact books.
  bool impact(int k, double t) {
    const ContactLaw& c = sys_.contact(k);
    const auto ia = static_cast<size_t>(c.a);
    const double T0 = sys_.kinetic_energy(y_.data());
    y_[ia] = c.stop_position;
    double v_out = c.rebound(sys_.sliding_velocity(k, t, y_.data()));
    sys_.evaluate(t, y_.data(), acc_.data(), fc_.data());
    const double back = c.lock * acc_[ia];  // > 0: back towards the stop
    ContactLaw::Landing how = c.landing(v_out, back, t);
    if (how == ContactLaw::Landing::rebound && impacts_accumulate(k, t)) how = ContactLaw::Landing::accumulation;
    if (how == ContactLaw::Landing::accumulation)
      out_.hybrid.warnings.push_back(fmt::format(
          "end stop '{}': its impacts accumulate (Zeno) at t = {:.12g} s; the body rests on the stop from the "
          "impact at t = {:.12g} s",
          m_.contacts[static_cast<size_t>(k)].name, c.accumulation_time(v_out, back, t), t));
    if (how != ContactLaw::Landing::rebound) v_out = 0.0;
    detail::impact_jump(sys_, k, v_out, t, y_.data(), impact_ties_);
    const double loss = T0 - sys_.kinetic_energy(y_.data());
    out_.hybrid.energy.impact_loss += loss;
    heat_.add_impact(k, loss);  // the stop's heat
    if (how == ContactLaw::Landing::rebound)
      record(t, "impact", nl_ + k, to_string(sys_.contact_mode(k)), to_string(sys_.contact_mode(k)));
    return how != ContactLaw::Landing::rebound;
  }
  /// Whether free end stop k, whose distance just crossed 0, was touched at rest while the loads
  /// pull its body off: its speed within the integrator's resolution (at_rest_to_resolution) and
  /// its acceleration not towards the stop. That is no impact (an impact is the stop reached at
  /// v⁻ ≠ 0, docs/hybrid.md): the body is put on the stop at zero speed and the stop decided with
  /// the contacts — free again, no event. It is where a load lifted off its stop is released with
  /// zero acceleration: the first step after the release (BDF's) may dip the distance by an error
  /// within the tolerances, and the dip was listed as an impact at the release (campaign `sway`
  /// class S1). A body pressed on (the end of a series of bounces) lands by impact() as before.
  bool reached_at_rest(int k, double t) {
    if (!at_rest_to_resolution(k, t)) return false;
    const ContactLaw& c = sys_.contact(k);
    const double q = y_[static_cast<size_t>(c.a)];
    y_[static_cast<size_t>(c.a)] = c.stop_position;
    sys_.evaluate(t, y_.data(), acc_.data(), fc_.data());
    if (c.lock * acc_[static_cast<size_t>(c.a)] > 0.0) {  // back towards the stop: a landing
      y_[static_cast<size_t>(c.a)] = q;
      return false;
    }
    sys_.zero_sliding_velocity(k, t, y_.data());
    return true;
  }
  /// Whether stop k's impacts accumulate beyond what its law foresees (a varying acceleration towards
  /// the stop): this one is the `chatter_count`-th within 1e-9·max(1, t) s — flights of 2e-11 s, some
  /// 200 times the events' location tolerance.
  bool impacts_accumulate(int k, double t) {
    auto& sw = impact_times_[static_cast<size_t>(k)];
    sw.push_back(t);
    const size_t K = static_cast<size_t>(std::max(2, opt_.chatter_count));
    if (sw.size() > 4 * K) sw.erase(sw.begin(), sw.end() - static_cast<long>(K));
    return sw.size() >= K && t - sw[sw.size() - K] < 1e-9 * std::max(1.0, t);
  }
  /// After an impact every mode is decided again with the velocities after the jump (the stop's own
  /// mode was set by impact()): a closed flank the jump left pulling opens (its natural mode), an
  /// element with states of its own takes its natural mode, and every contact the jump set sliding
  /// (a friction contact carries no impulse, a freewheel's partner overruns) takes the direction of
  /// its sliding velocity — one sliding before keeps its mode only if u keeps its sign. Those at
  /// exactly u = 0 are decided with the others (decided_at_event).
  void redecide_after_impact(double t) {
    for (int d = 0; d < nd_; ++d)
      if (sys_.drive(d).has_events()) set_drive_mode(d, t, sys_.natural_drive_mode(d, t, y_.data()), false);
    std::vector<double> g(static_cast<size_t>(sys_.event_slots()));
    sys_.event_functions(t, y_.data(), g.data());
    for (int l = 0; l < nl_; ++l) {
      const GapMode old = sys_.gap_mode(l);
      if (!sys_.link(l).gap || old == GapMode::open || (g[2 * static_cast<size_t>(l)] >= 0.0 && g[2 * static_cast<size_t>(l) + 1] >= 0.0))
        continue;
      const GapMode now = sys_.natural_gap_mode(l, y_.data());
      if (now == old) continue;
      const double V_old = link_elastic_energy(l), V_all = sys_.elastic_energy(y_.data());
      sys_.set_gap_mode(l, now);
      heat_.add_release(l, V_old - link_elastic_energy(l));
      release_loss_ += V_all - sys_.elastic_energy(y_.data());
      record(t, now == GapMode::open ? "gap_opened" : "gap_closed", l, to_string(old), to_string(now));
    }
    std::vector<ContactMode> modes = sys_.contact_modes();
    bool changed = false;
    for (int k = 0; k < nc_; ++k) {
      const ContactLaw& c = sys_.contact(k);
      ContactMode& md = modes[static_cast<size_t>(k)];
      if (c.joint || c.kinematic || gear_owned(k) || (c.stop && md != ContactMode::stuck)) continue;
      // A stuck one whose u is within the integrator's resolution was not set sliding by the jump:
      // that u is the rounding of its bodies' speeds (the jump's projection touches every body tied
      // to the stop's), and it is decided at zero speed with the others (decided_at_event).
      if (md == ContactMode::stuck && at_rest_to_resolution(k, t)) continue;
      const double u = sys_.sliding_velocity(k, t, y_.data());
      const ContactMode now = u > 0.0 ? ContactMode::slip_pos : ContactMode::slip_neg;
      if (u == 0.0 || now == md || !c.can_slide(now)) continue;
      md = now;
      changed = true;
    }
    if (changed) sys_.set_contact_modes(modes);
  }

  void initial_modes() {
    for (int d = 0; d < nd_; ++d)
      if (sys_.drive(d).has_events()) set_drive_mode(d, 0.0, sys_.natural_drive_mode(d, 0.0, y_.data()), true);
    for (int l = 0; l < nl_; ++l) {
      if (!m_.links[static_cast<size_t>(l)].has_gap) continue;
      const GapMode g = sys_.natural_gap_mode(l, y_.data());
      sys_.set_gap_mode(l, g);
      record(0.0, "initial", l, "", to_string(g));
    }
    std::vector<ContactMode> modes(static_cast<size_t>(nc_), ContactMode::stuck);
    std::vector<int> Z;
    for (int k = 0; k < nc_; ++k) {
      const double u = sys_.sliding_velocity(k, 0.0, y_.data());
      const ContactLaw& c = sys_.contact(k);
      if (c.joint) continue;  // always stuck, never decided
      // An end stop off its stop, or leaving it, is free: it "slides" in its free direction −lock.
      const bool stop_free = c.stop && (c.stop_distance(y_[static_cast<size_t>(c.a)]) > 0.0 || -c.lock * u > 0.0);
      if (stop_free) modes[static_cast<size_t>(k)] = static_cast<ContactMode>(-c.lock);
      else if (u == 0.0 && !gear_owned(k)) Z.push_back(k);
      else if (u != 0.0) modes[static_cast<size_t>(k)] = u > 0 ? ContactMode::slip_pos : ContactMode::slip_neg;
    }
    sys_.set_contact_modes(modes);
    if (!Z.empty()) modes = decide_contacts(sys_, 0.0, y_.data(), Z, strict_);
    // A gear at rest with its friction elements and clutches: decided together before the contacts
    // are recorded (decide_gears below repeats the same decision and records the gear).
    for (int g = 0; g < ng_; ++g)
      if (decided_at_rest(g)) (void)decide_gear_at_rest(sys_, g, 0.0, y_.data(), false, {});
    modes = sys_.contact_modes();
    apply_contact_modes(0.0, modes, modes, true);
    if (ng_ > 0) decide_gears(0.0, {}, true);
  }

  void handle_event(double t, const std::vector<int>& fired) {
    std::vector<int> gears;  // lossy gears whose event fired: decided after the others
    // Stuck contacts whose breakaway fired (a coupled gear's decision is strict on them); kept: no
    // allocation at every breakaway.
    std::vector<int>& broke = broke_;
    broke.clear();
    for (int slot : fired)
      if (!sys_.slot_is_link(slot) && !sys_.slot_is_drive(slot) && !sys_.slot_is_gear(slot) &&
          sys_.contact_mode(sys_.slot_element(slot)) == ContactMode::stuck)
        broke.push_back(sys_.slot_element(slot));
    remember_gears();
    for (int slot : fired) {
      if (!sys_.slot_is_gear(slot)) continue;
      const int g = sys_.slot_element(slot);
      gears.push_back(g);
      // Its speed reached zero: decided at rest (the located time lies a rounding error past it).
      if (slot % 2 == 0 && sys_.gear_mode(g) != GearMode::stuck) sys_.stop_gear(g, y_.data());
    }
    handle_contact_event(t, fired);
    if (ng_ > 0) decide_gears(t, gears, false, broke);
  }

  void handle_contact_event(double t, const std::vector<int>& fired) {
    std::vector<int>& Z = Z_;  // kept: no allocation per event
    Z.clear();
    strict_.clear();
    rested_.clear();
    const double V_before = sys_.elastic_energy(y_.data()), drive_released = drive_released_;
    bool gap_changed = false, impacted = false;
    std::vector<ContactMode>& before = old_modes_;  // kept: no allocation per event
    before = sys_.contact_modes();
    for (int slot : fired) {
      const int e = sys_.slot_element(slot);
      if (sys_.slot_is_gear(slot)) continue;
      if (sys_.slot_is_drive(slot)) {  // an element's own event (a speed drive at its torque limit)
        const int now = sys_.drive(e).mode_after(sys_.drive_mode(e), slot % 2);
        set_drive_mode(e, t, sys_.settle_drive_mode(e, t, y_.data(), now), false, true);
      } else if (sys_.slot_is_link(slot)) {
        const GapMode old = sys_.gap_mode(e);
        const GapMode now = LinkLaw::mode_after(old, slot % 2);
        if (now == old) continue;
        const double V_old = link_elastic_energy(e);
        sys_.set_gap_mode(e, now);
        heat_.add_release(e, V_old - link_elastic_energy(e));  // the flank's share of the release loss
        gap_changed = true;
        record(t, now == GapMode::open ? "gap_opened" : "gap_closed", e, to_string(old), to_string(now));
      } else if (sys_.contact(e).stop && sys_.contact_mode(e) != ContactMode::stuck) {
        if (reached_at_rest(e, t)) {
          Z.push_back(e);  // no impact: at rest on the stop, decided with the others (no event if it stays free)
        } else {
          if (impact(e, t)) Z.push_back(e), rested_.push_back(e);  // at rest on the stop: decided with the others
          impacted = true;
        }
      } else if (sys_.contact_mode(e) != ContactMode::stuck) {
        Z.push_back(e);  // sliding speed reached zero
      } else {
        strict_.push_back(e);  // breakaway
      }
    }
    if (gap_changed)  // the elements' releases at this event are booked by set_drive_mode
      release_loss_ += V_before - sys_.elastic_energy(y_.data()) - (drive_released_ - drive_released);
    if (impacted) redecide_after_impact(t);
    for (int k = 0; k < nc_; ++k)
      if (decided_at_event(k, t)) Z.push_back(k);
    std::sort(Z.begin(), Z.end());
    Z.erase(std::unique(Z.begin(), Z.end()), Z.end());
    if (Z.empty()) {
      if (impacted) apply_contact_modes(t, before, sys_.contact_modes(), false);  // the slides the jump started
      return;
    }
    // A contact whose sliding speed reached zero is decided at zero speed: the located time lies a
    // rounding error past the crossing, so its u is set to exactly 0 first (a slide that goes on,
    // or reverses, then starts on its event function's zero, not past it).
    for (int k : Z)
      if (before[static_cast<size_t>(k)] != ContactMode::stuck) sys_.zero_sliding_velocity(k, t, y_.data());
    at_rest_together_closed(t, Z);
    std::vector<ContactMode>& now = new_modes_;  // kept, as old_modes_
    decide_contacts(sys_, t, y_.data(), Z, strict_, now);
    strict_.clear();
    apply_contact_modes(t, before, now, false);
    // An impact that brought its body to rest is an event even when the stop does not hold it (the
    // loads pull it off at once): the stuck ones are listed as their stick.
    for (int k : rested_)
      if (now[static_cast<size_t>(k)] != ContactMode::stuck)
        record(t, "impact", nl_ + k, to_string(before[static_cast<size_t>(k)]), to_string(now[static_cast<size_t>(k)]));
  }

  /// The elastic energy of link l at the run's state y_ in its current mode (elements/link.hpp), J.
  double link_elastic_energy(int l) const {
    const LinkLaw& k = sys_.link(l);
    return k.elastic_energy(sys_.link_kinematics(l, y_.data()).delta, sys_.gap_mode(l), k.drum(y_.data()));
  }

  // ---- releases (model.hpp: Release): the masses are run state ----
  /// Applies every release due at t (time ≤ t) not yet applied: the drive system's mass and weight,
  /// the kinetic energy the released part carries away, an event "release".
  void apply_releases(double t) {
    while (released_ < m_.releases.size() && m_.releases[released_].time <= t) {
      const Release& r = m_.releases[released_];
      const double before = sys_.inertia(r.body);
      out_.hybrid.energy.released_kinetic += sys_.apply_release(r, y_.data() + n_);
      const char* unit = m_.bodies[static_cast<size_t>(r.body)].kind == BodyKind::translational ? "kg" : "kg*m^2";
      out_.hybrid.events.push_back({t, "release", r.name, fmt::format("{:.6g} {}", before, unit),
                                    fmt::format("{:.6g} {}", sys_.inertia(r.body), unit)});
      ++released_;
      stages_.push_back(std::make_unique<Model>(model_after_releases(m_, released_)));
    }
  }
  /// The model after its first k releases (k = 0: the model itself).
  const Model& stage(size_t k) const { return k == 0 ? m_ : *stages_[k - 1]; }
  /// The model as the releases so far left it.
  const Model& now() const { return stage(released_); }

  void time_event(double t) {
    remember_gears();
    contact_time_event(t);
    if (ng_ > 0) decide_gears(t, {}, false);  // a load's jump may start or stop a gear
  }

  void contact_time_event(double t) {
    // The bodies tied by the stuck contacts on one velocity per cluster first (their u exactly 0, as
    // every decision leaves them): BDF's Newton corrections mix the states, so a stuck pair's speeds
    // drift apart by rounding over a piece, and a clutch applied beside a stuck one read u = 1e-17 and
    // was set sliding at u ≡ 0 instead of being decided at rest (`contact.locked_slide`).
    if (nc_ > 0) sys_.project_velocities(t, y_.data());
    // A jump of a speed reference may carry the command across the torque limit.
    for (int d = 0; d < nd_; ++d)
      if (sys_.drive(d).has_events()) set_drive_mode(d, t, sys_.natural_drive_mode(d, t, y_.data()), false);
    log_applications(t);
    std::vector<int> Z;
    for (int k = 0; k < nc_; ++k)
      if (decided_at_event(k, t)) Z.push_back(k);
    if (Z.empty()) return;
    const std::vector<ContactMode> old = sys_.contact_modes();
    at_rest_together_closed(t, Z);
    apply_contact_modes(t, old, decide_contacts(sys_, t, y_.data(), Z, strict_), false);
  }

  /// The applications and releases of brakes and clutches at t (a breakpoint of their signals): a
  /// brake or clutch applied now while it slides starts a slip phase (it was released so far); one
  /// released now ends its phase (its application reached 0: it opens). At every breakpoint, also
  /// one where an event is located: breakpoints closer than 1e-12 t_end are one (Model::breakpoints),
  /// so a normal force falling to 0 an ulp before a table's point is already 0 at the merged
  /// breakpoint's left limit, and the stuck clutch's breakaway is located on the breakpoint itself.
  void log_applications(double t) {
    for (int k = 0; k < nc_; ++k) {
      const ContactMode md = sys_.contact_mode(k);
      const bool was = was_released_[static_cast<size_t>(k)] != 0, now = released(k, t);
      was_released_[static_cast<size_t>(k)] = now;
      if (was == now) continue;
      if (md == ContactMode::stuck) {  // a holding clutch opens: no slip phase to end
        if (now) record(t, "released", nl_ + k, to_string(md), "released");
        continue;
      }
      if (!now && open_phase_[static_cast<size_t>(k)] < 0) {
        // Applied while it slides: its label (no events while released) takes the direction of u; at
        // u = 0 it is decided with the others below — so also at a u within the integrator's
        // resolution of the speeds, put on 0 first (at_rest_to_resolution).
        if (at_rest_to_resolution(k, t)) sys_.zero_sliding_velocity(k, t, y_.data());
        const double u = sys_.sliding_velocity(k, t, y_.data());
        const ContactMode dir = u > 0.0 ? ContactMode::slip_pos : ContactMode::slip_neg;
        if (u != 0.0 && dir != md) {
          std::vector<ContactMode> modes = sys_.contact_modes();
          modes[static_cast<size_t>(k)] = dir;
          sys_.set_contact_modes(modes);
        }
        if (u == 0.0) {  // decided below: stuck silently (as it rested), or "applied" into a slide
          applied_at_rest_[static_cast<size_t>(k)] = 1;
          continue;
        }
        record(t, "applied", nl_ + k, "released", to_string(dir));
        open_phase(k, t, dir);
      } else if (now) {
        record(t, "released", nl_ + k, to_string(md), "released");
        close_phase(k, t);
      }
    }
  }

  /// Whether contact k's u at t is 0 within the integrator's resolution of its bodies' speeds over
  /// the run, 1e3 (atol + rtol (|v_a| + |v_b|)) — the error control's bound per step accumulated (the
  /// audit's global resolution), so no motion the run resolves. A u below it is rounding or drift
  /// (bodies held at rest or stuck together carry 1e-17 m/s from their stuck solve or a projection; an
  /// unloaded sun and carrier beside a held ring drift to 5e-12 rad/s): taken as a slide, a brake
  /// applied there or a stuck pair beside an impact slid and stuck again, two events that are none
  /// (campaign `mixed` seed 1 models 94 and 1, `planetary` seed 2 model 31).
  bool at_rest_to_resolution(int k, double t) const {
    const ContactLaw& c = sys_.contact(k);
    if (c.general || c.kinematic) return false;  // a joint's member or a prescribed motion: by u alone
    const double va = y_[static_cast<size_t>(n_ + c.a)], vb = c.b >= 0 ? y_[static_cast<size_t>(n_ + c.b)] : c.surface_velocity(t);
    return std::abs(va - vb) <= 1e3 * (m_.simulation.atol + m_.simulation.rtol * (std::abs(va) + std::abs(vb)));
  }
  /// Every contact of Z is at zero sliding speed at t: the velocities are projected onto u = 0 for
  /// all of them at once (with the stuck ones), so that each starts its new mode exactly on u = 0 —
  /// a slide from rest on its event function's zero, not at ±1e-20 beside it where the projection
  /// of a stuck neighbour alone would leave it (its event function negative at the restart).
  void at_rest_together(double t, const std::vector<int>& Z) {
    if (sys_.has_coupled_gears()) return;  // their contacts are settled with the gears
    std::vector<ContactMode>& rest = rest_modes_;  // kept: no allocation per event
    rest = sys_.contact_modes();
    for (int k : Z) rest[static_cast<size_t>(k)] = ContactMode::stuck;
    if (rest != sys_.contact_modes()) sys_.set_contact_modes(rest);
    sys_.project_velocities(t, y_.data());
  }

  /// at_rest_together, with Z closed over the friction contacts its projection brings to rest: a
  /// sliding contact whose bodies the stuck rows of Z tie (its u exactly 0 after the projection, not
  /// before) cannot slide (u ≡ 0) and is decided with them. A contact stopping at an event (BDF: f0
  /// on b1, its u crossing 0) beside a stuck clutch to b2, where f1 slid on b2 at the drift of the
  /// clutch's pair, 1e-13 m/s: f1 was left out of Z, kept sliding at u ≡ 0 beside the set that locks
  /// it (`contact.locked_slide`, campaign `signals` seed 1 #78). Two-sided friction only: a
  /// freewheel overrunning at u ≡ 0 without load is a consistent mode of its own (the reference
  /// keeps it), not a locked slide.
  void at_rest_together_closed(double t, std::vector<int>& Z) {
    for (;;) {
      at_rest_together(t, Z);
      const size_t before = Z.size();
      for (int k = 0; k < nc_; ++k) {
        const ContactLaw& c = sys_.contact(k);
        if (c.lock == 0 && !c.joint && !c.kinematic &&
            !std::binary_search(Z.begin(), Z.begin() + static_cast<std::ptrdiff_t>(before), k) && decided_at_event(k, t))
          Z.push_back(k);
      }
      if (Z.size() == before) return;
      std::sort(Z.begin(), Z.end());
    }
  }

  const Model& m_;
  const SimulateOptions& opt_;
  OutputSelection extra_;
  const Stepper* step_ = nullptr;  // the stepper of the current step (heat of an open piece)
  std::vector<double> p_, q_, temperature_;  // heat power, heat, temperatures at an output row
  SimulationResult& out_;
  DriveSystem sys_;
  /// Per merged gear, the drives on its side S (by the body the file names; S never holds the master).
  std::vector<std::vector<int>> merged_drives_ = [this] {
    std::vector<std::vector<int>> out;
    for (const MergedGear& g : m_.merged_gears) {
      out.emplace_back();
      for (size_t d = 0; d < m_.drives.size(); ++d)
        if (std::find(g.side.begin(), g.side.end(), m_.drives[d].given_body) != g.side.end())
          out.back().push_back(static_cast<int>(d));
    }
    return out;
  }();
  detail::MachineJumps jumps_;
  detail::Heat heat_;
  int n_, N_, nl_, nc_, nd_, ng_;
  bool has_events_ = false;
  bool jump_events_ = false;  // stepwise gears' jump functions follow the drive system's (event_functions)
  bool plain_rows_ = false;  // the output rows hold t, the states and the link loads only
  bool tail_groups_ = false;  // some column group after the gap modes (drives … extra outputs)
  bool contact_rows_ = false;  // the rows end with the contacts and gap modes (output_contacts)
  bool extremes_only_ = false;  // a piece has only the extremes to follow (on_segment)
  size_t row_ = 0, row_cap_ = 0;  // output rows written, rows the columns hold
  size_t row_fast_end_ = 0;       // on_output's rows below it need no test (row_cap_; 0 with observers of the rows)  // some element has an event function (else event_count() is 0)
  PeakTracker peaks_;
  PeakTracker::NewMax on_new_max_;
  std::vector<size_t> varying_;     // indices of the loads that depend on t or v
  std::vector<int> machine_bodies_;
  std::vector<Extreme> at_max_, at_min_;  // force ingredients at each link's extremes
  std::vector<double> extreme_acc_, extreme_fc_;  // scratch of contact_forces(): a released brake's λ
  std::vector<double> y_, acc_, fc_;
  std::vector<double> loads_;                // the link loads of an output row
  std::vector<double*> col_;                 // the columns' data (point_columns)
  std::vector<int> gap_links_, rope_links_;  // links with a gap-mode column, ropes with fall columns
  std::vector<int> flank_links_;  // links with flanks (LinkLaw::gap: gaps, ropes, one-sided links, buffers)
  std::vector<int> winding_links_;             // ropes wound on a drum (check_rope_ends)
  double last_t_ = 0.0;                        // the last rhs evaluation (state_name)
  const double* last_y_ = nullptr;
  std::vector<double> rope_q_;                 // scratch of check_rope_ends
  std::vector<size_t> drive_cols_;           // per element with states: its own output columns
  std::vector<double> drive_vals_;           // their values at an output row
  std::vector<int> open_phase_;
  std::vector<char> applied_at_rest_ = std::vector<char>(static_cast<size_t>(nc_), 0);  // per contact: applied at u = 0 now
  std::vector<char> was_released_;  // per contact: released at the last time event (or t = 0)
  std::vector<int> phase_window_;  // per contact: its open slip phase's window in peaks_
  std::vector<std::vector<double>> switches_;
  static constexpr int kMaxRedecisions = 8;  // handle_events: decisions at one instant before giving up
  double decided_at_ = std::numeric_limits<double>::quiet_NaN();  // the instant of the last decision
  int redecisions_ = 0;                                             // and how often it was decided again
  std::vector<int> rested_;  // handle_contact_event: end stops an impact brought to rest
  std::vector<int> from_rest_;  // apply_contact_modes: the slides starting at u = 0
  std::vector<std::vector<double>> impact_times_;  // per contact: the last impacts of a stop (impacts_accumulate)
  std::vector<char> impact_ties_;                  // per contact: may carry an impact's impulse (not a gear's)
  std::vector<int> strict_;  // stuck contacts whose limit event fired
  std::vector<int> own_;     // handle_events: the fired slots of the drive system
  std::vector<int> Z_;       // handle_contact_event: the contacts decided
  std::vector<int> broke_;   // handle_event: the stuck contacts whose breakaway fired
  std::vector<ContactMode> old_modes_, new_modes_, rest_modes_;  // handle_contact_event: their modes before and after
  std::chrono::steady_clock::time_point start_;
  long progress_steps_ = 0, initial_events_ = 0;
  double next_progress_ = 0.0;
  double release_loss_ = 0.0;
  double drive_released_ = 0.0;  // the part of release_loss_ elements released at their switches
  size_t released_ = 0;                        // releases applied so far (Model::releases order)
  std::vector<std::unique_ptr<Model>> stages_;  // the model after 1, 2, … releases
  std::vector<int> released_bodies_ = released_bodies(m_);  // their mass columns
  std::vector<double> acc_rows_;  // accelerations at the output rows (machines only)
  std::unique_ptr<Audit> audit_;  // the invariant audit, when SimulateOptions::check (else none)
  std::unique_ptr<SwayObserver> sway_;  // the spatial ropes' sway summary (none without a spatial rope)
  bool step_watch_ = false;             // audit_ or a progress report: on_step goes through on_step_rest()
  bool observed_rows_ = false;          // audit_ or sway_: on_output goes through output_observed()
};

}  // namespace

SimulationResult simulate(const Model& m) { return simulate(m, SimulateOptions{}); }

OutputSelection output_selection(const std::vector<std::string>& groups) {
  OutputSelection s;
  for (const auto& g : groups) {
    if (g == "deflection") s.deflection = true;
    else if (g == "acceleration") s.acceleration = true;
    else if (g == "power") s.power = true;
    else if (g == "heat") s.heat = true;
    else if (g == "all") s.deflection = s.acceleration = s.power = s.heat = true;
    else
      throw InputError(Location{"--outputs", 0, 0},
                       fmt::format("unknown output group '{}'; expected deflection, acceleration, power, heat or all", g));
  }
  return s;
}

std::size_t extra_columns_bound(const Model& m, const OutputSelection& s) {
  std::size_t n = 0;
  if (s.deflection) n += 2 * m.links.size();
  if (s.acceleration) n += m.bodies.size();
  if (s.power) n += m.loads.size() + m.drives.size() + m.links.size();
  if (s.heat) n += 2 * (m.contacts.size() + m.links.size() + m.lossy_gears.size() + m.drives.size() + 1);
  return n;
}

SimulationResult simulate(const Model& m, const SimulateOptions& options, const OutputSelection& extra) {
  if (m.simulation.initial == InitialState::equilibrium) return simulate(with_equilibrium_start(m), options, extra);
  // Compile bounded the standard grid by kMaxOutputBytes; the extra columns widen every row.
  const double base = static_cast<double>(output_columns_bound(m));
  const double bytes = output_bytes_bound(m) * (base + static_cast<double>(extra_columns_bound(m, extra))) / base;
  if (options.record_series && bytes > kMaxOutputBytes)
    throw InputError(Location{"--outputs", 0, 0},
                     fmt::format("the output with these groups needs {:.3g} GB in memory, more than the limit of {:.3g} "
                                 "GB; raise 'simulation.dt_out', shorten 't_end' or choose fewer groups",
                                 bytes / 1e9, kMaxOutputBytes / 1e9));
  SimulationResult out;
  DriveRun run(m, options, out, extra);
  run.run();
  return out;
}

SimulationResult simulate(const Model& m, const SimulateOptions& options, const LinkValueSink& link_values) {
  if (m.simulation.initial == InitialState::equilibrium)
    return simulate(with_equilibrium_start(m), options, link_values);
  SimulationResult out;
  DriveRun run(m, options, out);
  if (link_values) run.set_link_values(link_values);
  run.run();
  return out;
}

SimulationResult simulate(const Model& m, const SimulateOptions& options) {
  // `initial: equilibrium`: the same run from the static equilibrium at t = 0 (analysis/equilibrium.hpp).
  if (m.simulation.initial == InitialState::equilibrium) return simulate(with_equilibrium_start(m), options);
  SimulationResult out;
  DriveRun run(m, options, out);
  run.run();
  return out;
}

}  // namespace machdyn
