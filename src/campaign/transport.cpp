#include "rigid/campaign/transport.hpp"

#include <mpi.h>

#include <cstdlib>

namespace rigid::campaign {
namespace {

constexpr int kTagResults = 1;  // worker -> master: results of the last batch, and a request
constexpr int kTagTasks = 2;    // master -> worker: task ids
constexpr int kTagStop = 3;     // master -> worker: no more work

}  // namespace

bool MasterTransport::receive(std::vector<TaskResult>& results, int& rank) {
  int flag = 0;
  MPI_Status status;
  if (MPI_Iprobe(MPI_ANY_SOURCE, kTagResults, MPI_COMM_WORLD, &flag, &status) != MPI_SUCCESS || !flag) return false;
  int bytes = 0;
  MPI_Get_count(&status, MPI_BYTE, &bytes);
  results.resize(std::size_t(bytes) / sizeof(TaskResult));
  MPI_Recv(results.data(), bytes, MPI_BYTE, status.MPI_SOURCE, kTagResults, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
  rank = status.MPI_SOURCE;
  return true;
}

void MasterTransport::send_tasks(int rank, const std::vector<std::int64_t>& tasks) {
  MPI_Send(tasks.data(), int(tasks.size()), MPI_INT64_T, rank, kTagTasks, MPI_COMM_WORLD);
}

void MasterTransport::send_stop(int rank) { MPI_Send(nullptr, 0, MPI_INT64_T, rank, kTagStop, MPI_COMM_WORLD); }

void worker_loop(const std::function<TaskResult(std::int64_t)>& run_task) {
  std::vector<TaskResult> results;
  std::vector<std::int64_t> ids;
  for (;;) {
    MPI_Send(results.data(), int(results.size() * sizeof(TaskResult)), MPI_BYTE, 0, kTagResults, MPI_COMM_WORLD);
    results.clear();
    MPI_Status status;
    MPI_Probe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
    int count = 0;
    MPI_Get_count(&status, MPI_INT64_T, &count);
    ids.resize(std::size_t(count));
    MPI_Recv(ids.data(), count, MPI_INT64_T, 0, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (status.MPI_TAG == kTagStop) break;
    for (std::int64_t t : ids) results.push_back(run_task(t));
  }
}

void abort_all_ranks(int status) {
  MPI_Abort(MPI_COMM_WORLD, status);
  std::abort();  // MPI_Abort does not return; this tells the compiler so
}

}  // namespace rigid::campaign
