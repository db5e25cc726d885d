// Lossy gears: read with the links, put on the merged bodies after the ideal gears (model/compile_lossy.hpp).
#include "machdyn/model/describe.hpp"
//
// An end slaved by ideal gears moves as q_A = ρ_A q_a (RigidSlave), so the file's q_A = i q_B becomes
// q_a = (i ρ_B/ρ_A) q_b on the bodies that remain; the loss data stay in A's coordinate and the law
// converts them by |ρ_A| (elements/lossy_gear.hpp).
#include "model/compile_lossy.hpp"

#include "model/body_dims.hpp"
#include "model/compile_rigid.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <fmt/format.h>

#include "machdyn/common/units.hpp"

namespace machdyn::detail {
namespace {

/// The checks of one set of loss data (a constant or a table row); `at` locates the error.
void check_losses(const std::string& name, double eta1, double eta2, double bf1, double bf2, const SpecLoc& at,
                  Diagnostics& diag) {
  if (!(eta1 > 0.0 && eta1 <= 1.0))
    diag.error(at, fmt::format("lossy gear '{}': efficiency {:.12g} outside (0, 1] (η_mf1, power flowing from the "
                               "first body to the second)", name, eta1));
  if (!(eta2 >= 0.0 && eta2 <= 1.0))
    diag.error(at, fmt::format("lossy gear '{}': efficiency_reverse {:.12g} outside [0, 1] (η_mf2, power flowing "
                               "from the second body to the first; 0: self-locking)", name, eta2));
  if (!(bf1 >= 0.0) || !(bf2 >= 0.0) || !std::isfinite(bf1) || !std::isfinite(bf2))
    diag.error(at, fmt::format("lossy gear '{}': bearing friction must be finite and >= 0", name));
  if (eta1 == 1.0 && eta2 == 1.0 && bf1 != bf2)
    diag.error(at, fmt::format("lossy gear '{}': with both efficiencies 1 the bearing friction cannot depend on the "
                               "direction of the power flow (τ_bf1 = τ_bf,a + τ_bf,b = τ_bf2); give one value", name));
}

/// `loss_table: [[|v_A|, η_mf1, η_mf2, τ_bf1, τ_bf2], ...]` (MSL's lossTable), speeds increasing from 0.
void read_table(const SpecNode& n, const std::string& name, BodyKind k, LossyGear& g, Diagnostics& diag) {
  if (!n.is_seq() || n.items.empty()) {
    diag.error(n.loc, fmt::format("lossy gear '{}': 'loss_table' expected rows [speed, efficiency, "
                                  "efficiency_reverse, bearing_friction, bearing_friction_reverse]", name));
    return;
  }
  const Dim dims[5] = {velocity_dim(k), dim::none, dim::none, load_dim(k), load_dim(k)};
  for (const auto& row : n.items) {
    if (!row.is_seq() || row.items.size() != 5) {
      diag.error(row.loc, fmt::format("lossy gear '{}': 'loss_table' row expected 5 entries [speed, efficiency, "
                                      "efficiency_reverse, bearing_friction, bearing_friction_reverse]", name));
      continue;
    }
    double v[5];
    bool ok = true;
    for (size_t j = 0; j < 5; ++j) {
      std::string err;
      const auto x = row.items[j].is_scalar() ? parse_as(row.items[j].scalar, dims[j], &err) : std::nullopt;
      if (!x) {
        diag.error(row.items[j].loc, fmt::format("lossy gear '{}': 'loss_table': {}", name,
                                                 err.empty() ? "expected a number" : err));
        ok = false;
      }
      v[j] = x.value_or(0.0);
    }
    if (!ok) continue;
    if ((g.speeds.empty() && v[0] != 0.0) || (!g.speeds.empty() && v[0] <= g.speeds.back())) {
      diag.error(row.items[0].loc, fmt::format("lossy gear '{}': 'loss_table': the speeds must increase from 0", name));
      continue;
    }
    check_losses(name, v[1], v[2], v[3], v[4], row.loc, diag);
    g.speeds.push_back(v[0]);
    g.eta_forward.push_back(v[1]);
    g.eta_reverse.push_back(v[2]);
    g.bearing_forward.push_back(v[3]);
    g.bearing_reverse.push_back(v[4]);
  }
}

}  // namespace

void read_lossy_gear(const std::string& name, const SpecNode& spec, const Model& m, std::vector<LossyGearSpec>& out,
                     Diagnostics& diag) {
  FieldReader f(spec, fmt::format("lossy gear '{}'", name), diag);
  f.word("type", {"lossy-gear"});
  LossyGearSpec s;
  s.gear.name = name;
  s.where = Location(spec.key_loc);
  const SpecNode* between = f.node("between");
  bool ok = false;
  int idx[2] = {0, 0};
  if (!between) {
    diag.error(spec.loc, fmt::format("lossy gear '{}': missing field 'between' (two body names, e.g. [motor, drum])", name));
  } else if (!between->is_seq() || between->items.size() != 2 || !between->items[0].is_scalar() ||
             !between->items[1].is_scalar()) {
    diag.error(between->loc, fmt::format("lossy gear '{}': 'between' expected two body names, e.g. [motor, drum]", name));
  } else {
    ok = true;
    for (int k = 0; k < 2; ++k) {
      const SpecNode& item = between->items[static_cast<size_t>(k)];
      idx[k] = m.body_index(item.scalar);
      if (item.scalar == "ground") {
        diag.error(item.loc, fmt::format("lossy gear '{}': a gear to the ground would hold the other body fixed; to "
                                         "hold a body use a brake or a stop", name));
        ok = false;
      } else if (idx[k] < 0) {
        diag.error(item.loc, fmt::format("lossy gear '{}': unknown body '{}' (a lossy gear joins two bodies by name)",
                                         name, item.scalar));
        ok = false;
      } else if (m.bodies[static_cast<size_t>(idx[k])].machine) {
        diag.error(item.loc, fmt::format("lossy gear '{}': '{}' has a variable inertia; a lossy gear to a machine "
                                         "body is not supported yet", name, item.scalar));
        ok = false;
      }
    }
    if (ok && idx[0] == idx[1]) {
      diag.error(between->loc, fmt::format("lossy gear '{}': joins '{}' to itself", name, between->items[0].scalar));
      ok = false;
    }
    if (ok) s.body_a = between->items[0].scalar, s.body_b = between->items[1].scalar;
  }
  const BodyKind ka = ok ? m.bodies[static_cast<size_t>(idx[0])].kind : BodyKind::rotational;
  const BodyKind kb = ok ? m.bodies[static_cast<size_t>(idx[1])].kind : BodyKind::rotational;
  std::optional<double> r = f.quantity("ratio", position_dim(ka) / position_dim(kb), 1.0);
  if (r && (*r == 0.0 || !std::isfinite(*r))) {
    f.error_at("ratio", "field 'ratio' must be finite and not zero (q_a = ratio · q_b)");
    ok = false;
  }
  LossyGear& g = s.gear;
  if (const SpecNode* table = f.node("loss_table")) {
    for (const char* k : {"efficiency", "efficiency_reverse", "bearing_friction", "bearing_friction_reverse"})
      if (spec.find(k)) {
        f.error_at(k, fmt::format("field '{}' and 'loss_table' exclude each other; give the values in the table", k));
        f.node(k);
      }
    read_table(*table, name, ka, g, diag);
  } else {
    const auto eta1 = f.quantity("efficiency", dim::none);
    const auto eta2 = f.quantity("efficiency_reverse", dim::none, eta1.value_or(1.0));
    const auto bf1 = f.quantity("bearing_friction", load_dim(ka), 0.0);
    const auto bf2 = f.quantity("bearing_friction_reverse", load_dim(ka), bf1.value_or(0.0));
    if (eta1 && eta2 && bf1 && bf2) {
      const SpecNode* at = spec.find("efficiency");
      check_losses(name, *eta1, *eta2, *bf1, *bf2, at ? at->loc : spec.loc, diag);
      g.eta_forward = {*eta1};
      g.eta_reverse = {*eta2};
      g.bearing_forward = {*bf1};
      g.bearing_reverse = {*bf2};
    } else {
      ok = false;
    }
  }
  f.finish();
  if (!ok || !r || g.eta_forward.empty()) return;
  g.a = idx[0], g.b = idx[1];
  g.ratio = *r;
  out.push_back(std::move(s));
}

void resolve_lossy(Model& m, const std::vector<LossyGearSpec>& gears, Diagnostics& diag) {
  // The body (after the merge) and ρ of a file's body: itself with ρ = 1, or its ideal-gear master.
  auto place = [&](const std::string& name, int* body, double* rho) {
    *body = m.body_index(name);
    *rho = 1.0;
    if (*body >= 0) return;
    for (const RigidSlave& sl : m.slaves)
      if (sl.name == name) *body = sl.master, *rho = sl.ratio;
  };
  std::vector<int> used(m.bodies.size(), -1);
  std::vector<char> in_train(gears.size(), 0);          // per gear read: one of a two-stage train
  std::vector<std::pair<int, Location>> train_body;      // the trains' shared bodies
  std::vector<Location> where;  // of each gear in m.lossy_gears
  for (size_t k = 0; k < gears.size(); ++k) {
    const LossyGearSpec& s = gears[k];
    LossyGear g = s.gear;
    place(s.body_a, &g.a, &g.rho_a);
    place(s.body_b, &g.b, &g.rho_b);
    if (g.a < 0 || g.b < 0) continue;  // reported by the merge
    g.ratio = s.gear.ratio * g.rho_b / g.rho_a;  // q_A = i q_B, q_A = ρ_A q_a, q_B = ρ_B q_b
    if (g.a == g.b) {
      diag.error(s.where, fmt::format("lossy gear '{}': '{}' and '{}' move rigidly together through ideal gears, so "
                                      "the gear would close a rigid loop; remove it or one of the ideal gears",
                                      g.name, s.body_a, s.body_b));
      continue;
    }
    bool ok = true;
    // Two gears on one body are a two-stage train (analysis/gear_train.hpp): one shared body, two gears.
    const int ua = used[static_cast<size_t>(g.a)], ub = used[static_cast<size_t>(g.b)];
    for (int e : {g.a, g.b}) {
      int& u = used[static_cast<size_t>(e)];
      if (u >= 0) {
        const std::string other = gears[static_cast<size_t>(u)].gear.name;
        const std::string why = ua >= 0 && ub >= 0 ? std::string("both its bodies are geared already (a loop or a third stage)")
                                : in_train[static_cast<size_t>(u)] ? fmt::format("'{}' is a stage of a two-stage train already", other)
                                                                   : std::string();
        if (!why.empty()) {
          diag.error(s.where, fmt::format("lossy gear '{}': body '{}' is already geared by lossy gear '{}' and {}; "
                                          "more than two lossy gears in one train are not supported yet: put an "
                                          "inertia and a stiff spring between the stages",
                                          g.name, m.bodies[static_cast<size_t>(e)].name, other, why));
          ok = false;
        } else {
          in_train[static_cast<size_t>(u)] = in_train[k] = 1;
          train_body.push_back({e, s.where});
        }
      }
      u = static_cast<int>(k);
      // Friction to the fixed ground on a gear's body is decided with the gear (analysis/gear_lock.hpp),
      // a clutch to another body too (analysis/gear_clutch.hpp; checked below, once every gear is known).
      for (const FrictionContact& c : m.contacts) {
        if (c.a != e && c.b != e) continue;
        // A freewheel to another body is a one-sided clutch (analysis/gear_clutch.hpp); a backstop is
        // one more bounded row of the gear's friction (analysis/gear_lock.hpp).
        const char* why = c.b >= 0 ? nullptr
                          : c.stop ? "end stops on a lossy gear's bodies are not supported yet"
                          : c.lock != 0 ? nullptr
                          : c.surface_times.size() > 1 ||
                                    (!c.surface_velocities.empty() && c.surface_velocities[0] != 0.0)
                              ? "a ground contact with a moving surface on a lossy gear's body is not supported yet "
                                "(it would drive the gear while stuck to it)"
                              : nullptr;
        if (!why) continue;
        diag.error(s.where, fmt::format("lossy gear '{}': body '{}' has the friction element '{}'; {}", g.name,
                                        m.bodies[static_cast<size_t>(e)].name, c.name, why));
        ok = false;
      }
    }
    // Initial velocities on v_a = i v_b: one side's value gives the other's.
    Body& A = m.bodies[static_cast<size_t>(g.a)];
    Body& B = m.bodies[static_cast<size_t>(g.b)];
    // One side may be massless (MSL's flange between a gear and a clutch): the gear's law then moves
    // it, which needs inertia on the other side (analysis/gear_clutch.hpp).
    if (A.inertia == 0.0 && B.inertia == 0.0) {
      diag.error(s.where, fmt::format("lossy gear '{}': both '{}' and '{}' have zero inertia; the gear's law needs "
                                      "inertia on at least one side: give one of them an inertia", g.name, A.name,
                                      B.name));
      ok = false;
    }
    for (const Body* x : {&A, &B})
      if (x->inertia == 0.0 && x->motion != MotionKind::free) {
        diag.error(s.where, fmt::format("lossy gear '{}': '{}' has zero inertia and a prescribed motion; give it an "
                                        "inertia", g.name, x->name));
        ok = false;
      }
    if (A.v0 != 0.0 && B.v0 != 0.0 && !initial_values_agree(A.v0, g.ratio * B.v0)) {
      diag.error(s.where, fmt::format("lossy gear '{}': the initial velocities contradict the gear: {} {:.12g} and "
                                      "{} {:.12g} with v_a = {:.12g} v_b; give the velocity on one side only",
                                      g.name, A.name, A.v0, B.name, B.v0, g.ratio));
      ok = false;
    } else if (B.v0 != 0.0) {
      A.v0 = g.ratio * B.v0;
    } else {
      B.v0 = A.v0 / g.ratio;
    }
    if (A.q0 == 0.0 && B.q0 != 0.0) A.q0 = g.ratio * B.q0;
    else if (B.q0 == 0.0) B.q0 = A.q0 / g.ratio;
    if (!ok) continue;
    m.lossy_gears.push_back(std::move(g));
    where.push_back(s.where);
  }
  // A two-stage train (analysis/gear_train.hpp): nothing but links and loads on its three bodies, and
  // inertia on the two outer ones (the shared shaft may be massless).
  for (const auto& [shared, at] : train_body) {
    std::vector<int> bodies{shared};
    std::vector<std::string> names;
    for (const LossyGear& g : m.lossy_gears)
      if (g.a == shared || g.b == shared) bodies.push_back(g.a == shared ? g.b : g.a), names.push_back(g.name);
    if (names.size() != 2) continue;  // one of the two was refused above
    const std::string pre = fmt::format("lossy gears '{}' and '{}' (a two-stage train on '{}')", names[0], names[1],
                                        m.bodies[static_cast<size_t>(shared)].name);
    for (int e : bodies) {
      const Body& B = m.bodies[static_cast<size_t>(e)];
      for (const FrictionContact& c : m.contacts)
        if (c.a == e || c.b == e || (c.row.terms > 0 && std::find(c.row.body, c.row.body + c.row.terms, e) != c.row.body + c.row.terms))
          diag.error(at, fmt::format("{}: body '{}' has the friction element '{}'; friction elements, clutches and end "
                                     "stops on a two-stage train's bodies are not supported yet", pre, B.name, c.name));
      if (B.motion != MotionKind::free)
        diag.error(at, fmt::format("{}: body '{}' has a prescribed motion; not supported on a two-stage train yet", pre,
                                   B.name));
      if (e != shared && B.inertia == 0.0)
        diag.error(at, fmt::format("{}: the outer body '{}' has zero inertia; give it an inertia (only the shared shaft "
                                   "may be massless)", pre, B.name));
    }
  }
  // The initial velocities across the train: both gears' v_a = i v_b (the value given on one body).
  for (int pass = 0; pass < 2 && !train_body.empty(); ++pass)
    for (const LossyGear& g : m.lossy_gears) {
      Body& A = m.bodies[static_cast<size_t>(g.a)];
      Body& B = m.bodies[static_cast<size_t>(g.b)];
      if (A.v0 == 0.0 && B.v0 != 0.0) A.v0 = g.ratio * B.v0;
      else if (B.v0 == 0.0 && A.v0 != 0.0) B.v0 = A.v0 / g.ratio;
      else if (pass == 1 && !initial_values_agree(A.v0, g.ratio * B.v0))
        diag.error(m.where(g.name), fmt::format("lossy gear '{}': the initial velocities of its train contradict it: {} "
                                                "{:.12g} and {} {:.12g}; give the velocity on one body of the train only",
                                                g.name, A.name, A.v0, B.name, B.v0));
    }
  // Clutches on a gear's body (analysis/gear_clutch.hpp), also to another gear's body (the two decided
  // together at rest); a freewheel's other body on no lossy gear (friction to the ground beside them is
  // decided in the same decision).
  auto gear_of = [&](int body) {
    for (size_t k = 0; k < m.lossy_gears.size(); ++k)
      if (m.lossy_gears[k].a == body || m.lossy_gears[k].b == body) return static_cast<int>(k);
    return -1;
  };
  for (size_t k = 0; k < m.lossy_gears.size(); ++k) {
    const LossyGear& g = m.lossy_gears[k];
    const FrictionContact* clutch = nullptr;
    for (const FrictionContact& c : m.contacts) {
      const bool on_a = c.a == g.a || c.a == g.b, on_b = c.b >= 0 && (c.b == g.a || c.b == g.b);
      if ((!on_a && !on_b) || c.b < 0) continue;  // friction to the ground: decided with the gear too
      clutch = &c;
      const int other = on_a ? c.b : c.a;
      const std::string where_c = fmt::format("lossy gear '{}': contact '{}'", g.name, c.name);
      if (c.joint || c.row.terms > 0)
        diag.error(where[k], fmt::format("{}: a gear joint, or a contact acting through one, on a lossy gear's body "
                                         "is not supported yet", where_c));
      else if (on_a && on_b)
        diag.error(where[k], fmt::format("{} joins the gear's own two bodies (the gear fixes their relative motion); "
                                         "remove it", where_c));
      else if (gear_of(other) >= 0 && c.lock != 0)  // a clutch between two gears: decided together at rest
        diag.error(where[k], fmt::format("{} joins it to lossy gear '{}'; a freewheel between two lossy gears is not "
                                         "supported yet: put an inertia between them", where_c,
                                         m.lossy_gears[static_cast<size_t>(gear_of(other))].name));
    }
    // Prescribed motions: a stuck clutch chain could tie one to a stuck gear (two kinematic ends);
    // the coupled solve does not take them yet.
    const bool massless = m.bodies[static_cast<size_t>(g.a)].inertia == 0.0 || m.bodies[static_cast<size_t>(g.b)].inertia == 0.0;
    if (clutch || massless)
      for (const Body& b : m.bodies)
        if (b.motion != MotionKind::free) {
          diag.error(where[k], fmt::format("lossy gear '{}': {} in a model with a prescribed motion ('{}') is not "
                                           "supported yet", g.name,
                                           clutch ? fmt::format("a clutch on its body ('{}')", clutch->name)
                                                  : std::string("a massless side"), b.name));
          break;
        }
  }
}


// A lossy gear as the file wrote it: ratio, efficiencies both ways, bearing friction, self-locking.
ElementText describe_lossy_gear(const Model& m, const LossyGear& g) {
  const BodyKind k = m.bodies[static_cast<size_t>(g.a)].kind;
  const std::string lu = load_unit(k);
  const double i = g.ratio * g.rho_a / g.rho_b;  // the file's ratio (model.hpp LossyGear::ratio)
  const std::string A = m.bodies[static_cast<size_t>(g.a)].name, B = m.bodies[static_cast<size_t>(g.b)].name;
  std::string t = fmt::format("'{}' – '{}', ratio i = {} (v_A = i v_B)", A, B, describe_number(i));
  if (g.speeds.empty()) {
    t += fmt::format(", efficiency η = {} while A drives, {} while B drives", describe_number(g.eta_forward.at(0)),
                     describe_number(g.eta_reverse.at(0)));
    if (g.eta_reverse.at(0) == 0.0) t += " (self-locking)";
    if (g.bearing_forward.at(0) > 0.0 || g.bearing_reverse.at(0) > 0.0)
      t += fmt::format(", bearing friction {} / {} {} (in A's coordinate)", describe_number(g.bearing_forward.at(0)),
                       describe_number(g.bearing_reverse.at(0)), lu);
  } else {
    t += fmt::format(", losses tabulated over |v_A| at {} speeds up to {} {}: η {} … {} while A drives, {} … {} while B "
                     "drives",
                     g.speeds.size(), describe_number(g.speeds.back()), velocity_unit(k),
                     describe_number(g.eta_forward.front()), describe_number(g.eta_forward.back()),
                     describe_number(g.eta_reverse.front()), describe_number(g.eta_reverse.back()));
  }
  return {g.name, "lossy gear", t};
}

}  // namespace machdyn::detail
