#include "machdyn/analysis/chain_system.hpp"

#include <cmath>
#include <fmt/format.h>

#include "machdyn/analysis/modes.hpp"
#include "common/compiler.hpp"
#include "machdyn/model/machine.hpp"

namespace machdyn {
namespace {

template <int N>
void dense_rhs(const double* y, double* dydt, const double* Aq, const double* Av, const double* b) {
  using Vec = Eigen::Matrix<double, N, 1>;
  using Mat = Eigen::Matrix<double, N, N>;
  Eigen::Map<const Vec> q(y), v(y + N), bb(b);
  Eigen::Map<Vec> qd(dydt), acc(dydt + N);
  qd = v;
  acc.noalias() = Eigen::Map<const Mat>(Aq) * q + Eigen::Map<const Mat>(Av) * v + bb;
}

using DenseFn = void (*)(const double*, double*, const double*, const double*, const double*);
constexpr DenseFn kDense[] = {dense_rhs<1>, dense_rhs<2>, dense_rhs<3>, dense_rhs<4>,
                              dense_rhs<5>, dense_rhs<6>, dense_rhs<7>, dense_rhs<8>};

}  // namespace

ChainSystem::ChainSystem(const Model& model)
    : m_(model), n_(model.dof()), q_lo_(static_cast<size_t>(n_), -HUGE_VAL), q_hi_(static_cast<size_t>(n_), HUGE_VAL) {
  for (const auto& b : model.bodies) {
    inv_mass_.push_back(1.0 / b.inertia);
    machine_.push_back(b.machine.get());
    nonlinear_ = nonlinear_ || b.machine;
  }
  for (const auto& l : model.links) {
    FlatLink k{l.a, l.b, 1.0 / l.ratio, l.c, l.d};
    if (l.a_point) k.pa = machine_[static_cast<size_t>(l.a)];
    if (l.b_point) k.pb = machine_[static_cast<size_t>(l.b)];
    nonlinear_ = nonlinear_ || k.pa || k.pb;
    links_.push_back(k);
  }
  if (nonlinear_) return;
  for (const auto& k : links_) {
    if (k.a >= 0 && k.b >= 0) between_.push_back(k);
    // A ground link's deflection is q_a/i (ground at b) or −q_b (ground at a): store the body in
    // `a` with the signed factor, so F = c (s q) + d (s v) and the body gets −s F.
    else if (k.a >= 0) grounded_.push_back({k.a, -1, k.inv_ratio, k.c, k.d});
    else if (k.b >= 0) grounded_.push_back({k.b, -1, -1.0, k.c, k.d});
  }
  f_const_.assign(static_cast<size_t>(n_), 0.0);
  for (const auto& ld : model.loads) {
    if (ld.kind == LoadKind::constant) f_const_[static_cast<size_t>(ld.body)] += ld.value;
    else varying_.push_back(&ld);
  }
  if (n_ >= 1 && n_ <= 8) {
    const Eigen::VectorXd im = Eigen::Map<const Eigen::VectorXd>(inv_mass_.data(), n_);
    const Eigen::MatrixXd Aq = -(im.asDiagonal() * stiffness_matrix(model));
    const Eigen::MatrixXd Av = -(im.asDiagonal() * damping_matrix(model));
    Aq_.assign(Aq.data(), Aq.data() + Aq.size());
    Av_.assign(Av.data(), Av.data() + Av.size());
    for (int i = 0; i < n_; ++i) b_.push_back(f_const_[static_cast<size_t>(i)] * inv_mass_[static_cast<size_t>(i)]);
    dense_ = kDense[n_ - 1];
  }
}

ChainSystem::LinkState ChainSystem::link_state(const FlatLink& k, const double* y) const {
  const double* v = y + n_;
  const LinkDeflection d = link_deflection(k.a, k.b, k.inv_ratio, k.pa, k.pb, k.a >= 0 ? mq(k.a, y) : 0.0,
                                           k.b >= 0 ? mq(k.b, y) : 0.0, k.a >= 0 ? v[k.a] : 0.0, k.b >= 0 ? v[k.b] : 0.0);
  return {d.delta, d.rate, d.ja, d.jb};
}

void ChainSystem::initial_state(double* y) const {
  for (int i = 0; i < n_; ++i) {
    y[i] = m_.bodies[static_cast<size_t>(i)].q0;
    y[n_ + i] = m_.bodies[static_cast<size_t>(i)].v0;
  }
}

void ChainSystem::generalized_loads(double t, const double* y, double* f) const {
  for (int i = 0; i < n_; ++i) f[i] = machine_[static_cast<size_t>(i)] ? machine_[static_cast<size_t>(i)]->force(mq(i, y)) : 0.0;
  for (const auto& ld : m_.loads) f[ld.body] += ld.evaluate(t, y[ld.body], y[n_ + ld.body]);
}

void ChainSystem::set_evaluation_window(int body, double lo, double hi) {
  q_lo_[static_cast<size_t>(body)] = lo;
  q_hi_[static_cast<size_t>(body)] = hi;
}

double ChainSystem::link_load(int l, const double* y) const {
  const FlatLink& k = links_[static_cast<size_t>(l)];
  const LinkState s = link_state(k, y);
  return k.c * s.delta + k.d * s.rate;
}

SparseWeights ChainSystem::link_load_weights(int l) const {
  const FlatLink& k = links_[static_cast<size_t>(l)];
  SparseWeights w;
  auto add = [&](int i, double v) {
    for (size_t j = 0; j < w.idx.size(); ++j)
      if (w.idx[j] == i) {
        w.w[j] += v;
        return;
      }
    w.idx.push_back(i), w.w.push_back(v);
  };
  if (k.a >= 0) add(k.a, k.c * k.inv_ratio), add(n_ + k.a, k.d * k.inv_ratio);
  if (k.b >= 0) add(k.b, -k.c), add(n_ + k.b, -k.d);
  return w;
}

// Small chains dominate: the vectorizer's prologues cost more than they save at n = 2…20.
MACHDYN_NO_TREE_VECTORIZE void ChainSystem::rhs(double t, const double* y, double* dydt) {
  if (nonlinear_) return rhs_nonlinear(t, y, dydt);
  if (dense_) {
    dense_(y, dydt, Aq_.data(), Av_.data(), b_.data());
    for (const Load* ld : varying_)
      dydt[n_ + ld->body] += ld->evaluate(t, y[ld->body], y[n_ + ld->body]) * inv_mass_[static_cast<size_t>(ld->body)];
    return;
  }
  // Local, non-aliased pointers: the stores into acc must not force reloads of the model arrays.
  const int n = n_;
  const double* __restrict q = y;
  const double* __restrict v = y + n;
  double* __restrict acc = dydt + n;
  const double* __restrict fc = f_const_.data();
  const double* __restrict im = inv_mass_.data();
  for (int i = 0; i < n; ++i) {
    dydt[i] = v[i];
    acc[i] = fc[i];
  }
  for (const Load* ld : varying_) acc[ld->body] += ld->evaluate(t, q[ld->body], v[ld->body]);
  const FlatLink* __restrict L = between_.data();
  for (size_t j = 0, nl = between_.size(); j < nl; ++j) {
    const FlatLink& k = L[j];
    const double F = k.c * (q[k.a] * k.inv_ratio - q[k.b]) + k.d * (v[k.a] * k.inv_ratio - v[k.b]);
    acc[k.a] -= F * k.inv_ratio;
    acc[k.b] += F;
  }
  const FlatLink* __restrict G = grounded_.data();
  for (size_t j = 0, ng = grounded_.size(); j < ng; ++j) {
    const FlatLink& k = G[j];
    acc[k.a] -= (k.c * q[k.a] + k.d * v[k.a]) * k.inv_ratio * k.inv_ratio;
  }
  for (int i = 0; i < n; ++i) acc[i] *= im[i];
}

void ChainSystem::rhs_nonlinear(double t, const double* y, double* dydt) {
  const double* v = y + n_;
  double* acc = dydt + n_;
  for (int i = 0; i < n_; ++i) {
    dydt[i] = v[i];
    acc[i] = 0.0;
  }
  for (const auto& ld : m_.loads) acc[ld.body] += ld.evaluate(t, y[ld.body], v[ld.body]);
  for (const auto& k : links_) {
    const LinkState s = link_state(k, y);
    const double F = k.c * s.delta + k.d * s.rate;
    if (k.a >= 0) acc[k.a] -= F * s.ja;
    if (k.b >= 0) acc[k.b] += F * s.jb;
  }
  for (int i = 0; i < n_; ++i) {
    if (const Machine* mach = machine_[static_cast<size_t>(i)]) {
      // I q'' + ½ I′ q'² = Q_machine + loads + links (model/machine.hpp).
      double I, dI, Q;
      mach->dynamics(mq(i, y), &I, &dI, &Q);
      acc[i] = (acc[i] + Q - 0.5 * dI * v[i] * v[i]) / I;
    } else {
      acc[i] *= inv_mass_[static_cast<size_t>(i)];
    }
  }
}

void ChainSystem::numeric_jacobian(double t, const double* y, Eigen::Ref<Eigen::MatrixXd> J) {
  // Central differences, step √ε-scaled per state (fourth root of ε for the 2nd-order scheme).
  const int n = size();
  std::vector<double> yp(y, y + n), fp(static_cast<size_t>(n)), fm(static_cast<size_t>(n));
  for (int j = 0; j < n; ++j) {
    const double h = 6e-6 * std::max(1.0, std::abs(y[j]));
    yp[static_cast<size_t>(j)] = y[j] + h;
    rhs(t, yp.data(), fp.data());
    yp[static_cast<size_t>(j)] = y[j] - h;
    rhs(t, yp.data(), fm.data());
    yp[static_cast<size_t>(j)] = y[j];
    for (int i = 0; i < n; ++i) J(i, j) = (fp[static_cast<size_t>(i)] - fm[static_cast<size_t>(i)]) / (2 * h);
  }
}

void ChainSystem::jacobian(double t, const double* y, Eigen::Ref<Eigen::MatrixXd> J) {
  if (nonlinear_) {
    numeric_jacobian(t, y, J);
    return;
  }
  J.setZero();
  for (int i = 0; i < n_; ++i) J(i, n_ + i) = 1.0;
  // ∂(M⁻¹ f)/∂v from the motors.
  for (const auto& ld : m_.loads) {
    J(n_ + ld.body, n_ + ld.body) += ld.slope(t, y[ld.body], y[n_ + ld.body]);
    J(n_ + ld.body, ld.body) += ld.position_slope(t, y[ld.body], y[n_ + ld.body]);
  }
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

void ChainSystem::sparse_jacobian(double t, const double* y, Eigen::SparseMatrix<double>& J) {
  // The entries of jacobian(), as triplets (duplicates summed, zeros kept: a fixed pattern).
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(2 * n_ + 8 * static_cast<int>(links_.size()) + static_cast<int>(m_.loads.size())));
  for (int i = 0; i < n_; ++i) trip.emplace_back(i, n_ + i, 1.0);
  // Every diagonal entry present (zero for positions): CVODE forms I − γJ in place on this pattern;
  // a missing diagonal makes it rebuild the whole matrix at every setup.
  for (int i = 0; i < 2 * n_; ++i) trip.emplace_back(i, i, 0.0);
  auto im = [&](int i) { return inv_mass_[static_cast<size_t>(i)]; };
  for (const auto& ld : m_.loads) {
    trip.emplace_back(n_ + ld.body, n_ + ld.body, ld.slope(t, y[ld.body], y[n_ + ld.body]) * im(ld.body));
    trip.emplace_back(n_ + ld.body, ld.body, ld.position_slope(t, y[ld.body], y[n_ + ld.body]) * im(ld.body));
  }
  for (const auto& k : links_) {
    const int idx[2] = {k.a, k.b};
    const double w[2] = {k.inv_ratio, -1.0};
    for (int r = 0; r < 2; ++r) {
      if (idx[r] < 0) continue;
      for (int c = 0; c < 2; ++c) {
        if (idx[c] < 0) continue;
        trip.emplace_back(n_ + idx[r], idx[c], -k.c * w[r] * w[c] * im(idx[r]));
        trip.emplace_back(n_ + idx[r], n_ + idx[c], -k.d * w[r] * w[c] * im(idx[r]));
      }
    }
  }
  J.resize(2 * n_, 2 * n_);
  J.setFromTriplets(trip.begin(), trip.end());
  J.makeCompressed();
}

std::vector<double> ChainSystem::breakpoints(double t0, double t_end) const {
  std::vector<double> b = m_.breakpoints(t_end);
  std::erase_if(b, [&](double t) { return t <= t0; });
  return b;
}

std::string ChainSystem::state_name(int i) const {
  const bool vel = i >= n_;
  const auto& b = m_.bodies[static_cast<size_t>(vel ? i - n_ : i)];
  return fmt::format("body '{}' ({})", b.name, vel ? "velocity" : "position");
}

}  // namespace machdyn
