#pragma once
/// The MPI messages of a campaign. Workers send the results of their last batch, which is also a
/// request for more; the master answers with task ids or a stop. Only rank 0 is the master.
#include <cstdint>
#include <functional>
#include <vector>

#include "rigid/campaign/plan.hpp"

namespace rigid::campaign {

/// The master's end.
class MasterTransport {
 public:
  /// Takes one pending worker message, if any: its results and the rank now waiting for tasks.
  bool receive(std::vector<TaskResult>& results, int& rank);
  void send_tasks(int rank, const std::vector<std::int64_t>& tasks);
  /// No more work for this rank: its worker_loop returns.
  void send_stop(int rank);
};

/// A worker rank's loop: asks for tasks, runs each with `run_task`, returns when told to stop.
void worker_loop(const std::function<TaskResult(std::int64_t)>& run_task);

/// Ends every rank of the campaign with this exit status, now.
[[noreturn]] void abort_all_ranks(int status);

}  // namespace rigid::campaign
