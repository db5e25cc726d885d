// machdyn._machdyn: the C++ half of the Python module, a thin layer over the library functions the
// CLI calls (io/yaml_reader → model/cases compile → analysis/simulate → io/results). Everything
// numpy, pandas or matplotlib is in machdyn/*.py; this file only converts. Long calls (simulate,
// sweep, report) release the GIL: they read an immutable Model and write only their own result, so
// runs from several Python threads are safe.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>

#include "machdyn/model/element.hpp"
#include "machdyn/analysis/audit.hpp"
#include "machdyn/analysis/energy.hpp"
#include "machdyn/analysis/linear_analysis.hpp"
#include "machdyn/analysis/modes.hpp"
#include "machdyn/io/linear_results.hpp"
#include "machdyn/analysis/simulate.hpp"
#include "machdyn/analysis/extra_outputs.hpp"
#include "machdyn/analysis/rainflow.hpp"
#include "machdyn/common/diagnostics.hpp"
#include "machdyn/common/units.hpp"
#include "machdyn/gears/gear_model.hpp"
#include "machdyn/gears/synthesis.hpp"
#include "machdyn/gears/tooth_profile.hpp"
#include "machdyn/io/energy_results.hpp"
#include "machdyn/io/figures.hpp"
#include "machdyn/analysis/crane.hpp"
#include "machdyn/io/crane_results.hpp"
#include "machdyn/io/duty.hpp"
#include "machdyn/io/gears_output.hpp"
#include "machdyn/io/model_file.hpp"
#include "machdyn/io/report.hpp"
#include "machdyn/io/report_run.hpp"
#include "machdyn/io/results.hpp"
#include "machdyn/io/yaml_reader.hpp"
#include "machdyn/io/input_file.hpp"
#include "machdyn/io/output_file.hpp"
#include "machdyn/model/cases.hpp"
#include "machdyn/model/compile.hpp"
#include "machdyn/model/sheaves.hpp"
#include "machdyn/sweep/runner.hpp"

namespace py = pybind11;
using namespace machdyn;

