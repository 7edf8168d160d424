#pragma once
/// The master's end of the MPI protocol (campaign/transport): takes in the worker ranks' results,
/// which are also requests for more, and answers each with a batch from the pool or a stop.
/// Used by the master's main thread alone (the only thread that calls MPI), so it has no lock.
#include <functional>
#include <span>
#include <vector>

#include "rigid/campaign/task_pool.hpp"
#include "rigid/campaign/transport.hpp"

namespace rigid::campaign {

class Dispatcher {
 public:
  using Deliver = std::function<void(std::span<const TaskResult>)>;

  /// `ranks`: the campaign's, the master included (ranks - 1 workers); `deliver` takes each
  /// worker message's results.
  Dispatcher(TaskPool& pool, Deliver deliver, int ranks);

  /// Takes every pending worker message (its results delivered, its rank queued for an answer);
  /// true when something arrived.
  bool receive();
  /// Hands out work, or stops workers that will get none; a worker with nothing to do now keeps
  /// waiting (tasks in flight may unblock more).
  void answer();
  /// Worker ranks not yet told to stop.
  int active_workers() const { return active_workers_; }
  long tasks_sent() const { return tasks_sent_; }
  long messages_sent() const { return messages_sent_; }

 private:
  TaskPool& pool_;
  const Deliver deliver_;
  const int ranks_;
  MasterTransport transport_;
  std::vector<TaskResult> inbox_;  // one worker message
  std::vector<int> waiting_;       // worker ranks whose request is unanswered
  int active_workers_;
  long tasks_sent_ = 0, messages_sent_ = 0;
};

}  // namespace rigid::campaign
