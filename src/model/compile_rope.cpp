#include "compile_rope.hpp"
#include "machdyn/model/describe.hpp"

#include <optional>

#include <fmt/format.h>

namespace machdyn::detail {

bool compile_rope_length(FieldReader& f, Link& l, const Dim& ld, const Dim& qd, BodyKind side,
                         const std::vector<Body>& bodies) {
  const SpecNode& map = f.map();
  const bool is_map = map.is_map();
  auto has = [&](const char* k) { return is_map && map.find(k) != nullptr; };
  l.falls = static_cast<int>(f.integer("falls", 1, 1000, 1).value_or(1));
  if (l.falls > 1 && l.a != kGround) l.ratio *= l.falls;  // drum 1/R → n/R: drum angle per metre of hook travel
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
  const double n = l.falls, per_m = shown_ratio(m, l) / n;  // the file's drum ratio 1/R, rad/m
  std::string t = fmt::format("{} fall{}", l.falls, l.falls == 1 ? "" : "s");
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
  return t + "; tension only";
}

}  // namespace machdyn::detail
