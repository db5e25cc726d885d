#pragma once
/// @file
/// The append-only journal of a sweep (`DIR/sweep.journal`): the only file machdyn writes in
/// pieces. Finished rows are appended as they come, in completion order, so an interrupted sweep
/// (Ctrl-C, kill, power loss) keeps every row that reached the disk.
///
/// Format, one record a line:
///   #machdyn-sweep-journal v1 <fingerprint> <runs> <header>|<checksum>
///   <table row>|<checksum>
/// The checksum is 16 hex digits of FNV-1a 64 over the text before the last `|`. A line is valid
/// when it ends in a newline, its checksum matches and its run index is < runs. A torn last line
/// (a kill during write()) or a block of garbage after a power loss fails this test and is dropped;
/// a run index seen twice keeps its first row (both are identical: a run's row depends only on the
/// plan). Durability: rows are written with one write() each and fdatasync()ed at most every
/// `sync_interval_s` and at the end, so a power loss loses at most that much work, which --resume
/// then recomputes.

#include <string>
#include <string_view>
#include <vector>

namespace machdyn {

/// `text|checksum\n`.
std::string journal_record(std::string_view text);

/// The text of a valid record (without the newline), or false.
bool parse_journal_record(std::string_view line_with_newline, std::string& text);

class SweepJournal {
 public:
  /// Opens `path` for a sweep with this fingerprint, `runs` runs and table `header`.
  /// resume = false: creates the file; throws InputError when it already holds rows (so a finished
  /// or interrupted sweep is never overwritten by mistake). resume = true: reads the valid rows,
  /// then rewrites the file (atomically, through a rename) with exactly those, so new rows never
  /// follow a torn line; throws InputError when the journal belongs to another sweep. A missing
  /// journal with resume = true starts afresh.
  SweepJournal(std::string path, const std::string& fingerprint, long runs, const std::string& header, bool resume);
  ~SweepJournal();
  SweepJournal(const SweepJournal&) = delete;
  SweepJournal& operator=(const SweepJournal&) = delete;

  /// The row of every finished run, "" for runs not finished; indexed by run.
  [[nodiscard]] const std::vector<std::string>& rows() const { return rows_; }
  [[nodiscard]] long finished() const { return finished_; }
  /// Invalid lines dropped when reading (a torn tail after a kill).
  [[nodiscard]] long dropped() const { return dropped_; }

  /// Appends the row of run `index` (its first CSV field) unless that run is already in. Throws
  /// std::runtime_error when the write fails (disk full).
  void append(long index, const std::string& row);
  /// fdatasync() if the last one is older than `interval_s` (0: always).
  void sync(double interval_s = 0.0);

 private:
  std::string path_;
  int fd_ = -1;
  std::vector<std::string> rows_;
  long finished_ = 0;
  long dropped_ = 0;
  double last_sync_ = 0.0;
};

}  // namespace machdyn
