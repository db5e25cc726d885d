#include "machdyn/io/duty.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "machdyn/analysis/load_history.hpp"
#include "machdyn/common/spec.hpp"
#include "machdyn/common/units.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/cases.hpp"

namespace machdyn {

DutySpec read_duty(const std::string& path, const std::vector<std::string>& cases) {
  const SpecNode root = read_yaml_file(path);
  Diagnostics diag;
  DutySpec d;
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
      DutyOperation op;
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

DutyResult run_duty(const std::string& model_path, const std::string& duty_path, const std::vector<std::string>& sets) {
  DutyResult out;
  out.spec = read_duty(duty_path, case_names(read_yaml_file(model_path)));
  const DutySpec& duty = out.spec;

  // Each operation once: its extremes (for the gate), then its link loads as parts.
  std::vector<std::string> names;
  std::vector<int> links;
  std::vector<std::vector<RainflowPart>> parts;  // [operation][link]
  for (const DutyOperation& op : duty.operations) {
    const Model m = load_model_case(model_path, sets, op.load_case);
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
      if (names.empty()) throw InputError(Location{model_path, 0, 0}, "the model has no links to count");
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
  for (const DutyOperation& op : duty.operations) repeats.push_back(op.repeat);
  for (size_t k = 0; k < links.size(); ++k) {
    std::vector<RainflowPart> of_link;
    for (const auto& p : parts) of_link.push_back(p[k]);
    DutyLink l;
    l.link = names[k];
    l.cycles = merge_parts(of_link, repeats, duty.residue);
    l.history = stress_history(l.cycles, duty.m, duty.n_ref);
    if (l.history.total_cycles > 0) l.equivalent_range = equivalent_range(l.cycles, duty.m, l.history.total_cycles);
    if (duty.has_curve) l.damage = miner_damage(l.cycles, duty.curve);
    out.links.push_back(std::move(l));
  }
  return out;
}

nlohmann::json duty_json(const DutyResult& r) {
  const DutySpec& duty = r.spec;
  nlohmann::json j;
  j["residue"] = duty.residue == RainflowResidue::repeat ? "repeat" : "half";
  j["gate_fraction"] = duty.gate, j["m"] = duty.m, j["n_ref"] = duty.n_ref;
  for (const DutyOperation& op : duty.operations)
    j["operations"].push_back({{"name", op.name}, {"case", op.load_case}, {"repeat", op.repeat}});
  for (const DutyLink& l : r.links) {
    nlohmann::json e = {{"link", l.link},
                        {"cycles", l.history.total_cycles},
                        {"largest_range", l.history.largest},
                        {"equivalent_range", l.equivalent_range},
                        {"k", l.history.k},
                        {"nu", l.history.nu},
                        {"s", l.history.s}};
    if (duty.has_curve) e["damage"] = l.damage;
    j["links"].push_back(e);
  }
  return j;
}

std::string duty_table(const DutyResult& r) {
  const bool curve = r.spec.has_curve;
  std::string table = fmt::format("{:<16} {:>14} {:>14} {:>14} {:>12} {:>12}\n", "link", "cycles", "largest range",
                                  "equiv. range", "s", curve ? "damage" : "");
  for (const DutyLink& l : r.links)
    table += fmt::format("{:<16} {:>14.6g} {:>14.6g} {:>14.6g} {:>12.4g} {:>12}\n", l.link, l.history.total_cycles,
                         l.history.largest, l.equivalent_range, l.history.s,
                         curve ? fmt::format("{:.4g}", l.damage) : std::string());
  return table;
}

std::string duty_cycles_csv(const DutyResult& r) {
  std::string csv = "link,range,mean,count,from,to\n";
  for (const DutyLink& l : r.links)
    for (const RainflowCycle& c : l.cycles)
      csv += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", l.link, c.range(), c.mean(), c.count, c.from,
                         c.to);
  return csv;
}

std::string duty_matrix_csv(const DutyResult& r, bool from_to, int bins) {
  std::string csv = from_to ? "link,from_lo,from_hi,to_lo,to_hi,count\n" : "link,range_lo,range_hi,mean_lo,mean_hi,count\n";
  for (const DutyLink& l : r.links) {
    const RainflowMatrix M = from_to ? from_to_matrix(l.cycles, bins) : range_mean_matrix(l.cycles, bins, bins);
    const double wr = (M.row_hi - M.row_lo) / M.rows, wc = (M.col_hi - M.col_lo) / M.cols;
    for (int i = 0; i < M.rows; ++i)
      for (int k = 0; k < M.cols; ++k)
        if (M.at(i, k) != 0.0)
          csv += fmt::format("{},{:.17g},{:.17g},{:.17g},{:.17g},{:.17g}\n", l.link, M.row_lo + i * wr,
                             M.row_lo + (i + 1) * wr, M.col_lo + k * wc, M.col_lo + (k + 1) * wc, M.at(i, k));
  }
  return csv;
}

}  // namespace machdyn
