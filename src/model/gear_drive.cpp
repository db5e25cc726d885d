#include "machdyn/model/gear_drive.hpp"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <stdexcept>
#include <utility>

namespace machdyn {

GearDrive::GearDrive(Params p, gears::GearModel gear_model, const gears::GearSynthesis& synthesis)
    : p_(p), gears_(std::move(gear_model)), T_(gears_.T()), Theta_(gears_.Theta()) {
  if (gears_.law.kind() != gears::RatioLaw::Kind::Walking)
    throw std::invalid_argument("gear-drive: the propulsor's travel X(φ) is known for the walking law only");
  // X′ = A + B cos 2φ with B = k A (k = 3b/(a − b + c)) and X′(0) = A + B.
  const double k = gears_.law.k();
  A_ = gears_.law.travel(0.0) / (1.0 + k);
  B_ = k * A_;
  XT_ = A_ * T_ + B_ * std::sin(T_);
  const auto& S = synthesis.sectors;
  const size_t n = S.size();
  if (n == 0) throw std::invalid_argument("gear-drive: empty sector table");
  // Segments in increasing θ: B_k = θ of sector n − k (k = 1..n), B_0 = θ_1 − Θ (closed onto the
  // next big sector, so that φ(θ) is continuous and periodic whatever the synthesis defect).
  Bth_.assign(n + 1, 0.0);
  Pphi_.assign(n + 1, 0.0);
  Bth_[0] = S[0].theta - Theta_;
  Pphi_[0] = S[0].phi - T_;
  for (size_t j = 1; j <= n; ++j) {
    Bth_[j] = S[n - j].theta;
    Pphi_[j] = S[n - j].phi;
  }
  iseg_.resize(n);
  for (size_t m = 0; m < n; ++m) iseg_[m] = (Bth_[m + 1] - Bth_[m]) / (Pphi_[m + 1] - Pphi_[m]);
}

std::string GearDrive::part_name(int k) const { return k == 0 ? "pinion" : k == 1 ? "wheel" : "vehicle"; }

double GearDrive::reduce(double theta, double* k) const {
  *k = std::floor((theta - Bth_[0]) / Theta_);
  double w = theta - *k * Theta_;
  if (w >= Bth_.back()) w -= Theta_, *k += 1.0;  // rounding at the upper end
  if (w < Bth_[0]) w = Bth_[0];
  return w;
}

size_t GearDrive::segment(double theta_w) const {
  const auto it = std::upper_bound(Bth_.begin(), Bth_.end(), theta_w);
  const auto m = static_cast<size_t>(std::max<std::ptrdiff_t>(1, it - Bth_.begin())) - 1;
  return std::min(m, iseg_.size() - 1);
}

GearDrive::Kinematics GearDrive::kinematics(double theta) const {
  double k;
  const double w = reduce(theta, &k);
  if (p_.ratio == Ratio::stepwise) {
    const size_t m = segment(w);
    const double g = 1.0 / iseg_[m];
    return {k * T_ + Pphi_[m] + (w - Bth_[m]) * g, g, 0.0};
  }
  // Continuous: the big sector of θ ∈ [θ_1 − Θ, θ_1) is φ ∈ [−T/2, T/2) (θ(T/2) = θ_1).
  const double phi_w = gears_.law.phi_of_theta(w);
  const Jet i = gears_.law.ratio(phi_w);
  const double g = 1.0 / i.v;
  return {k * T_ + phi_w, g, -i.d * g * g * g};  // d(1/i)/dθ = −i′/i² · dφ/dθ
}

void GearDrive::travel(double phi, double* X, double* dX, double* ddX) const {
  const double pw = gears_.law.wrap(phi);
  const double k = std::round((phi - pw) / T_);
  const double s2 = std::sin(2.0 * pw), c2 = std::cos(2.0 * pw);
  *X = k * XT_ + A_ * pw + 0.5 * B_ * s2;
  *dX = A_ + B_ * c2;
  *ddX = -2.0 * B_ * s2;
}

void GearDrive::part_inertia(int k, double q, double* I, double* dI) const {
  if (k == 0) {
    *I = p_.I_p, *dI = 0.0;
    return;
  }
  const Kinematics kin = kinematics(q);
  if (k == 1) {
    *I = p_.I_H * kin.g * kin.g;
    *dI = 2.0 * p_.I_H * kin.g * kin.dg;
    return;
  }
  double X, dX, ddX;
  travel(kin.phi, &X, &dX, &ddX);
  const double Xt = dX * kin.g, Xtt = ddX * kin.g * kin.g + dX * kin.dg;
  *I = p_.m * Xt * Xt;
  *dI = 2.0 * p_.m * Xt * Xtt;
}

double GearDrive::force(double q) const {
  if (p_.F_r == 0.0) return 0.0;
  const Kinematics kin = kinematics(q);
  double X, dX, ddX;
  travel(kin.phi, &X, &dX, &ddX);
  return -p_.F_r * dX * kin.g;
}

void GearDrive::point(double q, double* p, double* dp, double* ddp) const {
  const Kinematics kin = kinematics(q);
  double X, dX, ddX;
  travel(kin.phi, &X, &dX, &ddX);
  *p = X;
  *dp = dX * kin.g;
  *ddp = ddX * kin.g * kin.g + dX * kin.dg;
}

void GearDrive::extras(double q, double* out) const {
  const Kinematics kin = kinematics(q);
  out[0] = kin.phi;
  out[1] = 1.0 / kin.g;
}

double GearDrive::next_jump(double q, int dir) const {
  if (p_.ratio != Ratio::stepwise) return Machine::next_jump(q, dir);
  const double tol = 1e-12 * (1.0 + std::abs(q));
  double k;
  const double w = reduce(q, &k);
  const size_t n = iseg_.size();
  if (dir > 0) {
    const auto idx = static_cast<size_t>(std::upper_bound(Bth_.begin(), Bth_.end(), w + tol) - Bth_.begin());
    return idx <= n ? k * Theta_ + Bth_[idx] : (k + 1.0) * Theta_ + Bth_[1];
  }
  const auto idx = std::lower_bound(Bth_.begin(), Bth_.end(), w - tol) - Bth_.begin();
  return idx >= 1 ? k * Theta_ + Bth_[static_cast<size_t>(idx - 1)] : (k - 1.0) * Theta_ + Bth_[n - 1];
}

double GearDrive::ratio_beside(double qj, int dir) const {
  double k;
  const double w = reduce(qj, &k);
  const size_t n = iseg_.size();
  size_t best = 0;
  for (size_t m = 1; m <= n; ++m)
    if (std::abs(Bth_[m] - w) < std::abs(Bth_[best] - w)) best = m;
  best %= n;  // B_n is B_0 of the next big sector
  return dir > 0 ? iseg_[best] : iseg_[(best + n - 1) % n];
}

double GearDrive::velocity_after_jump(double qj, int dir, double w, double* loss) const {
  if (p_.ratio != Ratio::stepwise) return Machine::velocity_after_jump(qj, dir, w, loss);
  const double i_minus = ratio_beside(qj, -dir), i_plus = ratio_beside(qj, dir);
  double X, dX, ddX;
  travel(kinematics(qj).phi, &X, &dX, &ddX);
  const double J_H = p_.I_H + p_.m * dX * dX;  // carrier side about φ
  const double I_minus = p_.I_p + J_H / (i_minus * i_minus), I_plus = p_.I_p + J_H / (i_plus * i_plus);
  // (I_p + J_H/i+²) θ'+ = (I_p + J_H/(i− i+)) θ'−  (header: plastic impact of the new tooth pair)
  const double w_plus = w * (p_.I_p + J_H / (i_minus * i_plus)) / I_plus;
  *loss = 0.5 * I_minus * w * w - 0.5 * I_plus * w_plus * w_plus;
  return w_plus;
}

}  // namespace machdyn
