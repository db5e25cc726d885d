// A rope's sheave losses as a lossy gear at its drum (model/sheaves.hpp).
#include "model/compile_sheaves.hpp"

#include <fmt/format.h>

#include "machdyn/model/reeving.hpp"
#include "machdyn/model/sheaves.hpp"

namespace machdyn {
namespace detail {

void add_sheave_losses(Model& m, std::vector<LossyGearSpec>& lossy, Diagnostics& diag) {
  const std::size_t nl = m.links.size();
  for (std::size_t k = 0; k < nl; ++k) {
    Link& l = m.links[k];
    if (!l.tension_only || l.buffer || !(l.sheave_efficiency < 1.0)) continue;
    const Reeving rv{l.falls, l.rope_ends, l.sheave_efficiency};
    if (rv.parts_per_end() < 2) continue;  // each end runs straight to the hook block: no sheave between
    const Location at = m.where(l.name);
    const std::string pre = fmt::format("rope '{}': its sheave losses ('sheave_efficiency')", l.name);
    if (l.a == kGround) {
      diag.error(at, pre + " act between the drum and the rope: the rope's first end must be the drum (a body), not "
                           "the ground");
      continue;
    }
    const Body& drum = m.bodies[static_cast<std::size_t>(l.a)];
    if (drum.machine || l.a_point) {
      diag.error(at, fmt::format("{} on a drum with variable inertia or at a machine's output point ('{}') are not "
                                 "supported yet", pre, drum.name));
      continue;
    }
    bool ok = true;
    for (const LossyGearSpec& g : lossy)
      if (g.body_a == drum.name || g.body_b == drum.name) {
        diag.error(at, fmt::format("{} act as a lossy gear at the drum '{}', which the lossy gear '{}' already gears; "
                                   "two lossy gears on one body are not supported yet: put the shaft between the "
                                   "gearbox and the drum (a spring) in the model", pre, drum.name, g.gear.name));
        ok = false;
      }
    for (const Body& b : m.bodies)
      if (ok && b.motion != MotionKind::free) {
        diag.error(at, fmt::format("{} act through a lossy gear with a massless side, which a model with a prescribed "
                                   "motion ('{}') does not support yet", pre, b.name));
        ok = false;
      }
    if (!ok) continue;
    // The rope's end at the drum: massless, in the hook's coordinate (q = q_drum / i; its q0 and v0
    // follow the drum's through the gear, resolve_lossy).
    Body node;
    node.name = l.name + kSheavesSuffix;
    node.kind = l.b != kGround ? m.bodies[static_cast<std::size_t>(l.b)].kind : BodyKind::translational;
    node.inertia = 0.0;
    LossyGearSpec s;
    s.gear.name = node.name;
    s.gear.a = l.a;
    s.gear.b = static_cast<int>(m.bodies.size());
    s.gear.ratio = l.ratio;  // (n/n_e)/R: drum angle per metre of hook travel
    // Power to the hook (hoisting): η_mf1 = η_r+; from it (lowering): η_mf2 = 1/η_r− (model/reeving.hpp).
    s.gear.eta_forward = {rv.efficiency(true)};
    s.gear.eta_reverse = {1.0 / rv.efficiency(false)};
    s.gear.bearing_forward = {0.0};
    s.gear.bearing_reverse = {0.0};
    s.body_a = drum.name;
    s.body_b = node.name;
    s.where = at;
    l.given_a = drum.name;  // displayed at the drum, as written (remember_given_bodies keeps it)
    l.drum_q0 = drum.q0 / l.ratio;  // a wound length's reference: the body's position at the drum's q_a0
    l.a = s.gear.b;
    l.ratio = 1.0;
    m.element_where.try_emplace(node.name, at);
    m.bodies.push_back(std::move(node));
    lossy.push_back(std::move(s));
  }
  m.index_bodies();
}

}  // namespace detail

int sheave_gear(const Model& m, const Link& l) {
  if (l.a < 0) return -1;
  for (std::size_t g = 0; g < m.lossy_gears.size(); ++g)
    if (m.lossy_gears[g].b == l.a && m.lossy_gears[g].name == l.name + kSheavesSuffix) return static_cast<int>(g);
  return -1;
}

bool is_sheave_gear(const Model& m, const LossyGear& g) {
  const std::string suffix = kSheavesSuffix;
  if (g.name.size() <= suffix.size() || g.name.compare(g.name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return false;
  const std::string rope = g.name.substr(0, g.name.size() - suffix.size());
  for (const Link& l : m.links)
    if (l.name == rope && l.a == g.b) return true;
  return false;
}

bool is_sheave_body(const Model& m, int i) {
  for (const LossyGear& g : m.lossy_gears)
    if (g.b == i && is_sheave_gear(m, g)) return true;
  return false;
}

int rope_drum(const Model& m, const Link& l) {
  const int g = sheave_gear(m, l);
  return g >= 0 ? m.lossy_gears[static_cast<std::size_t>(g)].a : l.a;
}

double rope_ratio(const Model& m, const Link& l) {
  const int g = sheave_gear(m, l);
  return g >= 0 ? m.lossy_gears[static_cast<std::size_t>(g)].ratio : l.ratio;
}

}  // namespace machdyn
