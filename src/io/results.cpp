#include "machdyn/io/results.hpp"

#include "machdyn/analysis/brake_summary.hpp"
#include "machdyn/analysis/sway_summary.hpp"
#include "machdyn/analysis/hybrid_stats.hpp"
#include "machdyn/common/csv.hpp"
#include "common/constants.hpp"
#include "io/number_text.hpp"

#include <cmath>
#include <numbers>
#include <fmt/format.h>

namespace machdyn {

void timeseries_csv(const SimulationResult& r, const ChunkSink& sink) {
  std::string s = csv_line(r.column_names) + '\n';  // names quoted as RFC 4180 needs (common/csv.hpp)
  const size_t rows = r.columns.empty() ? 0 : r.columns[0].size();
  // About 1 MB at a time: a long run's CSV is never held whole in memory.
  constexpr size_t chunk = size_t{1} << 20;
  s.reserve(chunk + 4096);
  for (size_t i = 0; i < rows; ++i) {
    for (size_t c = 0; c < r.columns.size(); ++c) {
      if (c) s += ',';
      fmt::format_to(std::back_inserter(s), "{:.17g}", r.columns[c][i]);
    }
    s += '\n';
    if (s.size() >= chunk) {
      sink(s);
      s.clear();
    }
  }
  sink(s);
}

std::string timeseries_csv(const SimulationResult& r) {
  std::string all;
  timeseries_csv(r, [&](std::string_view d) { all.append(d); });
  return all;
}

void write_timeseries_csv(const std::filesystem::path& path, const SimulationResult& r) {
  write_file_atomic(path, [&](const ChunkSink& sink) { timeseries_csv(r, sink); });
}

namespace {
const char* method_name(IntegratorChoice c) {
  switch (c) {
    case IntegratorChoice::dopri5: return "dopri5";
    case IntegratorChoice::bdf: return "bdf";
    default: return "auto";
  }
}

/// Events, slip phases with the link peaks inside each, per-contact stick–slip statistics and the
/// energy balance (analysis/hybrid_report.hpp).
void add_hybrid_summary(const Model& m, const SimulationResult& r, nlohmann::json& j) {
  const HybridReport& h = r.hybrid;
  nlohmann::json ev = nlohmann::json::array();
  for (const auto& e : h.events)
    ev.push_back({{"t", e.t}, {"kind", e.kind}, {"element", e.element}, {"from", e.from}, {"to", e.to}});
  j["events"] = ev;
  if (!h.warnings.empty()) j["warnings"] = h.warnings;  // absent without warnings
  nlohmann::json phases = nlohmann::json::array();
  for (const auto& p : h.slip_phases) {
    nlohmann::json peaks = nlohmann::json::object();
    for (size_t l = 0; l < m.links.size(); ++l)
      peaks[m.links[l].name] = {{"max", p.link_max[l]}, {"t_max", p.link_t_max[l]}, {"min", p.link_min[l]}, {"at_start", p.link_start[l]}};
    phases.push_back({{"contact", p.contact}, {"direction", p.direction}, {"t_start", p.t_start}, {"t_end", p.t_end},
                      {"link_peaks", peaks}});
  }
  j["slip_phases"] = phases;
  // Per link: the peak load in each slip phase, in order.
  for (size_t l = 0; l < m.links.size(); ++l) {
    nlohmann::json list = nlohmann::json::array();
    for (const auto& p : h.slip_phases)
      list.push_back({{"contact", p.contact}, {"t_start", p.t_start}, {"t_end", p.t_end}, {"max", p.link_max[l]},
                      {"t_max", p.link_t_max[l]}, {"min", p.link_min[l]}});
    j["links"][m.links[l].name]["slip_phase_peaks"] = list;
  }
  // Per contact: number of slips, the self-oscillation period (mean interval between the starts of
  // the slips in the second half of the run) and the largest link loads as multiples of the
  // contact's static limit.
  nlohmann::json contacts = nlohmann::json::object();
  const std::vector<ContactStatistics> stats = contact_statistics(m, r);
  for (size_t k = 0, next = 0; k < m.contacts.size(); ++k) {
    const FrictionContact& c = m.contacts[k];
    if (c.joint) continue;  // a gear joint: no limit, never slips (none in stats)
    const ContactStatistics& st = stats[next++];
    nlohmann::json ratio = nlohmann::json::object();
    for (size_t l = 0; l < m.links.size(); ++l) ratio[m.links[l].name] = json_number(st.link_max_over_static_limit[l]);
    contacts[c.name] = {{"kind", c.brake ? "brake" : c.clutch ? "clutch" : "contact"},
                        {"static_limit", c.static_limit},
                        {"kinetic_at_rest", c.kinetic_level(0.0)},
                        {"slips", st.slips},
                        {"period_s", json_number(st.period_s)},
                        {"link_max_over_static_limit", ratio},
                        {"unit", load_unit(m.bodies[static_cast<size_t>(c.a)].kind)}};
    // null for a brake that stays released over the run (t_apply = t_end there, compile_hybrid.cpp).
    if (c.brake || c.applied)
      contacts[c.name]["applied_at_s"] = c.released(c.t_apply) ? nlohmann::json() : nlohmann::json(c.t_apply);
  }
  j["contacts"] = contacts;
  const EnergyBalance& E = h.energy;
  j["energy"] = {{"source_work_J", E.source_work},     {"kinetic_start_J", E.kinetic_start},
                 {"kinetic_end_J", E.kinetic_end},     {"elastic_start_J", E.elastic_start},
                 {"elastic_end_J", E.elastic_end},     {"friction_loss_J", E.friction_loss},
                 {"damping_loss_J", E.damping_loss},   {"gap_release_loss_J", E.release_loss},
                 {"impact_loss_J", E.impact_loss},     {"released_kinetic_J", E.released_kinetic},
                 {"residual_J", E.residual()}};
  // The heat of all dissipative elements (the total heat_J of `--outputs heat` at t_end).
  j["energy"]["dissipated_J"] = E.friction_loss + E.damping_loss + E.release_loss + E.impact_loss;
}
}  // namespace

nlohmann::json brake_stops_json(const std::vector<BrakeSummary>& brakes) {
  nlohmann::json j = nlohmann::json::object();
  for (const BrakeSummary& s : brakes) {
    nlohmann::json stops = nlohmann::json::array();
    for (const BrakeStop& st : s.stops) {
      nlohmann::json travel = nlohmann::json::object();
      for (const auto& x : st.travel) travel[x.body] = {{"value", x.value}, {"unit", x.unit}};
      nlohmann::json e = {{"applied_at_s", st.t_applied},
                          {"start", start_name(st.start)},
                          {"ended_at_s", st.t_end},
                          {"end", end_name(st.end)},
                          {"stopped", st.stopping_time.has_value()},
                          {"stopping_time_s", st.stopping_time ? nlohmann::json(*st.stopping_time) : nlohmann::json()},
                          {"travel", travel},
                          {"energy_J", st.energy_J},
                          {"peak_power_W", st.peak_power_W},
                          {"t_peak_power_s", st.t_peak_power}};
      if (s.thermal) {
        e["temperature_applied_degC"] = st.temperature_applied_degC;
        e["temperature_end_degC"] = st.temperature_end_degC;
        e["temperature_rise_K"] = st.temperature_end_degC - st.temperature_applied_degC;
      }
      stops.push_back(e);
    }
    nlohmann::json e = {{"unit", s.unit},
                        {"energy_J", s.energy_J},
                        {"peak_power_W", s.peak_power_W},
                        {"t_peak_power_s", s.t_peak_power},
                        {"stops", stops}};
    if (s.thermal) {
      e["temperature_max_degC"] = s.temperature_max_degC;
      e["t_temperature_max_s"] = s.t_temperature_max;
      e["temperature_end_degC"] = s.temperature_end_degC;
    }
    j[s.brake] = e;
  }
  return j;
}

std::string sway_text(const std::vector<SwaySummary>& sway) {
  std::string out;
  for (const SwaySummary& s : sway) {
    std::string line = fmt::format("sway {}: largest {:.4g} deg ({:.4g} rad) at {:.6g} s", s.rope, s.max_sway_rad / kDeg,
                                   s.max_sway_rad, s.t_max_sway);
    if (s.residual_after)
      line += fmt::format("; residual {:.4g} deg after {:.6g} s", s.residual_sway_rad / kDeg, *s.residual_after);
    line += fmt::format("; horizontal force max {:.6g} N at {:.6g} s", s.max_horizontal_force_N, s.t_max_horizontal_force);
    if (s.dynamic_factor)
      line += fmt::format(", horizontal dynamic factor {:.4g} (m a = {:.6g} N)", *s.dynamic_factor, *s.rigid_force_N);
    line += fmt::format("; tension max {:.6g} N", s.max_tension_N);
    out += line + "\n";
  }
  return out;
}

std::string brake_stops_text(const std::vector<BrakeSummary>& brakes) {
  std::string out;
  for (const BrakeSummary& s : brakes) {
    std::string line = fmt::format("brake {}: ", s.brake);
    line += s.stops.empty() ? std::string("not applied in the run")
                            : fmt::format("{} stop{}", s.stops.size(), s.stops.size() == 1 ? "" : "s");
    line += fmt::format("; energy {:.6g} J, peak power {:.6g} W at {:.6g} s", s.energy_J, s.peak_power_W, s.t_peak_power);
    if (s.thermal)
      line += fmt::format("; temperature max {:.5g} degC at {:.6g} s, {:.5g} degC at the end", s.temperature_max_degC,
                          s.t_temperature_max, s.temperature_end_degC);
    out += line + "\n";
    for (size_t k = 0; k < s.stops.size(); ++k) {
      const BrakeStop& st = s.stops[k];
      line = fmt::format("  stop {}: {} {:.6g} s, ", k + 1,
                         st.start == BrakeStop::Start::applied    ? "applied at"
                         : st.start == BrakeStop::Start::overcome ? "overcome (sliding) at"
                                                                  : "sliding from", st.t_applied);
      switch (st.end) {
        case BrakeStop::End::stuck: line += fmt::format("stopped after {:.6g} s", *st.stopping_time); break;
        case BrakeStop::End::released: line += fmt::format("released after {:.6g} s", st.t_end - st.t_applied); break;
        case BrakeStop::End::run_end: line += "not at rest by t_end"; break;
      }
      for (const auto& x : st.travel) line += fmt::format(", {} {:.6g} {}", x.body, x.value, x.unit);
      line += fmt::format("; energy {:.6g} J, peak power {:.6g} W at {:.6g} s", st.energy_J, st.peak_power_W, st.t_peak_power);
      if (s.thermal) line += fmt::format("; temperature +{:.4g} K", st.temperature_end_degC - st.temperature_applied_degC);
      out += line + "\n";
    }
  }
  return out;
}

nlohmann::json simulation_summary(const Model& m, const SimulationResult& r) {
  nlohmann::json j;
  j["model"] = m.name;
  j["source"] = m.source;
  if (!m.load_case.empty()) j["case"] = m.load_case;
  const auto& s = m.simulation;
  j["settings"] = {{"t_end_s", s.t_end}, {"dt_out_s", s.dt_out}, {"rtol", s.rtol}, {"atol", s.atol},
                   {"integrator", method_name(s.integrator)}};
  nlohmann::json links = nlohmann::json::object();
  for (size_t l = 0; l < m.links.size(); ++l) {
    const auto& L = r.links[l];
    links[m.links[l].name] = {{"max", L.max},
                              {"min", L.min},
                              {"t_max", L.t_max},
                              {"t_min", L.t_min},
                              {"static_at_max", L.static_at_max},
                              {"static_at_min", L.static_at_min},
                              {"peak", L.peak},
                              {"t_peak", L.t_peak},
                              {"static", L.static_load},
                              {"dynamic_factor", json_number(L.dynamic_factor)},
                              {"unit", link_load_unit(m, m.links[l])}};
  }
  j["links"] = links;
  if (r.hybrid.active) add_hybrid_summary(m, r, j);
  if (const auto brakes = brake_summaries(m, r); !brakes.empty()) j["brakes"] = brake_stops_json(brakes);
  if (const auto& sway = r.sway; !sway.empty()) {  // spatial ropes: analysis/sway_summary.hpp
    nlohmann::json js = nlohmann::json::object();
    for (const SwaySummary& x : sway) {
      nlohmann::json e = {{"max_sway_rad", x.max_sway_rad}, {"t_max_sway_s", x.t_max_sway},
                          {"max_horizontal_force_N", x.max_horizontal_force_N},
                          {"t_max_horizontal_force_s", x.t_max_horizontal_force}, {"max_tension_N", x.max_tension_N}};
      if (x.residual_after) e["residual_after_s"] = *x.residual_after, e["residual_sway_rad"] = x.residual_sway_rad;
      if (x.dynamic_factor) e["rigid_force_N"] = *x.rigid_force_N, e["horizontal_dynamic_factor"] = *x.dynamic_factor;
      js[x.rope] = e;
    }
    j["sway"] = js;
  }
  if (!r.machines.empty()) {
    nlohmann::json ms = nlohmann::json::object();
    for (const auto& x : r.machines) {
      nlohmann::json e = {{"period_rad", x.period}, {"periods_run", x.periods_run}, {"jumps", x.jumps},
                          {"jump_loss_J", x.jump_loss}};
      if (x.window) {
        e["window_s"] = {x.t_from, x.t_to};
        e["omega_mean_rad_s"] = x.omega_mean;
        e["omega_max_rad_s"] = x.omega_max;
        e["omega_min_rad_s"] = x.omega_min;
        e["omega_delta"] = x.omega_delta;
        e["jumps_window"] = x.jumps_window;
        e["jump_loss_window_J"] = x.jump_loss_window;
        if (!x.point.empty())
          e[x.point + "_speed"] = {{"mean_m_s", x.v_mean},
                                   {"max_m_s", x.v_max},
                                   {"min_m_s", x.v_min},
                                   {"delta", x.delta},
                                   {"delta_previous_period", x.delta_previous >= 0 ? nlohmann::json(x.delta_previous)
                                                                                   : nlohmann::json(nullptr)}};
      }
      ms[x.body] = e;
    }
    j["machines"] = ms;
  }
  j["solver"] = {{"method", r.stats.method},
                 {"reason", r.method_reason},
                 {"steps", r.stats.stepper.steps},
                 {"rejected_steps", r.stats.stepper.rejected},
                 {"rhs_evals", r.stats.stepper.rhs_evals},
                 {"jac_evals", r.stats.stepper.jac_evals},
                 {"wall_time_s", r.stats.wall_time_s},
                 {"output_rows", r.columns.empty() ? 0 : r.columns[0].size()}};
  return j;
}

}  // namespace machdyn
