#include "machdyn/sweep/runner.hpp"

#include "machdyn/io/folder_lock.hpp"
#include "machdyn/io/output_file.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <memory>
#include <mutex>
#include <thread>
#include <fcntl.h>
#include <unistd.h>
#if defined(__GLIBC__)
#include <malloc.h>
#endif
#include <fmt/format.h>

#include "machdyn/common/diagnostics.hpp"
#include "machdyn/sweep/journal.hpp"
#include "machdyn/sweep/mpi.hpp"
#include "sweep/mpi_detail.hpp"

namespace machdyn {
namespace {

using Clock = std::chrono::steady_clock;

struct FinishedRow {
  long index = 0;
  std::string row;
  bool input_error = false;  ///< the run failed on its input (execute_run)
};

/// Worker threads computing the rows of `work` (run indices), next run from a shared counter.
class ThreadPool {
 public:
  ThreadPool(const SweepPlan& plan, const std::vector<SummaryColumns>& columns, std::vector<long> work, int threads,
             const std::atomic<bool>* stop)
      : plan_(plan), columns_(columns), names_(summary_column_names(plan, columns)), work_(std::move(work)), stop_(stop),
        running_(threads) {
    for (int t = 0; t < threads; ++t) threads_.emplace_back([this] { work_loop(); });
  }
  ~ThreadPool() {
    abandon();  // an exception on the writing thread (a full disk): no new run, join at once
    for (auto& t : threads_) t.join();
  }
  /// No worker starts another run.
  void abandon() { abandoned_ = true; }
  ThreadPool(const ThreadPool&) = delete;
  ThreadPool& operator=(const ThreadPool&) = delete;

  /// Waits up to `timeout` for rows, then moves out what finished. `idle` is set when every worker
  /// has exited and nothing is left to take.
  std::vector<FinishedRow> take(std::chrono::milliseconds timeout, bool& idle) {
    std::unique_lock lock(mutex_);
    cv_.wait_for(lock, timeout, [this] { return !queue_.empty() || running_ == 0; });
    std::vector<FinishedRow> out;
    out.swap(queue_);
    idle = running_ == 0 && out.empty();
    return out;
  }

 private:
  void work_loop() {
    for (;;) {
      if ((stop_ && stop_->load()) || abandoned_) break;
      const size_t i = next_.fetch_add(1);
      if (i >= work_.size()) break;
      const long idx = work_[i];
      bool input_error = false;
      std::string row = execute_run(plan_, plan_.runs[static_cast<size_t>(idx)], columns_, names_, &input_error);
      {
        std::lock_guard lock(mutex_);
        queue_.push_back({idx, std::move(row), input_error});
      }
      cv_.notify_one();
    }
    {
      std::lock_guard lock(mutex_);
      --running_;
    }
    cv_.notify_one();
  }

