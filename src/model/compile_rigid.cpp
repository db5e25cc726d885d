// Ideal gears: rigid connections resolved at compile time (model/compile_rigid.hpp).
#include "machdyn/model/describe.hpp"
//
// A group G of bodies tied by ideal gears moves as one: q_s = ρ_s q_M for every s in G, with the
// master M (ρ_M = 1) the group's first body in the file. ρ follows each gear q_a = i q_b along a
// spanning tree (ρ_a = i ρ_b); a gear that closes a loop must agree with the tree (|ρ_a − i ρ_b|
// within 1e-12 of |ρ_a|), otherwise the group could not move at all and that gear is an error.
// Virtual work over the group, δW = Σ_s F_s δq_s = (Σ_s ρ_s F_s) δq_M, and the kinetic energy
// T = ½ Σ_s I_s v_s² = ½ (Σ_s ρ_s² I_s) v_M², give the master's equation of motion
//   (I_M + Σ_s ρ_s² I_s) a_M = Σ_s ρ_s F_s(t, ρ_s q_M, ρ_s v_M)
// (Lagrange's equation of the constrained system): the reduced inertia, and each slave's load
// reduced by its ratio and evaluated at the slave's own position and speed (Load::ratio).
// A group with a prescribed member P (elements/prescribed_motion.hpp) is prescribed: P is its master
// (ρ re-based, ρ_u / ρ_P), so the merged body follows P's signal and q_s = ρ_s q_P; its motion
// source's force is the one at P's coordinate, R = (I_P + Σ ρ_s² I_s) a_P − Σ ρ_s F_s. Two
// prescribed members would over-determine the group: a located error (even when their signals agree).
// A link whose first end a is a slave, δ = q_a/i − q_b = ρ_a q_M/i − q_b, is the same link on M
// with the ratio i/ρ_a: its law and load are unchanged.
#include "model/compile_rigid.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <fmt/format.h>

#include "machdyn/model/element.hpp"

