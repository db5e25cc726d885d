#include "machdyn/analysis/equilibrium.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <Eigen/Core>
#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <Eigen/QR>
#include <fmt/format.h>

#include "analysis/independent_rows.hpp"
#include "machdyn/analysis/static_loads.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/elements/contact.hpp"
#include "machdyn/elements/link.hpp"
#include "machdyn/elements/lossy_gear.hpp"

namespace machdyn {
namespace {

/// The elements whose rest force the equilibrium does not decide are refused, located.
void check_supported(const Model& m) {
  Diagnostics diag;
  const std::string pre = "simulation: 'initial: equilibrium'";
  for (const auto& b : m.bodies)
    if (b.motion != MotionKind::free)
      diag.error(m.where(b.name), fmt::format("{} cannot start body '{}' (its motion is prescribed by 'motion') in "
                                              "equilibrium yet; use 'initial: given'", pre, b.name));
  for (const auto& b : m.bodies)
    if (b.machine)
      diag.error(m.where(b.name), fmt::format("{} cannot start body '{}' (a machine with variable inertia) in "
                                              "equilibrium yet; use 'initial: given'", pre, b.name));
  for (const auto& l : m.links)
    if (l.a_point || l.b_point)
      diag.error(m.where(l.name), fmt::format("{}: link '{}' ends at a machine's point, not supported yet", pre, l.name));
  for (const auto& c : m.contacts) {
    if (c.joint) {
      diag.error(m.where(c.name), fmt::format("{}: the gear joint '{}' (a planetary gear or a gear on a housing body) "
                                              "is not supported there yet; start with 'initial: given'", pre, c.name));
      continue;
    }
    // Stops are decided below; a brake or clutch applied at t = 0 holds (its body to the ground or its
    // two bodies together, within its limit), one not yet applied is free.
    if (c.stop || c.brake || c.clutch) continue;
    diag.error(m.where(c.name), fmt::format("{}: the force at rest of {} '{}' is not decided by its law (friction "
                                            "holds anything within its limit); start with 'initial: given'",
                                            pre, c.lock != 0 ? "freewheel" : "contact", c.name));
  }
  diag.throw_if_any();
}

struct State {
  Eigen::VectorXd g;      // generalized forces g(q), N or N·m
  Eigen::VectorXd scale;  // Σ |terms| per body, for the balance tolerance
  Eigen::MatrixXd J;      // ∂g/∂q
};

/// The equilibrium for the gears' modes `verge`: stuck (holding both sides at rest), or, for a gear
/// that cannot hold its sides alone, at rest on the verge of rolling in the direction it would start
/// (a rolling mode: its ratio row and its rolling relation at v = 0, the reaction H μ + f0 of
/// elements/lossy_gear.hpp reaction()) — allowed where a brake or stop holds its group. A stuck gear
/// that cannot hold is recorded in `starts` (the rolling mode it would start in) and is an error.
EquilibriumStart solve_equilibrium(const Model& m, const std::vector<GearMode>& verge, std::vector<GearMode>* starts) {
  const int n = m.dof();
  const auto nl = m.links.size();
  std::vector<LinkLaw> laws;
  laws.reserve(nl);
  for (const auto& l : m.links) laws.push_back(LinkLaw::of(m, l));
  // End stops; brakes to the ground applied at t = 0 (they hold their body where it is); brakes on a
  // housing body and clutches applied at t = 0 (they tie their bodies: a row of G, their stuck row
  // u = 0, elements/contact.hpp add_linear); lossy gears, each held at rest on both sides (stuck:
  // its ratio and rest rows, elements/lossy_gear.hpp add_linear), rows of G like a clutch's.
  std::vector<int> stops, brakes, couplings;
  for (size_t k = 0; k < m.contacts.size(); ++k) {
    const FrictionContact& c = m.contacts[k];
    if (c.stop) stops.push_back(static_cast<int>(k));
    if ((c.brake || c.clutch) && c.scale(0.0) > 0.0)
      (c.b == kGround && c.row.terms == 0 ? brakes : couplings).push_back(static_cast<int>(k));
  }
  LinearModel coupled(n);  // the couplings' rows
  for (int k : couplings)
    ContactLaw::of(m.contacts[static_cast<size_t>(k)], m).add_linear(ContactMode::stuck, true, 0.0, 0.0, coupled);
  std::vector<LossyGearLaw> gears;
  LinearModel geared(n);  // the gears' rows, two per gear (ratio, rest)
  std::vector<Eigen::Index> gear_row;  // each gear's first row in geared.G (two stuck, one on the verge)
  for (size_t k = 0; k < m.lossy_gears.size(); ++k) {
    gears.push_back(LossyGearLaw::of(m.lossy_gears[k]));
    gear_row.push_back(static_cast<Eigen::Index>(geared.G.size()));
    gears.back().add_linear(verge[k], geared);
  }
  // The gears on the verge: their reactions are not along their rows (H μ + f0, lossy_gear.hpp).
  std::vector<int> verge_of_row(geared.G.size(), -1);
  for (size_t k = 0; k < gears.size(); ++k)
    if (verge[k] != GearMode::stuck) verge_of_row[static_cast<size_t>(gear_row[k])] = static_cast<int>(k);
  auto reaction_of = [&](int g) { return gears[static_cast<size_t>(g)].reaction(verge[static_cast<size_t>(g)], 0.0); };
  ConstraintRows tying = geared.G;  // every row that ties bodies: the gears', then the couplings'
  tying.insert(tying.end(), coupled.G.begin(), coupled.G.end());

  Eigen::VectorXd q(n), q_given(n), v_given(n), M(n);
  for (int i = 0; i < n; ++i) {
    const Body& b = m.bodies[static_cast<size_t>(i)];
    q(i) = q_given(i) = b.q0;
    v_given(i) = b.v0;
    M(i) = b.inertia;
  }
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(n);
  const double q_scale = 1.0 + q_given.lpNorm<Eigen::Infinity>();

  // Modes: a gap or rope presses the flank it is on or beyond; a stop holds a body on or past it.
  std::vector<GapMode> mode(nl, GapMode::open);
  for (size_t k = 0; k < nl; ++k) {
    if (!laws[k].gap) continue;
    const double delta = laws[k].weighted(q.data());
    mode[k] = delta >= laws[k].hi ? GapMode::closed_pos : delta <= laws[k].lo ? GapMode::closed_neg : GapMode::open;
  }
  std::vector<char> held(m.contacts.size(), 0);
  for (int k : brakes) held[static_cast<size_t>(k)] = 1;
  for (int k : stops) {
    const ContactLaw law = ContactLaw::of(m.contacts[static_cast<size_t>(k)]);
    held[static_cast<size_t>(k)] = law.stop_distance(q(law.a)) <= 1e-12 * q_scale;
  }

  // g(q) and ∂g/∂q from the loads at t = 0 and the links' law in their modes.
  auto evaluate = [&](const Eigen::VectorXd& x) {
    State s{Eigen::VectorXd::Zero(n), Eigen::VectorXd::Zero(n), Eigen::MatrixXd::Zero(n, n)};
    for (const auto& ld : m.loads) {  // f_i = ρ_i M(q_X), ∂f_i/∂q_j = ρ_i ρ_j ∂M/∂q_X (model.hpp: Load)
      const double Mx = ld.at(0.0, x.data(), v_given.data());
      double dq = 0.0, dv = 0.0;
      ld.slopes_at(0.0, x.data(), v_given.data(), &dq, &dv);
      int b[2];
      double w[2];
      const int nt = ld.terms(b, w);
      for (int i = 0; i < nt; ++i) {
        s.g(b[i]) += w[i] * Mx;
        s.scale(b[i]) += std::abs(w[i] * Mx);
        for (int j = 0; j < nt; ++j) s.J(b[i], b[j]) += w[i] * w[j] * dq;
      }
    }
    for (size_t k = 0; k < nl; ++k) {
      const LinkLaw& law = laws[k];
      if (!law.transmits(mode[k]) || law.c <= 0.0) continue;
      const LinkLaw::Kinematics kin = law.kinematics(x.data(), zero.data());
      const double F = law.winding ? law.apply_at(x.data(), zero.data(), mode[k], s.g.data())
                                   : law.load(kin.delta, 0.0, mode[k]);
      if (!law.winding) law.apply(F, kin, s.g.data());
      if (law.a >= 0) s.scale(law.a) += std::abs(F * kin.ja);
      if (law.b >= 0) s.scale(law.b) += std::abs(F * kin.jb);
      if (law.third >= 0) s.scale(law.third) += std::abs(F * law.w3);
      law.jacobian(n, mode[k], false, x.data(), [&](int r, int c, double val) {
        if (c < n) s.J(r, c) += val;
      });
    }
    return s;
  };
  // Rigid motions of the transmitting springs, a held body counting as tied to the ground.
  auto rigid = [&]() {
    Model tied;
    tied.bodies = m.bodies;
    for (size_t k = 0; k < nl; ++k)
      if (laws[k].transmits(mode[k]) && m.links[k].c > 0.0) tied.links.push_back(m.links[k]);
    auto tie = [&](int body) {
      Link l;
      l.b = body;
      l.c = 1.0;
      tied.links.push_back(l);
    };
    for (size_t k = 0; k < m.contacts.size(); ++k)
      if (held[k]) tie(m.contacts[k].a);
    return rigid_motions(tied, tying);
  };
  // The pinned bodies (a held stop or brake) and the gears' and couplings' rows that add to them
  // (a clutch beside a brake on the same body; two clutches on one pair add one row): the rows of
  // the border, each independent of the pins and the rows before it.
  auto pinned = [&]() {
    std::vector<int> p;
    for (size_t k = 0; k < m.contacts.size(); ++k)
      if (held[k]) p.push_back(m.contacts[k].a);
    return p;
  };
  auto independent_couplings = [&](const std::vector<int>& pins, std::vector<size_t>* index) {
    ConstraintRows before, rows;
    for (int p : pins) before.push_back({{p, 1.0}});
    for (size_t k : detail::independent_rows(before, tying)) rows.push_back(tying[k]), index->push_back(k);
    return rows;
  };

  EquilibriumStart out;
  Eigen::MatrixXd R;
  State s;
  constexpr int kMaxIterations = 100;
  bool settled = false;
  for (int it = 0; it < kMaxIterations && !settled; ++it) {
    out.iterations = it + 1;
    s = evaluate(q);
    R = rigid();
    const auto r = R.cols();
    // A free group pushed by loads that do not balance moves as a whole until the first open rope,
    // gap flank or stop in its way takes it up (a hanging load sinks onto its slack rope).
    bool moved = false;
    for (Eigen::Index k = 0; k < r && !moved; ++k) {
      const double net = R.col(k).dot(s.g), scale = R.col(k).cwiseAbs().dot(s.scale);
      if (std::abs(net) <= 1e-9 * scale) continue;
      const Eigen::VectorXd u = (net > 0.0 ? 1.0 : -1.0) * R.col(k);
      double best = HUGE_VAL;
      int link = -1, stop = -1;
      GapMode closes = GapMode::open;
      for (size_t l = 0; l < nl; ++l) {
        const LinkLaw& law = laws[l];
        if (!law.gap || mode[l] != GapMode::open) continue;
        const double rate = law.weighted(u.data()), delta = law.weighted(q.data());
        const double d = rate > 0.0 ? (law.hi - delta) / rate : rate < 0.0 ? (law.lo - delta) / rate : HUGE_VAL;
        if (std::isfinite(d) && d < best) best = d, link = static_cast<int>(l), stop = -1,
                                          closes = rate > 0.0 ? GapMode::closed_pos : GapMode::closed_neg;
      }
      for (int c : stops) {
        if (held[static_cast<size_t>(c)]) continue;
        const ContactLaw law = ContactLaw::of(m.contacts[static_cast<size_t>(c)]);
        const double slope = -law.lock * u(law.a);  // d(distance)/dα
        if (slope >= 0.0) continue;
        const double d = law.stop_distance(q(law.a)) / -slope;
        if (d < best) best = d, stop = c, link = -1;
      }
      if (link < 0 && stop < 0) continue;  // nothing takes it up: reported below
      q += std::max(best, 0.0) * u;
      if (link >= 0) mode[static_cast<size_t>(link)] = closes;
      if (stop >= 0) held[static_cast<size_t>(stop)] = 1;
      moved = true;
    }
    if (moved) continue;
    const Eigen::MatrixXd MR = M.asDiagonal() * R;
    Eigen::VectorXd acc = Eigen::VectorXd::Zero(r);  // the rigid acceleration a'' of each free group
    if (r > 0) acc = (R.transpose() * MR).ldlt().solve(R.transpose() * s.g);
    // [K MR Gᵀ; (MR)ᵀ 0 0; G 0 0] [Δ; μ; λ] = [g − MR a''; RᵀM (q_given − q); 0], K = −∂g/∂q, G the
    // gears' and couplings' rows (G Δ = 0: a gear holds its sides, a clutch keeps the given relative
    // position); a held body's row pins it.
    std::vector<size_t> g_index;  // each row's place in `tying`
    const ConstraintRows G = independent_couplings(pinned(), &g_index);
    const auto nc = static_cast<Eigen::Index>(G.size());
    Eigen::MatrixXd A = Eigen::MatrixXd::Zero(n + r + nc, n + r + nc);
    Eigen::VectorXd rhs = Eigen::VectorXd::Zero(n + r + nc);
    A.topLeftCorner(n, n) = -s.J;
    A.block(0, n, n, r) = MR;
    A.block(n, 0, r, n) = MR.transpose();
    rhs.head(n) = s.g - MR * acc;
    for (Eigen::Index k = 0; k < nc; ++k) {
      const size_t row = g_index[static_cast<size_t>(k)];
      const int vg = row < verge_of_row.size() ? verge_of_row[row] : -1;
      for (const auto& [j, w] : G[static_cast<size_t>(k)]) A(n + r + k, j) += w;
      if (vg < 0) {
        for (const auto& [j, w] : G[static_cast<size_t>(k)]) A(j, n + r + k) += w;
      } else {  // a gear on the verge puts H μ + f0 on its bodies
        const LossyGearLaw::Reaction re = reaction_of(vg);
        for (const auto& [j, w] : re.H) A(j, n + r + k) -= w;
        rhs(gears[static_cast<size_t>(vg)].a) += re.f0_a;
      }
    }
    rhs.segment(n, r) = MR.transpose() * (q_given - q);
    auto pin = [&](int body, double to) {
      A.row(body).setZero();
      A(body, body) = 1.0;
      rhs(body) = to;
    };
    for (size_t k = 0; k < m.contacts.size(); ++k) {  // a stop pins its body at the stop, a brake where it is
      if (!held[k]) continue;
      const FrictionContact& c = m.contacts[k];
      pin(c.a, c.stop ? c.stop_position - q(c.a) : 0.0);
    }
    Eigen::FullPivLU<Eigen::MatrixXd> lu(A);
    if (!lu.isInvertible())
      throw InputError(Location{m.source, 0, 0}, "simulation: 'initial: equilibrium': the equilibrium equations are "
                                                  "singular (a loop of links with inconsistent ratios?)");
    const Eigen::VectorXd dq = lu.solve(rhs).head(n);
    q += dq;

    // Modes after the step: a flank pulled off opens, a flank passed closes; a stop pulled off lets
    // go, a stop passed holds.
    bool changed = false;
    const State at = evaluate(q);
    for (size_t k = 0; k < nl; ++k) {
      const LinkLaw& law = laws[k];
      if (!law.gap) continue;
      const double delta = law.weighted(q.data());
      const double F = law.load(delta, 0.0, mode[k], law.drum(q.data())), tol = 1e-12 * law.c * q_scale;
      GapMode next = mode[k];
      if (mode[k] == GapMode::closed_pos && F < -tol) next = GapMode::open;
      if (mode[k] == GapMode::closed_neg && F > tol) next = GapMode::open;
      if (mode[k] == GapMode::open)
        next = delta > law.hi + 1e-12 * q_scale ? GapMode::closed_pos
               : delta < law.lo - 1e-12 * q_scale ? GapMode::closed_neg
                                                   : GapMode::open;
      changed = changed || next != mode[k];
      mode[k] = next;
    }
    for (int k : stops) {
      const ContactLaw law = ContactLaw::of(m.contacts[static_cast<size_t>(k)]);
      const bool was = held[static_cast<size_t>(k)];
      // The stop carries λ = g (the load F acts on its body with −λ, model/model.hpp).
      const bool now = was ? law.holds(at.g(law.a), 0.0, false) : law.stop_distance(q(law.a)) < -1e-12 * q_scale;
      held[static_cast<size_t>(k)] = now ? 1 : 0;
      changed = changed || now != was;
    }
    settled = !changed && dq.lpNorm<Eigen::Infinity>() <= 1e-12 * q_scale;
  }
  if (!settled)
    throw InputError(Location{m.source, 0, 0}, fmt::format("simulation: 'initial: equilibrium': the modes of the ropes, "
                                                           "gaps and stops did not settle in {} steps", kMaxIterations));

  // Every free group balanced: the net load along its rigid motion vanishes; every held element holds
  // its reaction λ: Hᵀ λ = g − M R a'' over the rows H of everything held (a pinned body's unit row,
  // a coupling's row; the element puts −w_j λ on body j), least-norm where two share one body.
  s = evaluate(q);
  Diagnostics diag;
  ConstraintRows H;
  std::vector<int> brake_row(m.contacts.size(), -1);
  for (size_t k = 0; k < m.contacts.size(); ++k)
    if (held[k]) brake_row[k] = static_cast<int>(H.size()), H.push_back({{m.contacts[k].a, 1.0}});
  const auto first_gear = static_cast<Eigen::Index>(H.size());
  std::vector<double> f0(static_cast<size_t>(n), 0.0);  // the gears on the verge: H μ + f0, as a held row −H
  for (size_t k = 0; k < geared.G.size(); ++k) {
    if (verge_of_row[k] < 0) {
      H.push_back(geared.G[k]);
      continue;
    }
    const LossyGearLaw::Reaction re = reaction_of(verge_of_row[k]);
    std::vector<std::pair<int, double>> row;
    for (const auto& [j, w] : re.H) row.emplace_back(j, -w);
    H.push_back(row);
    f0[static_cast<size_t>(gears[static_cast<size_t>(verge_of_row[k])].a)] += re.f0_a;
  }
  const auto first_coupling = static_cast<Eigen::Index>(H.size());
  H.insert(H.end(), coupled.G.begin(), coupled.G.end());
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(H.size()));
  if (!H.empty()) {
    Eigen::MatrixXd Ht = Eigen::MatrixXd::Zero(n, static_cast<Eigen::Index>(H.size()));
    for (size_t k = 0; k < H.size(); ++k)
      for (const auto& [j, w] : H[k]) Ht(j, static_cast<Eigen::Index>(k)) += w;
    Eigen::VectorXd rest = s.g;
    for (int j = 0; j < n; ++j) rest(j) += f0[static_cast<size_t>(j)];
    if (R.cols() > 0) {
      const Eigen::MatrixXd MR = M.asDiagonal() * R;
      rest -= MR * (R.transpose() * MR).ldlt().solve(R.transpose() * s.g);
    }
    lambda = Ht.completeOrthogonalDecomposition().solve(rest);
  }
  const std::string pre = "simulation: 'initial: equilibrium': no static equilibrium:";
  auto unit_of = [&](int body) { return load_unit(m.bodies[static_cast<size_t>(body)].kind); };
  for (int k : brakes) {
    const FrictionContact& c = m.contacts[static_cast<size_t>(k)];
    const double l = lambda(brake_row[static_cast<size_t>(k)]);
    if (!ContactLaw::of(c).holds(l, 0.0, false))
      diag.error(m.where(c.name), fmt::format("{} brake '{}' would have to hold {:.6g} {}, more than its static limit "
                                              "{:.6g} {} at t = 0", pre, c.name, std::abs(l), unit_of(c.a),
                                              c.scale(0.0) * c.static_limit, unit_of(c.a)));
  }
  for (size_t k = 0; k < couplings.size(); ++k) {
    const FrictionContact& c = m.contacts[static_cast<size_t>(couplings[k])];
    const double l = lambda(first_coupling + static_cast<Eigen::Index>(k));
    if (!ContactLaw::of(c).holds(l, 0.0, false))
      diag.error(m.where(c.name), fmt::format("{} {} '{}' would have to hold {:.6g} {}, more than its static limit "
                                              "{:.6g} {} at t = 0", pre, c.clutch ? "clutch" : "brake", c.name,
                                              std::abs(l), unit_of(c.a), c.scale(0.0) * c.static_limit, unit_of(c.a)));
  }
  for (size_t g = 0; g < gears.size(); ++g) {
    // Stuck, the gear holds X = F_a and Y = −F_b/i (elements/lossy_gear.hpp): F_a, F_b are what its
    // two rows hold on its bodies, Σ_k w_kj λ_k. On the verge its relation holds by construction;
    // its group must be held (by a brake or a stop: no rigid motion of its bodies is left).
    const LossyGearLaw& law = gears[g];
    if (verge[g] != GearMode::stuck) {
      bool held_group = true;
      for (Eigen::Index k = 0; k < R.cols(); ++k) held_group = held_group && R(law.a, k) == 0.0 && R(law.b, k) == 0.0;
      if (!held_group)
        diag.error(m.where(law.spec->name), fmt::format("{} lossy gear '{}' cannot hold at rest and nothing holds its "
                                                        "group (a brake applied at t = 0); start with 'initial: given'",
                                                        pre, law.spec->name));
      continue;
    }
    double Fa = 0.0, Fb = 0.0;
    const Eigen::Index g0 = first_gear + gear_row[g];
    for (Eigen::Index k = g0; k < g0 + 2; ++k)
      for (const auto& [j, w] : H[static_cast<size_t>(k)]) (j == law.a ? Fa : Fb) += w * lambda(k);
    const double Ia = m.bodies[static_cast<size_t>(law.a)].inertia, Ib = m.bodies[static_cast<size_t>(law.b)].inertia;
    const GearMode md = law.decide(Fa, Fb, Ia, Ib, 0.0, law.allowance(Fa, Fb));
    if (md == GearMode::stuck) continue;
    if (starts) (*starts)[g] = md;
    const int dir = direction(md);
    const std::string& a = m.bodies[static_cast<size_t>(law.a)].name;
    const std::string& b = m.bodies[static_cast<size_t>(law.b)].name;
    diag.error(m.where(law.spec->name),
               fmt::format("{} lossy gear '{}' cannot hold at rest: the loads on its sides at t = 0 ({:.6g} {} on '{}', "
                           "{:.6g} {} on '{}') lie beyond its locking range by {:.6g} {} (in the coordinate of '{}'; "
                           "it would start {}); start with 'initial: given'",
                           pre, law.spec->name, Fa, unit_of(law.a), a, Fb, unit_of(law.b), b,
                           -law.start_margin(dir, Fa, Fb), unit_of(law.a), a, dir > 0 ? "forward" : "backward"));
  }
  for (Eigen::Index k = 0; k < R.cols(); ++k) {
    const double net = R.col(k).dot(s.g), scale = R.col(k).cwiseAbs().dot(s.scale);
    if (std::abs(net) <= 1e-9 * scale) continue;
    std::string names;
    int first = -1;
    for (int i = 0; i < n; ++i)
      if (R(i, k) != 0.0) {
        names += (names.empty() ? "'" : ", '") + m.bodies[static_cast<size_t>(i)].name + "'";
        if (first < 0) first = i;
      }
    const Body& b = m.bodies[static_cast<size_t>(first)];
    diag.error(m.where(b.name),
               fmt::format("simulation: 'initial: equilibrium': no static equilibrium: the free group of bodies {} (no "
                           "spring to the ground) has the net load {:.6g} {} at t = 0 along the motion of '{}'; balance "
                           "its loads or start with 'initial: given'", names, net, load_unit(b.kind), b.name));
  }
  diag.throw_if_any();

