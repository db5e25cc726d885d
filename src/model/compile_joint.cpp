// Joints (model/compile_joint.hpp): planetary gears and ideal gears on a housing body.
//
// A joint's row Σ_j w_j ω_j = 0 over its members. Planetary gear (Willis): with the carrier held,
// sun and ring turn as ω_s/ω_r = −z_r/z_s = −z, so in general ω_s − ω_c = −z (ω_r − ω_c), i.e.
// ω_s + z ω_r − (1 + z) ω_c = 0. A gear on a housing h: relative to the housing it is an ideal gear,
// ω_a − ω_h = i (ω_b − ω_h), i.e. ω_a − i ω_b + (i − 1) ω_h = 0. No inertia and no losses: the
// joint's power Σ_j (−w_j λ) ω_j = −λ · (row) = 0, so its load λ does no work.
#include "model/compile_joint.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <fmt/format.h>

#include "machdyn/model/element.hpp"

#include "model/compile_rigid.hpp"

namespace machdyn::detail {

namespace {

/// The index of member `name` (a body, not the ground, not a machine; rotational unless `any_kind`),
/// or −1 after an error at `at`.
int member_index(const std::string& what, const std::string& role, const std::string& name, const Location& at,
                 const Model& m, Diagnostics& diag) {
  const int i = m.body_index(name);
  if (name == "ground") {
    diag.error(at, fmt::format("{}: {} 'ground' would hold that member fixed; leave it out (a planetary gear with a "
                               "fixed member is an ideal gear) or hold a body with a brake", what, role));
    return -1;
  }
  if (i < 0) {
    diag.error(at, fmt::format("{}: unknown body '{}' as {}", what, name, role));
    return -1;
  }
  const Body& b = m.bodies[static_cast<size_t>(i)];
  if (b.machine) {
    diag.error(at, fmt::format("{}: {} '{}' has a variable inertia; a joint to a machine body is not supported yet",
                               what, role, name));
    return -1;
  }
  if (b.kind != BodyKind::rotational) {
    diag.error(at, fmt::format("{}: {} '{}' is translational; the members of a gear joint are rotational bodies", what,
                               role, name));
    return -1;
  }
  return i;
}

/// Reads the member `role` (a body name) of a joint into `j`.
bool read_member(FieldReader& f, const SpecNode& spec, const char* role, const Model& m, JointSpec& j,
                 Diagnostics& diag) {
  const auto nm = f.text(role);
  if (!nm) return false;
  const SpecNode* at = spec.find(role);
  if (member_index(j.what, role, *nm, at ? Location(at->loc) : j.where, m, diag) < 0) return false;
  j.member.push_back(*nm);
  j.role.push_back(role);
  return true;
}

/// Each member once: a member twice would make the joint a plain ratio between the others.
bool distinct_members(const JointSpec& j, const SpecNode& spec, Diagnostics& diag) {
  for (size_t p = 0; p < j.member.size(); ++p)
    for (size_t q = p + 1; q < j.member.size(); ++q)
      if (j.member[p] == j.member[q]) {
        const SpecNode* at = spec.find(j.role[q]);
        diag.error(at ? Location(at->loc) : j.where,
                   fmt::format("{}: '{}' is both {} and {}; each member must be a body of its own", j.what,
                               j.member[p], j.role[p], j.role[q]));
        return false;
      }
  return true;
}

/// z = z_ring/z_sun from `teeth: {sun: z_s, ring: z_r}` (and `planets: N`), checked to be buildable.
std::optional<double> ratio_from_teeth(FieldReader& f, const SpecNode& teeth, const std::string& what,
                                       Diagnostics& diag) {
  if (!teeth.is_map()) {
    diag.error(teeth.loc, fmt::format("{}: 'teeth' expected a map {{sun: z_s, ring: z_r}}", what));
    return std::nullopt;
  }
  FieldReader t(teeth, what + " teeth", diag);
  const auto zs = t.integer("sun", 1, 100000), zr = t.integer("ring", 1, 100000);
  t.finish();
  const auto planets = f.integer("planets", 1, 1000, 0);
  if (!zs || !zr) return std::nullopt;
  if (*zr <= *zs || (*zr - *zs) % 2 != 0) {
    diag.error(teeth.loc, fmt::format("{}: a ring of {} and a sun of {} teeth cannot be built: the planets mesh with "
                                      "both, z_p = (z_ring − z_sun)/2, which must be a whole number ≥ 1 (z_ring > "
                                      "z_sun, z_ring − z_sun even)", what, *zr, *zs));
    return std::nullopt;
  }
  if (planets && *planets > 0 && (*zs + *zr) % *planets != 0) {
    f.error_at("planets", fmt::format("{}: {} equally spaced planets cannot be assembled: z_sun + z_ring = {} is not "
                                      "divisible by {}", what, *planets, *zs + *zr, *planets));
    return std::nullopt;
  }
  return static_cast<double>(*zr) / static_cast<double>(*zs);
}

/// The terms of a row with `extra` (body, w) added, equal bodies merged.
void add_term(VelocityRow& r, int body, double w) {
  for (int j = 0; j < r.terms; ++j)
    if (r.body[j] == body) {
      r.w[j] += w;
      return;
    }
  r.body[r.terms] = body;
  r.w[r.terms] = w;
  ++r.terms;
}

/// The row without terms that cancelled (|w| ≤ 1e-12 of the largest).
void drop_zeros(VelocityRow& r) {
  double big = 0.0;
  for (int j = 0; j < r.terms; ++j) big = std::max(big, std::abs(r.w[j]));
  int k = 0;
  for (int j = 0; j < r.terms; ++j)
    if (std::abs(r.w[j]) > 1e-12 * big) r.body[k] = r.body[j], r.w[k] = r.w[j], ++k;
  r.terms = k;
}

/// Shifts every body index above x down by one (body x is removed).
void remove_body(Model& m, int x) {
  auto shift = [x](int& i) {
    if (i > x) --i;
  };
  for (Load& ld : m.loads) shift(ld.body), shift(ld.body2);
  for (Link& l : m.links) shift(l.a), shift(l.b), shift(l.third);
  for (FrictionContact& c : m.contacts) {
    shift(c.a), shift(c.b);
    for (int j = 0; j < c.row.terms; ++j) shift(c.row.body[j]);
  }
  for (Drive& d : m.drives) {
    shift(d.body), shift(d.body2);
    for (int& o : d.others) shift(o);
  }
  for (LossyGear& g : m.lossy_gears) shift(g.a), shift(g.b);
  for (RigidSlave& s : m.slaves) shift(s.master), shift(s.master2);
  for (MergedGear& g : m.merged_gears) shift(g.body);
  shift(m.crane.load);
  m.bodies.erase(m.bodies.begin() + x);
  m.index_bodies();
}

/// Rewrites link k if an end is on x (q_x = Σ sub.w q_sub.body): δ = Σ w q over its terms with x's
/// term replaced, its own other ends kept in their places (units, display), the rest in the free
/// places of a, b, e (model.hpp: Link). False after an error.
bool rewrite_link(Model& m, int k, int x, const VelocityRow& sub, const std::string& why, Diagnostics& diag,
                  EliminatedJoint& out) {
  Link& l = m.links[static_cast<size_t>(k)];
  if (l.a != x && l.b != x && l.third != x) return true;
  const std::string at = fmt::format("link '{}': {}", l.name, why);
  if (l.a_point || l.b_point || l.EA > 0.0 || l.buffer || m.crane.rope == k) {
    const char* what = l.a_point || l.b_point ? "a machine's output point" : l.EA > 0.0 ? "a rope wound on a drum"
                       : l.buffer ? "a buffer" : "the crane's hoist rope";
    diag.error(m.where(l.name), fmt::format("{}; {} on it is not supported: give it an inertia", at, what));
    return false;
  }
  // δ = Σ w q over the link's terms (model.hpp: q_a/i − w_b q_b + w_e q_e), x's term substituted.
  VelocityRow t;
  double wx = 0.0;
  const int end[3] = {l.a, l.b, l.third};
  const double w[3] = {1.0 / l.ratio, -l.b_weight, l.third_weight};
  for (int j = 0; j < 3; ++j) {
    if (end[j] < 0) continue;
    if (end[j] == x) wx += w[j];
    else add_term(t, end[j], w[j]);
  }
  for (int j = 0; j < sub.terms; ++j) add_term(t, sub.body[j], wx * sub.w[j]);
  drop_zeros(t);
  out.links.push_back(k), out.link_weight.push_back(wx);  // X's torque balance: −F ∂δ/∂q_X
  if (t.terms == 0) {
    diag.error(m.where(l.name), fmt::format("{}; its deflection is then always 0 (its ends move together): remove it",
                                            at));
    return false;
  }
  if (t.terms > 3) {
    diag.error(m.where(l.name), fmt::format("{}; the link would join {} bodies, at most 3 are supported: give one of "
                                            "its ends an inertia", at, t.terms));
    return false;
  }
  // Places: a keeps its body if it stays (weight 1/i), b likewise (weight −w_b); the rest fill a, b, e.
  int slot_body[3] = {kGround, kGround, kGround};
  double slot_w[3] = {0.0, 0.0, 0.0};
  std::vector<char> used(static_cast<size_t>(t.terms), 0);
  for (int s = 0; s < 2; ++s)
    for (int j = 0; j < t.terms; ++j)
      if (end[s] >= 0 && end[s] != x && t.body[j] == end[s]) slot_body[s] = t.body[j], slot_w[s] = t.w[j], used[static_cast<size_t>(j)] = 1;
  for (int j = 0; j < t.terms; ++j) {
    if (used[static_cast<size_t>(j)]) continue;
    int s = 0;
    while (slot_body[s] != kGround) ++s;
    slot_body[s] = t.body[j], slot_w[s] = t.w[j];
  }
  l.a = slot_body[0];
  l.ratio = l.a >= 0 ? 1.0 / slot_w[0] : 1.0;
  l.b = slot_body[1];
  l.b_weight = l.b >= 0 ? -slot_w[1] : 1.0;
  l.third = slot_body[2];
  l.third_weight = l.third >= 0 ? slot_w[2] : 0.0;
  // A merged ideal gear that summed this link's first end no longer knows its share: no torque output.
  std::erase_if(m.merged_gears, [k](const MergedGear& g) { return std::find(g.links.begin(), g.links.end(), k) != g.links.end(); });
  return true;
}

/// Eliminates member x of joint `j` (row `r`, x in it, zero inertia): contacts on x get x's terms
/// rewritten, x becomes a RigidSlave of the others. Errors for what would need x's equation of motion.
void eliminate(Model& m, const JointSpec& j, const VelocityRow& r, int x, const SpecNode* bodies, Diagnostics& diag) {
  const Body& X = m.bodies[static_cast<size_t>(x)];
  const std::string why = fmt::format("'{}' has no inertia, so {} eliminates it (its motion follows the other "
                                      "members)", X.name, j.what);
  bool ok = true;
  for (const LossyGear& g : m.lossy_gears)
    if (g.a == x || g.b == x) {
      diag.error(m.where(g.name), fmt::format("lossy gear '{}': {}; give '{}' an inertia", g.name, why, X.name));
      ok = false;
    }
  for (const RigidSlave& s : m.slaves)
    if (s.master == x || s.master2 == x) {
      diag.error(m.where(s.name), fmt::format("'{}' is tied by ideal gears to '{}', which {}; give one of them an "
                                              "inertia", s.name, X.name, why));
      ok = false;
    }
  if (m.crane.load == x) {
    diag.error(m.where(X.name), fmt::format("crane: the hook load '{}' has no inertia", X.name));
    ok = false;
  }
  // q_X = Σ_{k≠x} c_k q_k, c_k = −w_k / w_x.
  VelocityRow sub;
  double wx = 0.0;
  for (int k = 0; k < r.terms; ++k)
    if (r.body[k] == x) wx = r.w[k];
  for (int k = 0; k < r.terms; ++k)
    if (r.body[k] != x) add_term(sub, r.body[k], -r.w[k] / wx);
  // The joint's torques follow from X's torque balance (model.hpp: EliminatedJoint): what acts on X.
  EliminatedJoint ej{j.name, j.member, j.w, wx, X.kind, {}, {}, {}, {}, {}, {}, {}, {}};
  for (size_t k = 0; k < m.links.size(); ++k) ok = rewrite_link(m, static_cast<int>(k), x, sub, why, diag, ej) && ok;
  for (FrictionContact& c : m.contacts) {
    VelocityRow row = c.row;
    if (row.terms == 0) {
      row.terms = 0;
      add_term(row, c.a, 1.0);
      if (c.b >= 0) add_term(row, c.b, -1.0);
    }
    double wc = 0.0;
    for (int k = 0; k < row.terms; ++k)
      if (row.body[k] == x) wc = row.w[k];
    if (wc == 0.0) continue;
    ej.contacts.push_back(static_cast<int>(&c - m.contacts.data())), ej.contact_weight.push_back(wc);
    if (c.stop) {
      diag.error(m.where(c.name), fmt::format("stop '{}': {}; an end stop on it is not supported", c.name, why));
      ok = false;
      continue;
    }
    VelocityRow out;
    for (int k = 0; k < row.terms; ++k)
      if (row.body[k] != x) add_term(out, row.body[k], row.w[k]);
    for (int k = 0; k < sub.terms; ++k) {
      if (out.terms == VelocityRow::kMaxTerms && std::none_of(out.body, out.body + out.terms, [&](int b) { return b == sub.body[k]; })) {
        diag.error(m.where(c.name), fmt::format("'{}': {}; the contact would join more than {} bodies", c.name, why,
                                                VelocityRow::kMaxTerms));
        ok = false;
        break;
      }
      add_term(out, sub.body[k], wc * sub.w[k]);
    }
    drop_zeros(out);
    if (out.terms == 0) {
      diag.error(m.where(c.name), fmt::format("'{}': {}; its two sides then always move together, so it never "
                                              "slips: remove it", c.name, why));
      ok = false;
      continue;
    }
    c.row = out;
    c.a = out.body[0];
    if (c.b >= 0) c.b = out.terms > 1 ? out.body[1] : kGround;
  }
  if (!ok) return;
  // X's initial position and velocity follow the others; a value the file gives must agree.
  for (const char* key : {"position", "velocity"}) {
    const bool pos = key[0] == 'p';
    double x0 = 0.0;
    for (int k = 0; k < sub.terms; ++k) {
      const Body& b = m.bodies[static_cast<size_t>(sub.body[k])];
      x0 += sub.w[k] * (pos ? b.q0 : b.v0);
    }
    const double given = pos ? X.q0 : X.v0;
    if (const SpecNode* at = body_field(bodies, X.name, key); at && !initial_values_agree(given, x0))
      diag.error(at->loc, fmt::format("body '{}': {} {:.12g} contradicts {}, which gives it {:.12g} from the other "
                                      "members; leave it out", X.name, key, given, j.what, x0));
  }
  // A load on X acts on the others by virtual work, M δq_X = Σ c_k M δq_k (model.hpp: Load). A load
  // given on a body slaved to X (q_s = ρ q_X) keeps its ρ: weights ρ c_k.
  for (Load& ld : m.loads) {
    if (ld.body != x) continue;
    // On X: ρ M with Load::at() = M (a constant reduced below: at() = c M, so ρ/c).
    const bool reduce = sub.terms == 1 && ld.kind == LoadKind::constant;
    ej.loads.push_back(static_cast<int>(&ld - m.loads.data())), ej.load_weight.push_back(ld.ratio / (reduce ? sub.w[0] : 1.0));
    if (reduce) {  // one body: reduced once, as compile_rigid does
      ld.value *= sub.w[0];
      ld.signal = Signal::constant(ld.value);
      ld.body = sub.body[0];
      continue;
    }
    const double rho = ld.ratio;
    ld.body = sub.body[0], ld.ratio = rho * sub.w[0];
    if (sub.terms > 1) ld.body2 = sub.body[1], ld.ratio2 = rho * sub.w[1];
  }
  // A drive on X likewise: it sees ω_X = Σ c_k v_k and puts c_k M on the others (model.hpp: Drive);
  // every member is rotational (member_index), so its columns keep their units.
  for (Drive& d : m.drives) {
    if (std::find(d.others.begin(), d.others.end(), x) != d.others.end())  // plain bodies (model.hpp: Drive::others)
      diag.error(m.where(d.name), fmt::format("'{}': a {} on '{}', a joint's member without inertia, is not supported "
                                              "yet: give '{}' an inertia", d.name, d.law->type(), X.name, X.name));
    if (d.body != x) continue;
    ej.drives.push_back(static_cast<int>(&d - m.drives.data())), ej.drive_weight.push_back(d.ratio);
    const double rho = d.ratio;
    d.body = sub.body[0], d.ratio = rho * sub.w[0];
    if (sub.terms > 1) d.body2 = sub.body[1], d.ratio2 = rho * sub.w[1];
  }
  // Its torque output would need X's equation of motion, which is gone.
  std::erase_if(m.merged_gears, [x](const MergedGear& g) { return g.body == x; });
  RigidSlave s{X.name, X.kind, sub.body[0], sub.w[0], 0.0, sub.terms > 1 ? sub.body[1] : -1,
               sub.terms > 1 ? sub.w[1] : 0.0};
  remove_body(m, x);
  if (s.master > x) --s.master;
  if (s.master2 > x) --s.master2;
  m.slaves.push_back(s);
  m.eliminated_joints.push_back(std::move(ej));
}

/// A joint named `name` of kind `kind` ("planetary gear", "ideal gear") at its key.
JointSpec named_joint(const std::string& name, const char* kind, const SpecNode& spec) {
  JointSpec j;
  j.name = name;
  j.what = fmt::format("{} '{}'", kind, name);
  j.where = Location(spec.key_loc);
  return j;
}

}  // namespace

void read_planetary_gear(const std::string& name, const SpecNode& spec, const Model& m, std::vector<JointSpec>& out,
                         Diagnostics& diag) {
  JointSpec j = named_joint(name, "planetary gear", spec);
  FieldReader f(spec, j.what, diag);
  f.word("type", {"planetary-gear"});
  bool ok = true;
  for (const char* role : {"sun", "ring", "carrier"}) ok = read_member(f, spec, role, m, j, diag) && ok;
  ok = ok && distinct_members(j, spec, diag);
  double ratio = 0.0;  // 0: none (a valid ratio is > 1)
  if (const SpecNode* teeth = f.node("teeth")) {
    if (spec.find("ratio")) {
      f.error_at("ratio", fmt::format("{}: give either 'ratio' or 'teeth', not both", j.what));
      f.node("ratio");
    } else {
      ratio = ratio_from_teeth(f, *teeth, j.what, diag).value_or(0.0);
    }
  } else {
    f.integer("planets", 1, 1000, 0);
    const double z = f.quantity("ratio", dim::none).value_or(std::nan(""));  // NaN: missing or unreadable
    if (!std::isnan(z) && !(z > 1.0 && std::isfinite(z)))
      f.error_at("ratio", fmt::format("{}: ratio z = z_ring/z_sun = {:.12g} cannot be built: the ring is larger than "
                                      "the sun, z > 1", j.what, z));
    else if (!std::isnan(z))
      ratio = z;
  }
  f.finish();
  if (!ok || ratio == 0.0) return;
  j.w = {1.0, ratio, -(1.0 + ratio)};
  out.push_back(std::move(j));
}

void read_housed_gear(const std::string& name, const SpecNode& spec, const Model& m, std::vector<JointSpec>& out,
                      Diagnostics& diag) {
  JointSpec j = named_joint(name, "ideal gear", spec);
  FieldReader f(spec, j.what, diag);
  f.word("type", {"ideal-gear"});
  bool ok = true;
  const SpecNode* between = f.node("between");
  if (!between || !between->is_seq() || between->items.size() != 2 || !between->items[0].is_scalar() ||
      !between->items[1].is_scalar()) {
    diag.error(between ? between->loc : spec.loc,
               fmt::format("{}: 'between' expected two body names, e.g. [motor, drum]", j.what));
    ok = false;
  } else {
    for (int k = 0; k < 2; ++k) {
      const SpecNode& item = between->items[static_cast<size_t>(k)];
      const char* role = k == 0 ? "a" : "b";
      if (member_index(j.what, role, item.scalar, item.loc, m, diag) < 0) {
        ok = false;
        continue;
      }
      j.member.push_back(item.scalar);
      j.role.push_back(role);
    }
  }
  ok = read_member(f, spec, "housing", m, j, diag) && ok;
  if (ok && !distinct_members(j, spec, diag)) ok = false;
  const auto i = f.quantity("ratio", dim::none, 1.0);
  if (i && (*i == 0.0 || !std::isfinite(*i))) {
    f.error_at("ratio", "field 'ratio' must be finite and not zero (ω_a − ω_housing = ratio · (ω_b − ω_housing))");
    ok = false;
  }
  f.finish();
  if (!ok || !i) return;
  j.w = {1.0, -*i, *i - 1.0};
  out.push_back(std::move(j));
}

std::unordered_set<std::string> massless_members(const Model& m, const std::vector<JointSpec>& joints) {
  std::unordered_set<std::string> out;
  for (const JointSpec& j : joints)
    for (const std::string& nm : j.member)
      if (const int i = m.body_index(nm); i >= 0 && m.bodies[static_cast<size_t>(i)].inertia == 0.0) out.insert(nm);
  return out;
}

void resolve_joints(Model& m, const std::vector<JointSpec>& joints, const SpecNode* bodies, Diagnostics& diag) {
  for (const JointSpec& j : joints) {
    // The row over the bodies the ideal-gear merge left: a slaved member q = ρ q_master adds w ρ.
    VelocityRow r;
    bool ok = true;
    for (size_t k = 0; k < j.member.size() && ok; ++k) {
      int idx = m.body_index(j.member[k]);
      double rho = 1.0;
      if (idx < 0)
        for (const RigidSlave& s : m.slaves)
          if (s.name == j.member[k]) {
            idx = s.master2 < 0 ? s.master : -1;
            rho = s.ratio;
          }
      if (idx < 0) {
        diag.error(j.where, fmt::format("{}: its {} '{}' is a member of another joint without inertia; give it an "
                                        "inertia", j.what, j.role[k], j.member[k]));
        ok = false;
        break;
      }
      add_term(r, idx, j.w[k] * rho);
    }
    if (!ok) continue;
    drop_zeros(r);
    if (r.terms < 2) {
      diag.error(j.where, fmt::format("{}: ideal gears already tie its members so that it would {}; remove it or the "
                                      "ideal gears", j.what, r.terms == 0 ? "add nothing" : "hold them fixed"));
      continue;
    }
    std::vector<int> massless;
    for (int k = 0; k < r.terms; ++k)
      if (m.bodies[static_cast<size_t>(r.body[k])].inertia == 0.0) massless.push_back(r.body[k]);
    if (massless.size() > 1) {
      diag.error(j.where, fmt::format("{}: {} of its members have no inertia; at most one may (its motion then follows "
                                      "the others), give the others an inertia", j.what, massless.size()));
      continue;
    }
    if (massless.size() == 1) {
      eliminate(m, j, r, massless.front(), bodies, diag);
      continue;
    }
    bool on_lossy = false;
    for (const LossyGear& g : m.lossy_gears)
      for (int k = 0; k < r.terms; ++k)
        if (g.a == r.body[k] || g.b == r.body[k]) {
          diag.error(j.where, fmt::format("{}: '{}' is a body of lossy gear '{}', whose law needs bodies without "
                                          "contacts or joints; not supported yet", j.what,
                                          m.bodies[static_cast<size_t>(r.body[k])].name, g.name));
          on_lossy = true;
        }
    if (on_lossy) continue;
    // Initial velocities on the joint: Σ w_j v_j = 0.
    double res = 0.0, scale = 0.0;
    for (int k = 0; k < r.terms; ++k) {
      const double x = r.w[k] * m.bodies[static_cast<size_t>(r.body[k])].v0;
      res += x;
      scale += std::abs(x);
    }
    if (std::abs(res) > 1e-9 * scale + 1e-12) {
      std::string terms;
      for (int k = 0; k < r.terms; ++k)
        terms += fmt::format("{}{:+.12g}·{:.12g}", k ? " " : "", r.w[k], m.bodies[static_cast<size_t>(r.body[k])].v0);
      diag.error(j.where, fmt::format("{}: the initial velocities contradict it: Σ w ω = {} = {:.12g} rad/s, not 0; "
                                      "give velocities that satisfy it", j.what, terms, res));
      continue;
    }
    FrictionContact c;
    c.name = j.name;
    c.joint = true;
    c.row = r;
    c.a = r.body[0];
    c.b = r.body[1];
    m.contacts.push_back(std::move(c));
  }
}

}  // namespace machdyn::detail
