#include "machdyn/io/signal_files.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "machdyn/io/input_file.hpp"

namespace machdyn {
namespace {

/// Problems reported per file before the rest are summed up (a file of 10^6 bad rows gives ten).
constexpr int kMaxFileErrors = 10;

std::string_view trim_cell(std::string_view s) {
  while (!s.empty() && (s.front() == ' ' || s.front() == '\t' || s.front() == '\r')) s.remove_prefix(1);
  while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r')) s.remove_suffix(1);
  if (s.size() >= 2 && s.front() == '"' && s.back() == '"') s = s.substr(1, s.size() - 2);
  return s;
}

/// One cell of a row: its text and 1-based character column.
struct Cell {
  std::string_view text;
  int column;
};

std::vector<Cell> split_cells(std::string_view line, char sep) {
  std::vector<Cell> cells;
  std::size_t start = 0;
  for (;;) {
    const std::size_t end = line.find(sep, start);
    const std::string_view raw = line.substr(start, end == std::string_view::npos ? std::string_view::npos : end - start);
    // The column of the cell's first non-blank character.
    std::size_t lead = 0;
    while (lead < raw.size() && (raw[lead] == ' ' || raw[lead] == '\t')) ++lead;
    cells.push_back({trim_cell(raw), static_cast<int>(start + lead) + 1});
    if (end == std::string_view::npos) break;
    start = end + 1;
  }
  return cells;
}

/// A header name with its unit after the last '_' (`torque_kN*m` → torque, kN*m), if that parses.
struct Header {
  std::string name, base, unit;
  int column = 0;
};

Header parse_header(const Cell& c) {
  Header h{std::string(c.text), std::string(c.text), "", c.column};
  const std::size_t u = h.name.rfind('_');
  if (u != std::string::npos && u > 0 && u + 1 < h.name.size()) {
    std::string err;
    auto q = parse_quantity("1 " + h.name.substr(u + 1), &err);
    if (q && q->has_unit) h.base = h.name.substr(0, u), h.unit = h.name.substr(u + 1);
  }
  return h;
}

class FileSignal {
 public:
  FileSignal(SpecNode& sig, std::string what, Diagnostics& diag) : sig_(sig), what_(std::move(what)), diag_(diag) {
    const SpecNode* t = sig.find("type");
    given_at_ = (t ? t->loc : sig.loc).str();
  }

  void resolve() {
    const SpecNode* p = sig_.find("path");
    if (!p || !p->is_scalar() || p->scalar.empty()) {
      diag_.error(p ? p->loc : sig_.loc, fmt::format("{}: a 'file' signal needs 'path: FILE.csv'", what_));
      return;
    }
    std::filesystem::path path(p->scalar);
    const Location at = p->loc;
    if (path.is_relative() && !at.file.empty() && at.file.rfind("--", 0) != 0)
      path = std::filesystem::path(at.file).parent_path() / path;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(path, ec)) {
      diag_.error(at, fmt::format("{}: cannot open the signal file '{}' (looked for {})", what_, p->scalar, path.string()));
      return;
    }
    const auto bytes = std::filesystem::file_size(path, ec);
    if (ec || bytes > kMaxSignalFileBytes) {
      diag_.error(at, fmt::format("{}: the signal file '{}' has {} bytes, more than the limit of {} MiB; resample it",
                                  what_, p->scalar, ec ? 0 : bytes, kMaxSignalFileBytes >> 20));
      return;
    }
    std::string text;
    try {
      text = read_input_file(path.string(), kMaxSignalFileBytes, "signal file");
    } catch (const InputError& e) {  // vanished, unreadable or grown since the checks above
      diag_.error(at, fmt::format("{}: {}", what_, e.diagnostics().front().str()));
      return;
    }
    file_ = std::make_shared<const std::string>(path.string());
    read(text);
  }

 private:
  void error(int line, int col, const std::string& msg) {
    if (++errors_ <= kMaxFileErrors)
      diag_.error(SpecLoc(file_, line, col), fmt::format("{}: {} (the signal is given at {})", what_, msg, given_at_));
  }

  /// The index of the column chosen by spec field `key` (default `fallback`), or -1.
  int choose(const std::vector<Header>& hs, const char* key, int fallback) {
    const SpecNode* n = sig_.find(key);
    if (!n) {
      if (fallback < static_cast<int>(hs.size())) return fallback;
      diag_.error(sig_.loc, fmt::format("{}: the signal file {} has {} column(s); name the '{}' column", what_, *file_,
                                        hs.size(), key));
      return -1;
    }
    for (std::size_t k = 0; k < hs.size(); ++k)
      if (n->is_scalar() && (hs[k].name == n->scalar || hs[k].base == n->scalar)) return static_cast<int>(k);
    std::vector<std::string> names;
    for (const auto& h : hs) names.push_back(h.name);
    diag_.error(n->loc, fmt::format("{}: field '{}': no column '{}' in {}; its columns: {}", what_, key,
                                    n->is_scalar() ? n->scalar : std::string("?"), *file_, fmt::join(names, ", ")));
    return -1;
  }

