#include "machdyn/io/linear_results.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include "machdyn/analysis/mode_kinds.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/common/csv.hpp"
#include "io/number_text.hpp"

namespace machdyn {

namespace {
constexpr double kTwoPi = 2.0 * std::numbers::pi;
constexpr double kRpm = 60.0 / kTwoPi;

std::string csv_12_digits(double x) { return std::isfinite(x) ? fmt::format("{:.12g}", x) : ""; }

nlohmann::json shapes_json(const Model& m, const Eigen::VectorXd& omega, const Eigen::MatrixXd& shapes) {
  nlohmann::json out = nlohmann::json::array();
  for (Eigen::Index k = 0; k < shapes.cols(); ++k) {
    nlohmann::json amp = nlohmann::json::object();
    for (int i = 0; i < m.dof(); ++i) amp[m.bodies[static_cast<size_t>(i)].name] = shapes(i, k);
    out.push_back({{"mode", k + 1}, {"frequency_rad_s", omega(k)}, {"frequency_hz", omega(k) / kTwoPi},
                   {"amplitudes", amp}});
  }
  // A swinging load's model: each mode's kind and kinetic energy shares (analysis/mode_kinds.hpp).
  if (has_swinging_load(m)) {
    const std::vector<ModeShares> s = mode_shares(m, mass_diagonal(m), shapes);
    for (size_t k = 0; k < s.size(); ++k) {
      out[k]["kind"] = to_string(mode_kind(s[k]));
      out[k]["energy_shares"] = {{"sway", s[k].sway}, {"stretch", s[k].stretch}, {"drive", s[k].drive}};
    }
  }
  return out;
}
}  // namespace

nlohmann::json topology_modes_json(const Model& m, const TopologyModes& t) {
  nlohmann::json j;
  j["topology"] = t.label;
  nlohmann::json iv = nlohmann::json::array();
  for (const auto& [a, b] : t.intervals) iv.push_back({a, b});
  if (!t.intervals.empty()) j["intervals_s"] = iv;
  j["constraints"] = t.modes.constraints;
  j["dof"] = t.modes.dof;
  j["rigid_body_modes"] = t.modes.rigid_body_modes;
  std::vector<double> w(t.modes.omega.data(), t.modes.omega.data() + t.modes.omega.size()), hz;
  for (double x : w) hz.push_back(x / kTwoPi);
  j["frequencies_rad_s"] = w;
  j["frequencies_hz"] = hz;
  j["shapes"] = shapes_json(m, t.modes.omega, t.modes.shapes);
  if (has_swinging_load(m)) {
    nlohmann::json kinds = nlohmann::json::array();
    for (const auto& s : j["shapes"]) kinds.push_back(s["kind"]);
    j["kinds"] = kinds;
  }
  if (t.damped_skipped) j["damped_modes_skipped"] = "more coordinates than the dense state-space solver takes";
  if (t.damped) {
    nlohmann::json d = nlohmann::json::array();
    for (const DampedMode& md : t.damped_modes.modes) {
      nlohmann::json mag = nlohmann::json::object(), ph = nlohmann::json::object();
      for (int i = 0; i < m.dof(); ++i) {
        mag[m.bodies[static_cast<size_t>(i)].name] = std::abs(md.shape(i));
        ph[m.bodies[static_cast<size_t>(i)].name] = std::arg(md.shape(i)) * 360.0 / kTwoPi;
      }
      d.push_back({{"oscillatory", md.oscillatory},
                   {"lambda", {md.lambda.real(), md.lambda.imag()}},
                   {"omega_n_rad_s", md.omega_n},
                   {"omega_d_rad_s", md.omega_d},
                   {"zeta", json_number(md.zeta)},
                   {"decay_rate_1_s", md.decay_rate},
                   {"shape_magnitude", mag},
                   {"shape_phase_deg", ph}});
    }
    j["damped_modes"] = d;
    j["zero_eigenvalues"] = t.damped_modes.zero_eigenvalues;
  }
  return j;
}

nlohmann::json linear_modes_json(const Model& m, const std::vector<TopologyModes>& list) {
  nlohmann::json j;
  j["model"] = m.name;
  nlohmann::json bodies = nlohmann::json::array();
  for (const auto& b : m.bodies) bodies.push_back(b.name);
  j["bodies"] = bodies;
  nlohmann::json all = nlohmann::json::array();
  for (const auto& t : list) all.push_back(topology_modes_json(m, t));
  if (!list.empty()) {
    for (const char* k : {"rigid_body_modes", "frequencies_rad_s", "frequencies_hz", "shapes", "topology"})
      j[k] = all[0][k];
    if (all[0].contains("kinds")) j["kinds"] = all[0]["kinds"];
  }
  j["topologies"] = all;
  return j;
}

std::string linear_modes_csv(const std::vector<TopologyModes>& list) {
  std::string s = "topology,mode,omega_rad_s,f_Hz,zeta,omega_d_rad_s\n";
  for (const auto& t : list) {
    const std::string label = csv_field(t.label, true);
    for (Eigen::Index k = 0; k < t.modes.omega.size(); ++k) {
      double zeta = std::numeric_limits<double>::quiet_NaN(), wd = zeta;
      // The damped mode nearest in ω_n (oscillatory modes only).
      if (t.damped) {
        double best = std::numeric_limits<double>::infinity();
        for (const DampedMode& d : t.damped_modes.modes)
          if (d.oscillatory && std::abs(d.omega_n - t.modes.omega(k)) < best)
            best = std::abs(d.omega_n - t.modes.omega(k)), zeta = d.zeta, wd = d.omega_d;
      }
      s += fmt::format("{},{},{},{},{},{}\n", label, k + 1, csv_12_digits(t.modes.omega(k)),
                       csv_12_digits(t.modes.omega(k) / kTwoPi), csv_12_digits(zeta), csv_12_digits(wd));
    }
  }
  return s;
}

std::string frequency_response_csv(const FrequencyResponse& r) {
  std::string s = "omega_rad_s,f_Hz";
  for (const auto& o : r.outputs)
    s += "," + csv_line({fmt::format("{}.mag_{}_per_{}", o.name, unit_suffix(o.unit.c_str()),
                                     unit_suffix(r.input.unit.c_str())),
                         o.name + ".phase_deg"});
  s += '\n';
  const Eigen::MatrixXd mag = r.magnitude(), ph = r.phase_deg();
  for (Eigen::Index f = 0; f < r.omega.size(); ++f) {
    s += fmt::format("{},{}", csv_12_digits(r.omega(f)), csv_12_digits(r.omega(f) / kTwoPi));
    for (Eigen::Index k = 0; k < mag.cols(); ++k) s += fmt::format(",{},{}", csv_12_digits(mag(f, k)), csv_12_digits(ph(f, k)));
    s += '\n';
  }
  return s;
}

nlohmann::json frequency_response_json(const FrequencyResponse& r) {
  nlohmann::json j;
  j["input"] = {{"name", r.input.name}, {"unit", r.input.unit}};
  const Eigen::MatrixXd mag = r.magnitude(), ph = r.phase_deg();
  std::vector<double> w(r.omega.data(), r.omega.data() + r.omega.size());
  j["omega_rad_s"] = w;
  nlohmann::json outs = nlohmann::json::array();
  const auto peaks = resonance_peaks(r);
  for (size_t k = 0; k < r.outputs.size(); ++k) {
    nlohmann::json m = nlohmann::json::array(), p = nlohmann::json::array(), pk = nlohmann::json::array();
    for (Eigen::Index f = 0; f < r.omega.size(); ++f)
      m.push_back(json_number(mag(f, static_cast<Eigen::Index>(k)))), p.push_back(json_number(ph(f, static_cast<Eigen::Index>(k))));
    for (const auto& x : peaks)
      if (x.output == static_cast<int>(k))
        pk.push_back({{"omega_rad_s", x.omega}, {"f_hz", x.omega / kTwoPi}, {"magnitude", x.magnitude},
                      {"phase_deg", x.phase_deg}});
    outs.push_back({{"name", r.outputs[k].name},
                    {"unit", r.outputs[k].unit + "/" + r.input.unit},
                    {"magnitude", m},
                    {"phase_deg", p},
                    {"peaks", pk}});
  }
  j["outputs"] = outs;
  return j;
}

namespace {
plot::Figure bode(const Model& m, const FrequencyResponse& r, const std::string& topology, bool phase) {
  plot::Figure f;
  f.id = phase ? "bode_phase" : "bode_magnitude";
  const Eigen::MatrixXd mag = r.magnitude(), ph = r.phase_deg();
  // An output the input does not reach (another part of the machine, or held by a stuck brake) has
  // |H| of the solve's rounding, 1e-13 beside 7: no curve (its log scale spanned 30 decades of
  // noise), named in the title instead.
  std::vector<double> top(r.outputs.size(), 0.0);
  double largest = 0.0;
  for (size_t k = 0; k < r.outputs.size(); ++k) {
    for (Eigen::Index i = 0; i < r.omega.size(); ++i)
      if (const double y = mag(i, static_cast<Eigen::Index>(k)); std::isfinite(y)) top[k] = std::max(top[k], y);
    largest = std::max(largest, top[k]);
  }
  std::vector<std::string> quiet;
  for (size_t k = 0; k < r.outputs.size(); ++k)
    if (!(top[k] > 1e-9 * largest)) quiet.push_back(r.outputs[k].name);
  f.title = fmt::format("{}: {} from {}{}{}", m.name, phase ? "phase" : "frequency response |H|", r.input.name,
                        topology.empty() ? "" : " (" + topology + ")",
                        quiet.empty() ? "" : fmt::format("; not excited: {}", fmt::join(quiet, ", ")));
  f.x = plot::make_axis("frequency f", "Hz");
  f.x.log = r.omega.size() > 1 && r.omega.minCoeff() > 0.0;
  f.y = phase ? plot::make_axis("phase", "°") : plot::make_axis("|H|", "output unit per " + plot::pretty_unit(r.input.unit));
  f.y.log = !phase;
  for (size_t k = 0; k < r.outputs.size(); ++k) {
    if (!(top[k] > 1e-9 * largest)) continue;
    plot::Series s = plot::make_series(fmt::format("{} ({}/{})", r.outputs[k].name, plot::pretty_unit(r.outputs[k].unit),
                                                   plot::pretty_unit(r.input.unit)),
                                       {}, {});
    for (Eigen::Index i = 0; i < r.omega.size(); ++i) {
      const double y = phase ? ph(i, static_cast<Eigen::Index>(k)) : mag(i, static_cast<Eigen::Index>(k));
      s.x.push_back(r.omega(i) / kTwoPi);
      s.y.push_back(std::isfinite(y) && (phase || y > 0) ? y : std::numeric_limits<double>::quiet_NaN());
    }
    f.series.push_back(std::move(s));
  }
  f.legend = plot::Figure::Legend::below;
  return f;
}
}  // namespace

plot::Figure bode_magnitude_figure(const Model& m, const FrequencyResponse& r, const std::string& topology) {
  return bode(m, r, topology, false);
}
plot::Figure bode_phase_figure(const Model& m, const FrequencyResponse& r, const std::string& topology) {
  return bode(m, r, topology, true);
}

std::string position_frequencies_csv(const Model& m, const PositionFrequencies& p) {
  const int b = m.body_index(p.body);
  std::string s = csv_field(
      fmt::format("{}.position_{}", p.body, unit_suffix(position_unit(m.bodies[static_cast<size_t>(b)].kind))));
  for (Eigen::Index k = 0; k < p.omega.cols(); ++k) s += fmt::format(",omega_{}_rad_s", k + 1);
  s += '\n';
  for (Eigen::Index i = 0; i < p.positions.size(); ++i) {
    s += csv_12_digits(p.positions(i));
    for (Eigen::Index k = 0; k < p.omega.cols(); ++k) s += fmt::format(",{}", csv_12_digits(p.omega(i, k)));
    s += '\n';
  }
  return s;
}

plot::Figure position_frequencies_figure(const Model& m, const PositionFrequencies& p, const std::string& topology) {
  const int b = m.body_index(p.body);
  const bool rot = m.bodies[static_cast<size_t>(b)].kind == BodyKind::rotational;
  plot::Figure f;
  f.id = "frequencies_over_position";
  f.title = fmt::format("{}: natural frequencies over the position of {}{}", m.name, p.body,
                        topology.empty() ? "" : " (" + topology + ")");
  f.x = plot::make_axis(fmt::format("position of {}", p.body), rot ? "°" : "m");
  f.y = plot::make_axis("natural frequency f", "Hz");
  for (Eigen::Index k = 0; k < p.omega.cols(); ++k) {
    plot::Series s = plot::make_series(fmt::format("mode {}", k + 1), {}, {});
    for (Eigen::Index i = 0; i < p.positions.size(); ++i) {
      s.x.push_back(rot ? p.positions(i) * 360.0 / kTwoPi : p.positions(i));
      s.y.push_back(p.omega(i, k) / kTwoPi);
    }
    f.series.push_back(std::move(s));
  }
  return f;
}

plot::Figure campbell_figure(const Model& m, const Eigen::VectorXd& omega, const std::vector<ExcitationOrder>& orders,
                             double speed_lo, double speed_hi, const std::vector<CampbellCrossing>& crossings,
                             const std::string& shaft) {
  plot::Figure f;
  f.id = "campbell";
  f.title = fmt::format("{}: Campbell diagram over the speed of {}", m.name, shaft);
  f.x = plot::make_axis(fmt::format("speed of {}", shaft), "rpm");
  f.y = plot::make_axis("frequency f", "Hz");
  const double x0 = speed_lo * kRpm, x1 = speed_hi * kRpm;
  for (Eigen::Index k = 0; k < omega.size(); ++k) {
    plot::Series s = plot::make_series(fmt::format("mode {}: {:.4g} Hz", k + 1, omega(k) / kTwoPi), {x0, x1},
                                       {omega(k) / kTwoPi, omega(k) / kTwoPi});
    s.dashed = true;
    f.series.push_back(std::move(s));
  }
  for (const auto& o : orders)
    f.series.push_back(plot::make_series(fmt::format("{} (order {:g})", o.name, o.order), {x0, x1},
                                         {o.order * speed_lo / kTwoPi, o.order * speed_hi / kTwoPi}));
  if (!crossings.empty()) {
    plot::Series pts = plot::make_series("resonances", {}, {}, plot::Style::points);
    for (const auto& c : crossings) pts.x.push_back(c.speed * kRpm), pts.y.push_back(c.omega / kTwoPi);
    f.series.push_back(std::move(pts));
  }
  f.x.min = x0, f.x.max = x1;
  f.y.min = 0.0;
  // Every natural frequency in view, the order lines up to 1.5 × the highest (a steep line would
  // squash the modes).
  double top = 0.0;
  for (const auto& o : orders) top = std::max(top, o.order * speed_hi / kTwoPi);
  if (omega.size() > 0) {
    const double fmax = omega.maxCoeff() / kTwoPi;
    top = std::max(1.1 * fmax, std::min(top, 1.5 * fmax));
  }
  if (top > 0.0) f.y.max = top;
  f.legend = plot::Figure::Legend::below;
  return f;
}

nlohmann::json campbell_json(const std::vector<CampbellCrossing>& crossings, const std::string& shaft) {
  nlohmann::json a = nlohmann::json::array();
  for (const auto& c : crossings)
    a.push_back({{"order", c.order_name},
                 {"order_number", c.order},
                 {"mode", c.mode},
                 {"omega_rad_s", c.omega},
                 {"f_hz", c.omega / kTwoPi},
                 {"speed_rad_s", c.speed},
                 {"speed_rpm", c.speed * kRpm}});
  return {{"shaft", shaft}, {"crossings", a}};
}

}  // namespace machdyn
