#include "machdyn/analysis/simulate.hpp"

#include <chrono>
#include <cmath>
#include <limits>
#include <map>
#include <fmt/format.h>

#include "machdyn/analysis/chain_system.hpp"
#include "machdyn/analysis/hybrid.hpp"
#include "machdyn/analysis/static_loads.hpp"
#include "machdyn/analysis/machine_outputs.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/peak_tracker.hpp"
#include "machdyn/model/machine.hpp"
#include "analysis/machine_run.hpp"

namespace machdyn {

Method choose_method(const Model& m, std::string* reason) {
  const auto& s = m.simulation;
  if (s.integrator == IntegratorChoice::dopri5) {
    if (reason) *reason = "chosen in the model file";
    return Method::dopri5;
  }
  if (s.integrator == IntegratorChoice::bdf) {
    if (reason) *reason = "chosen in the model file";
    return Method::bdf;
  }
  // Gershgorin bounds from the links, O(n): ρ_D ≥ every damping rate of M⁻¹D, ω_K ≥ ω_max.
  std::vector<double> rowD(static_cast<size_t>(m.dof()), 0.0), rowK(rowD);
  for (const auto& l : m.links) {
    const int idx[2] = {l.a, l.b};
    const double w[2] = {1.0 / l.ratio, 1.0};
    for (int r = 0; r < 2; ++r) {
      if (idx[r] < 0) continue;
      for (int k = 0; k < 2; ++k) {
        if (idx[k] < 0) continue;
        rowD[static_cast<size_t>(idx[r])] += l.d * std::abs(w[r] * w[k]);
        rowK[static_cast<size_t>(idx[r])] += l.c * std::abs(w[r] * w[k]);
      }
    }
  }
  // A kinetic friction table rising with the sliding speed acts as a damper of its steepest rising
  // slope while the contact slides (dF_k/du: 7e9 N·s/m for 0.2 → 0.9 of 10 N over 1e-9 m/s).
  for (const auto& c : m.contacts) {
    double slope = 0.0;
    for (size_t i = 0; i + 1 < c.speeds.size() && i + 1 < c.kinetic.size(); ++i)
      slope = std::max(slope, (c.kinetic[i + 1] - c.kinetic[i]) / (c.speeds[i + 1] - c.speeds[i]));
    const int idx[2] = {c.a, c.b};
    for (int r = 0; r < 2; ++r)
      for (int k = 0; k < 2; ++k)
        if (idx[r] >= 0 && idx[k] >= 0) rowD[static_cast<size_t>(idx[r])] += slope;
  }
  double rho_D = 0.0, omega_K = 0.0;
  for (int i = 0; i < m.dof(); ++i) {
    const double I = m.bodies[static_cast<size_t>(i)].inertia;
    rho_D = std::max(rho_D, rowD[static_cast<size_t>(i)] / I);
    omega_K = std::max(omega_K, std::sqrt(rowK[static_cast<size_t>(i)] / I));
  }
  // Stiff: the fastest motion is damping-dominated (ρ_D ≥ ω_K, i.e. ζ ≳ 0.5) and so fast that an
  // explicit method would spend > 2e4 steps on stability alone.
  const double fastest = rho_D >= omega_K ? rho_D : 0.0;
  const double stiffness_index = fastest * s.t_end;
  if (stiffness_index > 2e4) {
    if (reason) *reason = fmt::format("auto: strongly damped fast motion, |Re λ|·t_end = {:.3g} > 2e4", stiffness_index);
    return Method::bdf;
  }
  if (reason) *reason = fmt::format("auto: non-stiff, |Re λ|·t_end = {:.3g} <= 2e4", stiffness_index);
  return Method::dopri5;
}

namespace {

/// Collects the output grid and the link-load peaks; at each new maximum or minimum of link l it
/// keeps the values of the loads then (O(#loads)), for the quasi-static loads at t_max and t_min.
class Recorder final : public StepObserver {
 public:
  Recorder(const Model& m, ChainSystem& sys, SimulationResult& out, const SimulateOptions& opt,
           detail::MachineRun& run)
      : m_(m), sys_(sys), out_(out), opt_(opt), run_(run), start_(std::chrono::steady_clock::now()), peaks_(sys.size(), weights(m, sys)),
        varying_(varying_loads(m)),
        loads_at_max_(m.links.size(), std::vector<double>(varying_.size(), 0.0)), loads_at_min_(loads_at_max_) {
    out_.column_names = chain_column_names(m);
    out_.columns.resize(out_.column_names.size());
    const auto rows = static_cast<size_t>(m.simulation.t_end / m.simulation.dt_out) + 2;
    for (auto& col : out_.columns) col.reserve(rows);
    on_new_max_ = [this](int l, bool is_max, double t, const double* y) {
      auto& vals = (is_max ? loads_at_max_ : loads_at_min_)[static_cast<size_t>(l)];
      for (size_t k = 0; k < varying_.size(); ++k) {
        const Load& ld = m_.loads[varying_[k]];
        vals[k] = ld.evaluate(t, y[ld.body], y[m_.dof() + ld.body]);
      }
    };
  }