  // Velocities: the rigid motions keep their momentum RᵀM v; nothing elastic moves.
  Eigen::VectorXd v = Eigen::VectorXd::Zero(n);
  if (R.cols() > 0) {
    const Eigen::MatrixXd MR = M.asDiagonal() * R;
    v = R * (R.transpose() * MR).ldlt().solve(MR.transpose() * v_given);
  }
  const double v_scale = v_given.lpNorm<Eigen::Infinity>();
  for (int i = 0; i < n; ++i) {
    if (std::abs(v(i) - v_given(i)) <= 1e-9 * v_scale) continue;
    const Body& b = m.bodies[static_cast<size_t>(i)];
    diag.error(m.where(b.name),
               fmt::format("simulation: 'initial: equilibrium': body '{}' starts at {:.6g} {}, which contradicts the "
                           "ratios of its stiff links (the rigid motion of its group gives {:.6g} {}; a body held by "
                           "the ground or a stop gives 0); give velocities that follow the ratios", b.name, v_given(i),
                           velocity_unit(b.kind), v(i), velocity_unit(b.kind)));
  }
  diag.throw_if_any();
  out.q0.assign(q.data(), q.data() + n);
  out.v0.assign(v.data(), v.data() + n);
  return out;
}

}  // namespace

EquilibriumStart static_equilibrium(const Model& m) {
  check_supported(m);
  // First every lossy gear stuck. A gear that cannot hold its sides alone starts moving unless a brake
  // holds its group: then the equilibrium has it at rest on the verge of the motion it would start,
  // its torques in that rolling mode's relation at v = 0 (the load drives it back through its
  // efficiency η_mf2, docs/model-files.md "initial: equilibrium"), and the brake holds the rest.
  std::vector<GearMode> verge(m.lossy_gears.size(), GearMode::stuck), starts = verge;
  try {
    return solve_equilibrium(m, verge, &starts);
  } catch (const InputError&) {
    if (starts == verge) throw;
    try {
      return solve_equilibrium(m, starts, nullptr);
    } catch (const InputError& e) {
      // Nothing holds the gear's group: the first answer (the gear cannot hold) says why.
      if (std::string(e.what()).find("nothing holds its group") == std::string::npos) throw;
    }
    return solve_equilibrium(m, verge, nullptr);
  }
}

Model with_equilibrium_start(const Model& m) {
  const EquilibriumStart e = static_equilibrium(m);
  Model out = m;
  for (size_t i = 0; i < out.bodies.size(); ++i) {
    out.bodies[i].q0 = e.q0[i];
    out.bodies[i].v0 = e.v0[i];
  }
  out.simulation.initial = InitialState::given;
  return out;
}

}  // namespace machdyn
