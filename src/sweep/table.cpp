#include "machdyn/sweep/table.hpp"

#include "machdyn/model/machine.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <fmt/format.h>

#include "machdyn/elements/modes.hpp"
#include "machdyn/analysis/hybrid_stats.hpp"
#include "machdyn/analysis/sway_summary.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/model/compile.hpp"

namespace machdyn {
namespace {

std::string exact_text(double v) {
  if (std::isnan(v)) return "nan";
  return fmt::format("{}", v);  // shortest text that reads back to the same double
}

/// A field of the table: RFC 4180 (common/csv.hpp) on one line, line breaks as spaces, since the
/// journal holds one row per line.
std::string one_line_field(std::string text) {
  for (auto& ch : text)
    if (ch == '\n' || ch == '\r') ch = ' ';
  return csv_field(text);
}

}  // namespace

std::vector<SummaryColumns> standard_summary_columns() {
  SummaryColumns peaks;
  peaks.header = [](const Model& m) {
    std::vector<std::string> h;
    for (const auto& l : m.links) {
      const auto u = unit_suffix(link_load_unit(m, l));
      for (const auto& f : {"max_" + u, "min_" + u, std::string("t_max_s"), "static_" + u, std::string("dynamic_factor")})
        h.push_back(l.name + "." + f);
    }
    return h;
  };
  peaks.values = [](const Model&, const SimulationResult& r, std::vector<double>& v) {
    for (const auto& s : r.links) {
      v.push_back(s.max);
      v.push_back(s.min);
      v.push_back(s.t_max);
      v.push_back(s.static_load);
      v.push_back(s.dynamic_factor);
    }
  };
  SummaryColumns solver;
  solver.header = [](const Model&) { return std::vector<std::string>{"steps", "rejected_steps", "rhs_evals"}; };
  solver.values = [](const Model&, const SimulationResult& r, std::vector<double>& v) {
    v.push_back(static_cast<double>(r.stats.stepper.steps));
    v.push_back(static_cast<double>(r.stats.stepper.rejected));
    v.push_back(static_cast<double>(r.stats.stepper.rhs_evals));
  };
  return {peaks, peak_summary_columns(), hybrid_summary_columns(), sway_summary_columns(), solver};
}

SummaryColumns sway_summary_columns() {
  SummaryColumns g;
  g.header = [](const Model& m) {
    std::vector<std::string> h;
    for (const auto& rope : sway_rope_names(m))
      for (const char* f : {"max_sway_rad", "residual_sway_rad", "max_horizontal_force_N", "horizontal_dynamic_factor"})
        h.push_back(rope + "." + f);
    return h;
  };
  g.values = [](const Model&, const SimulationResult& r, std::vector<double>& v) {
    constexpr double nan = std::numeric_limits<double>::quiet_NaN();
    for (const SwaySummary& s : r.sway)  // the keys of summary.json's `sway` (io/results.cpp)
      v.insert(v.end(), {s.max_sway_rad, s.residual_after ? s.residual_sway_rad : nan, s.max_horizontal_force_N,
                         s.dynamic_factor.value_or(nan)});
  };
  return g;
}

bool runs_event_driven(const Model& m) {
  // Case sweeps keep the energy books like `simulate --all-cases`, except a stepwise gear drive,
  // whose velocity jumps the books do not count (the compiler keeps those out of hybrid models).
  return m.is_hybrid() || (!m.load_case.empty() && !has_velocity_jumps(m));
}

SummaryColumns peak_summary_columns() {
  SummaryColumns g;
  g.header = [](const Model& m) {
    std::vector<std::string> h;
    if (!runs_event_driven(m)) return h;
    for (const auto& l : m.links) {
      const auto u = unit_suffix(link_load_unit(m, l));
      for (const auto& f : {"peak_" + u, std::string("t_peak_s"), "peak_static_" + u, std::string("peak_dynamic_factor")})
        h.push_back(l.name + "." + f);
    }
    return h;
  };
  g.values = [](const Model& m, const SimulationResult& r, std::vector<double>& v) {
    if (!runs_event_driven(m)) return;
    for (size_t l = 0; l < r.links.size(); ++l) {  // as the table of `simulate --all-cases`
      const LinkSummary& p = r.links[l];
      v.insert(v.end(), {p.peak, p.t_peak, p.static_load, p.dynamic_factor});
    }
  };
  return g;
}

SummaryColumns hybrid_summary_columns() {
  SummaryColumns g;
  g.header = [](const Model& m) {
    std::vector<std::string> h;
    if (!runs_event_driven(m)) return h;
    for (const auto& k : counted_event_kinds()) h.push_back("events_" + k);
    for (const auto& c : m.contacts) {
      if (c.joint) continue;  // as contact_statistics
      h.push_back(c.name + ".slips");
      h.push_back(c.name + ".period_s");
      for (const auto& l : m.links) h.push_back(c.name + "." + l.name + "_max_over_static_limit");
    }
    return h;
  };
  g.values = [](const Model& m, const SimulationResult& r, std::vector<double>& v) {
    if (!runs_event_driven(m)) return;
    for (long n : event_counts(r.hybrid)) v.push_back(static_cast<double>(n));
    for (const auto& s : contact_statistics(m, r)) {
      v.push_back(static_cast<double>(s.slips));
      v.push_back(s.period_s);
      for (double x : s.link_max_over_static_limit) v.push_back(x);
    }
  };
  return g;
}

std::vector<std::vector<std::string>> summary_column_names(const SweepPlan& plan,
                                                           const std::vector<SummaryColumns>& columns) {
  std::vector<std::vector<std::string>> out;
  const auto models = column_models(plan);
  for (const auto& g : columns) {
    std::vector<std::string> names;
    for (const Model* m : models)
      for (auto& name : g.header(*m))
        if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(std::move(name));
    out.push_back(std::move(names));
  }
  return out;
}

std::vector<std::string> split_csv_line(const std::string& line) {
  std::vector<std::string> out(1);
  bool quoted = false;
  for (size_t i = 0; i < line.size(); ++i) {
    const char ch = line[i];
    if (quoted) {
      if (ch == '"' && i + 1 < line.size() && line[i + 1] == '"') {
        out.back() += '"';
        ++i;
      } else if (ch == '"') {
        quoted = false;
      } else {
        out.back() += ch;
      }
    } else if (ch == '"') {
      quoted = true;
    } else if (ch == ',') {
      out.emplace_back();
    } else {
      out.back() += ch;
    }
  }
  return out;
}

std::string sweep_header(const SweepPlan& plan, const std::vector<SummaryColumns>& columns) {
  std::string h = "run";
  if (!plan.request.cases.empty()) h += ",case";
  for (const auto& a : plan.axes) {
    h += ',';
    h += one_line_field(a.target);
  }
  for (const auto& names : summary_column_names(plan, columns))
    for (const auto& name : names) {
      h += ',';
      h += one_line_field(name);
    }
  return h + ",status,message";
}

std::string execute_run(const SweepPlan& plan, const SweepRun& run, const std::vector<SummaryColumns>& columns) {
  return execute_run(plan, run, columns, summary_column_names(plan, columns));
}

std::string execute_run(const SweepPlan& plan, const SweepRun& run, const std::vector<SummaryColumns>& columns,
                        const std::vector<std::vector<std::string>>& names, bool* input_error) {
  if (input_error) *input_error = false;
  // The run's key: index, case, varied values.
  std::string row = std::to_string(run.index);
  if (run.case_index >= 0) {
    row += ',';
    row += one_line_field(plan.request.cases[static_cast<size_t>(run.case_index)]);
  }
  for (const auto& v : run.values) {
    row += ',';
    row += std::isnan(v.si) ? one_line_field(v.text) : exact_text(v.si);
  }

  size_t n_summary = 0;
  for (const auto& g : names) n_summary += g.size();
  std::string message;
  try {
    Model m = compile_model(run_spec(plan, run), plan.request.model_path);
    if (run.case_index >= 0) m.load_case = plan.request.cases[static_cast<size_t>(run.case_index)];
    // The cases of a file run event-driven, smooth or not, as with `simulate --all-cases`: every row
    // of a case sweep is computed alike and has the quasi-static load at a negative peak.
    // The table needs the summaries only: event-driven runs skip the time series (a third of a
    // travel start-up run; the smooth path needs its series for machines, analysis/machine_outputs),
    // and so do runs with a spatial rope: their sway summary is taken during the run.
    SimulateOptions summaries_only;
    summaries_only.record_series = false;
    summaries_only.event_driven = runs_event_driven(m);
    const SimulationResult r = simulate(m, summaries_only);
    // Each group's values, in the table's columns: a column the run's model has no element for
    // (a brake of another case) stays empty.
    std::vector<std::string> cells;
    cells.reserve(n_summary);
    std::vector<double> values;
    for (size_t k = 0; k < columns.size(); ++k) {
      const auto& g = columns[k];
      values.clear();
      g.values(m, r, values);
      const auto own = g.header(m);
      if (values.size() != own.size())
        throw std::runtime_error(fmt::format("the run gave {} summary values, its header has {}", values.size(), own.size()));
      if (own == names[k]) {
        for (double v : values) cells.push_back(exact_text(v));
        continue;
      }
      for (const auto& name : names[k]) {
        const auto it = std::find(own.begin(), own.end(), name);
        cells.push_back(it == own.end() ? std::string() : exact_text(values[static_cast<size_t>(it - own.begin())]));
      }
    }
    for (const auto& c : cells) {
      row += ',';
      row += c;
    }
    return row + ",ok,";
  } catch (const InputError& e) {
    if (input_error) *input_error = true;
    for (const auto& d : e.diagnostics()) {
      if (!message.empty()) message += "; ";
      message += d.str();
    }
  } catch (const std::exception& e) {
    message = e.what();
  }
  row += std::string(n_summary, ',');
  row += ",error,";
  row += one_line_field(message);
  return row;
}

}  // namespace machdyn
