#include "machdyn/io/output_file.hpp"

#include <algorithm>
#include <cerrno>
#include <iterator>
#include <cmath>
#include <cstring>
#include <csignal>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <fmt/format.h>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/input_file.hpp"
#include "io/file_kind.hpp"

namespace machdyn {
namespace {

/// An open temporary file that is removed unless committed (renamed over its target).
class TempFile {
 public:
  TempFile(std::filesystem::path target) : target_(std::move(target)) {
    tmp_ = target_;
    tmp_ += fmt::format(".tmp.{}", ::getpid());
    // A file of that name is a leftover of an earlier process with this pid: never write through it
    // (O_EXCL | O_NOFOLLOW: not through a link planted there either).
    (void)::unlink(tmp_.c_str());
    fd_ = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0666);  // 0666 & ~umask, as any new file
    if (fd_ < 0) fail(errno);
  }
  ~TempFile() {
    if (fd_ >= 0) ::close(fd_);
    if (!committed_) {
      std::error_code ec;
      std::filesystem::remove(tmp_, ec);
    }
  }
  TempFile(const TempFile&) = delete;
  TempFile& operator=(const TempFile&) = delete;

  void write(std::string_view d) {
    while (!d.empty()) {
      const ssize_t w = ::write(fd_, d.data(), d.size());
      if (w < 0) {
        if (errno == EINTR) continue;
        fail(errno);
      }
      d.remove_prefix(static_cast<size_t>(w));
    }
  }

  /// Flushes to the disk (a delayed ENOSPC shows here on some file systems), then renames.
  void commit() {
    if (::fdatasync(fd_) != 0 && errno != EINVAL && errno != EROFS) fail(errno);
    const int fd = fd_;
    fd_ = -1;
    if (::close(fd) != 0) fail(errno);
    std::error_code ec;
    std::filesystem::rename(tmp_, target_, ec);
    if (ec) throw OutputError(fmt::format("cannot write {}: {}", target_.string(), ec.message()));
    committed_ = true;
  }

 private:
  [[noreturn]] void fail(int err) const {
    std::string hint;
    if (err == ENOSPC || err == EDQUOT) hint = "; free space or choose another output folder with -o";
    if (err == EFBIG) hint = " (the file-size limit, ulimit -f, was reached)";
    throw OutputError(fmt::format("cannot write {}: {}{}; nothing was written there", target_.string(),
                                  std::strerror(err), hint));
  }

  std::filesystem::path target_, tmp_;
  int fd_ = -1;
  bool committed_ = false;
};

void make_parent(const std::filesystem::path& path) {
  if (!path.has_parent_path()) return;
  std::error_code ec;
  std::filesystem::create_directories(path.parent_path(), ec);
  if (ec) throw OutputError(fmt::format("cannot create the folder {}: {}", path.parent_path().string(), ec.message()));
}

/// The endings of the files machdyn writes (results, journal, figures, report, drawings).
constexpr const char* kResultExtensions[] = {".csv", ".json", ".journal", ".svg", ".png", ".html", ".dxf"};

/// True for the name of a temporary file of write_file_atomic whose process is gone: RESULT.tmp.PID
/// with RESULT of a kind machdyn writes (so that no other file of the folder is ever touched).
bool stale_temp_name(const std::string& name) {
  const auto dot = name.rfind(".tmp.");
  if (dot == std::string::npos || dot == 0 || dot + 5 >= name.size()) return false;
  const std::string result = name.substr(0, dot);
  const bool ours = std::any_of(std::begin(kResultExtensions), std::end(kResultExtensions),
                                [&](const char* ext) { return result.ends_with(ext); });
  if (!ours) return false;
  const std::string digits = name.substr(dot + 5);
  if (digits.size() > 9 || digits.find_first_not_of("0123456789") != std::string::npos) return false;
  const long pid = std::stol(digits);
  return pid > 0 && pid != ::getpid() && ::kill(static_cast<pid_t>(pid), 0) != 0 && errno == ESRCH;
}

}  // namespace

