#pragma once
// The CLI is a thin layer: each command lives in its own cmd_*.cpp, parses its options with CLI11
// and calls the library. register_* adds the subcommand to `app`; its callback stores the exit code
// (0 ok, 1 internal error, 2 input error, 3 numerical failure) in `exit_code`.

#include <filesystem>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "machdyn/io/plot.hpp"

namespace machdyn::cli {

/// Under a multi-rank MPI launch, ranks other than 0 stay silent (rank 0 reports errors and results
/// once): stderr is muted on them for the object's lifetime.
class SilentOtherRanks {
 public:
  explicit SilentOtherRanks(bool root) : buf_(std::cerr.rdbuf()) {
    if (!root) std::cerr.rdbuf(nullptr);
  }
  ~SilentOtherRanks() { std::cerr.rdbuf(buf_); }
  SilentOtherRanks(const SilentOtherRanks&) = delete;
  SilentOtherRanks& operator=(const SilentOtherRanks&) = delete;

 private:
  std::streambuf* buf_;
};

/// Runs `body`, turning exceptions into a message on stderr and an exit code:
/// InputError → 2 (every diagnostic on its own line), SolverError → 3, anything else → 1.
int guarded(const std::function<int()>& body);

/// Adds the `--set NAME.FIELD=VALUE` option (repeatable) to a command.
void add_set_option(CLI::App& cmd, std::vector<std::string>& sets);

/// Writes `content` to `path` through a temporary file and a rename, so a reader never sees a
/// half-written result. Creates parent folders. Throws std::runtime_error on failure.
void write_file_atomic(const std::string& path, const std::string& content);

/// Renders every figure with gnuplot (plot::render) and only then writes DIR/ID.svg and DIR/ID.png
/// for each (atomically), so a failure leaves no figure behind. Returns the file names written.
std::vector<std::string> write_figures(const std::filesystem::path& dir, const std::vector<plot::Figure>& figures);

/// The default output folder of a command: out/<model file stem>.
std::filesystem::path default_out_dir(const std::string& model_path);

/// The one output-folder convention of every command: OUT is `-o` or out/<model file stem>; a
/// run of load case NAME (`--case NAME`, and each case of `--all-cases`) writes to OUT/NAME.
std::filesystem::path output_dir(const std::string& model_path, const std::string& out_option,
                                 const std::string& load_case);

void register_simulate(CLI::App& app, int& exit_code);
void register_report(CLI::App& app, int& exit_code);
void register_modes(CLI::App& app, int& exit_code);
void register_examples(CLI::App& app, int& exit_code);
void register_energy(CLI::App& app, int& exit_code);
void register_gears(CLI::App& app, int& exit_code);
void register_sweep(CLI::App& app, int& exit_code);
void register_crane(CLI::App& app, int& exit_code);
void register_duty(CLI::App& app, int& exit_code);

}  // namespace machdyn::cli
