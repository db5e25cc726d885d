// The hybrid simulation as an event system of the one driver (solve/driver.hpp): its event
// functions and breakpoints, the decision of the new modes of all elements together at an event,
// and the observers (outputs, peaks, slip phases, energy books, progress).
#include "machdyn/analysis/hybrid.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <fmt/format.h>

#include "machdyn/analysis/machine_outputs.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/solve/driver.hpp"
#include "machdyn/solve/roots.hpp"

namespace machdyn {
namespace {

class HybridRun final : public EventSystem, public StepObserver {
 public:
  HybridRun(const Model& m, const HybridOptions& opt, SimulationResult& out)
      : m_(m), opt_(opt), out_(out), sys_(m), n_(m.dof()), N_(sys_.size()), nl_(static_cast<int>(m.links.size())),
        nc_(static_cast<int>(m.contacts.size())) {
    y_.assign(static_cast<size_t>(N_), 0.0);
    ytmp_ = dtmp_ = ya_ = yb_ = da_ = db_ = y_;
    acc_.assign(static_cast<size_t>(n_), 0.0);
    fc_.assign(static_cast<size_t>(nc_), 0.0);
    open_phase_.assign(static_cast<size_t>(nc_), -1);
    switches_.resize(static_cast<size_t>(nl_ + nc_));
    peak_.resize(static_cast<size_t>(nl_));
    rate_end_.assign(static_cast<size_t>(nl_), 0.0);
    setup_columns();
  }

  void run() {
    const auto start = std::chrono::steady_clock::now();
    const auto& s = m_.simulation;
    out_.hybrid.active = true;
    out_.hybrid.breakpoints = m_.breakpoints(s.t_end);
    const Method method = choose_method(m_, &out_.method_reason);
    sys_.initial_state(y_.data());
    initial_modes();
    initial_events_ = static_cast<long>(out_.hybrid.events.size());
    auto& E = out_.hybrid.energy;
    E.kinetic_start = sys_.kinetic_energy(y_.data());
    E.elastic_start = sys_.elastic_energy(y_.data());

    StepperOptions so;
    so.rtol = s.rtol;
    so.atol = s.atol;
    so.max_steps = s.max_steps;
    auto stepper = make_stepper(method, *this, so);
    Stepper& st = *stepper;
    DriveOptions drive;
    drive.dt_out = s.dt_out;
    drive.outputs = opt_.record_series;
    const double t_end = s.t_end;
    start_ = start;
    out_.stats = integrate(st, *this, 0.0, y_.data(), t_end, drive, *this);
    std::copy(st.y(), st.y() + N_, y_.begin());
    // Close the books.
    for (int k = 0; k < nc_; ++k) close_phase(k, t_end);
    E.kinetic_end = sys_.kinetic_energy(y_.data());
    E.elastic_end = sys_.elastic_energy(y_.data());
    E.source_work = y_[static_cast<size_t>(2 * n_)];
    E.friction_loss = y_[static_cast<size_t>(2 * n_ + 1)];
    E.damping_loss = y_[static_cast<size_t>(2 * n_ + 2)];
    E.release_loss = release_loss_;
    summarize_links();
    if (machines_)  // I(q), ε, inertia moments, output points (analysis/machine_outputs.hpp)
      append_machine_outputs(
          m_, out_,
          [&](size_t row, const double*, double* acc) {
            std::copy_n(acc_rows_.begin() + static_cast<long>(row) * n_, n_, acc);
          },
          {});
    out_.stats.wall_time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    report_progress(st, start, true);
  }

