// The layer direction common ← model ← solve ← analysis ← io ← sweep ← apps, checked on the
// sources: no file includes a header of a layer above its own (`gears/` sits beside `model/`;
// `solve` also never includes `model` or `gears`: integrators see no bodies).
#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <gtest/gtest.h>

namespace {

namespace fs = std::filesystem;

// Includes against the direction that another change is removing (issue 15: the model layer
// stops reading files; the YAML reading of cases and gear includes moves to io). Nothing new may
// join this list.
const std::set<std::pair<std::string, std::string>> kPendingMoves = {
    {"src/model/cases.cpp", "io"}, {"src/model/compile.cpp", "io"}, {"src/model/compile_machine.cpp", "io"}};

// Claim: every include in include/machdyn/LAYER and src/LAYER points to the same or a lower layer.
TEST(Layers, IncludesFollowTheDirection) {
  const std::map<std::string, int> rank = {{"common", 0}, {"gears", 1}, {"model", 1}, {"solve", 2},
                                           {"analysis", 3}, {"io", 4}, {"sweep", 5}};
  const fs::path root = MACHDYN_SOURCE_DIR;
  const std::regex inc(R"re(#include "(?:machdyn/)?(\w+)/)re");
  int files = 0;
  for (const char* top : {"include/machdyn", "src"}) {
    for (const auto& [layer, r] : rank) {
      const fs::path dir = root / top / layer;
      if (!fs::exists(dir)) continue;
      for (const auto& e : fs::directory_iterator(dir)) {
        ++files;
        std::ifstream in(e.path());
        std::stringstream ss;
        ss << in.rdbuf();
        const std::string text = ss.str();
        const std::string rel = fs::relative(e.path(), root).string();
        for (std::sregex_iterator it(text.begin(), text.end(), inc), end; it != end; ++it) {
          const std::string dep = (*it)[1];
          const auto d = rank.find(dep);
          if (d == rank.end()) continue;
          const bool against = d->second > r || (layer == "solve" && (dep == "model" || dep == "gears"));
          if (against && !kPendingMoves.count({rel, dep})) ADD_FAILURE() << rel << " includes " << dep << "/ (layer " << layer << ")";
        }
      }
    }
  }
  EXPECT_GT(files, 50);
}

}  // namespace
