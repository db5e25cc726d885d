#include "machdyn/analysis/hybrid.hpp"

#include <cmath>
#include <Eigen/Dense>
#include <fmt/format.h>

#include "common/compiler.hpp"
#include "machdyn/model/machine.hpp"

namespace machdyn {
namespace {
// y = A x for the few stuck contacts (1–3): a plain loop beats Eigen's dynamic GEMV set-up here.
void mat_vec(const Eigen::MatrixXd& A, const Eigen::VectorXd& x, Eigen::VectorXd& y) {
  const Eigen::Index n = A.rows(), m = A.cols();
  for (Eigen::Index i = 0; i < n; ++i) {
    double s = 0.0;
    for (Eigen::Index j = 0; j < m; ++j) s += A(i, j) * x(j);
    y(i) = s;
  }
}
}  // namespace

const char* to_string(ContactMode m) {
  switch (m) {
    case ContactMode::stuck: return "stuck";
    case ContactMode::slip_pos: return "slip+";
    case ContactMode::slip_neg: return "slip-";
  }
  return "?";
}

const char* to_string(GapMode m) {
  switch (m) {
    case GapMode::open: return "open";
    case GapMode::closed_pos: return "closed+";
    case GapMode::closed_neg: return "closed-";
  }
  return "?";
}

HybridSystem::HybridSystem(const Model& model)
    : m_(model), n_(model.dof()), nl_(static_cast<int>(model.links.size())),
      nc_(static_cast<int>(model.contacts.size())) {
  for (const auto& b : model.bodies) {
    inv_mass_.push_back(1.0 / b.inertia);
    machine_.push_back(b.machine.get());
    if (b.machine) machine_bodies_.push_back(static_cast<int>(machine_.size()) - 1);
  }
  has_machines_ = !machine_bodies_.empty();
  im_ = inv_mass_;
  for (const auto& l : model.links) {
    const Machine* pa = l.a_point && l.a >= 0 ? machine_[static_cast<size_t>(l.a)] : nullptr;
    const Machine* pb = l.b_point && l.b >= 0 ? machine_[static_cast<size_t>(l.b)] : nullptr;
    links_.push_back({l.a, l.b, 1.0 / l.ratio, l.c, l.d, l.has_gap, pa || pb, -l.gap_start, l.gap - l.gap_start});
    link_point_.emplace_back(pa, pb);
  }
  for (const auto& c : model.contacts) {
    FlatContact k{c.a, c.b, c.kinetic.size() > 1, c.surface_times.size() > 1, c.brake,
                  c.kinetic.empty() ? 0.0 : c.kinetic.front(),
                  c.surface_velocities.empty() ? 0.0 : c.surface_velocities.front()};
    contacts_.push_back(k);
    const double ma = model.bodies[static_cast<size_t>(c.a)].inertia;
    stuck_share_.push_back(c.b >= 0 ? ma / (ma + model.bodies[static_cast<size_t>(c.b)].inertia) : 1.0);
  }
  f_const_.assign(static_cast<size_t>(n_), 0.0);
  for (const auto& ld : model.loads) {
    if (ld.kind == LoadKind::constant) f_const_[static_cast<size_t>(ld.body)] += ld.value;
    else varying_.push_back(&ld);
  }
  affine_eligible_ = varying_.empty() && !has_machines_;  // machines: nonlinear in y
  for (const auto& l : model.links) affine_eligible_ = affine_eligible_ && l.d == 0.0;
  for (const auto& k : contacts_) affine_eligible_ = affine_eligible_ && !k.kinetic_table && !k.moving_surface && !k.brake;
  gap_.assign(static_cast<size_t>(nl_), GapMode::open);
  f_.assign(static_cast<size_t>(n_), 0.0);
  fc_.assign(static_cast<size_t>(nc_), 0.0);
  set_contact_modes(std::vector<ContactMode>(static_cast<size_t>(nc_), ContactMode::stuck));
}

void HybridSystem::initial_state(double* y) const {
  for (int i = 0; i < n_; ++i) {
    y[i] = m_.bodies[static_cast<size_t>(i)].q0;
    y[n_ + i] = m_.bodies[static_cast<size_t>(i)].v0;
  }
  y[2 * n_] = y[2 * n_ + 1] = y[2 * n_ + 2] = 0.0;
}

// Out of line: the constant-inertia callers (deflection, link_load) stay small enough to inline.
__attribute__((noinline)) HybridSystem::PointState HybridSystem::point_state(int l, const double* y) const {
  const FlatLink& k = links_[static_cast<size_t>(l)];
  const auto [pa, pb] = link_point_[static_cast<size_t>(l)];
  const double* v = y + n_;
  const LinkDeflection d = link_deflection(k.a, k.b, k.inv_ratio, pa, pb, k.a >= 0 ? y[k.a] : 0.0,
                                           k.b >= 0 ? y[k.b] : 0.0, k.a >= 0 ? v[k.a] : 0.0, k.b >= 0 ? v[k.b] : 0.0);
  return {d.delta, d.rate, d.ja, d.jb};
}

namespace {
// δ = q_a/i − q_b of a link without output points (also δ̇ from the velocities).
template <class Link>
inline double linear_deflection(const Link& k, const double* y) {
  double d = 0;
  if (k.a >= 0) d += y[k.a] * k.inv_ratio;
  if (k.b >= 0) d -= y[k.b];
  return d;
}
}  // namespace

double HybridSystem::deflection(int l, const double* y) const {
  const FlatLink& k = links_[static_cast<size_t>(l)];
  if (k.point) [[unlikely]] return point_state(l, y).delta;
  return linear_deflection(k, y);
}

double HybridSystem::deflection_rate(int l, const double* y) const {
  const FlatLink& k = links_[static_cast<size_t>(l)];
  if (k.point) [[unlikely]] return point_state(l, y).rate;
  return linear_deflection(k, y + n_);
}

double HybridSystem::link_load(int l, const double* y) const {
  const FlatLink& k = links_[static_cast<size_t>(l)];
  const double delta = deflection(l, y), rate = deflection_rate(l, y);
  if (!k.gap) return k.c * delta + k.d * rate;
  switch (gap_[static_cast<size_t>(l)]) {
    case GapMode::open: return 0.0;
    case GapMode::closed_pos: return k.c * (delta - k.hi) + k.d * rate;
    case GapMode::closed_neg: return k.c * (delta - k.lo) + k.d * rate;
  }
  return 0.0;
}

double HybridSystem::link_load_rate(int l, const double* y, const double* dy) const {
  const FlatLink& k = links_[static_cast<size_t>(l)];
  if (k.gap && gap_[static_cast<size_t>(l)] == GapMode::open) return 0.0;
  if (!k.point) return k.c * linear_deflection(k, dy) + k.d * linear_deflection(k, dy + n_);
  const auto [pa, pb] = link_point_[static_cast<size_t>(l)];
  // δ̇ = Σ ± p′ v (/i), δ̈ = Σ ± (p″ v² + p′ a) (/i).
  double rate = 0, acc = 0, p, dp, ddp;
  if (k.a >= 0) {
    const double va = y[n_ + k.a], aa = dy[n_ + k.a];
    if (pa) pa->point(y[k.a], &p, &dp, &ddp);
    else dp = 1.0, ddp = 0.0;
    rate += dp * va * k.inv_ratio;
    acc += (ddp * va * va + dp * aa) * k.inv_ratio;
  }
  if (k.b >= 0) {
    const double vb = y[n_ + k.b], ab = dy[n_ + k.b];
    if (pb) pb->point(y[k.b], &p, &dp, &ddp);
    else dp = 1.0, ddp = 0.0;
    rate -= dp * vb;
    acc -= ddp * vb * vb + dp * ab;
  }
  return k.c * rate + k.d * acc;
}

double HybridSystem::sliding_velocity(int k, double t, const double* y) const {
  const FrictionContact& c = m_.contacts[static_cast<size_t>(k)];
  return y[n_ + c.a] - (c.b >= 0 ? y[n_ + c.b] : c.surface_velocity(t));
}

void HybridSystem::zero_sliding_velocity(int k, double t, double* y) const {
  const FrictionContact& c = m_.contacts[static_cast<size_t>(k)];
  std::vector<double> im(static_cast<size_t>(n_));
  inverse_inertias(y, im.data());
  const double u = sliding_velocity(k, t, y);
  const double ia = im[static_cast<size_t>(c.a)], ib = c.b >= 0 ? im[static_cast<size_t>(c.b)] : 0.0;
  y[n_ + c.a] -= u * ia / (ia + ib);
  if (c.b >= 0) y[n_ + c.b] += u * ib / (ia + ib);
  // Exact zero (rounding of the split above): the contact's own body takes the remainder.
  y[n_ + c.a] -= sliding_velocity(k, t, y);
}

GapMode HybridSystem::natural_gap_mode(int l, const double* y) const {
  const FlatLink& k = links_[static_cast<size_t>(l)];
  if (!k.gap) return GapMode::open;
  const double delta = deflection(l, y), rate = deflection_rate(l, y);
  const double Fp = k.c * (delta - k.hi) + k.d * rate, Fn = k.c * (delta - k.lo) + k.d * rate;
  if ((delta > k.hi && Fp > 0) || (delta == k.hi && rate > 0)) return GapMode::closed_pos;
  if ((delta < k.lo && Fn < 0) || (delta == k.lo && rate < 0)) return GapMode::closed_neg;
  return GapMode::open;
}

void HybridSystem::set_contact_modes(const std::vector<ContactMode>& modes) {
  mode_ = modes;
  affine_ = nullptr;
  stuck_.clear();
  for (int k = 0; k < nc_; ++k)
    if (mode_[static_cast<size_t>(k)] == ContactMode::stuck) stuck_.push_back(k);
  const Eigen::Index ns = static_cast<Eigen::Index>(stuck_.size());
  r_.resize(ns);
  lam_.resize(ns);
  stuck_machine_ = false;
  for (int k : stuck_) {
    const FlatContact& c = contacts_[static_cast<size_t>(k)];
    stuck_machine_ = stuck_machine_ || machine_[static_cast<size_t>(c.a)] || (c.b >= 0 && machine_[static_cast<size_t>(c.b)]);
  }
  if (ns == 0) return;
  if (stuck_machine_) {  // G M(q)⁻¹ Gᵀ depends on q: formed at every evaluation
    P_.resize(ns, ns);
    return;
  }
  uint64_t key = 0;
  const bool cacheable = nc_ <= 64;
  if (cacheable) {
    for (int k : stuck_) key |= uint64_t{1} << k;
    if (auto it = projector_cache_.find(key); it != projector_cache_.end()) {
      P_ = it->second.P;
      Pproj_ = it->second.Pproj;
      return;
    }
  }
  form_stuck_solution(inv_mass_.data());
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  cod.setThreshold(1e-12);
  cod.compute(stuck_matrix(inv_mass_.data()));
  Pproj_ = cod.pseudoInverse();
  if (cacheable) projector_cache_[key] = {P_, Pproj_};
}

Eigen::MatrixXd HybridSystem::stuck_matrix(const double* im) const {
  // A = G M⁻¹ Gᵀ; row j of G has +1 at body a and −1 at body b of stuck contact j.
  const Eigen::Index ns = static_cast<Eigen::Index>(stuck_.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(ns, ns);
  for (Eigen::Index i = 0; i < ns; ++i) {
    const auto& ci = m_.contacts[static_cast<size_t>(stuck_[static_cast<size_t>(i)])];
    for (Eigen::Index j = 0; j < ns; ++j) {
      const auto& cj = m_.contacts[static_cast<size_t>(stuck_[static_cast<size_t>(j)])];
      const int ei[2] = {ci.a, ci.b}, ej[2] = {cj.a, cj.b};
      const double si[2] = {1.0, -1.0};
      for (int p = 0; p < 2; ++p)
        for (int q = 0; q < 2; ++q)
          if (ei[p] >= 0 && ei[p] == ej[q]) A(i, j) += si[p] * si[q] * im[ei[p]];
    }
  }
  return A;
}

void HybridSystem::form_stuck_solution(const double* im) {
  const Eigen::Index ns = static_cast<Eigen::Index>(stuck_.size());
  const Eigen::MatrixXd A = stuck_matrix(im);
  if (ns == 1 && stuck_machine_) {  // one stuck contact: λ = r / (1/I_a + 1/I_b), no decomposition
    P_.resize(1, 1);
    P_(0, 0) = 1.0 / A(0, 0);
    return;
  }
  Eigen::VectorXd w(ns);
  for (Eigen::Index i = 0; i < ns; ++i)
    w(i) = std::sqrt(m_.contacts[static_cast<size_t>(stuck_[static_cast<size_t>(i)])].static_limit);
  // Weighted least norm: λ = D z, min ‖z‖ subject to A D z = r, D = diag(√F_s0).
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  cod.setThreshold(1e-12);
  cod.compute(A * w.asDiagonal());
  P_ = w.asDiagonal() * cod.pseudoInverse();
}

void HybridSystem::inverse_inertias(const double* y, double* im) const {
  for (int i = 0; i < n_; ++i) im[i] = inv_mass_[static_cast<size_t>(i)];
  for (int i : machine_bodies_) {
    double I, dI;
    machine_[static_cast<size_t>(i)]->inertia(y[i], &I, &dI);
    im[i] = 1.0 / I;
  }
}

// Few bodies: the vectorizer's prologues cost more than they save (as in ChainSystem::rhs).
template <bool kMach>
MACHDYN_NO_TREE_VECTORIZE void HybridSystem::forces(double t, const double* y, double* f,
                                                                         double* fc, double* p_src, double* p_fric,
                          double* p_damp) {
  const double* v = y + n_;
  double src = 0, fric = 0, damp = 0;
  for (int i = 0; i < n_; ++i) {
    f[i] = f_const_[static_cast<size_t>(i)];
    src += f[i] * v[i];
  }
  for (const Load* ld : varying_) {
    const double val = ld->evaluate(t, y[ld->body], v[ld->body]);
    f[ld->body] += val;
    src += val * v[ld->body];
  }
  if constexpr (kMach) {
    // I q'' + ½ I′ q'² = Q + ...: the velocity term joins the forces (it does no work on its own:
    // d/dt ½ I v² = v (I v' + ½ I′ v²)); the machine's force Q(q) is a source.
    for (int i : machine_bodies_) {
      const Machine* mach = machine_[static_cast<size_t>(i)];
      double I, dI;
      mach->inertia(y[i], &I, &dI);
      im_[static_cast<size_t>(i)] = 1.0 / I;
      const double Q = mach->force(y[i]);
      f[i] += Q - 0.5 * dI * v[i] * v[i];
      src += Q * v[i];
    }
  }
  for (size_t l = 0; l < links_.size(); ++l) {
    const FlatLink& k = links_[l];
    if constexpr (kMach) {
      if (k.point) {  // a machine's output point: δ = p_a/i − p_b, forces −F ja, +F jb
        const PointState s = point_state(static_cast<int>(l), y);
        double F;
        if (!k.gap) {
          F = k.c * s.delta + k.d * s.rate;
        } else {
          const GapMode g = gap_[l];
          if (g == GapMode::open) continue;
          F = k.c * (s.delta - (g == GapMode::closed_pos ? k.hi : k.lo)) + k.d * s.rate;
        }
        damp += k.d * s.rate * s.rate;
        if (k.a >= 0) f[k.a] -= F * s.ja;
        if (k.b >= 0) f[k.b] += F * s.jb;
        continue;
      }
    }
    double delta = 0, rate = 0;
    if (k.a >= 0) delta += y[k.a] * k.inv_ratio, rate += v[k.a] * k.inv_ratio;
    if (k.b >= 0) delta -= y[k.b], rate -= v[k.b];
    double F;
    if (!k.gap) {
      F = k.c * delta + k.d * rate;
    } else {
      const GapMode g = gap_[l];
      if (g == GapMode::open) continue;
      F = k.c * (delta - (g == GapMode::closed_pos ? k.hi : k.lo)) + k.d * rate;
    }
    damp += k.d * rate * rate;
    if (k.a >= 0) f[k.a] -= F * k.inv_ratio;
    if (k.b >= 0) f[k.b] += F;
  }
  for (int k = 0; k < nc_; ++k) {
    const ContactMode md = mode_[static_cast<size_t>(k)];
    if (md == ContactMode::stuck) continue;
    const FlatContact& c = contacts_[static_cast<size_t>(k)];
    const FrictionContact& full = m_.contacts[static_cast<size_t>(k)];
    const double w = c.b >= 0 ? v[c.b] : c.moving_surface ? full.surface_velocity(t) : c.surface0;
    const double u = v[c.a] - w;
    const double level = c.kinetic_table ? full.kinetic_level(std::abs(u)) : c.kinetic0;
    const double F = static_cast<double>(static_cast<int>(md)) * (c.brake ? full.scale(t) : 1.0) * level;
    fc[k] = F;
    f[c.a] -= F;
    if (c.b >= 0) f[c.b] += F;
    else src -= F * w;
    fric += F * u;
  }
  if (p_src) *p_src = src, *p_fric = fric, *p_damp = damp;
}

void HybridSystem::evaluate(double t, const double* y, double* acc, double* fc) {
  double src, fric, damp;
  if (has_machines_) evaluate_impl<true>(t, y, acc, fc, &src, &fric, &damp);
  else evaluate_impl<false>(t, y, acc, fc, &src, &fric, &damp);
}

// Inlined into evaluate(): the constant-inertia call is the same single function as before.
template <bool kMach>
__attribute__((always_inline)) inline void HybridSystem::evaluate_impl(double t, const double* y, double* acc, double* fc,
                                                                       double* src, double* fric, double* damp) {
  forces<kMach>(t, y, acc, fc, src, fric, damp);
  const double* im = kMach ? im_.data() : inv_mass_.data();
  for (int i = 0; i < n_; ++i) acc[i] *= im[i];
  if (stuck_.empty()) return;
  for (size_t j = 0; j < stuck_.size(); ++j) {
    const FrictionContact& c = m_.contacts[static_cast<size_t>(stuck_[j])];
    r_(static_cast<Eigen::Index>(j)) = acc[c.a] - (c.b >= 0 ? acc[c.b] : c.surface_acceleration(t));
  }
  if constexpr (kMach)
    if (stuck_machine_) form_stuck_solution(im);
  mat_vec(P_, r_, lam_);
  for (size_t j = 0; j < stuck_.size(); ++j) {
    const FrictionContact& c = m_.contacts[static_cast<size_t>(stuck_[j])];
    const double lam = lam_(static_cast<Eigen::Index>(j));
    fc[stuck_[j]] = lam;
    acc[c.a] -= im[c.a] * lam;
    if (c.b >= 0) acc[c.b] += im[c.b] * lam;
    else *src -= lam * c.surface_velocity(t);  // work of the moving surface on the stuck body
  }
  if constexpr (kMach) enforce_stuck_weighted(t, acc, im);
  else enforce_stuck(t, acc);
}

void HybridSystem::enforce_stuck(double t, double* acc) const {
  // Remove the rounding of λ: stuck bodies get exactly equal accelerations (the momentum-weighted
  // mean; the ground's is the surface acceleration), so u stays exactly zero along a stuck mode.
  for (int k : stuck_) {
    const FlatContact& c = contacts_[static_cast<size_t>(k)];
    if (c.b < 0) {
      acc[c.a] = c.moving_surface ? m_.contacts[static_cast<size_t>(k)].surface_acceleration(t) : 0.0;
    } else {
      const double s = stuck_share_[static_cast<size_t>(k)];
      acc[c.a] = acc[c.b] = s * acc[c.a] + (1.0 - s) * acc[c.b];
    }
  }
}

void HybridSystem::enforce_stuck_weighted(double t, double* acc, const double* im) const {
  // As enforce_stuck, with the shares of the current inertias I(q): s = I_a/(I_a + I_b).
  for (int k : stuck_) {
    const FlatContact& c = contacts_[static_cast<size_t>(k)];
    if (c.b < 0) {
      acc[c.a] = c.moving_surface ? m_.contacts[static_cast<size_t>(k)].surface_acceleration(t) : 0.0;
    } else {
      const double s = im[c.b] / (im[c.a] + im[c.b]);
      acc[c.a] = acc[c.b] = s * acc[c.a] + (1.0 - s) * acc[c.b];
    }
  }
}

const HybridSystem::AffineMode& HybridSystem::compile_affine() {
  std::string key;
  for (auto g : gap_) key += static_cast<char>('0' + static_cast<int>(g));
  key += '/';
  for (auto md : mode_) key += static_cast<char>('0' + static_cast<int>(md));
  if (auto it = affine_cache_.find(key); it != affine_cache_.end()) return it->second;
  const int N = size();
  AffineMode a;
  a.c.resize(N);
  Eigen::MatrixXd J(N, N);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(N), d(N);
  rhs_general<false>(0.0, y.data(), a.c.data());
  for (int j = 0; j < N; ++j) {
    y(j) = 1.0;
    rhs_general<false>(0.0, y.data(), d.data());
    J.col(j) = d - a.c;
    y(j) = 0.0;
  }
  for (int i = 0; i < N; ++i) {
    a.row_start.push_back(static_cast<int>(a.col.size()));
    for (int j = 0; j < N; ++j)
      if (J(i, j) != 0.0) a.col.push_back(j), a.val.push_back(J(i, j));
  }
  a.row_start.push_back(static_cast<int>(a.col.size()));
  return affine_cache_.emplace(std::move(key), std::move(a)).first->second;
}

void HybridSystem::rhs(double t, const double* y, double* dydt) {
  if (!affine_eligible_) {
    if (has_machines_) rhs_general<true>(t, y, dydt);
    else rhs_general<false>(t, y, dydt);
    return;
  }
  if (!affine_) affine_ = &compile_affine();
  const int N = size();
  const AffineMode& a = *affine_;
  const int* rs = a.row_start.data();
  const int* col = a.col.data();
  const double* val = a.val.data();
  const double* c = a.c.data();
  for (int i = 0; i < N; ++i) {
    double s = c[i];
    for (int k = rs[i]; k < rs[i + 1]; ++k) s += val[k] * y[col[k]];
    dydt[i] = s;
  }
}

// Out of line: rhs() stays the small affine loop.
template <bool kMach>
__attribute__((noinline)) void HybridSystem::rhs_general(double t, const double* y, double* dydt) {
  for (int i = 0; i < n_; ++i) dydt[i] = y[n_ + i];
  double src, fric, damp;
  evaluate_impl<kMach>(t, y, dydt + n_, fc_.data(), &src, &fric, &damp);
  dydt[2 * n_] = src;
  dydt[2 * n_ + 1] = fric;
  dydt[2 * n_ + 2] = damp;
}

void HybridSystem::external_forces(double t, const double* y, double* f) {
  std::vector<double> acc(static_cast<size_t>(n_)), fc(static_cast<size_t>(nc_));
  evaluate(t, y, acc.data(), fc.data());
  for (int i = 0; i < n_; ++i) f[i] = 0.0;
  for (const auto& ld : m_.loads) f[ld.body] += ld.evaluate(t, y[ld.body], y[n_ + ld.body]);
  for (int i : machine_bodies_) f[i] += machine_[static_cast<size_t>(i)]->force(y[i]);
  for (int k = 0; k < nc_; ++k) {
    const FrictionContact& c = m_.contacts[static_cast<size_t>(k)];
    f[c.a] -= fc[static_cast<size_t>(k)];
    if (c.b >= 0) f[c.b] += fc[static_cast<size_t>(k)];
  }
}

double HybridSystem::kinetic_energy(const double* y) const {
  double T = 0;
  for (int i = 0; i < n_; ++i) {
    double I = m_.bodies[static_cast<size_t>(i)].inertia, dI;
    if (const Machine* mach = machine_[static_cast<size_t>(i)]) mach->inertia(y[i], &I, &dI);  // ½ I(q) v²
    T += 0.5 * I * y[n_ + i] * y[n_ + i];
  }
  return T;
}

double HybridSystem::elastic_energy(const double* y) const {
  double V = 0;
  for (int l = 0; l < nl_; ++l) {
    const FlatLink& k = links_[static_cast<size_t>(l)];
    double e = deflection(l, y);
    if (k.gap) {
      const GapMode g = gap_[static_cast<size_t>(l)];
      if (g == GapMode::open) continue;
      e -= g == GapMode::closed_pos ? k.hi : k.lo;
    }
    V += 0.5 * k.c * e * e;
  }
  return V;
}

void HybridSystem::event_functions(double t, const double* y, double* g) {
  if (!stuck_.empty()) {
    // λ of the stuck contacts, into fc_.
    std::vector<double>& acc = f_;
    evaluate(t, y, acc.data(), fc_.data());
  }
  for (int l = 0; l < nl_; ++l) {
    const FlatLink& k = links_[static_cast<size_t>(l)];
    double* gl = g + 2 * l;
    gl[0] = gl[1] = 1.0;
    if (!k.gap) continue;
    const double delta = deflection(l, y), rate = deflection_rate(l, y);
    const double Fp = k.c * (delta - k.hi) + k.d * rate, Fn = k.c * (delta - k.lo) + k.d * rate;
    switch (gap_[static_cast<size_t>(l)]) {
      case GapMode::closed_pos: gl[0] = Fp; break;
      case GapMode::closed_neg: gl[1] = -Fn; break;
      case GapMode::open:
        gl[0] = delta < k.hi ? k.hi - delta : -Fp;  // reaches the positive flank, pressing
        gl[1] = delta > k.lo ? delta - k.lo : Fn;   // reaches the negative flank, pressing
        break;
    }
  }
  for (int k = 0; k < nc_; ++k) {
    double* gc = g + 2 * nl_ + 2 * k;
    const FrictionContact& c = m_.contacts[static_cast<size_t>(k)];
    const ContactMode md = mode_[static_cast<size_t>(k)];
    if (md == ContactMode::stuck) {
      const double Fs = c.scale(t) * c.static_limit, lam = fc_[static_cast<size_t>(k)];
      gc[0] = Fs - lam;
      gc[1] = Fs + lam;
    } else {
      gc[0] = static_cast<double>(static_cast<int>(md)) * sliding_velocity(k, t, y);
      gc[1] = 1.0;
    }
  }
}

void HybridSystem::project_velocities(double t, double* y) const {
  if (stuck_.empty()) return;
  // Minimal M-norm velocity change that makes every stuck contact's sliding velocity zero:
  // Δv = −M⁻¹ Gᵀ (G M⁻¹ Gᵀ)⁺ G v. With machines M = diag(I_i(q_i)) at the current positions.
  const double* im = inv_mass_.data();
  const Eigen::MatrixXd* P = &Pproj_;
  std::vector<double> im_q;
  Eigen::MatrixXd P_q;
  if (has_machines_) {
    im_q.resize(static_cast<size_t>(n_));
    inverse_inertias(y, im_q.data());
    im = im_q.data();
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
    cod.setThreshold(1e-12);
    cod.compute(stuck_matrix(im));
    P_q = cod.pseudoInverse();
    P = &P_q;
  }
  Eigen::VectorXd r(static_cast<Eigen::Index>(stuck_.size()));
  for (size_t j = 0; j < stuck_.size(); ++j) r(static_cast<Eigen::Index>(j)) = sliding_velocity(stuck_[j], t, y);
  const Eigen::VectorXd mu = *P * r;
  double* v = y + n_;
  for (size_t j = 0; j < stuck_.size(); ++j) {
    const FrictionContact& c = m_.contacts[static_cast<size_t>(stuck_[j])];
    v[c.a] -= im[c.a] * mu(static_cast<Eigen::Index>(j));
    if (c.b >= 0) v[c.b] += im[c.b] * mu(static_cast<Eigen::Index>(j));
  }
  // Remove the rounding: u exactly 0 (as enforce_stuck does for the accelerations); the common
  // velocity is the momentum mean (I_a v_a + I_b v_b)/(I_a + I_b).
  for (int k : stuck_) {
    const FrictionContact& c = m_.contacts[static_cast<size_t>(k)];
    if (c.b < 0) {
      v[c.a] = c.surface_velocity(t);
    } else {
      const double ia = im[c.a], ib = im[c.b];
      v[c.a] = v[c.b] = (ib * v[c.a] + ia * v[c.b]) / (ia + ib);
    }
  }
}

std::string HybridSystem::state_name(int i) const {
  if (i >= 2 * n_) return "energy quadrature";
  const bool vel = i >= n_;
  const auto& b = m_.bodies[static_cast<size_t>(vel ? i - n_ : i)];
  return fmt::format("body '{}' ({})", b.name, vel ? "velocity" : "position");
}

}  // namespace machdyn