namespace machdyn::detail {

void read_ideal_gear(const std::string& name, const SpecNode& spec, const Model& m, std::vector<IdealGear>& out,
                     Diagnostics& diag) {
  FieldReader f(spec, fmt::format("ideal gear '{}'", name), diag);
  f.word("type", {"ideal-gear"});
  f.text("housing", "ground");  // a body as housing: a joint (model/compile_joint.hpp)
  IdealGear g;
  g.name = name;
  g.where = Location(spec.key_loc);
  g.ratio_where = g.where;
  const SpecNode* between = f.node("between");
  bool ok = false;
  if (!between) {
    diag.error(spec.loc, fmt::format("ideal gear '{}': missing field 'between' (two body names, e.g. [motor, drum])", name));
  } else if (!between->is_seq() || between->items.size() != 2 || !between->items[0].is_scalar() ||
             !between->items[1].is_scalar()) {
    diag.error(between->loc, fmt::format("ideal gear '{}': 'between' expected two body names, e.g. [motor, drum]", name));
  } else {
    ok = true;
    int idx[2];
    for (int k = 0; k < 2; ++k) {
      const SpecNode& item = between->items[static_cast<size_t>(k)];
      idx[k] = m.body_index(item.scalar);
      if (item.scalar == "ground") {
        diag.error(item.loc, fmt::format("ideal gear '{}': an ideal gear to the ground would hold the other body "
                                         "fixed; to hold a body use a stop or a brake, or remove the body", name));
        ok = false;
      } else if (idx[k] < 0) {
        diag.error(item.loc, fmt::format("ideal gear '{}': unknown body '{}' (an ideal gear joins two bodies by "
                                         "name; a machine's output point is not supported)", name, item.scalar));
        ok = false;
      } else if (m.bodies[static_cast<size_t>(idx[k])].machine) {
        diag.error(item.loc, fmt::format("ideal gear '{}': '{}' has a variable inertia; an ideal gear to a machine "
                                         "body is not supported yet (use a stiff link)", name, item.scalar));
        ok = false;
      }
    }
    if (ok && idx[0] == idx[1]) {
      diag.error(between->loc, fmt::format("ideal gear '{}': joins '{}' to itself", name, between->items[0].scalar));
      ok = false;
    }
    g.a = idx[0], g.b = idx[1];
  }
  auto pdim = [&](int i) {
    return ok && m.bodies[static_cast<size_t>(i)].kind == BodyKind::translational ? dim::length : dim::none;
  };
  std::optional<double> r;
  if (ok) r = f.quantity("ratio", pdim(g.a) / pdim(g.b), 1.0);
  else f.node("ratio");
  if (const SpecNode* rn = spec.is_map() ? spec.find("ratio") : nullptr) g.ratio_where = Location(rn->loc);
  if (r && (*r == 0.0 || !std::isfinite(*r))) {
    f.error_at("ratio", "field 'ratio' must be finite and not zero (q_a = ratio · q_b)");
    ok = false;
  }
  f.finish();
  if (!ok || !r) return;
  g.ratio = *r;
  out.push_back(g);
}

const SpecNode* body_field(const SpecNode* bodies, const std::string& name, const char* key) {
  const SpecNode* b = bodies && bodies->is_map() ? bodies->find(name) : nullptr;
  return b && b->is_map() ? b->find(key) : nullptr;
}

bool initial_values_agree(double x, double y) {
  return std::abs(x - y) <= 1e-9 * std::max(std::abs(x), std::abs(y)) + 1e-12;
}

namespace {

/// ρ² (and 1/ρ², as a link on a slave is reduced by i/ρ) must be a normal double, with room for the
/// inertias, stiffnesses and loads it multiplies: |ρ| in [1e-100, 1e100]. A chain of gears beyond
/// that is a mistake in the ratios (a machine's overall ratio is far inside it), and its reduced
/// inertia would overflow to inf or vanish into a subnormal (NaN frequencies, a crash downstream).
constexpr double kMinRatioSquare = 1e-200;
bool ratio_product_representable(double rho) {
  const double r2 = rho * rho;
  return std::isfinite(r2) && r2 >= kMinRatioSquare && r2 <= 1.0 / kMinRatioSquare;
}

const char* kind_word(BodyKind k) { return k == BodyKind::rotational ? "rotational" : "translational"; }

/// Fills m.merged_gears (model.hpp: MergedGear) from the groups (master, ρ per body in the file's
/// indices; idx: the indices after the merge), before loads and links are re-attached: for each gear
/// the side S without the master, found by a walk over the other gears from the gear's end on S.
void merged_gear_outputs(Model& m, const std::vector<IdealGear>& gears, const std::vector<int>& master,
                         const std::vector<double>& rho, const std::vector<int>& idx) {
  const size_t n = m.bodies.size();
  std::vector<std::vector<size_t>> adj(n);
  for (size_t k = 0; k < gears.size(); ++k) {
    adj[static_cast<size_t>(gears[k].a)].push_back(k);
    adj[static_cast<size_t>(gears[k].b)].push_back(k);
  }
  // The bodies reachable from `from` without gear `skip`.
  auto side = [&](size_t from, size_t skip) {
    std::vector<char> in(n, 0);
    std::vector<size_t> todo{from};
    in[from] = 1;
    while (!todo.empty()) {
      const size_t u = todo.back();
      todo.pop_back();
      for (size_t k : adj[u]) {
        if (k == skip) continue;
        const auto w = static_cast<size_t>(gears[k].a == static_cast<int>(u) ? gears[k].b : gears[k].a);
        if (!in[w]) in[w] = 1, todo.push_back(w);
      }
    }
    return in;
  };
  for (size_t k = 0; k < gears.size(); ++k) {
    const IdealGear& g = gears[k];
    const auto a = static_cast<size_t>(g.a), b = static_cast<size_t>(g.b);
    const auto M = static_cast<size_t>(master[a]);
    std::vector<char> S = side(b, k);
    if (S[a]) continue;  // a loop of gears: no side to sum
    MergedGear out{g.name, idx[M], !S[M], m.bodies[b].kind, g.ratio, rho[b], 0.0, {}, {}, {}};
    if (S[M]) {
      S = side(a, k);
      out.rho = rho[a];
    }
    bool plain = true;
    for (size_t s = 0; s < n; ++s) {
      if (!S[s]) continue;
      plain = plain && !m.bodies[s].machine;
      out.inertia += rho[s] * rho[s] * m.bodies[s].inertia;
      out.side.push_back(m.bodies[s].name);
    }
    if (!plain) continue;
    for (size_t l = 0; l < m.loads.size(); ++l)
      if (S[static_cast<size_t>(m.loads[l].body)]) out.loads.push_back(static_cast<int>(l));
    for (size_t l = 0; l < m.links.size(); ++l)
      if (m.links[l].a >= 0 && S[static_cast<size_t>(m.links[l].a)]) out.links.push_back(static_cast<int>(l));
    m.merged_gears.push_back(std::move(out));
  }
}
}  // namespace

void resolve_rigid(Model& m, const std::vector<IdealGear>& gears, const SpecNode* bodies,
                   const std::unordered_set<std::string>& massless_ok, Diagnostics& diag) {
  const size_t n = m.bodies.size();
  std::vector<int> master(n, -1);
  std::vector<double> rho(n, 1.0);
  if (!gears.empty()) {
    std::vector<std::vector<size_t>> adj(n);
    for (size_t k = 0; k < gears.size(); ++k) {
      adj[static_cast<size_t>(gears[k].a)].push_back(k);
      adj[static_cast<size_t>(gears[k].b)].push_back(k);
    }
    std::vector<char> gear_used(gears.size(), 0);
    for (size_t s = 0; s < n; ++s) {  // the group's first body in the file is its master
      if (master[s] >= 0 || adj[s].empty()) continue;
      master[s] = static_cast<int>(s);
      bool overflow_told = false;  // one error per group
      std::vector<size_t> todo{s};
      while (!todo.empty()) {
        const size_t u = todo.back();
        todo.pop_back();
        for (size_t k : adj[u]) {
          if (gear_used[k]) continue;
          gear_used[k] = 1;
          const IdealGear& g = gears[k];
          const auto a = static_cast<size_t>(g.a), b = static_cast<size_t>(g.b);
          const size_t w = a == u ? b : a;
          const double want = a == u ? rho[a] / g.ratio : g.ratio * rho[b];  // q_a = i q_b
          if (master[w] < 0) {
            master[w] = static_cast<int>(s);
            rho[w] = want;
            todo.push_back(w);
            if (!ratio_product_representable(want) && !overflow_told) {
              overflow_told = true;
              diag.error(g.ratio_where,
                         fmt::format("ideal gear '{}': the product of the ideal gears' ratios from '{}' to '{}' is "
                                     "{:.3g}; its square (which reduces inertias, loads and stiffnesses to '{}') "
                                     "must lie between {:.0e} and {:.0e} to be computed in double precision: check "
                                     "the ratios' units and direction (q_a = ratio · q_b)", g.name,
                                     m.bodies[s].name, m.bodies[w].name, want, m.bodies[s].name, kMinRatioSquare,
                                     1.0 / kMinRatioSquare));
            }
          } else if (std::abs(rho[w] - want) > 1e-12 * std::abs(rho[w])) {  // a loop
            diag.error(g.ratio_where,
                       fmt::format("ideal gear '{}': closes a loop of ideal gears whose ratios disagree: the other "
                                   "gears give q_{}/q_{} = {:.12g}, this one {:.12g}; a rigid loop must have a "
                                   "consistent product of ratios", g.name, m.bodies[a].name, m.bodies[b].name,
                                   rho[a] / rho[b], g.ratio));
          }
        }
      }
      // A prescribed member is the group's master (its signal is the group's motion).
      int given = -1;
      for (size_t u = s; u < n; ++u) {
        if (master[u] != static_cast<int>(s) || m.bodies[u].motion == MotionKind::free) continue;
        if (given < 0) {
          given = static_cast<int>(u);
          continue;
        }
        diag.error(m.where(m.bodies[u].name),
                   fmt::format("body '{}' has a prescribed motion ('motion') and ideal gears tie it to '{}', which has "
                               "one too; a rigid group can follow one motion only: prescribe one of them", m.bodies[u].name,
                               m.bodies[static_cast<size_t>(given)].name));
      }
      if (given > static_cast<int>(s)) {
        const double r = rho[static_cast<size_t>(given)];
        for (size_t u = s; u < n; ++u) {
          if (master[u] != static_cast<int>(s)) continue;
          master[u] = given, rho[u] /= r;
          if (!ratio_product_representable(rho[u]) && !overflow_told) {
            overflow_told = true;
            diag.error(m.where(m.bodies[u].name),
                       fmt::format("body '{}': the product of the ideal gears' ratios from the prescribed body '{}' "
                                   "is {:.3g}; its square must lie between {:.0e} and {:.0e}", m.bodies[u].name,
                                   m.bodies[static_cast<size_t>(given)].name, rho[u], kMinRatioSquare,
                                   1.0 / kMinRatioSquare));
          }
        }
      }
    }
  }
  // Initial positions and velocities along the gears: the master's, or a slave's when only it gives one.
  for (size_t s = 0; s < n; ++s) {
    if (master[s] != static_cast<int>(s)) continue;
    for (const char* key : {"position", "velocity"}) {
      const bool pos = key[0] == 'p';
      // The group's value in the master's coordinate: a prescribed master's own (its speed or position
      // signal sets it, read_motion), else from the first body that gives one.
      std::optional<double> base;
      size_t from = s;
      const MotionKind mk = m.bodies[s].motion;
      if (mk == MotionKind::position || (mk == MotionKind::speed && !pos)) base = pos ? m.bodies[s].q0 : m.bodies[s].v0;
      for (size_t u = 0; u < n && !base; ++u) {
        if (master[u] != static_cast<int>(s) || !body_field(bodies, m.bodies[u].name, key)) continue;
        base = (pos ? m.bodies[u].q0 : m.bodies[u].v0) / rho[u];
        from = u;
        break;
      }
      const double x0 = base.value_or(0.0);
      for (size_t u = 0; u < n; ++u) {
        if (master[u] != static_cast<int>(s)) continue;
        double& x = pos ? m.bodies[u].q0 : m.bodies[u].v0;
        const SpecNode* at = body_field(bodies, m.bodies[u].name, key);
        if (at && !initial_values_agree(x, rho[u] * x0))
          diag.error(at->loc, fmt::format("body '{}': {} {:.12g} contradicts the ideal gears that tie it to '{}': "
                                          "{} {:.12g} there gives {:.12g} here (q = {:.12g} q_{}); give it on one body "
                                          "of the group only", m.bodies[u].name, key, x, m.bodies[from].name, key,
                                          pos ? m.bodies[from].q0 : m.bodies[from].v0, rho[u] * x0,
                                          rho[u] / rho[from], m.bodies[from].name));
        x = rho[u] * x0;
      }
    }
  }
  // Reduced inertia I_M + Σ ρ² I_s, and massless bodies.
  for (size_t s = 0; s < n; ++s)
    if (master[s] >= 0 && master[s] != static_cast<int>(s))
      m.bodies[static_cast<size_t>(master[s])].inertia += rho[s] * rho[s] * m.bodies[s].inertia;
  for (size_t s = 0; s < n; ++s)
    if (master[s] == static_cast<int>(s) && !std::isfinite(m.bodies[s].inertia) && diag.empty())
      diag.error(m.where(m.bodies[s].name),
                 fmt::format("body '{}': the inertia of its group of ideal gears, reduced to it (I + Σ ρ² I_s), "
                             "overflows; check the ratios and inertias of the group", m.bodies[s].name));
  for (size_t s = 0; s < n; ++s) {
    const Body& b = m.bodies[s];
    if (b.machine || b.inertia > 0.0 || (master[s] >= 0 && master[s] != static_cast<int>(s))) continue;
    if (master[s] < 0 && massless_ok.count(b.name)) continue;  // a joint eliminates it
    const SpecNode* at = body_field(bodies, b.name, b.kind == BodyKind::rotational ? "inertia" : "mass");
    diag.error(at ? Location(at->loc) : m.where(b.name),
               master[s] < 0
                   ? fmt::format("body '{}': zero {}; a massless body has no equation of motion of its own (its "
                                 "acceleration is undefined) unless an ideal gear ties it to a body with inertia; "
                                 "give it an inertia or connect it with 'type: ideal-gear'", b.name,
                                 b.kind == BodyKind::rotational ? "inertia" : "mass")
                   : fmt::format("body '{}' and every body tied to it by ideal gears have zero inertia together; "
                                 "the group's acceleration would be undefined: give one of them an inertia", b.name));
  }
  if (gears.empty()) return;
  // New indices: slaves are removed.
  std::vector<int> idx(n, -1);
  int next = 0;
  for (size_t s = 0; s < n; ++s)
    if (master[s] < 0 || master[s] == static_cast<int>(s)) idx[s] = next++;
  auto is_slave = [&](int i) { return i >= 0 && master[static_cast<size_t>(i)] >= 0 && master[static_cast<size_t>(i)] != i; };
  auto to = [&](int i) { return i < 0 ? i : is_slave(i) ? idx[static_cast<size_t>(master[static_cast<size_t>(i)])] : idx[static_cast<size_t>(i)]; };
  auto slave_text = [&](int i) {
    const auto u = static_cast<size_t>(i);
    return fmt::format("'{}' is tied by ideal gears to '{}' (q_{} = {:.12g} q_{})", m.bodies[u].name,
                       m.bodies[static_cast<size_t>(master[u])].name, m.bodies[u].name, rho[u],
                       m.bodies[static_cast<size_t>(master[u])].name);
  };
  merged_gear_outputs(m, gears, master, rho, idx);
  for (Load& ld : m.loads) {
    if (!is_slave(ld.body)) {
      ld.body = to(ld.body);
      continue;
    }
    const double r = rho[static_cast<size_t>(ld.body)];
    if (ld.kind == LoadKind::constant) {  // ρ M, once here
      ld.value *= r;
      ld.signal = Signal::constant(ld.value);
    } else {
      ld.ratio = r;
    }
    ld.body = to(ld.body);
  }
  for (Link& l : m.links) {
    if (is_slave(l.b)) {
      diag.error(m.where(l.name), fmt::format("link '{}': its second end {}; a link whose second end is a slaved "
                                              "body is not supported yet: write it with that body first (between: "
                                              "[{}, OTHER], ratio 1/i, stiffness in OTHER's coordinate) or attach it "
                                              "to '{}'", l.name, slave_text(l.b), m.bodies[static_cast<size_t>(l.b)].name,
                                              m.bodies[static_cast<size_t>(master[static_cast<size_t>(l.b)])].name));
      continue;
    }
    if (is_slave(l.a)) l.ratio /= rho[static_cast<size_t>(l.a)];  // δ = ρ q_M / i − q_b
    if (l.third >= 0 && is_slave(l.third)) l.third_weight *= rho[static_cast<size_t>(l.third)];  // w_e q_e = w_e ρ q_M
    l.a = to(l.a), l.b = to(l.b), l.third = to(l.third);
    if (l.a == l.b && l.a >= 0)
      diag.error(m.where(l.name), fmt::format("link '{}': both ends move rigidly together through ideal gears, so "
                                              "its deflection never changes; remove it or one of the gears", l.name));
  }
  for (FrictionContact& c : m.contacts) {
    for (int e : {c.a, c.b})
      if (is_slave(e))
        diag.error(m.where(c.name), fmt::format("'{}': {}; contacts, brakes, clutches, freewheels and stops on a "
                                                "slaved body are not supported yet: attach it to '{}'", c.name,
                                                slave_text(e),
                                                m.bodies[static_cast<size_t>(master[static_cast<size_t>(e)])].name));
    c.a = to(c.a), c.b = to(c.b);
  }
  // A drive on a slave sees ω_s = ρ ω_M and puts ρ M on the master (model.hpp: Drive::ratio), as a load
  // does; its columns keep the slave's units only while both have one kind.
  for (Drive& d : m.drives) {
    if (is_slave(d.body)) {
      const auto M = static_cast<size_t>(master[static_cast<size_t>(d.body)]);
      if (m.bodies[static_cast<size_t>(d.body)].kind != m.bodies[M].kind)
        diag.error(m.where(d.name), fmt::format("drive '{}': {}, a {} body on a {} one; a drive on a slaved body "
                                                "of another kind than its master is not supported yet: put it on "
                                                "'{}'", d.name, slave_text(d.body),
                                                kind_word(m.bodies[static_cast<size_t>(d.body)].kind),
                                                kind_word(m.bodies[M].kind), m.bodies[M].name));
      d.ratio *= rho[static_cast<size_t>(d.body)];
    }
    d.body = to(d.body);
    for (int& o : d.others) {  // ports ≥ 1 are plain bodies (model.hpp: Drive::others)
      if (is_slave(o))
        diag.error(m.where(d.name), fmt::format("'{}': {}; a {} on a slaved body is not supported yet: attach it to '{}'",
                                                d.name, slave_text(o), d.law->type(),
                                                m.bodies[static_cast<size_t>(master[static_cast<size_t>(o)])].name));
      o = to(o);
    }
  }
  if (m.crane.load >= 0) {
    if (is_slave(m.crane.load))
      diag.error(m.where(m.bodies[static_cast<size_t>(m.crane.load)].name),
                 fmt::format("crane: the hook load {}; it must be a body of its own", slave_text(m.crane.load)));
    m.crane.load = to(m.crane.load);
  }
  std::vector<Body> kept;
  for (size_t s = 0; s < n; ++s) {
    if (is_slave(static_cast<int>(s))) {
      m.slaves.push_back({m.bodies[s].name, m.bodies[s].kind, idx[static_cast<size_t>(master[s])], rho[s],
                          m.bodies[s].inertia});
    } else {
      kept.push_back(std::move(m.bodies[s]));
    }
  }
  m.bodies = std::move(kept);
  m.index_bodies();
  for (const IdealGear& g : gears) m.ideal_gears.push_back(g.name);
}


// The ideal gears compile merged: the ratio where compile kept it (MergedGear), the group they form.
std::vector<ElementText> describe_ideal_gears(const Model& m) {
  std::vector<ElementText> out;
  for (const std::string& name : m.ideal_gears) {
    const auto g = std::find_if(m.merged_gears.begin(), m.merged_gears.end(), [&](const MergedGear& x) { return x.name == name; });
    ElementText e{name, "ideal gear", ""};
    if (g != m.merged_gears.end())
      e.definition = fmt::format("ratio i = {} (q_A = i q_B), no loss; merged into the rigid group of '{}'",
                                 describe_number(g->ratio), m.bodies[static_cast<size_t>(g->body)].name);
    else
      e.definition = "no loss; its bodies move as one rigid group (the ratio is in the model file)";
    out.push_back(std::move(e));
  }
  return out;
}

}  // namespace machdyn::detail
