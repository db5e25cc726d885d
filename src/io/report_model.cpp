// The content of `machdyn report`: the model as tables with units, run settings, results, plots.
#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "machdyn/analysis/mode_kinds.hpp"
#include "machdyn/model/describe.hpp"
#include "machdyn/model/element.hpp"
#include "machdyn/model/sheaves.hpp"
#include "machdyn/io/figures.hpp"
#include "machdyn/io/report.hpp"
#include "machdyn/io/crane_results.hpp"
#include "machdyn/io/linear_results.hpp"
#include "io/report_brakes.hpp"
#include "io/report_sway.hpp"

namespace machdyn::report {

namespace {

using plot::pretty_unit;

Table table(std::string caption, std::vector<std::string> header) {
  Table t;
  t.caption = std::move(caption);
  t.header = std::move(header);
  return t;
}

std::string num(double v) {
  if (!std::isfinite(v)) return "–";
  return fmt::format("{:.6g}", v);
}

std::string body_name(const Model& m, int b) {
  return b == kGround ? std::string("ground") : m.bodies[static_cast<std::size_t>(b)].name;
}

/// A link's ends as the file names them (compile may have moved them: model.hpp, Link::given_a).
std::string ends(const Model& m, const Link& l) {
  return shown_body(m, l.a, l.given_a) + " – " + shown_body(m, l.b, l.given_b);
}

/// The coordinate a link's load and stiffness are measured in: body b, or a for a link to the ground.
BodyKind link_kind_body(const Model& m, const Link& l) {
  const int b = l.b != kGround ? l.b : l.a;
  return b == kGround ? BodyKind::rotational : m.bodies[static_cast<std::size_t>(b)].kind;
}

std::string ratio_unit(const Model& m, const Link& l) {
  const int a = rope_drum(m, l);  // a rope's drum, also behind its sheave losses (model/sheaves.hpp)
  if (a == kGround || l.b == kGround) return "";
  const auto ka = m.bodies[static_cast<std::size_t>(a)].kind, kb = m.bodies[static_cast<std::size_t>(l.b)].kind;
  if (ka == kb) return "";
  return std::string(position_unit(ka)) + "/" + position_unit(kb);
}

/// A motor's contactor and direction, or another load's `scale`, if switched.
std::string switching(const Load& L) {
  if (!L.switched) return "";
  const bool motor = L.kind == LoadKind::motor_linear || L.kind == LoadKind::motor_kloss || L.kind == LoadKind::motor_table;
  if (!motor) return fmt::format("; scale: {}", L.on.describe(""));
  return fmt::format("; on: {}; direction: {}", L.on.describe(""), L.direction.describe(""));
}

std::string load_description(const Model& m, const Load& L) {
  const auto kind = m.bodies[static_cast<std::size_t>(L.body)].kind;
  const std::string u = pretty_unit(load_unit(kind)), vu = pretty_unit(velocity_unit(kind));
  const char* sym = kind == BodyKind::translational ? "F" : "M";
  switch (L.kind) {
    case LoadKind::constant: return fmt::format("{} = {} {}", sym, num(shown_value(m, L)), u);
    case LoadKind::signal: return fmt::format("{}(t): {}", sym, L.signal.describe(u));
    case LoadKind::expression: return fmt::format("{} = {} [{}]", sym, L.law->text(), u);
    case LoadKind::speed_table: return fmt::format("{}(v) over the speed [{}]: {}", sym, vu, L.signal.describe(u));
    case LoadKind::position_table: return fmt::format("{}(q) over the position: {}", sym, L.signal.describe(u));
    case LoadKind::drag: return fmt::format("drag {} = −k v|v|, k = {}", sym, num(L.value));
    case LoadKind::eddy_current:
      return fmt::format("eddy-current brake: M_k = {} {} at ω_k = {} {}", num(L.value), u, num(L.omega0), vu);
    case LoadKind::motor_linear:
      return fmt::format("linear motor: stall {} {}, no-load speed ω0 = {} {}{}", num(L.value), u, num(L.omega0), vu,
                         switching(L));
    case LoadKind::motor_kloss:
      return fmt::format("Kloss motor: breakdown {} {}, slip s_k = {}, synchronous ω0 = {} {}{}", num(L.value), u,
                         num(L.s_k), num(L.omega0), vu, switching(L));
    case LoadKind::motor_table:
      return fmt::format("motor, catalogue curve over the speed [{}]: {}{}", vu, L.signal.describe(u), switching(L));
  }
  return "";
}

const char* load_kind(LoadKind k) {
  switch (k) {
    case LoadKind::constant: return "constant";
    case LoadKind::signal: return "signal";
    case LoadKind::expression: return "expression";
    case LoadKind::speed_table: return "speed_table";
    case LoadKind::position_table: return "position_table";
    case LoadKind::drag: return "drag";
    case LoadKind::eddy_current: return "eddy_current";
    case LoadKind::motor_linear: return "motor_linear";
    case LoadKind::motor_kloss: return "motor_kloss";
    case LoadKind::motor_table: return "motor_table";
  }
  return "";
}

const char* integrator_setting(IntegratorChoice c) {
  switch (c) {
    case IntegratorChoice::dopri5: return "dopri5";
    case IntegratorChoice::bdf: return "bdf";
    default: return "auto";
  }
}

Table settings_table(const Model& m, const SimulationResult& r) {
  const auto& s = m.simulation;
  Table t = table("Run settings and solver", {"setting", "value"});
  t.text_values = true;
  t.rows = {{"end time t_end", num(s.t_end) + " s"},
            {"output step dt_out", num(s.dt_out) + " s"},
            {"tolerances rtol / atol", num(s.rtol) + " / " + num(s.atol)},
            {"integrator (setting)", integrator_setting(s.integrator)},
            {"integrator used", r.stats.method + " — " + r.method_reason},
            {"steps (rejected)", fmt::format("{} ({})", r.stats.stepper.steps, r.stats.stepper.rejected)},
            {"right-hand-side evaluations", fmt::format("{}", r.stats.stepper.rhs_evals)},
            {"output rows", fmt::format("{}", r.columns.empty() ? 0 : r.columns[0].size())},
            {"wall time", fmt::format("{:.3g} ms", r.stats.wall_time_s * 1e3)}};
  return t;
}

Table results_table(const Model& m, const SimulationResult& r) {
  Table t = table("Link loads: peaks, quasi-static loads, dynamic factors", {"link", "between", "max", "t_max, s", "min", "t_min, s", "static", "dynamic factor", "unit"});
  for (std::size_t l = 0; l < m.links.size() && l < r.links.size(); ++l) {
    const auto& L = m.links[l];
    const auto& s = r.links[l];
    t.rows.push_back({L.name, ends(m, L), num(s.max), num(s.t_max), num(s.min),
                      num(s.t_min), num(s.static_load), num(s.dynamic_factor), pretty_unit(link_load_unit(m, L))});
  }
  t.note = "Peaks are located on the continuous solution. static: the load of rigid acceleration (the particular "
           "solution, paper 002 eq. 22) with the loads acting at t_max; dynamic factor = max / static.";
  return t;
}

Table modes_table(const Model& m, const Modes& modes) {
  Table t = table("Natural frequencies and mass-normalized mode shapes", {"mode", "ω, rad/s", "f, Hz"});
  // A swinging load's model: each mode's kind (analysis/mode_kinds.hpp).
  const bool kinds = has_swinging_load(m);
  const std::vector<ModeKind> kind = kinds ? mode_kinds(m, modes.shapes) : std::vector<ModeKind>{};
  if (kinds) t.header.push_back("kind");
  for (const auto& b : m.bodies) t.header.push_back("φ(" + b.name + ")");
  for (Eigen::Index k = 0; k < modes.omega.size(); ++k) {
    std::vector<std::string> row{fmt::format("{}", k + 1), num(modes.omega(k)), num(modes.omega(k) / (2 * std::numbers::pi))};
    if (kinds) row.push_back(to_string(kind[static_cast<size_t>(k)]));
    for (Eigen::Index i = 0; i < modes.shapes.rows(); ++i) row.push_back(fmt::format("{:+.4f}", modes.shapes(i, k)));
    t.rows.push_back(std::move(row));
  }
  t.note = fmt::format("{} rigid-body mode(s). Shapes: φᵀ M φ = 1, largest entry positive; units 1/√(kg·m²) "
                       "(rotational) or 1/√kg (translational).", modes.rigid_body_modes);
  return t;
}

}  // namespace

Table events_table(const SimulationResult& r) {
  Table t = table("Mode events (gaps, stick and slip)", {"t, s", "kind", "element", "from", "to"});
  const auto& ev = r.hybrid.events;
  for (std::size_t k = 0; k < ev.size() && k < kMaxEventRows; ++k)
    t.rows.push_back({fmt::format("{:.9g}", ev[k].t), ev[k].kind, ev[k].element, ev[k].from.empty() ? "–" : ev[k].from,
                      ev[k].to});
  long changes = 0;
  for (const auto& e : ev) changes += e.kind != "initial";
  t.note = fmt::format("{} mode events (the `initial` rows give the modes at t = 0), located to ~1e-13 s.", changes);
  if (ev.size() > kMaxEventRows)
    t.note += fmt::format(" The first {} of {} rows are shown; all are in summary.json.", kMaxEventRows, ev.size());
  t.collapsed = t.rows.size() > 12;
  return t;
}

Table slip_phases_table(const Model& m, const SimulationResult& r) {
  Table t = table("Slip phases with the link loads at breakaway and their maxima",
                  {"#", "contact", "direction", "t_start, s", "t_end, s", "duration, s"});
  for (const auto& L : m.links) {
    const std::string u = pretty_unit(link_load_unit(m, L));
    t.header.push_back(fmt::format("{} at breakaway, {}", L.name, u));
    t.header.push_back(fmt::format("{} max, {}", L.name, u));
  }
  const auto& ph = r.hybrid.slip_phases;
  for (std::size_t k = 0; k < ph.size() && k < kMaxEventRows; ++k) {
    const auto& p = ph[k];
    std::vector<std::string> row{fmt::format("{}", k + 1), p.contact, p.direction > 0 ? "u > 0" : "u < 0",
                                 fmt::format("{:.6g}", p.t_start), fmt::format("{:.6g}", p.t_end),
                                 fmt::format("{:.4g}", p.t_end - p.t_start)};
    for (std::size_t l = 0; l < m.links.size(); ++l) {
      row.push_back(l < p.link_start.size() ? num(p.link_start[l]) : "–");
      row.push_back(l < p.link_max.size() ? num(p.link_max[l]) : "–");
    }
    t.rows.push_back(std::move(row));
  }
  t.note = "Breakaway: the link load at the located start of the phase (the exact slip limit); max: the largest "
           "link load inside the phase (its time is in summary.json, slip_phases). ";
  if (ph.size() > kMaxEventRows) t.note += fmt::format("The first {} of {} phases are shown.", kMaxEventRows, ph.size());
  t.collapsed = t.rows.size() > 12;
  return t;
}

Table cases_table(const std::vector<Case>& cases) {
  Table t = table("Load cases compared: peak link loads and dynamic factors",
                  {"case", "link", "max", "min", "peak", "t_peak, s", "static", "dynamic factor", "unit", "events"});
  for (const auto& c : cases) {
    const Model& m = *c.model;
    const SimulationResult& r = *c.result;
    long events = 0;
    for (const auto& e : r.hybrid.events) events += e.kind != "initial";
    for (std::size_t l = 0; l < m.links.size() && l < r.links.size(); ++l) {
      const LinkSummary& p = r.links[l];
      t.rows.push_back({l == 0 ? c.name : "", m.links[l].name, num(r.links[l].max), num(r.links[l].min), num(p.peak),
                        num(p.t_peak), num(p.static_load), p.dynamic_factor == p.dynamic_factor ? fmt::format("{:.3g}", p.dynamic_factor) : "–",
                        pretty_unit(link_load_unit(m, m.links[l])), l == 0 ? fmt::format("{}", events) : ""});
    }
  }
  t.note = "peak: the extreme of larger magnitude; static: the quasi-static load (particular solution) with the "
           "loads acting at that time; dynamic factor = peak / static (large but harmless where the static load is "
           "small). events: mode changes of gaps, contacts and brakes.";
  return t;
}

std::vector<Table> model_tables(const Model& m) {
  Table bodies = table("Bodies", {"body", "type", "inertia / mass", "unit", "initial position", "initial velocity"});
  for (const auto& b : m.bodies) {
    if (is_sheave_body(m, static_cast<int>(&b - m.bodies.data()))) continue;  // a rope's, not the file's (model/sheaves.hpp)
    const bool rot = b.kind == BodyKind::rotational;
    bodies.rows.push_back({b.name, rot ? "rotational" : "translational", num(b.inertia), rot ? "kg·m²" : "kg",
                           num(b.q0) + " " + position_unit(b.kind), num(b.v0) + " " + velocity_unit(b.kind)});
  }
  Table links = table("Links", {"link", "type", "between", "ratio i", "stiffness c", "damping d", "as written"});
  for (const auto& l : m.links) {
    const auto kind = link_kind_body(m, l);
    const std::string load = pretty_unit(load_unit(kind)), pos = position_unit(kind);
    const std::string ru = ratio_unit(m, l);
    const ElementText text = describe_link(m, l);  // the element's own words (model/describe.hpp)
    links.rows.push_back({l.name, text.type, ends(m, l), num(shown_ratio(m, l)) + (ru.empty() ? "" : " " + ru),
                          l.kind == LinkKind::damper ? "–" : num(l.c) + " " + load + "/" + pos,
                          l.kind == LinkKind::spring ? "–" : num(l.d) + " " + load + "·s/" + pos, pretty_unit(text.definition)});
  }
  const bool gaps = std::any_of(m.links.begin(), m.links.end(), [](const Link& l) { return l.has_gap; });
  if (gaps) {
    links.header.push_back("gap Δ (start)");
    for (std::size_t k = 0; k < m.links.size(); ++k) {
      const auto& l = m.links[k];
      const std::string pos = position_unit(link_kind_body(m, l));
      links.rows[k].push_back(!l.has_gap         ? "–"
                              : l.tension_only ? fmt::format("one flank at δ = {} {}", num(l.gap), pos)
                                               : fmt::format("{} {} ({} {})", num(l.gap), pos, num(l.gap_start), pos));
    }
  }
  links.note = "Deflection δ = q_a / i − q_b, load F = c δ + d δ̇ (positive: tension), in the coordinate of the second body.";
  if (gaps) links.note += " Gap: the link carries load only on a flank; start: the position inside the gap at δ = 0.";
  Table contacts = table("Friction contacts, brakes, clutches, freewheels and end stops",
                         {"element", "type", "between", "as written"});
  for (const auto& c : m.contacts) {
    if (c.joint) continue;  // a gear joint is no friction element
    const ElementText text = describe_contact(m, c);  // the element's own words (model/describe.hpp)
    contacts.rows.push_back({c.name, text.type, shown_body(m, c.a, c.given_a) + " – " + shown_body(m, c.b, c.given_b),
                             pretty_unit(text.definition)});
  }
  contacts.text_values = true;
  contacts.note = "Stuck while the transmitted force stays within F_s; sliding with F_k against the sliding velocity "
                  "u = v_a − v_b (docs/hybrid.md).";
  Table gears = table("Gearboxes", {"gear", "type", "as written"});
  for (const ElementText& g : describe_gears(m)) gears.rows.push_back({g.name, g.type, pretty_unit(g.definition)});
  gears.text_values = true;
  gears.note = "An ideal gear ties its bodies rigidly (compile merges them into one coordinate); a lossy gear keeps "
               "both and loses power by its efficiencies (docs/model-files.md, lossy gears).";
  Table loads = table("Loads", {"load", "type", "body", "definition"});
  for (const auto& L : m.loads)
    loads.rows.push_back({L.name, L.kind == LoadKind::signal ? Signal::kind_name(L.signal.kind()) : load_kind(L.kind),
                          shown_body(m, L.body, L.given_body), load_description(m, L)});
  Table drives = table("Drives", {"drive", "type", "body", "definition"});
  for (const auto& d : m.drives)
    drives.rows.push_back({d.name, d.law->type(),
                           [&] {
                             std::string at = shown_body(m, d.body, d.given_body);
                             for (size_t p = 0; p < d.others.size(); ++p)
                               at += ", " + shown_body(m, d.others[p], p < d.given_others.size() ? d.given_others[p] : "");
                             return at;
                           }(),
                           d.law->describe(m.bodies[static_cast<std::size_t>(d.body)].kind)});
  drives.note = "Elements with states of their own: L di/dt = u − R i − k ω, M = k i (DC motor); PI speed control "
                "M = K_p e + (K_p/T_i) ∫e dt, |M| ≤ M_max, integral held while limited (speed drive); the laws of "
                "the others in docs/model-files.md#drives.";
  Table releases = table("Releases", {"release", "body", "released", "time", "weight change"});
  for (const auto& r : m.releases) {
    const bool tr = m.bodies[static_cast<size_t>(r.body)].kind == BodyKind::translational;
    releases.rows.push_back({r.name, body_name(m, r.body), num(r.amount) + (tr ? " kg" : " kg·m²"), num(r.time) + " s",
                             r.weight_load >= 0 ? num(r.weight_change) + " N" : "–"});
  }
  releases.note = "At its time the body loses the released mass (or inertia) with position and velocity continuous; "
                  "the released part's weight and kinetic energy leave with it (docs/model-files.md#releases).";
  std::vector<Table> t{std::move(bodies)};
  if (!m.links.empty()) t.push_back(std::move(links));
  if (!contacts.rows.empty()) t.push_back(std::move(contacts));
  if (!gears.rows.empty()) t.push_back(std::move(gears));
  if (!m.loads.empty()) t.push_back(std::move(loads));
  if (!m.drives.empty()) t.push_back(std::move(drives));
  if (!m.releases.empty()) t.push_back(std::move(releases));
  return t;
}

namespace {
/// The crane factors of one case: the table of `machdyn crane` and each factor's time history.
Section crane_section(const CraneReport& cr, const std::string& case_name) {
  Section s;
  s.title = case_name.empty() ? "Crane factors (EN 13001-2)" : "Crane factors — case " + case_name;
  s.paragraphs.push_back("Each factor simulated beside the standard's value (docs/crane-factors.md); margin > 0: the "
                         "standard's value is on the safe side of this model.");
  Table t;
  t.caption = "Dynamic factors";
  t.header = {"factor", "case", "simulated", "standard", "margin", "clause/table", "note"};
  auto num = [](double x) { return std::isfinite(x) ? fmt::format("{:.4f}", x) : std::string("–"); };
  for (const auto& x : cr.rows)
    t.rows.push_back({x.factor, x.case_name, num(x.simulated),
                      !std::isfinite(x.standard_lo)    ? std::string("–")
                      : x.standard_lo == x.standard_hi ? fmt::format("{:.4g}", x.standard_lo)
                                                     : fmt::format("{:.4g}–{:.4g}", x.standard_lo, x.standard_hi),
                      num(x.margin), x.clause, x.note});
  s.tables.push_back(std::move(t));
  for (const auto& x : cr.rows)
    if (!x.warning.empty()) s.paragraphs.push_back(fmt::format("Warning — {} ({}): {}", x.factor, x.case_name, x.warning));
  s.figures = crane_figures(cr);
  return s;
}
}  // namespace

Document simulation_report(const std::vector<Case>& cases, const std::string& command) {
  Document d;
  if (cases.empty() || !cases[0].model || !cases[0].result) throw std::invalid_argument("simulation_report: no case");
  const Model& m0 = *cases[0].model;
  // Several cases: the title is the file's model name, without the first case's " [case]".
  d.title = cases.size() > 1 && !m0.load_case.empty() ? m0.name.substr(0, m0.name.rfind(" [")) : m0.name;
  d.subtitle = fmt::format("{} · {}", m0.source, command);
  Section model;
  model.title = "Model";
  if (!m0.description.empty()) model.paragraphs.push_back(m0.description);
  model.tables = model_tables(m0);
  d.sections.push_back(std::move(model));
  if (cases.size() > 1) {
    Section cmp;
    cmp.title = "Cases compared";
    cmp.tables.push_back(cases_table(cases));
    d.sections.push_back(std::move(cmp));
  }
  const bool many = cases.size() > 1;
  for (const auto& c : cases) {
    const Model& m = *c.model;
    const SimulationResult& r = *c.result;
    // One case: a run section and a plots section. Several: one section per case, tables then plots.
    Section run;
    run.title = c.name.empty() ? "Run" : "Case " + c.name;
    if (!c.description.empty()) run.paragraphs.push_back(c.description);
    run.tables.push_back(settings_table(m, r));
    if (!m.links.empty()) run.tables.push_back(results_table(m, r));
    if (r.hybrid.active) {
      run.tables.push_back(events_table(r));
      if (!r.hybrid.slip_phases.empty()) run.tables.push_back(slip_phases_table(m, r));
    }
    if (auto brakes = brake_stops_table(m, r)) run.tables.push_back(std::move(*brakes));  // io/report_brakes.hpp
    if (c.topologies) run.tables.push_back(topology_modes_table(m, *c.topologies));
    else if (c.modes) run.tables.push_back(modes_table(m, *c.modes));
    Section plots;
    plots.title = c.name.empty() ? "Plots" : "Plots — case " + c.name;
    FigureOptions figure_options;
    figure_options.links = c.links;
    plots.figures = simulation_figures(m, r, figure_options);
    if (c.modes && c.modes->shapes.cols() > 0) plots.figures.push_back(mode_shapes_figure(m, *c.modes));
    if (c.frf) {
      plots.figures.push_back(bode_magnitude_figure(m, *c.frf, c.frf_topology));
      plots.figures.push_back(bode_phase_figure(m, *c.frf, c.frf_topology));
    }
    if (c.energy)
      for (auto& f : energy_figures(m, *c.energy)) plots.figures.push_back(std::move(f));
    if (many) {
      for (auto& f : plots.figures) run.figures.push_back(std::move(f));
      d.sections.push_back(std::move(run));
    } else {
      d.sections.push_back(std::move(run));
      d.sections.push_back(std::move(plots));
    }
    if (auto sway = sway_section(m, r, c.name)) d.sections.push_back(std::move(*sway));  // io/report_sway.hpp
    if (c.crane) d.sections.push_back(crane_section(*c.crane, c.name));
  }
  return d;
}

}  // namespace machdyn::report
