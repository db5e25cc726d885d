#pragma once
/// @file
/// One run at a time per output folder. Two sweeps (or two simulations) writing into one folder
/// would mix their files: one journal with the rows of both, a table of one beside the summary of
/// the other. A run that writes several files into a folder holds an advisory lock (flock) on
/// `FOLDER/.machdyn.lock` (a sweep for its whole run, simulate/modes/energy while they write); a
/// second run into the same folder fails with an error naming the holder (its pid and command
/// line, which the holder writes into the file). The kernel releases the lock when the holder ends, however it ends (SIGKILL too), so a
/// lock is never stale; the file itself stays (removing it would race with a new holder).
///
/// Whoever takes the lock also removes the temporary files `NAME.tmp.PID` of dead processes in the
/// folder (io/output_file.hpp), the leftovers of a run killed while writing.

#include <filesystem>
#include <string>

namespace machdyn {

class FolderLock {
 public:
  /// Creates `dir` if needed and locks it, waiting up to `wait_s` seconds for another holder to
  /// finish (0: not at all). Throws InputError (located at `dir`, naming the holder) when another
  /// process still holds the lock, OutputError when the folder or the lock file cannot be made.
  explicit FolderLock(const std::filesystem::path& dir, double wait_s = 0.0);
  ~FolderLock();
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

  /// The lock file, FOLDER/.machdyn.lock.
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }
  /// Temporary files of dead processes removed when the lock was taken.
  [[nodiscard]] std::size_t stale_removed() const { return stale_removed_; }

 private:
  std::filesystem::path path_;
  int fd_ = -1;
  std::size_t stale_removed_ = 0;
};

/// How long a command that holds its folder only while it writes its results (simulate, modes,
/// energy: seconds) waits for another such writer before it gives up: two of them into one folder
/// then write one after the other, each a complete set. A sweep holds its folder for its whole run
/// and does not wait: a second sweep fails at once.
inline constexpr double kFolderLockWriteWait_s = 30.0;

/// The name of the lock file in a locked folder.
inline constexpr const char* kFolderLockName = ".machdyn.lock";

}  // namespace machdyn
