#pragma once
// Helpers shared by the tests: temporary model files and running the CLI as a user would.
#include <filesystem>
#include <string>

namespace machdyn::test {

/// A fresh empty folder under the system temp dir, removed at exit of the test process.
std::filesystem::path temp_dir();

/// Writes `text` to temp_dir()/name and returns the path.
std::string write_temp(const std::string& name, const std::string& text);

struct CliResult {
  int exit_code = -1;
  std::string out, err;
};

/// Runs the machdyn binary with `args` (shell words, already quoted as needed) in `cwd`.
CliResult run_cli(const std::string& args, const std::filesystem::path& cwd = temp_dir());

/// Path of a shipped example.
std::string example(const std::string& name);

}  // namespace machdyn::test
