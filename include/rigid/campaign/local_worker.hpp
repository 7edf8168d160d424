#pragma once
/// The master rank's own simulations: a thread that takes tasks from the pool one at a time, runs
/// them and hands the results on, so that on 2 ranks both cores simulate. It never calls MPI and
/// holds no lock of its own: its only state is its thread and whether it has ended.
#include <atomic>
#include <cstdint>
#include <functional>
#include <span>
#include <thread>

#include "rigid/campaign/task_pool.hpp"

namespace rigid::campaign {

class LocalWorker {
 public:
  using RunTask = std::function<TaskResult(std::int64_t)>;
  using Deliver = std::function<void(std::span<const TaskResult>)>;

  /// Starts the thread: it runs tasks with `run` and hands each result to `deliver`, until the
  /// pool is over. `idle`: it ends at once (with --noop on several ranks, so that the run
  /// measures what the master alone can hand out).
  LocalWorker(TaskPool& pool, RunTask run, Deliver deliver, bool idle);
  /// Joins the thread.
  ~LocalWorker();
  LocalWorker(const LocalWorker&) = delete;
  LocalWorker& operator=(const LocalWorker&) = delete;

  /// The thread has delivered its last result.
  bool done() const { return done_; }
  /// Waits for the thread to end. Idempotent.
  void join();

 private:
  void loop();

  TaskPool& pool_;
  const RunTask run_;
  const Deliver deliver_;
  const bool idle_;
  std::atomic<bool> done_{false};
  std::thread thread_;  // last: started once the fields above exist
};

}  // namespace rigid::campaign
