// The figures of a duty and its report section (io/duty_figures.hpp). Each function only selects
// and labels data; the counts and figures are those of run_duty.
#include "machdyn/io/duty_figures.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <functional>
#include <map>

#include <fmt/format.h>

#include "machdyn/analysis/duty_classes.hpp"
#include "io/number_text.hpp"

namespace machdyn {
namespace {

/// A file stem of a link name: letters, digits, '_' and '-' kept, anything else '_'.
std::string stem(const std::string& name) {
  std::string s = name;
  for (char& c : s)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_' && c != '-') c = '_';
  return s;
}

/// The exceedance diagram with x = H on a log axis (log_x) or x = log10 H on a linear one (both the
/// report's charts, which have linear axes only, and gnuplot, whose log-axis labels of 10^6 and
/// 10^7 run into each other, use the latter).
plot::Figure exceedance_figure(const DutyLink& l, double m, bool log_x) {
  const Exceedance e = exceedance(l.cycles);
  const double largest = e.range.empty() ? 0.0 : e.range.front();
  const auto [k, unit] = engineering_unit(largest, l.unit);
  plot::Figure f;
  f.id = "duty_exceedance_" + stem(l.link);
  f.title = fmt::format("{}: cumulative spectrum of the load ranges, {} cycles", l.link, label_number(l.history.total_cycles));
  f.x = log_x ? plot::make_axis("cumulative cycles H", "") : plot::make_axis("cumulative cycles log₁₀ H", "");
  f.x.log = log_x;
  f.y = plot::make_axis("load range Δ", unit);
  f.y.min = 0.0;
  // The staircase: from (H_{j-1}, Δ_j) to (H_j, Δ_j); the first step starts at H of the largest.
  std::vector<double> x, y;
  double before = 0.0;
  for (std::size_t j = 0; j < e.range.size(); ++j) {
    const double from = j == 0 ? std::min(e.cycles[0], 1.0) : before;
    x.push_back(log_x ? from : std::log10(std::max(from, 1e-300))), y.push_back(k * e.range[j]);
    x.push_back(log_x ? e.cycles[j] : std::log10(e.cycles[j])), y.push_back(k * e.range[j]);
    before = e.cycles[j];
  }
  if (!log_x)  // H < 1 (a half cycle alone) has log10 H < 0: the axis starts at the first count
    for (double& v : x) v = std::max(v, std::log10(std::min(e.cycles.empty() ? 1.0 : e.cycles[0], 1.0)));
  f.series.push_back(plot::make_series(l.link, x, y));
  if (largest > 0.0) {
    f.ref_lines.push_back(plot::make_ref_line(k * l.equivalent_range, fmt::format("Δ_eq = {} {} (N_t cycles)",
                                                                                label_number(k * l.equivalent_range), unit), 0));
    for (int L = 1; L <= 3; ++L) {
      const double lim = spectrum_class_limit(L);
      f.ref_lines.push_back(plot::make_ref_line(k * largest * std::pow(lim, 1.0 / m),
                                                fmt::format("k = {} (L{}/L{})", label_number(lim), L, L + 1), -1));
    }
  }
  f.legend = plot::Figure::Legend::top_right;
  return f;
}

}  // namespace

Exceedance exceedance(const std::vector<RainflowCycle>& cycles) {
  std::map<double, double, std::greater<>> by_range;  // range → count, largest first
  for (const RainflowCycle& c : cycles)
    if (c.count > 0.0) by_range[c.range()] += c.count;
  Exceedance e;
  double sum = 0.0;
  for (const auto& [range, count] : by_range) {
    sum += count;
    e.range.push_back(range), e.cycles.push_back(sum);
  }
  return e;
}

plot::Figure duty_exceedance_figure(const DutyLink& l, double m) { return exceedance_figure(l, m, false); }

std::string duty_heat_map_data(const DutyLink& l, int bins) {
  const RainflowMatrix M = range_mean_matrix(l.cycles, bins, bins);
  const double wr = (M.row_hi - M.row_lo) / M.rows, wc = (M.col_hi - M.col_lo) / M.cols;
  std::string data;
  for (int i = 0; i < M.rows; ++i)
    for (int j = 0; j < M.cols; ++j)
      if (M.at(i, j) > 0.0)
        data += fmt::format("{:.10g} {:.10g} {:.10g} {:.10g} {:.10g}\n", M.row_lo + i * wr, M.row_lo + (i + 1) * wr,
                            M.col_lo + j * wc, M.col_lo + (j + 1) * wc, M.at(i, j));
  return data;
}

plot::Rendered render_duty_heat_map(const DutyLink& l, int bins) {
  const RainflowMatrix M = range_mean_matrix(l.cycles, bins, bins);
  const double largest = std::max({M.row_hi, std::abs(M.col_lo), std::abs(M.col_hi)});
  const auto [k, unit] = engineering_unit(largest, l.unit);
  // Cells in the engineering unit; an empty axis (one range or one mean) a cell of unit width.
  std::string data;
  const double wr = (M.row_hi - M.row_lo) / M.rows, wc = (M.col_hi - M.col_lo) / M.cols;
  for (int i = 0; i < M.rows; ++i)
    for (int j = 0; j < M.cols; ++j)
      if (M.at(i, j) > 0.0) {
        double r0 = M.row_lo + i * wr, r1 = M.row_lo + (i + 1) * wr, m0 = M.col_lo + j * wc, m1 = M.col_lo + (j + 1) * wc;
        if (!(r1 > r0)) r0 -= 0.5, r1 += 0.5;
        if (!(m1 > m0)) m0 -= 0.5, m1 += 0.5;
        data += fmt::format("{:.10g} {:.10g} {:.10g} {:.10g} {:.10g} {:.10g} {:.10g}\n", k * 0.5 * (m0 + m1),
                            k * 0.5 * (r0 + r1), k * m0, k * m1, k * r0, k * r1, M.at(i, j));
      }
  const std::string title = fmt::format("{}: rainflow matrix, {} cycles in {} × {} classes (colour: cycles, log scale)",
                                        l.link, label_number(M.total()), bins, bins);
  const auto script = [&, unit = unit](plot::Format format, const std::string& data_path, const std::string& out) {
    const bool svg = format == plot::Format::svg;
    std::string g = "reset\nset encoding utf8\n";
    g += svg ? "set terminal svg size 800,500 dynamic noenhanced font 'DejaVu Sans,12' background '#ffffff' linewidth 1\n"
             : "set terminal pngcairo size 1600,1000 noenhanced font 'DejaVu Sans,24' background '#ffffff' linewidth 2\n";
    g += "set output " + plot::quote(out) + "\n";
    g += "set border 3 lw 1\nset tics nomirror out\nset key off\n";
    g += "set title " + plot::quote(title) + "\n";
    g += "set xlabel " + plot::quote("mean load, " + unit) + "\n";
    g += "set ylabel " + plot::quote("load range Δ, " + unit) + "\n";
    g += "set format x '%.10g'\nset format y '%.10g'\n";
    g += "set logscale cb\n";
    // Viridis, as the sweep's heat map: monotone in lightness, readable in greyscale.
    g += "set palette defined (0 '#440154', 0.25 '#3b528b', 0.5 '#21918c', 0.75 '#5ec962', 1 '#fde725')\n";
    g += "set yrange [0:*]\n";
    g += "plot " + plot::quote(data_path) + " using 1:2:3:4:5:6:7 with boxxyerror fill solid 1.0 noborder lc palette notitle\n";
    return g + "unset output\n";
  };
  return plot::render_script(data, script, "the duty heat map of " + l.link);
}

report::Section duty_report_section(const DutyResult& r) {
  const DutySpec& d = r.spec;
  report::Section s;
  s.title = "Duty: load cycles and classification";
  s.paragraphs.push_back(fmt::format(
      "Each operation simulated once; every counted link load rainflow-counted over its located turning points "
      "(residue: {}, gate {} of each operation's range), the counts multiplied by the operations' numbers and merged "
      "over the duty. k_m = Σ n_i ∫|P|³dt / (P_max³ Σ n_i T_i) over the running time; classes of ISO 4301-1 / "
      "FEM 1.001 (docs/duty.md).",
      d.residue == RainflowResidue::repeat ? "closed by repetition" : "half cycles", label_number(d.gate)));
  report::Table ops;
  ops.caption = "Operations";
  ops.header = {"operation", "case", "per hour", "number n", "running time T_i, s"};
  for (std::size_t i = 0; i < d.operations.size(); ++i) {
    const DutyOperation& op = d.operations[i];
    ops.rows.push_back({op.name, op.load_case.empty() ? "(model)" : op.load_case,
                        op.per_hour >= 0.0 ? label_number(op.per_hour) : "", fmt::format("{:.0f}", op.repeat),
                        i < r.op_seconds.size() ? label_number(r.op_seconds[i]) : ""});
  }
  ops.note = fmt::format("running time Σ n_i T_i = {:.6g} h: class of utilization T{}{}", r.running_hours,
                         r.utilization_class,
                         d.design_life_h > 0.0 ? fmt::format(" (design life {:.6g} h)", d.design_life_h) : "");
  s.tables.push_back(ops);
  report::Table t;
  t.caption = "Per link";
  t.header = {"link", "unit", "cycles N_t", "largest range Δ̂", "Δ_eq", "s", "S (EN 13001)", "P_max", "k_m", "L", "M"};
  if (d.has_curve) t.header.push_back("Miner damage D");
  for (const DutyLink& l : r.links) {
    std::vector<std::string> row = {l.link,
                                    plot::pretty_unit(l.unit),
                                    label_number(l.history.total_cycles),
                                    label_number(l.history.largest),
                                    label_number(l.equivalent_range),
                                    label_number(l.history.s),
                                    stress_history_class_name(l.stress_class),
                                    label_number(l.p_max) + (l.rated ? " (rated)" : ""),
                                    fmt::format("{:.4f}", l.k_m),
                                    fmt::format("L{}", l.spectrum_class),
                                    fmt::format("M{}", l.group)};
    if (d.has_curve) row.push_back(label_number(l.damage));
    t.rows.push_back(row);
  }
  t.note = fmt::format("s = Σ n (Δ/Δ̂)^m / N_ref with m = {}, N_ref = {}; Δ_eq for N_t cycles with exponent m", label_number(d.m),
                       label_number(d.n_ref));
  s.tables.push_back(t);
  for (const DutyLink& l : r.links)
    if (!l.cycles.empty()) s.figures.push_back(exceedance_figure(l, d.m, false));
  return s;
}

}  // namespace machdyn
