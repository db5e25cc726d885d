#pragma once
/// @file
/// Runs a sweep plan on all cores (a thread pool) and, under mpirun, on every rank; journals the
/// rows as they finish (sweep/journal.hpp) and writes the table in run order at the end.
///
/// Files in `out_dir`:
///   sweep.journal  append-only, rows in completion order (what --resume reads)
///   sweep.csv      the table (sweep/table.hpp), rows in run order; written through a temporary
///                  file and a rename once every run has finished, so it is never partial
///   .machdyn.lock  held (flock) by rank 0 for the whole run: a second sweep into the same folder
///                  fails at once, naming the holder (io/folder_lock.hpp)
///
/// Parallelism: workers take the next pending run from a shared counter and compute it alone
/// (compile + simulate: no shared mutable state). Under MPI the pending runs are dealt out
/// cyclically (pending run p to rank p mod size); every rank runs its share on its own threads and
/// sends rows to rank 0, which alone writes the journal and the table. A row depends only on the
/// plan and its run, so the table is byte-identical for any number of threads and ranks.

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "machdyn/sweep/plan.hpp"
#include "machdyn/sweep/table.hpp"

namespace machdyn {

struct SweepProgress {
  long done = 0;          ///< finished runs, from the journal included
  long total = 0;         ///< runs of the plan
  long done_now = 0;      ///< finished in this session
  double elapsed_s = 0.0; ///< since this session started running
};

struct SweepOptions {
  std::string out_dir;
  int jobs = 0;             ///< worker threads per process; 0: all cores (divided among the ranks on a node)
  bool resume = false;      ///< continue the journal in out_dir
  double sync_interval_s = 1.0;  ///< fdatasync of the journal at most this often (0: every row)
  /// Set (e.g. by a SIGINT handler) to stop: no new run starts, finished rows are journaled and
  /// synced, no table is written. May be null.
  const std::atomic<bool>* stop = nullptr;
  /// Called on the writing thread (rank 0) after rows were journaled, at most every 0.1 s, and once
  /// at the end.
  std::function<void(const SweepProgress&)> progress;
  /// Summary columns; empty: standard_summary_columns().
  std::vector<SummaryColumns> columns;
  /// Keep the memory a run frees for the next run of the same worker instead of giving it back to
  /// the kernel (glibc: M_TRIM_THRESHOLD 256 MB and M_TOP_PAD 16 MB, set once for the process and
  /// not restored). A run allocates its solver and its time series afresh (~0.5 MB for the travel
  /// start-up); without this glibc returns them at every free and the next run faults them in again:
  /// 97 000 page faults and ~20 % more CPU per 1000 runs (docs/benchmarks-issue7.md). The cost: the
  /// process holds on to its peak heap until it ends.
  bool retain_memory = true;
};

struct SweepOutcome {
  bool complete = false;    ///< every run finished and the table was written (rank 0)
  long total = 0;
  long from_journal = 0;    ///< rows found by --resume
  long dropped = 0;         ///< invalid journal lines dropped by --resume
  long computed = 0;        ///< runs finished in this session (all ranks)
  long ok = 0, errors = 0;  ///< status counts over the whole table (when complete)
  /// Runs computed by this process's threads in this session (rank 0: without the other ranks'),
  /// how many of them failed on their input (execute_run), and the lowest run index among those
  /// (-1: none). A sweep with no `ok` row whose every run computed here failed on input is an
  /// input error of the whole sweep: `machdyn sweep` exits 2 with that run's message.
  long computed_here = 0, input_errors = 0, first_input_error = -1;
  std::string first_input_message;  ///< the message of run first_input_error (when complete)
  int threads = 0;          ///< per process
  int ranks = 1;
  double wall_s = 0.0;
  std::string table_path, journal_path;
};

/// Worker threads per process when SweepOptions::jobs is 0: the cores of this machine divided by
/// the MPI ranks on it (at least 1).
int default_sweep_jobs();

/// Runs the plan. Throws InputError when the journal cannot be used (exists without resume,
/// belongs to another sweep) or another run holds the folder's lock; std::runtime_error when a file cannot be written. Failing runs are
/// rows with status `error`, not exceptions. On ranks other than 0 the outcome has only
/// `computed` (that rank's) and `threads`.
SweepOutcome run_sweep(const SweepPlan& plan, const SweepOptions& options);

}  // namespace machdyn
