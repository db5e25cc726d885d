#include "machdyn/analysis/drive_system.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <utility>
#include <Eigen/Dense>
#include <fmt/format.h>

#include "analysis/affine_kernels.hpp"
#include "analysis/bounded_share.hpp"
#include "common/compiler.hpp"
#include "machdyn/model/machine.hpp"

namespace machdyn {

namespace {
/// The M-orthogonal (momentum-keeping) step that takes the residual e of a velocity row Σ w_j x_j to
/// zero: Δx_j = −e (w_j/I_j) / Σ_i w_i²/I_i, for velocities or accelerations x.
void step_onto_row(const VelocityRow& r, double e, double* x, const double* im) {
  double s = 0.0;
  for (int j = 0; j < r.terms; ++j) s += r.w[j] * r.w[j] * im[r.body[j]];
  for (int j = 0; j < r.terms; ++j) x[r.body[j]] -= e * r.w[j] * im[r.body[j]] / s;
}

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

namespace {
// out = A y + c for R rows (DriveSystem::AffineRows): the R sums stay in registers, one column of
// A at a time. Each sum starts at c and adds the columns in ascending order. C > 0: out[i] = y[C + i]
// for i < C first (q̇ = v), the rows then from out[C] on.
template <int R, int C>
void affine_rows(const int* cols, int ncols, const double* A, const double* c, const double* y, double* out) {
  double s[R];
  for (int r = 0; r < R; ++r) s[r] = c[r];
  for (int k = 0; k < ncols; ++k, A += R) {
    const double x = y[cols[k]];
    for (int r = 0; r < R; ++r) s[r] += A[r] * x;
  }
  detail::store_in_pairs<C, R>(y, s, out);
}
using detail::RowsKernel;
// The kernels by row count R = 1…16: without a copy (contact forces), with C = R (a chain's
// accelerations, a mode without energy books) and with C = R − 3 (a mode with the three energy rates).
template <int... Rs>
constexpr std::array<RowsKernel, sizeof...(Rs)> kernels(int shift, std::integer_sequence<int, Rs...>) {
  if (shift == 0) return {affine_rows<Rs + 1, 0>...};
  if (shift == 1) return {affine_rows<Rs + 1, Rs + 1>...};
  return {(Rs + 1 > 3 ? affine_rows<Rs + 1, (Rs + 1 > 3 ? Rs + 1 - 3 : 0)> : nullptr)...};
}
// A small chain's accelerations: a = Aq q + Av v + b as fixed-size products (A = [Aq, Av], n × 2n
// column-major), q̇ = v first: the rounding of the chain path as it always was.
template <int N>
void chain_rows(const int*, int, const double* A, const double* b, const double* y, double* dydt) {
  using Vec = Eigen::Matrix<double, N, 1>;
  using Mat = Eigen::Matrix<double, N, N>;
  Eigen::Map<const Vec> q(y), v(y + N), bb(b);
  Vec acc;
  acc.noalias() = Eigen::Map<const Mat>(A) * q + Eigen::Map<const Mat>(A + N * N) * v + bb;
  detail::store_in_pairs<N, N>(y, acc.data(), dydt);  // q̇ = v, then the accelerations
}
constexpr RowsKernel kChain[] = {chain_rows<1>, chain_rows<2>, chain_rows<3>, chain_rows<4>,
                                 chain_rows<5>, chain_rows<6>, chain_rows<7>, chain_rows<8>};
// A chain without dampers: Av = 0 (entries ±0), so Av v is a zero for every finite v, and
// (Aq q + Av v) + b = Aq q + b to the bit: x + (±0) = x for x ≠ 0; for x = ±0 both sides are b
// when b ≠ 0, and +0 when b = +0 (b = f_const/I is never −0: f_const sums from +0).
template <int N>
void chain_rows_undamped(const int*, int, const double* A, const double* b, const double* y, double* dydt) {
  using Vec = Eigen::Matrix<double, N, 1>;
  using Mat = Eigen::Matrix<double, N, N>;
  Eigen::Map<const Vec> q(y), bb(b);
  Vec acc;
  acc.noalias() = Eigen::Map<const Mat>(A) * q + bb;
  detail::store_in_pairs<N, N>(y, acc.data(), dydt);
}
constexpr RowsKernel kChainUndamped[] = {chain_rows_undamped<1>, chain_rows_undamped<2>, chain_rows_undamped<3>,
                                         chain_rows_undamped<4>, chain_rows_undamped<5>, chain_rows_undamped<6>,
                                         chain_rows_undamped<7>, chain_rows_undamped<8>};

constexpr auto kRows = kernels(0, std::make_integer_sequence<int, 16>{});
constexpr auto kRowsCopy = kernels(1, std::make_integer_sequence<int, 16>{});
constexpr auto kRowsEnergy = kernels(2, std::make_integer_sequence<int, 16>{});
constexpr int kMaxRowsCols = 32;  // beyond: the compressed rows (dense zeros would cost more)

}  // namespace

void DriveSystem::AffineRows::build(const Eigen::MatrixXd& M, const Eigen::VectorXd& c0, int r0, int r1, int m) {
  rows = r1 - r0;
  copy = m;
  kernel = nullptr;
  cols.clear(), A.clear(), c.clear();
  if (rows < 1 || rows > static_cast<int>(kRows.size())) return;
  const RowsKernel k = m == 0 ? kRows[static_cast<size_t>(rows - 1)]
                       : m == rows ? kRowsCopy[static_cast<size_t>(rows - 1)]
                       : m == rows - 3 ? kRowsEnergy[static_cast<size_t>(rows - 1)]
                                       : nullptr;
  if (!k) return;
  cols.reserve(static_cast<size_t>(M.cols()));  // sized once, as A and c: no allocation per doubling
  for (Eigen::Index j = 0; j < M.cols(); ++j)
    if ((M.block(r0, j, rows, 1).array() != 0.0).any()) cols.push_back(static_cast<int>(j));
  if (static_cast<int>(cols.size()) > kMaxRowsCols) {
    cols.clear();
    return;
  }
  A.reserve(cols.size() * static_cast<size_t>(rows));
  c.reserve(static_cast<size_t>(rows));
  for (const int j : cols)
    for (int r = r0; r < r1; ++r) A.push_back(M(r, j));
  for (int r = r0; r < r1; ++r) c.push_back(c0(r));
  kernel = k;
  const int K = static_cast<int>(cols.size());
  if (rows <= detail::kUnrolledRows && K >= 1 && K <= detail::kUnrolledCols) {
    static const bool avx = detail::cpu_has_avx();
    const auto shape = m == 0 ? detail::RowsCopy::none : m == rows ? detail::RowsCopy::all : detail::RowsCopy::energy;
    kernel = detail::unrolled_rows_kernel(rows, K, shape, avx);
  }
}

DriveSystem::DriveSystem(const Model& model, bool energy_books)
    : m_(model), n_(model.dof()), nl_(static_cast<int>(model.links.size())),
      nc_(static_cast<int>(model.contacts.size())), energy_(energy_books),
      q_lo_(static_cast<size_t>(n_), -HUGE_VAL), q_hi_(static_cast<size_t>(n_), HUGE_VAL) {
  for (const auto& b : model.bodies) {
    inertia_.push_back(b.inertia);
    inv_mass_.push_back(1.0 / b.inertia);
    machine_.push_back(b.machine.get());
    if (b.machine) machine_bodies_.push_back(static_cast<int>(machine_.size()) - 1);
  }
  // Prescribed motions: infinitely heavy (inverse inertia 0), their acceleration from the signal.
  for (int i = 0; i < n_; ++i)
    if (model.bodies[static_cast<size_t>(i)].motion != MotionKind::free) {
      motions_.push_back(PrescribedMotionLaw::of(model, i));
      inv_mass_[static_cast<size_t>(i)] = 0.0;
    }
  motion_f_.assign(motions_.size(), 0.0);
  im_ = inv_mass_;
  for (const auto& l : model.links) {
    links_.push_back(LinkLaw::of(model, l));
    const LinkLaw& k = links_.back();
    has_machines_ = has_machines_ || k.point;
    all_plain_ = all_plain_ && !(k.gap || k.capped || k.shaped || k.winding || k.point);
  }
  has_machines_ = has_machines_ || !machine_bodies_.empty();
  for (const auto& c : model.contacts) {
    contacts_.push_back(ContactLaw::of(c, model));  // kinematic: between prescribed motions
    const double ma = model.bodies[static_cast<size_t>(c.a)].inertia;
    stuck_share_.push_back(c.b >= 0 ? ma / (ma + model.bodies[static_cast<size_t>(c.b)].inertia) : 1.0);
  }
  for (const auto& dr : model.drives) {
    drives_.push_back(dr.law.get());
    drive_body_.push_back(dr.body);
    drive_off_.push_back(2 * n_ + nx_);
    nx_ += dr.law->states();
  }
  nd_ = static_cast<int>(drives_.size());
  for (const auto& g : model.lossy_gears) gears_.push_back(LossyGearLaw::of(g));
  ng_ = static_cast<int>(gears_.size());
  gear_mode_.assign(static_cast<size_t>(ng_), GearMode::stuck);
  gear_t_.assign(static_cast<size_t>(ng_), {});
  gear_fa_.assign(static_cast<size_t>(ng_), 0.0);
  gear_fb_.assign(static_cast<size_t>(ng_), 0.0);
  // A prescribed side (elements/lossy_gear.hpp "Prescribed side"; compile allows at most one).
  gear_motion_.assign(static_cast<size_t>(ng_), -1);
  gear_b_given_.assign(static_cast<size_t>(ng_), 0);
  gear_now_.assign(static_cast<size_t>(ng_), GearMode::stuck);
  for (int g = 0; g < ng_; ++g)
    for (size_t j = 0; j < motions_.size(); ++j) {
      const LossyGearLaw& k = gears_[static_cast<size_t>(g)];
      if (motions_[j].body != k.a && motions_[j].body != k.b) continue;
      gear_motion_[static_cast<size_t>(g)] = static_cast<int>(j);
      gear_b_given_[static_cast<size_t>(g)] = motions_[j].body == k.b;
    }
  locks_ = machdyn::gear_locks(gears_, contacts_);
  // Clutches on a gear's body (analysis/gear_clutch.hpp): the stuck contacts then see the gears' law.
  gear_of_body_.assign(static_cast<size_t>(n_), -1);
  gear_clutch_.assign(static_cast<size_t>(ng_), 0);
  gear_joint_.assign(static_cast<size_t>(ng_), 0);
  for (int g = 0; g < ng_; ++g)
    gear_of_body_[static_cast<size_t>(gears_[static_cast<size_t>(g)].a)] =
        gear_of_body_[static_cast<size_t>(gears_[static_cast<size_t>(g)].b)] = g;
  for (const ContactLaw& c : contacts_)
    for (int p = 0; p < c.row.terms && !c.grounded && !c.joint; ++p)
      if (const int g = gear_of_body_[static_cast<size_t>(c.row.body[p])]; g >= 0) gear_clutch_[static_cast<size_t>(g)] = 1;
  for (char c : gear_clutch_) coupled_ = coupled_ || c != 0;
  // Two lossy gears on one body (analysis/gear_train.hpp): their own joint solve, no contacts on them.
  trains_ = find_gear_trains(gears_, inertia_);
  train_of_gear_.assign(static_cast<size_t>(ng_), -1);
  for (size_t t = 0; t < trains_.size(); ++t)
    for (int g : trains_[t].gears) train_of_gear_[static_cast<size_t>(g)] = static_cast<int>(t);
  train_f_.assign(trains_.size(), {});
  for (int g = 0; g < ng_; ++g) {  // a massless side: 1/I is infinite, C is not
    const LossyGearLaw& k = gears_[static_cast<size_t>(g)];
    if (train_of_gear_[static_cast<size_t>(g)] < 0)
      coupled_ = coupled_ || inertia_[static_cast<size_t>(k.a)] == 0.0 || inertia_[static_cast<size_t>(k.b)] == 0.0;
  }
  general_ = has_machines_ || nd_ > 0 || !motions_.empty();
  drive_mode_.assign(static_cast<size_t>(nd_), 0);
  f_const_.assign(static_cast<size_t>(n_), 0.0);
  for (const auto& ld : model.loads) {
    if (ld.kind == LoadKind::constant) ld.spread(ld.value, f_const_.data());
    else varying_.push_back(&ld);
  }
  affine_eligible_ = varying_.empty() && nd_ == 0 && ng_ == 0 && !has_machines_ && motions_.empty() && (nl_ + nc_ > 0);  // machines: nonlinear in y
  // A winding rope's c(q_a) and a shaped buffer's F_e(e) + F_v(δ̇) make their loads nonlinear in y:
  // the general path.
  for (const auto& l : links_) affine_eligible_ = affine_eligible_ && l.d == 0.0 && !l.winding && !l.shaped;
  for (const auto& k : contacts_) affine_eligible_ = affine_eligible_ && !k.kinetic_table && !k.moving_surface && !k.applied;
  gap_.assign(static_cast<size_t>(nl_), GapMode::open);
  f_.assign(static_cast<size_t>(n_), 0.0);
  fc_.assign(static_cast<size_t>(nc_), 0.0);
  set_contact_modes(std::vector<ContactMode>(static_cast<size_t>(nc_), ContactMode::stuck));
  // The small chain without events: its linear part as dense M⁻¹K and M⁻¹D, from the links' own
  // Jacobian terms (elements/link.hpp).
  bool gaps = false;
  for (const auto& l : links_) gaps = gaps || l.gap;
  if (!energy_ && !has_machines_ && !gaps && nc_ == 0 && nd_ == 0 && ng_ == 0 && motions_.empty() && n_ >= 1 &&
      n_ <= 8)
    form_dense();
}

void DriveSystem::form_dense() {
  auto& A = chain_.A;  // [−M⁻¹K, −M⁻¹D], n × 2n column-major
  A.assign(static_cast<size_t>(2 * n_ * n_), 0.0);
  for (const auto& l : links_)
    l.jacobian(n_, GapMode::open, [&](int r, int c, double v) { A[static_cast<size_t>(c * n_ + r)] += v; });
  // −K and −D summed over the links first, then scaled: the rounding of M⁻¹ (f − K q − D v).
  for (size_t e = 0; e < A.size(); ++e) A[e] *= inv_mass_[e % static_cast<size_t>(n_)];
  chain_.c.clear();
  std::vector<double> f0 = f_const_;
  for (const auto& l : links_) l.rest_forces(f0.data());  // a free length's constant part (elements/link.hpp)
  for (int i = 0; i < n_; ++i) chain_.c.push_back(f0[static_cast<size_t>(i)] * inv_mass_[static_cast<size_t>(i)]);
  chain_.rows = chain_.copy = n_;
  const bool undamped = std::all_of(A.begin() + n_ * n_, A.end(), [](double a) { return a == 0.0; });
  chain_.kernel = undamped ? kChainUndamped[n_ - 1] : kChain[n_ - 1];
  dense_ = true;
  mode_changed();
}

double DriveSystem::apply_release(const Release& r, const double* v) {
  const auto i = static_cast<size_t>(r.body);
  const double released = 0.5 * r.amount * v[r.body] * v[r.body];
  inertia_[i] -= r.amount;
  const bool prescribed = m_.bodies[i].motion != MotionKind::free;  // stays infinitely heavy; R sees the new I
  inv_mass_[i] = im_[i] = prescribed ? 0.0 : 1.0 / inertia_[i];
  for (PrescribedMotionLaw& k : motions_)
    if (k.body == r.body) k.inertia = inertia_[i];
  f_const_[i] += r.weight_change;  // the released part's weight leaves with it (model.hpp: Release)
  // Everything formed from the masses, formed again: the momentum shares of stuck contacts, the
  // dense chain, the affine map of each mode, the projectors of each stuck set.
  for (int k = 0; k < nc_; ++k) {
    const auto& c = m_.contacts[static_cast<size_t>(k)];
    const double ma = inertia_[static_cast<size_t>(c.a)];
    stuck_share_[static_cast<size_t>(k)] = c.b >= 0 ? ma / (ma + inertia_[static_cast<size_t>(c.b)]) : 1.0;
  }
  affine_cache_.clear();  // before mode_changed(): no pointer into the old cache stays
  projector_cache_.clear();
  mode_changed();
  if (dense_) form_dense();
  set_contact_modes(std::vector<ContactMode>(mode_));
  return released;
}

void DriveSystem::initial_state(double* y) const {
  for (int i = 0; i < n_; ++i) {
    y[i] = m_.bodies[static_cast<size_t>(i)].q0;
    y[n_ + i] = m_.bodies[static_cast<size_t>(i)].v0;
  }
  for (int d = 0; d < nd_; ++d) drive(d).initial_states(y + drive_offset(d));
  if (energy_) y[energy_index()] = y[energy_index() + 1] = y[energy_index() + 2] = 0.0;
}

void DriveSystem::set_evaluation_window(int body, double lo, double hi) {
  q_lo_[static_cast<size_t>(body)] = lo;
  q_hi_[static_cast<size_t>(body)] = hi;
  windows_ = true;
}

const double* DriveSystem::machine_positions(const double* y) const {
  if (!windows_) return y;
  qw_.assign(y, y + n_);
  for (int i : machine_bodies_)
    qw_[static_cast<size_t>(i)] = std::clamp(y[i], q_lo_[static_cast<size_t>(i)], q_hi_[static_cast<size_t>(i)]);
  return qw_.data();
}

LinkLaw::Kinematics DriveSystem::point_kinematics(int l, const double* y) const {
  return links_[static_cast<size_t>(l)].kinematics(machine_positions(y), y + n_);
}

double DriveSystem::point_load_rate(int l, const double* y, const double* dy) const {
  return links_[static_cast<size_t>(l)].load_rate(machine_positions(y), y + n_, dy + n_, gap_[static_cast<size_t>(l)]);
}

void DriveSystem::zero_sliding_velocity(int k, double t, double* y) const {
  const ContactLaw& c = contacts_[static_cast<size_t>(k)];
  // I⁻¹: the constant inverse masses themselves unless a machine's inertia varies (no copy per event).
  std::vector<double> im_q;
  const double* im = inv_mass_.data();
  if (!machine_bodies_.empty()) {
    im_q.resize(static_cast<size_t>(n_));
    inverse_inertias(y, im_q.data());
    im = im_q.data();
  }
  const double u = sliding_velocity(k, t, y);
  if (c.kinematic) {  // no inertia to share by: its first body takes the rounding of the motions
    y[n_ + c.row.body[0]] -= u / c.row.w[0];
    return;
  }
  if (c.general) {  // the rounding of the step stays (no unit row to share exactly)
    step_onto_row(c.row, u, y + n_, im);
    return;
  }
  if (coupled_ && c.b >= 0) {  // a clutch on a gear's body: the other side takes u (the gear holds v_a = i v_b)
    const bool ga = gear_of_body_[static_cast<size_t>(c.a)] >= 0, gb = gear_of_body_[static_cast<size_t>(c.b)] >= 0;
    if (ga != gb) {
      const int from = ga ? c.b : c.a;
      const double dv = y[n_ + (ga ? c.a : c.b)] - y[n_ + from];
      // Every body at exactly the same speed through contacts beside it (a freewheel and its clutch)
      // moves along, so their u stays exactly 0.
      std::vector<int> group{from};
      for (size_t j = 0; j < group.size(); ++j)
        for (const ContactLaw& d : contacts_) {
          if (d.general || d.b < 0 || (d.a != group[j] && d.b != group[j])) continue;
          const int other = d.a == group[j] ? d.b : d.a;
          if (gear_of_body_[static_cast<size_t>(other)] >= 0 || y[n_ + other] != y[n_ + group[j]]) continue;
          if (std::find(group.begin(), group.end(), other) == group.end()) group.push_back(other);
        }
      for (int x : group) y[n_ + x] += dv;
      return;
    }
  }
  const double ia = im[c.a], ib = c.b >= 0 ? im[c.b] : 0.0;
  y[n_ + c.a] -= u * ia / (ia + ib);
  if (c.b >= 0) y[n_ + c.b] += u * ib / (ia + ib);
  // Exact zero (rounding of the split above): the contact's own body takes the remainder.
  y[n_ + c.a] -= sliding_velocity(k, t, y);
}

GapMode DriveSystem::natural_gap_mode(int l, const double* y) const {
  const LinkLaw::Kinematics s = link_kinematics(l, y);
  const LinkLaw& k = links_[static_cast<size_t>(l)];
  return k.natural_mode(s.delta, s.rate, k.drum(y));
}

void DriveSystem::set_contact_modes(const std::vector<ContactMode>& modes) {
  mode_ = modes;
  mode_changed();
  stuck_.clear();
  for (int k = 0; k < nc_; ++k)
    // A kinematic contact is no constraint: its bodies' motions are given (elements/contact.hpp).
    if (mode_[static_cast<size_t>(k)] == ContactMode::stuck && !contacts_[static_cast<size_t>(k)].kinematic)
      stuck_.push_back(k);
  const Eigen::Index ns = static_cast<Eigen::Index>(stuck_.size());
  r_.resize(ns);
  lam_.resize(ns);
  stuck_machine_ = false;
  timed_share_ = false;
  one_sided_.clear();
  masked_.clear();
  if (ns >= 2)
    for (Eigen::Index j = 0; j < std::min<Eigen::Index>(ns, 64); ++j)
      if (contacts_[static_cast<size_t>(stuck_[static_cast<size_t>(j)])].lock != 0) one_sided_.push_back(j);
  for (int k : stuck_) {
    const VelocityRow& r = contacts_[static_cast<size_t>(k)].row;
    for (int j = 0; j < r.terms; ++j) stuck_machine_ = stuck_machine_ || machine_[static_cast<size_t>(r.body[j])];
  }
  if (ns == 0 || coupled_) return;  // coupled: solved at every evaluation (solve_coupled)
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
      timed_share_ = it->second.timed;
      return;
    }
  }
  form_stuck_solution(inv_mass_.data(), 0.0);
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  cod.setThreshold(1e-12);
  cod.compute(stuck_matrix(inv_mass_.data()));
  Pproj_ = cod.pseudoInverse();
  // A redundant set (two contacts lock one motion) shares its load by the limits at the instant: with
  // a brake or clutch among them (r(t) F_s0) the share changes with t. Shared by F_s0, two clutches
  // in parallel ramped at different rates broke away at F_s1 + F_k2 instead of F_s1 + F_s2 (issue 27:
  // the one with the smaller r took more than its limit, was released and slid at u ≡ 0 beside the other).
  if (cod.rank() < ns)
    for (int k : stuck_) timed_share_ = timed_share_ || contacts_[static_cast<size_t>(k)].applied;
  if (cacheable) projector_cache_[key] = {P_, Pproj_, timed_share_};
}

