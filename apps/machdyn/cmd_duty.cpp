// `machdyn duty MODEL DUTY [-o DIR] [--json] [--set ...]`: the load cycles of a duty (docs/duty.md).
// DUTY lists operations — each a load case of MODEL (or the model as it is) and how many times it is
// done; each operation is simulated once, its link loads counted over their located turning points
// (analysis/load_history.hpp), and the counts merged over the whole duty with the residue rule
// (merge_parts, analysis/rainflow.hpp). Prints per link the cycles, the largest and the equivalent
// range, EN 13001's s and, with an S–N curve, the Miner damage; writes DIR/duty.json and
// DIR/duty_cycles.csv (default out/MODEL) after everything is computed.
#include <algorithm>
#include <cmath>
#include <memory>
#include <iostream>
#include <limits>
#include <fmt/format.h>
#include <fmt/ranges.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "machdyn/analysis/fatigue.hpp"
#include "machdyn/analysis/load_history.hpp"
#include "machdyn/analysis/rainflow.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/spec.hpp"
#include "machdyn/common/units.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/cases.hpp"

namespace machdyn::cli {
namespace {

struct DutyArgs {
  std::string model, duty, out;
  bool json = false;
  std::vector<std::string> sets;
};

struct Operation {
  std::string name, load_case;  // load_case empty: the model as it is
  double repeat = 1.0;
};

/// What the duty file says.
struct Duty {
  std::vector<Operation> operations;
  std::vector<std::string> links;  // empty: all
  std::vector<Location> link_locs;
  RainflowResidue residue = RainflowResidue::half_cycles;
  double gate = 1e-6;  // fraction of each operation's load range
  double m = 3.0;      // exponent of Δ_eq and s
  double n_ref = 2e6;  // EN 13001's reference number of cycles
  bool has_curve = false;
  SNCurve curve;
};

Duty read_duty(const std::string& path, const std::vector<std::string>& cases) {
  const SpecNode root = read_yaml_file(path);
  Diagnostics diag;
  Duty d;
  if (!root.is_map()) {
    diag.error(root.loc, "a duty file is a map with 'operations:' (docs/duty.md)");
    diag.throw_if_any();
  }
  FieldReader r(root, "the duty", diag);
  if (auto w = r.word("residue", {"half", "repeat"}, std::string("half")))
    d.residue = *w == "repeat" ? RainflowResidue::repeat : RainflowResidue::half_cycles;
  if (auto g = r.quantity("gate", dim::none, 1e-6)) {
    if (!(*g >= 0.0 && *g < 1.0)) r.error_at("gate", "the gate is a fraction of the load range in [0, 1)");
    d.gate = *g;
  }
  if (auto m = r.positive("m", dim::none, 3.0)) d.m = *m;
  if (auto n = r.positive("n_ref", dim::none, 2e6)) d.n_ref = *n;
  if (const SpecNode* links = r.node("links")) {
    if (!links->is_seq()) diag.error(links->loc, "'links' is a list of link names");
    else
      for (const SpecNode& l : links->items) {
        if (!l.is_scalar()) diag.error(l.loc, "a link name");
        else d.links.push_back(l.scalar), d.link_locs.push_back(l.loc);
      }
  }
  if (const SpecNode* sn = r.node("sn_curve")) {
    if (!sn->is_map()) {
      diag.error(sn->loc, "'sn_curve' is a map: m, delta_ref, n_ref, optional n_knee and m2");
    } else {
      FieldReader c(*sn, "the S-N curve", diag);
      const auto m = c.positive("m", dim::none);  // required: a curve without a slope is refused
      const auto dr = c.positive("delta_ref", dim::none);
      const auto nr = c.positive("n_ref", dim::none);
      const auto nk = c.positive("n_knee", dim::none, 0.0, true);
      const auto m2 = c.positive("m2", dim::none, std::numeric_limits<double>::infinity());
      c.finish();
      if (m && dr && nr && nk && m2) {
        d.has_curve = true;
        d.curve = SNCurve{.m = *m, .delta_ref = *dr, .n_ref = *nr, .n_knee = *nk, .m2 = *m2};
      }
    }
  }
  const SpecNode* ops = r.node("operations");
  if (!ops) r.error_at("operations", "a duty needs 'operations:', a map of NAME: {case: CASE, repeat: N}");
  else if (!ops->is_map() || ops->fields.empty())
    diag.error(ops->loc, "'operations' is a non-empty map of NAME: {case: CASE, repeat: N}");
  else
    for (const SpecField& f : ops->fields) {
      Operation op;
      op.name = f.first;
      if (!f.second.is_map()) {
        diag.error(f.second.loc, fmt::format("operation '{}' is a map {{case: CASE, repeat: N}}", f.first));
        continue;
      }
      FieldReader o(f.second, fmt::format("operation '{}'", f.first), diag);
      if (auto c = o.text("case", std::string())) {
        op.load_case = *c;
        if (!c->empty() && std::find(cases.begin(), cases.end(), *c) == cases.end())
          o.error_at("case", fmt::format("unknown load case '{}'; the model has: {}", *c,
                                         cases.empty() ? std::string("none") : fmt::format("{}", fmt::join(cases, ", "))));
      }
      if (auto n = o.quantity("repeat", dim::none)) {
        if (!(*n >= 0.0) || *n != std::floor(*n) || *n > 1e15)
          o.error_at("repeat", fmt::format("the repetitions are a whole number >= 0, not {}", *n));
        op.repeat = *n;
      }
      o.finish();
      d.operations.push_back(op);
    }
  r.finish();
  diag.throw_if_any();
  return d;
}

int run_duty(const DutyArgs& a) {
  const Duty duty = read_duty(a.duty, case_names(read_yaml_file(a.model)));
  const std::filesystem::path out_dir = output_dir(a.model, a.out, "");

  // Each operation once: its extremes (for the gate), then its link loads as parts.
  std::vector<std::string> names;
  std::vector<int> links;
  std::vector<std::vector<RainflowPart>> parts;  // [operation][link]
  for (const Operation& op : duty.operations) {
    const Model m = load_model_case(a.model, a.sets, op.load_case);
    if (names.empty()) {  // the links to count, by name (the first operation's model)
      Diagnostics diag;
      for (size_t k = 0; k < duty.links.size(); ++k) {
        int found = -1;
        for (size_t l = 0; l < m.links.size(); ++l)
          if (m.links[l].name == duty.links[k]) found = static_cast<int>(l);
        if (found < 0) diag.error(duty.link_locs[k], fmt::format("the model has no link '{}'", duty.links[k]));
        links.push_back(found);
      }
      diag.throw_if_any();
      if (links.empty())
        for (size_t l = 0; l < m.links.size(); ++l) links.push_back(static_cast<int>(l));
      for (const int l : links) names.push_back(m.links[static_cast<size_t>(l)].name);
      if (names.empty()) throw InputError(Location{a.model, 0, 0}, "the model has no links to count");
    }
    SimulateOptions opt;
    opt.record_series = false;
    const SimulationResult plain = simulate(m, opt);
    LinkCycleOptions count;
    count.links = links;
    for (const int l : links) {
      const LinkSummary& s = plain.links[static_cast<size_t>(l)];
      count.gates.push_back(duty.gate * (s.max - s.min));
    }
    parts.push_back(link_parts(m, opt, count));
  }

  // Merge per link over the duty, then the figures.
  std::vector<double> repeats;
  for (const Operation& op : duty.operations) repeats.push_back(op.repeat);
  nlohmann::json j;
  j["model"] = a.model, j["duty"] = a.duty;
  j["residue"] = duty.residue == RainflowResidue::repeat ? "repeat" : "half";
  j["gate_fraction"] = duty.gate, j["m"] = duty.m, j["n_ref"] = duty.n_ref;
  for (const Operation& op : duty.operations)
    j["operations"].push_back({{"name", op.name}, {"case", op.load_case}, {"repeat", op.repeat}});
  std::string csv = "link,range,mean,count,from,to\n";
  std::string table = fmt::format("{:<16} {:>14} {:>14} {:>14} {:>12} {:>12}\n", "link", "cycles", "largest range",
                                  "equiv. range", "s", duty.has_curve ? "damage" : "");
  for (size_t k = 0; k < links.size(); ++k) {
    std::vector<RainflowPart> link_parts_k;
    for (const auto& p : parts) link_parts_k.push_back(p[k]);
    const std::vector<RainflowCycle> cycles = merge_parts(link_parts_k, repeats, duty.residue);
    const StressHistory h = stress_history(cycles, duty.m, duty.n_ref);
    const double eq = h.total_cycles > 0 ? equivalent_range(cycles, duty.m, h.total_cycles) : 0.0;
    nlohmann::json l = {{"link", names[k]},          {"cycles", h.total_cycles}, {"largest_range", h.largest},
                        {"equivalent_range", eq},    {"k", h.k},                 {"nu", h.nu},
                        {"s", h.s}};
    double damage = 0.0;
    if (duty.has_curve) l["damage"] = damage = miner_damage(cycles, duty.curve);
    j["links"].push_back(l);
    table += fmt::format("{:<16} {:>14.6g} {:>14.6g} {:>14.6g} {:>12.4g} {:>12}\n", names[k], h.total_cycles, h.largest,
                         eq, h.s, duty.has_curve ? fmt::format("{:.4g}", damage) : std::string());
    for (const RainflowCycle& c : cycles)
      csv += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", names[k], c.range(), c.mean(), c.count, c.from,
                         c.to);
  }
  write_file_atomic((out_dir / "duty_cycles.csv").string(), csv);
  write_file_atomic((out_dir / "duty.json").string(), j.dump(2) + "\n");
  if (a.json) std::cout << j.dump(2) << "\n";
  else std::cout << table;
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
  cmd->add_option("-o,--out", a->out, "Output folder (default out/MODEL): duty.json, duty_cycles.csv");
  add_set_option(*cmd, a->sets);
  cmd->callback([a, &exit_code] { exit_code = guarded([&] { return run_duty(*a); }); });
}

}  // namespace machdyn::cli
