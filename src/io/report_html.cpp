// The self-contained HTML page of a report::Document: tables, and figures drawn by the embedded
// uPlot from JSON blocks in the page. Nothing is loaded from the network.
#include <algorithm>
#include <cmath>
#include <stdexcept>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "io/report_assets.hpp"
#include "machdyn/io/report.hpp"

namespace machdyn::report {

namespace {

std::string escape_html(const std::string& s) {
  std::string o;
  o.reserve(s.size());
  for (const char ch : s) {
    switch (ch) {
      case '&': o += "&amp;"; break;
      case '<': o += "&lt;"; break;
      case '>': o += "&gt;"; break;
      case '"': o += "&quot;"; break;
      default: o += ch;
    }
  }
  return o;
}

/// JSON inside <script>: "</" would end the element early.
std::string script_safe(std::string s) {
  for (std::size_t p = 0; (p = s.find("</", p)) != std::string::npos; p += 3) s.replace(p, 2, "<\\/");
  return s;
}

void append_number(std::string& o, double v, int digits) {
  if (std::isfinite(v)) fmt::format_to(std::back_inserter(o), "{:.{}g}", v, digits);
  else o += "null";
}

bool same_x(const std::vector<plot::Series>& s) {
  for (std::size_t k = 1; k < s.size(); ++k)
    if (s[k].x != s[0].x) return false;
  return true;
}

const char* style_name(plot::Style s) {
  switch (s) {
    case plot::Style::steps: return "steps";
    case plot::Style::linepoints: return "linepoints";
    case plot::Style::thin: return "thin";
    case plot::Style::points: return "points";
    default: return "line";
  }
}

// The page's own script: builds one uPlot per figure, adds reference lines, wheel zoom and
// Shift+drag pan, and writes a status for tests. Kept in one raw string, no templating.
constexpr const char* kPageScript = R"js(
(function () {
  "use strict";
  var status = { done: false, errors: [], plots: [] };
  var statusEl = document.getElementById("machdyn-status");
  function writeStatus() { statusEl.textContent = JSON.stringify(status); }
  window.addEventListener("error", function (e) { status.errors.push(String(e.message || e)); writeStatus(); });
  writeStatus();

  function fmtNum(v) {
    if (v == null || !isFinite(v)) return "–";
    var a = Math.abs(v);
    if (a !== 0 && (a < 1e-3 || a >= 1e6)) return v.toExponential(4);
    return String(Number(v.toPrecision(6)));
  }
  function hexRgb(h) { return [parseInt(h.substr(1, 2), 16), parseInt(h.substr(3, 2), 16), parseInt(h.substr(5, 2), 16)]; }

  // Dashed horizontal lines (e.g. the static load M*) in the colour of their series, labelled.
  function refLinesPlugin(spec) {
    return { hooks: { draw: [function (u) {
      var ctx = u.ctx, dpr = window.devicePixelRatio || 1;
      spec.refs.forEach(function (r) {
        if (r.series >= 0 && !u.series[r.series + 1].show) return;
        var key = r.axis === 2 ? "y2" : "y";
        var y = Math.round(u.valToPos(r.value, key, true));
        if (y < u.bbox.top || y > u.bbox.top + u.bbox.height) return;
        ctx.save();
        ctx.strokeStyle = r.color; ctx.fillStyle = r.color;
        ctx.lineWidth = 1.5 * dpr; ctx.setLineDash([8 * dpr, 5 * dpr]);
        ctx.beginPath(); ctx.moveTo(u.bbox.left, y); ctx.lineTo(u.bbox.left + u.bbox.width, y); ctx.stroke();
        ctx.font = (12 * dpr) + "px sans-serif"; ctx.textAlign = "right"; ctx.textBaseline = "bottom";
        var tx = u.bbox.left + u.bbox.width - 6 * dpr, tw = ctx.measureText(r.label).width;
        ctx.fillStyle = "rgba(255,255,255,0.85)";
        ctx.fillRect(tx - tw - 3 * dpr, y - 17 * dpr, tw + 6 * dpr, 15 * dpr);
        ctx.fillStyle = r.color;
        ctx.fillText(r.label, tx, y - 3 * dpr);
        ctx.restore();
      });
      if (spec.zero_line) {
        var y0 = Math.round(u.valToPos(0, "y", true));
        if (y0 >= u.bbox.top && y0 <= u.bbox.top + u.bbox.height) {
          ctx.save(); ctx.strokeStyle = "#777"; ctx.lineWidth = dpr;
          ctx.beginPath(); ctx.moveTo(u.bbox.left, y0); ctx.lineTo(u.bbox.left + u.bbox.width, y0); ctx.stroke();
          ctx.restore();
        }
      }
    }] } };
  }

  // Shaded x intervals (slip phases), behind the grid and the series.
  function bandsPlugin(spec) {
    return { hooks: { drawClear: [function (u) {
      if (!spec.bands.length) return;
      var ctx = u.ctx;
      ctx.save(); ctx.fillStyle = spec.band_color;
      spec.bands.forEach(function (b) {
        var x0 = Math.max(u.bbox.left, u.valToPos(b[0], "x", true));
        var x1 = Math.min(u.bbox.left + u.bbox.width, u.valToPos(b[1], "x", true));
        if (x1 > x0) ctx.fillRect(x0, u.bbox.top, x1 - x0, u.bbox.height);
      });
      ctx.restore();
    }] } };
  }

  // Mouse wheel: zoom x around the cursor. Shift+drag or middle-drag: pan x and y.
  function wheelPanPlugin() {
    return { hooks: { ready: [function (u) {
      var over = u.over;
      over.addEventListener("wheel", function (e) {
        e.preventDefault();
        var rect = over.getBoundingClientRect();
        var xv = u.posToVal(e.clientX - rect.left, "x");
        var f = e.deltaY < 0 ? 0.8 : 1.25;
        var mn = u.scales.x.min, mx = u.scales.x.max;
        u.setScale("x", { min: xv - (xv - mn) * f, max: xv + (mx - xv) * f });
      }, { passive: false });
      u.root.addEventListener("mousedown", function (e) {
        if (!(e.shiftKey || e.button === 1) || !over.contains(e.target)) return;
        e.preventDefault(); e.stopPropagation();
        var x0 = e.clientX, y0 = e.clientY;
        var sx = { min: u.scales.x.min, max: u.scales.x.max }, sy = { min: u.scales.y.min, max: u.scales.y.max };
        var pxX = (sx.max - sx.min) / u.bbox.width * (window.devicePixelRatio || 1);
        var pxY = (sy.max - sy.min) / u.bbox.height * (window.devicePixelRatio || 1);
        function move(ev) {
          var dx = (ev.clientX - x0) * pxX, dy = (ev.clientY - y0) * pxY;
          u.batch(function () {
            u.setScale("x", { min: sx.min - dx, max: sx.max - dx });
            u.setScale("y", { min: sy.min + dy, max: sy.max + dy });
          });
        }
        function up() { document.removeEventListener("mousemove", move); document.removeEventListener("mouseup", up); }
        document.addEventListener("mousemove", move); document.addEventListener("mouseup", up);
      }, true);
    }] } };
  }

  // Pixels of each series' colour on the canvas: proof that the series was drawn.
  function drawnPixels(u, spec) {
    var c = u.ctx.canvas, img = u.ctx.getImageData(0, 0, c.width, c.height).data;
    var cols = spec.series.map(function (s) { return hexRgb(s.color); });
    var counts = cols.map(function () { return 0; });
    // The canvas is transparent: an anti-aliased pixel of one line keeps the line's RGB, with less alpha.
    for (var p = 0; p < img.length; p += 4) {
      if (img[p + 3] < 96) continue;
      for (var k = 0; k < cols.length; k++) {
        var col = cols[k];
        if (Math.abs(img[p] - col[0]) <= 12 && Math.abs(img[p + 1] - col[1]) <= 12 && Math.abs(img[p + 2] - col[2]) <= 12) counts[k]++;
      }
    }
    return counts;
  }

  // Whether the laid-out text of el lies inside box (1 px of rounding): its words are not cut.
  function inside(el, box) {
    if (!el || !box) return false;
    var r = document.createRange(); r.selectNodeContents(el);
    var a = r.getBoundingClientRect(), b = box.getBoundingClientRect();
    return a.width > 0 && a.left >= b.left - 1 && a.right <= b.right + 1 && a.top >= b.top - 1 && a.bottom <= b.bottom + 1;
  }

  // An axis title as uPlot draws it on the canvas, centred on the plotting area along its axis: it
  // fits when half its width reaches neither end of the canvas (all in canvas pixels).
  function axisTitle(u, ax) {
    var label = ax.label || "", ctx = u.ctx;
    ctx.save();
    ctx.font = Array.isArray(ax.labelFont) ? ax.labelFont[0] : (ax.labelFont || "bold 12px sans-serif");
    var w = ctx.measureText(label).width;
    ctx.restore();
    var horizontal = ax.side % 2 === 0;
    var c = horizontal ? u.bbox.left + u.bbox.width / 2 : u.bbox.top + u.bbox.height / 2;
    var total = horizontal ? ctx.canvas.width : ctx.canvas.height;
    // Its tick labels as drawn (uPlot's _values; empty ones are the unlabelled grid lines).
    var ticks = (ax._values || []).filter(function (t) { return t != null && t !== ""; }).map(String);
    return { label: label, fits: label.length > 0 && w / 2 <= Math.min(c, total - c) + 1, ticks: ticks };
  }

  // Whether series k lies under a series drawn after it on the same axis (within 1 % of the axis's
  // span at 95 % of their common points): two bodies turning together show one curve, the first
  // visible only where they part briefly (a coupling's switch-on swing).
  function coveredBy(u, spec, k) {
    var key = spec.series[k].axis === 2 ? "y2" : "y", sc = u.scales[key], tol = 0.01 * Math.abs(sc.max - sc.min);
    var a = spec.data[k + 1];
    for (var j = k + 1; j < spec.series.length; j++) {
      if ((spec.series[j].axis === 2 ? "y2" : "y") !== key) continue;
      var b = spec.data[j + 1], near = 0, common = 0;
      for (var i = 0; i < a.length; i++) {
        if (a[i] == null || b[i] == null) continue;
        common++;
        if (Math.abs(a[i] - b[i]) <= tol) near++;
      }
      if (common > 0 && near >= 0.95 * common) return true;
    }
    return false;
  }

  function makeChart(spec) {
    var t0 = performance.now();
    var host = document.getElementById("chart-" + spec.id);
    var width = Math.max(480, host.clientWidth || 900);
    var tickLabels = {};
    spec.x.ticks.forEach(function (t) { tickLabels[t[0]] = t[1]; });
    var series = [{ label: spec.x.label, value: function (u, v) { return v == null ? "–" : (tickLabels[v] || fmtNum(v)); } }];
    spec.series.forEach(function (s) {
      var o = {
        label: s.name, stroke: s.color, width: s.style === "thin" ? 1 : 2, scale: s.axis === 2 ? "y2" : "y",
        spanGaps: spec.union, value: function (u, v) { return fmtNum(v); },
        points: { show: s.style === "linepoints" || s.style === "points", size: s.style === "points" ? 9 : 8, fill: s.color }
      };
      if (s.style === "points") { o.paths = function () { return null; }; o.spanGaps = false; }
      if (s.dashed) o.dash = [8, 5];
      if (s.style === "steps") o.paths = uPlot.paths.stepped({ align: 1 });
      series.push(o);
    });
    function padRange(refsAxis) {
      return function (u, mn, mx) {
        spec.refs.forEach(function (r) { if (r.axis === refsAxis) { mn = Math.min(mn, r.value); mx = Math.max(mx, r.value); } });
        if (spec.zero_line && refsAxis === 1) { mn = Math.min(mn, 0); mx = Math.max(mx, 0); }
        var fix = refsAxis === 1 ? spec.y : spec.y2;
        if (fix.min != null) mn = fix.min;
        if (fix.max != null) mx = fix.max;
        var span = mx - mn || Math.abs(mx) || 1;
        return [fix.min != null ? mn : mn - 0.06 * span, fix.max != null ? mx : mx + 0.06 * span];
      };
    }
    var axes = [
      { label: spec.x.label, labelSize: 28, size: 44 },
      { label: spec.y.label, labelSize: 28, size: 70, scale: "y" }
    ];
    if (spec.x.ticks.length) {
      axes[0].splits = function () { return spec.x.ticks.map(function (t) { return t[0]; }); };
      axes[0].values = function (u, splits) { return splits.map(function (v) { return tickLabels[v] || ""; }); };
    }
    // A log axis (distr 3): whole decades around the data, as gnuplot draws it.
    function logRange(u, mn, mx) { return uPlot.rangeLog(mn, mx, 10, true); }
    var scales = { x: { time: false }, y: { range: padRange(1) } };
    // Its tick labels: uPlot's own keep three decimals (1e-4 read "0"): decades below 1e-3 or from 1e6
    // on as 1e-4, 1e6, the others (the axis's ends) to three digits.
    function logValues(u, splits) {
      return splits.map(function (v) {
        if (v == null) return "";
        var a = Math.abs(v);
        return a !== 0 && (a < 1e-3 || a >= 1e6) ? v.toExponential(0) : String(Number(v.toPrecision(3)));
      });
    }
    if (spec.x.log) { scales.x.distr = 3; scales.x.log = 10; scales.x.range = function (u, mn, mx) { return [mn, mx]; }; }
    if (spec.x.log && !spec.x.ticks.length) axes[0].values = logValues;
    if (spec.y.log) { scales.y = { distr: 3, log: 10, range: logRange }; axes[1].values = logValues; }
    if (spec.x.min != null && spec.x.max != null) scales.x.range = function () { return [spec.x.min, spec.x.max]; };
    if (spec.y2) {
      axes.push({ label: spec.y2.label, labelSize: 28, size: 70, scale: "y2", side: 1, grid: { show: false } });
      if (spec.y2.log) axes[2].values = logValues;
      scales.y2 = spec.y2.log ? { distr: 3, log: 10, range: logRange } : { range: padRange(2) };
    }
    var u = new uPlot({
      width: width, height: 400, series: series, axes: axes, scales: scales,
      cursor: { drag: { x: true, y: true, uni: 40 }, focus: { prox: 24 } },
      focus: { alpha: 0.35 },
      legend: { live: true },
      plugins: [bandsPlugin(spec), refLinesPlugin(spec), wheelPanPlugin(), { hooks: { draw: [firstDraw] } }]
    }, spec.data, host);
    window.addEventListener("resize", function () { u.setSize({ width: Math.max(480, host.clientWidth), height: 400 }); });
    // uPlot draws in a microtask after construction: record what was drawn at the first draw.
    var rec = { id: spec.id, series: spec.series.length, points: spec.data.slice(1).map(function (col) {
      return col.filter(function (v) { return v != null; }).length; }), drawn: null, ms: null,
      // A series of one value throughout (a link that carries nothing in this case) may lie under
      // another or on the zero line: no pixels of its own is no defect then.
      flat: spec.data.slice(1).map(function (col) {
        var lo = Infinity, hi = -Infinity;
        col.forEach(function (v) { if (v != null) { lo = Math.min(lo, v); hi = Math.max(hi, v); } });
        return !(hi > lo);
      }) };
    status.plots.push(rec);
    function firstDraw(uu) {
      if (rec.drawn !== null) return;
      rec.drawn = drawnPixels(uu, spec);
      rec.ms = Math.round(performance.now() - t0);
      // What a reader sees of the words: the title (inside the page's column) and each axis title
      // (inside the chart), as laid out — a title cut at an edge fails here.
      rec.title = spec.title;
      rec.title_fits = inside(host.parentNode.querySelector("h3"), document.querySelector("main"));
      rec.axes = uu.axes.filter(function (ax) { return ax.show !== false; }).map(axisTitle.bind(null, uu));
      rec.covered = spec.series.map(function (s, k) { return coveredBy(uu, spec, k); });
      status.done = status.plots.length === blocks.length && status.plots.every(function (p) { return p.drawn !== null; });
      writeStatus();
    }
  }

  var blocks = document.querySelectorAll("script[data-figure]");
  for (var i = 0; i < blocks.length; i++) {
    try { makeChart(JSON.parse(blocks[i].textContent)); }
    catch (e) { status.errors.push(String(e && e.stack || e)); }
  }
  if (blocks.length === 0) status.done = true;
  // Tables that reach past the page's column (a wide one scrolls in its .wide box instead).
  var column = document.querySelector("main");
  if (column) {
    var right = column.getBoundingClientRect().right;
    status.tables_outside = Array.prototype.filter.call(document.querySelectorAll("main table"), function (t) {
      if (t.closest(".uplot")) return false;  // a chart's legend
      return (t.closest(".wide") || t).getBoundingClientRect().right > right + 1;
    }).map(function (t) { var c = t.querySelector("caption"); return c ? c.textContent : "table"; });
  }
  writeStatus();
})();
)js";

constexpr const char* kPageStyle = R"css(
body { font: 15px/1.45 "DejaVu Sans", "Segoe UI", Helvetica, Arial, sans-serif; color: #1a1a1a; margin: 0; background: #fafafa; }
main { max-width: 1100px; margin: 0 auto; padding: 24px 32px 48px; background: #fff; }
h1 { font-size: 26px; margin: 0 0 4px; } h2 { font-size: 20px; margin: 32px 0 8px; border-bottom: 2px solid #0072B2; padding-bottom: 3px; }
h3 { font-size: 16px; margin: 22px 0 6px; } .sub { color: #555; margin: 0; } code { font-size: 13px; background: #f2f2f2; padding: 1px 4px; }
table { border-collapse: collapse; margin: 6px 0 4px; font-size: 14px; }
caption { text-align: left; font-weight: bold; padding: 4px 0; } .wide { max-width: 100%; overflow-x: auto; }
th, td { border-bottom: 1px solid #ddd; padding: 4px 12px 4px 0; text-align: right; white-space: nowrap; }
th { border-bottom: 2px solid #888; } th:first-child, td:first-child { text-align: left; }
td.text, table.text th { text-align: left; white-space: normal; } .note { color: #555; font-size: 13px; margin: 2px 0 12px; }
details { margin: 8px 0; } summary { font-weight: bold; cursor: pointer; padding: 4px 0; }
.figure { margin: 18px 0 26px; } .key { font-size: 13px; margin: 2px 0; }
.swatch { display: inline-block; width: 22px; height: 12px; margin-right: 6px; vertical-align: -1px; border: 1px solid #bbb; } .hint { color: #666; font-size: 12px; margin: 2px 0; }
.uplot .u-legend { font-size: 13px; text-align: left; } .uplot .u-legend th { border: 0; font-weight: normal; }
.uplot .u-legend td, .uplot .u-legend th { border: 0; padding: 1px 8px 1px 0; }
nav { font-size: 14px; margin: 10px 0 0; } nav a { margin-right: 14px; color: #0072B2; }
footer { color: #777; font-size: 12px; margin-top: 40px; }
)css";

std::string section_anchor(std::size_t k) { return fmt::format("sec-{}", k + 1); }

void write_table(std::string& o, const Table& t) {
  if (t.collapsed)
    o += fmt::format("<details><summary>{} ({} rows; click to show)</summary>\n", escape_html(t.caption), t.rows.size());
  // A table wider than the page's column (a slip phase's loads of every link) scrolls in its own box.
  o += "<div class=\"wide\">";
  o += t.text_values ? "<table class=\"text\">" : "<table>";
  if (!t.caption.empty() && !t.collapsed) o += "<caption>" + escape_html(t.caption) + "</caption>";
  o += "<thead><tr>";
  for (const auto& h : t.header) o += "<th>" + escape_html(h) + "</th>";
  o += "</tr></thead><tbody>\n";
  for (const auto& row : t.rows) {
    o += "<tr>";
    for (std::size_t c = 0; c < row.size(); ++c) {
      // A cell that is not a number (names, types, reasons) reads better left-aligned.
      const bool text = c > 0 && !row[c].empty() && (t.text_values ||
                        row[c].find_first_not_of("0123456789.eE+-−– ") != std::string::npos);
      o += (text ? "<td class=\"text\">" : "<td>") + escape_html(row[c]) + "</td>";
    }
    o += "</tr>\n";
  }
  o += "</tbody></table></div>\n";
  if (!t.note.empty()) o += "<p class=\"note\">" + escape_html(t.note) + "</p>\n";
  if (t.collapsed) o += "</details>\n";
}

}  // namespace

bool assets_available() { return !assets::kUplotJs.empty(); }
std::string uplot_version() { return std::string(assets::kUplotVersion); }

std::string figure_json(const plot::Figure& fig, const std::string& dom_id) {
  plot::validate(fig);
  for (const auto& s : fig.series)
    for (std::size_t k = 1; k < s.x.size(); ++k)
      if (s.x[k] < s.x[k - 1])
        throw std::invalid_argument(fmt::format("figure '{}': series '{}' has decreasing x; the report's charts need "
                                                "x ascending", fig.id, s.name));
  nlohmann::ordered_json j;
  j["id"] = dom_id.empty() ? fig.id : dom_id;
  j["title"] = fig.title;
  auto axis = [](const plot::Axis& a) {
    nlohmann::ordered_json ax;
    ax["label"] = a.label();
    ax["min"] = a.min ? nlohmann::ordered_json(*a.min) : nlohmann::ordered_json();
    ax["max"] = a.max ? nlohmann::ordered_json(*a.max) : nlohmann::ordered_json();
    nlohmann::ordered_json ticks = nlohmann::ordered_json::array();
    for (const auto& [v, l] : a.ticks) ticks.push_back({v, l});
    ax["ticks"] = ticks;
    ax["log"] = a.log;  // a logarithmic scale (a Bode plot's frequency and |H|)
    return ax;
  };
  j["x"] = axis(fig.x);
  j["y"] = axis(fig.y);
  j["y2"] = fig.y2.used() ? axis(fig.y2) : nlohmann::ordered_json();
  j["zero_line"] = fig.zero_line;
  nlohmann::ordered_json series = nlohmann::ordered_json::array();
  for (std::size_t k = 0; k < fig.series.size(); ++k) {
    const auto& s = fig.series[k];
    series.push_back({{"name", s.name},
                      {"color", s.style == plot::Style::thin ? std::string("#b4b4b4") : plot::series_color(k)},
                      {"style", style_name(s.style)},
                      {"axis", s.y_axis},
                      {"dashed", s.dashed}});
  }
  j["series"] = series;
  nlohmann::ordered_json refs = nlohmann::ordered_json::array();
  for (const auto& r : fig.ref_lines)
    refs.push_back({{"value", r.value},
                    {"label", r.label},
                    {"series", r.series},
                    {"axis", r.y_axis},
                    {"color", r.series >= 0 ? plot::series_color(static_cast<std::size_t>(r.series)) : "#000000"}});
  j["refs"] = refs;
  nlohmann::ordered_json bands = nlohmann::ordered_json::array();
  for (const auto& b : fig.bands) bands.push_back({b.x0, b.x1});
  j["bands"] = bands;
  j["bands_label"] = fig.bands_label;
  j["band_color"] = plot::kBandColor;

  // Columns on one x grid: shared when every series has the same x, else the union with nulls.
  std::vector<double> xs;
  std::vector<std::vector<double>> ys;
  const bool shared = same_x(fig.series);
  j["union"] = !shared;
  if (fig.series.empty()) {
  } else if (shared) {
    xs = fig.series[0].x;
    for (const auto& s : fig.series) ys.push_back(s.y);
  } else {
    for (const auto& s : fig.series) xs.insert(xs.end(), s.x.begin(), s.x.end());
    std::sort(xs.begin(), xs.end());
    xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
    for (const auto& s : fig.series) {
      std::vector<double> y(xs.size(), std::nan(""));
      for (std::size_t k = 0; k < s.x.size(); ++k)
        y[static_cast<std::size_t>(std::lower_bound(xs.begin(), xs.end(), s.x[k]) - xs.begin())] = s.y[k];
      ys.push_back(std::move(y));
    }
  }
  // The numbers by hand: fast for 1e5 points per series and shorter than 17 digits.
  std::string text = j.dump();
  text.pop_back();  // '}'
  std::string data = ",\"data\":[[";
  data.reserve(16 * xs.size() * (ys.size() + 1));
  for (std::size_t k = 0; k < xs.size(); ++k) {
    if (k) data += ',';
    append_number(data, xs[k], 10);
  }
  data += ']';
  for (const auto& y : ys) {
    data += ",[";
    for (std::size_t k = 0; k < y.size(); ++k) {
      if (k) data += ',';
      append_number(data, y[k], 7);
    }
    data += ']';
  }
  return text + data + "]}";
}

std::string to_html(const Document& doc) {
  if (!assets_available())
    throw std::runtime_error("this machdyn was built without the report's charting library (CMake option "
                             "MACHDYN_REPORT=OFF or npm missing at configure time); rebuild with nodejs and npm");
  std::string o;
  o += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  o += "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n";
  o += "<meta name=\"generator\" content=\"machdyn " MACHDYN_VERSION "\">\n";
  o += "<title>" + escape_html(doc.title) + "</title>\n<style>\n";
  o += std::string(assets::kUplotCss) + "\n" + kPageStyle + "</style>\n";
  o += "<script>\n" + std::string(assets::kUplotJs) + "\n</script>\n</head>\n<body>\n<main>\n";
  o += "<h1>" + escape_html(doc.title) + "</h1>\n";
  if (!doc.subtitle.empty()) o += "<p class=\"sub\">" + escape_html(doc.subtitle) + "</p>\n";
  o += "<nav>";
  for (std::size_t k = 0; k < doc.sections.size(); ++k)
    o += fmt::format("<a href=\"#{}\">{}</a>", section_anchor(k), escape_html(doc.sections[k].title));
  o += "</nav>\n";
  std::string data_blocks;
  int figure_no = 0;
  for (std::size_t k = 0; k < doc.sections.size(); ++k) {
    const auto& sec = doc.sections[k];
    o += fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n", section_anchor(k), escape_html(sec.title));
    for (const auto& p : sec.paragraphs) o += "<p>" + escape_html(p) + "</p>\n";
    for (const auto& t : sec.tables) write_table(o, t);
    for (const auto& f : sec.figures) {
      const std::string dom_id = fmt::format("{}-{}", f.id, ++figure_no);  // unique when cases repeat a figure
      o += fmt::format("<div class=\"figure\">\n<h3>{}</h3>\n<div class=\"chart\" id=\"chart-{}\"></div>\n",
                       escape_html(f.title), dom_id);
      if (!f.bands.empty() && !f.bands_label.empty())
        o += fmt::format("<p class=\"key\"><span class=\"swatch\" style=\"background:{}\"></span>{}</p>\n", plot::kBandColor,
                         escape_html(f.bands_label));
      o += "<p class=\"hint\">Drag: zoom (x, y or box) · double-click: reset · wheel: zoom time · Shift+drag: pan · "
           "click a legend entry: hide/show the series · hover: values</p>\n</div>\n";
      data_blocks += fmt::format("<script type=\"application/json\" data-figure=\"{}\">", dom_id) +
                     script_safe(figure_json(f, dom_id)) + "</script>\n";
    }
    o += "</section>\n";
  }
  o += fmt::format("<footer>Made by machdyn {} with uPlot {} (embedded; this file loads nothing from the network).</footer>\n",
                   MACHDYN_VERSION, uplot_version());
  o += "</main>\n<pre id=\"machdyn-status\" hidden>pending</pre>\n";
  o += data_blocks;
  o += "<script>" + std::string(kPageScript) + "</script>\n</body>\n</html>\n";
  return o;
}

}  // namespace machdyn::report
