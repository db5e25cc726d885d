// Static figures through gnuplot: the data file, the script, and the subprocess that runs it.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fmt/format.h>

#include "machdyn/io/plot.hpp"

extern char** environ;

namespace machdyn::plot {

std::string quote(const std::string& s) {
  std::string q = "'";
  for (const char ch : s) q += ch == '\'' ? std::string("''") : std::string(1, ch);
  return q + "'";
}

namespace {

namespace fs = std::filesystem;

/// Characters, not bytes, of a UTF-8 string (for margins).
std::size_t utf8_length(const std::string& s) {
  return static_cast<std::size_t>(std::count_if(s.begin(), s.end(), [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; }));
}

/// A title as a gnuplot string, broken into lines of at most kTitleWidth characters: a longer one
/// is cut off at both ends of the canvas (about 90 characters of 12 pt fit 800 px). Breaks after
/// the last "; ", ": " or ", " that fits (else the last space); a double-quoted string, so "\n" breaks.
std::string title_string(const std::string& title) {
  constexpr std::size_t kTitleWidth = 84;
  std::vector<std::string> lines;
  std::string rest = title;
  while (utf8_length(rest) > kTitleWidth) {
    std::size_t limit = 0;  // the byte after the kTitleWidth-th character
    for (std::size_t chars = 0; limit < rest.size() && chars <= kTitleWidth; ++limit)
      if ((static_cast<unsigned char>(rest[limit]) & 0xC0) != 0x80) ++chars;
    std::size_t cut = std::string::npos;
    for (const char* sep : {"; ", ": ", ", "}) {
      const std::size_t p = rest.rfind(sep, limit - 2);
      if (p != std::string::npos && p >= limit / 2 && (cut == std::string::npos || p + 1 > cut)) cut = p + 1;
    }
    if (cut == std::string::npos) cut = rest.rfind(' ', limit - 1);
    if (cut == std::string::npos || cut == 0) break;
    lines.push_back(rest.substr(0, cut));
    rest = rest.substr(cut + 1);
  }
  lines.push_back(rest);
  std::string q = "\"";
  for (std::size_t k = 0; k < lines.size(); ++k) {
    if (k) q += "\\n";
    for (const char ch : lines[k]) {
      if (ch == '"' || ch == '\\') q += '\\';
      q += ch;
    }
  }
  return q + "\"";
}

bool finite_point(const Series& s, std::size_t k) { return std::isfinite(s.x[k]) && std::isfinite(s.y[k]); }

bool has_points(const Series& s) {
  for (std::size_t k = 0; k < s.x.size(); ++k)
    if (finite_point(s, k)) return true;
  return false;
}

struct Range {
  double lo = std::numeric_limits<double>::infinity(), hi = -std::numeric_limits<double>::infinity();
  void add(double v) {
    if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
  }
  [[nodiscard]] bool valid() const { return lo <= hi; }
};

/// The range gnuplot draws for an axis: the fixed one, else the data (and reference lines) with a
/// margin of `pad` of the span on each side (none on x for time series: the run starts and ends there).
std::string range_cmd(const char* axis, const Axis& a, Range r, double pad) {
  if (a.min) r.lo = *a.min;
  if (a.max) r.hi = *a.max;
  if (!r.valid()) return fmt::format("set autoscale {}\n", axis);
  if (a.log && r.lo > 0) {  // the margin as a factor: the same share of the log axis on each side
    const double ratio = std::pow(r.hi / r.lo, pad);
    return fmt::format("set {}range [{:.9g}:{:.9g}]\n", axis, a.min ? *a.min : r.lo / ratio, a.max ? *a.max : r.hi * ratio);
  }
  double span = r.hi - r.lo;
  if (span <= 0) span = std::max(std::abs(r.hi), 1.0);
  const double lo = a.min ? *a.min : r.lo - pad * span, hi = a.max ? *a.max : r.hi + pad * span;
  if (lo == hi) return fmt::format("set {}range [{:.9g}:{:.9g}]\n", axis, lo - 0.5, hi + 0.5);
  return fmt::format("set {}range [{:.9g}:{:.9g}]\n", axis, lo, hi);
}

std::string ticks_cmd(const char* axis, const Axis& a) {
  if (a.ticks.empty()) return "";
  std::string s = fmt::format("set {}tics (", axis);
  for (std::size_t k = 0; k < a.ticks.size(); ++k)
    s += fmt::format("{}{} {:.9g}", k ? ", " : "", quote(a.ticks[k].second), a.ticks[k].first);
  return s + ")\n";
}

const char* key_position(Figure::Legend l) {
  switch (l) {
    case Figure::Legend::top_left: return "inside top left";
    case Figure::Legend::bottom_right: return "inside bottom right";
    case Figure::Legend::bottom_left: return "inside bottom left";
    case Figure::Legend::below: return "outside below center horizontal";
    default: return "inside top right";
  }
}

/// Runs `exe args...` with stdout and stderr into `log`; returns the exit status (-1 if not run).
int run_process(const fs::path& exe, const std::vector<std::string>& args, const fs::path& log) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  std::vector<std::string> argv_s{exe.string()};
  argv_s.insert(argv_s.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (auto& a : argv_s) argv.push_back(a.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int rc = posix_spawn(&pid, exe.c_str(), &fa, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&fa);
  if (rc != 0) return -1;
  int status = 0;
  while (waitpid(pid, &status, 0) < 0)
    if (errno != EINTR) return -1;
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

/// A fresh private folder under the temp dir, removed when this goes out of scope.
struct TempDir {
  fs::path path;
  TempDir() {
    std::string tmpl = (fs::temp_directory_path() / "machdyn-plot-XXXXXX").string();
    if (!::mkdtemp(tmpl.data())) throw std::runtime_error("cannot create a temporary folder for gnuplot");
    path = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
};

}  // namespace

std::string gnuplot_data(const Figure& fig) {
  std::string d;
  for (const auto& s : fig.series) {
    if (!has_points(s)) continue;
    d += "# " + s.name + "\n";
    bool broken = true;  // no blank line at the start of a block or twice in a row
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      if (!finite_point(s, k)) {
        if (!broken) d += '\n';
        broken = true;
        continue;
      }
      fmt::format_to(std::back_inserter(d), "{:.10g} {:.10g}\n", s.x[k], s.y[k]);
      broken = false;
    }
    d += "\n\n";
  }
  return d;
}

std::string gnuplot_script(const Figure& fig, Format format, const std::string& data_path,
                           const std::string& output_path) {
  validate(fig);
  std::string g = "reset\nset encoding utf8\n";
  // 16 cm × 10 cm: SVG at 12 pt, PNG at twice the pixels and font (≈ 250 dpi at print size).
  if (format == Format::svg)
    g += "set terminal svg size 800,500 dynamic noenhanced font 'DejaVu Sans,12' background '#ffffff' linewidth 1\n";
  else
    g += "set terminal pngcairo size 1600,1000 noenhanced font 'DejaVu Sans,24' background '#ffffff' linewidth 2\n";
  g += "set output " + quote(output_path) + "\n";
  if (!fig.title.empty()) g += "set title " + title_string(fig.title) + "\n";
  g += "set border 3 lw 1\nset tics nomirror out\n";
  g += "set grid xtics ytics lc rgb '#d0d0d0' lw 1 dt 1\n";
  g += "set xlabel " + quote(fig.x.label()) + "\n";
  g += "set ylabel " + quote(fig.y.label()) + "\n";
  const bool y2 = std::any_of(fig.series.begin(), fig.series.end(), [](const Series& s) { return s.y_axis == 2; });
  if (y2) {
    g += "set border 11 lw 1\nset y2tics nomirror out\nset y2label " + quote(fig.y2.label()) + "\n";
  }
  g += ticks_cmd("x", fig.x) + ticks_cmd("y", fig.y);
  if (fig.x.log) g += "set logscale x\n";
  if (fig.y.log) g += "set logscale y\n";
  g += fmt::format("set key {} noautotitle samplen 2.5 spacing 1.15 width 1\n", key_position(fig.legend));

  // Plain decimal tick labels, never e-notation (the figure functions scale to kN, kN·m, ...).
  g += "set format x '%.10g'\nset format y '%.10g'\n";
  if (y2) g += "set format y2 '%.10g'\n";

  Range rx, ry, ry2;
  for (const auto& s : fig.series)
    for (std::size_t k = 0; k < s.x.size(); ++k)
      if (finite_point(s, k)) rx.add(s.x[k]), (s.y_axis == 2 ? ry2 : ry).add(s.y[k]);
  for (const auto& r : fig.ref_lines) (r.y_axis == 2 ? ry2 : ry).add(r.value);
  for (const auto& n : fig.notes) (n.y_axis == 2 ? ry2 : ry).add(n.y);
  if (fig.zero_line) ry.add(0.0);
  if (fig.zero_line && y2) ry2.add(0.0);
  if (fig.equal_aspect) {
    g += "set size ratio -1\n";
    g += range_cmd("x", fig.x, rx, 0.04) + range_cmd("y", fig.y, ry, 0.04);
  } else if (fig.zero_line && y2 && ry.valid() && ry2.valid() && !fig.y.min && !fig.y.max && !fig.y2.min &&
             !fig.y2.max) {
    // Two axes, one zero line: the zeros sit at the same height, so a curve on either axis is read
    // against the same line (a rope at 43.5 kN never looks slack).
    g += range_cmd("x", fig.x, rx, fig.x.ticks.empty() ? 0.0 : 0.08);
    auto pad = [](Range r) {
      const double span = r.hi - r.lo > 0 ? r.hi - r.lo : std::max(std::abs(r.hi), 1.0);
      r.lo = r.lo < 0 ? r.lo - 0.08 * span : 0.0;
      r.hi = r.hi > 0 ? r.hi + 0.08 * span : 0.0;
      if (r.lo == r.hi) r.hi = 1.0;
      return r;
    };
    Range a = pad(ry), b = pad(ry2);
    // Fraction of the height below zero: the larger one for both axes.
    const double f = std::max(-a.lo / (a.hi - a.lo), -b.lo / (b.hi - b.lo));
    for (Range* r : {&a, &b}) {
      if (f >= 1.0) r->hi = 0.0, r->lo = std::min(r->lo, -1.0);
      else if (r->hi > 0.0) r->lo = std::min(r->lo, -f / (1.0 - f) * r->hi);
      else r->hi = -r->lo * (1.0 - f) / f;
    }
    g += fmt::format("set yrange [{:.9g}:{:.9g}]\nset y2range [{:.9g}:{:.9g}]\n", a.lo, a.hi, b.lo, b.hi);
  } else {
    g += range_cmd("x", fig.x, rx, fig.x.ticks.empty() ? 0.0 : 0.08);
    // Room above the data for the labels of reference lines and an inside legend.
    g += range_cmd("y", fig.y, ry, 0.08);
    if (y2) g += range_cmd("y2", fig.y2, ry2, 0.08);
  }
  // Events: dotted vertical lines, labels written upwards from just inside the bottom (the peak
  // note sits at the top) on an opaque box, so a curve behind them does not garble them.
  const std::string small_font = format == Format::svg ? "DejaVu Sans,9" : "DejaVu Sans,18";
  if (!fig.events.empty()) g += "set style textbox opaque noborder\n";
  for (const auto& e : fig.events) {
    g += fmt::format("set arrow from first {0:.10g}, graph 0 to first {0:.10g}, graph 1 nohead lc rgb '#707070' lw 1 "
                     "dt 3 back\n",
                     e.x);
    if (!e.label.empty())
      g += fmt::format("set label {} at first {:.10g}, graph 0.02 rotate by 90 left offset -0.4,0 tc rgb '#505050' "
                       "font '{}' boxed front\n",
                       quote(e.label), e.x, small_font);
  }
  for (const auto& n : fig.notes) {
    const std::string color = n.series >= 0 ? series_color(static_cast<std::size_t>(n.series)) : "#000000";
    // Text on the side with room: right of the point in the left 60 % of the plot, else left of it.
    const bool left = rx.valid() && rx.hi > rx.lo && (n.x - rx.lo) / (rx.hi - rx.lo) > 0.6;
    g += fmt::format("set label {} at first {:.10g}, {} {:.10g} {} point pt 6 ps 1.6 lc rgb '{}' offset {},0.6 "
                     "tc rgb '{}' front\n",
                     quote(n.text), n.x, n.y_axis == 2 ? "second" : "first", n.y, left ? "right" : "left", color,
                     left ? "-1.2" : "1.2", color);
  }
  for (std::size_t k = 0; k < fig.bands.size(); ++k)
    g += fmt::format("set object {} rect from first {:.10g}, graph 0 to first {:.10g}, graph 1 behind fc rgb '{}' "
                     "fs solid 1.0 noborder\n", k + 1, fig.bands[k].x0, fig.bands[k].x1, kBandColor);
  if (fig.zero_line) g += "set arrow from graph 0, first 0 to graph 1, first 0 nohead lc rgb '#777777' lw 1 dt 1\n";
  // Reference lines: labels in the right margin (clear of the curves) unless y2 needs that margin;
  // then inside, on an opaque box.
  std::size_t label_chars = 0;
  for (const auto& r : fig.ref_lines) label_chars = std::max(label_chars, utf8_length(r.label));
  if (!y2 && label_chars > 0) g += fmt::format("set rmargin {}\n", label_chars + 2);
  if (y2) g += "set style textbox opaque noborder\n";
  for (const auto& r : fig.ref_lines) {
    const std::string color = r.series >= 0 ? series_color(static_cast<std::size_t>(r.series)) : "#000000";
    const char* coord = r.y_axis == 2 ? "second" : "first";
    g += fmt::format("set arrow from graph 0, {2} {0:.10g} to graph 1, {2} {0:.10g} nohead lc rgb '{1}' lw 1.5 dt 2 front\n",
                     r.value, color, coord);
    if (r.label.empty()) continue;
    if (!y2)
      g += fmt::format("set label {} at graph 1, {} {:.10g} left offset 0.8,0 tc rgb '{}' front\n", quote(r.label), coord,
                       r.value, color);
    else
      g += fmt::format("set label {} at graph 0.99, {} {:.10g} right offset 0,0.8 tc rgb '{}' boxed front\n",
                       quote(r.label), coord, r.value, color);
  }

  std::vector<std::string> items;
  int index = 0;
  for (std::size_t k = 0; k < fig.series.size(); ++k) {
    const Series& s = fig.series[k];
    if (!has_points(s)) continue;
    std::string item = fmt::format("{} index {} using 1:2", quote(data_path), index++);
    const std::string axes = s.y_axis == 2 ? " axes x1y2" : " axes x1y1";
    const std::string dash = s.dashed ? " dt 2" : " dt 1";
    const std::string title = s.in_legend ? "title " + quote(s.name) : std::string("notitle");
    switch (s.style) {
      case Style::thin:
        item += " with lines lc rgb '#b4b4b4' lw 0.6 dt 1 notitle" + axes;
        break;
      case Style::steps:
        item += fmt::format(" with steps lc rgb '{}' lw 2{} {}{}", series_color(k), dash, title, axes);
        break;
      case Style::linepoints:
        item += fmt::format(" with linespoints lc rgb '{}' lw 2{} pt 7 ps 1.2 {}{}", series_color(k), dash, title,
                            axes);
        break;
      case Style::points:
        item += fmt::format(" with points lc rgb '{}' pt 7 ps 1.1 {}{}", series_color(k), title, axes);
        break;
      case Style::line:
        item += fmt::format(" with lines lc rgb '{}' lw 2{} {}{}", series_color(k), dash, title, axes);
        break;
    }
    items.push_back(item);
  }
  if (!fig.bands.empty() && !fig.bands_label.empty() && !items.empty())
    items.push_back(fmt::format("NaN with boxes fs solid 1.0 noborder fc rgb '{}' title {}", kBandColor,
                                quote(fig.bands_label)));
  if (items.empty()) {
    g += "set label 'no data' at graph 0.5, graph 0.5 center\nplot NaN notitle\n";
  } else {
    g += "plot ";
    for (std::size_t k = 0; k < items.size(); ++k) g += (k ? ", \\\n     " : "") + items[k];
    g += "\n";
  }
  g += "unset output\n";
  return g;
}

fs::path find_gnuplot() {
  const std::string hint = "install it with `apt-get install gnuplot-nox` (scripts/install-deps.sh does)";
  if (const char* env = std::getenv("MACHDYN_GNUPLOT"); env && *env) {
    if (::access(env, X_OK) == 0) return env;
    throw std::runtime_error(fmt::format("MACHDYN_GNUPLOT={} is not an executable; the static figures need gnuplot: {}",
                                         env, hint));
  }
  if (const char* path = std::getenv("PATH")) {
    std::stringstream ss(path);
    for (std::string dir; std::getline(ss, dir, ':');) {
      if (dir.empty()) continue;
      const fs::path p = fs::path(dir) / "gnuplot";
      if (::access(p.c_str(), X_OK) == 0) return p;
    }
  }
  throw std::runtime_error("the static figures (--plot) need gnuplot, which is not on PATH: " + hint);
}

Rendered render_script(const std::string& data, const ScriptFor& script, const std::string& what) {
  const fs::path gnuplot = find_gnuplot();
  TempDir tmp;
  const fs::path data_path = tmp.path / "data.dat", svg = tmp.path / "figure.svg", png = tmp.path / "figure.png",
                 script_path = tmp.path / "figure.gp", log = tmp.path / "gnuplot.log";
  std::ofstream(data_path, std::ios::binary) << data;
  std::ofstream(script_path, std::ios::binary) << script(Format::svg, data_path.string(), svg.string())
                                               << script(Format::png, data_path.string(), png.string());
  const int rc = run_process(gnuplot, {script_path.string()}, log);
  if (rc != 0)
    throw std::runtime_error(
        fmt::format("gnuplot ({}) failed drawing {} (exit {}): {}", gnuplot.string(), what, rc, slurp(log)));
  Rendered r{slurp(svg), slurp(png)};
  if (r.svg.empty() || r.png.empty()) throw std::runtime_error(fmt::format("gnuplot wrote no {}: {}", what, slurp(log)));
  return r;
}

Rendered render(const Figure& fig) {
  validate(fig);
  return render_script(
      gnuplot_data(fig),
      [&](Format f, const std::string& data_path, const std::string& out) { return gnuplot_script(fig, f, data_path, out); },
      fmt::format("figure '{}'", fig.id));
}

}  // namespace machdyn::plot
