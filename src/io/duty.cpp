#include "machdyn/io/duty.hpp"

#include <algorithm>
#include <atomic>
#include <exception>
#include <thread>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "machdyn/analysis/duty_classes.hpp"
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
  if (auto life = r.positive("design_life", dim::time, 0.0, true)) d.design_life_h = *life / 3600.0;
  if (const SpecNode* rated = r.node("rated")) {
    if (!rated->is_map()) diag.error(rated->loc, "'rated' is a map LINK: rated load (N or N*m, the link's unit)");
    else {
      FieldReader rr(*rated, "'rated'", diag);
      for (const SpecField& f : rated->fields)
        if (auto v = rr.positive(f.first, dim::none)) d.rated.emplace_back(f.first, *v), d.rated_locs.push_back(f.second.loc);
      rr.finish();
    }
  }
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
  const double life_h = d.design_life_h;
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
      const bool per_hour = f.second.find("per_hour") != nullptr;
      if (per_hour && f.second.find("repeat") != nullptr) {
        o.node("repeat");  // known, only not with per_hour: one message, not a second "unknown field"
        o.error_at("per_hour", "give either 'repeat' (a count) or 'per_hour' (with the duty's design_life), not both");
      }
      if (per_hour) {
        if (auto n = o.quantity("per_hour", dim::none)) {
          if (!(*n >= 0.0) || !std::isfinite(*n))
            o.error_at("per_hour", fmt::format("the operations per hour are a number >= 0, not {}", *n));
          else if (!(life_h > 0.0))
            o.error_at("per_hour", "'per_hour' needs the duty's 'design_life' (hours of operation of the design life)");
          else if (const double total = std::round(*n * life_h); total > 1e15)
            o.error_at("per_hour", fmt::format("{} per hour over {} h is more than 1e15 operations", *n, life_h));
          else
            op.per_hour = *n, op.repeat = total;
        }
      } else if (auto n = o.quantity("repeat", dim::none)) {
        if (!(*n >= 0.0) || *n != std::floor(*n) || *n > 1e15)
          o.error_at("repeat", fmt::format("the repetitions are a whole number >= 0, not {}", *n));
        op.repeat = *n;
      }
      o.finish();
      d.operations.push_back(op);
    }
  if (!d.operations.empty() &&
      std::all_of(d.operations.begin(), d.operations.end(), [](const DutyOperation& op) { return op.repeat == 0.0; }))
    diag.error(ops->loc, "every operation is done 0 times: the duty's load history is empty");
  r.finish();
  diag.throw_if_any();
  return d;
}

