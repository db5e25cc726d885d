#include "machdyn/io/model_file.hpp"

#include <algorithm>
#include <filesystem>
#include <set>
#include <tuple>
#include <fmt/format.h>

#include "machdyn/io/signal_files.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/cases.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn {
namespace {

/// Errors listed one by one before the rest are counted (compile_model_case).
constexpr size_t kMaxListedErrors = 100;

void resolve_in_bodies(SpecNode* bodies, Diagnostics& diag) {
  if (!bodies || !bodies->is_map()) return;
  for (auto& [name, body] : bodies->fields) {
    SpecNode* g = body.is_map() ? body.find("gears") : nullptr;
    if (!g || !g->is_scalar()) continue;
    std::filesystem::path path(g->scalar);
    const Location at = g->loc;
    // Relative to the file the value is written in; a `--set` value has no file.
    if (path.is_relative() && !at.file.empty() && at.file.rfind("--", 0) != 0)
      path = std::filesystem::path(at.file).parent_path() / path;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
      diag.error(at, fmt::format("body '{}': field 'gears': cannot open the gear spec '{}' (looked for {})", name,
                                 g->scalar, path.string()));
      continue;
    }
    try {
      SpecNode spec = read_yaml_file(path.string());
      spec.key_loc = g->key_loc;
      *g = std::move(spec);
    } catch (const InputError& e) {
      for (const auto& d : e.diagnostics()) diag.error(d.where, d.message);
    }
  }
}

}  // namespace

void resolve_gear_includes(SpecNode& root, Diagnostics& diag) {
  if (!root.is_map()) return;
  resolve_in_bodies(root.find("bodies"), diag);
  if (SpecNode* cases = root.find("cases"); cases && cases->is_map())
    for (auto& [name, c] : cases->fields)
      if (c.is_map()) resolve_in_bodies(c.find("bodies"), diag);
}

void resolve_gear_includes(SpecNode& root) {
  Diagnostics diag;
  resolve_gear_includes(root, diag);
  diag.throw_if_any();
}

Model load_model(const std::string& path, const std::vector<std::string>& overrides) {
  return load_model_case(path, overrides, "");
}

Model load_model_case(const std::string& path, const std::vector<std::string>& overrides,
                      const std::string& case_name) {
  return compile_model_case(read_yaml_file(path), path, overrides, case_name);
}

Model compile_model_case(SpecNode root, const std::string& source, const std::vector<std::string>& overrides,
                         const std::string& case_name) {
  if (!case_name.empty()) apply_case(root, case_name);
  for (const auto& o : overrides) apply_set(root, o);
  // Every problem at once: those of reading included files and those of compiling, one per place
  // (a file that could not be read is not reported again as an unread `gears:` by the compiler).
  Diagnostics diag;
  resolve_gear_includes(root, diag);
  resolve_signal_files(root, diag);
  Model m;
  try {
    m = compile_model(root, source);
  } catch (const InputError& e) {
    std::set<std::tuple<std::string, int, int>> seen;  // a set: a file may have 10^6 bad values
    for (const Diagnostic& r : diag.list()) seen.emplace(r.where.file, r.where.line, r.where.column);
    const bool read_errors = !diag.empty();
    for (const Diagnostic& d : e.diagnostics()) {
      // A signal file that could not be read is reported above, at its `path`, not again as unread.
      const bool unread_file = read_errors && d.message.find("'file' signal is read when") != std::string::npos;
      if (seen.emplace(d.where.file, d.where.line, d.where.column).second && !unread_file) diag.error(d.where, d.message);
    }
  }
  // Every problem, but not a flood: a table of 10^6 decreasing times is the first kMaxListedErrors
  // and a count of the rest.
  if (diag.list().size() > kMaxListedErrors) {
    Diagnostics first;
    for (size_t i = 0; i < kMaxListedErrors; ++i) first.error(diag.list()[i].where, diag.list()[i].message);
    first.error(Location{source, 0, 0}, fmt::format("... and {} more errors", diag.list().size() - kMaxListedErrors));
    first.throw_if_any();
  }
  diag.throw_if_any();
  if (!case_name.empty()) {
    m.load_case = case_name;
    m.name += " [" + case_name + "]";
  }
  return m;
}

}  // namespace machdyn