double DriveSystem::share_weight(int k, double t) const {
  const ContactLaw& c = contacts_[static_cast<size_t>(k)];
  // Only a redundant set's share depends on the weights (a full-rank set has one λ): its limits at t
  // when one of them varies (timed_share_), else the constant F_s0 of the mode's cached pseudo-inverse.
  return timed_share_ && c.applied && !c.joint && c.lock == 0 ? std::sqrt(c.holding_limit(t)) : c.share_weight();
}

Eigen::MatrixXd DriveSystem::stuck_matrix(const double* im) const {
  // A = G M⁻¹ Gᵀ; row j of G is stuck contact j's velocity row (+1 at a, −1 at b for most).
  const Eigen::Index ns = static_cast<Eigen::Index>(stuck_.size());
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(ns, ns);
  for (Eigen::Index i = 0; i < ns; ++i) {
    const VelocityRow& ri = contacts_[static_cast<size_t>(stuck_[static_cast<size_t>(i)])].row;
    for (Eigen::Index j = 0; j < ns; ++j) {
      const VelocityRow& rj = contacts_[static_cast<size_t>(stuck_[static_cast<size_t>(j)])].row;
      for (int p = 0; p < ri.terms; ++p)
        for (int q = 0; q < rj.terms; ++q)
          if (ri.body[p] == rj.body[q]) A(i, j) += ri.w[p] * rj.w[q] * im[ri.body[p]];
    }
  }
  return A;
}