namespace {

/// What one operation's run leaves: per chosen link its kept turning points (append_turning_point),
/// its range and its ∫|P|³ dt.
struct OperationRun {
  std::vector<std::vector<double>> points;
  std::vector<double> lo, hi;
  std::vector<double> cube, seconds, peak;  ///< ∫|P|³ dt, its running time and max |P| (CubicLoadIntegral)
};

/// An operation's run, or the error that stopped it, packed for rank 0 (MPI): doubles and counts as
/// their bytes (ranks of one job share the byte order), an error as its kind and message.
struct Packer {
  std::string bytes;
  void put(double v) { bytes.append(reinterpret_cast<const char*>(&v), sizeof v); }
  void put(std::size_t n) { put(static_cast<double>(n)); }
  void put(const std::vector<double>& v) {
    put(v.size());
    bytes.append(reinterpret_cast<const char*>(v.data()), v.size() * sizeof(double));
  }
  void put(const std::string& s) {
    put(s.size());
    bytes.append(s);
  }
};

struct Unpacker {
  const std::string& bytes;
  std::size_t at = 0;
  double number() {
    if (at + sizeof(double) > bytes.size()) throw std::runtime_error("duty: a rank's results were cut short");
    double v;
    std::memcpy(&v, bytes.data() + at, sizeof v);
    at += sizeof v;
    return v;
  }
  std::size_t count() { return static_cast<std::size_t>(number()); }
  std::vector<double> numbers() {
    std::vector<double> v(count());
    if (at + v.size() * sizeof(double) > bytes.size()) throw std::runtime_error("duty: a rank's results were cut short");
    if (!v.empty()) std::memcpy(v.data(), bytes.data() + at, v.size() * sizeof(double));
    at += v.size() * sizeof(double);
    return v;
  }
  std::string text() {
    const std::size_t n = count();
    if (at + n > bytes.size()) throw std::runtime_error("duty: a rank's results were cut short");
    std::string s = bytes.substr(at, n);
    at += n;
    return s;
  }
};

// Error kinds across ranks: a solver failure keeps its element and time; anything else its message.
enum class RemoteError { none = 0, solver = 1, other = 2 };

void pack_run(Packer& p, std::size_t index, const OperationRun& run, const std::exception_ptr& error) {
  p.put(index);
  if (error) {
    try {
      std::rethrow_exception(error);
    } catch (const SolverError& e) {
      p.put(static_cast<double>(RemoteError::solver)), p.put(e.element()), p.put(e.time()), p.put(std::string(e.what()));
    } catch (const std::exception& e) {
      p.put(static_cast<double>(RemoteError::other)), p.put(std::string(e.what()));
    }
    return;
  }
  p.put(static_cast<double>(RemoteError::none));
  p.put(run.points.size());
  for (const auto& v : run.points) p.put(v);
  for (const auto* v : {&run.lo, &run.hi, &run.cube, &run.seconds, &run.peak}) p.put(*v);
}

void unpack_run(Unpacker& u, std::vector<OperationRun>& runs, std::vector<std::exception_ptr>& errors) {
  const std::size_t i = u.count();
  if (i >= runs.size()) throw std::runtime_error("duty: a rank sent an operation that is not in the duty");
  const auto kind = static_cast<RemoteError>(static_cast<int>(u.number()));
  if (kind == RemoteError::solver) {
    std::string element = u.text();
    const double t = u.number();
    std::string message = u.text();
    // The message is SolverError's own "… in ELEMENT at t = …: WHAT": rebuilt from WHAT, it reads the same.
    const std::string prefix = SolverError(element, t, "").what();
    if (message.starts_with(prefix)) message.erase(0, prefix.size());
    errors[i] = std::make_exception_ptr(SolverError(std::move(element), t, message));
    return;
  }
  if (kind == RemoteError::other) {
    errors[i] = std::make_exception_ptr(std::runtime_error(u.text()));
    return;
  }
  OperationRun& run = runs[i];
  run.points.resize(u.count());
  for (auto& v : run.points) v = u.numbers();
  for (auto* v : {&run.lo, &run.hi, &run.cube, &run.seconds, &run.peak}) *v = u.numbers();
}

/// Runs one operation once, keeping what the counts and k_m need of each chosen link's history.
OperationRun run_operation(const Model& m, const std::vector<int>& links) {
  OperationRun run;
  const std::size_t n = links.size();
  run.points.resize(n);
  std::vector<CubicLoadIntegral> cubes(n);
  run.lo.assign(n, std::numeric_limits<double>::infinity()), run.hi.assign(n, -std::numeric_limits<double>::infinity());
  std::vector<int> slot(m.links.size(), -1);
  for (std::size_t k = 0; k < n; ++k) slot[static_cast<std::size_t>(links[k])] = static_cast<int>(k);
  SimulateOptions opt;
  opt.record_series = false;
  simulate(m, opt, [&](int l, double t, double v) {
    const int k = slot[static_cast<std::size_t>(l)];
    if (k < 0) return;
    const auto j = static_cast<std::size_t>(k);
    append_turning_point(run.points[j], v);
    run.lo[j] = std::min(run.lo[j], v), run.hi[j] = std::max(run.hi[j], v);
    cubes[j].add(t, v);
  });
  for (const CubicLoadIntegral& c : cubes)
    run.cube.push_back(c.integral()), run.seconds.push_back(c.duration()), run.peak.push_back(c.peak());
  return run;
}

/// fn(i) for i in [0, n) on `jobs` threads (0: all cores, shared with the other ranks of this node),
/// each index once; each index's exception is kept in `errors[i]`.
template <class Fn>
void for_each_index(std::size_t n, int jobs, int ranks_on_node, std::vector<std::exception_ptr>& errors, Fn fn) {
  std::atomic<std::size_t> next{0};
  auto work = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < n;) {
      try {
        fn(i);
      } catch (...) {
        errors[i] = std::current_exception();
      }
    }
  };
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency() / static_cast<unsigned>(std::max(1, ranks_on_node)));
  const std::size_t threads = std::min<std::size_t>(n, jobs > 0 ? static_cast<std::size_t>(jobs) : hw);
  if (threads <= 1) {
    work();
  } else {
    std::vector<std::thread> pool;
    for (std::size_t k = 0; k < threads; ++k) pool.emplace_back(work);
    for (auto& t : pool) t.join();
  }
}

}  // namespace

