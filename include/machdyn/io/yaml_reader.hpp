#pragma once
/// @file
/// YAML input into the spec tree (common/spec.hpp), keeping the line and column of every value,
/// and the `--set NAME.FIELD=VALUE` overrides that edit it.

#include <string>
#include <string_view>

#include "machdyn/common/spec.hpp"

namespace machdyn {

/// Reads a YAML file. Throws InputError (with line and column) if it cannot be opened or parsed.
SpecNode read_yaml_file(const std::string& path);

/// Parses YAML text; `source` names it in messages.
SpecNode parse_yaml_string(const std::string& text, const std::string& source);

/// Applies one command-line override `NAME.FIELD=VALUE` (or `FIELD=VALUE` for a top-level field).
/// NAME is a top-level map (e.g. `simulation`) or an element inside one of the top-level sections
/// (`bodies`, `links`, ...). VALUE is parsed as YAML (so `[[0,0],[1,5]]` gives a table). The new
/// value's location is "--set NAME.FIELD". Throws InputError if NAME is not found.
void apply_set(SpecNode& root, std::string_view assignment);

}  // namespace machdyn
