#pragma once
/// @file
/// Sample specs of a parameter sweep and the three ways of choosing points from them: the full grid,
/// uniform random sampling and Latin hypercube sampling. Everything here is a pure function of its
/// arguments (the seed included), so a sweep reproduces exactly on every machine, thread count and
/// MPI rank.
///
/// A sample spec (the text after `=` in `--vary NAME.FIELD=SPEC`):
///   `a:b:n`       n values evenly spaced from a to b, both included (grid)
///   `a:b:n:log`   n values evenly spaced in log(x) from a to b (a and b nonzero, same sign) (grid)
///   `a:b`         the range [a, b] (random, lhs)
///   `a:b:log`     the range [a, b], sampled uniformly in log(x) (random, lhs)
///   `v1,v2,...`   these values (any method; random and lhs pick among them)
/// a, b and the list values may carry units (`2 mm:8 mm:4`, `1.2 kN*m,1.5 kN*m`); a plain number is
/// SI. Values are converted to SI here; that they fit the field (dimension, range) is checked by the
/// model compiler (sweep/plan.hpp).

#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "machdyn/common/units.hpp"

namespace machdyn {

/// A pseudo-random generator with a fully specified output: xoshiro256** (Blackman & Vigna 2018),
/// its 256-bit state filled from the 64-bit seed by splitmix64. std::uniform_real_distribution is
/// not used because its output differs between standard libraries.
class Xoshiro256 {
 public:
  explicit Xoshiro256(std::uint64_t seed);
  std::uint64_t next();
  /// Uniform on [0, 1): the top 53 bits of next() times 2⁻⁵³.
  double uniform();
  /// Uniform integer in [0, n), n > 0, by rejection (no modulo bias).
  std::uint64_t below(std::uint64_t n);

 private:
  std::uint64_t s_[4];
};

/// One parsed `--vary` spec.
struct SampleSpec {
  enum class Kind { range, list };
  Kind kind = Kind::range;
  // range: the end points as written, in SI, and their dimension
  std::string a_text, b_text;
  double a = 0.0, b = 0.0;
  int n = 0;         ///< number of grid points; 0 when not given (`a:b`)
  bool log = false;  ///< spaced (grid) or sampled (random, lhs) uniformly in log(x)
  // list: the values as written; SI value of each when it is a quantity (else NaN: a word, which
  // the compiler checks, e.g. `dopri5,bdf` for simulation.integrator)
  std::vector<std::string> texts;
  std::vector<double> values;

  /// The texts a user wrote (end points or list items), to be checked against the field.
  [[nodiscard]] std::vector<std::string> written() const;
};

/// Parses SPEC. Throws InputError located at `where` (e.g. "--vary c1.stiffness") when the syntax
/// is wrong, n < 1, a log range includes 0 or changes sign, or values have different dimensions.
SampleSpec parse_sample_spec(std::string_view spec, const std::string& where);

/// One varied value of a run: the text applied to the field (`--set NAME.FIELD=text`) and the value
/// recorded in the table (SI; NaN for a word, whose text is recorded instead).
struct AxisValue {
  std::string text;
  double si = 0.0;
};

/// The n grid values of one spec (range with n, or list). For a range, value k is
/// a + (b − a)·k/(n − 1) (log: a·(b/a)^(k/(n−1))), with the end points exactly a and b.
std::vector<AxisValue> grid_values(const SampleSpec& s);

/// The value of spec `s` at the unit coordinate u ∈ [0, 1): a + (b − a)·u for a range (log:
/// a·(b/a)^u), item ⌊u·k⌋ of a list of k items.
AxisValue value_at(const SampleSpec& s, double u);

/// Full factorial design over axes of sizes `sizes`: the index tuples in row-major order — the
/// FIRST axis varies slowest, the LAST fastest, as nested loops written in `--vary` order.
/// Run r has index tuple (r / (n2·…·nd) mod n1, …, r mod nd).
std::vector<std::vector<int>> grid_indices(const std::vector<int>& sizes);

/// N points of d unit coordinates, uniform on [0, 1)^d: point i takes d consecutive draws of
/// Xoshiro256(seed).uniform().
std::vector<std::vector<double>> random_unit(int n_points, int dims, std::uint64_t seed);

/// Latin hypercube: N points in [0, 1)^d such that, in every dimension, each stratum
/// [k/N, (k+1)/N) holds exactly one point. Draws from Xoshiro256(seed), dimension by dimension: a
/// Fisher–Yates permutation π (j from N−1 down to 1, swap with below(j+1)), then N offsets v_i;
/// point i has coordinate (π(i) + v_i) / N.
std::vector<std::vector<double>> latin_hypercube_unit(int n_points, int dims, std::uint64_t seed);

}  // namespace machdyn
