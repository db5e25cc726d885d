#include "machdyn/common/spec.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <fmt/ranges.h>


namespace machdyn {

const SpecNode* SpecNode::find(std::string_view key) const {
  for (const auto& [k, v] : fields)
    if (k == key) return &v;
  return nullptr;
}

SpecNode* SpecNode::find(std::string_view key) {
  for (auto& [k, v] : fields)
    if (k == key) return &v;
  return nullptr;
}

void SpecNode::set(const std::string& key, SpecNode value) {
  if (auto* v = find(key)) *v = std::move(value);
  else fields.emplace_back(key, std::move(value));
}

bool SpecNode::erase(std::string_view key) {
  auto it = std::find_if(fields.begin(), fields.end(), [&](const SpecField& f) { return f.first == key; });
  if (it == fields.end()) return false;
  fields.erase(it);
  return true;
}

FieldReader::FieldReader(const SpecNode& map, std::string what, Diagnostics& diag)
    : map_(map), what_(std::move(what)), diag_(diag) {
  if (!map.is_map()) diag_.error(map.loc, fmt::format("{}: expected a map of fields", what_));
}

const SpecNode* FieldReader::take(std::string_view key, bool required) {
  known_.emplace_back(key);
  const SpecNode* n = map_.is_map() ? map_.find(key) : nullptr;
  if (!n && required && map_.is_map())
    diag_.error(map_.loc, fmt::format("{}: missing field '{}'", what_, key));
  return n;
}

const SpecNode* FieldReader::node(std::string_view key) { return take(key, false); }

void FieldReader::error_at(std::string_view key, const std::string& message) {
  const SpecNode* n = map_.is_map() ? map_.find(key) : nullptr;
  diag_.error(n ? n->loc : map_.loc, fmt::format("{}: {}", what_, message));
}

std::optional<double> FieldReader::quantity(std::string_view key, const Dim& d,
                                            std::optional<double> fallback) {
  const SpecNode* n = take(key, !fallback.has_value());
  if (!n) return fallback;
  if (!n->is_scalar()) {
    diag_.error(n->loc, fmt::format("{}: field '{}' expected {}", what_, key, describe(d)));
    return std::nullopt;
  }
  std::string err;
  auto v = parse_as(n->scalar, d, &err);
  if (!v) diag_.error(n->loc, fmt::format("{}: field '{}': {}", what_, key, err));
  return v;
}

std::optional<double> FieldReader::positive(std::string_view key, const Dim& d,
                                            std::optional<double> fallback, bool allow_zero) {
  auto v = quantity(key, d, fallback);
  if (v && (allow_zero ? *v < 0.0 : *v <= 0.0)) {
    error_at(key, fmt::format("field '{}' must be {}, got {}", key,
                              allow_zero ? "zero or positive" : "positive", *v));
    return std::nullopt;
  }
  return v;
}

std::optional<std::string> FieldReader::word(std::string_view key, const std::vector<std::string>& allowed,
                                             std::optional<std::string> fallback) {
  auto t = text(key, fallback);
  if (t && std::find(allowed.begin(), allowed.end(), *t) == allowed.end()) {
    error_at(key, fmt::format("field '{}' is '{}'; expected one of: {}", key, *t, fmt::join(allowed, ", ")));
    return std::nullopt;
  }
  return t;
}

std::optional<std::string> FieldReader::text(std::string_view key, std::optional<std::string> fallback) {
  const SpecNode* n = take(key, !fallback.has_value());
  if (!n) return fallback;
  if (!n->is_scalar()) {
    diag_.error(n->loc, fmt::format("{}: field '{}' expected a single word", what_, key));
    return std::nullopt;
  }
  return n->scalar;
}

std::optional<long> FieldReader::integer(std::string_view key, long lo, long hi, std::optional<long> fallback) {
  const SpecNode* n = take(key, !fallback.has_value());
  if (!n) return fallback;
  char* end = nullptr;
  long v = n->is_scalar() ? std::strtol(n->scalar.c_str(), &end, 10) : 0;
  if (!n->is_scalar() || end == n->scalar.c_str() || *end != '\0' || v < lo || v > hi) {
    diag_.error(n->loc, fmt::format("{}: field '{}' expected a whole number from {} to {}", what_, key, lo, hi));
    return std::nullopt;
  }
  return v;
}

void FieldReader::finish() {
  if (!map_.is_map()) return;
  for (const auto& [k, v] : map_.fields)
    if (std::find(known_.begin(), known_.end(), k) == known_.end())
      diag_.error(v.key_loc, fmt::format("{}: unknown field '{}'; known fields: {}", what_, k, fmt::join(known_, ", ")));
}

}  // namespace machdyn
