#pragma once
/// @file
/// Reading the files a run is made of (model files, gear specs, signal CSV files) with bounds, and
/// remembering them so that no result is ever written over one (io/output_file.hpp).
///
/// A model is a text file of a few kB; a hostile path (/dev/zero, a FIFO, a 10 GB file) must end
/// in a located error, not in memory growing without bound or a read that never returns. So:
///   - the path is opened without blocking (a FIFO with no writer would block the open) and must be
///     a regular file: a folder, FIFO, socket or device is an InputError;
///   - a file larger than the limit is an InputError (read at most limit + 1 bytes, so a file that
///     grows while it is read is caught too);
///   - each file read is noted (device and inode) as an input of this process.

#include <cstdint>
#include <string>

namespace machdyn {

/// Model files and gear specs: 16 MiB (the largest example is 30 kB; the YAML reader also bounds
/// values and depth, io/yaml_reader.hpp).
inline constexpr std::uint64_t kMaxModelFileBytes = std::uint64_t{16} << 20;

/// The bytes of the regular file `path`, at most `limit_bytes` of them. `what` names the file in
/// messages ("model file", "signal file"). Throws InputError located at `path` when the file cannot
/// be opened, is not a regular file, or is larger than the limit. Notes the file as an input.
std::string read_input_file(const std::string& path, std::uint64_t limit_bytes, const char* what);

/// Remembers the file `path` refers to (after symbolic links) as an input of this process; a path
/// that does not exist is ignored. read_input_file does this itself.
void note_input_file(const std::string& path);

/// The input file (as it was named when read) that `path` refers to, following symbolic links and
/// hard links alike (same device and inode), or "" when it is none.
std::string input_file_at(const std::string& path);

}  // namespace machdyn
