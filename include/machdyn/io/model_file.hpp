#pragma once
/// @file
/// Reading a model file into a compiled Model: YAML → spec tree (io/yaml_reader.hpp), a load case
/// (model/cases.hpp), `--set` overrides, included gear spec files (`gears: FILE` of a gear-drive
/// body) and measured signals (`type: file`, io/signal_files.hpp), then compile (model/compile.hpp). The model layer reads no files; this is where they are read.

#include <string>
#include <vector>

#include "machdyn/common/spec.hpp"
#include "machdyn/model/model.hpp"

namespace machdyn {

/// Replaces every `gears: FILE` of a body (in `bodies:` and in each case's `bodies:`) by the gear spec
/// that FILE holds, read as YAML. FILE is relative to the file the value came from (the model file;
/// the working directory for a `--set` value). Records in `diag` each field whose file cannot be
/// read, with its place (the field is left as it is); a problem inside an included file carries
/// that file's place.
void resolve_gear_includes(SpecNode& root, Diagnostics& diag);
/// As above; throws InputError with every problem found.
void resolve_gear_includes(SpecNode& root);

/// Reads `path`, applies the `--set` overrides in order, reads included gear specs, compiles.
/// Throws InputError.
Model load_model(const std::string& path, const std::vector<std::string>& overrides = {});

/// Reads `path`, applies case `case_name` (if not empty), then the `--set` overrides, reads included
/// gear specs, compiles. The model's name gets " [case]" appended and Model::load_case is set.
Model load_model_case(const std::string& path, const std::vector<std::string>& overrides,
                      const std::string& case_name);

/// The same for a spec already read (a file's or a string's; `source` names it in messages and in
/// Model::source): applies the case, then the overrides, reads included gear specs, compiles.
/// Throws InputError with every problem found.
Model compile_model_case(SpecNode root, const std::string& source, const std::vector<std::string>& overrides,
                         const std::string& case_name);

}  // namespace machdyn