namespace {

/// A compiled model with what it was compiled from, so that a case or a sweep can start again from
/// the file's spec (as `machdyn simulate --case` and `machdyn sweep` do).
struct PyModel {
  std::string source;       ///< file path, or the name given to a string ("<string>")
  bool from_file = false;
  std::string text;         ///< the YAML text as loaded (a sweep parses it again, never the file)
  SpecNode file_spec;       ///< the file as read, before case and overrides
  std::vector<std::string> sets;  ///< NAME.FIELD=VALUE, in order
  std::string load_case;
  std::shared_ptr<const Model> model;
};

std::shared_ptr<PyModel> compile(SpecNode spec, std::string source, bool from_file, std::string text,
                                 std::vector<std::string> sets, std::string load_case) {
  auto p = std::make_shared<PyModel>();
  p->model = std::make_shared<const Model>(compile_model_case(spec, source, sets, load_case));
  p->source = std::move(source), p->from_file = from_file, p->text = std::move(text);
  p->file_spec = std::move(spec), p->sets = std::move(sets), p->load_case = std::move(load_case);
  return p;
}

/// A run's result, kept alive by the numpy arrays that view its columns.
struct PyResult {
  std::shared_ptr<const Model> model;
  SimulationResult result;
};

const char* kind_name(BodyKind k) { return k == BodyKind::rotational ? "rotational" : "translational"; }
const char* kind_name(LinkKind k) {
  return k == LinkKind::spring ? "spring" : k == LinkKind::damper ? "damper" : "spring-damper";
}
const char* kind_name(LoadKind k) {
  switch (k) {
    case LoadKind::constant: return "constant";
    case LoadKind::signal: return "signal";  // loads() names the signal's kind instead
    case LoadKind::expression: return "expression";
    case LoadKind::speed_table: return "table-speed";
    case LoadKind::position_table: return "table-position";
    case LoadKind::drag: return "drag";
    case LoadKind::eddy_current: return "eddy-current-brake";
    case LoadKind::motor_linear: return "motor-linear";
    case LoadKind::motor_kloss: return "motor-kloss";
    case LoadKind::motor_table: return "motor-table";
  }
  return "?";
}

py::list bodies(const Model& m) {
  py::list out;
  for (const auto& b : m.bodies) {
    if (is_sheave_body(m, static_cast<int>(&b - m.bodies.data()))) continue;  // a rope's (model/sheaves.hpp)
    const bool rot = b.kind == BodyKind::rotational;
    py::dict d;
    d["name"] = b.name, d["type"] = kind_name(b.kind);
    d[rot ? "inertia_kg_m2" : "mass_kg"] = b.inertia;
    d[rot ? "position_rad" : "position_m"] = b.q0;
    d[rot ? "velocity_rad_s" : "velocity_m_s"] = b.v0;
    d["variable_inertia"] = static_cast<bool>(b.machine);
    out.append(d);
  }
  return out;
}

py::list links(const Model& m) {
  py::list out;
  for (const auto& l : m.links) {
    py::dict d;
    d["name"] = l.name, d["type"] = kind_name(l.kind);
    d["between"] = py::make_tuple(shown_body(m, l.a, l.given_a), shown_body(m, l.b, l.given_b));
    d["ratio"] = shown_ratio(m, l), d["stiffness"] = l.c, d["damping"] = l.d;
    d["load_unit"] = link_load_unit(m, l);
    d["gap"] = l.has_gap ? py::cast(l.gap) : py::none();
    out.append(d);
  }
  return out;
}

py::list loads(const Model& m) {
  py::list out;
  for (const auto& l : m.loads) {
    py::dict d;
    d["name"] = l.name, d["type"] = l.kind == LoadKind::signal ? Signal::kind_name(l.signal.kind()) : kind_name(l.kind),
    d["body"] = shown_body(m, l.body, l.given_body), d["value"] = shown_value(m, l);
    out.append(d);
  }
  return out;
}

py::list drives(const Model& m) {
  py::list out;
  for (const auto& d : m.drives) {
    py::dict e;
    e["name"] = d.name, e["type"] = d.law->type();
    e["body"] = shown_body(m, d.body, d.given_body), e["states"] = d.states();
    if (!d.others.empty()) {  // an element between two bodies (its "other") or on several ("others")
      py::list others;
      for (size_t p = 0; p < d.others.size(); ++p)
        others.append(py::str(shown_body(m, d.others[p], p < d.given_others.size() ? d.given_others[p] : "")));
      e["other"] = py::str(shown_body(m, d.others[0], d.given_others.empty() ? "" : d.given_others[0]));
      if (d.others.size() > 1) e["others"] = others;
    }
    out.append(e);
  }
  return out;
}

py::list contacts(const Model& m) {
  py::list out;
  for (const auto& c : m.contacts) {
    py::dict d;
    d["name"] = c.name, d["type"] = c.brake ? "brake" : "contact";
    d["between"] = py::make_tuple(shown_body(m, c.a, c.given_a), shown_body(m, c.b, c.given_b));
    d["static_limit"] = c.static_limit;
    out.append(d);
  }
  return out;
}

py::dict settings(const Model& m) {
  const auto& s = m.simulation;
  py::dict d;
  d["t_end_s"] = s.t_end, d["dt_out_s"] = s.dt_out, d["rtol"] = s.rtol, d["atol"] = s.atol;
  d["integrator"] = s.integrator == IntegratorChoice::automatic ? "auto"
                    : s.integrator == IntegratorChoice::dopri5  ? "dopri5"
                                                                : "bdf";
  d["max_steps"] = s.max_steps;
  return d;
}

py::list events(const SimulationResult& r) {
  py::list out;
  for (const auto& e : r.hybrid.events) {
    py::dict d;
    d["t_s"] = e.t, d["kind"] = e.kind, d["element"] = e.element, d["from"] = e.from, d["to"] = e.to;
    out.append(d);
  }
  return out;
}

/// Runs `f` without the GIL.
template <class F>
auto nogil(F&& f) {
  py::gil_scoped_release release;
  return f();
}

}  // namespace

