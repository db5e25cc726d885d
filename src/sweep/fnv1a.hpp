#pragma once
// The 64-bit FNV-1a hash (Fowler, Noll, Vo) of a byte string (private to src/sweep): the journal's
// line checksums and the plan's fingerprint. Not cryptographic; it detects torn or edited lines and
// a changed plan.
#include <cstdint>
#include <string_view>

namespace machdyn::detail {

/// FNV-1a of `s`, continuing from `h` (the offset basis starts a new hash).
inline std::uint64_t fnv1a(std::string_view s, std::uint64_t h = 0xcbf29ce484222325ULL) {
  for (unsigned char c : s) {
    h ^= c;
    h *= 0x100000001b3ULL;  // the 64-bit FNV prime
  }
  return h;
}

}  // namespace machdyn::detail
