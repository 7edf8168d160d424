#include "rigid/campaign/local_worker.hpp"

#include <chrono>

namespace rigid::campaign {

LocalWorker::LocalWorker(TaskPool& pool, RunTask run, Deliver deliver, bool idle)
    : pool_(pool), run_(std::move(run)), deliver_(std::move(deliver)), idle_(idle), thread_([this] { loop(); }) {}

LocalWorker::~LocalWorker() { join(); }

void LocalWorker::join() {
  if (thread_.joinable()) thread_.join();
}

void LocalWorker::loop() {
  while (!idle_) {
    const Handout h = pool_.take_one();
    if (h.over) break;
    if (h.tasks.empty()) {  // tasks in flight elsewhere may unblock more
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    const TaskResult r = run_(h.tasks.front());
    deliver_(std::span<const TaskResult>(&r, 1));
  }
  done_ = true;
}

}  // namespace rigid::campaign