void DriveSystem::form_stuck_solution(const double* im, double t) {
  const Eigen::Index ns = static_cast<Eigen::Index>(stuck_.size());
  const Eigen::MatrixXd A = stuck_matrix(im);
  if (ns == 1 && stuck_machine_) {  // one stuck contact: λ = r / (1/I_a + 1/I_b), no decomposition
    P_.resize(1, 1);
    P_(0, 0) = 1.0 / A(0, 0);
    return;
  }
  Eigen::VectorXd w(ns);
  for (Eigen::Index i = 0; i < ns; ++i)
    w(i) = share_weight(stuck_[static_cast<size_t>(i)], t);
  // Weighted least norm: λ = D z, min ‖z‖ subject to A D z = r, D = diag(√F_s(t)).
  Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
  cod.setThreshold(1e-12);
  cod.compute(A * w.asDiagonal());
  P_ = w.asDiagonal() * cod.pseudoInverse();
}

void DriveSystem::share_one_sided(const double* im, double t) {
  // The one-sided contacts whose least-norm share pulls against their lock beyond its resolution,
  // the hold allowance ε_h: a share within it is the hold rule's "at the limit" (a freewheel that
  // carries nothing, its share −7e-13 N by rounding, was masked with a backstop pulled 0.046 N
  // against its lock; without the freewheel's row the others no longer had the rank, and the plain
  // share stood for both: campaign `mixed` seed 7 #146, dopri5).
  uint64_t mask = 0;
  for (Eigen::Index j : one_sided_) {
    const ContactLaw& c = contacts_[static_cast<size_t>(stuck_[static_cast<size_t>(j)])];
    if (c.lock * lam_(j) < -c.hold_tol) mask |= uint64_t{1} << j;
  }
  if (mask == 0) return;
  auto it = masked_.find(mask);
  if (it == masked_.end() || stuck_machine_ || timed_share_) {
    // λ = D z, min ‖z‖ subject to A D z = r, with weight 0 for the masked contacts; used only if the
    // others carry every load alone (rank A D = rank A), else (empty) the plain share stands.
    const Eigen::Index ns = static_cast<Eigen::Index>(stuck_.size());
    const Eigen::MatrixXd A = stuck_matrix(im);
    Eigen::VectorXd w(ns);
    for (Eigen::Index i = 0; i < ns; ++i)
      w(i) = (mask >> i & 1) != 0 ? 0.0 : share_weight(stuck_[static_cast<size_t>(i)], t);
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> full, cod;
    full.setThreshold(1e-12);
    cod.setThreshold(1e-12);
    full.compute(A);
    cod.compute(A * w.asDiagonal());
    Eigen::MatrixXd P;
    if (cod.rank() == full.rank()) P = w.asDiagonal() * cod.pseudoInverse();
    it = masked_.insert_or_assign(mask, std::move(P)).first;
  }
  if (it->second.size() > 0) mat_vec(it->second, r_, lam_);
}

void DriveSystem::inverse_inertias(const double* y, double* im) const {
  for (int i = 0; i < n_; ++i) im[i] = inv_mass_[static_cast<size_t>(i)];
  for (int i : machine_bodies_) {
    double I, dI;
    machine_[static_cast<size_t>(i)]->inertia(machine_positions(y)[i], &I, &dI);
    im[i] = 1.0 / I;
  }
}

// Few bodies: the vectorizer's prologues cost more than they save (the chain loops of small models).
template <bool kMach>
MACHDYN_NO_TREE_VECTORIZE void DriveSystem::forces(double t, const double* y, double* f, double* fc, double* p_src,
                                                    double* p_fric, double* p_damp) {
  const double* v = y + n_;
  double src = 0, fric = 0, damp = 0;
  for (int i = 0; i < n_; ++i) {
    f[i] = f_const_[static_cast<size_t>(i)];
    src += f[i] * v[i];
  }
  for (const Load* ld : varying_) {
    const double val = ld->at(t, y, v);
    ld->spread(val, f);
    src += val * ld->own(v);
  }
  const double* q = y;
  if constexpr (kMach) {
    if (nd_ > 0) src += drive_forces(t, y, f, &damp);
    q = machine_positions(y);
    // I q'' + ½ I′ q'² = Q + ...: the velocity term joins the forces (it does no work on its own:
    // d/dt ½ I v² = v (I v' + ½ I′ v²)); the machine's force Q(q) is a source.
    for (int i : machine_bodies_) {
      const Machine* mach = machine_[static_cast<size_t>(i)];
      double I, dI, Q;
      mach->dynamics(q[i], &I, &dI, &Q);
      im_[static_cast<size_t>(i)] = 1.0 / I;
      f[i] += Q - 0.5 * dI * v[i] * v[i];
      src += Q * v[i];
    }
  }
  for (size_t l = 0; l < links_.size(); ++l) {
    const LinkLaw& k = links_[l];
    const GapMode g = gap_[l];
    if (!k.transmits(g)) continue;
    if constexpr (kMach) {
      if (k.point && !k.winding) {  // a machine's output point: forces −F j_a, +F j_b
        const LinkLaw::Kinematics s = k.kinematics(q, v);
        k.apply(k.load(s.delta, s.rate, g), s, f);
        damp += k.dissipation(s.delta, s.rate, g);
        continue;
      }
    }
    if (k.winding) [[unlikely]] {  // c(q_a) and the winding term on the drum (elements/link.hpp)
      k.apply_at(q, v, g, f);
      damp += k.dissipation(k.weighted(q), k.weighted(v), g, k.drum(q));  // δ over a frame too
      continue;
    }
    const double delta = k.linear(q), rate = k.linear(v), F = k.load(delta, rate, g);
    damp += k.dissipation(delta, rate, g);
    if (k.a >= 0) f[k.a] -= F * k.inv_ratio;
    if (k.b >= 0) f[k.b] += F;
  }
  for (int k = 0; k < nc_; ++k) {
    const ContactMode md = mode_[static_cast<size_t>(k)];
    const ContactLaw& c = contacts_[static_cast<size_t>(k)];
    if (md == ContactMode::stuck) {
      if (c.kinematic) [[unlikely]] fc[k] = 0.0;  // carries no load (elements/contact.hpp)
      continue;
    }
    const double u = c.sliding_velocity(t, v);
    const double F = c.kinetic_force(md, t, u);
    fc[k] = F;
    c.apply(F, f);
    if (c.grounded) src -= F * c.surface_velocity(t);  // the moving surface's work
    fric += F * u;
  }
  if (p_src) *p_src = src, *p_fric = fric, *p_damp = damp;
}

