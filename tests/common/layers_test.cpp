// The layer direction of docs/design.md, checked on the sources themselves:
//   common ← gears ← model ← elements ← solve ← analysis ← io ← sweep ← apps
// A file may include its own layer and the layers to its left, never one to its right; and solve
// does not include model or elements either (steppers never see bodies: analysis joins the two). The test
// reads every #include "..." of src/, include/machdyn/ and apps/, so a new file or a new layer
// directory is covered without listing it here (an unknown layer directory fails the test).
#include <array>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <unistd.h>
#include <gtest/gtest.h>

namespace machdyn {
namespace MACHDYN_UNITY_ID {

namespace fs = std::filesystem;

constexpr std::array<const char*, 9> kOrder = {"common", "gears", "model", "elements", "solve", "analysis", "io", "sweep", "apps"};

int rank_of(const std::string& layer) {
  for (size_t k = 0; k < kOrder.size(); ++k)
    if (layer == kOrder[k]) return static_cast<int>(k);
  return -1;
}

/// The layer of a file: the directory under src/ or include/machdyn/; everything under apps/ is apps.
std::string layer_of_file(const fs::path& root, const fs::path& file) {
  const fs::path rel = fs::relative(file, root);
  auto it = rel.begin();
  const std::string top = it->string();
  if (top == "apps") return "apps";
  if (top == "include") ++it;  // include/machdyn/LAYER/...
  ++it;
  return it == rel.end() ? "" : it->string();
}

/// The layer an include names: "machdyn/LAYER/x.hpp", "LAYER/x.hpp" (src-relative) or "x.hpp" (the
/// including file's own directory, hence its own layer). Empty for anything else.
std::string layer_of_include(const std::string& inc, const fs::path& file, const std::string& own) {
  const fs::path p(inc);
  auto it = p.begin();
  if (it == p.end()) return "";
  if (it->string() == "machdyn") ++it;
  const std::string first = it == p.end() ? "" : it->string();
  if (rank_of(first) >= 0 && std::next(it) != p.end()) return first;
  if (fs::exists(file.parent_path() / p)) return own;
  return "";
}

/// Every violation in the tree under `root`, as "file:line: LAYER includes LAYER (inc)".
std::vector<std::string> violations(const fs::path& root) {
  std::vector<std::string> out;
  const std::regex include_re(R"re(^\s*#\s*include\s*"([^"]+)")re");
  for (const char* dir : {"src", "include/machdyn", "apps"}) {
    if (!fs::exists(root / dir)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root / dir)) {
      if (!entry.is_regular_file()) continue;
      const auto ext = entry.path().extension().string();
      if (ext != ".cpp" && ext != ".hpp" && ext != ".h") continue;
      const std::string own = layer_of_file(root, entry.path());
      if (rank_of(own) < 0) {
        out.push_back(entry.path().string() + ": in no known layer '" + own + "' (add it to the order)");
        continue;
      }
      std::ifstream in(entry.path());
      std::string line;
      int n = 0;
      while (std::getline(in, line)) {
        ++n;
        std::smatch m;
        if (!std::regex_search(line, m, include_re)) continue;
        const std::string to = layer_of_include(m[1].str(), entry.path(), own);
        const bool solve_sees_model = own == "solve" && (to == "model" || to == "elements");
        if (!to.empty() && (rank_of(to) > rank_of(own) || solve_sees_model))
          out.push_back(entry.path().string() + ":" + std::to_string(n) + ": " + own + " includes " + to + " (" +
                        m[1].str() + ")");
      }
    }
  }
  return out;
}

// Claim: no file of the library or the CLI includes a layer to its right.
TEST(Layers, NoIncludeAgainstTheDirection) {
  const auto bad = violations(MACHDYN_SOURCE_DIR);
  std::string all;
  for (const auto& b : bad) all += b + "\n";
  EXPECT_TRUE(bad.empty()) << all;
}

// Claim: the check finds a violation when there is one (a model file including io, as
// model/compile.cpp once did to read gear spec files; solve including model) and accepts the
// allowed directions.
TEST(Layers, TheCheckCatchesAModelFileIncludingIo) {
  const fs::path root = fs::temp_directory_path() / ("machdyn-layers-" + std::to_string(::getpid()));
  fs::create_directories(root / "src/model");
  fs::create_directories(root / "src/io");
  std::ofstream(root / "src/model/bad.cpp") << "#include \"machdyn/common/spec.hpp\"\n#include \"machdyn/io/yaml_reader.hpp\"\n";
  std::ofstream(root / "src/io/good.cpp") << "#include \"machdyn/model/model.hpp\"\n#include \"local.hpp\"\n";
  std::ofstream(root / "src/io/local.hpp") << "\n";
  fs::create_directories(root / "src/solve");
  std::ofstream(root / "src/solve/stepper.cpp") << "#include \"machdyn/common/units.hpp\"\n#include \"machdyn/model/model.hpp\"\n";
  const auto bad = violations(root);
  fs::remove_all(root);
  ASSERT_EQ(bad.size(), 2u);
  const std::string all = bad[0] + "\n" + bad[1];
  EXPECT_NE(all.find("bad.cpp:2: model includes io"), std::string::npos) << all;
  EXPECT_NE(all.find("stepper.cpp:2: solve includes model"), std::string::npos) << all;
}

}  // namespace
}  // namespace machdyn
