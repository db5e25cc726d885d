// The papers' plots as Figures (io/figures.hpp). Each function only selects and labels data.
#include "machdyn/io/figures.hpp"
#include "machdyn/model/sheaves.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>
#include <fmt/ranges.h>
#include "common/constants.hpp"
#include "io/number_text.hpp"

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/model/machine.hpp"

namespace machdyn {

namespace {


/// The output column whose name starts with `prefix` (e.g. "c1.load_"); columns are found by name
/// so that commands adding columns (events, gaps) do not shift them.
const std::vector<double>& column(const SimulationResult& r, const std::string& prefix) {
  for (std::size_t c = 0; c < r.column_names.size(); ++c)
    if (r.column_names[c].rfind(prefix, 0) == 0) return r.columns[c];
  throw std::logic_error("simulation result has no column " + prefix);
}

std::vector<double> scaled(std::vector<double> v, double k) {
  if (k != 1.0)
    for (double& x : v) x *= k;
  return v;
}

/// "MODEL [case]: what" — a figure in a report names the model and the case.
std::string titled(const Model& m, const std::string& what) { return m.name + ": " + what; }

/// The events of a hybrid run as marks: brakes applied (at t_apply > 0, if ever), gaps closing and opening,
/// contacts breaking away and sticking. With more than 12, only the first of each kind and element
/// (a stick–slip run has hundreds); the title of the figure says so through `*thinned`.
std::vector<plot::EventMark> event_marks(const Model& m, const SimulationResult& r, bool* thinned) {
  std::vector<plot::EventMark> all;
  for (const auto& c : m.contacts)
    // t_apply is t_end for a brake never applied in the run (released there): no mark.
    if (c.brake && c.t_apply > 0.0 && !c.released(c.t_apply)) all.push_back({c.t_apply, c.name + " applied"});
  for (const auto& e : r.hybrid.events) {
    if (e.kind == "initial") continue;
    std::string what = e.kind == "slip" ? "breakaway" : e.kind == "stick" ? "sticks" : e.kind;
    for (auto& ch : what)
      if (ch == '_') ch = ' ';
    all.push_back({e.t, e.element + " " + what});
  }
  std::stable_sort(all.begin(), all.end(), [](const auto& a, const auto& b) { return a.x < b.x; });
  *thinned = false;
  std::vector<plot::EventMark> marks;
  if (all.size() <= 12) {
    marks = all;
  } else {
    *thinned = true;
    for (const auto& e : all)
      if (std::none_of(marks.begin(), marks.end(), [&](const plot::EventMark& f) { return f.label == e.label; }))
        marks.push_back(e);
  }
  // Labels closer than 2.5 % of the run would overprint: such a line keeps no label.
  double last = -1e300;
  for (auto& e : marks) {
    if (e.x - last < 0.025 * m.simulation.t_end) e.label.clear();
    else last = e.x;
  }
  return marks;
}

/// The link loads as series of `f` (left axis N·m, right axis N when both occur), in engineering
/// units; `static_in_legend`: the quasi-static load as a dashed line in the link's colour with its
/// value in the legend entry (one label per link, so many links never overlap).
void add_link_loads(const Model& m, const SimulationResult& r, bool static_in_legend, plot::Figure& f,
                    const std::vector<std::size_t>& which) {
  const auto& t = column(r, "t_s");
  const bool any_torque = std::any_of(which.begin(), which.end(),
                                      [&](std::size_t l) { return std::string(link_load_unit(m, m.links[l])) == "N*m"; });
  const bool any_force = std::any_of(which.begin(), which.end(),
                                     [&](std::size_t l) { return std::string(link_load_unit(m, m.links[l])) == "N"; });
  double largest[3] = {0, 0, 0};
  auto axis_of = [&](const Link& L) { return any_torque && std::string(link_load_unit(m, L)) == "N" ? 2 : 1; };
  for (const std::size_t l : which)
    for (double v : column(r, m.links[l].name + ".load_"))
      if (std::isfinite(v)) largest[axis_of(m.links[l])] = std::max(largest[axis_of(m.links[l])], std::abs(v));
  const auto [k1, u1] = engineering_unit(largest[1], any_torque ? "N*m" : "N");
  const auto [k2, u2] = engineering_unit(largest[2], "N");
  f.y = any_torque ? plot::make_axis("link torque M", u1) : plot::make_axis("link force F", u1);
  if (any_torque && any_force) f.y2 = plot::make_axis("link force F", u2);
  double peak_abs = -1.0;
  plot::Annotation peak;
  for (const std::size_t l : which) {
    const Link& L = m.links[l];
    const int axis = axis_of(L);
    const double k = axis == 2 ? k2 : k1;
    const std::string& unit = axis == 2 ? u2 : u1;
    // The ends as the file names them (a rope's drum also behind its sheave losses, model/sheaves.hpp).
    std::string name = fmt::format("{} ({}–{})", L.name, shown_body(m, L.a, L.given_a), shown_body(m, L.b, L.given_b));
    const bool has_static = l < r.links.size() && std::isfinite(r.links[l].static_load);
    const int series_index = static_cast<int>(f.series.size());
    if (static_in_legend && has_static) {
      name += fmt::format(", {}* = {} {}", L.name, label_number(k * r.links[l].static_load), unit);
      f.ref_lines.push_back(plot::make_ref_line(k * r.links[l].static_load, "", series_index, axis));
    }
    f.series.push_back(plot::make_series(name, t, scaled(column(r, L.name + ".load_"), k), plot::Style::line, axis));
    // The peak: the extreme of larger magnitude of the link whose peak is largest (in its unit).
    if (l < r.links.size()) {
      const auto& S = r.links[l];
      const bool use_max = std::abs(S.max) >= std::abs(S.min);
      const double v = use_max ? S.max : S.min, tv = use_max ? S.t_max : S.t_min;
      if (std::isfinite(v) && std::abs(v) * k > peak_abs) {
        peak_abs = std::abs(v) * k;
        peak = {tv, k * v, fmt::format("{} peak {} {} at {} s", L.name, label_number(k * v), unit, label_number(tv)),
                series_index, axis};
      }
    }
  }
  if (peak_abs > 0.0) f.notes.push_back(peak);
}

std::vector<std::size_t> all_links(const Model& m) {
  std::vector<std::size_t> v(m.links.size());
  for (std::size_t l = 0; l < v.size(); ++l) v[l] = l;
  return v;
}

plot::Figure link_loads_panel(const Model& m, const SimulationResult& r, const std::vector<std::size_t>& which,
                              std::string id, const std::string& what) {
  plot::Figure f;
  f.id = std::move(id);
  f.x = plot::make_axis("time t", "s");
  add_link_loads(m, r, true, f, which);
  bool thinned = false;
  if (r.hybrid.active) f.events = event_marks(m, r, &thinned);
  f.title = titled(m, what + (f.events.empty() ? "" : thinned ? "; dotted: first events of each kind" : "; dotted: events"));
  f.zero_line = true;
  f.legend = plot::Figure::Legend::below;
  return f;
}

}  // namespace

plot::Figure link_loads_figure(const Model& m, const SimulationResult& r) {
  return link_loads_panel(m, r, all_links(m), "link_loads", "link loads");
}

std::vector<std::size_t> chosen_links(const Model& m, const std::vector<std::string>& links, const std::string& option) {
  if (links.empty()) return all_links(m);
  std::vector<std::size_t> chosen;
  for (const auto& name : links) {
    const auto it = std::find_if(m.links.begin(), m.links.end(), [&](const Link& l) { return l.name == name; });
    if (it == m.links.end()) {
      std::vector<std::string> known;
      for (const auto& l : m.links) known.push_back(l.name);
      throw InputError(Location{option, 0, 0},
                       fmt::format("no link '{}'; the model's links: {}", name, fmt::join(known, ", ")));
    }
    const auto l = static_cast<std::size_t>(it - m.links.begin());
    if (std::find(chosen.begin(), chosen.end(), l) == chosen.end()) chosen.push_back(l);
  }
  return chosen;
}

std::vector<std::vector<std::size_t>> link_load_groups(const Model& m, const SimulationResult& r,
                                                       const std::vector<std::string>& links) {
  std::vector<std::size_t> chosen = chosen_links(m, links);
  // Per unit (N·m, N), in descending order of the peak magnitude; a link whose peak is below
  // 1/kPanelRatio of its panel's largest starts a new panel, so each panel's curves are readable.
  constexpr double kPanelRatio = 8.0;
  auto peak_of = [&](std::size_t l) {
    return l < r.links.size() ? std::max(std::abs(r.links[l].max), std::abs(r.links[l].min)) : 0.0;
  };
  // Unless chosen by name, a link that carries nothing in the run (its load 0 throughout: a trolley's
  // drive while the hoist lifts) gets no panel of its own; link_loads_figures names it.
  if (links.empty() && std::any_of(chosen.begin(), chosen.end(), [&](std::size_t l) { return peak_of(l) > 0.0; }))
    chosen.erase(std::remove_if(chosen.begin(), chosen.end(), [&](std::size_t l) { return !(peak_of(l) > 0.0); }),
                 chosen.end());
  std::vector<std::vector<std::size_t>> groups;
  for (const char* unit : {"N*m", "N"}) {
    std::vector<std::size_t> of_unit;
    for (const std::size_t l : chosen)
      if (std::string(link_load_unit(m, m.links[l])) == unit) of_unit.push_back(l);
    std::stable_sort(of_unit.begin(), of_unit.end(), [&](std::size_t a, std::size_t b) { return peak_of(a) > peak_of(b); });
    double top = 0.0;
    for (const std::size_t l : of_unit) {
      if (groups.empty() || std::string(link_load_unit(m, m.links[groups.back().front()])) != unit ||
          peak_of(l) * kPanelRatio < top) {
        groups.emplace_back();
        top = peak_of(l);
      }
      groups.back().push_back(l);
    }
  }
  // Inside a panel, the links in the file's order (their colours follow it).
  for (auto& g : groups) std::sort(g.begin(), g.end());
  return groups;
}

std::vector<plot::Figure> link_loads_figures(const Model& m, const SimulationResult& r,
                                             const std::vector<std::string>& links) {
  const auto groups = link_load_groups(m, r, links);
  // The links left out for carrying nothing, named in the first panel's title.
  std::vector<std::string> idle;
  for (std::size_t l = 0; l < m.links.size() && links.empty(); ++l)
    if (std::none_of(groups.begin(), groups.end(), [&](const auto& g) { return std::find(g.begin(), g.end(), l) != g.end(); }))
      idle.push_back(m.links[l].name);
  std::vector<plot::Figure> figs;
  for (std::size_t g = 0; g < groups.size(); ++g) {
    std::vector<std::string> names;
    for (const std::size_t l : groups[g]) names.push_back(m.links[l].name);
    const bool one = groups.size() == 1 && links.empty() && idle.empty();
    std::string what = one                  ? std::string("link loads")
                       : groups.size() == 1 ? fmt::format("link loads ({})", fmt::join(names, ", "))
                                            : fmt::format("link loads ({}; panel {} of {})", fmt::join(names, ", "), g + 1,
                                                          groups.size());
    if (g == 0 && !idle.empty()) what += fmt::format("; no load in this run: {}", fmt::join(idle, ", "));
    figs.push_back(link_loads_panel(m, r, groups[g], g == 0 ? "link_loads" : fmt::format("link_loads_{}", g + 1), what));
  }
  return figs;
}

plot::Figure body_speeds_figure(const Model& m, const SimulationResult& r) { return body_speeds_figure(m, r, {}); }

plot::Figure body_speeds_figure(const Model& m, const SimulationResult& r, const FigureOptions& opt) {
  plot::Figure f;
  f.id = "body_speeds";
  f.title = titled(m, "body speeds");
  f.x = plot::make_axis("time t", "s");
  const auto& t = column(r, "t_s");
  const bool any_rot = std::any_of(m.bodies.begin(), m.bodies.end(), [](const Body& b) { return b.kind == BodyKind::rotational; });
  const bool any_tr = std::any_of(m.bodies.begin(), m.bodies.end(), [](const Body& b) { return b.kind == BodyKind::translational; });
  f.y = !any_rot ? plot::make_axis("velocity v", "m/s")
        : opt.rpm ? plot::make_axis("speed n", "rpm")
                  : plot::make_axis("angular velocity ω", "rad/s");
  if (any_rot && any_tr) f.y2 = plot::make_axis("velocity v", "m/s");
  const double to_rpm = 60.0 / (2.0 * kPi);
  for (const Body& b : m.bodies) {
    if (is_sheave_body(m, static_cast<int>(&b - m.bodies.data()))) continue;  // a rope's, not the file's
    const bool rot = b.kind == BodyKind::rotational;
    f.series.push_back(plot::make_series(b.name, t, scaled(column(r, b.name + ".velocity_"), rot && opt.rpm ? to_rpm : 1.0),
                                         plot::Style::line, any_rot && !rot ? 2 : 1));
  }
  f.legend = plot::Figure::Legend::below;
  return f;
}

namespace {

/// The contacts whose slipping the cyclogram shows: those between two bodies (adhesion, clutches),
/// or every contact when all act against the ground (brakes, resistances).
std::vector<std::size_t> slipping_contacts(const Model& m) {
  std::vector<std::size_t> ks;
  for (std::size_t k = 0; k < m.contacts.size(); ++k)
    if (m.contacts[k].b != kGround && !m.contacts[k].brake && !m.contacts[k].joint) ks.push_back(k);
  if (ks.empty())
    for (std::size_t k = 0; k < m.contacts.size(); ++k)
      if (!m.contacts[k].joint) ks.push_back(k);
  return ks;
}

/// The slip phases of the contacts `ks` as shaded bands, and their legend entry.
void add_slip_bands(const Model& m, const SimulationResult& r, const std::vector<std::size_t>& ks, plot::Figure& f) {
  std::vector<std::string> names;
  for (const std::size_t k : ks) names.push_back(m.contacts[k].name);
  for (const auto& p : r.hybrid.slip_phases)
    if (std::find(names.begin(), names.end(), p.contact) != names.end() && p.t_end > p.t_start)
      f.bands.push_back({p.t_start, p.t_end});
  if (!names.empty()) f.bands_label = fmt::format("{} slip{}", fmt::join(names, ", "), names.size() == 1 ? "s" : "");
}

const char* contact_unit(const Model& m, const FrictionContact& c) {
  return load_unit(m.bodies[static_cast<std::size_t>(c.a)].kind);
}

}  // namespace

plot::Figure load_cyclogram_figure(const Model& m, const SimulationResult& r) {
  if (m.links.empty() || !r.hybrid.active)
    throw std::invalid_argument("load cyclogram: needs the hybrid (event-driven) result of a model with links");
  plot::Figure f;
  f.x = plot::make_axis("time t", "s");
  // The cyclogram compares with the adhesion limit, not the quasi-static load.
  add_link_loads(m, r, false, f, all_links(m));
  f.id = "load_cyclogram";
  f.zero_line = true;
  f.legend = plot::Figure::Legend::below;
  const auto ks = slipping_contacts(m);
  const std::string y_unit = link_load_unit(m, m.links[0]);
  // The scale add_link_loads chose for the left axis (1, 1e-3 or 1e-6), from its unit's prefix.
  const double k_left = f.y.unit.rfind("k", 0) == 0 ? 1e-3 : f.y.unit.rfind("M", 0) == 0 ? 1e-6 : 1.0;
  for (const std::size_t k : ks) {
    const auto& c = m.contacts[k];
    if (c.brake || std::string(contact_unit(m, c)) != y_unit) continue;
    f.ref_lines.push_back(plot::make_ref_line(
        k_left * c.static_limit, fmt::format("F_sc = {} {}", label_number(k_left * c.static_limit), f.y.unit), -1));
  }
  add_slip_bands(m, r, ks, f);
  f.title = titled(m, fmt::format("load cyclogram{}", f.ref_lines.empty() ? "" : "; dashed: static limit F_sc"));
  // The breakaway loads: the link load at the start of every slip phase of these contacts.
  const std::size_t n_links = m.links.size();
  for (std::size_t l = 0; l < n_links; ++l) {
    plot::Series s = plot::make_series(fmt::format("{} at breakaway", m.links[l].name), {}, {}, plot::Style::points,
                                       f.series[l].y_axis);
    for (const auto& p : r.hybrid.slip_phases) {
      const bool shown = std::any_of(ks.begin(), ks.end(), [&](std::size_t k) { return m.contacts[k].name == p.contact; });
      if (!shown || l >= p.link_start.size()) continue;
      const double k = f.series[l].y_axis == 2 ? (f.y2.unit.rfind("k", 0) == 0 ? 1e-3 : f.y2.unit.rfind("M", 0) == 0 ? 1e-6 : 1.0)
                                               : k_left;
      s.x.push_back(p.t_start);
      s.y.push_back(k * p.link_start[l]);
    }
    if (!s.x.empty()) {
      const std::string& unit = f.series[l].y_axis == 2 ? f.y2.unit : f.y.unit;
      const double lo = *std::min_element(s.y.begin(), s.y.end()), hi = *std::max_element(s.y.begin(), s.y.end());
      s.name += hi - lo <= 5e-4 * std::max(std::abs(hi), 1e-3)
                    ? fmt::format(" ({} {})", label_number(hi), unit)
                    : fmt::format(" ({} … {} {})", label_number(lo), label_number(hi), unit);
      f.series.push_back(std::move(s));
    }
  }
  return f;
}

plot::Figure contacts_figure(const Model& m, const SimulationResult& r) {
  if (m.contacts.empty() || !r.hybrid.active)
    throw std::invalid_argument("contacts figure: needs the hybrid (event-driven) result of a model with contacts");
  return contacts_figure(m, r, m.bodies[static_cast<std::size_t>(m.contacts[0].a)].kind);
}

plot::Figure contacts_figure(const Model& m, const SimulationResult& r, BodyKind kind) {
  if (m.contacts.empty() || !r.hybrid.active)
    throw std::invalid_argument("contacts figure: needs the hybrid (event-driven) result of a model with contacts");
  const BodyKind first = m.bodies[static_cast<std::size_t>(m.contacts[0].a)].kind;
  plot::Figure f;
  // The figure of the first contact's kind is `contacts`; the other kind (a brake in N·m beside a
  // wheel contact in N) gets its own, so no contact is left out for its unit.
  f.id = kind == first ? "contacts" : kind == BodyKind::rotational ? "contacts_torques" : "contacts_forces";
  const bool rot = kind == BodyKind::rotational;
  // A brake's torque is no force: the two figures of a model with both kinds differ in their titles.
  f.title = titled(m, rot ? "contacts: torque (solid, left), sliding velocity (dashed, right)"
                          : "contacts: force (solid, left), sliding velocity (dashed, right)");
  f.x = plot::make_axis("time t", "s");
  double largest = 0.0;
  for (const auto& c : m.contacts)
    if (!c.joint && m.bodies[static_cast<std::size_t>(c.a)].kind == kind)
      for (double v : column(r, c.name + ".force_"))
        if (std::isfinite(v)) largest = std::max(largest, std::abs(v));
  const auto [k_force, u_force] = engineering_unit(largest, rot ? "N*m" : "N");
  f.y = rot ? plot::make_axis("contact torque M", u_force) : plot::make_axis("contact force F", u_force);
  f.y2 = rot ? plot::make_axis("sliding velocity u", "rad/s") : plot::make_axis("sliding velocity u", "m/s");
  const auto& t = column(r, "t_s");
  for (const auto& c : m.contacts) {
    if (c.joint || m.bodies[static_cast<std::size_t>(c.a)].kind != kind) continue;  // one kind of unit per figure
    f.series.push_back(plot::make_series(c.name + ": force", t, scaled(column(r, c.name + ".force_"), k_force)));
    plot::Series u = plot::make_series(c.name + ": sliding velocity", t, column(r, c.name + ".sliding_velocity_"),
                                       plot::Style::line, 2);
    u.dashed = true;
    f.series.push_back(std::move(u));
  }
  add_slip_bands(m, r, slipping_contacts(m), f);
  f.zero_line = true;
  f.legend = plot::Figure::Legend::below;
  return f;
}

std::vector<plot::Figure> simulation_figures(const Model& m, const SimulationResult& r, const FigureOptions& opt) {
  std::vector<plot::Figure> figs;
  // Friction elements, not gear joints (their torques are columns, not stick–slip).
  const auto friction = std::find_if(m.contacts.begin(), m.contacts.end(), [](const FrictionContact& c) { return !c.joint; });
  const bool hybrid = r.hybrid.active && friction != m.contacts.end();
  if (hybrid && !m.links.empty()) figs.push_back(load_cyclogram_figure(m, r));
  if (!m.links.empty())
    for (auto& f : link_loads_figures(m, r, opt.links)) figs.push_back(std::move(f));
  figs.push_back(body_speeds_figure(m, r, opt));
  if (hybrid) {
    const BodyKind first = m.bodies[static_cast<std::size_t>(friction->a)].kind;
    figs.push_back(contacts_figure(m, r, first));
    const bool other = std::any_of(m.contacts.begin(), m.contacts.end(), [&](const FrictionContact& c) {
      return !c.joint && m.bodies[static_cast<std::size_t>(c.a)].kind != first;
    });
    if (other)
      figs.push_back(contacts_figure(m, r, first == BodyKind::rotational ? BodyKind::translational : BodyKind::rotational));
  }
  return figs;
}

plot::Figure mode_shapes_figure(const Model& m, const Modes& modes, int max_modes) {
  plot::Figure f;
  f.id = "mode_shapes";
  const Eigen::Index shown = std::min<Eigen::Index>(modes.shapes.cols(), std::max(1, max_modes));
  // Angles (rad) beside displacements (m) have no common scale: a 32 t load's bounce would look
  // still beside a motor's rotation. Then each coordinate is weighted by √I (√(kg·m²) or √kg), so
  // √I_i φ_i is dimensionless and its square the body's share of the mode's kinetic energy
  // (Σ I_i φ_i² = 1 for the mass-normalized shape), then scaled to max 1 as the rest.
  const bool mixed = std::any_of(m.bodies.begin(), m.bodies.end(), [](const Body& b) { return b.kind == BodyKind::rotational; }) &&
                     std::any_of(m.bodies.begin(), m.bodies.end(), [](const Body& b) { return b.kind == BodyKind::translational; });
  Eigen::MatrixXd shapes = modes.shapes;
  if (mixed)
    for (int i = 0; i < m.dof() && i < shapes.rows(); ++i) shapes.row(i) *= std::sqrt(m.bodies[static_cast<std::size_t>(i)].inertia);
  const std::string how = mixed ? "rad and m: each coordinate × √I (kinetic-energy share), scaled to max 1"
                                : "each scaled to max |φ| = 1";
  f.title = titled(m, shown < modes.shapes.cols()
                         ? fmt::format("the {} lowest of {} elastic mode shapes ({})", shown, modes.shapes.cols(), how)
                         : fmt::format("elastic mode shapes ({})", how));
  f.x = plot::make_axis("body", "");
  // The file's bodies (a rope's massless end at its drum is the rope's: model/sheaves.hpp), at 1 … n.
  std::vector<int> body;
  for (int i = 0; i < m.dof() && i < shapes.rows(); ++i)
    if (!is_sheave_body(m, i)) body.push_back(i);
  const int n = static_cast<int>(body.size());
  auto name = [&](int j) { return m.bodies[static_cast<std::size_t>(body[static_cast<std::size_t>(j)])].name; };
  // Every body named while the names fit; a long chain names every k-th body.
  std::size_t name_chars = 0;
  for (int j = 0; j < n; ++j) name_chars += name(j).size() + 2;
  const int every = std::max(1, static_cast<int>((name_chars + 59) / 60));
  for (int j = 0; j < n; j += every) f.x.ticks.push_back({j + 1.0, name(j)});
  if (every > 1 && (n - 1) % every >= 2)  // the last body too, unless its neighbour is named
    f.x.ticks.push_back({static_cast<double>(n), name(n - 1)});
  f.y = mixed ? plot::make_axis("relative amplitude √I·φ / max|√I·φ|", "") : plot::make_axis("relative amplitude φ / max|φ|", "");
  for (Eigen::Index k = 0; k < shown; ++k) {
    const double scale = shapes.col(k).cwiseAbs().maxCoeff();
    plot::Series s = plot::make_series(fmt::format("mode {}: {:.4g} Hz ({:.4g} rad/s)", k + 1,
                                                   modes.omega(k) / (2 * kPi), modes.omega(k)),
                                       {}, {}, plot::Style::linepoints);
    for (int j = 0; j < n; ++j) {
      s.x.push_back(j + 1.0);
      s.y.push_back(scale > 0 ? shapes(body[static_cast<std::size_t>(j)], k) / scale : 0.0);
    }
    if (n > 12) s.style = plot::Style::line;  // markers would crowd a long chain
    f.series.push_back(std::move(s));
  }
  f.y.min = -1.1, f.y.max = 1.1;
  f.zero_line = true;
  f.legend = plot::Figure::Legend::below;
  return f;
}

plot::Figure gears_pitch_figure(const io::GearReport& r) {
  const auto& m = r.model;
  const double dx = m.L_installed * 1e3;  // pinion centre, mm
  plot::Figure f;
  f.id = "pitch_curves";
  f.title = fmt::format("Pitch curves and sector boundaries (L = {:.5g} mm)", dx);
  f.x = plot::make_axis("x", "mm");
  f.y = plot::make_axis("y", "mm");
  f.equal_aspect = true;
  // Sector boundaries: a ray from each centre through every sector start, a little beyond the curve.
  plot::Series rays = plot::make_series("sector boundaries", {}, {}, plot::Style::thin);
  auto ray = [&](double cx, double beta, double radius) {
    rays.x.insert(rays.x.end(), {cx, cx + radius * std::cos(beta), kNaN});
    rays.y.insert(rays.y.end(), {0.0, radius * std::sin(beta), kNaN});
  };
  const int pinion_big = static_cast<int>(std::lround(2 * kPi / m.Theta()));
  for (int q = 0; q < m.N; ++q)
    for (const auto& row : r.synthesis.sectors) ray(0.0, -row.phi + q * m.T(), row.rH * 1e3 * 1.06);
  for (int q = 0; q < pinion_big; ++q)
    for (const auto& row : r.synthesis.sectors) ray(dx, kPi + row.theta + q * m.Theta(), row.r * 1e3 * 1.08);
  f.series.push_back(std::move(rays));
  const auto c = gears::sample_pitch_curves(m, 360);
  plot::Series wheel = plot::make_series(fmt::format("wheel (H), z_H = {}: r_H(φ)", m.zH), {}, {});
  plot::Series pinion = plot::make_series(fmt::format("pinion, z = {}: r(θ)", m.z), {}, {});
  for (std::size_t k = 0; k < c.wheel_x.size(); ++k) wheel.x.push_back(c.wheel_x[k] * 1e3), wheel.y.push_back(c.wheel_y[k] * 1e3);
  for (std::size_t k = 0; k < c.pinion_x.size(); ++k)
    pinion.x.push_back(dx + c.pinion_x[k] * 1e3), pinion.y.push_back(c.pinion_y[k] * 1e3);
  f.series.push_back(std::move(wheel));
  f.series.push_back(std::move(pinion));
  plot::Series centres = plot::make_series("centres", {0.0, dx}, {0.0, 0.0}, plot::Style::linepoints);
  centres.dashed = true;
  centres.in_legend = false;
  f.series.push_back(std::move(centres));
  f.legend = plot::Figure::Legend::below;
  return f;
}

plot::Figure gears_ratio_figure(const io::GearReport& r) {
  const auto& m = r.model;
  const double T = m.T(), deg = 180.0 / kPi;
  plot::Figure f;
  f.id = "ratio";
  f.title = "Gear ratio over one big sector";
  f.x = plot::make_axis("wheel angle φ", "deg");
  f.x.min = -0.5 * T * deg, f.x.max = 0.5 * T * deg;
  f.y = plot::make_axis("ratio i = dθ/dφ", "");
  plot::Series law = plot::make_series("theoretical i(φ) of the law", {}, {});
  plot::Series step = plot::make_series("stepwise Δθ_j/Δφ_j of the sectors", {}, {});
  for (int q = 0; q <= 600; ++q) {
    const double phi = -0.5 * T + T * q / 600.0;
    law.x.push_back(phi * deg);
    law.y.push_back(m.law.ratio(phi).v);
  }
  // Sectors run from φ_j down to φ_j − Δφ_j; draw them from left to right as a staircase.
  auto rows = r.synthesis.sectors;
  std::sort(rows.begin(), rows.end(), [](const auto& a, const auto& b) { return a.phi < b.phi; });
  for (const auto& row : rows) {
    const double i = row.dtheta / row.dphi;
    step.x.insert(step.x.end(), {(row.phi - row.dphi) * deg, row.phi * deg});
    step.y.insert(step.y.end(), {i, i});
  }
  f.series.push_back(std::move(law));
  f.series.push_back(std::move(step));
  f.legend = plot::Figure::Legend::below;
  return f;
}

plot::Figure speed_distance_figure(const Model& m, const EnergyResult& r) {
  if (m.bodies.empty() || r.table.empty()) throw std::invalid_argument("speed figure: empty energy result");
  const Machine* mach = m.bodies[0].machine.get();
  const bool distance = mach && !r.point_name.empty() && r.point_name != "piston";
  plot::Figure f;
  f.id = distance ? "speed_distance" : "speed_angle";
  f.y = plot::make_axis("angular velocity ω", "rad/s");
  plot::Series w = plot::make_series("ω, energy integral", {}, {});
  const double limit = r.omega_limit && std::isfinite(*r.omega_limit) ? *r.omega_limit : kNaN;
  if (distance) {
    // The wheel's travel is linear in q (x = R_r φ) but not in β, the table's coordinate, whose rows
    // crowd at the start and thin out as x grows without bound near β → π. So resample uniformly in q
    // up to where ω is within 1 % of a finite limit, or, with no limit, up to 90 % of the β range.
    const auto& rows = r.table;
    std::size_t end = rows.size() - 1;
    for (std::size_t k = 10; k < rows.size(); ++k)
      if (std::isfinite(limit) ? std::abs(rows[k].omega - limit) <= 1e-2 * std::abs(limit)
                               : r.limit_kind == "unbounded" &&
                                     std::abs(rows[k].s - rows[0].s) >= 0.9 * std::abs(rows.back().s - rows[0].s)) {
        end = k;
        break;
      }
    const EnergyIntegral integral(m);
    constexpr int kPoints = 400;
    for (int i = 0; i <= kPoints; ++i) {
      const double q = rows[0].q + (rows[end].q - rows[0].q) * i / kPoints;
      double p = 0, dp = 0, ddp = 0;
      mach->point(q, &p, &dp, &ddp);
      const double omega = i == kPoints ? rows[end].omega : integral.omega(q);  // the end may be a turning point
      if (!std::isfinite(p) || !std::isfinite(omega)) continue;
      w.x.push_back(p);
      w.y.push_back(omega);
    }
    f.x = plot::make_axis(fmt::format("distance travelled {}", r.point_name), "m");
    f.title = fmt::format("Speed against distance: {}", m.name);
  } else {
    for (const auto& row : r.table) {
      w.x.push_back(row.q * 180.0 / kPi);
      w.y.push_back(row.omega);
    }
    f.x = plot::make_axis(fmt::format("angle {}", r.s_name == "q" ? "φ" : r.s_name), "deg");
    f.title = fmt::format("Speed against angle: {}", m.name);
  }
  // A scan backwards (ω0 < 0) runs to decreasing x; the charts want x ascending.
  if (w.x.size() > 1 && w.x.back() < w.x.front()) {
    std::reverse(w.x.begin(), w.x.end());
    std::reverse(w.y.begin(), w.y.end());
  }
  f.series.push_back(std::move(w));
  if (std::isfinite(limit))
    f.ref_lines.push_back(plot::make_ref_line(limit, fmt::format("ω_lim = {} rad/s", label_number(limit)), -1));
  f.legend = plot::Figure::Legend::bottom_right;
  return f;
}

plot::Figure inertia_moments_figure(const Model& m, const EnergyResult& r) {
  const Machine* mach = m.bodies.empty() ? nullptr : m.bodies[0].machine.get();
  if (!mach || r.table.empty()) throw std::invalid_argument("inertia moments: needs the energy result of a machine");
  const EnergyIntegral integral(m);
  plot::Figure f;
  f.id = "inertia_moments";
  f.title = fmt::format("Inertia moments M_k = −I_k ε − ½ I_k′ ω²: {}", m.name);
  f.x = plot::make_axis("angle φ", "deg");
  f.y = plot::make_axis("inertia moment M", "N·m");
  const int parts = mach->parts();
  std::vector<plot::Series> series;
  for (int k = 0; k < parts; ++k) series.push_back(plot::make_series(mach->part_name(k), {}, {}));
  plot::Series total = plot::make_series("sum Σ M_k", {}, {});
  total.dashed = true;
  std::vector<double> I(static_cast<std::size_t>(parts)), dI(I.size());
  for (const auto& row : r.table) {
    double I_sum = 0, dI_sum = 0;
    for (int k = 0; k < parts; ++k) {
      mach->part_inertia(k, row.q, &I[static_cast<std::size_t>(k)], &dI[static_cast<std::size_t>(k)]);
      I_sum += I[static_cast<std::size_t>(k)], dI_sum += dI[static_cast<std::size_t>(k)];
    }
    I_sum += integral.added_inertia();
    const double w = row.omega * r.direction;
    const double eps = (integral.force_s(row.s) - 0.5 * dI_sum * w * w) / I_sum;  // paper 004 eq. 4
    const double x = row.q * 180.0 / kPi;
    double sum = 0;
    for (int k = 0; k < parts; ++k) {
      const double Mk = -I[static_cast<std::size_t>(k)] * eps - 0.5 * dI[static_cast<std::size_t>(k)] * w * w;
      series[static_cast<std::size_t>(k)].x.push_back(x);
      series[static_cast<std::size_t>(k)].y.push_back(Mk);
      sum += Mk;
    }
    total.x.push_back(x);
    total.y.push_back(sum);
  }
  for (auto& s : series) f.series.push_back(std::move(s));
  f.series.push_back(std::move(total));
  f.zero_line = true;
  f.legend = plot::Figure::Legend::below;
  return f;
}

std::vector<plot::Figure> energy_figures(const Model& m, const EnergyResult& r) {
  std::vector<plot::Figure> figs{speed_distance_figure(m, r)};
  const Machine* mach = m.bodies.empty() ? nullptr : m.bodies[0].machine.get();
  if (mach && mach->parts() > 1 && r.point_name == "piston") figs.push_back(inertia_moments_figure(m, r));
  return figs;
}

}  // namespace machdyn