// Out of line: the plain chain's loops stay as they were for models without drives.
__attribute__((noinline)) double DriveSystem::drive_forces(double t, const double* y, double* f, double* loss) const {
  double src = 0.0;
  for (int d = 0; d < nd_; ++d) {  // their forces from their bodies and states (model/element.hpp)
    const Element& k = drive(d);
    const double* x = y + drive_offset(d);
    const ElementMotion b = drive_motion(d, y);  // ω_X (model.hpp: Drive; the body's velocity on one body)
    double M[ElementMotion::kMax] = {};
    k.forces(t, b, x, drive_mode(d), M);
    drive_place(d).spread_all(M, f);
    // Its heat is a loss, not work taken out: the source work is Σ M v + heat (0 for a brake), plus
    // the rate of the energy it stores (counted with the elastic energy).
    const double heat = k.heat_power(t, b, x, drive_mode(d));
    double P = M[0] * b.v[0];
    for (int i = 1; i < b.n; ++i) P += M[i] * b.v[i];
    src += P + heat;
    if (k.has_energy()) src += k.stored_power(t, b, x, drive_mode(d));
    *loss += heat;
  }
  return src;
}

__attribute__((noinline)) void DriveSystem::drive_rates(double t, const double* y, double* dydt) const {
  for (int d = 0; d < nd_; ++d) {
    const int o = drive_offset(d);
    drive(d).rates(t, drive_motion(d, y, dydt + n_), y + o, drive_mode(d), dydt + o);
  }
}

int DriveSystem::port_body(int d, int p) const {
  const Drive& place = drive_place(d);
  if (p > 0) return place.others[static_cast<size_t>(p - 1)];
  return place.body2 < 0 && place.ratio == 1.0 ? place.body : -1;
}

// An element that holds a body at rest in its mode (Element::held_port) puts there its law's force
// against everything else on it: forces() above put its force for no other load; the free forces f
// on the body less that are its load R, and its force for R replaces it. The stuck set's loads,
// solved after this, carry what it does not (a contact stuck on the same body).
void DriveSystem::hold_forces(double t, const double* y, double* f) {
  for (int d = 0; d < nd_; ++d) {
    const Element& k = drive(d);
    const int md = drive_mode(d), p = k.held_port(md);
    if (p < 0) continue;
    const int j = port_body(d, p);
    ElementMotion b = drive_motion(d, y);
    double M[ElementMotion::kMax] = {};
    k.forces(t, b, y + drive_offset(d), md, M);
    b.load[p] = f[j] - M[p];
    k.forces(t, b, y + drive_offset(d), md, M);
    f[j] = b.load[p] + M[p];
  }
}

ElementMotion DriveSystem::drive_motion_at(int d, double t, const double* y) const {
  ElementMotion b = drive_motion(d, y);
  const int p = drive(d).held_port(drive_mode(d));
  if (p < 0) return b;
  // The free forces on the held body at (t, y), as evaluate() forms them before hold_forces().
  thread_local std::vector<double> f, fc;
  f.assign(static_cast<size_t>(n_), 0.0), fc.assign(static_cast<size_t>(nc_), 0.0);
  double src, fric, damp;
  const_cast<DriveSystem*>(this)->forces<true>(t, y, f.data(), fc.data(), &src, &fric, &damp);
  double M[ElementMotion::kMax] = {};
  drive(d).forces(t, b, y + drive_offset(d), drive_mode(d), M);
  b.load[p] = f[static_cast<size_t>(port_body(d, p))] - M[p];
  return b;
}

void DriveSystem::evaluate(double t, const double* y, double* acc, double* fc) {
  double src, fric, damp;
  if (general_) evaluate_impl<true>(t, y, acc, fc, &src, &fric, &damp);
  else evaluate_impl<false>(t, y, acc, fc, &src, &fric, &damp);
}

// Inlined into evaluate(): the constant-inertia call is the same single function as before.
template <bool kMach>
__attribute__((always_inline)) inline void DriveSystem::evaluate_impl(double t, const double* y, double* acc, double* fc,
                                                                       double* src, double* fric, double* damp) {
  forces<kMach>(t, y, acc, fc, src, fric, damp);
  if constexpr (kMach)
    if (nd_ > 0) hold_forces(t, y, acc);
  if (ng_ > 0) apply_gears(t, y, acc, fric);
  if constexpr (kMach)
    if (!motions_.empty()) motion_forces(t, y + n_, acc, src);
  const double* im = kMach ? im_.data() : inv_mass_.data();
  for (int i = 0; i < n_; ++i) acc[i] *= im[i];
  if (ng_ > 0) enforce_gears(acc);
  if constexpr (kMach)
    if (!motions_.empty()) enforce_motions(t, acc);
  if (stuck_.empty()) return;
  if (coupled_) [[unlikely]] {  // stuck contacts with the gears' law inside (analysis/gear_clutch.hpp)
    solve_coupled(t, y, acc, fc, im, src, fric);
    return;
  }
  for (size_t j = 0; j < stuck_.size(); ++j)
    r_(static_cast<Eigen::Index>(j)) = contacts_[static_cast<size_t>(stuck_[j])].sliding_acceleration(t, acc);
  if constexpr (kMach)
    if (stuck_machine_) form_stuck_solution(im, t);
  if (timed_share_) [[unlikely]] form_stuck_solution(im, t);
  mat_vec(P_, r_, lam_);
  if (!one_sided_.empty()) share_one_sided(im, t);
  if (stuck_.size() >= 2) detail::bound_share(stuck_, contacts_, t, lam_, r_, [&] { return stuck_matrix(im); },
              [&](int k) { return share_weight(k, t); });
  for (size_t j = 0; j < stuck_.size(); ++j) {
    const ContactLaw& c = contacts_[static_cast<size_t>(stuck_[j])];
    const double lam = lam_(static_cast<Eigen::Index>(j));
    fc[stuck_[j]] = lam;
    if (c.general) [[unlikely]] {
      for (int i = 0; i < c.row.terms; ++i) acc[c.row.body[i]] -= im[c.row.body[i]] * c.row.w[i] * lam;
    } else {
      acc[c.a] -= im[c.a] * lam;
      if (c.b >= 0) acc[c.b] += im[c.b] * lam;
    }
    if (c.grounded) *src -= lam * c.surface_velocity(t);  // work of the moving surface on the stuck body
  }
  if constexpr (kMach)  // a stuck contact's force on a prescribed body is carried by its source
    for (size_t j = 0; j < motions_.size() && !stuck_.empty(); ++j)
      for (size_t i = 0; i < stuck_.size(); ++i) {
        const ContactLaw& c = contacts_[static_cast<size_t>(stuck_[i])];
        const int b = motions_[j].body;
        const double dR = c.a == b ? lam_(static_cast<Eigen::Index>(i)) : c.b == b ? -lam_(static_cast<Eigen::Index>(i)) : 0.0;
        motion_f_[j] += dR;
        *src += dR * y[n_ + b];
      }
  if constexpr (kMach) enforce_stuck_weighted(t, acc, im);
  else enforce_stuck(t, acc);
  if (!locks_.empty()) share_locks(t, fc);
}

void DriveSystem::motion_forces(double t, const double* v, const double* f, double* src) {
  for (size_t j = 0; j < motions_.size(); ++j) {
    const PrescribedMotionLaw& k = motions_[j];
    motion_f_[j] = k.force(t, f[k.body]);
    *src += motion_f_[j] * v[k.body];  // the motion source's work
  }
}

void DriveSystem::enforce_motions(double t, double* acc) const {
  for (const PrescribedMotionLaw& k : motions_) acc[k.body] = k.acceleration(t);
}

void DriveSystem::apply_gears(double t, const double* y, double* f, double* p_fric) {
  for (size_t tr = 0; tr < trains_.size(); ++tr) apply_train(static_cast<int>(tr), y, f, p_fric);
  for (int g = 0; g < ng_; ++g) {
    const LossyGearLaw& k = gears_[static_cast<size_t>(g)];
    const auto gi = static_cast<size_t>(g);
    if (train_of_gear_[gi] >= 0) [[unlikely]] continue;
    gear_fa_[gi] = f[k.a];
    gear_fb_[gi] = f[k.b];
    const double va = y[n_ + k.a];
    if (gear_motion_[gi] >= 0) [[unlikely]]  // a prescribed side (elements/lossy_gear.hpp)
      gear_t_[gi] = given_gear_torques(g, t, y, f);
    else
      gear_t_[gi] = k.solve(gear_mode_[gi], f[k.a], f[k.b], 1.0 / inv_mass_[static_cast<size_t>(k.a)],
                            1.0 / inv_mass_[static_cast<size_t>(k.b)], va);
    k.apply(gear_t_[gi], f);
    if (p_fric) *p_fric += LossyGearLaw::loss_power(gear_t_[gi], va);
  }
}

