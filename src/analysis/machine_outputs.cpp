#include "machdyn/analysis/machine_outputs.hpp"

#include <algorithm>

#include "machdyn/model/machine.hpp"

namespace machdyn {

bool has_machines(const Model& m) {
  return std::any_of(m.bodies.begin(), m.bodies.end(), [](const Body& b) { return b.machine != nullptr; }) ||
         std::any_of(m.links.begin(), m.links.end(), [](const Link& l) { return l.a_point || l.b_point; });
}

namespace {
size_t find_column(const SimulationResult& r, const std::string& prefix) {
  for (size_t c = 0; c < r.column_names.size(); ++c)
    if (r.column_names[c].rfind(prefix, 0) == 0) return c;
  return r.column_names.size();
}
}  // namespace

void append_machine_outputs(const Model& m, SimulationResult& r,
                            const std::function<void(size_t row, const double* y, double* acc)>& accel) {
  if (!has_machines(m) || r.columns.empty()) return;
  const int n = m.dof();
  const size_t rows = r.columns[0].size();
  // The state at every output row, from the position and velocity columns.
  std::vector<size_t> qc(static_cast<size_t>(n)), vc(static_cast<size_t>(n));
  for (int i = 0; i < n; ++i) {
    qc[static_cast<size_t>(i)] = find_column(r, m.bodies[static_cast<size_t>(i)].name + ".position_");
    vc[static_cast<size_t>(i)] = find_column(r, m.bodies[static_cast<size_t>(i)].name + ".velocity_");
    if (qc[static_cast<size_t>(i)] >= r.columns.size() || vc[static_cast<size_t>(i)] >= r.columns.size()) return;
  }
  std::vector<std::vector<double>> Y(rows, std::vector<double>(static_cast<size_t>(2 * n)));
  std::vector<std::vector<double>> dY(rows, std::vector<double>(static_cast<size_t>(2 * n)));
  for (size_t k = 0; k < rows; ++k) {
    for (int i = 0; i < n; ++i) {
      Y[k][static_cast<size_t>(i)] = r.columns[qc[static_cast<size_t>(i)]][k];
      Y[k][static_cast<size_t>(n + i)] = r.columns[vc[static_cast<size_t>(i)]][k];
    }
    accel(k, Y[k].data(), dY[k].data() + n);
  }
  for (int i = 0; i < n; ++i) {
    const Body& b = m.bodies[static_cast<size_t>(i)];
    if (!b.machine) continue;
    const Machine& mach = *b.machine;
    const auto ui = static_cast<size_t>(i), vi = static_cast<size_t>(n + i);
    std::vector<std::string> names = {b.name + ".inertia_kg_m2", b.name + ".acceleration_rad_s2"};
    for (int p = 0; p < mach.parts(); ++p) names.push_back(b.name + ".M_" + mach.part_name(p) + "_N_m");
    if (!mach.point_name().empty()) names.push_back(b.name + "." + mach.point_name() + "_m");
    const bool point_speed = !mach.point_name().empty() && mach.reports_point_speed();
    if (point_speed) names.push_back(b.name + "." + mach.point_name() + "_speed_m_s");
    for (const auto& e : mach.extra_names()) names.push_back(b.name + "." + e);
    std::vector<std::vector<double>> cols(names.size());
    std::vector<double> extra(mach.extra_names().size());
    for (size_t k = 0; k < rows; ++k) {
      const double q = Y[k][ui], w = Y[k][vi], eps = dY[k][vi];
      size_t c = 0;
      double I, dI;
      mach.inertia(q, &I, &dI);
      cols[c++].push_back(I);
      cols[c++].push_back(eps);
      for (int p = 0; p < mach.parts(); ++p) {
        mach.part_inertia(p, q, &I, &dI);
        cols[c++].push_back(-I * eps - 0.5 * dI * w * w);  // paper 004 eq. 5
      }
      if (!mach.point_name().empty()) {
        double x, dx, ddx;
        mach.point(q, &x, &dx, &ddx);
        cols[c++].push_back(x);
        if (point_speed) cols[c++].push_back(dx * w);
      }
      mach.extras(q, extra.data());
      for (double e : extra) cols[c++].push_back(e);
    }
    for (size_t c = 0; c < names.size(); ++c) {
      r.column_names.push_back(names[c]);
      r.columns.push_back(std::move(cols[c]));
    }
  }
}

}  // namespace machdyn
