#include "machdyn/analysis/simulate.hpp"

#include <cmath>
#include <limits>
#include <fmt/format.h>

#include "machdyn/analysis/chain_system.hpp"
#include "machdyn/analysis/machine_outputs.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/peak_tracker.hpp"

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
  const Modes modes = compute_modes(m);
  const Eigen::MatrixXd D = damping_matrix(m);
  const Eigen::VectorXd M = mass_diagonal(m);
  double fastest = 0.0;  // |Re λ| of the fastest strongly damped motion, 1/s
  for (Eigen::Index k = 0; k < modes.omega.size(); ++k) {
    const double w = modes.omega(k);
    const double zeta = modes.shapes.col(k).dot(D * modes.shapes.col(k)) / (2.0 * w);
    if (zeta < 0.5) continue;
    const double re = zeta >= 1.0 ? w * (zeta + std::sqrt(zeta * zeta - 1.0)) : zeta * w;
    fastest = std::max(fastest, re);
  }
  for (Eigen::Index i = 0; i < M.size(); ++i) fastest = std::max(fastest, D(i, i) / M(i));  // dampers without springs
  const double stiffness_index = fastest * s.t_end;
  if (stiffness_index > 2e4) {
    if (reason) *reason = fmt::format("auto: strongly damped fast motion, |Re λ|·t_end = {:.3g} > 2e4", stiffness_index);
    return Method::bdf;
  }
  if (reason) *reason = fmt::format("auto: non-stiff, |Re λ|·t_end = {:.3g} <= 2e4", stiffness_index);
  return Method::dopri5;
}

namespace {

/// Collects the output grid and the link-load peaks.
class Recorder final : public StepObserver {
 public:
  Recorder(const Model& m, ChainSystem& sys, SimulationResult& out) : m_(m), sys_(sys), out_(out) {
    const int n = m.dof();
    out_.column_names.push_back("t_s");
    auto suffix = [](const char* unit) {
      std::string s(unit);
      for (auto& ch : s)
        if (ch == '*' || ch == '/') ch = '_';
      return s;
    };
    for (const auto& b : m.bodies) {
      out_.column_names.push_back(b.name + ".position_" + suffix(position_unit(b.kind)));
      out_.column_names.push_back(b.name + ".velocity_" + suffix(velocity_unit(b.kind)));
    }
    for (size_t l = 0; l < m.links.size(); ++l) {
      out_.column_names.push_back(m.links[l].name + ".load_" + suffix(link_load_unit(m, m.links[l])));
      trackers_.emplace_back(sys.link_load_weights(static_cast<int>(l)));
    }
    out_.columns.resize(out_.column_names.size());
    (void)n;
  }

  void on_step(const Stepper& s) override {
    for (auto& tr : trackers_) tr.on_step(s);
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

  const std::vector<PeakTracker>& trackers() const { return trackers_; }

 private:
  const Model& m_;
  ChainSystem& sys_;
  SimulationResult& out_;
  std::vector<PeakTracker> trackers_;
};

}  // namespace

SimulationResult simulate(const Model& m) {
  SimulationResult out;
  const Method method = choose_method(m, &out.method_reason);
  ChainSystem sys(m);
  std::vector<double> y0(static_cast<size_t>(sys.size()));
  sys.initial_state(y0.data());
  StepperOptions opt;
  opt.rtol = m.simulation.rtol;
  opt.atol = m.simulation.atol;
  opt.max_steps = m.simulation.max_steps;
  auto stepper = make_stepper(method, sys, opt);
  Recorder rec(m, sys, out);
  out.stats = integrate(*stepper, 0.0, y0.data(), m.simulation.t_end, m.simulation.dt_out, rec);

  // Quasi-static loads at each link's peak time.
  const Modes modes = compute_modes(m);
  const int n = m.dof();
  std::vector<double> f(static_cast<size_t>(n));
  for (size_t l = 0; l < m.links.size(); ++l) {
    const PeakTracker& tr = rec.trackers()[l];
    LinkSummary s;
    s.max = tr.max();
    s.min = tr.min();
    s.t_max = tr.t_max();
    s.t_min = tr.t_min();
    sys.generalized_loads(s.t_max, tr.y_at_max().data(), f.data());
    const Eigen::VectorXd F = static_link_loads(m, modes, Eigen::Map<const Eigen::VectorXd>(f.data(), n));
    s.static_load = F(static_cast<Eigen::Index>(l));
    const double scale = std::max({std::abs(s.max), std::abs(s.min), 1e-300});
    s.dynamic_factor = std::abs(s.static_load) > 1e-12 * scale ? s.max / s.static_load
                                                               : std::numeric_limits<double>::quiet_NaN();
    out.links.push_back(s);
  }
  append_machine_outputs(m, sys, out);  // variable-inertia series (analysis/machine_outputs.hpp)
  return out;
}

}  // namespace machdyn
