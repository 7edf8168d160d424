#include "rigid/campaign/task_pool.hpp"

#include <algorithm>

namespace rigid::campaign {

TaskPool::TaskPool(Plan& plan, const std::atomic<bool>& stopping) : plan_(plan), stopping_(stopping) {}

Handout TaskPool::take(long want) {
  Handout h;
  if (!stopping_) {
    while (long(h.tasks.size()) < want) {
      const auto t = plan_.next();
      if (!t) break;
      h.tasks.push_back(*t);
    }
  }
  h.over = h.tasks.empty() && (stopping_ || plan_.finished());
  return h;
}

Handout TaskPool::take_one() {
  std::lock_guard<std::mutex> lock(mutex_);
  return take(1);
}

Handout TaskPool::take_batch(int ranks) {
  std::lock_guard<std::mutex> lock(mutex_);
  const long left = plan_.size() - plan_.done() - plan_.in_flight();
  const long want =
      std::clamp(long(0.25 / std::max(mean_wall_s_, 1e-6)), 1L, std::max(1L, std::min(256L, left / (2L * ranks))));
  return take(want);
}

void TaskPool::complete(std::span<const TaskResult> results) {
  std::lock_guard<std::mutex> lock(mutex_);
  for (const TaskResult& r : results) {
    plan_.complete(r);
    mean_wall_s_ = 0.9 * mean_wall_s_ + 0.1 * r.wall_s;
  }
}

bool TaskPool::over() {
  std::lock_guard<std::mutex> lock(mutex_);
  return stopping_ || plan_.finished();
}

PoolCounts TaskPool::counts() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return {plan_.done(), plan_.remaining(), plan_.in_flight(), plan_.failures(), plan_.size()};
}

long TaskPool::in_flight() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return plan_.in_flight();
}

}  // namespace rigid::campaign