DutyResult run_duty(const std::string& model_path, const std::string& duty_path, const std::vector<std::string>& sets,
                    int jobs, DutyRanks* ranks_of_run) {
  DutyResult out;
  out.spec = read_duty(duty_path, case_names(read_yaml_file(model_path)));
  const DutySpec& duty = out.spec;

  // Every operation's model first (bad input stops before anything runs), the links by name (the
  // first operation's model).
  std::vector<Model> models;
  for (const DutyOperation& op : duty.operations) models.push_back(load_model_case(model_path, sets, op.load_case));
  std::vector<std::string> names, units;
  std::vector<int> links;
  {
    const Model& m = models.front();
    Diagnostics diag;
    for (size_t k = 0; k < duty.links.size(); ++k) {
      int found = -1;
      for (size_t l = 0; l < m.links.size(); ++l)
        if (m.links[l].name == duty.links[k]) found = static_cast<int>(l);
      if (found < 0) diag.error(duty.link_locs[k], fmt::format("the model has no link '{}'", duty.links[k]));
      links.push_back(found);
    }
    if (links.empty())
      for (size_t l = 0; l < m.links.size(); ++l) links.push_back(static_cast<int>(l));
    for (const int l : links)
      if (l >= 0) {
        names.push_back(m.links[static_cast<size_t>(l)].name);
        units.emplace_back(link_load_unit(m, m.links[static_cast<size_t>(l)]));
      }
    for (size_t k = 0; k < duty.rated.size(); ++k)
      if (std::find(names.begin(), names.end(), duty.rated[k].first) == names.end())
        diag.error(duty.rated_locs[k], fmt::format("'rated' names '{}', not a counted link; counted: {}", duty.rated[k].first,
                                                   fmt::join(names, ", ")));
    diag.throw_if_any();
    if (names.empty()) throw InputError(Location{model_path, 0, 0}, "the model has no links to count");
  }

  // Each operation simulated once, on all cores: its link histories kept as turning points; the gate
  // (a fraction of the operation's range, known only at its end) applied to them afterwards, which
  // counts what a counter gated during the run counts (append_turning_point is lossless).
  // Over ranks (`mpirun -np N machdyn duty …`, DutyRanks) rank r runs the operations i with
  // i mod N = r and sends them to rank 0, which merges all in the duty's order as a serial run does;
  // the other ranks return without links (they write nothing).
  const int rank = ranks_of_run ? ranks_of_run->rank() : 0, ranks = ranks_of_run ? ranks_of_run->size() : 1;
  std::vector<std::size_t> mine;
  for (std::size_t i = 0; i < models.size(); ++i)
    if (static_cast<int>(i % static_cast<std::size_t>(ranks)) == rank) mine.push_back(i);
  std::vector<OperationRun> runs(models.size());
  std::vector<std::exception_ptr> errors(models.size()), mine_errors(mine.size());
  for_each_index(mine.size(), jobs, ranks_of_run ? ranks_of_run->on_this_node() : 1, mine_errors,
                 [&](std::size_t k) { runs[mine[k]] = run_operation(models[mine[k]], links); });
  for (std::size_t k = 0; k < mine.size(); ++k) errors[mine[k]] = mine_errors[k];
  if (ranks > 1) {
    if (rank != 0) {
      Packer p;
      for (std::size_t k = 0; k < mine.size(); ++k) pack_run(p, mine[k], runs[mine[k]], errors[mine[k]]);
      ranks_of_run->send_to_root(p.bytes);
      return out;
    }
    for (int source = 1; source < ranks; ++source) {
      const std::string bytes = ranks_of_run->receive_from(source);
      Unpacker u{bytes};
      while (u.at < bytes.size()) unpack_run(u, runs, errors);
    }
  }
  for (const auto& e : errors)  // the first failure in the duty's order, as a serial loop reports it
    if (e) std::rethrow_exception(e);

  std::vector<double> repeats;
  for (const DutyOperation& op : duty.operations) repeats.push_back(op.repeat);
  double running = 0.0;  // Σ n_i T_i, s
  for (size_t i = 0; i < runs.size(); ++i) {
    double t = 0.0;
    for (const double c : runs[i].seconds) t = std::max(t, c);
    out.op_seconds.push_back(t);
    running += repeats[i] * t;
  }
  out.running_hours = running / 3600.0;
  out.utilization_class = utilization_class(out.running_hours);

  for (size_t k = 0; k < links.size(); ++k) {
    std::vector<RainflowPart> of_link;
    double cube = 0.0, peak = 0.0;
    for (size_t i = 0; i < runs.size(); ++i) {
      const OperationRun& r = runs[i];
      const double range = r.hi[k] >= r.lo[k] ? r.hi[k] - r.lo[k] : 0.0;
      of_link.push_back(rainflow_part(r.points[k], duty.gate * range));
      if (repeats[i] > 0.0) cube += repeats[i] * r.cube[k], peak = std::max(peak, r.peak[k]);
    }
    DutyLink l;
    l.link = names[k], l.unit = units[k];
    l.cycles = merge_parts(of_link, repeats, duty.residue);
    l.history = stress_history(l.cycles, duty.m, duty.n_ref);
    if (l.history.total_cycles > 0) l.equivalent_range = equivalent_range(l.cycles, duty.m, l.history.total_cycles);
    if (duty.has_curve) l.damage = miner_damage(l.cycles, duty.curve);
    l.p_max = peak;
    for (const auto& [name, value] : duty.rated)
      if (name == l.link) l.p_max = value, l.rated = true;
    if (running > 0.0 && l.p_max > 0.0) l.k_m = cube / (l.p_max * l.p_max * l.p_max * running);
    l.spectrum_class = spectrum_class(l.k_m);
    l.group = mechanism_group(l.spectrum_class, out.utilization_class);
    l.stress_class = stress_history_class(l.history.s);
    out.links.push_back(std::move(l));
  }
  return out;
}

