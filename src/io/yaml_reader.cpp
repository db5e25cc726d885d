#include "machdyn/io/yaml_reader.hpp"

#include "machdyn/io/input_file.hpp"

#include <fstream>
#include <sstream>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

namespace machdyn {
namespace {

/// Builds the spec tree straight from the parser's events (no yaml-cpp node graph, which costs
/// several hundred bytes per value), with the limits that keep hostile files from exhausting the
/// stack or memory: nesting depth, node count, and alias expansion (a "billion laughs" file grows
/// exponentially through anchors of anchors; `&x [*x]` refers to itself). Each limit is a located
/// InputError.
class SpecBuilder final : public YAML::EventHandler {
 public:
  explicit SpecBuilder(const std::string& source) : source_(std::make_shared<const std::string>(source)) {}

  SpecNode take_root() {
    // An empty document is a null value at the start of the file: errors about it still have a place.
    if (!root_.loc.file) root_.loc = root_.key_loc = SpecLoc(source_, 1, 1);
    return std::move(root_);
  }
  Diagnostics& diagnostics() { return diag_; }

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    SpecNode n;
    n.loc = n.key_loc = loc_of(mark);
    count(mark, 1);
    finish(std::move(n), anchor, 1);
  }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t anchor) override {
    auto it = anchors_.find(anchor);
    if (it == anchors_.end())  // its anchor is still open: the node would contain itself
      fail(mark, "an alias refers to a node that contains it (a self-reference); expected a finished anchor");
    aliased_ += it->second.second;
    if (aliased_ > kSpecMaxAliasValues)
      fail(mark, fmt::format("aliases expand to more than {} values; expected a file without nested alias "
                             "expansion (a \"billion laughs\" file?)", kSpecMaxAliasValues));
    count(mark, it->second.second);
    finish(SpecNode(it->second.first), 0, it->second.second);
  }
  void OnScalar(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                const std::string& value) override {
    SpecNode n;
    n.kind = SpecNode::Kind::Scalar;
    n.loc = n.key_loc = loc_of(mark);
    n.scalar = value;
    count(mark, 1);
    finish(std::move(n), anchor, 1);
  }
  void OnSequenceStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                       YAML::EmitterStyle::value) override {
    open(mark, SpecNode::Kind::Sequence, anchor);
  }
  void OnSequenceEnd() override { close(); }
  void OnMapStart(const YAML::Mark& mark, const std::string&, YAML::anchor_t anchor,
                  YAML::EmitterStyle::value) override {
    open(mark, SpecNode::Kind::Map, anchor);
  }
  void OnMapEnd() override { close(); }

 private:
  struct Frame {
    SpecNode node;
    YAML::anchor_t anchor = 0;
    std::size_t first_count = 0;  ///< nodes_ when the frame opened: its size is the difference
    bool want_key = true;         ///< Kind::Map: the next finished node is a key
    bool key_ok = false;          ///< the pending key is a usable, new name
    std::string key;
    SpecLoc key_loc;
    std::unordered_set<std::string> keys;  ///< for duplicate keys in O(1)
  };

  SpecLoc loc_of(const YAML::Mark& m) const {
    if (m.line < 0) return {source_, 0, 0};
    return {source_, m.line + 1, m.column + 1};
  }
  [[noreturn]] void fail(const YAML::Mark& mark, const std::string& what) const {
    throw InputError(loc_of(mark), what);
  }
  void count(const YAML::Mark& mark, std::size_t n) {
    nodes_ += n;
    if (nodes_ > kSpecMaxValues)
      fail(mark, fmt::format("the file has more than {} values; expected a smaller model (split long tables?)",
                             kSpecMaxValues));
  }
  void open(const YAML::Mark& mark, SpecNode::Kind kind, YAML::anchor_t anchor) {
    if (stack_.size() >= kSpecMaxDepth)
      fail(mark, fmt::format("the file is nested deeper than {} levels; expected a value (a number, a name) "
                             "instead of another '[' / '{{' / indented block", kSpecMaxDepth));
    count(mark, 1);
    Frame f;
    f.node.kind = kind;
    f.node.loc = f.node.key_loc = loc_of(mark);
    f.anchor = anchor;
    f.first_count = nodes_;
    stack_.push_back(std::move(f));
  }
  void close() {
    Frame f = std::move(stack_.back());
    stack_.pop_back();
    f.node.items.shrink_to_fit();
    f.node.fields.shrink_to_fit();
    finish(std::move(f.node), f.anchor, 1 + nodes_ - f.first_count);
  }
  /// A node is complete: remember it under its anchor, then hand it to its parent.
  void finish(SpecNode n, YAML::anchor_t anchor, std::size_t size) {
    if (anchor != 0) anchors_.insert_or_assign(anchor, std::make_pair(n, size));
    if (stack_.empty()) {
      root_ = std::move(n);
      return;
    }
    Frame& p = stack_.back();
    if (p.node.is_seq()) {
      p.node.items.push_back(std::move(n));
      return;
    }
    if (p.want_key) {
      p.want_key = false;
      p.key_ok = false;
      p.key_loc = n.loc;
      if (!n.is_scalar()) {
        diag_.error(n.loc, "expected a plain name as a key");
      } else if (!p.keys.insert(n.scalar).second) {
        diag_.error(n.loc, fmt::format("duplicate key '{}'", n.scalar));
      } else {
        p.key_ok = true;
        p.key = std::move(n.scalar);
      }
      return;
    }
    p.want_key = true;
    if (!p.key_ok) return;
    n.key_loc = p.key_loc;
    p.node.fields.emplace_back(std::move(p.key), std::move(n));
  }

  std::shared_ptr<const std::string> source_;
  std::vector<Frame> stack_;
  std::unordered_map<YAML::anchor_t, std::pair<SpecNode, std::size_t>> anchors_;
  std::size_t nodes_ = 0, aliased_ = 0;
  SpecNode root_;
  Diagnostics diag_;
};

}  // namespace

