#include "machdyn/sweep/journal.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <chrono>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <fcntl.h>
#include <unistd.h>
#include <fmt/format.h>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/output_file.hpp"
#include "sweep/fnv1a.hpp"

namespace machdyn {
namespace {

double now_s() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void write_all(int fd, std::string_view data, const std::string& path) {
  while (!data.empty()) {
    const ssize_t w = ::write(fd, data.data(), data.size());
    if (w < 0) {
      if (errno == EINTR) continue;
      throw std::runtime_error(fmt::format("cannot write {}: {}", path, std::strerror(errno)));
    }
    data.remove_prefix(static_cast<size_t>(w));
  }
}

void fsync_dir(const std::filesystem::path& dir) {
  const int d = ::open(dir.empty() ? "." : dir.c_str(), O_RDONLY | O_DIRECTORY);
  if (d >= 0) {
    (void)::fsync(d);
    ::close(d);
  }
}

/// Leading run index of a row, or -1.
long row_index(std::string_view row) {
  long v = 0;
  size_t i = 0;
  for (; i < row.size() && row[i] >= '0' && row[i] <= '9' && i < 12; ++i) v = v * 10 + (row[i] - '0');
  if (i == 0 || i >= row.size() || row[i] != ',') return -1;
  return v;
}

std::string header_text(const std::string& fingerprint, long runs, const std::string& header) {
  return fmt::format("#machdyn-sweep-journal v1 {} {} {}", fingerprint, runs, header);
}

}  // namespace

std::string journal_record(std::string_view text) {
  return fmt::format("{}|{:016x}\n", text, detail::fnv1a(text));
}

bool parse_journal_record(std::string_view line, std::string& text) {
  if (line.size() < 18 || line.back() != '\n') return false;
  line.remove_suffix(1);
  const auto bar = line.size() - 17;
  if (line[bar] != '|') return false;
  const auto body = line.substr(0, bar);
  if (fmt::format("{:016x}", detail::fnv1a(body)) != line.substr(bar + 1)) return false;
  text.assign(body);
  return true;
}

SweepJournal::SweepJournal(std::string path, const std::string& fingerprint, long runs, const std::string& header,
                           bool resume)
    : path_(std::move(path)), rows_(static_cast<size_t>(runs)) {
  namespace fs = std::filesystem;
  const fs::path p(path_);
  if (p.has_parent_path()) fs::create_directories(p.parent_path());
  const Location where{path_, 0, 0};
  const std::string expected_header = header_text(fingerprint, runs, header);

  // A FIFO there would block the read below, a device or a link be replaced by the rewrite.
  if (std::error_code ec; fs::exists(fs::symlink_status(p, ec)) && !fs::is_regular_file(fs::symlink_status(p, ec)))
    throw InputError(where, "this is not a regular file (a link, FIFO, device or folder), so not a sweep journal; "
                            "remove it or choose another -o");
  if (fs::exists(p)) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string all = ss.str();
    size_t pos = 0;
    bool first = true;
    std::string text;
    long rows_seen = 0;
    bool foreign = false;  // the journal of another sweep (header with another fingerprint)
    while (pos < all.size()) {
      const auto nl = all.find('\n', pos);
      const auto end = nl == std::string::npos ? all.size() : nl + 1;
      const std::string_view line(all.data() + pos, end - pos);
      pos = end;
      const bool valid = parse_journal_record(line, text);
      if (first) {
        first = false;
        if (valid && text == expected_header) continue;
        if (!valid || !text.starts_with("#machdyn-sweep-journal"))
          throw InputError(where, "this is not a machdyn sweep journal; remove it or choose another -o");
        if (resume)
          throw InputError(where, "this journal belongs to another sweep (other model file, --set, --vary, "
                                  "method, samples or seed); remove it or choose another -o");
        foreign = true;  // counted below: a fresh sweep may replace a journal without rows, nothing else
        continue;
      }
      ++rows_seen;
      const long idx = valid ? row_index(text) : -1;
      if (idx < 0 || idx >= runs) {
        ++dropped_;
        continue;
      }
      auto& slot = rows_[static_cast<size_t>(idx)];
      if (slot.empty()) {
        slot = text;
        ++finished_;
      }
    }
    // A finished or interrupted run is never discarded: the same plan needs --resume, another plan
    // another folder (its table, sweep.csv beside the journal, would be replaced too).
    if (!resume && rows_seen > 0 && foreign)
      throw InputError(where, fmt::format("holds {} finished run(s) of another sweep (other model file, --set, "
                                          "--vary, method, samples or seed); choose another -o, or remove the "
                                          "file to replace that sweep",
                                          rows_seen));
    if (!resume && rows_seen > 0)
      throw InputError(where, fmt::format("holds {} finished run(s) of an earlier sweep; add --resume to continue it, "
                                          "or remove the file to start again",
                                          rows_seen));
    if (!resume) {
      std::fill(rows_.begin(), rows_.end(), std::string());
      finished_ = dropped_ = 0;
    }
  }

  // (Re)write the journal atomically: the header and the valid rows in run order.
  std::string content = journal_record(expected_header);
  for (const auto& r : rows_)
    if (!r.empty()) content += journal_record(r);
  write_file_atomic(p, content);  // a full disk leaves the earlier journal as it was
  fsync_dir(p.parent_path());
  fd_ = ::open(p.c_str(), O_WRONLY | O_APPEND | O_CLOEXEC);
  if (fd_ < 0) throw std::runtime_error(fmt::format("cannot open {}: {}", path_, std::strerror(errno)));
  last_sync_ = now_s();
}

SweepJournal::~SweepJournal() {
  if (fd_ >= 0) {
    (void)::fdatasync(fd_);
    ::close(fd_);
  }
}

void SweepJournal::append(long index, const std::string& row) {
  auto& slot = rows_.at(static_cast<size_t>(index));
  if (!slot.empty()) return;
  write_all(fd_, journal_record(row), path_);  // one write(): a kill leaves at most this line torn
  slot = row;
  ++finished_;
}

void SweepJournal::sync(double interval_s) {
  const double t = now_s();
  if (interval_s > 0.0 && t - last_sync_ < interval_s) return;
  (void)::fdatasync(fd_);
  last_sync_ = t;
}

}  // namespace machdyn
