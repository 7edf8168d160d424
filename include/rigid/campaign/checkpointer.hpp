#pragma once
/// A campaign's checkpoints: every result journalled as it arrives, the journal fsynced on
/// request (the checkpoint proper), and the cube rewritten from a shadow plan (a compaction that
/// lets the journal start over). The policy and its reasons are at the top of
/// src/campaign/checkpointer.cpp. No MPI: the master wires it to its threads.
///
/// Locks: `mutex_` guards the journal, the results since the last snapshot, the failure and the
/// statistics; every public method takes it for short spells only. `rewrite_mutex_` makes
/// rewrites one at a time and guards the shadow plan; a rewrite takes `mutex_` while holding it,
/// never the other way round.
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <mutex>
#include <span>
#include <string>
#include <vector>

#include "rigid/campaign/journal.hpp"
#include "rigid/campaign/plan.hpp"
#include "rigid/io/cube.hpp"

namespace rigid::campaign {

/// What checkpointing has cost so far (the verbose summary, and the rewrite schedule).
struct CheckpointStats {
  long syncs = 0, rewrites = 0;
  double last_rewrite_s = 0;   ///< duration of the last rewrite (unit: s)
  double longest_stall_s = 0;  ///< the longest time one rewrite held the journal's lock (unit: s)
  std::chrono::steady_clock::time_point last_rewrite_start;
};

class Checkpointer {
 public:
  /// The cube of a plan's state (the campaign's make_cube).
  using CubeOf = std::function<io::Cube(const Plan&)>;

  /// Starts OUTPUT.journal for `key` (the campaign's combined input digest) holding `carried`
  /// (the old journal's results, not yet in a cube). `restored`: the plan as restored from disk,
  /// copied as the shadow plan. A failure to start the journal is recorded like any other (see
  /// failure()). `stop` is set at the first failure, so that the campaign stops dispatching.
  Checkpointer(std::string output, std::string key, const Plan& restored, CubeOf cube_of,
               const std::vector<TaskResult>& carried, std::atomic<bool>& stop);
  Checkpointer(const Checkpointer&) = delete;
  Checkpointer& operator=(const Checkpointer&) = delete;

  /// Journals finished results (buffered; handed to the kernel by flush()). After a failed cube
  /// write the journal still takes them: they are kept for the resume.
  void record(std::span<const TaskResult> results);
  /// Hands the journalled results to the kernel: they survive a kill of the process.
  void flush();
  /// The checkpoint proper: the journal's records to disk (the fsync runs without the lock).
  void sync();
  /// The compaction: writes the cube of every result up to a snapshot, then restarts the journal
  /// with what arrived after it. False after a failure (recorded in failure()); nothing is
  /// written once one has happened. One at a time: a second caller waits.
  bool rewrite();
  /// Whether a periodic rewrite is due: the amortization rule (time since the last rewrite
  /// started >= max(interval, K x its duration)) or the journal's size bound.
  bool rewrite_due(double interval_s) const;

  /// The first failed write as printed ("" while none): dispatch stops, and the last good cube
  /// and the journal stay as they were (both are only ever replaced by a rename).
  std::string failure() const;
  CheckpointStats stats() const;

 private:
  void fail(const std::string& message);         // caller holds mutex_
  void journal_failed(const std::exception& e);  // caller holds mutex_
  void flush_locked();                           // caller holds mutex_
  // the rewrite's steps; each takes mutex_ for short spells and adds that time to `stall_s`
  bool take_snapshot(double& stall_s);
  bool write_shadow_cube();
  bool restart_journal(double& stall_s);

  const std::string output_;
  const CubeOf cube_of_;
  std::atomic<bool>& stop_;

  mutable std::mutex mutex_;  // guards the fields below, up to rewrite_mutex_
  std::unique_ptr<Journal> journal_;
  bool journal_ok_ = false;
  std::string failure_;
  std::vector<TaskResult> since_snapshot_;  // results not in the cube being written
  CheckpointStats stats_;
  std::uint64_t journal_limit_bytes_ = 0;  // the journal's size that forces a rewrite

  std::mutex rewrite_mutex_;  // held for a whole rewrite; guards shadow_
  Plan shadow_;               // the plan as of the last snapshot, without tasks in flight
};

}  // namespace rigid::campaign