std::string output_target_problem(const std::filesystem::path& path) {
  struct stat st {};
  if (::lstat(path.c_str(), &st) != 0) return {};  // a new path (or one the write will report)
  if (!S_ISREG(st.st_mode)) {
    std::string to;
    if (S_ISLNK(st.st_mode)) {
      std::error_code ec;
      const auto target = std::filesystem::read_symlink(path, ec);
      if (!ec) to = fmt::format(" to {}", target.string());
      if (const std::string input = input_file_at(path.string()); !input.empty())
        to += fmt::format(", the input file {} of this run", input);
    }
    return fmt::format("it is {}{}; machdyn writes only to a new path or over a regular file", detail::file_kind(st.st_mode), to);
  }
  if (const std::string input = input_file_at(path.string()); !input.empty())
    return fmt::format("it is the input file {} of this run{}; choose another output", input,
                       input == path.string() ? "" : " (the same file under another name)");
  return {};
}

std::size_t remove_stale_temp_files(const std::filesystem::path& dir) {
  std::size_t removed = 0;
  std::error_code ec;
  for (std::filesystem::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    if (!stale_temp_name(it->path().filename().string())) continue;
    std::error_code rm;
    if (it->is_regular_file(rm) && std::filesystem::remove(it->path(), rm)) ++removed;
  }
  return removed;
}

void write_file_atomic(const std::filesystem::path& path, std::string_view content) {
  write_file_atomic(path, [&](const ChunkSink& sink) { sink(content); });
}

void write_file_atomic(const std::filesystem::path& path, const std::function<void(const ChunkSink&)>& produce) {
  if (const std::string problem = output_target_problem(path); !problem.empty())
    throw OutputError(fmt::format("refusing to write {}: {}", path.string(), problem));
  make_parent(path);
  TempFile f(path);
  produce([&](std::string_view d) { f.write(d); });
  f.commit();
}

OutputEstimate estimate_timeseries(const Model& m) {
  OutputEstimate e;
  const auto& s = m.simulation;
  const double dt = s.dt_out > 0.0 ? s.dt_out : s.t_end / 1000.0;
  // Output times k·dt_out for k = 0 … n, plus t_end itself when it is not on the grid.
  const double n = std::floor(s.t_end / dt * (1.0 + 1e-12));
  const double rows = n + 1.0 + (n * dt < s.t_end * (1.0 - 1e-12) ? 1.0 : 0.0);
  e.rows = rows < 1e18 ? static_cast<std::uint64_t>(rows) : std::uint64_t{1'000'000'000'000'000'000ULL};
  e.columns = chain_column_names(m).size() + 3 * m.contacts.size();
  for (const auto& l : m.links) e.columns += l.has_gap ? 1 : 0;
  // Saturate instead of overflowing: anything near these numbers is refused anyway.
  const double bytes = static_cast<double>(e.rows) * static_cast<double>(e.columns) * 24.0;
  e.csv_bytes = bytes < 1e18 ? static_cast<std::uint64_t>(bytes) : std::uint64_t{1'000'000'000'000'000'000ULL};
  e.memory_bytes = e.csv_bytes / 3;
  return e;
}

std::string byte_size_text(std::uint64_t bytes) {
  const double b = static_cast<double>(bytes);
  if (b >= 1e12) return fmt::format("{:.3g} TB", b / 1e12);
  if (b >= 1e9) return fmt::format("{:.3g} GB", b / 1e9);
  if (b >= 1e6) return fmt::format("{:.3g} MB", b / 1e6);
  if (b >= 1e3) return fmt::format("{:.3g} kB", b / 1e3);
  return fmt::format("{} B", bytes);
}

void check_output_size(const Model& m, std::uint64_t limit_bytes, const std::string& insist_hint) {
  const OutputEstimate e = estimate_timeseries(m);
  if (e.csv_bytes <= limit_bytes) return;
  const auto& s = m.simulation;
  const double factor = static_cast<double>(e.csv_bytes) / static_cast<double>(limit_bytes);
  throw InputError(Location{m.source, 0, 0},
                   fmt::format("the time series would be about {} ({} rows × {} columns: t_end = {:g} s in steps of "
                               "dt_out = {:g} s), more than the limit of {}; raise simulation.dt_out (to at least "
                               "{:.3g} s, e.g. --set simulation.dt_out={:.3g}) or pass {} to write it anyway",
                               byte_size_text(e.csv_bytes), e.rows, e.columns, s.t_end, s.dt_out,
                               byte_size_text(limit_bytes), s.dt_out * factor, s.dt_out * factor * 1.01, insist_hint));
}

}  // namespace machdyn