SpecNode parse_yaml_string(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  SpecBuilder builder(source);
  try {
    YAML::Parser parser(in);
    parser.HandleNextDocument(builder);
  } catch (const YAML::Exception& e) {
    Location at{source, e.mark.line < 0 ? 0 : e.mark.line + 1, e.mark.line < 0 ? 0 : e.mark.column + 1};
    throw InputError(at, fmt::format("invalid YAML: {}", e.msg));
  }
  builder.diagnostics().throw_if_any();
  return builder.take_root();
}

SpecNode read_yaml_file(const std::string& path) {
  return parse_yaml_string(read_input_file(path, kMaxModelFileBytes, "file"), path);
}

namespace {
/// Sets FIELD (or a dotted path into nested maps, `release.time`) of the map `m`; missing maps on
/// the way are created, a scalar on the way is an error.
void set_field(SpecNode& m, const std::string& field, SpecNode value, const Location& cli) {
  const auto dot = field.find('.');
  if (dot == std::string::npos) {
    m.set(field, std::move(value));
    return;
  }
  const std::string key = field.substr(0, dot), rest = field.substr(dot + 1);
  if (key.empty() || rest.empty()) throw InputError(cli, "expected NAME.FIELD=VALUE (an empty name between dots)");
  SpecNode* child = m.find(key);
  if (!child) {
    SpecNode fresh;
    fresh.kind = SpecNode::Kind::Map;
    fresh.loc = value.loc;
    m.set(key, std::move(fresh));
    child = m.find(key);
  }
  if (!child->is_map())
    throw InputError(cli, fmt::format("'{}' is not a map of fields, so it has no field '{}'", key, rest));
  set_field(*child, rest, std::move(value), cli);
}
}  // namespace

void apply_set(SpecNode& root, std::string_view assignment) {
  const Location cli{fmt::format("--set {}", assignment), 0, 0};
  auto eq = assignment.find('=');
  if (eq == std::string_view::npos || eq == 0)
    throw InputError(cli, "expected NAME.FIELD=VALUE");
  std::string path(assignment.substr(0, eq));
  std::string value_text(assignment.substr(eq + 1));
  SpecNode value = parse_yaml_string(value_text, cli.file);
  const SpecLoc at(Location{fmt::format("--set {}", path), 0, 0});
  auto set_loc = [&](auto&& self, SpecNode& n) -> void {
    n.loc = n.key_loc = at;
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
    set_field(*top, field, std::move(value), cli);
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
          set_field(body, field, std::move(value), cli);
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
  set_field(m, field, std::move(value), cli);
  root.set(name, std::move(m));
}

}  // namespace machdyn
