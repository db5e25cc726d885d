#pragma once
// What a path is when it is not a regular file, in words for messages (private to src/io): the input
// files machdyn reads and the result files it writes refuse anything else with these words.
#include <sys/stat.h>

namespace machdyn::detail {

/// The kind of file of `mode` (st_mode of stat, or of lstat, which alone sees symbolic links).
inline const char* file_kind(mode_t mode) {
  if (S_ISDIR(mode)) return "a folder";
  if (S_ISLNK(mode)) return "a symbolic link";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  return "not a regular file";
}

}  // namespace machdyn::detail
