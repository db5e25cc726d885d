// `machdyn examples` lists the shipped example models; `machdyn demo` runs the default one.
#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <fmt/format.h>

#include "commands.hpp"

namespace machdyn::cli {

int run_simulate(const std::string& model_path, const std::vector<std::string>& sets, std::string out_dir, bool json);
int run_modes(const std::string& model_path, const std::vector<std::string>& sets, bool json);

namespace {

/// MACHDYN_EXAMPLES if set; else the installed examples beside an installed CLI
/// (PREFIX/bin/machdyn → PREFIX/share/machdyn/examples); else the source tree it was built from.
std::filesystem::path examples_dir() {
  if (const char* env = std::getenv("MACHDYN_EXAMPLES")) return env;
  std::error_code ec;
  const auto exe = std::filesystem::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const auto installed = exe.parent_path().parent_path() / "share" / "machdyn" / "examples";
    if (std::filesystem::is_directory(installed, ec)) return installed;
  }
  return MACHDYN_EXAMPLES_DIR;
}

/// The first comment line of an example, without "# ".
std::string describe(const std::filesystem::path& p) {
  std::ifstream in(p);
  std::string line;
  while (std::getline(in, line))
    if (line.rfind("# ", 0) == 0) return line.substr(2);
  return "";
}

}  // namespace

void register_examples(CLI::App& app, int& exit_code) {
  auto* ex = app.add_subcommand("examples", "List the shipped example models");
  ex->callback([&exit_code] {
    exit_code = guarded([] {
      const auto dir = examples_dir();
      std::vector<std::filesystem::path> files;
      for (const auto& e : std::filesystem::recursive_directory_iterator(dir))  // with crane/, msl/, ...
        if (e.path().extension() == ".yaml") files.push_back(e.path());
      std::sort(files.begin(), files.end());
      std::cout << fmt::format("examples in {}:\n", dir.string());
      for (const auto& f : files)
        std::cout << fmt::format("  {:<28} {}\n", std::filesystem::relative(f, dir).generic_string(), describe(f));
      return 0;
    });
  });
  auto* demo = app.add_subcommand("demo", "Run the default example (the three-mass hoist of paper 002)");
  auto out = std::make_shared<std::string>("machdyn-demo");
  demo->add_option("-o,--out", *out, "Output folder (default machdyn-demo)");
  demo->callback([&exit_code, out] {
    exit_code = guarded([&] {
      const std::string model = (examples_dir() / "hoist-3mass.yaml").string();
      std::cout << "== machdyn modes " << model << "\n";
      run_modes(model, {}, false);
      std::cout << "\n== machdyn simulate " << model << " -o " << *out << "\n";
      return run_simulate(model, {}, *out, false);
    });
  });
}

}  // namespace machdyn::cli
