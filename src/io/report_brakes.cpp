#include "report_brakes.hpp"

#include <cmath>
#include <string>

#include <fmt/format.h>

namespace machdyn::report {

std::optional<Table> brake_stops_table(const Model& m, const SimulationResult& r) {
  const std::vector<BrakeStop> stops = brake_stops(m, r);
  if (stops.empty()) return std::nullopt;
  Table t;
  t.caption = "Brakes: stops, energy, temperature";
  t.header = {"brake", "applied, s", "stopping time, s", "travel", "energy, J", "peak power, W", "max. temperature, °C",
              "temperature at the end, °C"};
  auto num = [](double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : std::string("–"); };
  for (const BrakeStop& s : stops) {
    std::string travel;
    for (const auto& x : s.travel) travel += fmt::format("{}{} {} {}", travel.empty() ? "" : ", ", x.body, num(x.value), x.unit);
    t.rows.push_back({s.brake, s.t_applied ? num(*s.t_applied) : "not applied",
                      s.stopping_time ? num(*s.stopping_time) : (s.t_applied ? "not at rest by t_end" : "–"),
                      travel.empty() ? "–" : travel, num(s.energy_J),
                      fmt::format("{} at {} s", num(s.peak_power_W), num(s.t_peak_power)),
                      s.thermal ? fmt::format("{} at {} s", num(s.temperature_max_degC), num(s.t_temperature_max)) : "–",
                      s.thermal ? num(s.temperature_end_degC) : "–"});
  }
  t.note = "From the first application that meets its body moving to its body at rest; the travel of the braked body and of "
           "every translational body joined to it (the load) in that time; the energy is the brake's friction heat over the "
           "whole run.";
  return t;
}

}  // namespace machdyn::report
