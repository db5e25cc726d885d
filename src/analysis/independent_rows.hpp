#pragma once
/// @file
/// Which constraint rows add a constraint (private to the quasi-static load and the equilibrium
/// start): two brakes on one drum, or a clutch beside a brake on the same body, add one row, and a
/// bordered system with both would be singular.

#include <cstddef>
#include <vector>

#include "machdyn/analysis/static_loads.hpp"

namespace machdyn::detail {

/// The indices of the rows of `rows` that raise the rank of `before` and of the rows kept ahead of
/// them, in order: a dense elimination (FullPivLU, threshold 1e-10) over the bodies the rows touch,
/// so its cost follows the few held elements, not the model's size.
std::vector<size_t> independent_rows(const ConstraintRows& before, const ConstraintRows& rows);

}  // namespace machdyn::detail
