#pragma once
/// @file
/// Named load cases in a model file (paper 002's operating modes). A case is a patch of the spec:
///   cases:
///     NAME:
///       description: text
///       remove: [element, ...]                  # drop elements of any section (e.g. the motor)
///       bodies|links|loads|contacts|brakes: {ELEMENT: {field: value, ...}, ...}
///       simulation: {field: value, ...}
/// An element that exists gets the case's fields (field by field); a new one is added. Changing an
/// element's `type` keeps its other fields, so replace it (remove + a new name) instead.

#include <string>
#include <vector>

#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// A case name becomes the folder OUT/NAME of its results and a cell of tables, so it must be one
/// plain name: not empty, not "." or "..", no '/' or '\\', no control character, at most this many
/// bytes (a file name's limit is 255).
inline constexpr std::size_t kMaxCaseNameBytes = 128;

/// Why `name` cannot be a case name ("is empty", "contains '/', a path separator", ...), or "".
std::string case_name_problem(const std::string& name);

/// The case names in file order (empty if the file has no `cases:`).
std::vector<std::string> case_names(const SpecNode& root);

/// Applies case `name` to the spec and removes its `cases:` section (the result is a plain model;
/// compile_model checks every case of a file that still has them). Throws InputError if there is no
/// such case, its name is not a plain name (case_name_problem, located at the name in the file) or
/// the case is malformed (with the place of each problem).
void apply_case(SpecNode& root, const std::string& name);

// Reading a model file with a case: load_model_case in io/model_file.hpp.


}  // namespace machdyn
