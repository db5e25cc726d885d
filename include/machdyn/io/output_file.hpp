#pragma once
/// @file
/// Writing result files so that none is ever left half-written, and refusing outputs too large to
/// be meant. Every result file of machdyn goes through write_file_atomic: the bytes go to
/// `PATH.tmp.PID` in the same folder, are flushed to the disk (fdatasync), and only then renamed
/// over PATH. On any failure (disk full, file-size limit, no permission) the temporary file is
/// removed, an earlier PATH stays as it was, and an OutputError names the file and the cause.
/// (The CLI ignores SIGXFSZ, so past `ulimit -f` the write fails with EFBIG instead of the process
/// being killed with its temporary file left behind.)

#include <cstdint>
#include <filesystem>
#include <functional>
#include <stdexcept>
#include <string>
#include <string_view>

#include "machdyn/model/model.hpp"

namespace machdyn {

/// A result file could not be written (e.g. "cannot write out/m/timeseries.csv: No space left on
/// device"). The CLI exits with code 1 (not an input error, not a numerical failure).
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Receives the file's bytes in pieces, in order.
using ChunkSink = std::function<void(std::string_view)>;

/// Why `path` must not be written, or "" when it may: a result goes only to a new path or over a
/// regular file that is not an input of this process (io/input_file.hpp: the model, a gear spec, a
/// signal file, also under another name or through a link). A device, FIFO, folder or symbolic link
/// there is refused: the rename would replace the node itself (as root, `-o /dev/null` would
/// replace /dev/null).
std::string output_target_problem(const std::filesystem::path& path);

/// Removes the temporary files `NAME.tmp.PID` in `dir` whose process PID is gone (a SIGKILLed
/// run's leftovers; a live process's are kept), NAME ending as machdyn's results do (.csv, .json,
/// .journal, .svg, .png, .html, .dxf). Returns how many were removed. Called by whoever
/// holds the folder's lock (io/folder_lock.hpp).
std::size_t remove_stale_temp_files(const std::filesystem::path& dir);

/// Writes `content` to `path` atomically (see the file comment); creates parent folders.
/// Throws OutputError, also when output_target_problem(path) says the path must not be written.
void write_file_atomic(const std::filesystem::path& path, std::string_view content);

/// The same for content produced in pieces by `produce(sink)` (a large CSV is never held whole in
/// memory). An exception from `produce` also removes the temporary file and is rethrown.
void write_file_atomic(const std::filesystem::path& path, const std::function<void(const ChunkSink&)>& produce);

/// What the time series of a run will hold, known before the run: rows = the output times k·dt_out
/// up to t_end (and t_end itself), columns of the smooth chain plus those of contacts and gaps (machine outputs add a few
/// more, so this is a lower bound), bytes = rows · columns · 24 (a `%.17g` number and its comma).
struct OutputEstimate {
  std::uint64_t rows = 0;
  std::uint64_t columns = 0;
  std::uint64_t csv_bytes = 0;     ///< size of timeseries.csv
  std::uint64_t memory_bytes = 0;  ///< rows · columns · 8, the columns held during the run
};
OutputEstimate estimate_timeseries(const Model& m);

/// Default limit of check_output_size: 1 GB of CSV (about 4·10⁷ numbers, 330 MB of memory).
inline constexpr std::uint64_t kDefaultOutputLimitBytes = 1'000'000'000ULL;

/// Throws InputError (located at the model file, exit 2) when the time series would exceed
/// `limit_bytes`, saying the estimated rows, columns and size, and how to get less (a larger
/// `simulation.dt_out`) or to insist (`insist_hint`, e.g. "--large-output").
void check_output_size(const Model& m, std::uint64_t limit_bytes, const std::string& insist_hint);

/// "5.1 GB", "320 MB", "12 kB", "512 B" (decimal units).
std::string byte_size_text(std::uint64_t bytes);

}  // namespace machdyn
