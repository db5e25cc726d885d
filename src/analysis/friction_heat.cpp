#include "analysis/friction_heat.hpp"

#include <algorithm>

namespace machdyn::detail {

FrictionHeat::FrictionHeat(const Model& m, DriveSystem& sys) : sys_(sys), nc_(static_cast<int>(m.contacts.size())) {
  for (int k = 0; k < nc_; ++k)
    if (const auto& th = m.contacts[static_cast<size_t>(k)].thermal) {
      thermal_.push_back(k);
      law_.emplace_back(*th);
      T_.push_back(th->initial);
    }
  heat_.assign(static_cast<size_t>(nc_), 0.0);
  part_heat_ = heat_;
  part_T_ = T_;
  p_.assign(static_cast<size_t>(nc_), 0.0);
  fc_.assign(static_cast<size_t>(nc_), 0.0);
  acc_.assign(static_cast<size_t>(m.dof()), 0.0);
  yq_.assign(static_cast<size_t>(sys.size()), 0.0);
}

void FrictionHeat::power(double t, const double* y, double* p) {
  sys_.evaluate(t, y, acc_.data(), fc_.data());
  for (int k = 0; k < nc_; ++k)
    p[k] = sys_.contact_mode(k) == ContactMode::stuck ? 0.0 : fc_[static_cast<size_t>(k)] * sys_.sliding_velocity(k, t, y);
}

void FrictionHeat::integrate(const Stepper& st, double ta, double tb, double* heat, double* temperature) {
  if (!(tb > ta) || nc_ == 0) return;
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
    for (int k = 0; k < nc_; ++k) heat[k] += half * kW[q] * p[static_cast<size_t>(k)];
    for (size_t j = 0; j < thermal_.size(); ++j)
      temperature[j] += law_[j].rise(half * kW[q] * p[static_cast<size_t>(thermal_[j])], tb - tq);
  }
}

void FrictionHeat::close_piece(const Stepper& st, double ta, double tb) {
  integrate(st, ta, tb, heat_.data(), T_.data());
  t_ = tb;
}

void FrictionHeat::at(const Stepper* st, double t, const double* y, double* power_out, double* heat, double* temperature) {
  // The values up to t: those of the closed pieces plus the open piece [t_, t] of the current step
  // (the output rows inside a step come before its piece is closed).
  std::copy(heat_.begin(), heat_.end(), part_heat_.begin());
  std::copy(T_.begin(), T_.end(), part_T_.begin());
  if (st && t > t_) integrate(*st, t_, t, part_heat_.data(), part_T_.data());
  if (power_out) power(t, y, power_out);
  if (heat) std::copy(part_heat_.begin(), part_heat_.end(), heat);
  if (temperature) std::copy(part_T_.begin(), part_T_.end(), temperature);
}

}  // namespace machdyn::detail
