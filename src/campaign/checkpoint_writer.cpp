#include "rigid/campaign/checkpoint_writer.hpp"

namespace rigid::campaign {

CheckpointWriter::CheckpointWriter(Checkpointer& checkpointer)
    : checkpointer_(checkpointer), thread_([this] { loop(); }) {}

CheckpointWriter::~CheckpointWriter() { stop(); }

void CheckpointWriter::loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return sync_wanted_ || rewrite_wanted_ || quit_; });
    if (quit_) return;  // what is pending is left to the final rewrite
    if (sync_wanted_) {
      sync_wanted_ = false;
      lock.unlock();
      checkpointer_.sync();
      lock.lock();
    } else {
      rewrite_wanted_ = false;
      rewrite_running_ = true;
      lock.unlock();
      checkpointer_.rewrite();
      lock.lock();
      rewrite_running_ = false;
    }
  }
}

void CheckpointWriter::request(bool sync, bool rewrite) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    sync_wanted_ = sync_wanted_ || sync;
    rewrite_wanted_ = rewrite_wanted_ || rewrite;
  }
  wake_.notify_one();
}

bool CheckpointWriter::rewrite_pending() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return rewrite_wanted_ || rewrite_running_;
}

void CheckpointWriter::stop() {
  if (!thread_.joinable()) return;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    quit_ = true;
  }
  wake_.notify_one();
  thread_.join();
}

}  // namespace rigid::campaign
