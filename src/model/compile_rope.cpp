#include "compile_rope.hpp"
#include "machdyn/model/describe.hpp"
#include "machdyn/model/sheaves.hpp"

#include <optional>

#include <fmt/format.h>

namespace machdyn::detail {

bool compile_rope_length(FieldReader& f, Link& l, const Dim& ld, const Dim& qd, BodyKind side,
                         const std::vector<Body>& bodies) {
  const SpecNode& map = f.map();
  const bool is_map = map.is_map();
  auto has = [&](const char* k) { return is_map && map.find(k) != nullptr; };
  l.falls = static_cast<int>(f.integer("falls", 1, 1000, 1).value_or(1));
  // Reeving as drawn (model/reeving.hpp): n_e rope ends on the drum, each feeding n/n_e falls.
  l.rope_ends = static_cast<int>(f.integer("rope_ends", 1, 1000, 1).value_or(1));
  if (l.rope_ends > 1 && l.a == kGround)
    f.error_at("rope_ends", "'rope_ends' are wound on a drum: the rope's first end (body a) must be the drum");
  else if (l.falls % l.rope_ends != 0)
    f.error_at("rope_ends", fmt::format("the {} falls must be shared equally by the {} rope ends on the drum (falls a "
                                        "multiple of rope_ends, e.g. 4/2 reeving: falls: 4, rope_ends: 2)",
                                        l.falls, l.rope_ends));
  if (l.falls % l.rope_ends != 0) l.rope_ends = 1;
  if (auto eta = f.quantity("sheave_efficiency", dim::none, 1.0)) {
    if (!(*eta > 0.0 && *eta <= 1.0)) f.error_at("sheave_efficiency", "field 'sheave_efficiency' must lie in (0, 1]");
    else l.sheave_efficiency = *eta;
  }
  // drum 1/R → (n/n_e)/R: drum angle per metre of hook travel
  if (l.falls > 1 && l.a != kGround) l.ratio *= static_cast<double>(l.falls / l.rope_ends);
  // The body the drum and the reeving's upper sheaves sit on (a trolley on an elastic girder): the
  // rope's deflection gains its position, δ = q_a/i − x_b + x_frame, and its load pulls it down with
  // −F (Link::third, weight 1; law: elements/link.hpp, a third body).
  if (const SpecNode* fr = f.node("frame")) {
    int frame = -1;
    for (size_t k = 0; k < bodies.size(); ++k)
      if (fr->is_scalar() && bodies[k].name == fr->scalar) frame = static_cast<int>(k);
    if (!fr->is_scalar() || (frame < 0 && !bodies.empty()))
      f.error_at("frame", "field 'frame' expected the name of a translational body (the trolley or girder the drum hangs from)");
    else if (frame >= 0 && bodies[static_cast<size_t>(frame)].kind != BodyKind::translational)
      f.error_at("frame", fmt::format("the frame '{}' must be a translational body (the girder's vertical deflection, m)", fr->scalar));
    else if (frame >= 0 && (frame == l.a || frame == l.b))
      f.error_at("frame", "the frame must be a third body, not an end of the rope");
    else if (frame >= 0 && side != BodyKind::translational)
      f.error_at("frame", "a rope with a 'frame' needs a translational hook (body b)");
    else if (frame >= 0 && (l.a_point || l.b_point))
      f.error_at("frame", "a rope with a 'frame' ends at bodies (not at a machine's output point)");
    else if (frame >= 0) {
      l.third = frame;
      l.third_weight = 1.0;
    }
  }
  const bool given = has("length") || has("EA") || has("elastic_modulus") || has("area");
  if (!given) {
    if (l.falls > 1 && !has("stiffness"))
      f.error_at("falls", "a rope with 'falls' needs its 'length' and 'EA' (or a 'stiffness' at the hook)");
    return false;
  }
  if (has("stiffness"))
    f.error_at("stiffness", "a rope with a 'length' has the stiffness n E A / L of its falls; give no 'stiffness'");
  f.node("stiffness");
  if (side != BodyKind::translational) f.error_at("length", "a rope's 'length' needs a translational hook (body b)");
  if (l.a_point || l.b_point) f.error_at("length", "a rope with a 'length' cannot end at a machine's output point");
  std::optional<double> L;
  if (has("length")) L = f.positive("length", qd);
  else f.error_at(has("EA") ? "EA" : has("elastic_modulus") ? "elastic_modulus" : "area",
                  "a rope with 'EA' (or 'elastic_modulus') needs its free 'length'");
  std::optional<double> EA;
  if (!has("EA") && !has("elastic_modulus") && !has("area")) {
    f.error_at("length", "a rope with a 'length' needs 'EA', or 'elastic_modulus' and 'area'");
  } else if (has("EA") && (has("elastic_modulus") || has("area"))) {
    f.error_at("EA", "give either 'EA' or 'elastic_modulus' and 'area', not both");
    f.node("elastic_modulus"), f.node("area"), f.node("EA");
  } else if (has("EA")) {
    EA = f.positive("EA", ld);
  } else {
    auto E = f.positive("elastic_modulus", ld / (dim::length * dim::length));
    auto A = f.positive("area", dim::length * dim::length);
    if (E && A) EA = *E * *A;
  }
  if (!L || !EA) return true;
  l.EA = *EA;
  l.length = *L;
  l.drum_q0 = l.a >= 0 && static_cast<size_t>(l.a) < bodies.size() ? bodies[static_cast<size_t>(l.a)].q0 : 0.0;
  l.c = l.falls * l.EA / l.length;
  return true;
}


// A rope as the file wrote it: falls, EA, free length, the drum's 1/R, and the hook stiffness they give.
std::string describe_rope(const Model& m, const Link& l) {
  // the file's drum ratio 1/R, rad/m: the link's ratio is (n/n_e)/R, divided by ρ when an ideal gear
  // slaves the drum (shown_ratio multiplies it back, but leaves links with a third body alone)
  double ratio = shown_ratio(m, l);
  if (l.third != kGround)
    for (const RigidSlave& s : m.slaves)
      if (s.name == l.given_a && s.master == l.a) ratio = l.ratio * s.ratio;
  const int sheaves = sheave_gear(m, l);  // its drum's ratio: shown_ratio
  if (sheaves >= 0) ratio = shown_ratio(m, l);
  const double n = l.falls, per_m = ratio * l.rope_ends / n;
  std::string t = fmt::format("{} fall{}", l.falls, l.falls == 1 ? "" : "s");
  if (l.rope_ends > 1) t += fmt::format(" from {} rope ends on the drum ({}/{} reeving)", l.rope_ends, l.falls, l.rope_ends);
  if (l.sheave_efficiency < 1.0) t += fmt::format(", sheave efficiency η = {}", describe_number(l.sheave_efficiency));
  if (sheaves >= 0) {
    const LossyGear& g = m.lossy_gears[static_cast<std::size_t>(sheaves)];
    t += fmt::format(" (reeving efficiency {} hoisting, {} lowering, acting at the drum)",
                     describe_number(g.eta_forward.at(0)), describe_number(g.eta_reverse.at(0)));
  }
  if (l.EA > 0.0)
    t += fmt::format(", EA = {} N, free length L = {} m per fall at the start, drum 1/R = {} rad/m (R = {} m); "
                     "hook stiffness n·EA/L = {} N/m at the start (changes as the drum winds)",
                     describe_number(l.EA), describe_number(l.length), describe_number(per_m),
                     describe_number(1.0 / per_m), describe_number(l.c));
  else
    t += fmt::format(", drum 1/R = {} rad/m; stiffness at the hook c = {} N/m (constant)", describe_number(per_m),
                     describe_number(l.c));
  if (l.d > 0.0) t += fmt::format(", damping d = {} N·s/m", describe_number(l.d));
  if (l.gap > 0.0) t += fmt::format(", slack {} m", describe_number(l.gap));
  if (l.third != kGround)
    t += fmt::format(", hung from the frame '{}'", m.bodies[static_cast<std::size_t>(l.third)].name);
  return t + "; tension only";
}

}  // namespace machdyn::detail
