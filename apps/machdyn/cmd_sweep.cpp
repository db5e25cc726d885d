// `machdyn sweep MODEL --vary NAME.FIELD=SPEC ... [--method grid|lhs|random] [--samples N] [--seed S]
//  [-o DIR] [--jobs J] [--resume] [--plot OUTPUT[:X[:Y]]] [--case NAME ... | --all-cases] [--set ...]`
//  — parameter studies
// (library: machdyn/sweep/*). Works the same under `mpirun -np N`.
#include <atomic>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <unistd.h>
#include <fmt/format.h>

#include "commands.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/cases.hpp"
#include "machdyn/sweep/mpi.hpp"
#include "machdyn/sweep/plot_data.hpp"
#include "machdyn/sweep/runner.hpp"

namespace machdyn::cli {
namespace {

struct SweepArgs {
  std::string model;
  std::vector<std::string> vary, sets;
  std::string method = "grid";
  int samples = 0;
  std::uint64_t seed = 1;
  std::string out_dir;
  int jobs = 0;
  bool resume = false;
  std::string plot;
  std::vector<std::string> cases;  ///< --case, in order
  bool all_cases = false;
};

std::atomic<bool> g_stop{false};

/// First SIGINT/SIGTERM: stop starting runs, journal what finished. Second: the default action.
extern "C" void on_stop_signal(int sig) {
  if (g_stop.exchange(true)) {
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
}

std::string clock_text(double s) {
  if (!(s < 1e9)) return "?";
  const long t = std::lround(s);
  return t >= 3600 ? fmt::format("{}:{:02}:{:02}", t / 3600, t / 60 % 60, t % 60) : fmt::format("{}:{:02}", t / 60, t % 60);
}

int run_sweep_command(const SweepArgs& a) {
  MpiSession mpi;  // MPI only under a multi-rank launcher
  const bool root = MpiSession::rank() == 0;
  const SilentOtherRanks silent(root);  // other ranks write nothing

  SweepRequest req;
  req.model_path = a.model;
  req.sets = a.sets;
  req.vary = a.vary;
  req.method = a.method == "lhs" ? SweepMethod::lhs : a.method == "random" ? SweepMethod::random : SweepMethod::grid;
  req.samples = a.samples;
  req.seed = a.seed;
  if (a.all_cases && !a.cases.empty()) throw InputError(Location{"--case", 0, 0}, "give either --case NAME ... or --all-cases");
  req.cases = a.cases;
  if (a.all_cases) {
    req.cases = case_names(read_yaml_file(a.model));
    if (req.cases.empty()) throw InputError(Location{a.model, 0, 0}, "--all-cases: the model file has no 'cases:'");
  }
  req.apply_case = [](SpecNode& spec, const std::string& name) { apply_case(spec, name); };
  const SweepPlan plan = make_sweep_plan(req);  // every input error, before any run

  SweepOptions opt;
  opt.out_dir = a.out_dir.empty()
                    ? (std::filesystem::path("out") / (std::filesystem::path(a.model).stem().string() + "-sweep")).string()
                    : a.out_dir;
  opt.jobs = a.jobs;
  opt.resume = a.resume;
  opt.stop = &g_stop;
  std::optional<SweepPlotSpec> plot;
  if (!a.plot.empty()) {
    plot = parse_plot_spec(a.plot, plan, sweep_header(plan, standard_summary_columns()));
    plot::find_gnuplot();  // say it before a long sweep, not after
  }

  const bool tty = root && ::isatty(STDERR_FILENO);
  if (tty) {
    opt.progress = [](const SweepProgress& p) {
      const double rate = p.elapsed_s > 0 ? static_cast<double>(p.done_now) / p.elapsed_s : 0.0;
      const double left = rate > 0 ? static_cast<double>(p.total - p.done) / rate : 1e300;
      std::fprintf(stderr, "\r%ld/%ld runs  %.1f runs/s  %s left   ", p.done, p.total, rate, clock_text(left).c_str());
      std::fflush(stderr);
    };
  }
  g_stop = false;
  std::signal(SIGINT, on_stop_signal);
  std::signal(SIGTERM, on_stop_signal);
  if (root) std::cerr << fmt::format("sweep: {}; {} thread(s){}\n", plan.description, opt.jobs > 0 ? opt.jobs : default_sweep_jobs(),
                                     MpiSession::size() > 1 ? fmt::format(" on each of {} ranks", MpiSession::size()) : "");
  const SweepOutcome r = run_sweep(plan, opt);
  std::signal(SIGINT, SIG_DFL);
  std::signal(SIGTERM, SIG_DFL);
  if (tty) std::fputc('\n', stderr);
  if (!root) return 0;
  if (r.from_journal > 0 || r.dropped > 0)
    std::cerr << fmt::format("resumed: {} finished run(s) from the journal{}\n", r.from_journal,
                             r.dropped ? fmt::format(", {} torn or invalid line(s) dropped", r.dropped) : "");
  if (!r.complete) {
    std::cerr << fmt::format("interrupted: {} of {} runs are in {}; continue with the same command and --resume\n",
                             r.from_journal + r.computed, r.total, r.journal_path);
    if (MpiSession::active()) MpiSession::abort(130);
    return 130;
  }
  const double rate = r.wall_s > 0 ? static_cast<double>(r.computed) / r.wall_s : 0.0;
  std::cout << fmt::format("sweep: {} runs, {} ok, {} error(s); {} computed in {:.3g} s ({:.4g} runs/s, {} thread(s) × {} rank(s))\n",
                           r.total, r.ok, r.errors, r.computed, r.wall_s, rate, r.threads, r.ranks);
  std::cout << fmt::format("wrote {}\n", r.table_path);
  // Every run refused on its input (what `simulate` refuses with exit 2, e.g. a model with no
  // equilibrium): the sweep as a whole is an input error. The table stays, with its error rows.
  if (r.ok == 0 && r.computed_here > 0 && r.input_errors == r.computed_here) {
    std::cerr << fmt::format("machdyn: every run of the sweep failed on its input; the table ({}) has only error "
                             "rows. The first, run {}:\n{}\n",
                             r.table_path, r.first_input_error, r.first_input_message);
    return 2;
  }
  if (plot) {
    std::string name = plot->output;
    for (const auto& x : plot->inputs) name += "-vs-" + x;
    // Column names hold element names, which may hold '/': the file name stays in the folder.
    for (char& ch : name)
      if (ch == '/' || ch == '\\' || static_cast<unsigned char>(ch) < 0x20) ch = '_';
    const auto dir = std::filesystem::path(r.table_path).parent_path();
    const auto data = (dir / ("plot-" + name + ".csv")).string();
    const std::string csv = sweep_plot_csv(r.table_path, *plot);
    write_file_atomic(data, csv);
    const auto stem = (dir / ("plot-" + name)).string();
    try {
      const auto img = render_sweep_plot(csv, *plot);
      write_file_atomic(stem + ".svg", img.svg);
      write_file_atomic(stem + ".png", img.png);
      std::cout << fmt::format("wrote {}, {}.svg and {}.png\n", data, stem, stem);
    } catch (const std::runtime_error& e) {
      // The table is complete; a missing gnuplot only costs the picture.
      std::cout << fmt::format("wrote {} (plot data only)\n", data);
      std::cerr << fmt::format("warning: no picture: {}\n", e.what());
    }
  }
  return 0;
}

}  // namespace

void register_sweep(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<SweepArgs>();
  auto* cmd = app.add_subcommand("sweep", "Parameter study: many runs of a model with varied fields, one CSV table");
  cmd->add_option("MODEL", a->model, "Model file (YAML)")->required();
  cmd->add_option("--vary", a->vary,
                  "NAME.FIELD=SPEC, SPEC = a:b:n (linear), a:b:n:log, a:b[:log] (random, lhs) or v1,v2,...; "
                  "values may carry units (\"2 mm:8 mm:4\"); repeatable")
      ->required()
      ->allow_extra_args(false);
  cmd->add_option("--method", a->method, "grid (full factorial, last --vary fastest), lhs or random")
      ->check(CLI::IsMember({"grid", "lhs", "random"}));
  cmd->add_option("--samples", a->samples, "Number of points for lhs and random");
  cmd->add_option("--seed", a->seed, "Seed for lhs and random (same seed, same points)");
  cmd->add_option("-o,--out", a->out_dir, "Output folder for sweep.csv and sweep.journal (default out/MODEL-sweep)");
  cmd->add_option("--jobs", a->jobs, "Worker threads per process (default: all cores)")->check(CLI::NonNegativeNumber);
  cmd->add_flag("--resume", a->resume, "Continue an interrupted sweep from its journal in the output folder");
  cmd->add_option("--plot", a->plot, "OUTPUT[:X[:Y]]: summary plot (CSV data, SVG, PNG) of a table column "
                                     "against one or two varied fields");
  cmd->add_option("--case", a->cases, "Run every point for this load case of the file's 'cases:' (repeatable); "
                                     "the table gets a `case` column, the case varying slowest")
      ->allow_extra_args(false);
  cmd->add_flag("--all-cases", a->all_cases, "Run every point for every load case of the file");
  add_set_option(*cmd, a->sets);
  cmd->callback([a, &exit_code] { exit_code = guarded([&] { return run_sweep_command(*a); }); });
}

}  // namespace machdyn::cli