  void on_segment(const Stepper& s, double ta, double tb) override {
    peaks_.on_segment(s, ta, tb, on_new_max_);
    run_.on_segment(s, ta, tb);
  }
  void on_event(double, const double*, const std::vector<int>&) override { peaks_.restart(); }

  void on_step(const Stepper& s) override {
    // Progress: look at the clock every 32 steps only, report every progress_interval_s.
    if (opt_.progress && (++steps_ & 31) == 0) {
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
      if (wall >= next_report_) {
        next_report_ = wall + opt_.progress_interval_s;
        opt_.progress(progress(s.t(), wall, false));
      }
    }
  }

  SimulationProgress progress(double t, double wall, bool finished) const {
    SimulationProgress p;
    p.t = t;
    p.t_end = m_.simulation.t_end;
    p.steps = steps_;
    p.events = run_.jumps();  // velocity jumps of stepwise gears
    p.wall_s = wall;
    p.finished = finished;
    return p;
  }

  /// The last progress report, at the end of the run.
  void finish() const {
    if (!opt_.progress) return;
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    opt_.progress(progress(m_.simulation.t_end, wall, true));
  }

  void on_output(double t, const double* y) override {
    const int n = m_.dof();
    size_t c = 0;
    out_.columns[c++].push_back(t);
    for (int i = 0; i < n; ++i) {
      out_.columns[c++].push_back(y[i]);
      out_.columns[c++].push_back(y[n + i]);
    }
    for (size_t l = 0; l < m_.links.size(); ++l) out_.columns[c++].push_back(sys_.link_load(static_cast<int>(l), y));
  }

  const PeakTracker& peaks() const { return peaks_; }
  /// The values of the time- or speed-dependent loads when link l had its maximum (or minimum);
  /// the constant loads are the same at every instant.
  const std::vector<double>& varying_at(size_t l, bool at_max) const {
    return (at_max ? loads_at_max_ : loads_at_min_)[l];
  }
  /// The generalized forces of all loads for the varying loads' values `vals`.
  Eigen::VectorXd forces(const std::vector<double>& vals) const {
    Eigen::VectorXd f = Eigen::VectorXd::Zero(m_.dof());
    size_t v = 0;
    for (size_t k = 0; k < m_.loads.size(); ++k) {
      const Load& ld = m_.loads[k];
      f(ld.body) += v < varying_.size() && varying_[v] == k ? vals[v++] : ld.evaluate(0.0, 0.0, 0.0);
    }
    return f;
  }

