#include "machdyn/model/cases.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "machdyn/model/compile.hpp"

namespace machdyn {
namespace {

/// The name as it may be printed on one line: control characters as \xNN, at most 80 bytes.
std::string printable(const std::string& name) {
  std::string out;
  for (const char ch : name.substr(0, 80)) {
    const auto u = static_cast<unsigned char>(ch);
    out += u < 0x20 || u == 0x7f ? fmt::format("\\x{:02x}", u) : std::string(1, ch);
  }
  return name.size() > 80 ? out + "..." : out;
}

}  // namespace

std::vector<std::string> case_names(const SpecNode& root) {
  std::vector<std::string> out;
  const SpecNode* cases = root.is_map() ? root.find("cases") : nullptr;
  if (cases && cases->is_map())
    for (const auto& [k, v] : cases->fields) out.push_back(k);
  return out;
}

std::string case_name_problem(const std::string& name) {
  if (name.empty()) return "is empty";
  if (name == "." || name == "..") return fmt::format("is '{}', a folder of its own", name);
  if (name.size() > kMaxCaseNameBytes) return fmt::format("has {} bytes, more than {}", name.size(), kMaxCaseNameBytes);
  for (const char ch : name) {
    if (ch == '/' || ch == '\\') return fmt::format("contains '{}', a path separator", ch);
    if (static_cast<unsigned char>(ch) < 0x20 || ch == 0x7f) return "contains a control character (newline, tab, NUL, ...)";
  }
  return {};
}

void apply_case(SpecNode& root, const std::string& name) {
  const Location cli{fmt::format("--case {}", name), 0, 0};
  SpecNode* cases = root.is_map() ? root.find("cases") : nullptr;
  if (!cases || !cases->is_map()) throw InputError(cli, "the model file has no 'cases:' section");
  const SpecNode* c = cases->find(name);
  if (!c)
    throw InputError(cli, fmt::format("no case named '{}'; the file has: {}", name, fmt::join(case_names(root), ", ")));
  // The name becomes a folder (OUT/NAME) and a table cell: it must be one plain name.
  if (const std::string problem = case_name_problem(name); !problem.empty())
    throw InputError(Location(c->key_loc), fmt::format("case '{}': the name {}; a case name becomes the folder OUT/NAME of its "
                                             "results, so it must be a plain name (no '/', '\\', control characters, "
                                             "not '.' or '..', at most {} bytes)",
                                             printable(name), problem, kMaxCaseNameBytes));
  const SpecNode patch = *c;  // copy: root is edited below
  Diagnostics diag;
  if (!patch.is_map()) {
    diag.error(patch.loc, fmt::format("case '{}': expected a map of sections", name));
    diag.throw_if_any();
  }
  for (const auto& [section, body] : patch.fields) {
    if (section == "description") continue;
    if (section == "remove") {
      if (!body.is_seq()) {
        diag.error(body.loc, fmt::format("case '{}': 'remove' expected a list of element names", name));
        continue;
      }
      for (const auto& item : body.items) {
        bool found = false;
        for (const auto& sec : element_sections()) {
          SpecNode* s = root.find(sec);
          if (!s || !s->is_map()) continue;
          if (s->erase(item.scalar)) found = true;
        }
        if (!found) diag.error(item.loc, fmt::format("case '{}': cannot remove '{}': no such element", name, item.scalar));
      }
      continue;
    }
    if (section == "crane") {  // the crane analysis of this case: fields replaced one by one, or `none`
      if (body.is_scalar() && (body.scalar == "none" || body.scalar == "off")) {
        root.erase("crane");
        continue;
      }
      if (!body.is_map()) {
        diag.error(body.loc, fmt::format("case '{}': 'crane' expected a map of fields (replaced one by one) or 'none' "
                                         "(no crane analysis in this case)", name));
        continue;
      }
    }
    const bool is_sim = section == "simulation" || section == "crane";
    if (!is_sim && std::find(element_sections().begin(), element_sections().end(), section) == element_sections().end()) {
      diag.error(body.key_loc, fmt::format("case '{}': unknown section '{}'; known: description, remove, {}, simulation, crane",
                                           name, section, fmt::join(element_sections(), ", ")));
      continue;
    }
    if (!body.is_map()) {
      diag.error(body.loc, fmt::format("case '{}': '{}' expected a map", name, section));
      continue;
    }
    SpecNode* target = root.find(section);
    if (!target) {
      SpecNode empty;
      empty.kind = SpecNode::Kind::Map;
      empty.loc = empty.key_loc = body.loc;
      root.set(section, empty);
      target = root.find(section);
    }
    if (!target->is_map()) continue;  // the compiler reports it
    if (is_sim) {
      for (const auto& [k, v] : body.fields) target->set(k, v);
      continue;
    }
    for (const auto& [elem, fields] : body.fields) {
      SpecNode* e = target->find(elem);
      if (!e || !e->is_map() || !fields.is_map()) {
        target->set(elem, fields);
        continue;
      }
      for (const auto& [k, v] : fields.fields) e->set(k, v);
    }
  }
  diag.throw_if_any();
  root.erase("cases");  // applied: the result is a plain model (compile checks no other case of it)
}

}  // namespace machdyn