namespace train_side_detail {
/// The rounding allowance of the side function s X̃ (or −s Ỹ) of gear g of train tr at its loads F:
/// it comes out of the train's 3 × 3 solve, so its rounding is that of the train's loads,
/// 1e-12 Σ |ρ_j F_j| in r's coordinate (train_allowance), in the gear's own coordinate / |ρ_a|
/// (campaign gear seed 7 #52: at the switch of the second stage's side both combinations read ∓3e-16,
/// the current one the smaller violation; it was kept with its function at −3e-16 — disarmed, the
/// switch 1.9 ms late, the gear delivering power meanwhile).
double allowance(const GearTrain& tr, const std::vector<LossyGearLaw>& gears, const std::array<double, 3>& F, int g) {
  return train_allowance(tr, gears, F) / std::abs(tr.rho_of(gears[static_cast<size_t>(g)].a));
}
}  // namespace train_side_detail

std::array<double, 3> DriveSystem::train_inertia(int t) const {
  const GearTrain& tr = trains_[static_cast<size_t>(t)];
  return {inertia_[static_cast<size_t>(tr.bodies[0])], inertia_[static_cast<size_t>(tr.bodies[1])],
          inertia_[static_cast<size_t>(tr.bodies[2])]};
}

void DriveSystem::apply_train(int t, const double* y, double* f, double* p_fric) {
  // Both gears from the forces on the three bodies before either acts (analysis/gear_train.hpp).
  const GearTrain& tr = trains_[static_cast<size_t>(t)];
  std::array<double, 3>& F = train_f_[static_cast<size_t>(t)];
  for (size_t j = 0; j < 3; ++j) F[j] = f[tr.bodies[j]];
  const auto g0 = static_cast<size_t>(tr.gears[0]), g1 = static_cast<size_t>(tr.gears[1]);
  for (size_t g : {g0, g1}) gear_fa_[g] = f[gears_[g].a], gear_fb_[g] = f[gears_[g].b];
  const double v_r = y[n_ + tr.bodies[0]];
  const int s = direction(gear_mode_[g0]) * (tr.rho_of(gears_[g0].a) > 0.0 ? 1 : -1);
  if (s != 0 && direction(gear_mode_[g1]) != 0) {
    const TrainSolution x =
        train_roll(tr, gears_, s, {b_drives(gear_mode_[g0]), b_drives(gear_mode_[g1])}, F, train_inertia(t), v_r);
    gear_t_[g0] = x.T[0], gear_t_[g1] = x.T[1];
  } else {  // stuck (a mixed pair only inside a decision: held until it is decided)
    const std::array<LossyGearLaw::Torques, 2> T = stuck_train_torques(tr, gears_, F);
    gear_t_[g0] = T[0], gear_t_[g1] = T[1];
    gear_t_[g0].acc = gear_t_[g1].acc = 0.0;
  }
  for (size_t g : {g0, g1}) {
    gears_[g].apply(gear_t_[g], f);
    if (p_fric) *p_fric += LossyGearLaw::loss_power(gear_t_[g], y[n_ + gears_[g].a]);
  }
}

namespace {
/// v_a of a gear with a prescribed side from the velocities v: the motion's speed snapped onto its
/// signal (a hold is exactly at rest; elements/prescribed_motion.hpp), × i when b is the given side.
double given_speed(const PrescribedMotionLaw& p, const LossyGearLaw& k, bool b_given, double t, const double* v) {
  const double vp = p.snapped_velocity(t, v[p.body]);
  return b_given ? k.i * vp : vp;
}
}  // namespace

LossyGearLaw::Torques DriveSystem::given_gear_torques(int g, double t, const double* y, const double* f) {
  // The prescribed body's inertia is its motion's (inv_mass_ is 0 there); a = i a_b when b is given.
  const auto gi = static_cast<size_t>(g);
  const LossyGearLaw& k = gears_[gi];
  const PrescribedMotionLaw& p = motions_[static_cast<size_t>(gear_motion_[gi])];
  const bool bg = gear_b_given_[gi] != 0;
  const double acc = bg ? k.i * p.acceleration(t) : p.acceleration(t);
  const double Ia = bg ? inertia_[static_cast<size_t>(k.a)] : p.inertia, Ib = bg ? p.inertia : inertia_[static_cast<size_t>(k.b)];
  // The mode of (t) alone (lossy_gear.hpp "Mode law"), from the motion's speed: a hold exactly at rest.
  // The rounding allowances (lossy_gear.hpp "Mode law"): 1e-12 of the prescribed speed's scale (per s for a).
  const double rest = 1e-12 * p.speed_scale * (bg ? std::abs(k.i) : 1.0);
  gear_now_[gi] = k.decide_given(bg, acc, f[k.a], f[k.b], Ia, Ib, given_speed(p, k, bg, t, y + n_), rest, rest);
  return k.solve_given(gear_now_[gi], bg, acc, f[k.a], f[k.b], Ia, Ib, y[n_ + k.a]);
}

void DriveSystem::enforce_gears(double* acc) const {
  // The rounding of (F_a − X)/I_a removed: the two bodies stay exactly on v_a = i v_b.
  for (int g = 0; g < ng_; ++g) {
    const LossyGearLaw& k = gears_[static_cast<size_t>(g)];
    const auto gi = static_cast<size_t>(g);
    const double a = gear_mode_[gi] == GearMode::stuck && gear_motion_[gi] < 0 ? 0.0 : gear_t_[gi].acc;
    // (A gear of a train: gear_t_ holds 0 for a stuck pair, also while the other gear is decided.)
    acc[k.a] = a;
    acc[k.b] = a / k.i;
  }
}

GearMode DriveSystem::natural_gear_mode(int g, double t, const double* y, bool strict) {
  evaluate(t, y, f_.data(), fc_.data());
  const LossyGearLaw& k = gears_[static_cast<size_t>(g)];
  const double Fa = gear_fa_[static_cast<size_t>(g)], Fb = gear_fb_[static_cast<size_t>(g)];
  // A prescribed side: the evaluation has decided it (given_gear_torques, from a(t) and v_a(t)).
  if (gear_motion_[static_cast<size_t>(g)] >= 0) return gear_now_[static_cast<size_t>(g)];
  if (const int tn = train_of_gear_[static_cast<size_t>(g)]; tn >= 0) {  // decided with its train
    const GearTrain& tr = trains_[static_cast<size_t>(tn)];
    const std::array<double, 3>& F = train_f_[static_cast<size_t>(tn)];
    const auto g0 = static_cast<size_t>(tr.gears[0]), g1 = static_cast<size_t>(tr.gears[1]);
    const std::array<GearMode, 2> md = decide_train(tr, gears_, F, train_inertia(tn), y[n_ + tr.bodies[0]],
                                                    strict ? 0.0 : train_allowance(tr, gears_, F),
                                                    {gear_mode_[g0], gear_mode_[g1]});
    return md[g == tr.gears[0] ? 0 : 1];
  }
  return k.decide(Fa, Fb, 1.0 / inv_mass_[static_cast<size_t>(k.a)], 1.0 / inv_mass_[static_cast<size_t>(k.b)],
                  y[n_ + k.a], strict ? 0.0 : k.allowance(Fa, Fb));
}

LossyGearLaw::Torques DriveSystem::gear_torques(int g, double t, const double* y) {
  evaluate(t, y, f_.data(), fc_.data());
  return gear_t_[static_cast<size_t>(g)];
}

void DriveSystem::stop_gear(int g, double* y) const {
  const LossyGearLaw& k = gears_[static_cast<size_t>(g)];
  y[n_ + k.a] = y[n_ + k.b] = 0.0;
  if (const int tn = train_of_gear_[static_cast<size_t>(g)]; tn >= 0)
    for (int b : trains_[static_cast<size_t>(tn)].bodies) y[n_ + b] = 0.0;
  // A gear a stuck clutch ties to it stops with it (u ≡ 0 on the clutch: the other's speed is rounding).
  if (!coupled_) return;
  for (size_t c = 0; c < contacts_.size(); ++c) {
    const ContactLaw& law = contacts_[c];
    if (mode_[c] != ContactMode::stuck || law.joint || law.general || law.b < 0) continue;
    for (const auto& [from, to] : {std::pair{law.a, law.b}, std::pair{law.b, law.a}}) {
      const int h = gear_of_body_[static_cast<size_t>(to)];
      if ((from == k.a || from == k.b) && h >= 0 && h != g && y[n_ + gears_[static_cast<size_t>(h)].a] != 0.0)
        stop_gear(h, y);
    }
  }
}

void DriveSystem::enforce_stuck(double t, double* acc) const {
  // Remove the rounding of λ: stuck bodies get exactly equal accelerations (the momentum-weighted
  // mean; the ground's is the surface acceleration), so u stays exactly zero along a stuck mode.
  for (int k : stuck_) {
    const ContactLaw& c = contacts_[static_cast<size_t>(k)];
    if (c.general) {
      step_onto_row(c.row, c.sliding_acceleration(t, acc), acc, inv_mass_.data());
    } else if (c.b < 0) {
      acc[c.a] = c.surface_acceleration(t);
    } else {
      const double s = stuck_share_[static_cast<size_t>(k)];
      acc[c.a] = acc[c.b] = s * acc[c.a] + (1.0 - s) * acc[c.b];
    }
  }
}

void DriveSystem::enforce_stuck_weighted(double t, double* acc, const double* im) const {
  // As enforce_stuck, with the shares of the current inertias I(q): s = I_a/(I_a + I_b).
  for (int k : stuck_) {
    const ContactLaw& c = contacts_[static_cast<size_t>(k)];
    if (c.general) {
      step_onto_row(c.row, c.sliding_acceleration(t, acc), acc, im);
    } else if (c.b < 0) {
      acc[c.a] = c.surface_acceleration(t);
    } else {
      const double s = im[c.b] / (im[c.a] + im[c.b]);
      acc[c.a] = acc[c.b] = s * acc[c.a] + (1.0 - s) * acc[c.b];
    }
  }
}

