#include "machdyn/io/energy_results.hpp"

#include <cmath>

#include "machdyn/model/machine.hpp"
#include "io/number_text.hpp"

namespace machdyn {

nlohmann::json energy_json(const Model& m, const EnergyResult& r) {
  const Machine* mach = m.bodies[0].machine.get();
  nlohmann::json j;
  j["model"] = m.name;
  j["source"] = m.source;
  j["body"] = r.body;
  j["machine"] = r.machine;
  j["q0"] = r.q0;
  j["omega0"] = r.omega0;
  j["direction"] = r.direction;
  j["turning_points"] = r.turning_points;
  j["omega_max"] = r.omega_max;
  j["q_at_omega_max"] = r.q_at_omega_max;
  j["omega_min"] = r.omega_min;
  j["q_at_omega_min"] = r.q_at_omega_min;
  j["omega_limit"] = r.omega_limit ? json_number(*r.omega_limit) : nlohmann::json();
  j["limit"] = r.limit_kind;
  j["epsilon_limit"] = r.epsilon_limit ? json_number(*r.epsilon_limit) : nlohmann::json();  // rad/s², with "unbounded"
  if (r.work_per_period) j["work_per_period"] = *r.work_per_period;
  j["units"] = {{"q", "rad"}, {"omega", "rad/s"}, {"epsilon_limit", "rad/s^2"}, {"I", "kg*m^2"}, {"A", "J"}};
  // Values in the sweep coordinate (β for the wheel) and at the output point (x, piston).
  std::vector<double> tp_s, tp_p;
  auto point = [&](double q) {
    double p, dp, ddp;
    mach->point(q, &p, &dp, &ddp);
    return p;
  };
  if (mach && r.s_name != "q") {
    j[r.s_name + "_0"] = mach->s_of_q(r.q0);
    for (double q : r.turning_points) tp_s.push_back(mach->s_of_q(q));
    j[r.s_name + "_turning_points"] = tp_s;
    j[r.s_name + "_at_omega_max"] = mach->s_of_q(r.q_at_omega_max);
    j[r.s_name + "_at_omega_min"] = mach->s_of_q(r.q_at_omega_min);
    if (mach->s_end()) j[r.s_name + "_limit"] = *mach->s_end();
    j["units"][r.s_name] = "rad";
  }
  if (mach && !r.point_name.empty()) {
    for (double q : r.turning_points) tp_p.push_back(point(q));
    j[r.point_name + "_turning_points"] = tp_p;
    j[r.point_name + "_at_omega_max"] = point(r.q_at_omega_max);
    j[r.point_name + "_at_omega_min"] = point(r.q_at_omega_min);
    j["units"][r.point_name] = "m";
  }
  nlohmann::json t;
  std::vector<double> q, w, I, A, s, p;
  for (const auto& row : r.table) {
    q.push_back(row.q), w.push_back(row.omega), I.push_back(row.inertia), A.push_back(row.work), s.push_back(row.s);
    if (mach && !r.point_name.empty()) p.push_back(point(row.q));
  }
  t["q"] = q;
  t["omega"] = w;
  t["I"] = I;
  t["A"] = A;
  if (r.s_name != "q") t[r.s_name] = s;
  if (!p.empty()) t[r.point_name] = p;
  j["table"] = t;
  return j;
}

nlohmann::json steady_json(const SteadyResult& s) {
  return {{"omega_mean", s.omega_mean},
          {"work_per_period", s.work_per_period},
          {"balancing_torque", s.balancing_torque},
          {"delta", s.delta},
          {"omega_max", s.omega_max},
          {"omega_min", s.omega_min},
          {"mean_inertia", s.mean_inertia},
          {"delta_target", s.delta_target},
          {"flywheel_inertia", s.flywheel_inertia},
          {"flywheel_estimate", s.flywheel_estimate},
          {"delta_with_flywheel", s.delta_with_flywheel},
          {"omega_max_with_flywheel", s.omega_max_fw},
          {"omega_min_with_flywheel", s.omega_min_fw},
          {"omega_start_with_flywheel", s.omega_start_fw}};
}

}  // namespace machdyn