  // ---- the event system the driver integrates: HybridSystem in its current modes ----
  [[nodiscard]] int size() const override { return sys_.size(); }
  void rhs(double t, const double* y, double* dydt) override { sys_.rhs(t, y, dydt); }
  [[nodiscard]] std::string state_name(int i) const override { return sys_.state_name(i); }
  [[nodiscard]] int event_count() const override { return sys_.event_slots(); }
  void event_functions(double t, const double* y, double* g) override { sys_.event_functions(t, y, g); }
  [[nodiscard]] std::vector<double> breakpoints(double, double) const override { return out_.hybrid.breakpoints; }
  bool handle_events(double t, double* y, const std::vector<int>& fired) override {
    std::copy(y, y + N_, y_.begin());
    if (fired.empty())
      time_event(t);
    else
      handle_event(t, fired);
    std::copy(y_.begin(), y_.end(), y);
    return true;
  }

  // ---- the observer of the driver ----
  void on_step(const Stepper& st) override { report_progress(st, start_, false); }
  void on_segment(const Stepper& st, double ta, double tb) override { segment(st, ta, tb); }
  void on_output(double t, const double* y) override { output(t, y); }
  void on_event(double, const double*, const std::vector<int>&) override { seg_end_ = -1.0; }

 private:
  // ---- output ----
  void setup_columns() {
    auto& names = out_.column_names;
    names = chain_column_names(m_);
    for (const auto& c : m_.contacts) {
      const BodyKind k = m_.bodies[static_cast<size_t>(c.a)].kind;
      names.push_back(c.name + ".force_" + unit_suffix(load_unit(k)));
      names.push_back(c.name + ".sliding_velocity_" + unit_suffix(velocity_unit(k)));
      names.push_back(c.name + ".mode");
    }
    for (const auto& l : m_.links)
      if (l.has_gap) names.push_back(l.name + ".gap_mode");
    out_.columns.resize(names.size());
  }

  void output(double t, const double* y) {
    size_t c = 0;
    auto& cols = out_.columns;
    cols[c++].push_back(t);
    for (int i = 0; i < n_; ++i) {
      cols[c++].push_back(y[i]);
      cols[c++].push_back(y[n_ + i]);
    }
    for (int l = 0; l < nl_; ++l) cols[c++].push_back(sys_.link_load(l, y));
    if (nc_ > 0 || machines_) sys_.evaluate(t, y, acc_.data(), fc_.data());
    if (machines_) acc_rows_.insert(acc_rows_.end(), acc_.begin(), acc_.end());  // for the machine series
    for (int k = 0; k < nc_; ++k) {
      cols[c++].push_back(fc_[static_cast<size_t>(k)]);
      cols[c++].push_back(sys_.sliding_velocity(k, t, y));
      cols[c++].push_back(static_cast<double>(static_cast<int>(sys_.contact_mode(k))));
    }
    for (int l = 0; l < nl_; ++l)
      if (m_.links[static_cast<size_t>(l)].has_gap)
        cols[c++].push_back(static_cast<double>(static_cast<int>(sys_.gap_mode(l))));
  }

  // ---- the solution on [ta, tb] inside the last step, in the current modes ----
  void segment(const Stepper& st, double ta, double tb) {
    if (nl_ == 0) return;
    // The start of a step that continues the last one was already seen: reuse its state and rate.
    const bool continued = ta == seg_end_;
    if (!continued) {
      st.interpolate(ta, ya_.data());
      st.derivative(ta, da_.data());
    }
    const double* yb = st.y();
    const double* db = st.dydt();
    if (tb != st.t()) {
      st.interpolate(tb, yb_.data());
      st.derivative(tb, db_.data());
      yb = yb_.data(), db = db_.data();
    }
    for (int l = 0; l < nl_; ++l) {
      if (!continued) consider(l, ta, sys_.link_load(l, ya_.data()), ya_.data());
      consider(l, tb, sys_.link_load(l, yb), yb);
      double r0 = continued ? rate_end_[static_cast<size_t>(l)] : sys_.link_load_rate(l, ya_.data(), da_.data());
      double r1 = sys_.link_load_rate(l, yb, db);
      rate_end_[static_cast<size_t>(l)] = r1;
      if (!((r0 > 0 && r1 < 0) || (r0 < 0 && r1 > 0))) continue;
      // The interior extremum: where the load rate changes sign (solve/roots.hpp).
      const Bracket br = illinois(
          [&](double tm) {
            st.derivative(tm, dtmp_.data());
            if (sys_.link_uses_point(l)) st.interpolate(tm, ytmp_.data());  // the rate depends on q there
            return sys_.link_load_rate(l, ytmp_.data(), dtmp_.data());
          },
          ta, r0, tb, r1, 1e-15 * std::max(1.0, std::abs(tb)), 100, /*bisect_every=*/0);  // a smooth rate
      const double te = 0.5 * (br.lo + br.hi);
      st.interpolate(te, ytmp_.data());
      consider(l, te, sys_.link_load(l, ytmp_.data()), ytmp_.data());
    }
    // Only a segment that ends a whole step can be continued by the next step.
    seg_end_ = tb == st.t() ? tb : -1.0;
  }