PYBIND11_MODULE(_machdyn, mod) {
  mod.doc() = "machdyn C++ core (use the `machdyn` package, not this module)";
  mod.attr("__version__") = MACHDYN_VERSION;
  mod.attr("spec_max_depth") = kSpecMaxDepth;  // io/yaml_reader.hpp (from_dict checks a dict's depth)

  // Errors: InputError carries every diagnostic (file, line, column, message); SolverError the
  // element and the time. Both derive from the Python exceptions a user would expect.
  static py::exception<InputError> input_error(mod, "InputError", PyExc_ValueError);
  static py::exception<SolverError> solver_error(mod, "SolverError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const InputError& e) {
      py::list diags;
      std::string text;
      for (const auto& d : e.diagnostics()) {
        diags.append(py::make_tuple(d.where.file, d.where.line, d.where.column, d.message));
        text += (text.empty() ? "" : "\n") + d.str();
      }
      py::object exc = py::reinterpret_borrow<py::object>(input_error.ptr())(py::str(text));
      exc.attr("diagnostics") = diags;
      PyErr_SetObject(input_error.ptr(), exc.ptr());
    } catch (const SolverError& e) {
      py::object exc = py::reinterpret_borrow<py::object>(solver_error.ptr())(py::str(e.what()));
      exc.attr("element") = e.element();
      exc.attr("time") = e.time();
      // A violation of the invariant audit (check=True) names its invariant; other failures: None.
      const auto* audit = dynamic_cast<const AuditError*>(&e);
      exc.attr("invariant") = audit ? py::object(py::str(audit->invariant())) : py::object(py::none());
      PyErr_SetObject(solver_error.ptr(), exc.ptr());
    }
  });

  py::class_<PyModel, std::shared_ptr<PyModel>>(mod, "Model")
      .def_property_readonly("name", [](const PyModel& p) { return p.model->name; })
      .def_property_readonly("description", [](const PyModel& p) { return p.model->description; })
      .def_property_readonly("source", [](const PyModel& p) { return p.source; })
      .def_property_readonly("from_file", [](const PyModel& p) { return p.from_file; })
      .def_property_readonly("text", [](const PyModel& p) { return p.text; })
      .def_property_readonly("sets", [](const PyModel& p) { return p.sets; })
      .def_property_readonly("case", [](const PyModel& p) { return p.load_case; })
      .def_property_readonly("cases", [](const PyModel& p) { return case_names(p.file_spec); })
      .def_property_readonly("dof", [](const PyModel& p) { return p.model->dof(); })
      .def_property_readonly("is_hybrid", [](const PyModel& p) { return p.model->is_hybrid(); })
      .def_property_readonly("bodies", [](const PyModel& p) { return bodies(*p.model); })
      .def_property_readonly("links", [](const PyModel& p) { return links(*p.model); })
      // The links a plot(links=…) draws, checked as the CLI's --links (one message, io/figures.hpp).
      .def("chosen_links",
           [](const PyModel& p, const std::vector<std::string>& names) {
             std::vector<std::string> out;
             for (const std::size_t l : chosen_links(*p.model, names, "links=")) out.push_back(p.model->links[l].name);
             return out;
           })
      .def_property_readonly("loads", [](const PyModel& p) { return loads(*p.model); })
      .def_property_readonly("drives", [](const PyModel& p) { return drives(*p.model); })
      .def_property_readonly("contacts", [](const PyModel& p) { return contacts(*p.model); })
      .def_property_readonly("simulation", [](const PyModel& p) { return settings(*p.model); })
      .def("with_case",
           [](const PyModel& p, const std::string& c) {
             return compile(p.file_spec, p.source, p.from_file, p.text, p.sets, c);
           })
      .def("with_sets", [](const PyModel& p, const std::vector<std::string>& more) {
        auto sets = p.sets;
        sets.insert(sets.end(), more.begin(), more.end());
        return compile(p.file_spec, p.source, p.from_file, p.text, sets, p.load_case);
      });

  mod.def("load_file", [](const std::string& path, const std::vector<std::string>& sets, const std::string& c) {
    // The text is kept: a sweep of this model sweeps what was loaded, not the file as it is later.
    std::string text = read_input_file(path, kMaxModelFileBytes, "file");
    SpecNode spec = parse_yaml_string(text, path);
    return compile(std::move(spec), path, true, std::move(text), sets, c);
  });
  mod.def("load_text", [](const std::string& text, const std::string& source, const std::vector<std::string>& sets,
                          const std::string& c) {
    return compile(parse_yaml_string(text, source), source, false, text, sets, c);
  });

  py::class_<PyResult, std::shared_ptr<PyResult>>(mod, "Result")
      .def_property_readonly("column_names", [](const PyResult& r) { return r.result.column_names; })
      .def("column",
           [](const std::shared_ptr<PyResult>& r, std::size_t k) {
             const auto& c = r->result.columns.at(k);
             // A read-only view of the result's memory; the array keeps the result alive.
             py::array_t<double> a(static_cast<py::ssize_t>(c.size()), c.data(), py::cast(r));
             a.attr("flags").attr("writeable") = false;
             return a;
           })
      .def("summary_json", [](const PyResult& r) { return simulation_summary(*r.model, r.result).dump(2); })
      .def("timeseries_csv", [](const PyResult& r) { return timeseries_csv(r.result); })
      .def_property_readonly("events", [](const PyResult& r) { return events(r.result); })
      .def_property_readonly("hybrid", [](const PyResult& r) { return r.result.hybrid.active; })
      .def_property_readonly("method_reason", [](const PyResult& r) { return r.result.method_reason; })
      .def_property_readonly("wall_time_s", [](const PyResult& r) { return r.result.stats.wall_time_s; });

  mod.def("simulate", [](const PyModel& p, const std::vector<std::string>& outputs, bool check) {
    auto r = std::make_shared<PyResult>();
    r->model = p.model;
    const OutputSelection extra = output_selection(outputs);  // the groups of `--outputs`
    SimulateOptions options;
    options.check = check;  // the invariant audit, as `--check`
    r->result = nogil([&] { return simulate(*p.model, options, extra); });
    return r;
  }, pybind11::arg("model"), pybind11::arg("outputs") = std::vector<std::string>{}, pybind11::arg("check") = false);

  // Rainflow counting of any series (analysis/rainflow.hpp): the cycles as five arrays.
  mod.def("rainflow", [](py::array_t<double, py::array::c_style | py::array::forcecast> series, double gate_fraction,
                         bool repeat) {
    if (series.ndim() != 1) throw py::value_error("rainflow: the series must be one-dimensional");
    const std::span<const double> x(series.data(), static_cast<std::size_t>(series.size()));
    RainflowOptions opt;
    opt.gate_fraction = gate_fraction;
    opt.residue = repeat ? RainflowResidue::repeat : RainflowResidue::half_cycles;
    const std::vector<RainflowCycle> cs = nogil([&] { return rainflow(x, opt); });
    const auto n = static_cast<py::ssize_t>(cs.size());
    py::array_t<double> from(n), to(n), count(n), range(n), mean(n);
    auto f = from.mutable_unchecked<1>(), t = to.mutable_unchecked<1>(), c = count.mutable_unchecked<1>(),
         r = range.mutable_unchecked<1>(), mu = mean.mutable_unchecked<1>();
    for (py::ssize_t k = 0; k < n; ++k) {
      const RainflowCycle& y = cs[static_cast<std::size_t>(k)];
      f(k) = y.from, t(k) = y.to, c(k) = y.count, r(k) = y.range(), mu(k) = y.mean();
    }
    py::dict d;
    d["range"] = range, d["mean"] = mean, d["count"] = count, d["from"] = from, d["to"] = to;
    return d;
  }, py::arg("series"), py::arg("gate_fraction") = 0.0, py::arg("repeat") = false);

  // A duty (io/duty.hpp), as `machdyn duty` runs it: duty.json's dict and the cycles per link.
  mod.def("duty", [](const std::string& model_path, const std::string& duty_path, const std::vector<std::string>& sets) {
    const DutyResult r = nogil([&] { return run_duty(model_path, duty_path, sets); });
    return py::make_tuple(duty_json(r).dump(), duty_cycles_csv(r));
  });

  // For bench/python_bench.py: the median wall time of `repeats` calls of simulate() timed in C++,
  // the reference for the Python call's overhead.
  mod.def("_time_simulate", [](const PyModel& p, int repeats) {
    return nogil([&] {
      std::vector<double> t;
      for (int k = 0; k < repeats; ++k) {
        const auto a = std::chrono::steady_clock::now();
        const SimulationResult r = simulate(*p.model);
        t.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - a).count());
      }
      std::sort(t.begin(), t.end());
      return t.empty() ? 0.0 : t[t.size() / 2];
    });
  });

  // As `machdyn modes [--topology TEXT]`: every topology (or the one named), the first one's
  // frequencies and shapes as arrays.
  mod.def("modes", [](const PyModel& p, const std::string& topology) {
    const Model& m = *p.model;
    std::vector<TopologyModes> list;
    if (topology.empty())
      for (const Topology& t : all_topologies(m)) list.push_back(analyse_topology(m, t));
    else
      list.push_back(analyse_topology(m, parse_topology(m, topology, Location{"topology", 1, 0})));
    return py::make_tuple(linear_modes_json(m, list).dump(), list.front().modes.omega, list.front().modes.shapes);
  });

  mod.def("energy", [](const PyModel& p, const std::string& to, int points, double delta,
                       const std::string& mean_speed) {
    const Model& m = *p.model;
    auto quantity = [](const std::string& what, const std::string& text, const Dim& d) {
      std::string err;
      auto v = parse_as(text, d, &err);
      if (!v) throw InputError(Location{what, 0, 0}, err);
      return *v;
    };
    EnergyOptions opt;
    opt.points = points;
    if (!to.empty()) opt.s_to = quantity("to", to, dim::none);
    const EnergyResult r = energy_analysis(m, opt);
    nlohmann::json j = energy_json(m, r);
    if (delta > 0) {
      const double wm = mean_speed.empty() ? std::abs(m.bodies[0].v0) : quantity("mean_speed", mean_speed, dim::angular_velocity);
      j["steady"] = steady_json(steady_running(m, wm, delta));
    }
    return j.dump();
  });

  // As `machdyn crane --json`: the crane table (analysis/crane.hpp), GIL released for its runs.
  mod.def("crane", [](const PyModel& p, const std::vector<int>& drive_classes) {
    return nogil([&] { return crane_json(crane_analysis(*p.model, drive_classes)).dump(); });
  });

  mod.def("gears", [](const std::string& path, const std::vector<std::string>& sets) {
    SpecNode root = read_yaml_file(path);
    for (const auto& s : sets) apply_set(root, s);
    const gears::GearModel model = gears::compile_gears(root);
    const gears::GearSynthesis syn = gears::synthesize(model);
    const gears::ToothProfiles teeth = gears::generate_profiles(model, syn);
    const gears::SpeedUniformity speed = gears::speed_uniformity(model, syn);
    const io::GearReport report{model, syn, speed, teeth};
    return py::make_tuple(io::gears_json(report), io::gears_text(report));
  });

  // As `machdyn report`: the one pipeline of the CLI (io/report_run.hpp), so the same sections.
  mod.def("report_html", [](const PyModel& p, const std::string& command, const std::string& frf_input,
                            const std::vector<std::string>& frf_outputs, double f_lo_hz, double f_hi_hz,
                            const std::vector<std::string>& links) {
    report::ReportOptions opt;
    opt.frf.input = frf_input, opt.frf.outputs = frf_outputs, opt.frf.f_lo_hz = f_lo_hz, opt.frf.f_hi_hz = f_hi_hz;
    opt.frf.option_prefix = "frf_";
    opt.links = links;
    opt.links_option = "links=";
    return nogil([&] {
      report::ReportRun run;
      run.name = p.load_case;
      run.model = *p.model;
      report::run_report_case(run, opt);
      return report::to_html(report::simulation_report({run.as_case()}, command));
    });
  });

  // A result file as every machdyn writer writes it (io/output_file.hpp): atomically, and never over
  // an input file of this process (the model, also through a link) nor over a device or FIFO.
  mod.def("write_result_file", [](const std::string& path, const std::string& text) {
    if (const std::string problem = output_target_problem(path); !problem.empty())
      throw InputError(Location{path, 0, 0}, "refusing to write here: " + problem);
    nogil([&] { write_file_atomic(path, std::string_view(text)); });
  });

  // A sweep as `machdyn sweep` runs it (sweep/plan.hpp, sweep/runner.hpp): same designs, same table.
  mod.def("sweep", [](const PyModel& p, const std::vector<std::string>& vary, const std::string& method, int samples,
                      std::uint64_t seed, const std::vector<std::string>& cases, const std::string& out_dir, int jobs,
                      bool resume) {
    SweepRequest req;
    req.model_path = p.source;
    req.model_text = p.text;  // the loaded model, never the file again (it may have changed since)
    req.sets = p.sets;
    req.vary = vary;
    if (method != "grid" && method != "lhs" && method != "random")
      throw InputError(Location{"method", 0, 0}, "expected grid, lhs or random, not '" + method + "'");
    req.method = method == "lhs" ? SweepMethod::lhs : method == "random" ? SweepMethod::random : SweepMethod::grid;
    req.samples = samples;
    req.seed = seed;
    req.cases = cases;
    req.apply_case = [](SpecNode& spec, const std::string& name) { apply_case(spec, name); };
    const SweepPlan plan = make_sweep_plan(req);
    SweepOptions opt;
    opt.out_dir = out_dir;
    opt.jobs = jobs;
    opt.resume = resume;
    // Ctrl-C: run_sweep calls `progress` on this thread every 0.1 s; a pending KeyboardInterrupt
    // stops new runs (finished ones stay in the journal, for resume=True) and is raised afterwards.
    std::atomic<bool> stop{false};
    bool interrupted = false;
    opt.stop = &stop;
    opt.progress = [&](const SweepProgress&) {
      if (interrupted) return;
      py::gil_scoped_acquire gil;
      if (PyErr_CheckSignals() != 0) interrupted = true, stop = true;
    };
    const SweepOutcome r = nogil([&] { return run_sweep(plan, opt); });
    if (interrupted) throw py::error_already_set();
    py::dict d;
    d["table_path"] = r.table_path, d["total"] = r.total, d["ok"] = r.ok, d["errors"] = r.errors;
    d["threads"] = r.threads, d["wall_s"] = r.wall_s, d["description"] = plan.description;
    return d;
  });
}
