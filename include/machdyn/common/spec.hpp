#pragma once
/// @file
/// The spec: what an input file says, as a tree of text with the place of every value, before any
/// checking. Model files and gear spec files both read into it; `--set` edits it; the compilers
/// (model/compile.hpp, gears) turn it into validated, immutable objects and report every problem.

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/units.hpp"

namespace machdyn {

struct SpecNode {
  enum class Kind { Null, Scalar, Sequence, Map };
  Kind kind = Kind::Null;
  Location loc;      ///< where the value starts
  Location key_loc;  ///< where its key starts, for a value inside a map (else = loc)
  std::string scalar;                                    ///< Kind::Scalar
  std::vector<SpecNode> items;                           ///< Kind::Sequence
  std::vector<std::pair<std::string, SpecNode>> fields;  ///< Kind::Map, in file order

  [[nodiscard]] bool is_map() const { return kind == Kind::Map; }
  [[nodiscard]] bool is_seq() const { return kind == Kind::Sequence; }
  [[nodiscard]] bool is_scalar() const { return kind == Kind::Scalar; }
  [[nodiscard]] const SpecNode* find(std::string_view key) const;
  SpecNode* find(std::string_view key);
  /// Sets (or adds) a map field.
  void set(const std::string& key, SpecNode value);
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
