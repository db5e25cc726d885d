// One case of a report, run and analysed (io/report_run.hpp): the one pipeline of the CLI's
// `machdyn report` and Python's machdyn.report().
#include "machdyn/io/report_run.hpp"

#include "machdyn/io/figures.hpp"

namespace machdyn::report {

Case ReportRun::as_case() const {
  Case c;
  c.name = name, c.description = description;
  c.model = &model, c.result = &result, c.modes = &modes;
  c.energy = energy ? &*energy : nullptr;
  c.topologies = &topologies;
  c.frf = frf.get(), c.frf_topology = frf_topology;
  c.crane = crane ? &*crane : nullptr;
  c.links = links;
  return c;
}

void check_report_choices(const Model& m, const ReportOptions& opt) {
  if (!opt.links.empty()) (void)chosen_links(m, opt.links, opt.links_option);
  if (!opt.frf.input.empty()) (void)linear_input(m, opt.frf.input, Location{opt.frf.option_prefix + "input", 0, 0});
}

void run_report_case(ReportRun& run, const ReportOptions& opt) {
  const Model& m = run.model;
  check_report_choices(m, opt);  // a typo costs no simulation
  run.links = opt.links;
  run.result = simulate(m, opt.simulate);
  run.modes = compute_modes(m);
  run.energy = machine_energy(m);
  run.topologies = run_topology_modes(m, run.result.hybrid, m.simulation.t_end);
  run.frf = default_frequency_response(m, run.topologies, &run.frf_topology, opt.frf);
  if (m.crane.given) run.crane = crane_analysis(m);
}

}  // namespace machdyn::report
