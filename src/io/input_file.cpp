#include "machdyn/io/input_file.hpp"

#include <cerrno>
#include <cstring>
#include <map>
#include <mutex>
#include <utility>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>
#include <fmt/format.h>

#include "machdyn/common/diagnostics.hpp"
#include "io/file_kind.hpp"

namespace machdyn {
namespace {

/// The inputs of this process: (device, inode) → the path it was read as. Threads of a sweep and
/// of the Python module read files concurrently.
struct InputRegistry {
  std::mutex mutex;
  std::map<std::pair<dev_t, ino_t>, std::string> files;
};

InputRegistry& registry() {
  static InputRegistry r;
  return r;
}

void note(const struct stat& st, const std::string& path) {
  auto& r = registry();
  std::lock_guard lock(r.mutex);
  r.files.try_emplace({st.st_dev, st.st_ino}, path);
}

/// Closes the descriptor on every path out.
struct Fd {
  int fd;
  ~Fd() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

std::string read_input_file(const std::string& path, std::uint64_t limit_bytes, const char* what) {
  const Location at{path, 0, 0};
  // O_NONBLOCK: opening a FIFO without a writer returns at once (and is refused below).
  const Fd f{::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC)};
  if (f.fd < 0) throw InputError(at, fmt::format("cannot open the {}: {}", what, std::strerror(errno)));
  struct stat st {};
  if (::fstat(f.fd, &st) != 0) throw InputError(at, fmt::format("cannot read the {}: {}", what, std::strerror(errno)));
  if (!S_ISREG(st.st_mode))
    throw InputError(at, fmt::format("the {} is {}; expected a regular file", what, detail::file_kind(st.st_mode)));
  const auto too_large = [&](std::uint64_t bytes, bool at_least) {
    return InputError(at, fmt::format("the {} has {}{} bytes, more than the limit of {} MiB; expected a {} of a "
                                      "sensible size",
                                      what, at_least ? "more than " : "", bytes, limit_bytes >> 20, what));
  };
  if (static_cast<std::uint64_t>(st.st_size) > limit_bytes) throw too_large(static_cast<std::uint64_t>(st.st_size), false);
  const int flags = ::fcntl(f.fd, F_GETFL);
  if (flags >= 0) (void)::fcntl(f.fd, F_SETFL, flags & ~O_NONBLOCK);
  std::string text;
  text.resize(static_cast<size_t>(st.st_size));
  size_t have = 0;
  for (;;) {
    if (have == text.size()) {
      // The file may have grown since fstat: read on, up to one byte past the limit.
      if (have > limit_bytes) throw too_large(limit_bytes, true);
      text.resize(std::min<std::uint64_t>(limit_bytes + 1, have + 65536));
    }
    const ssize_t n = ::read(f.fd, text.data() + have, text.size() - have);
    if (n < 0) {
      if (errno == EINTR) continue;
      throw InputError(at, fmt::format("cannot read the {}: {}", what, std::strerror(errno)));
    }
    if (n == 0) break;
    have += static_cast<size_t>(n);
  }
  text.resize(have);
  note(st, path);
  return text;
}

void note_input_file(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) == 0) note(st, path);
}

std::string input_file_at(const std::string& path) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) return {};
  auto& r = registry();
  std::lock_guard lock(r.mutex);
  const auto it = r.files.find({st.st_dev, st.st_ino});
  return it == r.files.end() ? std::string() : it->second;
}

}  // namespace machdyn
