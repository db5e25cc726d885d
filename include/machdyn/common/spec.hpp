#pragma once
/// @file
/// The spec: what an input file says, as a tree of text with the place of every value, before any
/// checking. Model files and gear spec files both read into it; `--set` edits it; the compilers
/// (model/compile.hpp, gears) turn it into validated, immutable objects and report every problem.

#include <cstddef>
#include <memory>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/units.hpp"

namespace machdyn {

/// A place in a spec, kept small because a spec holds one per value (a 10^6-point table has 3·10^6):
/// the source name is shared by every node of a file instead of copied. Converts to and from Location.
struct SpecLoc {
  std::shared_ptr<const std::string> file;
  int line = 0;
  int column = 0;
  SpecLoc() = default;
  SpecLoc(std::shared_ptr<const std::string> f, int l, int c) : file(std::move(f)), line(l), column(c) {}
  explicit SpecLoc(const Location& l)
      : file(std::make_shared<const std::string>(l.file)), line(l.line), column(l.column) {}
  operator Location() const { return {file ? *file : std::string(), line, column}; }  // NOLINT
  [[nodiscard]] std::string str() const { return Location(*this).str(); }
};

struct SpecField;

/// One value of the spec. A map keeps its fields in file order; keys are unique (the reader
/// rejects duplicates with a hashed set, so reading stays linear in the size of the file).
/// find() is a linear scan: it serves element maps of a few fields, not sections of 10^5 elements.
struct SpecNode {
  enum class Kind : unsigned char { Null, Scalar, Sequence, Map };
  Kind kind = Kind::Null;
  SpecLoc loc;      ///< where the value starts
  SpecLoc key_loc;  ///< where its key starts, for a value inside a map (else = loc)
  std::string scalar;             ///< Kind::Scalar
  std::vector<SpecNode> items;    ///< Kind::Sequence
  std::vector<SpecField> fields;  ///< Kind::Map, in file order

  [[nodiscard]] bool is_map() const { return kind == Kind::Map; }
  [[nodiscard]] bool is_seq() const { return kind == Kind::Sequence; }
  [[nodiscard]] bool is_scalar() const { return kind == Kind::Scalar; }
  [[nodiscard]] const SpecNode* find(std::string_view key) const;
  SpecNode* find(std::string_view key);
  /// Sets (or adds) a map field.
  void set(const std::string& key, SpecNode value);
  /// Removes a map field; false if there was none.
  bool erase(std::string_view key);
};

/// A key and its value. (A struct of its own rather than std::pair, which must not be instantiated
/// while SpecNode is incomplete: clang with libstdc++ rejects that.)
struct SpecField {
  std::string first;  ///< the key
  SpecNode second;    ///< the value
  SpecField(std::string k, SpecNode v) : first(std::move(k)), second(std::move(v)) {}
};

/// Reads the fields of one map node with checks, recording problems in `diag` instead of throwing.
/// `what` names the element in messages, e.g. "link 'c1'". Call finish() to report unknown keys.
class FieldReader {
 public:
  FieldReader(const SpecNode& map, std::string what, Diagnostics& diag);

  /// A quantity of dimension `d`. Without `fallback` the field is required.
  std::optional<double> quantity(std::string_view key, const Dim& d,
                                 std::optional<double> fallback = std::nullopt);
  /// Like quantity() with an extra check: value > 0 (or >= 0 when `allow_zero`).
  std::optional<double> positive(std::string_view key, const Dim& d,
                                 std::optional<double> fallback = std::nullopt, bool allow_zero = false);
  /// A word out of `allowed`.
  std::optional<std::string> word(std::string_view key, const std::vector<std::string>& allowed,
                                  std::optional<std::string> fallback = std::nullopt);
  /// Any scalar text (a name).
  std::optional<std::string> text(std::string_view key, std::optional<std::string> fallback = std::nullopt);
  /// A whole number in [lo, hi].
  std::optional<long> integer(std::string_view key, long lo, long hi, std::optional<long> fallback = std::nullopt);
  /// The raw node (marks the key used); nullptr if absent.
  const SpecNode* node(std::string_view key);
  /// Records an error at the field's value, or at the element if the field is absent.
  void error_at(std::string_view key, const std::string& message);
  /// Reports keys that no call above asked for, with the list of known keys.
  void finish();

  [[nodiscard]] const SpecNode& map() const { return map_; }
  [[nodiscard]] const std::string& what() const { return what_; }
  [[nodiscard]] Diagnostics& diagnostics() { return diag_; }

 private:
  const SpecNode* take(std::string_view key, bool required);
  const SpecNode& map_;
  std::string what_;
  Diagnostics& diag_;
  std::vector<std::string> known_;
};

}  // namespace machdyn