 private:
  static std::vector<size_t> varying_loads(const Model& m) {
    std::vector<size_t> v;
    for (size_t k = 0; k < m.loads.size(); ++k)
      if (m.loads[k].kind != LoadKind::constant) v.push_back(k);
    return v;
  }
  static std::vector<SparseWeights> weights(const Model& m, const ChainSystem& sys) {
    std::vector<SparseWeights> w;
    for (size_t l = 0; l < m.links.size(); ++l) w.push_back(sys.link_load_weights(static_cast<int>(l)));
    return w;
  }
  const Model& m_;
  ChainSystem& sys_;
  SimulationResult& out_;
  const SimulateOptions& opt_;
  detail::MachineRun& run_;
  std::chrono::steady_clock::time_point start_;
  long steps_ = 0;
  double next_report_ = 0.0;
  PeakTracker peaks_;
  std::vector<size_t> varying_;  // indices of the loads that depend on t or v
  std::vector<std::vector<double>> loads_at_max_, loads_at_min_;
  PeakTracker::NewMax on_new_max_;
};

}  // namespace

void set_peak(LinkSummary& s) {
  const bool neg = std::abs(s.min) > std::abs(s.max);
  s.peak = neg ? s.min : s.max;
  s.t_peak = neg ? s.t_min : s.t_max;
  s.static_load = neg ? s.static_at_min : s.static_at_max;
  s.dynamic_factor = std::abs(s.static_load) > 1e-9 * std::abs(s.peak) ? s.peak / s.static_load
                                                                       : std::numeric_limits<double>::quiet_NaN();
}

SimulationResult simulate(const Model& m) { return simulate(m, SimulateOptions{}); }

SimulationResult simulate(const Model& m, const SimulateOptions& options) {
  if (m.is_hybrid() || options.event_driven) {
    HybridOptions hybrid;
    hybrid.progress = options.progress;
    hybrid.progress_interval_s = options.progress_interval_s;
    hybrid.record_series = options.record_series;
    return simulate_hybrid(m, hybrid);
  }
  SimulationResult out;
  const Method method = choose_method(m, &out.method_reason);
  ChainSystem sys(m);
  std::vector<double> y0(static_cast<size_t>(sys.size()));
  sys.initial_state(y0.data());
  StepperOptions opt;
  opt.rtol = m.simulation.rtol;
  opt.atol = m.simulation.atol;
  opt.max_steps = m.simulation.max_steps;
  detail::MachineRun run(m, sys);  // velocity jumps (stepwise gears) and the point-speed report
  run.start(0.0, y0.data());
  EventSystem& events = run.has_jumps() ? static_cast<EventSystem&>(run) : sys;
  auto stepper = make_stepper(method, events, opt);
  Recorder rec(m, sys, out, options, run);
  DriveOptions drive;
  drive.dt_out = m.simulation.dt_out;
  drive.event_tol = 4e-16;  // jump positions of stepwise gears: to the last bits of t
  out.stats = integrate(*stepper, events, 0.0, y0.data(), m.simulation.t_end, drive, rec);
  rec.finish();
  out.machines = run.reports();

  // Quasi-static loads at each link's extremes: one sparse factorization, one solve per distinct
  // load vector (constant loads: a single solve for every link).
  const ParticularSolver particular(m);
  std::map<std::vector<double>, Eigen::VectorXd> solved;
  auto static_loads = [&](const std::vector<double>& vals) -> const Eigen::VectorXd& {
    auto it = solved.find(vals);
    if (it == solved.end()) it = solved.emplace(vals, particular.solve(rec.forces(vals))).first;
    return it->second;
  };
  for (size_t l = 0; l < m.links.size(); ++l) {
    const int j = static_cast<int>(l);
    LinkSummary s;
    s.max = rec.peaks().max(j);
    s.min = rec.peaks().min(j);
    s.t_max = rec.peaks().t_max(j);
    s.t_min = rec.peaks().t_min(j);
    s.static_at_max = static_loads(rec.varying_at(l, true))(j);
    s.static_at_min = static_loads(rec.varying_at(l, false))(j);
    set_peak(s);
    out.links.push_back(s);
  }
  append_machine_outputs(m, sys, out);  // variable-inertia series (analysis/machine_outputs.hpp)
  return out;
}

}  // namespace machdyn
