#pragma once
/// @file
/// YAML input into the spec tree (common/spec.hpp), keeping the line and column of every value,
/// and the `--set NAME.FIELD=VALUE` overrides that edit it.

#include <cstddef>
#include <string>
#include <string_view>

#include "machdyn/common/spec.hpp"

namespace machdyn {

/// Limits on what a file may hold, each a located InputError when exceeded: nesting depth, values
/// (scalars, lists and maps together), and values copied by aliases (`*name`).
inline constexpr std::size_t kSpecMaxDepth = 64;
inline constexpr std::size_t kSpecMaxValues = 10'000'000;
inline constexpr std::size_t kSpecMaxAliasValues = 200'000;

/// Reads a YAML file. Throws InputError (with line and column) if it cannot be opened or parsed,
/// or if it exceeds a limit above. Anchors and aliases are expanded (a self-reference is an error).
SpecNode read_yaml_file(const std::string& path);

/// Parses YAML text; `source` names it in messages.
SpecNode parse_yaml_string(const std::string& text, const std::string& source);

/// Applies one command-line override `NAME.FIELD=VALUE` (or `FIELD=VALUE` for a top-level field).
/// NAME is a top-level map (e.g. `simulation`) or an element inside one of the top-level sections
/// (`bodies`, `links`, ...). VALUE is parsed as YAML (so `[[0,0],[1,5]]` gives a table). The new
/// value's location is "--set NAME.FIELD". Throws InputError if NAME is not found.
void apply_set(SpecNode& root, std::string_view assignment);

}  // namespace machdyn
