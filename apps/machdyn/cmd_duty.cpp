// `machdyn duty MODEL DUTY [-o DIR] [--json] [--set ...]`: the load cycles of a duty (docs/duty.md).
// DUTY lists operations — each a load case of MODEL (or the model as it is) and how many times it is
// done; each operation is simulated once, its link loads counted over their located turning points
// (analysis/load_history.hpp), and the counts merged over the whole duty with the residue rule
// (merge_parts, analysis/rainflow.hpp). Prints per link the cycles, the largest and the equivalent
// range, EN 13001's s and, with an S–N curve, the Miner damage; writes DIR/duty.json and
// DIR/duty_cycles.csv, DIR/duty_range_mean.csv and DIR/duty_from_to.csv (32 × 32 bins; default
// out/MODEL) after everything is computed; --plot also the figures of each link (the exceedance
// diagram and the rainflow heat map, SVG + PNG, io/duty_figures.hpp), rendered before anything is
// written. The operations run on all cores (-j N: on N threads; the result is the same), and under
// `mpirun -np R` over R ranks as sweeps do (rank 0 merges, reports and writes; the result is the same).
#include <memory>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "machdyn/io/duty.hpp"
#include "machdyn/io/duty_figures.hpp"
#include "machdyn/sweep/mpi.hpp"

namespace machdyn::cli {
namespace {

struct DutyArgs {
  std::string model, duty, out;
  bool json = false, plot = false;
  int jobs = 0;
  std::vector<std::string> sets;
};

int run_duty_command(const DutyArgs& a) {
  MpiSession mpi;  // MPI only under a multi-rank launcher
  const bool root = MpiSession::rank() == 0;
  const SilentOtherRanks silent(root);  // other ranks write nothing
  if (a.plot && root) plot::find_gnuplot();  // said before the runs, not after
  const std::unique_ptr<DutyRanks> ranks = MpiSession::size() > 1 ? mpi_duty_ranks() : nullptr;
  const DutyResult r = run_duty(a.model, a.duty, a.sets, a.jobs, ranks.get());
  if (!root) return 0;
  const std::filesystem::path out_dir = output_dir(a.model, a.out, "");
  nlohmann::json j = duty_json(r);
  j["model"] = a.model, j["duty"] = a.duty;
  // Every figure rendered before the first file is written: a failing gnuplot leaves nothing behind.
  std::vector<std::pair<std::string, plot::Rendered>> figures;
  if (a.plot)
    for (const DutyLink& l : r.links) {
      if (l.cycles.empty()) continue;
      const plot::Figure f = duty_exceedance_figure(l, r.spec.m);
      figures.emplace_back(f.id, plot::render(f));
      figures.emplace_back("duty_heatmap_" + f.id.substr(std::string("duty_exceedance_").size()), render_duty_heat_map(l));
    }
  write_file_atomic((out_dir / "duty_cycles.csv").string(), duty_cycles_csv(r));
  write_file_atomic((out_dir / "duty_range_mean.csv").string(), duty_matrix_csv(r, false));
  write_file_atomic((out_dir / "duty_from_to.csv").string(), duty_matrix_csv(r, true));
  for (const auto& [stem, rendered] : figures) {
    write_file_atomic((out_dir / (stem + ".svg")).string(), rendered.svg);
    write_file_atomic((out_dir / (stem + ".png")).string(), rendered.png);
  }
  write_file_atomic((out_dir / "duty.json").string(), j.dump(2) + "\n");
  if (a.json) std::cout << j.dump(2) << "\n";
  else std::cout << duty_table(r);
  return 0;
}

}  // namespace

void register_duty(CLI::App& app, int& exit_code) {
  auto a = std::make_shared<DutyArgs>();
  auto* cmd = app.add_subcommand("duty", "Load cycles of a duty: rainflow counts of every operation merged, "
                                         "equivalent range, EN 13001 s, Miner damage (docs/duty.md)");
  cmd->add_option("MODEL", a->model, "Model file (YAML); operations name its load cases")->required();
  cmd->add_option("DUTY", a->duty, "Duty file (YAML): operations, residue, gate, m, n_ref, links, sn_curve")->required();
  cmd->add_flag("--json", a->json, "Print JSON to stdout");
  cmd->add_option("-o,--out", a->out, "Output folder (default out/MODEL): duty.json, duty_cycles.csv, duty_range_mean.csv, duty_from_to.csv");
  cmd->add_flag("--plot", a->plot, "Also write per link duty_exceedance_LINK and duty_heatmap_LINK (.svg, .png; needs gnuplot)");
  cmd->add_option("-j,--jobs", a->jobs, "Threads for the operations (default: all cores, shared by the MPI ranks of a node; the result is the same)")
      ->check(CLI::NonNegativeNumber);
  add_set_option(*cmd, a->sets);
  cmd->callback([a, &exit_code] { exit_code = guarded([&] { return run_duty_command(*a); }); });
}

}  // namespace machdyn::cli
