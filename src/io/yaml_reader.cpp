#include "machdyn/io/yaml_reader.hpp"

#include <fstream>
#include <sstream>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/yaml.h>

namespace machdyn {
namespace {

Location loc_of(const YAML::Mark& m, const std::string& source) {
  if (m.line < 0) return {source, 0, 0};
  return {source, m.line + 1, m.column + 1};
}

SpecNode convert(const YAML::Node& n, const std::string& source, Diagnostics& diag) {
  SpecNode out;
  out.loc = out.key_loc = loc_of(n.Mark(), source);
  switch (n.Type()) {
    case YAML::NodeType::Scalar:
      out.kind = SpecNode::Kind::Scalar;
      out.scalar = n.Scalar();
      break;
    case YAML::NodeType::Sequence:
      out.kind = SpecNode::Kind::Sequence;
      for (const auto& item : n) out.items.push_back(convert(item, source, diag));
      break;
    case YAML::NodeType::Map:
      out.kind = SpecNode::Kind::Map;
      for (const auto& kv : n) {
        if (!kv.first.IsScalar()) {
          diag.error(loc_of(kv.first.Mark(), source), "expected a plain name as a key");
          continue;
        }
        std::string key = kv.first.Scalar();
        if (out.find(key)) {
          diag.error(loc_of(kv.first.Mark(), source), fmt::format("duplicate key '{}'", key));
          continue;
        }
        SpecNode value = convert(kv.second, source, diag);
        value.key_loc = loc_of(kv.first.Mark(), source);
        out.fields.emplace_back(key, std::move(value));
      }
      break;
    default:
      out.kind = SpecNode::Kind::Null;
  }
  return out;
}

}  // namespace

SpecNode parse_yaml_string(const std::string& text, const std::string& source) {
  YAML::Node doc;
  try {
    doc = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw InputError(loc_of(e.mark, source), fmt::format("invalid YAML: {}", e.msg));
  }
  Diagnostics diag;
  SpecNode root = convert(doc, source, diag);
  diag.throw_if_any();
  return root;
}

SpecNode read_yaml_file(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw InputError(Location{path, 0, 0}, "cannot open the file");
  std::stringstream ss;
  ss << in.rdbuf();
  return parse_yaml_string(ss.str(), path);
}

void apply_set(SpecNode& root, std::string_view assignment) {
  const Location cli{fmt::format("--set {}", assignment), 0, 0};
  auto eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0)
    throw InputError(cli, "expected NAME.FIELD=VALUE");
  std::string path(assignment.substr(0, eq));
  std::string value_text(assignment.substr(eq + 1));
  SpecNode value = parse_yaml_string(value_text, cli.file);
  auto set_loc = [&](auto&& self, SpecNode& n) -> void {
    n.loc = n.key_loc = Location{fmt::format("--set {}", path), 0, 0};
    for (auto& i : n.items) self(self, i);
    for (auto& [k, f] : n.fields) self(self, f);
  };
  set_loc(set_loc, value);

  auto dot = path.find('.');
  if (dot == std::string::npos) {  // a top-level field
    if (!root.is_map()) throw InputError(cli, "the file has no top-level map to override");
    root.set(path, std::move(value));
    return;
  }
  std::string name = path.substr(0, dot), field = path.substr(dot + 1);
  if (field.empty() || name.empty()) throw InputError(cli, "expected NAME.FIELD=VALUE");
  if (auto* top = root.find(name); top && top->is_map()) {
    top->set(field, std::move(value));
    return;
  }
  if (!root.find(name)) {
    std::vector<std::string> names;
    for (auto& [section, node] : root.fields) {
      if (!node.is_map()) continue;
      for (auto& [elem, body] : node.fields) {
        if (!body.is_map()) continue;
        names.push_back(elem);
        if (elem == name) {
          body.set(field, std::move(value));
          return;
        }
      }
    }
    throw InputError(cli, fmt::format("no element named '{}'; the model has: {}", name,
                                      fmt::join(names, ", ")));
  }
  // A top-level scalar with a dotted path: create the map.
  SpecNode m;
  m.kind = SpecNode::Kind::Map;
  m.loc = value.loc;
  m.set(field, std::move(value));
  root.set(name, std::move(m));
}

}  // namespace machdyn