  struct Peak {
    bool started = false;
    double max = 0, min = 0, t_max = 0, t_min = 0;
    std::vector<double> f_at_max, f_at_min;  // external generalized forces at t_max, t_min
    // The state and contact modes at t_max and t_min (forces are formed once, at the end).
    std::vector<double> y_max, y_min;
    std::vector<ContactMode> modes_max, modes_min;
  };

  void forces_at(double t, const std::vector<double>& y, const std::vector<ContactMode>& modes, std::vector<double>& f) {
    f.assign(static_cast<size_t>(n_), 0.0);
    if (y.empty()) return;
    const std::vector<ContactMode> keep = sys_.contact_modes();
    sys_.set_contact_modes(modes);
    sys_.external_forces(t, y.data(), f.data());
    sys_.set_contact_modes(keep);
  }

  void consider(int l, double t, double F, const double* y) {
    Peak& p = peak_[static_cast<size_t>(l)];
    if (!p.started || F > p.max) {
      p.max = F, p.t_max = t;
      p.y_max.assign(y, y + N_);
      p.modes_max = sys_.contact_modes();
    }
    if (!p.started || F < p.min) {
      p.min = F, p.t_min = t;
      p.y_min.assign(y, y + N_);
      p.modes_min = sys_.contact_modes();
    }
    p.started = true;
    for (int k = 0; k < nc_; ++k) {
      const int ph = open_phase_[static_cast<size_t>(k)];
      if (ph < 0) continue;
      SlipPhase& s = out_.hybrid.slip_phases[static_cast<size_t>(ph)];
      const size_t li = static_cast<size_t>(l);
      if (F > s.link_max[li]) s.link_max[li] = F, s.link_t_max[li] = t;
      s.link_min[li] = std::min(s.link_min[li], F);
    }
  }

  void summarize_links() {
    const Modes modes = compute_modes(m_);
    for (int l = 0; l < nl_; ++l) {
      Peak& p = peak_[static_cast<size_t>(l)];
      forces_at(p.t_max, p.y_max, p.modes_max, p.f_at_max);
      forces_at(p.t_min, p.y_min, p.modes_min, p.f_at_min);
      LinkSummary s;
      s.max = p.max, s.min = p.min, s.t_max = p.t_max, s.t_min = p.t_min;
      const Eigen::VectorXd F =
          static_link_loads(m_, modes, Eigen::Map<const Eigen::VectorXd>(p.f_at_max.data(), n_));
      s.static_at_max = F(l);
      s.static_at_min = static_link_loads(m_, modes, Eigen::Map<const Eigen::VectorXd>(p.f_at_min.data(), n_))(l);
      set_peak(s);
      out_.links.push_back(s);
    }
  }

  // ---- events ----
  /// Progress: the clock is read every 32 steps only; a report at most every progress_interval_s.
  void report_progress(const Stepper& st, std::chrono::steady_clock::time_point start, bool finished) {
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
    p.events = static_cast<long>(out_.hybrid.events.size()) - initial_events_;
    p.wall_s = wall;
    p.finished = finished;
    opt_.progress(p);
  }

