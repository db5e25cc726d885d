#pragma once
/// @file
/// A rope's sheave losses as a lossy gear at its drum (model/sheaves.hpp states the design).

#include <vector>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/model/model.hpp"
#include "model/compile_lossy.hpp"

namespace machdyn::detail {

/// For every rope of `m` with sheave losses (η < 1, k = n/n_e > 1): appends the massless body
/// NAME.sheaves (the rope's end at the drum, in the hook's coordinate), a lossy gear NAME.sheaves
/// from the drum to it with the reeving's efficiencies (model/reeving.hpp) to `lossy`, and moves the
/// rope's first end onto that body with ratio 1. What the lossy gear does not support around the drum
/// is a located error at the rope. Runs after the links are read, before anything refers to the bodies
/// by index beyond them.
void add_sheave_losses(Model& m, std::vector<LossyGearSpec>& lossy, Diagnostics& diag);

}  // namespace machdyn::detail