const DriveSystem::AffineMode& DriveSystem::compile_affine() {
  std::string key;
  for (auto g : gap_) key += static_cast<char>('0' + static_cast<int>(g));
  key += '/';
  for (auto md : mode_) key += static_cast<char>('0' + static_cast<int>(md));
  if (auto it = affine_cache_.find(key); it != affine_cache_.end()) return it->second;
  // A redundant stuck set with a bounded contact shares its load by the bounded split (bound_share),
  // piecewise linear in y: it has no affine map, and the run takes the general path from here on.
  if (stuck_.size() >= 2 && std::any_of(stuck_.begin(), stuck_.end(), [&](int k) { return !contacts_[static_cast<size_t>(k)].joint; })) {
    Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd> cod;
    cod.setThreshold(1e-12);
    cod.compute(stuck_matrix(inv_mass_.data()));
    if (cod.rank() < static_cast<Eigen::Index>(stuck_.size())) {
      affine_eligible_ = false;
      static const AffineMode none;
      return none;
    }
  }
  const int N = size();
  AffineMode a;
  a.c.resize(N);
  Eigen::MatrixXd J(N, N), G(nc_, N);
  Eigen::VectorXd y = Eigen::VectorXd::Zero(N), d(N);
  rhs_general<false>(0.0, y.data(), a.c.data());
  a.force_c = Eigen::Map<const Eigen::VectorXd>(fc_.data(), nc_);
  // The energy books (the last three states) are quadratures that no rate reads: their columns of J
  // and G are 0, not evaluated.
  const int read = energy_ ? energy_index() : N;
  J.rightCols(N - read).setZero(), G.rightCols(N - read).setZero();
  for (int j = 0; j < read; ++j) {
    y(j) = 1.0;
    rhs_general<false>(0.0, y.data(), d.data());
    J.col(j) = d - a.c;
    G.col(j) = Eigen::Map<const Eigen::VectorXd>(fc_.data(), nc_) - a.force_c;
    y(j) = 0.0;
  }
  auto compress = [N](const Eigen::MatrixXd& M, std::vector<int>& start, std::vector<int>& col, std::vector<double>& val) {
    // Sized once: one allocation per vector, not one per doubling.
    const auto nnz = static_cast<size_t>((M.array() != 0.0).count());
    start.reserve(static_cast<size_t>(M.rows()) + 1), col.reserve(nnz), val.reserve(nnz);
    for (int i = 0; i < M.rows(); ++i) {
      start.push_back(static_cast<int>(col.size()));
      for (int j = 0; j < N; ++j)
        if (M(i, j) != 0.0) col.push_back(j), val.push_back(M(i, j));
    }
    start.push_back(static_cast<int>(col.size()));
  };
  compress(J, a.row_start, a.col, a.val);
  a.first_row = n_;
  for (int i = 0; i < n_; ++i) {
    const int k = a.row_start[static_cast<size_t>(i)];
    if (a.c[i] != 0.0 || a.row_start[static_cast<size_t>(i) + 1] != k + 1 || a.col[static_cast<size_t>(k)] != n_ + i ||
        a.val[static_cast<size_t>(k)] != 1.0)
      a.first_row = 0;
  }
  compress(G, a.force_start, a.force_col, a.force_val);
  if (a.first_row == n_) a.dense.build(J, a.c, n_, N, n_);  // the whole right-hand side (rhs)
  a.force_dense.build(G, a.force_c, 0, nc_, 0);
  return affine_cache_.emplace(std::move(key), std::move(a)).first->second;
}

void DriveSystem::rhs_other(double t, const double* y, double* dydt) {
  if (dense_) {
    chain_.apply(y, dydt);
    for (const Load* ld : varying_) {  // ρ_i M on body i (model.hpp: Load::terms)
      const double Mx = ld->at(t, y, y + n_);
      int b[2];
      double w[2];
      for (int i = 0, nt = ld->terms(b, w); i < nt; ++i)
        dydt[n_ + b[i]] += w[i] * Mx * inv_mass_[static_cast<size_t>(b[i])];
    }
    return;
  }
  if (!affine_eligible_) {
    if (general_) rhs_general<true>(t, y, dydt);
    else rhs_general<false>(t, y, dydt);
    return;
  }
  // The mode's map may have been compiled already by contact_forces (a decision's λ, the event
  // functions): its small kernel is taken here too, not only where this call compiled it.
  if (!affine_) use_affine();
  if (!affine_eligible_) {  // the mode has no affine map (compile_affine)
    mode_changed();
    rhs_other(t, y, dydt);
    return;
  }
  if (affine_->dense.kernel) {  // from now on inline (rhs)
    fast_ = &affine_->dense;
    rhs(t, y, dydt);
    return;
  }
  const int N = size();
  const AffineMode& a = *affine_;
  const int* rs = a.row_start.data();
  const int* col = a.col.data();
  const double* val = a.val.data();
  const double* c = a.c.data();
  for (int i = 0; i < a.first_row; ++i) dydt[i] = y[n_ + i];
  for (int i = a.first_row; i < N; ++i) {
    double s = c[i];
    for (int k = rs[i]; k < rs[i + 1]; ++k) s += val[k] * y[col[k]];
    dydt[i] = s;
  }
}

// Out of line: rhs() stays the small affine loop.
template <bool kMach>
__attribute__((noinline)) void DriveSystem::rhs_general(double t, const double* y, double* dydt) {
  for (int i = 0; i < n_; ++i) dydt[i] = y[n_ + i];
  double src, fric, damp;
  evaluate_impl<kMach>(t, y, dydt + n_, fc_.data(), &src, &fric, &damp);
  if constexpr (kMach)
    if (nd_ > 0) drive_rates(t, y, dydt);
  if (!energy_) return;
  const int e = energy_index();
  dydt[e] = src;
  dydt[e + 1] = fric;
  dydt[e + 2] = damp;
}

