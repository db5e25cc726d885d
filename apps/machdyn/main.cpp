// machdyn — dynamics of machine drives. Entry point: registers the commands, runs one.
#include <csignal>

#include "commands.hpp"

int main(int argc, char** argv) {
  // Past the file-size limit (ulimit -f) a write fails with EFBIG instead of the kernel killing the
  // process with SIGXFSZ: the writer reports an OutputError naming the file (exit 1) and removes its
  // temporary file (io/output_file.hpp).
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"machdyn — dynamics of machine drives: elastic chains, gaps and friction, "
               "variable inertia, non-circular gears"};
  app.set_version_flag("--version", std::string("machdyn ") + MACHDYN_VERSION);
  app.require_subcommand(1);
  int exit_code = 0;
  machdyn::cli::register_simulate(app, exit_code);
  machdyn::cli::register_modes(app, exit_code);
  machdyn::cli::register_examples(app, exit_code);
  machdyn::cli::register_gears(app, exit_code);
  machdyn::cli::register_energy(app, exit_code);
  machdyn::cli::register_sweep(app, exit_code);
  machdyn::cli::register_report(app, exit_code);
  machdyn::cli::register_crane(app, exit_code);
  machdyn::cli::register_duty(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    int rc = app.exit(e);
    return rc == 0 ? 0 : 2;
  }
  return exit_code;
}