  const SweepPlan& plan_;
  const std::vector<SummaryColumns>& columns_;
  const std::vector<std::vector<std::string>> names_;  // the table's summary columns, per group
  const std::vector<long> work_;
  const std::atomic<bool>* stop_;
  std::atomic<size_t> next_{0};
  std::atomic<bool> abandoned_{false};
  std::mutex mutex_;
  std::condition_variable cv_;
  std::vector<FinishedRow> queue_;
  int running_;
  std::vector<std::thread> threads_;
};

/// Leading run index of a row.
long index_of(const std::string& row) { return std::stol(row.substr(0, row.find(','))); }

/// Writes the table through a temporary file and a rename (io/output_file.hpp): a full disk is an
/// OutputError naming the table, never a truncated table.
void write_table(const std::filesystem::path& path, const std::string& header, const std::vector<std::string>& rows) {
  write_file_atomic(path, [&](const ChunkSink& sink) {
    std::string buf = header + "\n";
    for (const auto& r : rows) {
      buf += r;
      buf += '\n';
      if (buf.size() > (1u << 20)) {
        sink(buf);
        buf.clear();
      }
    }
    sink(buf);
  });
}

}  // namespace

int default_sweep_jobs() {
  const unsigned hw = std::max(1u, std::thread::hardware_concurrency());
  return std::max(1, static_cast<int>(hw) / MpiSession::local_size());
}

SweepOutcome run_sweep(const SweepPlan& plan, const SweepOptions& options) {
  namespace fs = std::filesystem;
  const auto columns = options.columns.empty() ? standard_summary_columns() : options.columns;
  const std::string header = sweep_header(plan, columns);
  const int rank = MpiSession::rank(), ranks = MpiSession::size();
  const long total = static_cast<long>(plan.runs.size());

  SweepOutcome out;
  out.total = total;
  out.ranks = ranks;
  out.threads = options.jobs > 0 ? options.jobs : default_sweep_jobs();
  out.table_path = (fs::path(options.out_dir) / "sweep.csv").string();
  out.journal_path = (fs::path(options.out_dir) / "sweep.journal").string();

#if defined(__GLIBC__)
  // Per-worker memory reuse: freed run memory stays in the worker's arena (see SweepOptions).
  if (options.retain_memory) {
    ::mallopt(M_TRIM_THRESHOLD, 256 << 20);
    ::mallopt(M_TOP_PAD, 16 << 20);
  }
#endif

  // Rank 0 opens the journal; every rank learns which runs are finished.
  std::unique_ptr<SweepJournal> journal;
  std::unique_ptr<FolderLock> lock;  // one sweep at a time in out_dir (io/folder_lock.hpp)
  std::vector<char> finished(static_cast<size_t>(total), 0);
  int ready = 1;
  if (rank == 0) {
    try {
      lock = std::make_unique<FolderLock>(options.out_dir.empty() ? fs::path(".") : fs::path(options.out_dir));
      journal = std::make_unique<SweepJournal>(out.journal_path, plan.fingerprint, total, header, options.resume);
    } catch (...) {
      ready = 0;
      if (ranks > 1) mpi_detail::broadcast(ready);
      throw;
    }
    out.from_journal = journal->finished();
    out.dropped = journal->dropped();
    for (long i = 0; i < total; ++i) finished[static_cast<size_t>(i)] = journal->rows()[static_cast<size_t>(i)].empty() ? 0 : 1;
  }
  if (ranks > 1) {
    mpi_detail::broadcast(ready);
    if (!ready) return out;  // rank 0 reports why
    mpi_detail::broadcast(finished);
  }

  // This rank's share of the pending runs.
  std::vector<long> work;
  long pending = 0;
  for (long i = 0; i < total; ++i) {
    if (finished[static_cast<size_t>(i)]) continue;
    if (pending++ % ranks == rank) work.push_back(i);
  }

  const auto start = Clock::now();
  auto last_progress = start - std::chrono::seconds(1);
  auto report = [&](bool force) {
    if (!options.progress || rank != 0) return;
    const auto now = Clock::now();
    if (!force && now - last_progress < std::chrono::milliseconds(100)) return;
    last_progress = now;
    options.progress({journal->finished(), total, journal->finished() - out.from_journal,
                      std::chrono::duration<double>(now - start).count()});
  };

  {
    ThreadPool pool(plan, columns, std::move(work), out.threads, options.stop);
    int ranks_done = 1;  // rank 0 itself, once its pool is idle
    bool pool_idle = false;
    std::string incoming, text;
    while (true) {
      auto rows = pool.take(std::chrono::milliseconds(50), pool_idle);
      if (rank == 0) {
        for (auto& r : rows) {
          journal->append(r.index, r.row);
          if (r.input_error) {
            ++out.input_errors;
            if (out.first_input_error < 0 || r.index < out.first_input_error) out.first_input_error = r.index;
          }
        }
        out.computed += static_cast<long>(rows.size());
        out.computed_here += static_cast<long>(rows.size());
        if (ranks > 1) {
          // Rows from the other ranks: journal records, validated like the file.
          incoming.clear();
          ranks_done += mpi_detail::poll_rows(incoming);
          size_t pos = 0;
          while (pos < incoming.size()) {
            const auto nl = incoming.find('\n', pos);
            const auto end = nl == std::string::npos ? incoming.size() : nl + 1;
            if (parse_journal_record(std::string_view(incoming).substr(pos, end - pos), text)) {
              journal->append(index_of(text), text);
              ++out.computed;
            }
            pos = end;
          }
        }
        journal->sync(options.sync_interval_s);
        report(false);
        const bool stopped = options.stop && options.stop->load();
        if (pool_idle && (ranks_done == ranks || stopped)) break;
      } else {
        std::string records;
        for (const auto& r : rows) records += journal_record(r.row);
        out.computed += static_cast<long>(rows.size());
        if (!records.empty()) mpi_detail::send_rows(records);
        if (pool_idle) {
          mpi_detail::send_rows(std::string());
          break;
        }
      }
    }
  }
  out.wall_s = std::chrono::duration<double>(Clock::now() - start).count();
  if (rank != 0) return out;

  journal->sync();
  report(true);
  if (journal->finished() < total) return out;  // stopped: the journal holds what finished

  write_table(out.table_path, header, journal->rows());
  for (const auto& r : journal->rows()) (r.ends_with(",ok,") ? out.ok : out.errors)++;
  if (out.first_input_error >= 0)
    out.first_input_message = split_csv_line(journal->rows()[static_cast<size_t>(out.first_input_error)]).back();
  out.complete = true;
  return out;
}

}  // namespace machdyn
