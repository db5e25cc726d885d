#pragma once
/// @file
/// Ideal gears (`type: ideal-gear` under links): rigid connections q_a = i q_b resolved when the model
/// compiles. The connected bodies become one degree of freedom in the coordinate of a master body;
/// every consumer downstream sees an ordinary model (model.hpp: RigidSlave, Load::ratio).

#include <string>
#include <unordered_set>
#include <vector>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

/// An ideal gear as read from the file: q_a = ratio · q_b (ratio = ω_a/ω_b, nonzero; negative
/// reverses; [q_a]/[q_b], e.g. rad/m for a rope drum with ratio 1/R).
struct IdealGear {
  std::string name;
  int a = 0, b = 0;       ///< body indices (never the ground)
  double ratio = 1.0;
  Location where;         ///< the gear's key
  Location ratio_where;   ///< its ratio (or the key)
};

/// Reads the fields of an ideal gear `name` (between, ratio) into `out`; errors are located.
void read_ideal_gear(const std::string& name, const SpecNode& spec, const Model& m, std::vector<IdealGear>& out,
                     Diagnostics& diag);

/// Merges the bodies tied by `gears` into one body per rigid group (the master: the group's body with
/// a prescribed motion, else its first body in the file; two prescribed members are an error), re-attaches loads and links of the slaved bodies, checks initial conditions,
/// ratios around loops and massless bodies, and fills m.slaves. `bodies` is the file's `bodies:`
/// section (for the places of positions and velocities). `massless_ok`: bodies that may have zero
/// inertia without an ideal gear (a joint eliminates them: model/compile_joint.hpp). Call after
/// every element is compiled.
void resolve_rigid(Model& m, const std::vector<IdealGear>& gears, const SpecNode* bodies,
                   const std::unordered_set<std::string>& massless_ok, Diagnostics& diag);

/// The place of field `key` of body `name` in the `bodies:` section, if the file gives it.
const SpecNode* body_field(const SpecNode* bodies, const std::string& name, const char* key);
/// Whether an initial value x given in the file agrees with the value y a rigid connection implies:
/// within 1e-9 relative, 1e-12 absolute.
bool initial_values_agree(double x, double y);

}  // namespace machdyn::detail
