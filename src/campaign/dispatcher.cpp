#include "rigid/campaign/dispatcher.hpp"

namespace rigid::campaign {

Dispatcher::Dispatcher(TaskPool& pool, Deliver deliver, int ranks)
    : pool_(pool), deliver_(std::move(deliver)), ranks_(ranks), active_workers_(ranks - 1) {}

bool Dispatcher::receive() {
  bool busy = false;
  int rank = 0;
  while (transport_.receive(inbox_, rank)) {
    busy = true;
    deliver_(inbox_);
    waiting_.push_back(rank);
  }
  return busy;
}

void Dispatcher::answer() {
  for (auto it = waiting_.begin(); it != waiting_.end();) {
    const Handout h = pool_.take_batch(ranks_);
    if (!h.tasks.empty()) {
      transport_.send_tasks(*it, h.tasks);
      tasks_sent_ += long(h.tasks.size());
      ++messages_sent_;
      it = waiting_.erase(it);
    } else if (h.over) {
      transport_.send_stop(*it);
      --active_workers_;
      it = waiting_.erase(it);
    } else {
      ++it;
    }
  }
}

}  // namespace rigid::campaign