  const std::string& element_name(int e) const {
    return e < nl_ ? m_.links[static_cast<size_t>(e)].name : m_.contacts[static_cast<size_t>(e - nl_)].name;
  }

  void record(double t, const char* kind, int element, const char* from, const char* to) {
    out_.hybrid.events.push_back({t, kind, element_name(element), from, to});
    if (std::string_view(kind) == "initial") return;
    if (static_cast<long>(out_.hybrid.events.size()) > opt_.max_events)
      throw SolverError(element_name(element), t,
                        fmt::format("more than {} mode events; raise max_events or check the model", opt_.max_events));
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
  bool released(int k, double t) const {
    const FrictionContact& c = m_.contacts[static_cast<size_t>(k)];
    return c.brake && t < c.t_apply;
  }

  void open_phase(int k, double t, ContactMode md) {
    if (released(k, t)) return;
    SlipPhase p;
    p.contact = m_.contacts[static_cast<size_t>(k)].name;
    p.direction = static_cast<int>(md);
    p.t_start = p.t_end = t;
    p.link_max.assign(static_cast<size_t>(nl_), -std::numeric_limits<double>::infinity());
    p.link_t_max.assign(static_cast<size_t>(nl_), t);
    p.link_min.assign(static_cast<size_t>(nl_), std::numeric_limits<double>::infinity());
    for (int l = 0; l < nl_; ++l) p.link_start.push_back(sys_.link_load(l, y_.data()));
    out_.hybrid.slip_phases.push_back(p);
    open_phase_[static_cast<size_t>(k)] = static_cast<int>(out_.hybrid.slip_phases.size()) - 1;
  }

  void close_phase(int k, double t) {
    int& ph = open_phase_[static_cast<size_t>(k)];
    if (ph < 0) return;
    SlipPhase& p = out_.hybrid.slip_phases[static_cast<size_t>(ph)];
    p.t_end = t;
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

  /// |λ| within the static limit. A contact whose limit event just fired is judged strictly (the
  /// event located the crossing on this very function); the others get a rounding allowance, so a
  /// load exactly at the limit holds.
  bool stuck_ok(int k, double t) const {
    const FrictionContact& c = m_.contacts[static_cast<size_t>(k)];
    const double Fs = c.scale(t) * c.static_limit, F = std::abs(fc_[static_cast<size_t>(k)]);
    if (std::find(strict_.begin(), strict_.end(), k) != strict_.end()) return F <= Fs;
    return F <= Fs + 1e-12 * c.static_limit;
  }
  double sliding_accel(int k, double t) const {
    const FrictionContact& c = m_.contacts[static_cast<size_t>(k)];
    return acc_[static_cast<size_t>(c.a)] - (c.b >= 0 ? acc_[static_cast<size_t>(c.b)] : c.surface_acceleration(t));
  }
  bool consistent(const std::vector<ContactMode>& modes, const std::vector<int>& Z, double t) {
    sys_.set_contact_modes(modes);
    sys_.evaluate(t, y_.data(), acc_.data(), fc_.data());
    for (int k : Z) {
      const ContactMode md = modes[static_cast<size_t>(k)];
      if (md == ContactMode::stuck ? !stuck_ok(k, t)
                                   : static_cast<double>(static_cast<int>(md)) * sliding_accel(k, t) < 0.0)
        return false;
    }
    return true;
  }

  /// The modes of the contacts in Z (zero sliding speed) at (t, y_), decided together.
  std::vector<ContactMode> decide_contacts(double t, const std::vector<int>& Z) {
    std::vector<ContactMode> modes = sys_.contact_modes();
    for (int k : Z) modes[static_cast<size_t>(k)] = ContactMode::stuck;
    // Release the most overloaded stuck contact until the stuck set holds.
    for (size_t round = 0; round <= Z.size(); ++round) {
      sys_.set_contact_modes(modes);
      sys_.evaluate(t, y_.data(), acc_.data(), fc_.data());
      int worst = -1;
      double worst_ratio = 1.0;
      for (int k : Z) {
        if (modes[static_cast<size_t>(k)] != ContactMode::stuck || stuck_ok(k, t)) continue;
        const FrictionContact& c = m_.contacts[static_cast<size_t>(k)];
        const double Fs = c.scale(t) * c.static_limit;
        const double ratio = Fs > 0 ? std::abs(fc_[static_cast<size_t>(k)]) / Fs : std::numeric_limits<double>::infinity();
        if (worst < 0 || ratio > worst_ratio) worst = k, worst_ratio = ratio;
      }
      if (worst < 0) break;
      modes[static_cast<size_t>(worst)] = fc_[static_cast<size_t>(worst)] > 0 ? ContactMode::slip_pos : ContactMode::slip_neg;
    }
    if (consistent(modes, Z, t)) return modes;
    // Every combination, fewest sliding contacts first, then in index order.
    if (Z.size() > 10)
      throw SolverError(m_.contacts[static_cast<size_t>(Z[0])].name, t,
                        "no consistent stick/slip modes found for more than 10 contacts at rest at once");
    long total = 1;
    for (size_t i = 0; i < Z.size(); ++i) total *= 3;
    std::vector<long> codes(static_cast<size_t>(total));
    for (long c = 0; c < total; ++c) codes[static_cast<size_t>(c)] = c;
    auto sliding = [&](long c) {
      int s = 0;
      for (size_t i = 0; i < Z.size(); ++i, c /= 3) s += c % 3 != 0;
      return s;
    };
    std::stable_sort(codes.begin(), codes.end(), [&](long x, long y) { return sliding(x) < sliding(y); });
    for (long code : codes) {
      long c = code;
      for (size_t i = 0; i < Z.size(); ++i, c /= 3)
        modes[static_cast<size_t>(Z[i])] = c % 3 == 0 ? ContactMode::stuck : c % 3 == 1 ? ContactMode::slip_pos : ContactMode::slip_neg;
      if (consistent(modes, Z, t)) return modes;
    }
    std::string names;
    for (int k : Z) names += (names.empty() ? "" : "', '") + m_.contacts[static_cast<size_t>(k)].name;
    throw SolverError(names, t, "no consistent stick/slip modes (the contacts' static limits contradict)");
  }

  void apply_contact_modes(double t, const std::vector<ContactMode>& old_modes, const std::vector<ContactMode>& modes,
                           bool initial) {
    sys_.set_contact_modes(modes);
    for (int k = 0; k < nc_; ++k) {
      const ContactMode a = old_modes[static_cast<size_t>(k)], b = modes[static_cast<size_t>(k)];
      if (!initial && a == b) continue;
      const char* kind = initial ? "initial" : b == ContactMode::stuck ? "stick" : a == ContactMode::stuck ? "slip" : "reversal";
      record(t, kind, nl_ + k, initial ? "" : released(k, t) ? "released" : to_string(a),
             released(k, t) ? "released" : to_string(b));
      close_phase(k, t);
      if (b != ContactMode::stuck) open_phase(k, t, b);
    }
    sys_.project_velocities(t, y_.data());
  }

  void initial_modes() {
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
      if (u == 0.0) Z.push_back(k);
      else modes[static_cast<size_t>(k)] = u > 0 ? ContactMode::slip_pos : ContactMode::slip_neg;
    }
    sys_.set_contact_modes(modes);
    if (!Z.empty()) modes = decide_contacts(0.0, Z);
    apply_contact_modes(0.0, modes, modes, true);
  }

  void handle_event(double t, const std::vector<int>& fired) {
    std::vector<int> Z;
    strict_.clear();
    const double V_before = sys_.elastic_energy(y_.data());
    bool gap_changed = false;
    for (int slot : fired) {
      const int e = sys_.slot_element(slot);
      if (sys_.slot_is_link(slot)) {
        const GapMode old = sys_.gap_mode(e);
        GapMode now = old != GapMode::open ? GapMode::open : (slot % 2 == 0 ? GapMode::closed_pos : GapMode::closed_neg);
        if (now == old) continue;
        sys_.set_gap_mode(e, now);
        gap_changed = true;
        record(t, now == GapMode::open ? "gap_opened" : "gap_closed", e, to_string(old), to_string(now));
      } else if (sys_.contact_mode(e) != ContactMode::stuck) {
        Z.push_back(e);  // sliding speed reached zero
      } else {
        strict_.push_back(e);  // breakaway
      }
    }
    if (gap_changed) release_loss_ += V_before - sys_.elastic_energy(y_.data());
    for (int k = 0; k < nc_; ++k)
      if (sys_.contact_mode(k) == ContactMode::stuck) Z.push_back(k);
    std::sort(Z.begin(), Z.end());
    Z.erase(std::unique(Z.begin(), Z.end()), Z.end());
    if (Z.empty()) return;
    const std::vector<ContactMode> old = sys_.contact_modes();
    // A contact whose sliding speed reached zero is decided at zero speed: the located time lies a
    // rounding error past the crossing, so its u is set to exactly 0 first (a slide that goes on,
    // or reverses, then starts on its event function's zero, not past it).
    for (int k : Z)
      if (old[static_cast<size_t>(k)] != ContactMode::stuck) sys_.zero_sliding_velocity(k, t, y_.data());
    const std::vector<ContactMode> now = decide_contacts(t, Z);
    strict_.clear();
    apply_contact_modes(t, old, now, false);
  }

  void time_event(double t) {
    // A brake applied now while its body moves starts a slip phase (it was released so far).
    for (int k = 0; k < nc_; ++k) {
      const FrictionContact& c = m_.contacts[static_cast<size_t>(k)];
      const ContactMode md = sys_.contact_mode(k);
      if (c.brake && t == c.t_apply && md != ContactMode::stuck && open_phase_[static_cast<size_t>(k)] < 0) {
        record(t, "applied", nl_ + k, "released", to_string(md));
        open_phase(k, t, md);
      }
    }
    std::vector<int> Z;
    for (int k = 0; k < nc_; ++k)
      if (sys_.contact_mode(k) == ContactMode::stuck) Z.push_back(k);
    if (Z.empty()) return;
    const std::vector<ContactMode> old = sys_.contact_modes();
    apply_contact_modes(t, old, decide_contacts(t, Z), false);
  }

  const Model& m_;
  const HybridOptions& opt_;
  SimulationResult& out_;
  HybridSystem sys_;
  int n_, N_, nl_, nc_;
  std::vector<double> y_, ytmp_, dtmp_, ya_, yb_, da_, db_, acc_, fc_;
  double seg_end_ = -1.0;          // end of the last segment if the next step continues it, else −1
  std::vector<double> rate_end_;   // link-load rates there
  std::vector<int> open_phase_;
  std::vector<std::vector<double>> switches_;
  std::vector<Peak> peak_;
  std::vector<int> strict_;  // stuck contacts whose limit event fired
  std::chrono::steady_clock::time_point start_;
  long progress_steps_ = 0, initial_events_ = 0;
  double next_progress_ = 0.0;
  double release_loss_ = 0.0;
  bool machines_ = has_machines(m_);
  std::vector<double> acc_rows_;  // accelerations at the output rows (machines only)
};

}  // namespace

SimulationResult simulate_hybrid(const Model& m, const HybridOptions& options) {
  SimulationResult out;
  HybridRun run(m, options, out);
  run.run();
  return out;
}

}  // namespace machdyn
