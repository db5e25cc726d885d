#include "machdyn/sweep/sampling.hpp"

#include <cmath>
#include <limits>
#include <numeric>
#include <optional>
#include <fmt/format.h>

#include "machdyn/common/diagnostics.hpp"

namespace machdyn {

// ---- PRNG -------------------------------------------------------------------------------------

namespace {
std::uint64_t splitmix64(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9e3779b97f4a7c15ULL);
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}
std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }
}  // namespace

Xoshiro256::Xoshiro256(std::uint64_t seed) {
  for (auto& s : s_) s = splitmix64(seed);
}

std::uint64_t Xoshiro256::next() {
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double Xoshiro256::uniform() { return static_cast<double>(next() >> 11) * 0x1.0p-53; }

std::uint64_t Xoshiro256::below(std::uint64_t n) {
  // Accept x only below the largest multiple of n, so every residue is equally likely.
  const std::uint64_t limit = std::numeric_limits<std::uint64_t>::max() - std::numeric_limits<std::uint64_t>::max() % n;
  std::uint64_t x = next();
  while (x >= limit) x = next();
  return x % n;
}

// ---- specs ------------------------------------------------------------------------------------

namespace {

std::string trim_blanks(std::string_view s) {
  const auto b = s.find_first_not_of(" \t");
  if (b == std::string_view::npos) return {};
  const auto e = s.find_last_not_of(" \t");
  return std::string(s.substr(b, e - b + 1));
}

std::vector<std::string> split_trimmed(std::string_view s, char sep) {
  std::vector<std::string> out;
  size_t start = 0;
  for (;;) {
    const auto p = s.find(sep, start);
    out.push_back(trim_blanks(s.substr(start, p == std::string_view::npos ? std::string_view::npos : p - start)));
    if (p == std::string_view::npos) return out;
    start = p + 1;
  }
}

}  // namespace

std::vector<std::string> SampleSpec::written() const {
  if (kind == Kind::list) return texts;
  return {a_text, b_text};
}

SampleSpec parse_sample_spec(std::string_view spec, const std::string& where) {
  const Location loc{where, 0, 0};
  auto fail = [&](const std::string& msg) -> void {
    throw InputError(loc, fmt::format("{} in '{}' (expected a:b:n, a:b:n:log, a:b, a:b:log or v1,v2,...)", msg, spec));
  };
  SampleSpec s;
  if (spec.find(':') == std::string_view::npos) {
    // A list (one value is a list of one).
    s.kind = SampleSpec::Kind::list;
    s.texts = split_trimmed(spec, ',');
    std::optional<Dim> dim0;
    for (const auto& t : s.texts) {
      if (t.empty()) fail("an empty value");
      std::string err;
      const auto q = parse_quantity(t, &err);
      s.values.push_back(q ? q->value : std::numeric_limits<double>::quiet_NaN());
      if (q && q->has_unit) {
        if (dim0 && !(*dim0 == q->dim))
          fail(fmt::format("values of different dimensions ({} and {})", describe(*dim0), describe(q->dim)));
        dim0 = q->dim;
      }
    }
    return s;
  }
  auto parts = split_trimmed(spec, ':');
  if (!parts.empty() && parts.back() == "log") {
    s.log = true;
    parts.pop_back();
  }
  if (parts.size() != 2 && parts.size() != 3) fail("wrong number of ':' fields");
  s.a_text = parts[0];
  s.b_text = parts[1];
  std::string err;
  const auto qa = parse_quantity(s.a_text, &err);
  if (!qa) fail(err);
  const auto qb = parse_quantity(s.b_text, &err);
  if (!qb) fail(err);
  if (qa->has_unit && qb->has_unit && !(qa->dim == qb->dim))
    fail(fmt::format("end points of different dimensions ({} and {})", describe(qa->dim), describe(qb->dim)));
  s.a = qa->value;
  s.b = qb->value;
  if (parts.size() == 3) {
    const auto& nt = parts[2];
    char* end = nullptr;
    const long n = std::strtol(nt.c_str(), &end, 10);
    if (nt.empty() || *end != '\0' || n < 1 || n > 100'000'000) fail(fmt::format("n = '{}' is not a whole number >= 1", nt));
    s.n = static_cast<int>(n);
  }
  if (s.log && !(s.a * s.b > 0.0)) fail("a log range needs nonzero end points of the same sign");
  return s;
}

// ---- values -----------------------------------------------------------------------------------

namespace {

AxisValue axis_value(double v) { return {fmt::format("{}", v), v}; }  // shortest exact text

double range_value(const SampleSpec& s, double u) {
  if (s.log) return s.a * std::pow(s.b / s.a, u);
  return s.a + (s.b - s.a) * u;
}

}  // namespace

std::vector<AxisValue> grid_values(const SampleSpec& s) {
  std::vector<AxisValue> out;
  if (s.kind == SampleSpec::Kind::list) {
    for (size_t k = 0; k < s.texts.size(); ++k) out.push_back({s.texts[k], s.values[k]});
    return out;
  }
  for (int k = 0; k < s.n; ++k) {
    if (k == 0) {
      out.push_back(axis_value(s.a));
    } else if (k == s.n - 1) {
      out.push_back(axis_value(s.b));
    } else {
      out.push_back(axis_value(range_value(s, static_cast<double>(k) / static_cast<double>(s.n - 1))));
    }
  }
  return out;
}

AxisValue value_at(const SampleSpec& s, double u) {
  if (s.kind == SampleSpec::Kind::list) {
    auto k = static_cast<size_t>(u * static_cast<double>(s.texts.size()));
    if (k >= s.texts.size()) k = s.texts.size() - 1;
    return {s.texts[k], s.values[k]};
  }
  return axis_value(range_value(s, u));
}

std::vector<std::vector<int>> grid_indices(const std::vector<int>& sizes) {
  long total = 1;
  for (int n : sizes) total *= n;
  std::vector<std::vector<int>> out(static_cast<size_t>(total), std::vector<int>(sizes.size()));
  for (long r = 0; r < total; ++r) {
    long rest = r;
    for (size_t d = sizes.size(); d-- > 0;) {  // the last axis is the fastest digit
      out[static_cast<size_t>(r)][d] = static_cast<int>(rest % sizes[d]);
      rest /= sizes[d];
    }
  }
  return out;
}

std::vector<std::vector<double>> random_unit(int n_points, int dims, std::uint64_t seed) {
  Xoshiro256 rng(seed);
  std::vector<std::vector<double>> out(static_cast<size_t>(n_points), std::vector<double>(static_cast<size_t>(dims)));
  for (auto& p : out)
    for (auto& u : p) u = rng.uniform();
  return out;
}

std::vector<std::vector<double>> latin_hypercube_unit(int n_points, int dims, std::uint64_t seed) {
  Xoshiro256 rng(seed);
  const auto n = static_cast<size_t>(n_points);
  std::vector<std::vector<double>> out(n, std::vector<double>(static_cast<size_t>(dims)));
  std::vector<size_t> perm(n);
  for (size_t d = 0; d < static_cast<size_t>(dims); ++d) {
    std::iota(perm.begin(), perm.end(), size_t{0});
    for (size_t j = n; j-- > 1;) std::swap(perm[j], perm[static_cast<size_t>(rng.below(j + 1))]);
    for (size_t i = 0; i < n; ++i) {
      double u = (static_cast<double>(perm[i]) + rng.uniform()) / static_cast<double>(n);
      // (k + v)/N can round up to (k+1)/N for large N; keep the point inside its stratum.
      if (u >= static_cast<double>(perm[i] + 1) / static_cast<double>(n))
        u = std::nextafter(static_cast<double>(perm[i] + 1) / static_cast<double>(n), 0.0);
      out[i][d] = u;
    }
  }
  return out;
}

}  // namespace machdyn
