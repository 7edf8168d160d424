#pragma once
/// The campaign's plan while the master runs: the one place where tasks are handed out (to the
/// master's own simulation thread and to the worker ranks) and finished tasks are marked done.
/// Its mutex guards the plan and the running mean of task wall times; nothing else reaches the
/// plan until the run is over. No I/O, no MPI.
#include <atomic>
#include <cstdint>
#include <mutex>
#include <span>
#include <vector>

#include "rigid/campaign/plan.hpp"

namespace rigid::campaign {

/// Tasks handed out at once, and whether the receiver may stop asking.
struct Handout {
  std::vector<std::int64_t> tasks;
  /// No task now and none will come: every cell is settled, or the campaign is stopping.
  bool over = false;
};

/// Counts for a progress line, taken together under the pool's lock.
struct PoolCounts {
  long done = 0, remaining = 0, in_flight = 0, failures = 0, size = 0;
};

class TaskPool {
 public:
  /// `stopping`: set by whoever stops the campaign (a signal, a failed write); no task is handed
  /// out once it is. The pool reads it without its own lock.
  TaskPool(Plan& plan, const std::atomic<bool>& stopping);
  TaskPool(const TaskPool&) = delete;
  TaskPool& operator=(const TaskPool&) = delete;

  /// One task, for the master's own simulation thread.
  Handout take_one();
  /// A batch for a worker rank of `ranks` in all: about a quarter second of work by the mean
  /// task time so far, fewer near the end so that the last tasks spread over the ranks.
  Handout take_batch(int ranks);
  /// Marks finished tasks done and updates the mean task time.
  void complete(std::span<const TaskResult> results);

  /// True when nothing is left to hand out or wait for: stopping, or every cell settled.
  bool over();
  PoolCounts counts() const;
  long in_flight() const;
  /// Runs `read` on the plan under the pool's lock (e.g. to build the final cube).
  template <typename Read>
  auto read(Read&& read) const {
    std::lock_guard<std::mutex> lock(mutex_);
    return read(static_cast<const Plan&>(plan_));
  }

 private:
  Handout take(long want);  // caller holds mutex_

  mutable std::mutex mutex_;  // guards plan_ and mean_wall_s_
  Plan& plan_;
  double mean_wall_s_ = 0.05;  // running mean task wall time, for batch sizes (unit: s)
  const std::atomic<bool>& stopping_;
};

}  // namespace rigid::campaign
