#include "machdyn/sweep/plan.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "machdyn/io/input_file.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/model/compile.hpp"
#include "sweep/fnv1a.hpp"

namespace machdyn {
namespace {

/// The plan holds every run's values (some 230 bytes a run: 10^6 runs ≈ 230 MB; 10^8 were 23 GB, an
/// out-of-memory before the first run): a larger sweep is split (docs/sweeps.md).
constexpr long kMaxRuns = 1'000'000;

const char* method_name(SweepMethod m) {
  switch (m) {
    case SweepMethod::grid: return "grid";
    case SweepMethod::random: return "random";
    case SweepMethod::lhs: return "lhs";
  }
  return "?";
}

/// Checks one axis against the field it varies, by compiling `base` (the file and --set, or with
/// cases the file, case `case_name` and --set: the spec the runs apply the axis to) with each written
/// value (end points or list items). Adds diagnostics for an input error of the axis as a whole; with
/// a case they name it (a field only some cases have).
void probe_axis(const SpecNode& base, const std::string& model_path, const VaryAxis& axis,
                const std::string& case_name, Diagnostics& diag) {
  const Location where{"--vary " + axis.target + (case_name.empty() ? "" : " (case " + case_name + ")"), 0, 0};
  std::vector<Diagnostic> first_failure;
  int failures = 0;
  const auto written = axis.spec.written();
  for (const auto& text : written) {
    SpecNode s = base;
    try {
      apply_set(s, axis.target + "=" + text);  // unknown element: an error of the axis
    } catch (const InputError& e) {
      for (const auto& d : e.diagnostics()) diag.error(where, d.message);
      return;
    }
    try {
      (void)compile_model(s, model_path);
      continue;
    } catch (const InputError& e) {
      ++failures;
      if (first_failure.empty()) first_failure = e.diagnostics();
      // A unit that does not fit the field: the same number in SI compiles.
      std::string err;
      const auto q = parse_quantity(text, &err);
      if (q && q->has_unit) {
        SpecNode plain = base;
        apply_set(plain, fmt::format("{}={:.17g}", axis.target, q->value));
        bool plain_ok = true;
        try {
          (void)compile_model(plain, model_path);
        } catch (const InputError&) {
          plain_ok = false;
        }
        if (plain_ok) {
          diag.error(where, fmt::format("the unit of '{}' does not fit {}", text, axis.target));
          for (const auto& d : e.diagnostics()) diag.error(d.where, d.message);
          return;
        }
      }
    }
  }
  if (failures == static_cast<int>(written.size())) {
    diag.error(where, fmt::format("every value given ({}) is rejected; the first:", fmt::join(written, ", ")));
    for (const auto& d : first_failure) diag.error(d.where, d.message);
  }
}

}  // namespace

SweepPlan make_sweep_plan(const SweepRequest& request) {
  SweepPlan plan;
  plan.request = request;

  // The base: file and --set; it must compile on its own.
  // The file is read once: the spec and the fingerprint are of the same text.
  const std::string text = request.model_text.empty()
                               ? read_input_file(request.model_path, kMaxModelFileBytes, "file")
                               : request.model_text;
  const SpecNode file = parse_yaml_string(text, request.model_path);
  plan.base = file;
  for (const auto& o : request.sets) apply_set(plan.base, o);
  resolve_gear_includes(plan.base);  // `gears: FILE` is read once here, not per run
  plan.base_model = compile_model(plan.base, request.model_path);

  // Parse the axes; check each against its field.
  Diagnostics diag;
  const Location cli{"--vary", 0, 0};
  if (request.vary.empty()) diag.error(cli, "give at least one --vary NAME.FIELD=SPEC");
  for (const auto& v : request.vary) {
    const auto eq = v.find('=');
    if (eq == std::string::npos || eq == 0) {
      diag.error({"--vary " + v, 0, 0}, "expected NAME.FIELD=SPEC");
      continue;
    }
    VaryAxis axis;
    axis.target = v.substr(0, eq);
    for (const auto& other : plan.axes)
      if (other.target == axis.target) diag.error({"--vary " + v, 0, 0}, "this field is already varied");
    try {
      axis.spec = parse_sample_spec(std::string_view(v).substr(eq + 1), "--vary " + axis.target);
    } catch (const InputError& e) {
      for (const auto& d : e.diagnostics()) diag.error(d.where, d.message);
      continue;
    }
    const Location where{"--vary " + axis.target, 0, 0};
    const bool range = axis.spec.kind == SampleSpec::Kind::range;
    if (request.method == SweepMethod::grid && range && axis.spec.n == 0)
      diag.error(where, "a grid needs the number of points: a:b:n (or a list v1,v2,...)");
    if (request.method != SweepMethod::grid && range && axis.spec.n != 0)
      diag.error(where, fmt::format("--method {} samples the range a:b (or a:b:log) with --samples points; "
                                    "drop the n of a:b:n",
                                    method_name(request.method)));
    plan.axes.push_back(std::move(axis));
  }
  if (request.method == SweepMethod::grid && request.samples != 0)
    diag.error({"--samples", 0, 0}, "--samples is for --method random or lhs; a grid has n1·n2·… runs");
  if (request.method != SweepMethod::grid && request.samples <= 0)
    diag.error({"--samples", 0, 0}, fmt::format("--method {} needs --samples N (N >= 1)", method_name(request.method)));
  if (!request.cases.empty() && !request.apply_case)
    diag.error({"--case", 0, 0}, "this model format has no named cases");
  diag.throw_if_any();
  // Cases: file, case, --set (as `simulate --case NAME --set ...`), each compiled once here.
  for (size_t c = 0; c < request.cases.size(); ++c) {
    const auto& name = request.cases[c];
    if (std::find(request.cases.begin(), request.cases.begin() + static_cast<long>(c), name) !=
        request.cases.begin() + static_cast<long>(c)) {
      diag.error({"--case " + name, 0, 0}, "this case is already given");
      continue;
    }
    try {
      SpecNode s = file;
      request.apply_case(s, name);
      for (const auto& o : request.sets) apply_set(s, o);
      resolve_gear_includes(s);
      Model m = compile_model(s, request.model_path);
      m.load_case = name;
      plan.case_bases.push_back(std::move(s));
      plan.case_models.push_back(std::move(m));
    } catch (const InputError& e) {
      for (const auto& d : e.diagnostics()) diag.error(d.where, d.message);
    }
  }
  diag.throw_if_any();
  // Each axis against the spec its runs apply it to: the base, or every case's (a field that only
  // a case adds, `travel.reference.length` of a shaped reference, is checked on that case).
  // An axis every case refuses alike (a unit that fits no case) is told once, without a case.
  for (const auto& axis : plan.axes) {
    if (plan.case_bases.empty()) {
      probe_axis(plan.base, request.model_path, axis, "", diag);
      continue;
    }
    std::vector<Diagnostics> per_case(plan.case_bases.size());
    for (size_t c = 0; c < plan.case_bases.size(); ++c)
      probe_axis(plan.case_bases[c], request.model_path, axis, request.cases[c], per_case[c]);
    auto messages = [](const Diagnostics& d) {
      std::vector<std::string> m;
      for (const auto& x : d.list()) m.push_back(x.message);
      return m;
    };
    const bool alike = std::all_of(per_case.begin(), per_case.end(), [&](const Diagnostics& d) {
      return !d.empty() && messages(d) == messages(per_case.front());
    });
    if (alike && per_case.size() > 1) probe_axis(plan.case_bases.front(), request.model_path, axis, "", diag);
    else
      for (const auto& d : per_case)
        for (const auto& x : d.list()) diag.error(x.where, x.message);
  }
  diag.throw_if_any();

  // The points, in run order.
  const int dims = static_cast<int>(plan.axes.size());
  std::vector<std::vector<AxisValue>> points;
  if (request.method == SweepMethod::grid) {
    std::vector<std::vector<AxisValue>> values;
    std::vector<int> sizes;
    long total = 1;
    for (const auto& a : plan.axes) {
      values.push_back(grid_values(a.spec));
      sizes.push_back(static_cast<int>(values.back().size()));
      total *= sizes.back();
      if (total > kMaxRuns) throw InputError(cli, fmt::format("more than {} runs; split the sweep", kMaxRuns));
    }
    for (const auto& idx : grid_indices(sizes)) {
      std::vector<AxisValue> p;
      for (int d = 0; d < dims; ++d) p.push_back(values[static_cast<size_t>(d)][static_cast<size_t>(idx[static_cast<size_t>(d)])]);
      points.push_back(std::move(p));
    }
    plan.description = fmt::format("grid {} = {} runs", fmt::join(sizes, " × "), total);
  } else {
    if (request.samples > kMaxRuns) throw InputError({"--samples", 0, 0}, fmt::format("more than {} runs", kMaxRuns));
    const auto unit = request.method == SweepMethod::lhs ? latin_hypercube_unit(request.samples, dims, request.seed)
                                                         : random_unit(request.samples, dims, request.seed);
    for (const auto& u : unit) {
      std::vector<AxisValue> p;
      for (int d = 0; d < dims; ++d) p.push_back(value_at(plan.axes[static_cast<size_t>(d)].spec, u[static_cast<size_t>(d)]));
      points.push_back(std::move(p));
    }
    plan.description = fmt::format("{}, {} samples, seed {}", method_name(request.method), request.samples, request.seed);
  }

  // Runs: cases outermost.
  const int n_cases = request.cases.empty() ? 1 : static_cast<int>(request.cases.size());
  if (static_cast<long>(points.size()) * n_cases > kMaxRuns)
    throw InputError(cli, fmt::format("more than {} runs; split the sweep", kMaxRuns));
  plan.runs.reserve(points.size() * static_cast<size_t>(n_cases));
  for (int c = 0; c < n_cases; ++c) {
    for (const auto& p : points) {
      SweepRun r;
      r.index = static_cast<long>(plan.runs.size());
      r.case_index = request.cases.empty() ? -1 : c;
      r.values = p;
      plan.runs.push_back(std::move(r));
    }
  }
  if (!request.cases.empty()) plan.description += fmt::format(" × {} cases = {} runs", n_cases, plan.runs.size());

  // Fingerprint: what decides the table (model text, options), so --resume refuses another sweep.
  std::uint64_t h = detail::fnv1a("machdyn-sweep-v1");
  auto add = [&](std::string_view s) { h = detail::fnv1a(s, detail::fnv1a("\x1f", h)); };
  add(text);
  for (const auto& s : request.sets) add(s);
  add("vary");
  for (const auto& v : request.vary) add(v);
  add(method_name(request.method));
  add(std::to_string(request.samples));
  add(std::to_string(request.seed));
  for (const auto& c : request.cases) add(c);
  plan.fingerprint = fmt::format("{:016x}", h);
  return plan;
}

SpecNode run_spec(const SweepPlan& plan, const SweepRun& run) {
  SpecNode s = run.case_index >= 0 ? plan.case_bases[static_cast<size_t>(run.case_index)] : plan.base;
  for (size_t d = 0; d < plan.axes.size(); ++d) apply_set(s, plan.axes[d].target + "=" + run.values[d].text);
  return s;
}

std::vector<const Model*> column_models(const SweepPlan& plan) {
  if (plan.case_models.empty()) return {&plan.base_model};
  std::vector<const Model*> out;
  for (const auto& m : plan.case_models) out.push_back(&m);
  return out;
}

}  // namespace machdyn
