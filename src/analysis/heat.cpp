#include "analysis/heat.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <fmt/format.h>

namespace machdyn::detail {

Heat::Heat(const Model& m, DriveSystem& sys) : sys_(sys), n_(m.dof()) {
  contact_el_.assign(m.contacts.size(), -1);
  link_el_.assign(m.links.size(), -1);
  drive_el_.assign(m.drives.size(), -1);
  auto add = [&](std::vector<int>& kind, std::vector<int>* el, int i, const std::string& name) {
    if (el) (*el)[static_cast<size_t>(i)] = static_cast<int>(names_.size());
    kind.push_back(i);
    names_.push_back(name);
  };
  for (int k = 0; k < static_cast<int>(m.contacts.size()); ++k)
    if (!sys.contact(k).joint) add(contacts_, &contact_el_, k, m.contacts[static_cast<size_t>(k)].name);
  for (int l = 0; l < static_cast<int>(m.links.size()); ++l)
    if (const LinkLaw& k = sys.link(l); k.d > 0.0 || k.kh > 0.0) add(links_, &link_el_, l, m.links[static_cast<size_t>(l)].name);
  for (int g = 0; g < static_cast<int>(m.lossy_gears.size()); ++g)
    add(gears_, nullptr, g, m.lossy_gears[static_cast<size_t>(g)].name);
  own_power_.assign(names_.size(), 0);
  for (int d = 0; d < static_cast<int>(m.drives.size()); ++d) {
    const Drive& dr = m.drives[static_cast<size_t>(d)];
    if (!dr.law->dissipates()) continue;
    add(drives_, &drive_el_, d, dr.name);
    const auto own = dr.law->output_names(m.bodies[static_cast<size_t>(dr.body)].kind);
    own_power_.push_back(std::find(own.begin(), own.end(), "heat_power_W") != own.end());
  }
  for (int k : contacts_)
    if (const auto& th = m.contacts[static_cast<size_t>(k)].thermal) {
      thermal_.push_back(contact_el_[static_cast<size_t>(k)]);
      law_.emplace_back(*th);
      T_.push_back(th->initial);
    }
  heat_.assign(names_.size(), 0.0);
  part_heat_ = heat_;
  part_T_ = T_;
  p_.assign(names_.size(), 0.0);
  fc_.assign(m.contacts.size(), 0.0);
  acc_.assign(static_cast<size_t>(n_), 0.0);
  yq_.assign(static_cast<size_t>(sys.size()), 0.0);
}

void Heat::power(double t, const double* y, double* p) {
  int j = 0;
  if (!contacts_.empty()) sys_.evaluate(t, y, acc_.data(), fc_.data());
  for (int k : contacts_)  // + 0.0: a free stop's 0 · u is −0 for u < 0
    p[j++] = sys_.contact_mode(k) == ContactMode::stuck ? 0.0 : fc_[static_cast<size_t>(k)] * sys_.sliding_velocity(k, t, y) + 0.0;
  for (int l : links_) {
    const LinkLaw& k = sys_.link(l);
    const LinkLaw::Kinematics s = sys_.link_kinematics(l, y);
    p[j++] = k.dissipation(s.delta, s.rate, sys_.gap_mode(l), k.drum(y));
  }
  for (int g : gears_) p[j++] = LossyGearLaw::loss_power(sys_.gear_torques(g, t, y), y[n_ + sys_.lossy_gear(g).a]);
  for (int d : drives_)
    p[j++] = sys_.drive(d).heat_power(t, sys_.drive_motion(d, y), y + sys_.drive_offset(d), sys_.drive_mode(d));
}

void Heat::integrate(const Stepper& st, double ta, double tb, double* heat, double* temperature) {
  if (!(tb > ta) || names_.empty()) return;
  static constexpr double kX[3] = {-0.7745966692414834, 0.0, 0.7745966692414834};  // ±√(3/5), 0
  static constexpr double kW[3] = {5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0};
  const double mid = 0.5 * (ta + tb), half = 0.5 * (tb - ta);
  // T(tb) = T_a + (T(ta) − T_a) e^{−(tb−ta)/τ} + (1/C) ∫ e^{−(tb−s)/τ} P(s) ds (elements/thermal.hpp).
  for (size_t j = 0; j < thermal_.size(); ++j) temperature[j] = law_[j].relax(temperature[j], tb - ta);
  std::vector<double>& p = p_;
  for (int q = 0; q < 3; ++q) {
    const double tq = mid + half * kX[q];
    st.interpolate(tq, yq_.data());
    power(tq, yq_.data(), p.data());
    for (size_t j = 0; j < names_.size(); ++j) heat[j] += half * kW[q] * p[j];
    for (size_t j = 0; j < thermal_.size(); ++j)
      temperature[j] += law_[j].rise(half * kW[q] * p[static_cast<size_t>(thermal_[j])], tb - tq);
  }
  // A temperature beyond the doubles (a heat capacity of 1e-307 J/K heated by a few joules) is no
  // result: stop the run naming the element, instead of writing `inf`.
  for (size_t j = 0; j < thermal_.size(); ++j)
    if (!std::isfinite(temperature[j]))
      throw SolverError(names_[static_cast<size_t>(thermal_[j])], tb,
                        fmt::format("its temperature overflows: the friction heat over the heat capacity "
                                    "{:.3g} J/K is beyond any temperature (thermal: heat_capacity is too small)",
                                    law_[j].C));
}

void Heat::close_piece(const Stepper& st, double ta, double tb) {
  integrate(st, ta, tb, heat_.data(), T_.data());
  t_ = tb;
}

void Heat::add_impact(int contact, double loss) {
  if (const int j = contact_el_[static_cast<size_t>(contact)]; j >= 0) heat_[static_cast<size_t>(j)] += loss;
}

void Heat::add_release(int link, double loss) {
  // Only a damped flank opens off its flank (an undamped one opens at c e = 0): nothing else releases.
  if (const int j = link_el_[static_cast<size_t>(link)]; j >= 0) heat_[static_cast<size_t>(j)] += loss;
}

void Heat::add_drive_release(int drive, double loss) {
  if (const int j = drive_el_[static_cast<size_t>(drive)]; j >= 0) heat_[static_cast<size_t>(j)] += loss;
}

void Heat::at(const Stepper* st, double t, const double* y, double* power_out, double* heat, double* temperature) {
  // The values up to t: those of the closed pieces plus the open piece [t_, t] of the current step
  // (the output rows inside a step come before its piece is closed).
  std::copy(heat_.begin(), heat_.end(), part_heat_.begin());
  std::copy(T_.begin(), T_.end(), part_T_.begin());
  if (st && t > t_) integrate(*st, t_, t, part_heat_.data(), part_T_.data());
  const auto n = static_cast<long>(names_.size());
  if (power_out) {
    power(t, y, power_out);
    power_out[n] = std::accumulate(power_out, power_out + n, 0.0);
  }
  if (heat) {
    std::copy(part_heat_.begin(), part_heat_.end(), heat);
    heat[n] = std::accumulate(part_heat_.begin(), part_heat_.end(), 0.0);
  }
  if (temperature) std::copy(part_T_.begin(), part_T_.end(), temperature);
}

}  // namespace machdyn::detail
