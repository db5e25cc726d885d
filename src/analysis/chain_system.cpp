#include "machdyn/analysis/chain_system.hpp"

#include <fmt/format.h>

namespace machdyn {

ChainSystem::ChainSystem(const Model& model) : m_(model), n_(model.dof()) {
  for (const auto& b : model.bodies) inv_mass_.push_back(1.0 / b.inertia);
  for (const auto& l : model.links) links_.push_back({l.a, l.b, 1.0 / l.ratio, l.c, l.d});
}

void ChainSystem::initial_state(double* y) const {
  for (int i = 0; i < n_; ++i) {
    y[i] = m_.bodies[static_cast<size_t>(i)].q0;
    y[n_ + i] = m_.bodies[static_cast<size_t>(i)].v0;
  }
}

void ChainSystem::generalized_loads(double t, const double* y, double* f) const {
  for (int i = 0; i < n_; ++i) f[i] = 0.0;
  for (const auto& ld : m_.loads) f[ld.body] += ld.evaluate(t, y[n_ + ld.body]);
}

double ChainSystem::link_load(int l, const double* y) const {
  const FlatLink& k = links_[static_cast<size_t>(l)];
  const double* v = y + n_;
  double delta = 0, rate = 0;
  if (k.a >= 0) delta += y[k.a] * k.inv_ratio, rate += v[k.a] * k.inv_ratio;
  if (k.b >= 0) delta -= y[k.b], rate -= v[k.b];
  return k.c * delta + k.d * rate;
}

std::vector<double> ChainSystem::link_load_weights(int l) const {
  const FlatLink& k = links_[static_cast<size_t>(l)];
  std::vector<double> w(static_cast<size_t>(2 * n_), 0.0);
  if (k.a >= 0) {
    w[static_cast<size_t>(k.a)] += k.c * k.inv_ratio;
    w[static_cast<size_t>(n_ + k.a)] += k.d * k.inv_ratio;
  }
  if (k.b >= 0) {
    w[static_cast<size_t>(k.b)] -= k.c;
    w[static_cast<size_t>(n_ + k.b)] -= k.d;
  }
  return w;
}

void ChainSystem::rhs(double t, const double* y, double* dydt) {
  const double* v = y + n_;
  double* acc = dydt + n_;
  for (int i = 0; i < n_; ++i) dydt[i] = v[i];
  generalized_loads(t, y, acc);
  for (const auto& k : links_) {
    double delta = 0, rate = 0;
    if (k.a >= 0) delta += y[k.a] * k.inv_ratio, rate += v[k.a] * k.inv_ratio;
    if (k.b >= 0) delta -= y[k.b], rate -= v[k.b];
    const double F = k.c * delta + k.d * rate;
    if (k.a >= 0) acc[k.a] -= F * k.inv_ratio;
    if (k.b >= 0) acc[k.b] += F;
  }
  for (int i = 0; i < n_; ++i) acc[i] *= inv_mass_[static_cast<size_t>(i)];
}

void ChainSystem::jacobian(double t, const double* y, Eigen::Ref<Eigen::MatrixXd> J) {
  J.setZero();
  for (int i = 0; i < n_; ++i) J(i, n_ + i) = 1.0;
  // ∂(M⁻¹ f)/∂v from the motors.
  for (const auto& ld : m_.loads) J(n_ + ld.body, n_ + ld.body) += ld.slope(t, y[n_ + ld.body]);
  // −Bᵀ C B and −Bᵀ D B, link by link: row l of B has inv_ratio at a and −1 at b.
  for (const auto& k : links_) {
    const int idx[2] = {k.a, k.b};
    const double w[2] = {k.inv_ratio, -1.0};
    for (int r = 0; r < 2; ++r) {
      if (idx[r] < 0) continue;
      for (int s = 0; s < 2; ++s) {
        if (idx[s] < 0) continue;
        J(n_ + idx[r], idx[s]) -= k.c * w[r] * w[s];
        J(n_ + idx[r], n_ + idx[s]) -= k.d * w[r] * w[s];
      }
    }
  }
  for (int i = 0; i < n_; ++i) J.row(n_ + i) *= inv_mass_[static_cast<size_t>(i)];
}

std::string ChainSystem::state_name(int i) const {
  const bool vel = i >= n_;
  const auto& b = m_.bodies[static_cast<size_t>(vel ? i - n_ : i)];
  return fmt::format("body '{}' ({})", b.name, vel ? "velocity" : "position");
}

}  // namespace machdyn
