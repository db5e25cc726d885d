#include "machdyn/io/folder_lock.hpp"

#include <cerrno>
#include <chrono>
#include <thread>
#include <cstring>
#include <fstream>
#include <iterator>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>
#include <fmt/format.h>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/io/output_file.hpp"

namespace machdyn {
namespace {

/// This process's command line, for the lock file: "machdyn sweep m.yaml --vary ..." (Linux
/// /proc; elsewhere just the pid is written).
std::string command_line() {
  std::ifstream in("/proc/self/cmdline", std::ios::binary);
  std::string s((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  while (!s.empty() && s.back() == '\0') s.pop_back();
  for (char& c : s)
    if (c == '\0' || c == '\n' || c == '\r') c = ' ';
  return s.size() > 300 ? s.substr(0, 300) + "..." : s;
}

/// What the holder wrote: "pid 1234: machdyn sweep ..." (first line, at most 400 bytes).
std::string holder_text(int fd) {
  char buf[400];
  const ssize_t n = ::pread(fd, buf, sizeof buf, 0);
  if (n <= 0) return "another process (it has not written its pid yet)";
  std::string s(buf, static_cast<size_t>(n));
  s = s.substr(0, s.find('\n'));
  return s.empty() ? std::string("another process") : s;
}

}  // namespace

FolderLock::FolderLock(const std::filesystem::path& dir, double wait_s) : path_(dir / kFolderLockName) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw OutputError(fmt::format("cannot create the folder {}: {}", dir.string(), ec.message()));
  // O_NOFOLLOW: a link planted as the lock file is not followed (its target would be truncated).
  fd_ = ::open(path_.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0644);
  if (fd_ < 0)
    throw OutputError(fmt::format("cannot lock the output folder {}: cannot open {}: {}", dir.string(), path_.string(),
                                  std::strerror(errno)));
  struct stat st {};
  if (::fstat(fd_, &st) != 0 || !S_ISREG(st.st_mode) || st.st_nlink != 1) {
    ::close(fd_);
    fd_ = -1;
    throw OutputError(fmt::format("cannot lock the output folder {}: {} is not a plain file of its own; remove it",
                                  dir.string(), path_.string()));
  }
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::duration<double>(wait_s);
  while (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    if (errno == EINTR) continue;
    const int err = errno;
    if (err == EWOULDBLOCK && std::chrono::steady_clock::now() < give_up) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      continue;
    }
    const std::string holder = err == EWOULDBLOCK ? holder_text(fd_) : std::string();
    ::close(fd_);
    fd_ = -1;
    if (err != EWOULDBLOCK)
      throw OutputError(fmt::format("cannot lock the output folder {}: {}", dir.string(), std::strerror(err)));
    throw InputError(Location{dir.string(), 0, 0},
                     fmt::format("the output folder is in use by another machdyn run ({}){}; wait until it has "
                                 "finished or choose another output folder (-o)",
                                 holder, wait_s > 0 ? fmt::format(", still after {:g} s", wait_s) : ""));
  }
  // Ours now: say who holds it (for the next one's message).
  const std::string who = fmt::format("pid {}: {}\n", ::getpid(), command_line());
  if (::ftruncate(fd_, 0) == 0) (void)!::pwrite(fd_, who.data(), who.size(), 0);
  stale_removed_ = remove_stale_temp_files(dir);
}

FolderLock::~FolderLock() {
  if (fd_ >= 0) ::close(fd_);  // releases the lock
}

}  // namespace machdyn
