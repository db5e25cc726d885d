#pragma once
/// @file
/// A rope's sheave losses as compile builds them (model/compile_sheaves.cpp; the reeving's law:
/// model/reeving.hpp). A rope with `sheave_efficiency` η < 1 whose rope ends each feed k = n/n_e > 1
/// parts becomes, between its drum and its hook:
///
///   drum ══ lossy gear NAME.sheaves (ratio i) ══ body NAME.sheaves (massless, m) ── rope spring ── hook
///
/// The loss is lumped at the drum side of the rope's spring: the body NAME.sheaves is the rope's end
/// at the drum in the hook's metres (q = q_drum / i, its speed the rope's speed over the sheaves in
/// hook metres), and the lossy gear (elements/lossy_gear.hpp: the law written once) joins it to the
/// drum with the reeving's two efficiencies, T_0 the force in the part at the drum, F the hook load:
///   drum drives (hoisting, power to the hook):   F = n η_r+ T_0,   η_mf1 = η_r+ = (1/k) Σ_{j<k} η^j
///   hook drives (lowering, the load overhauls):  T_0 = F / (n η_r−), η_mf2 = 1/η_r− = 1/((1/k) Σ_{j<k} η^−j)
/// (the balance of the parts over the sheaves, model/reeving.hpp). So hoisting at a steady speed
/// the drum needs the torque F/(i η_r+), lowering F/(i η_r−); at rest the gear sticks while the drum's
/// torque lies between the two (the band F (1/η_r− … 1/η_r+)/i, the sheaves' friction holding the
/// difference), and a change of the rope's direction over the sheaves is the gear's event. The loss
/// power (X − Y) v ≥ 0 is the gear's heat (the energy books' friction column, NAME.sheaves.loss_power_W).
/// The rope itself keeps its law (elements/link.hpp) from NAME.sheaves to the hook with ratio 1: its
/// deflection, stretch, slack, frame and wound length (L_f from NAME.sheaves' position) are those of
/// the ideal reeving. The names contain '.', so they never clash with a file's names.

#include <string>

#include "machdyn/model/model.hpp"

namespace machdyn {

/// The suffix of the massless body and the lossy gear of a rope's sheave losses.
inline constexpr const char* kSheavesSuffix = ".sheaves";

/// The lossy gear of rope l's sheave losses (index into Model::lossy_gears), or −1.
[[nodiscard]] int sheave_gear(const Model& m, const Link& l);
/// Whether lossy gear g, resp. body i, was built from a rope's sheave losses (not written in the file).
[[nodiscard]] bool is_sheave_gear(const Model& m, const LossyGear& g);
[[nodiscard]] bool is_sheave_body(const Model& m, int i);
/// The rope's drum (its body a as the file wrote it, the sheave gear's other body) and its ratio i
/// (drum angle per metre of hook travel, (n/n_e)/R), for a rope with or without sheave losses.
[[nodiscard]] int rope_drum(const Model& m, const Link& l);
[[nodiscard]] double rope_ratio(const Model& m, const Link& l);

}  // namespace machdyn