nlohmann::json duty_json(const DutyResult& r) {
  const DutySpec& duty = r.spec;
  nlohmann::json j;
  j["residue"] = duty.residue == RainflowResidue::repeat ? "repeat" : "half";
  j["gate_fraction"] = duty.gate, j["m"] = duty.m, j["n_ref"] = duty.n_ref;
  if (duty.design_life_h > 0.0) j["design_life_h"] = duty.design_life_h;
  for (size_t i = 0; i < duty.operations.size(); ++i) {
    const DutyOperation& op = duty.operations[i];
    nlohmann::json o = {{"name", op.name}, {"case", op.load_case}, {"repeat", op.repeat}};
    if (op.per_hour >= 0.0) o["per_hour"] = op.per_hour;
    if (i < r.op_seconds.size()) o["seconds"] = r.op_seconds[i];
    j["operations"].push_back(o);
  }
  j["running_hours"] = r.running_hours;
  j["utilization_class"] = fmt::format("T{}", r.utilization_class);
  for (const DutyLink& l : r.links) {
    nlohmann::json e = {{"link", l.link},
                        {"cycles", l.history.total_cycles},
                        {"largest_range", l.history.largest},
                        {"equivalent_range", l.equivalent_range},
                        {"k", l.history.k},
                        {"nu", l.history.nu},
                        {"s", l.history.s},
                        {"stress_history_class", stress_history_class_name(l.stress_class)},
                        {"k_m", l.k_m},
                        {"p_max", l.p_max},
                        {"p_max_rated", l.rated},
                        {"spectrum_class", fmt::format("L{}", l.spectrum_class)},
                        {"mechanism_group", fmt::format("M{}", l.group)}};
    if (duty.has_curve) e["damage"] = l.damage;
    j["links"].push_back(e);
  }
  return j;
}

std::string duty_table(const DutyResult& r) {
  const bool curve = r.spec.has_curve;
  std::string table = fmt::format("{:<16} {:>14} {:>14} {:>14} {:>12} {:>4} {:>8} {:>4} {:>4} {:>12}\n", "link",
                                  "cycles", "largest range", "equiv. range", "s", "S", "k_m", "L", "M",
                                  curve ? "damage" : "");
  for (const DutyLink& l : r.links)
    table += fmt::format("{:<16} {:>14.6g} {:>14.6g} {:>14.6g} {:>12.4g} {:>4} {:>8.4f} {:>4} {:>4} {:>12}\n", l.link,
                         l.history.total_cycles, l.history.largest, l.equivalent_range, l.history.s,
                         stress_history_class_name(l.stress_class), l.k_m, fmt::format("L{}", l.spectrum_class),
                         fmt::format("M{}", l.group),
                         curve ? fmt::format("{:.4g}", l.damage) : std::string());
  table += fmt::format("running time {:.6g} h (T{}){}; k_m over it, P_max the {}\n", r.running_hours, r.utilization_class,
                       r.spec.design_life_h > 0.0 ? fmt::format(" of a design life of {:.6g} h", r.spec.design_life_h) : "",
                       r.spec.rated.empty() ? "largest |load| of the duty" : "rated load where given, else the largest |load|");
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