void DriveSystem::numeric_jacobian(double t, const double* y, Eigen::Ref<Eigen::MatrixXd> J) {
  // Central differences, step scaled per state (about the cube root of ε for the 2nd-order scheme).
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

void DriveSystem::jacobian(double t, const double* y, Eigen::Ref<Eigen::MatrixXd> J) {
  if (has_machines_) {
    numeric_jacobian(t, y, J);
    return;
  }
  Eigen::SparseMatrix<double> S;
  sparse_jacobian(t, y, S);
  J = Eigen::MatrixXd(S);
}

void DriveSystem::sparse_jacobian(double t, const double* y, Eigen::SparseMatrix<double>& J) {
  // q' = v; M v' = f(t, v) − (link terms): the loads' slopes ∂f/∂v and each link's own Jacobian
  // terms (elements/link.hpp), divided by the inertias. Duplicates are summed and zeros kept, so the
  // pattern is the same at every call.
  std::vector<Eigen::Triplet<double>> trip;
  trip.reserve(static_cast<size_t>(3 * n_ + 8 * nl_) + 2 * m_.loads.size());
  for (int i = 0; i < n_; ++i) trip.emplace_back(i, n_ + i, 1.0);
  // Every diagonal entry present (zero for positions): CVODE forms I − γJ in place on this pattern;
  // a missing diagonal makes it rebuild the whole matrix at every setup.
  for (int i = 0; i < 2 * n_; ++i) trip.emplace_back(i, i, 0.0);
  auto im = [&](int i) { return inv_mass_[static_cast<size_t>(i)]; };
  for (const auto& ld : m_.loads) {  // f_i = ρ_i M(q_X, v_X): ∂f_i/∂x_j = ρ_i ρ_j ∂M/∂x_X (model.hpp: Load)
    double dq = 0.0, dv = 0.0;
    ld.slopes_at(t, y, y + n_, &dq, &dv);
    int b[2];
    double w[2];
    const int nt = ld.terms(b, w);
    for (int i = 0; i < nt; ++i)
      for (int j = 0; j < nt; ++j) {
        trip.emplace_back(n_ + b[i], n_ + b[j], w[i] * w[j] * dv * im(b[i]));
        trip.emplace_back(n_ + b[i], b[j], w[i] * w[j] * dq * im(b[i]));
      }
  }
  for (int l = 0; l < nl_; ++l) {
    const LinkLaw& k = links_[static_cast<size_t>(l)];
    const GapMode g = gap_[static_cast<size_t>(l)];
    k.jacobian(n_, g, k.on_cap(k.linear(y), k.linear(y + n_), g, k.drum(y)), y, y + n_, [&](int r, int c, double v) {
      trip.emplace_back(n_ + r, c, v * im(r));
    });
  }
  // Elements (model/element.hpp): M_p(q, v, x) on their bodies' accelerations, the state rates
  // x'(q, v, x); the q terms where the element reads positions (a fixed pattern either way).
  for (int d = 0; d < nd_; ++d) {
    const Element& k = drive(d);
    const int o = drive_offset(d), nx = k.states();
    const bool pos = k.reads_positions();
    const ElementJacobian jd = k.jacobian(t, drive_motion(d, y), y + o, drive_mode(d));
    const Drive& place = drive_place(d);
    const int np = place.ports();
    int b[ElementMotion::kMax][2];
    double w[ElementMotion::kMax][2];  // port p: ω_p = Σ w_i v_i, f_i += w_i M_p (model.hpp: Drive)
    int nt[ElementMotion::kMax];
    nt[0] = place.terms(b[0], w[0]);
    for (int p = 1; p < np; ++p) nt[p] = 1, b[p][0] = place.others[static_cast<size_t>(p - 1)], w[p][0] = 1.0;
    for (int p = 0; p < np; ++p)
      for (int i = 0; i < nt[p]; ++i) {
        const int vb = n_ + b[p][i];
        for (int r = 0; r < np; ++r)
          for (int c = 0; c < nt[r]; ++c) {
            trip.emplace_back(vb, n_ + b[r][c], w[p][i] * w[r][c] * jd.dM_dv[p][r] * im(b[p][i]));
            if (pos) trip.emplace_back(vb, b[r][c], w[p][i] * w[r][c] * jd.dM_dq[p][r] * im(b[p][i]));
          }
        for (int j = 0; j < nx; ++j) {
          trip.emplace_back(vb, o + j, w[p][i] * jd.dM_dx[p][j] * im(b[p][i]));
          trip.emplace_back(o + j, vb, w[p][i] * jd.dx_dv[j][p]);
          if (pos) trip.emplace_back(o + j, b[p][i], w[p][i] * jd.dx_dq[j][p]);
        }
      }
    for (int j = 0; j < nx; ++j)
      for (int c = 0; c < nx; ++c) trip.emplace_back(o + j, o + c, jd.dx_dx[j][c]);
  }
  J.resize(2 * n_ + nx_, 2 * n_ + nx_);
  J.setFromTriplets(trip.begin(), trip.end());
  J.makeCompressed();
}

void DriveSystem::external_forces(double t, const double* y, const double* fc, double* f) const {
  for (int i = 0; i < n_; ++i) f[i] = 0.0;
  for (const auto& ld : m_.loads) ld.spread(ld.at(t, y, y + n_), f);
  for (int d = 0; d < nd_; ++d) drive_spread(d, t, y, f);
  const double* q = machine_positions(y);
  for (int i : machine_bodies_) f[i] += machine_[static_cast<size_t>(i)]->force(q[i]);
  for (int k = 0; k < nc_; ++k) contacts_[static_cast<size_t>(k)].apply(fc[k], f);
}

double DriveSystem::kinetic_energy(const double* y) const {
  double T = 0;
  const double* q = machine_positions(y);
  for (int i = 0; i < n_; ++i) {
    double I = inertia_[static_cast<size_t>(i)], dI;
    if (const Machine* mach = machine_[static_cast<size_t>(i)]) mach->inertia(q[i], &I, &dI);  // ½ I(q) v²
    T += 0.5 * I * y[n_ + i] * y[n_ + i];
  }
  return T;
}

double DriveSystem::elastic_energy(const double* y) const {
  double V = 0;
  for (int l = 0; l < nl_; ++l)
    V += links_[static_cast<size_t>(l)].elastic_energy(link_kinematics(l, y).delta, gap_[static_cast<size_t>(l)],
                                                       links_[static_cast<size_t>(l)].drum(y));
  for (int d = 0; d < nd_; ++d)  // elements that store energy (a gear mesh's teeth: model/element.hpp)
    if (drive(d).has_energy()) V += drive(d).energy(drive_motion(d, y), y + drive_offset(d), drive_mode(d));
  return V;
}

namespace {
/// A link whose law is c δ + d δ̇ in every mode (no gap, cap, shape, winding or machine point).
/// Calling the one law under this test lets the compiler drop the law's other branches: the
/// same arithmetic, a fraction of the instructions.
bool plain(const LinkLaw& k) { return !(k.gap | k.capped | k.shaped | k.winding | k.point); }
/// A plain link with a gap (no cap, shape, winding or machine point): the same law from the flank of
/// its mode, 0 while open; the same test lets the compiler drop the other branches.
bool gap_only(const LinkLaw& k) { return k.gap & !(k.capped | k.shaped | k.winding | k.point); }
/// A plain link or a gap link (no cap, shape, winding or machine point): the law with the flank of
/// its mode at run time (a plain link has no flank but its rest length, whatever its mode).
bool plain_or_gap(const LinkLaw& k) { return !(k.capped | k.shaped | k.winding | k.point); }

/// The loads of links [l, nl) by the general law (link_load: the plain and gap links' own arithmetic
/// for them too). Out of line: link_loads' loop over plain and gap links (every link of most models),
/// which ends here by a tail call, calls nothing else and keeps no frame (an output row's link loads).
__attribute__((noinline)) void general_link_loads(const DriveSystem& s, int l, int nl, const double* y, double* F) {
  for (; l < nl; ++l) F[l] = s.link_load(l, y);
}

}  // namespace

void DriveSystem::link_loads(const double* y, double* F) const {
  const LinkLaw* k = links_.data();  // walked by pointer, the bounds in registers
  for (int l = 0, nl = nl_; l < nl; ++l, ++k) {
    if (!plain_or_gap(*k)) [[unlikely]] return general_link_loads(*this, l, nl, y, F);
    F[l] = k->load(k->linear(y), k->linear(y + n_), gap_[static_cast<size_t>(l)], 0.0);
  }
}

void DriveSystem::link_loads_and_rates(const double* y, const double* dy, double* F, double* rate) const {
  const LinkLaw* k = links_.data();
  if (all_plain_) {
    for (int l = 0, nl = nl_; l < nl; ++l, ++k) {
      if (plain(*k)) {
        F[l] = k->load(k->linear(y), k->linear(y + n_), GapMode::open, 0.0);
        rate[l] = k->load_rate(y, dy, dy + n_, GapMode::open);
      } else {
        F[l] = link_load(l, y);
        rate[l] = link_load_rate(l, y, dy);
      }
    }
    return;
  }
  for (int l = 0, nl = nl_; l < nl; ++l, ++k) {
    if (plain_or_gap(*k)) {
      const GapMode g = gap_[static_cast<size_t>(l)];
      F[l] = k->load(k->linear(y), k->linear(y + n_), g, 0.0);
      rate[l] = k->load_rate(y, dy, dy + n_, g);
    } else {
      F[l] = link_load(l, y);
      rate[l] = link_load_rate(l, y, dy);
    }
  }
}

void DriveSystem::contact_forces_other(double t, const double* y, double* fc) {
  if (affine_eligible_ && !dense_) {  // the mode's affine rows (compile_affine)
    if (!affine_) use_affine();
    if (!affine_eligible_) {  // the mode has no affine map (compile_affine)
      mode_changed();
      evaluate(t, y, f_.data(), fc);
      return;
    }
    const AffineMode& a = *affine_;
    if (a.force_dense.kernel) {
      a.force_dense.apply(y, fc);
      return;
    }
    for (int k = 0; k < nc_; ++k) {
      double s = a.force_c[k];
      for (int i = a.force_start[static_cast<size_t>(k)]; i < a.force_start[static_cast<size_t>(k) + 1]; ++i)
        s += a.force_val[static_cast<size_t>(i)] * y[a.force_col[static_cast<size_t>(i)]];
      fc[k] = s;
    }
    return;
  }
  evaluate(t, y, f_.data(), fc);
}

void DriveSystem::event_functions(double t, const double* y, double* g) {
  if (!stuck_.empty()) contact_forces(t, y, fc_.data());  // λ of the stuck contacts
  for (int l = 0; l < nl_; ++l) {
    const LinkLaw& k = links_[static_cast<size_t>(l)];
    if (!k.gap) {
      g[2 * l] = g[2 * l + 1] = 1.0;
      continue;
    }
    if (gap_only(k)) {  // the same law without the branches this link does not have
      k.events(k.linear(y), k.linear(y + n_), gap_[static_cast<size_t>(l)], 0.0, g + 2 * l);
      continue;
    }
    const LinkLaw::Kinematics s = link_kinematics(l, y);
    k.events(s.delta, s.rate, gap_[static_cast<size_t>(l)], k.drum(y), g + 2 * l);
  }
  for (int k = 0; k < nc_; ++k) {
    const ContactLaw& c = contacts_[static_cast<size_t>(k)];
    const ContactMode md = mode_[static_cast<size_t>(k)];
    c.events(md, t, fc_[static_cast<size_t>(k)], md == ContactMode::stuck && !c.kinematic ? 0.0 : c.sliding_velocity(t, y + n_),
             y[c.a], g + 2 * nl_ + 2 * k);
  }
  // An element may read its body's acceleration in its mode (a speed drive on its limit).
  bool accelerations = false;
  for (int d = 0; d < nd_; ++d) accelerations = accelerations || drive(d).reads_acceleration(drive_mode(d));
  if (accelerations) evaluate(t, y, f_.data(), fc_.data());
  if (ng_ > 0) {  // lossy gears: from the forces on their bodies in the current modes
    if (!accelerations) evaluate(t, y, f_.data(), fc_.data());
    for (int gi = 0; gi < ng_; ++gi) {
      const LossyGearLaw& k = gears_[static_cast<size_t>(gi)];
      const auto u = static_cast<size_t>(gi);
      if (gear_motion_[u] >= 0) [[unlikely]] {
        const PrescribedMotionLaw& p = motions_[static_cast<size_t>(gear_motion_[u])];
        k.events_given(gear_mode_[u], gear_now_[u], given_speed(p, k, gear_b_given_[u] != 0, t, y + n_), gear_t_[u],
                       g + 2 * (nl_ + nc_ + nd_ + gi));
        continue;
      }
      if (const int tn = train_of_gear_[u]; tn >= 0 && gear_mode_[u] == GearMode::stuck) [[unlikely]] {
        // A stuck train: its two start margins in its first gear's slots (analysis/gear_train.hpp).
        const GearTrain& tr = trains_[static_cast<size_t>(tn)];
        double* ev = g + 2 * (nl_ + nc_ + nd_ + gi);
        if (gi == static_cast<int>(tr.gears[0])) {
          const std::array<double, 3>& F = train_f_[static_cast<size_t>(tn)];
          ev[0] = train_start_margin(tr, gears_, +1, F, train_inertia(tn));
          ev[1] = train_start_margin(tr, gears_, -1, F, train_inertia(tn));
        } else {
          ev[0] = ev[1] = 1.0;
        }
        continue;
      }
      k.events(gear_mode_[u], gear_fa_[u], gear_fb_[u], 1.0 / inv_mass_[static_cast<size_t>(k.a)],
               1.0 / inv_mass_[static_cast<size_t>(k.b)], y[n_ + k.a], gear_t_[u], g + 2 * (nl_ + nc_ + nd_ + gi));
      if (const int tn = train_of_gear_[u]; tn >= 0) [[unlikely]]  // a rolling train's side: its rounding allowance
        g[2 * (nl_ + nc_ + nd_ + gi) + 1] +=
            train_side_detail::allowance(trains_[static_cast<size_t>(tn)], gears_, train_f_[static_cast<size_t>(tn)], gi);
      if (gear_joint_[u] != 0 && locks_.of_gear[u] < 0)  // held on its locking range by the split: its limit's allowance
        for (int e = 0; e < 2; ++e) g[2 * (nl_ + nc_ + nd_ + gi) + e] += k.allowance(gear_fa_[u], gear_fb_[u]);
    }
    if (!locks_.empty()) lock_event_functions(t, g);
  }
  for (int d = 0; d < nd_; ++d) {
    drive(d).events(t, accelerations ? evaluated_motion(d, t, y) : drive_motion(d, y), y + drive_offset(d),
                    drive_mode(d), g + 2 * (nl_ + nc_ + d));
  }
}

ElementMotion DriveSystem::evaluated_motion(int d, double t, const double* y) const {
  ElementMotion b = drive_motion(d, y, f_.data());
  // On each port on one body, everything else on it with the stuck set's loads: I a − M_p.
  double M[ElementMotion::kMax] = {};
  const int p_held = drive(d).held_port(drive_mode(d));
  drive(d).forces(t, p_held < 0 ? b : drive_motion_at(d, t, y), y + drive_offset(d), drive_mode(d), M);
  for (int p = 0; p < b.n; ++p)
    if (const int j = port_body(d, p); j >= 0 && (general_ ? im_ : inv_mass_)[static_cast<size_t>(j)] > 0.0)
      b.load[p] = f_[static_cast<size_t>(j)] / (general_ ? im_ : inv_mass_)[static_cast<size_t>(j)] - M[p];
  return b;
}

int DriveSystem::natural_drive_mode(int d, double t, const double* y) {
  const Element& k = drive(d);
  const int cur = drive_mode(d);
  const bool acc = k.reads_acceleration(cur);
  if (acc) evaluate(t, y, f_.data(), fc_.data());
  return confirm_hold(d, t, y, k.natural_mode(t, acc ? evaluated_motion(d, t, y) : drive_motion(d, y), y + drive_offset(d), cur));
}

int DriveSystem::settle_drive_mode(int d, double t, const double* y, int now) {
  const Element& k = drive(d);
  const int old = drive_mode(d);
  if (!k.settles(old, now)) return now;
  evaluate(t, y, f_.data(), fc_.data());
  return confirm_hold(d, t, y, k.settle(t, evaluated_motion(d, t, y), y + drive_offset(d), old, now));
}

// A mode that starts holding a body is judged in itself (its loads, the stuck set's with it, are
// those of that mode): where its own event function starts negative — the loads outside what it can
// hold — it is settled again from there at once, as the driver would hand it back.
int DriveSystem::confirm_hold(int d, double t, const double* y, int md) {
  const Element& k = drive(d);
  const int old = drive_mode(d);
  if (k.held_port(md) < 0 || k.held_port(old) == k.held_port(md)) return md;
  set_drive_mode(d, md);
  evaluate(t, y, f_.data(), fc_.data());
  const ElementMotion b = evaluated_motion(d, t, y);
  double g[2];
  k.events(t, b, y + drive_offset(d), md, g);
  if (g[1] < 0.0) md = k.settle(t, b, y + drive_offset(d), md, k.mode_after(md, 1));
  set_drive_mode(d, old);
  return md;
}

namespace {

/// The root of body i in a union-find forest (path halving).
int cluster_root(std::vector<int>& parent, int i) {
  while (parent[static_cast<size_t>(i)] != i) i = parent[static_cast<size_t>(i)] = parent[static_cast<size_t>(parent[static_cast<size_t>(i)])];
  return i;
}

void exact_clusters(const std::vector<ContactLaw>& contacts, const std::vector<int>& stuck, int n, double t, double* v,
                    const double* im) {
  // The bodies tied together by stuck unit rows form clusters; each moves with one velocity, so
  // every stuck contact has u = 0 exactly: the ground's w(t) where a contact ties the cluster to the
  // ground, else the momentum mean Σ v_i/m_i⁻¹ / Σ 1/m_i⁻¹ (a pair (m_b⁻¹ v_a + m_a⁻¹ v_b)/(m_a⁻¹ + m_b⁻¹));
  // a cluster whose velocities are already all equal keeps them. (Pairwise means one contact after
  // another are not exact on a chain: the last one moves a body of the first, and a contact decided
  // to slide from rest beside them started at u = ±1e-20, its event function negative.)
  // Scratch kept per thread: this runs at every event, and allocations were a measurable part of
  // the travel start-up's time.
  thread_local std::vector<int> parent, grounded, first, second, count;
  thread_local std::vector<double> p, m;
  thread_local std::vector<char> equal;
  const auto N = static_cast<size_t>(n);
  parent.resize(N);
  for (int i = 0; i < n; ++i) parent[static_cast<size_t>(i)] = i;
  grounded.assign(N, -1);  // per root: a contact tying it to the ground
  for (int k : stuck) {
    const ContactLaw& c = contacts[static_cast<size_t>(k)];
    if (c.b >= 0) {
      const int ra = cluster_root(parent, c.a), rb = cluster_root(parent, c.b);
      if (ra == rb) continue;
      parent[static_cast<size_t>(ra)] = rb;
      if (grounded[static_cast<size_t>(rb)] < 0) grounded[static_cast<size_t>(rb)] = grounded[static_cast<size_t>(ra)];
    } else {
      const int ra = cluster_root(parent, c.a);
      if (grounded[static_cast<size_t>(ra)] < 0) grounded[static_cast<size_t>(ra)] = k;
    }
  }
  // Per root, from the velocities before any is changed (the clusters are disjoint): its first two
  // bodies, its size, whether all its velocities are equal, Σ v_i/m_i⁻¹ and Σ 1/m_i⁻¹ in body order.
  first.assign(N, -1), second.assign(N, -1), count.assign(N, 0), p.assign(N, 0.0), m.assign(N, 0.0), equal.assign(N, 1);
  for (int i = 0; i < n; ++i) {
    const auto r = static_cast<size_t>(cluster_root(parent, i));
    if (count[r]++ == 0) first[r] = i;
    else if (count[r] == 2) second[r] = i;
    equal[r] = equal[r] && v[i] == v[first[r]];
    p[r] += v[i] / im[i], m[r] += 1.0 / im[i];
  }
  // The common velocity per root, into p; `equal` left 0 for the roots whose bodies take it.
  for (size_t r = 0; r < N; ++r) {
    const bool keep = count[r] < 2 && grounded[r] < 0;
    if (keep || (grounded[r] < 0 && equal[r])) {
      equal[r] = 1;
      continue;
    }
    if (grounded[r] >= 0) {
      p[r] = contacts[static_cast<size_t>(grounded[r])].surface_velocity(t);
    } else if (count[r] == 2) {
      const double ia = im[first[r]], ib = im[second[r]];
      p[r] = (ib * v[first[r]] + ia * v[second[r]]) / (ia + ib);
    } else {
      p[r] /= m[r];
    }
    equal[r] = 0;
  }
  for (int i = 0; i < n; ++i) {
    const auto r = static_cast<size_t>(cluster_root(parent, i));
    if (!equal[r]) v[i] = p[r];
  }
}

}  // namespace

void DriveSystem::project_velocities(double t, double* y) const {
  if (stuck_.empty()) return;
  if (coupled_) {  // u ≡ 0 exactly from the gears' bodies outwards (no projector: C is not M⁻¹)
    enforce_coupled(t, y + n_, inv_mass_.data(), true);
    return;
  }
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
    const VelocityRow& row = contacts_[static_cast<size_t>(stuck_[j])].row;
    for (int i = 0; i < row.terms; ++i) v[row.body[i]] -= im[row.body[i]] * row.w[i] * mu(static_cast<Eigen::Index>(j));
  }
  // Remove the rounding: u exactly 0 (as enforce_stuck does for the accelerations).
  bool general = false;
  for (int k : stuck_) general = general || contacts_[static_cast<size_t>(k)].general;
  if (!general) {
    exact_clusters(contacts_, stuck_, n_, t, v, im);
    return;
  }
  // With general rows: contact by contact, the common velocity of a pair the momentum mean
  // (I_a v_a + I_b v_b)/(I_a + I_b). The general rows first (their step touches every body of the
  // row, leaving the rounding in their own u), then the unit rows, exact: a row stepped after them
  // moved their bodies again (a ring brake beside a planetary gear's joint read u = −1e-29).
  for (int k : stuck_) {
    const ContactLaw& c = contacts_[static_cast<size_t>(k)];
    if (c.general) step_onto_row(c.row, c.sliding_velocity(t, v), v, im);
  }
  for (int k : stuck_) {
    const ContactLaw& c = contacts_[static_cast<size_t>(k)];
    if (c.general) {
      continue;
    } else if (c.b < 0) {
      v[c.a] = c.surface_velocity(t);
    } else {
      const double ia = im[c.a], ib = im[c.b];
      v[c.a] = v[c.b] = (ib * v[c.a] + ia * v[c.b]) / (ia + ib);
    }
  }
}

std::string DriveSystem::state_name(int i) const {
  if (i >= energy_index()) return "energy quadrature";
  if (i >= 2 * n_) {
    int d = nd_ - 1;
    while (d > 0 && drive_off_[static_cast<size_t>(d)] > i) --d;
    return fmt::format("drive '{}' ({})", m_.drives[static_cast<size_t>(d)].name,
                       drive(d).state_name(i - drive_offset(d)));
  }
  const bool vel = i >= n_;
  const auto& b = m_.bodies[static_cast<size_t>(vel ? i - n_ : i)];
  return fmt::format("body '{}' ({})", b.name, vel ? "velocity" : "position");
}

}  // namespace machdyn
