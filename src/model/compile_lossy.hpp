#pragma once
/// @file
/// Lossy gears (`type: lossy-gear` under links; model/model.hpp LossyGear, law in
/// elements/lossy_gear.hpp): read with the links, resolved onto the bodies after the ideal-gear merge.

#include <string>
#include <vector>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn::detail {

/// A lossy gear as read from the file: the names of its bodies, its loss data (in A's coordinate).
struct LossyGearSpec {
  LossyGear gear;               ///< a, b, ratio still the file's (body indices before the merge)
  std::string body_a, body_b;   ///< the file's names
  Location where;               ///< the gear's key
};

/// Reads the fields of lossy gear `name` (between, ratio, efficiency, efficiency_reverse,
/// bearing_friction, bearing_friction_reverse, or loss_table); errors are located.
void read_lossy_gear(const std::string& name, const SpecNode& spec, const Model& m, std::vector<LossyGearSpec>& out,
                     Diagnostics& diag);

/// Puts the gears on the bodies left by the ideal-gear merge (ratio and speeds through ρ of slaved
/// ends), checks what the law does not support (both ends one rigid group, a body in three lossy gears
/// or a train of more than two, contacts on its bodies or on a two-stage train's) and the initial
/// velocities v_a = i v_b (across a two-stage train too), and fills m.lossy_gears.
void resolve_lossy(Model& m, const std::vector<LossyGearSpec>& gears, Diagnostics& diag);

}  // namespace machdyn::detail