  void read(const std::string& text) {
    std::vector<Header> hs;
    int line_no = 0;
    char sep = ',';
    std::size_t pos = 0;
    auto next_line = [&](std::string_view* line) {
      if (pos >= text.size()) return false;
      const std::size_t end = text.find('\n', pos);
      *line = std::string_view(text).substr(pos, end == std::string::npos ? std::string::npos : end - pos);
      pos = end == std::string::npos ? text.size() : end + 1;
      ++line_no;
      return true;
    };
    std::string_view line;
    while (next_line(&line)) {
      const std::string_view t = trim_cell(line);
      if (t.empty() || t.front() == '#') continue;
      sep = line.find(',') != std::string_view::npos   ? ','
            : line.find(';') != std::string_view::npos ? ';'
            : line.find('\t') != std::string_view::npos ? '\t'
                                                        : ',';
      for (const Cell& c : split_cells(line, sep)) hs.push_back(parse_header(c));
      break;
    }
    if (hs.empty()) {
      error(std::max(line_no, 1), 1, "the signal file has no header row (names of the columns, e.g. t_s,torque_N*m)");
      return;
    }
    const int header_line = line_no;
    const int it = choose(hs, "time", 0), iv = choose(hs, "column", 1);
    if (it < 0 || iv < 0) return;
    SpecNode points;
    points.kind = SpecNode::Kind::Sequence;
    points.loc = sig_.find("path")->loc;
    double t_last = -HUGE_VAL;
    std::size_t rows = 0;
    while (next_line(&line)) {
      const std::string_view t = trim_cell(line);
      if (t.empty() || t.front() == '#') continue;
      if (++rows > kMaxSignalFileRows) {
        error(line_no, 1, fmt::format("more than {} rows; resample the record", kMaxSignalFileRows));
        return;
      }
      const std::vector<Cell> cells = split_cells(line, sep);
      SpecNode pair;
      pair.kind = SpecNode::Kind::Sequence;
      pair.loc = SpecLoc(file_, line_no, 1);
      bool ok = true;
      double tv = 0.0;
      for (int k : {it, iv}) {
        if (k >= static_cast<int>(cells.size())) {
          error(line_no, static_cast<int>(line.size()) + 1,
                fmt::format("the row has {} cells; column '{}' is number {}", cells.size(), hs[static_cast<std::size_t>(k)].name, k + 1));
          ok = false;
          break;
        }
        const Cell& c = cells[static_cast<std::size_t>(k)];
        const std::string s(c.text);
        char* end = nullptr;
        errno = 0;
        const double v = std::strtod(s.c_str(), &end);
        if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE || !std::isfinite(v)) {
          error(line_no, c.column, fmt::format("column '{}': expected a number, got '{}'", hs[static_cast<std::size_t>(k)].name, s));
          ok = false;
          continue;
        }
        if (k == it) tv = v;
        SpecNode cell;
        cell.kind = SpecNode::Kind::Scalar;
        cell.loc = cell.key_loc = SpecLoc(file_, line_no, c.column);
        cell.scalar = s;
        pair.items.push_back(std::move(cell));
      }
      if (!ok) continue;
      if (tv < t_last) {
        error(line_no, cells[static_cast<std::size_t>(it)].column,
              fmt::format("column '{}': time {} is earlier than the row before ({}); times must not decrease",
                          hs[static_cast<std::size_t>(it)].name, tv, t_last));
        continue;
      }
      t_last = tv;
      if (it > iv) std::swap(pair.items[0], pair.items[1]);  // [t, value]
      points.items.push_back(std::move(pair));
    }
    if (errors_ > kMaxFileErrors)
      diag_.error(SpecLoc(file_, line_no, 1), fmt::format("{}: {} more problems in {}", what_, errors_ - kMaxFileErrors, *file_));
    if (rows == 0) error(header_line, 1, "the signal file has a header but no rows of data");
    if (errors_ > 0) return;
    // The table that replaces the file: its units from the spec, else from the header.
    auto unit_from = [&](const char* key, const Header& h) {
      if (sig_.find(key) || h.unit.empty()) return;
      SpecNode u;
      u.kind = SpecNode::Kind::Scalar;
      u.loc = u.key_loc = SpecLoc(file_, header_line, h.column);
      u.scalar = h.unit;
      sig_.set(key, std::move(u));
    };
    unit_from("time_unit", hs[static_cast<std::size_t>(it)]);
    unit_from("unit", hs[static_cast<std::size_t>(iv)]);
    sig_.find("type")->scalar = "table";
    sig_.erase("time");
    sig_.erase("column");
    sig_.erase("path");
    sig_.set("points", std::move(points));
  }

  SpecNode& sig_;
  std::string what_;
  Diagnostics& diag_;
  std::string given_at_;
  std::shared_ptr<const std::string> file_;
  int errors_ = 0;
};

void walk(SpecNode& n, const std::string& what, Diagnostics& diag, int depth) {
  if (depth > 64) return;  // the YAML reader bounds nesting already
  if (n.is_map()) {
    const SpecNode* t = n.find("type");
    if (t && t->is_scalar() && t->scalar == "file") {
      FileSignal(n, what, diag).resolve();
      return;
    }
    for (auto& f : n.fields) walk(f.second, what, diag, depth + 1);
  } else if (n.is_seq()) {
    for (auto& item : n.items)
      if (!item.is_scalar()) walk(item, what, diag, depth + 1);
  }
}

void resolve_sections(SpecNode& root, Diagnostics& diag) {
  static const std::pair<const char*, const char*> kSections[] = {{"loads", "load"}, {"contacts", "contact"}, {"brakes", "brake"},
                                                                 {"clutches", "clutch"}, {"drives", "drive"}};
  for (const auto& [section, kind] : kSections) {
    SpecNode* sec = root.find(section);
    if (!sec || !sec->is_map()) continue;
    for (auto& [name, el] : sec->fields) walk(el, fmt::format("{} '{}'", kind, name), diag, 0);
  }
}

}  // namespace

void resolve_signal_files(SpecNode& root, Diagnostics& diag) {
  if (!root.is_map()) return;
  resolve_sections(root, diag);
  if (SpecNode* cases = root.find("cases"); cases && cases->is_map())
    for (auto& [name, c] : cases->fields)
      if (c.is_map()) resolve_sections(c, diag);
}

}  // namespace machdyn
