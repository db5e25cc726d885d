#include "report_brakes.hpp"

#include <cmath>
#include <string>

#include <fmt/format.h>

namespace machdyn::report {

std::optional<Table> brake_stops_table(const Model& m, const SimulationResult& r) {
  const std::vector<BrakeSummary> brakes = brake_summaries(m, r);
  if (brakes.empty()) return std::nullopt;
  Table t;
  t.caption = "Brakes: stops, energy, temperature";
  t.header = {"brake", "stop", "from, s", "end", "travel", "energy, J", "peak power, W", "temperature rise, K",
              "max. temperature, °C", "temperature at the end, °C"};
  auto num = [](double v) { return std::isfinite(v) ? fmt::format("{:.6g}", v) : std::string("–"); };
  for (const BrakeSummary& s : brakes) {
    const std::string t_max = s.thermal ? fmt::format("{} at {} s", num(s.temperature_max_degC), num(s.t_temperature_max)) : "–";
    const std::string t_last = s.thermal ? num(s.temperature_end_degC) : "–";
    if (s.stops.empty())
      t.rows.push_back({s.brake, "–", "not applied", "–", "–", num(s.energy_J),
                        fmt::format("{} at {} s", num(s.peak_power_W), num(s.t_peak_power)), "–", t_max, t_last});
    for (size_t k = 0; k < s.stops.size(); ++k) {
      const BrakeStop& st = s.stops[k];
      std::string travel;
      for (const auto& x : st.travel) travel += fmt::format("{}{} {} {}", travel.empty() ? "" : ", ", x.body, num(x.value), x.unit);
      const std::string end = st.end == BrakeStop::End::stuck      ? fmt::format("stopped after {} s", num(*st.stopping_time))
                              : st.end == BrakeStop::End::released ? fmt::format("released after {} s", num(st.t_end - st.t_applied))
                                                                   : std::string("not at rest by t_end");
      const std::string from = st.start == BrakeStop::Start::applied ? num(st.t_applied)
                               : st.start == BrakeStop::Start::overcome ? num(st.t_applied) + " (overcome)"
                                                                          : num(st.t_applied) + " (sliding)";
      t.rows.push_back({s.brake, fmt::format("{}", k + 1), from, end, travel.empty() ? "–" : travel,
                        num(st.energy_J), fmt::format("{} at {} s", num(st.peak_power_W), num(st.t_peak_power)),
                        s.thermal ? num(st.temperature_end_degC - st.temperature_applied_degC) : "–", t_max, t_last});
    }
  }
  t.note = "A stop runs from where the applied brake begins to slide to its body at rest (stopped) or the brake lifted "
           "(released); the travel of the braked body and of every translational body joined to it (the load), the "
           "energy (the brake's friction heat), peak power and temperature rise are those of the stop; the temperatures "
           "at the right are the run's.";
  return t;
}

}  // namespace machdyn::report
