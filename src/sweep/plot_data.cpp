#include "machdyn/sweep/plot_data.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>


#include <fmt/format.h>
#include <fmt/ranges.h>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/sweep/table.hpp"


namespace machdyn {
namespace {

namespace fs = std::filesystem;

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// The plot data parsed: columns x[, y], z per ok row, with their texts (a word-valued input is NaN).
struct PlotData {
  std::vector<std::string> x_text, y_text;
  std::vector<double> x, y, z;
};

double to_number(const std::string& t) {
  if (t == "nan" || t.empty()) return std::numeric_limits<double>::quiet_NaN();
  try {
    size_t used = 0;
    const double v = std::stod(t, &used);
    return used == t.size() ? v : std::numeric_limits<double>::quiet_NaN();
  } catch (const std::exception&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

PlotData parse_data(const std::string& csv, size_t inputs) {
  PlotData d;
  std::istringstream in(csv);
  std::string line;
  std::getline(in, line);  // header
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const auto f = split_csv_line(line);
    if (f.size() != inputs + 1) continue;
    d.x_text.push_back(f[0]);
    d.x.push_back(to_number(f[0]));
    if (inputs == 2) {
      d.y_text.push_back(f[1]);
      d.y.push_back(to_number(f[1]));
    }
    d.z.push_back(to_number(f[inputs]));
  }
  return d;
}

/// Distinct texts in order of first appearance.
std::vector<std::string> distinct(const std::vector<std::string>& texts) {
  std::vector<std::string> out;
  for (const auto& t : texts)
    if (std::find(out.begin(), out.end(), t) == out.end()) out.push_back(t);
  return out;
}

/// A word-valued x (e.g. the integrator): positions 0, 1, ... with the words as tick labels.
void categorical_x(PlotData& d, plot::Axis& axis) {
  if (std::none_of(d.x.begin(), d.x.end(), [](double v) { return std::isnan(v); })) return;
  const auto words = distinct(d.x_text);
  for (size_t i = 0; i < d.x.size(); ++i)
    d.x[i] = static_cast<double>(std::find(words.begin(), words.end(), d.x_text[i]) - words.begin());
  for (size_t k = 0; k < words.size(); ++k) axis.ticks.emplace_back(static_cast<double>(k), words[k]);
}

/// Points (x, z) in x order (a sweep table is in run order, random samples are not sorted).
void sort_by_x(std::vector<double>& x, std::vector<double>& z) {
  std::vector<size_t> order(x.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) { return x[a] < x[b]; });
  std::vector<double> xs, zs;
  for (size_t i : order) xs.push_back(x[i]), zs.push_back(z[i]);
  x.swap(xs);
  z.swap(zs);
}

std::string value_label(const std::string& text, const plot::Axis& axis) {
  const double v = to_number(text);
  const std::string number = std::isnan(v) ? text : fmt::format("{:.4g}", v);
  return axis.unit.empty() || std::isnan(v) ? number : number + " " + axis.unit;
}

/// Runs `exe script` with output into `log`; the exit status (-1 if not run).
/// Half-widths of the cells of a grid axis: from each value to the midpoints with its neighbours
/// (the end cells mirror their inner half). Keyed by the value's text.
std::map<std::string, std::pair<double, double>> grid_cells(const std::vector<std::string>& texts, bool log_axis) {
  std::vector<std::pair<double, std::string>> v;
  for (const auto& t : distinct(texts)) v.emplace_back(to_number(t), t);
  std::sort(v.begin(), v.end());
  std::map<std::string, std::pair<double, double>> cells;
  auto f = [&](double a) { return log_axis ? std::log(a) : a; };
  auto finv = [&](double a) { return log_axis ? std::exp(a) : a; };
  for (size_t i = 0; i < v.size(); ++i) {
    const double c = f(v[i].first);
    double lo = i > 0 ? 0.5 * (c + f(v[i - 1].first)) : std::numeric_limits<double>::quiet_NaN();
    double hi = i + 1 < v.size() ? 0.5 * (c + f(v[i + 1].first)) : std::numeric_limits<double>::quiet_NaN();
    if (std::isnan(lo)) lo = std::isnan(hi) ? c - 0.5 : 2 * c - hi;
    if (std::isnan(hi)) hi = 2 * c - lo;
    cells[v[i].second] = {finv(lo), finv(hi)};
  }
  return cells;
}

/// A heat map of z over (x, y): cells for a full grid, dots for scattered points. SVG then PNG
/// (the sizes and fonts of io/plot.hpp).
plot::Rendered render_heat_map(const PlotData& d, const SweepPlotSpec& spec) {
  const auto xs = distinct(d.x_text), ys = distinct(d.y_text);
  const bool grid = xs.size() * ys.size() == d.z.size() && xs.size() > 1 && ys.size() > 1;
  auto positive = [](const std::vector<double>& v) {
    return std::all_of(v.begin(), v.end(), [](double a) { return a > 0; });
  };
  // A log-spaced grid axis (constant ratio of neighbours) is drawn on a log scale.
  auto log_spaced = [&](const std::vector<std::string>& texts) {
    std::vector<double> v;
    for (const auto& t : distinct(texts)) v.push_back(to_number(t));
    std::sort(v.begin(), v.end());
    if (v.size() < 3 || !positive(v)) return false;
    const double r = v[1] / v[0];
    if (r < 1.5) return false;
    for (size_t i = 2; i < v.size(); ++i)
      if (std::abs(v[i] / v[i - 1] / r - 1) > 1e-6) return false;
    return true;
  };
  const bool logx = spec.input_axes[0].log || (grid && log_spaced(d.x_text)),
             logy = spec.input_axes[1].log || (grid && log_spaced(d.y_text));
  std::string data;
  const auto cx = grid_cells(d.x_text, logx), cy = grid_cells(d.y_text, logy);
  for (size_t i = 0; i < d.z.size(); ++i) {
    if (!std::isfinite(d.x[i]) || !std::isfinite(d.y[i]) || !std::isfinite(d.z[i])) continue;
    const auto [xl, xh] = cx.at(d.x_text[i]);
    const auto [yl, yh] = cy.at(d.y_text[i]);
    data += fmt::format("{:.10g} {:.10g} {:.10g} {:.10g} {:.10g} {:.10g} {:.10g}\n", d.x[i], d.y[i], xl, xh, yl, yh, d.z[i]);
  }
  const auto script = [&](plot::Format format, const std::string& data_path, const std::string& out) {
    const bool svg = format == plot::Format::svg;
    std::string g = "reset\nset encoding utf8\n";
    g += svg ? "set terminal svg size 800,500 dynamic noenhanced font 'DejaVu Sans,12' background '#ffffff' linewidth 1\n"
             : "set terminal pngcairo size 1600,1000 noenhanced font 'DejaVu Sans,24' background '#ffffff' linewidth 2\n";
    g += "set output " + plot::quote(out) + "\n";
    g += "set border 3 lw 1\nset tics nomirror out\nset key off\n";
    if (!spec.title.empty()) g += "set title " + plot::quote(spec.title) + "\n";
    g += "set format x '%.10g'\nset format y '%.10g'\nset format cb '%.10g'\n";
    g += "set xlabel " + plot::quote(spec.input_axes[0].label()) + "\n";
    g += "set ylabel " + plot::quote(spec.input_axes[1].label()) + "\n";
    g += "set cblabel " + plot::quote(spec.output_axis.label()) + "\n";
    // Viridis: monotone in lightness, readable for colour-blind readers and in greyscale.
    g += "set palette defined (0 '#440154', 0.25 '#3b528b', 0.5 '#21918c', 0.75 '#5ec962', 1 '#fde725')\n";
    if (logx) g += "set logscale x\n";
    if (logy) g += "set logscale y\n";
    if (grid) {
      g += "set autoscale xfix\nset autoscale yfix\n";
      g += "plot " + plot::quote(data_path) +
           " using 1:2:3:4:5:6:7 with boxxyerror fill solid 1.0 noborder lc palette notitle\n";
    } else {
      g += "set offsets graph 0.02, graph 0.02, graph 0.04, graph 0.04\n";
      g += "plot " + plot::quote(data_path) + " using 1:2:7 with points pt 7 ps " + (svg ? "0.8" : "1.2") +
           " lc palette notitle\n";
    }
    return g + "unset output\n";
  };
  return plot::render_script(data, script, "the sweep plot");
}

}  // namespace

plot::Axis column_axis(const std::string& column) {
  std::string name = column, unit;
  for (const auto& [tail, u] : std::vector<std::pair<std::string, std::string>>{
           {"_N_m", "N·m"}, {"_N", "N"}, {"_s", "s"}, {"_J", "J"}, {"_m", "m"}, {"_rad", "rad"}}) {
    if (ends_with(name, tail)) {
      name.resize(name.size() - tail.size());
      unit = u;
      break;
    }
  }
  const auto dot = name.find('.');
  const std::string elem = dot == std::string::npos ? "" : name.substr(0, dot);
  const std::string field = dot == std::string::npos ? name : name.substr(dot + 1);
  std::string quantity = column;
  if (!elem.empty()) {
    if (field == "max") quantity = "peak load of " + elem;
    else if (field == "min") quantity = "minimum load of " + elem;
    else if (field == "t_max") quantity = "time of the peak of " + elem;
    else if (field == "static") quantity = "quasi-static load of " + elem + " at its peak";
    else if (field == "dynamic_factor") quantity = "dynamic factor of " + elem;
    else if (field == "peak") quantity = "signed peak load of " + elem;
    else if (field == "t_peak") quantity = "time of the peak of " + elem;
    else if (field == "peak_static") quantity = "quasi-static load of " + elem + " at its peak";
    else if (field == "peak_dynamic_factor") quantity = "peak dynamic factor of " + elem;
    else if (field == "slips") quantity = "slips of " + elem;
    else if (field == "period") quantity = "self-oscillation period of " + elem;
    else if (field == "max_sway") quantity = "largest sway of " + elem;  // sway_summary_columns()
    else if (field == "residual_sway") quantity = "residual sway of " + elem;
    else if (field == "max_horizontal_force") quantity = "largest horizontal force of " + elem;
    else if (field == "horizontal_dynamic_factor") quantity = "horizontal dynamic factor of " + elem;
    else if (ends_with(field, "_max_over_static_limit"))
      quantity = "F_max(" + field.substr(0, field.size() - 22) + ") / F_s(" + elem + ")";
    else quantity = name;
  } else if (name.rfind("events_", 0) == 0) {
    quantity = "number of " + name.substr(7) + " events";
  } else {
    quantity = name;  // steps, rejected_steps, rhs_evals
  }
  return plot::make_axis(quantity, unit);
}

std::string field_unit(const Model& m, const std::string& target) {
  const auto dot = target.find('.');
  if (dot == std::string::npos) return "";
  const std::string elem = target.substr(0, dot), field = target.substr(dot + 1);
  auto rot = [](BodyKind k) { return k == BodyKind::rotational; };
  if (elem == "simulation") return field == "t_end" || field == "dt_out" ? "s" : "";
  for (const auto& b : m.bodies) {
    if (b.name != elem) continue;
    if (field == "mass") return "kg";
    if (field == "inertia") return rot(b.kind) ? "kg·m²" : "kg";
    if (field == "position") return position_unit(b.kind);
    if (field == "velocity") return velocity_unit(b.kind);
    // Machine bodies (model/machine.hpp): lengths, masses, the thread force, angles, speeds.
    if (field == "R1" || field == "r1" || field == "r2" || field == "H" || field == "rho" ||
        field == "crank_radius" || field == "rod_length" || field == "rod_com")
      return "m";
    if (field == "m1" || field == "m2" || field == "rod_mass" || field == "piston_mass") return "kg";
    if (field == "rod_inertia" || field == "crank_inertia") return "kg·m²";
    if (field == "F") return "N";
    if (field == "beta0") return "rad";
    if (field == "omega0") return "rad/s";
    return "";
  }
  for (const auto& l : m.links) {
    if (l.name != elem) continue;
    const bool r = std::string(link_load_unit(m, l)) == "N*m";
    if (field == "stiffness") return r ? "N·m/rad" : "N/m";
    if (field == "damping") return r ? "N·m·s/rad" : "N·s/m";
    if (field == "gap" || field == "gap_start") return r ? "rad" : "m";
    if (field == "EA") return "N";  // a rope's axial stiffness
    if (field == "length" || field == "slack" || field == "drum_radius" || field == "radius") return "m";
    if (field == "elastic_modulus") return "Pa";
    if (l.buffer && (field == "min" || field == "max" || field == "stroke")) return r ? "rad" : "m";
    if (l.buffer && field == "force") return r ? "N·m" : "N";
    if (field == "area") return "m²";
    return "";
  }
  for (const auto& l : m.loads) {
    if (l.name != elem) continue;
    const BodyKind k = m.bodies[static_cast<size_t>(l.body)].kind;
    if (field == "value" || field == "before" || field == "stall_torque" || field == "breakdown_torque")
      return plot::pretty_unit(load_unit(k));
    if (field == "t0" || field == "t1" || field == "time" || field == "start" || field == "end") return "s";
    if (field == "omega0" || field == "speed" || field == "no_load_speed" || field == "synchronous_speed")
      return velocity_unit(k);
    return "";
  }
  if (elem == "crane") {  // the `crane:` section's speeds and release mass
    if (field == "hoist_speed" || field == "creep_speed") return "m/s";
    if (field == "release_mass" || field == "mass") return "kg";
    return "";
  }
  for (const auto& d : m.drives) {  // a drive's times, speeds and torques by the field's name
    if (d.name != elem) continue;
    const BodyKind k = m.bodies[static_cast<size_t>(d.body)].kind;
    if (field.find("time") != std::string::npos || field == "t0" || field == "t1") return "s";
    if (field == "length" || field == "height" || field == "drum_radius") return "m";  // a spatial rope's
    if (field == "EA") return "N";
    // A field of a reference signal (`reference.end`, a shaped reference's `reference.length`).
    const std::string last = field.substr(field.rfind('.') + 1);
    if (last != field && (last == "end" || last == "start")) return "s";
    if (last != field && last == "length") return "m";
    if (field.find("speed") != std::string::npos) return velocity_unit(k);
    if (field.find("torque") != std::string::npos || field.find("force") != std::string::npos ||
        field.find("limit") != std::string::npos)
      return plot::pretty_unit(load_unit(k));
    return "";
  }
  for (const auto& c : m.contacts) {
    if (c.name != elem) continue;
    const BodyKind k = m.bodies[static_cast<size_t>(c.a)].kind;
    if (c.stop && (field == "min" || field == "max")) return position_unit(k);
    if (field == "static" || field == "kinetic" || field == "holding" || field == "braking")
      return plot::pretty_unit(load_unit(k));
    if (field == "normal_force") return "N";
    if (field == "radius") return "m";
    if (field == "time" || field == "ramp") return "s";
    if (field == "surface_velocity") return velocity_unit(k);
    return "";
  }
  return "";
}

SweepPlotSpec parse_plot_spec(const std::string& text, const SweepPlan& plan, const std::string& header) {
  const Location where{"--plot " + text, 0, 0};
  const auto columns = split_csv_line(header);
  std::vector<std::string> parts;
  size_t start = 0;
  for (;;) {
    const auto p = text.find(':', start);
    parts.push_back(text.substr(start, p == std::string::npos ? std::string::npos : p - start));
    if (p == std::string::npos) break;
    start = p + 1;
  }
  if (parts.size() > 3 || parts[0].empty()) throw InputError(where, "expected OUTPUT, OUTPUT:X or OUTPUT:X:Y");
  SweepPlotSpec spec;
  spec.output = parts[0];
  if (std::find(columns.begin(), columns.end(), spec.output) == columns.end() || spec.output == "run" ||
      spec.output == "status" || spec.output == "message")
    throw InputError(where, fmt::format("no output column '{}'; the table has: {}", spec.output,
                                        fmt::join(columns.begin() + 1, columns.end() - 2, ", ")));
  std::vector<std::string> targets;
  for (const auto& a : plan.axes) targets.push_back(a.target);
  if (!plan.request.cases.empty()) targets.push_back("case");
  if (parts.size() == 1) {
    for (size_t d = 0; d < std::min<size_t>(2, targets.size()); ++d) spec.inputs.push_back(targets[d]);
    if (targets.size() > 2 && targets.back() == "case") spec.inputs.back() = "case";  // one curve per case
  } else {
    for (size_t k = 1; k < parts.size(); ++k) {
      if (std::find(targets.begin(), targets.end(), parts[k]) == targets.end())
        throw InputError(where, fmt::format("'{}' is not varied; the varied fields are: {}", parts[k], fmt::join(targets, ", ")));
      spec.inputs.push_back(parts[k]);
    }
    // With load cases every x has one point per case: one curve per case, never one line zig-zagging
    // between the cases.
    const bool cases = !plan.request.cases.empty();
    if (cases && spec.inputs.size() == 1 && spec.inputs[0] != "case") spec.inputs.push_back("case");
    if (cases && spec.inputs.size() == 2 && spec.inputs[0] != "case" && spec.inputs[1] != "case")
      throw InputError(where, "with load cases, one of X and Y must be 'case' (one curve per case)");
  }
  for (const auto& x : spec.inputs) {
    spec.input_axes.push_back(plot::make_axis(x, field_unit(plan.base_model, x)));
    for (const auto& a : plan.axes)
      if (a.target == x) spec.input_axes.back().log = a.spec.kind == SampleSpec::Kind::range && a.spec.log;
  }
  spec.output_axis = column_axis(spec.output);
  spec.title = fmt::format("{}: {} against {}", plan.base_model.name, spec.output_axis.quantity, fmt::join(spec.inputs, " and "));
  return spec;
}

std::string sweep_plot_csv(const std::string& table_path, const SweepPlotSpec& spec) {
  std::ifstream in(table_path);
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error("cannot read " + table_path);
  const auto header = split_csv_line(line);
  auto col = [&](const std::string& name) {
    return static_cast<size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  std::vector<size_t> pick;
  for (const auto& x : spec.inputs) pick.push_back(col(x));
  pick.push_back(col(spec.output));
  const size_t status = col("status");
  std::string out;
  auto add = [&out](size_t k, const std::string& field) {
    if (k > 0) out += ',';
    out += csv_field(field);
  };
  for (size_t k = 0; k < pick.size(); ++k) add(k, header.at(pick[k]));
  out += '\n';
  while (std::getline(in, line)) {
    const auto f = split_csv_line(line);
    if (f.size() != header.size() || f[status] != "ok") continue;
    for (size_t k = 0; k < pick.size(); ++k) add(k, f[pick[k]]);
    out += '\n';
  }
  return out;
}

plot::Figure sweep_plot_figure(const std::string& data_csv, const SweepPlotSpec& spec) {
  if (spec.inputs.empty() || spec.inputs.size() > 2 || spec.input_axes.size() != spec.inputs.size())
    throw std::invalid_argument("a sweep plot needs one or two inputs with their axes");
  PlotData d = parse_data(data_csv, spec.inputs.size());
  plot::Figure f;
  f.id = "sweep_plot";
  f.title = spec.title;
  f.x = spec.input_axes[0];
  f.y = spec.output_axis;
  categorical_x(d, f.x);
  // A log axis over less than a decade or two gets one labelled tick at every design value.
  if (f.x.log && f.x.ticks.empty()) {
    std::vector<double> xs;
    for (double v : d.x)
      if (std::isfinite(v) && v > 0 && std::find(xs.begin(), xs.end(), v) == xs.end()) xs.push_back(v);
    std::sort(xs.begin(), xs.end());
    if (xs.size() <= 12)
      for (double v : xs) f.x.ticks.emplace_back(v, fmt::format("{:.4g}", v));
  }
  auto style = [](size_t points) { return points <= 60 ? plot::Style::linepoints : plot::Style::line; };
  if (spec.inputs.size() == 1) {
    std::vector<double> x = d.x, z = d.z;
    sort_by_x(x, z);
    const size_t n = x.size();
    f.series.push_back(plot::make_series(spec.output, std::move(x), std::move(z), style(n)));
    f.series.back().in_legend = false;  // one curve: the y axis says what it is
    return f;
  }
  const auto ys = distinct(d.y_text);
  const bool by_case = spec.inputs[1] == "case";
  if (!by_case && static_cast<int>(ys.size()) > kMaxCurves)
    throw std::invalid_argument(fmt::format("{} takes {} values: more than {} curves, a heat map", spec.inputs[1], ys.size(), kMaxCurves));
  std::vector<std::pair<double, std::string>> order;
  for (const auto& y : ys) order.emplace_back(to_number(y), y);
  std::stable_sort(order.begin(), order.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (const auto& [value, text] : order) {
    std::vector<double> x, z;
    for (size_t i = 0; i < d.z.size(); ++i)
      if (d.y_text[i] == text) x.push_back(d.x[i]), z.push_back(d.z[i]);
    sort_by_x(x, z);
    const size_t n = x.size();
    f.series.push_back(plot::make_series(by_case ? text : spec.inputs[1] + " = " + value_label(text, spec.input_axes[1]),
                                         std::move(x), std::move(z), style(n)));
    // Past the palette's colours (plot::series_color repeats) a curve is dashed.
    const size_t k = f.series.size() - 1;
    for (size_t j = 0; j < k; ++j)
      if (plot::series_color(j) == plot::series_color(k)) f.series.back().dashed = true;
  }
  f.legend = plot::Figure::Legend::below;
  return f;
}

plot::Rendered render_sweep_plot(const std::string& data_csv, const SweepPlotSpec& spec) {
  if (spec.inputs.size() == 2 && spec.inputs[1] != "case") {
    PlotData d = parse_data(data_csv, 2);
    if (static_cast<int>(distinct(d.y_text).size()) > kMaxCurves) return render_heat_map(d, spec);
  }
  return plot::render(sweep_plot_figure(data_csv, spec));
}

}  // namespace machdyn
