#include "machdyn/analysis/static_loads.hpp"

#include <algorithm>
#include <cmath>
#include <vector>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

#include "analysis/independent_rows.hpp"
#include "machdyn/elements/link.hpp"

namespace machdyn {

namespace {
/// A row's entries on free bodies, scaled to unit length (empty when none is left).
std::vector<std::pair<int, double>> free_unit_row(const Model& m, const std::vector<std::pair<int, double>>& g) {
  std::vector<std::pair<int, double>> r;
  double norm = 0.0;
  for (const auto& [j, w] : g)
    if (j >= 0 && w != 0.0 && m.bodies[static_cast<size_t>(j)].motion == MotionKind::free) r.emplace_back(j, w), norm += w * w;
  for (auto& [j, w] : r) w /= std::sqrt(norm);
  return r;
}

/// The rows of G that constrain free bodies: entries on bodies with prescribed motion dropped (they
/// are supports), each row scaled to unit length, and a row that repeats the others (two brakes on
/// one drum) left out (detail::independent_rows). `kept` (if given): the index in G of each row returned.
ConstraintRows free_independent_rows(const Model& m, const ConstraintRows& G, std::vector<size_t>* kept = nullptr) {
  ConstraintRows rows;
  std::vector<size_t> from;
  for (size_t k = 0; k < G.size(); ++k) {
    std::vector<std::pair<int, double>> r = free_unit_row(m, G[k]);
    if (r.empty()) continue;
    rows.push_back(std::move(r));
    from.push_back(k);
  }
  ConstraintRows out;
  for (size_t k : detail::independent_rows({}, rows)) {
    out.push_back(std::move(rows[k]));
    if (kept) kept->push_back(from[k]);
  }
  return out;
}

/// K from the links' own Jacobian terms (elements/link.hpp): ∂(acc·M)/∂q = −K, every link counted
/// as a closed spring; the entries in a row or column of `skip` left out.
void stiffness_triplets(const Model& m, const std::vector<char>& skip, std::vector<Eigen::Triplet<double>>& trip) {
  const int n = m.dof();
  for (const auto& l : m.links) {
    if (l.c <= 0.0) continue;
    LinkLaw::of(m, l).jacobian(n, GapMode::closed_pos, [&](int row, int col, double v) {
      if (col >= n || skip[static_cast<size_t>(row)] || skip[static_cast<size_t>(col)]) return;
      trip.emplace_back(row, col, -v);
    });
  }
}
}  // namespace

namespace detail {
std::vector<size_t> independent_rows(const ConstraintRows& before, const ConstraintRows& rows) {
  // Columns: only the bodies the rows touch.
  std::vector<int> col;
  auto column = [&](int j) {
    for (size_t c = 0; c < col.size(); ++c)
      if (col[c] == j) return static_cast<Eigen::Index>(c);
    col.push_back(j);
    return static_cast<Eigen::Index>(col.size() - 1);
  };
  for (const auto* set : {&before, &rows})
    for (const auto& g : *set)
      for (const auto& [j, w] : g) column(j);
  const auto width = static_cast<Eigen::Index>(col.size());
  auto rank = [](const Eigen::MatrixXd& X) {
    Eigen::FullPivLU<Eigen::MatrixXd> lu(X);
    lu.setThreshold(1e-10);
    return lu.rank();
  };
  auto with = [&](const Eigen::MatrixXd& D, const std::vector<std::pair<int, double>>& g) {
    Eigen::MatrixXd E(D.rows() + 1, width);
    E.topRows(D.rows()) = D;
    E.row(D.rows()).setZero();
    for (const auto& [j, w] : g) E(D.rows(), column(j)) += w;
    return E;
  };
  Eigen::MatrixXd D = Eigen::MatrixXd::Zero(0, width);
  for (const auto& g : before) D = with(D, g);
  Eigen::Index have = D.rows() > 0 ? rank(D) : 0;
  std::vector<size_t> kept;
  for (size_t k = 0; k < rows.size(); ++k) {
    Eigen::MatrixXd E = with(D, rows[k]);
    const Eigen::Index now = rank(E);
    if (now <= have) continue;
    D = std::move(E), have = now;
    kept.push_back(k);
  }
  return kept;
}
}  // namespace detail

namespace {
/// ker K when a link ends on a massless member (elements/link.hpp: δ over three bodies, or a weight
/// on b), which the walk over two-body links below cannot follow: the null space of the springs'
/// K = Σ c j jᵀ, scaled to a unit diagonal (bodies without a spring keep 1) so that rotational and
/// translational coordinates weigh alike; a body with prescribed motion is held (a support). With
/// constraint rows G: the null space of the sum with Σ (S g)(S g)ᵀ / |S g|², ker K ∩ ker G.
Eigen::MatrixXd rigid_motions_by_null_space(const Model& m, const ConstraintRows& G) {
  const int n = m.dof();
  Eigen::MatrixXd K = Eigen::MatrixXd::Zero(n, n);
  for (const auto& l : m.links) {
    if (l.c <= 0.0) continue;
    LinkLaw::of(m, l).jacobian(n, GapMode::closed_pos, [&](int r, int c, double v) {
      if (c < n) K(r, c) -= v;
    });
  }
  Eigen::VectorXd s(n);
  for (int i = 0; i < n; ++i) s(i) = K(i, i) > 0.0 ? 1.0 / std::sqrt(K(i, i)) : 1.0;
  Eigen::MatrixXd S = s.asDiagonal() * K * s.asDiagonal();
  for (int i = 0; i < n; ++i)
    if (m.bodies[static_cast<size_t>(i)].motion != MotionKind::free) S(i, i) += 1.0;
  for (const auto& g : G) {
    Eigen::VectorXd sg = Eigen::VectorXd::Zero(n);
    for (const auto& [j, w] : g) sg(j) += s(j) * w;
    S += sg * sg.transpose() / sg.squaredNorm();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(S);
  const double tol = 1e-10 * std::max(1.0, eig.eigenvalues().cwiseAbs().maxCoeff());
  std::vector<Eigen::Index> null;
  for (Eigen::Index k = 0; k < n; ++k)
    if (std::abs(eig.eigenvalues()(k)) <= tol) null.push_back(k);
  Eigen::MatrixXd R(n, static_cast<Eigen::Index>(null.size()));
  for (size_t k = 0; k < null.size(); ++k) {
    Eigen::VectorXd col = s.asDiagonal() * eig.eigenvectors().col(null[k]);
    Eigen::Index big = 0;
    col.cwiseAbs().maxCoeff(&big);
    R.col(static_cast<Eigen::Index>(k)) = col / col(big);  // its largest coordinate 1, as the walk's root
  }
  return R;
}
}  // namespace

Eigen::MatrixXd rigid_motions(const Model& m, const ConstraintRows& G_all) {
  const int n = m.dof();
  const ConstraintRows G = free_independent_rows(m, G_all);
  for (const auto& l : m.links)
    if (l.c > 0.0 && (l.third >= 0 || l.b_weight != 1.0)) return rigid_motions_by_null_space(m, G);
  for (const auto& g : G)
    if (g.size() > 2) return rigid_motions_by_null_space(m, G);  // a row over three bodies (a planetary joint)
  // Spring graph: adjacency with the factor that carries q across a link (q_b = q_a / i).
  struct Edge {
    int to;
    double factor;
  };
  std::vector<std::vector<Edge>> adj(static_cast<size_t>(n));
  std::vector<bool> grounded(static_cast<size_t>(n), false);
  // A body with prescribed motion is a support (elements/prescribed_motion.hpp): no free motion.
  for (int i = 0; i < n; ++i) grounded[static_cast<size_t>(i)] = m.bodies[static_cast<size_t>(i)].motion != MotionKind::free;
  for (const auto& l : m.links) {
    if (l.c <= 0.0) continue;
    if (l.a < 0 || l.b < 0) {
      grounded[static_cast<size_t>(l.a < 0 ? l.b : l.a)] = true;
      continue;
    }
    adj[static_cast<size_t>(l.a)].push_back({l.b, 1.0 / l.ratio});
    adj[static_cast<size_t>(l.b)].push_back({l.a, l.ratio});
  }
  // A held element: a row on one body holds it to the ground, a row w_a v_a + w_b v_b = 0 carries q
  // as a link's ratio does, q_b = −(w_a / w_b) q_a.
  for (const auto& g : G) {
    if (g.size() == 1) {
      grounded[static_cast<size_t>(g[0].first)] = true;
      continue;
    }
    const auto [a, wa] = g[0];
    const auto [b, wb] = g[1];
    adj[static_cast<size_t>(a)].push_back({b, -wa / wb});
    adj[static_cast<size_t>(b)].push_back({a, -wb / wa});
  }
  std::vector<double> value(static_cast<size_t>(n), 0.0);
  std::vector<int> group(static_cast<size_t>(n), -1);
  std::vector<Eigen::VectorXd> columns;
  for (int root = 0; root < n; ++root) {
    if (group[static_cast<size_t>(root)] >= 0) continue;
    const int g = static_cast<int>(columns.size());
    bool free_group = true;
    std::vector<int> stack{root}, members;
    group[static_cast<size_t>(root)] = g;
    value[static_cast<size_t>(root)] = 1.0;
    while (!stack.empty()) {
      const int a = stack.back();
      stack.pop_back();
      members.push_back(a);
      if (grounded[static_cast<size_t>(a)]) free_group = false;
      for (const auto& e : adj[static_cast<size_t>(a)]) {
        const double v = value[static_cast<size_t>(a)] * e.factor;
        if (group[static_cast<size_t>(e.to)] < 0) {
          group[static_cast<size_t>(e.to)] = g;
          value[static_cast<size_t>(e.to)] = v;
          stack.push_back(e.to);
        } else if (std::abs(value[static_cast<size_t>(e.to)] - v) > 1e-12 * std::abs(v)) {
          free_group = false;  // a loop of gears with inconsistent ratios locks the group
        }
      }
    }
    Eigen::VectorXd col = Eigen::VectorXd::Zero(n);
    if (free_group)
      for (int i : members) col(i) = value[static_cast<size_t>(i)];
    columns.push_back(col);
  }
  int r = 0;
  for (const auto& c : columns) r += c.squaredNorm() > 0 ? 1 : 0;
  Eigen::MatrixXd R(n, r);
  int k = 0;
  for (const auto& c : columns)
    if (c.squaredNorm() > 0) R.col(k++) = c;
  return R;
}

struct ParticularSolver::Impl {
  const Model& m;
  Eigen::MatrixXd R, MR;
  Eigen::LDLT<Eigen::MatrixXd> rigid;  // Rᵀ M R
  Eigen::SparseLU<Eigen::SparseMatrix<double>> lu;
  std::vector<int> pins;  // pinned coordinates (q_p = 0), or empty: the bordered system
  std::vector<int> fixed;  // bodies with prescribed motion: supports (q = 0), in both systems
  Eigen::Index rows = 0;   // size of the system: n (+ r with the border) + the rows of G
  bool reacting = false;   // some row's reaction is not along it (H ≠ G): a'' solved with q_e and λ
  explicit Impl(const Model& model) : m(model) {}
};

ParticularSolver::ParticularSolver(const Model& m, const ConstraintRows& G_all, const ConstraintRows& H_all)
    : impl_(new Impl(m)) {
  const int n = m.dof();
  Impl& s = *impl_;
  std::vector<size_t> kept;
  const ConstraintRows G = free_independent_rows(m, G_all, &kept);
  // The reaction rows on free bodies, unit length; a row whose reaction reaches no free body would
  // leave its λ undetermined: taken along its row.
  ConstraintRows H(G.size());
  for (size_t k = 0; k < G.size(); ++k)
    if (kept[k] < H_all.size() && !H_all[kept[k]].empty()) {
      H[k] = free_unit_row(m, H_all[kept[k]]);
      s.reacting = s.reacting || !H[k].empty();
    }
  s.R = rigid_motions(m, G);
  const auto r = s.R.cols();
  Eigen::VectorXd M(n);
  for (int i = 0; i < n; ++i) M(i) = m.bodies[static_cast<size_t>(i)].inertia;
  s.MR = M.asDiagonal() * s.R;
  if (r > 0) s.rigid.compute(s.R.transpose() * s.MR);

  // The link loads do not see rigid motions (K R = 0), so any solution of K q = f_e serves: pin one
  // coordinate per rigid motion (q_p = 0) where R restricted to the pinned rows is nonsingular.
  // Then the pinned rows' equations hold too (Rᵀ f_e = 0 and Rᵀ K = 0 leave R_pᵀ·residual_p = 0),
  // and the matrix stays as sparse as K: O(n) for a chain. R's columns walk disjoint spring graphs,
  // so the largest entry of each column gives independent pins; if not (checked), the bordered
  // saddle-point system [K MR; (MR)ᵀ 0] below, whose dense border fills in (O(n²) for long chains).
  std::vector<int> pin(static_cast<size_t>(r), -1);
  std::vector<char> pinned(static_cast<size_t>(n), 0), fixed(static_cast<size_t>(n), 0);
  for (int i = 0; i < n; ++i)
    if (m.bodies[static_cast<size_t>(i)].motion != MotionKind::free) fixed[static_cast<size_t>(i)] = 1, s.fixed.push_back(i);
  bool pins_ok = r > 0;
  for (Eigen::Index k = 0; k < r && pins_ok; ++k) {
    Eigen::Index i = 0;
    s.R.col(k).cwiseAbs().maxCoeff(&i);
    pins_ok = !pinned[static_cast<size_t>(i)];
    pin[static_cast<size_t>(k)] = static_cast<int>(i), pinned[static_cast<size_t>(i)] = 1;
  }
  if (pins_ok) {
    Eigen::MatrixXd Rp(r, r);
    for (Eigen::Index k = 0; k < r; ++k) Rp.row(k) = s.R.row(pin[static_cast<size_t>(k)]);
    pins_ok = Eigen::FullPivLU<Eigen::MatrixXd>(Rp).rank() == r;
  }
  if (s.reacting) {
    reacting_system(G, H, pins_ok ? pin : std::vector<int>{}, fixed);
    return;
  }
  // K without the rows and columns of pinned coordinates and of prescribed bodies.
  std::vector<Eigen::Triplet<double>> trip;
  std::vector<char> skip = fixed;
  if (pins_ok)
    for (int i : pin) skip[static_cast<size_t>(i)] = 1;
  stiffness_triplets(m, skip, trip);
  for (int i : s.fixed) trip.emplace_back(i, i, 1.0);
  // The rows of G border the system ([K Gᵀ; G 0]); a pinned coordinate's entries drop out with it
  // (q_p = 0; a row left empty is implied by the pins, as R spans ker G).
  auto border_constraints = [&](Eigen::Index base) {
    for (const auto& g : G) {
      bool any = false;
      for (const auto& [j, w] : g)
        if (!(pins_ok && pinned[static_cast<size_t>(j)])) {
          trip.emplace_back(base, j, w), trip.emplace_back(j, base, w);
          any = true;
        }
      if (any) ++base;
    }
    return base;
  };
  if (pins_ok) {
    for (int i : pin) trip.emplace_back(i, i, 1.0);
    s.pins = pin;
    s.rows = border_constraints(n);
    Eigen::SparseMatrix<double> A(s.rows, s.rows);
    A.setFromTriplets(trip.begin(), trip.end());
    s.lu.compute(A);
    return;
  }
  for (Eigen::Index k = 0; k < r; ++k)
    for (int i = 0; i < n; ++i)
      if (s.MR(i, k) != 0.0) {
        trip.emplace_back(i, n + k, s.MR(i, k));
        trip.emplace_back(n + k, i, s.MR(i, k));
      }
  s.rows = border_constraints(n + r);
  Eigen::SparseMatrix<double> A(s.rows, s.rows);
  A.setFromTriplets(trip.begin(), trip.end());
  s.lu.compute(A);
}

void ParticularSolver::reacting_system(const ConstraintRows& G, const ConstraintRows& H, const std::vector<int>& pins,
                                       const std::vector<char>& fixed) {
  // [K −Hᵀ MR; G 0 0; P 0 0] [q_e; λ; a''] = [f; 0; 0] (header): all of K (a pinned coordinate's
  // equation is needed, its q is set by its row of P), a body with prescribed motion a support.
  Impl& s = *impl_;
  const Model& m = s.m;
  const int n = m.dof();
  const auto nG = static_cast<Eigen::Index>(G.size()), r = s.R.cols();
  std::vector<Eigen::Triplet<double>> trip;
  stiffness_triplets(m, fixed, trip);
  for (int i : s.fixed) trip.emplace_back(i, i, 1.0);
  for (Eigen::Index k = 0; k < nG; ++k) {
    const auto& g = G[static_cast<size_t>(k)];
    const auto& h = H[static_cast<size_t>(k)].empty() ? g : H[static_cast<size_t>(k)];
    for (const auto& [j, w] : g) trip.emplace_back(n + k, j, w);
    for (const auto& [j, w] : h) trip.emplace_back(j, n + k, -w);
  }
  for (Eigen::Index k = 0; k < r; ++k) {
    const Eigen::Index row = n + nG + k;
    for (int i = 0; i < n; ++i)
      if (s.MR(i, k) != 0.0) {
        trip.emplace_back(i, row, s.MR(i, k));
        if (pins.empty()) trip.emplace_back(row, i, s.MR(i, k));  // no pins: (MR)ᵀ q_e = 0
      }
    if (!pins.empty()) trip.emplace_back(row, pins[static_cast<size_t>(k)], 1.0);
  }
  s.rows = n + nG + r;
  Eigen::SparseMatrix<double> A(s.rows, s.rows);
  A.setFromTriplets(trip.begin(), trip.end());
  s.lu.compute(A);
}

ParticularSolver::~ParticularSolver() { delete impl_; }

Eigen::VectorXd ParticularSolver::solve(const Eigen::VectorXd& f) const {
  const Impl& s = *impl_;
  const Model& m = s.m;
  const int n = m.dof();
  Eigen::VectorXd rhs = Eigen::VectorXd::Zero(s.rows);
  rhs.head(n) = f;
  if (s.R.cols() > 0 && !s.reacting) rhs.head(n) -= s.MR * s.rigid.solve(s.R.transpose() * f);
  // A spring's free length (elements/link.hpp): F = c (δ − δ₀), its constant part −c δ₀ a pair of
  // forces on its ends that do no work in a rigid motion (Rᵀ f₀ = 0), so only the elastic part sees it.
  for (const Link& l : m.links) LinkLaw::of(m, l).rest_forces(rhs.data());
  for (int p : s.pins) rhs(p) = 0.0;
  for (int p : s.fixed) rhs(p) = 0.0;
  const Eigen::VectorXd sol = s.lu.solve(rhs);
  Eigen::VectorXd F(static_cast<Eigen::Index>(m.links.size()));
  for (size_t k = 0; k < m.links.size(); ++k) {
    const LinkLaw law = LinkLaw::of(m, m.links[k]);
    // From the flank of the open mode: δ₀ without a gap, 0 with one (as every flank taken closed).
    F(static_cast<Eigen::Index>(k)) = law.spring_load(law.weighted(sol.data()) - law.flank(GapMode::open));
  }
  return F;
}

Eigen::VectorXd particular_link_loads(const Model& m, const Eigen::VectorXd& f, const ConstraintRows& G,
                                      const ConstraintRows& H) {
  return ParticularSolver(m, G, H).solve(f);
}

}  // namespace machdyn
