// Bad input never crashes: random mutations of a valid model file end in a clean InputError (or a
// SolverError from a run that is legal but numerically hopeless), never in another exception.
#include <cstdint>
#include <fstream>
#include <sstream>
#include <gtest/gtest.h>

#include "machdyn/analysis/modes.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "support/support.hpp"

namespace machdyn {
namespace MACHDYN_UNITY_ID {

struct SplitMix {  // a fixed generator, so every failure reproduces
  uint64_t s;
  uint64_t next() {
    uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  size_t below(size_t n) { return static_cast<size_t>(next() % n); }
};

std::string mutate(std::string s, SplitMix& rng) {
  static const char* junk[] = {"-", "0", "nan", "1e400", "kg", "[", "]", "{", "}", ":", ",", "ground", "I1",
                               "spring", "\n", " ", "'", "-1e-300", "*m^", "bdf", "1/0"};
  const int edits = 1 + static_cast<int>(rng.below(3));
  for (int e = 0; e < edits && !s.empty(); ++e) {
    const size_t pos = rng.below(s.size());
    switch (rng.below(4)) {
      case 0: s.erase(pos, 1 + rng.below(8)); break;
      case 1: s.insert(pos, junk[rng.below(std::size(junk))]); break;
      case 2: s.resize(pos); break;
      default: s[pos] = static_cast<char>(32 + rng.below(95));
    }
  }
  return s;
}

// Claim: 400 random mutations of the hoist file each compile or fail with InputError; those that
// compile run `modes` and a short `simulate` ending normally or with SolverError.
TEST(Robustness, MutatedModelFilesFailCleanly) {
  std::ifstream in(test::example("hoist-3mass.yaml"));
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string base = ss.str();
  SplitMix rng{20261121};
  int compiled = 0, rejected = 0;
  for (int k = 0; k < 400; ++k) {
    const std::string text = mutate(base, rng);
    try {
      SpecNode root = parse_yaml_string(text, "mutant.yaml");
      apply_set(root, "simulation.t_end=0.02");
      apply_set(root, "simulation.max_steps=20000");
      const Model m = compile_model(root, "mutant.yaml");
      ++compiled;
      (void)compute_modes(m);
      try {
        (void)simulate(m);
      } catch (const SolverError&) {
      }
    } catch (const InputError& e) {
      ++rejected;
      EXPECT_FALSE(e.diagnostics().empty());
    } catch (const std::exception& e) {
      ADD_FAILURE() << "mutant " << k << " threw " << e.what() << "\n" << text;
    }
  }
  EXPECT_GT(rejected, 100);
  EXPECT_GT(compiled, 10);
}

}  // namespace
}  // namespace machdyn
