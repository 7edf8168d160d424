#pragma once
/// The thread that does a campaign's file work (journal syncs and cube rewrites, one at a time,
/// as asked), so that the master's dispatch never waits for the disk. Its mutex guards only the
/// requests; the work itself is the Checkpointer's, called without that mutex.
#include <condition_variable>
#include <mutex>
#include <thread>

#include "rigid/campaign/checkpointer.hpp"

namespace rigid::campaign {

class CheckpointWriter {
 public:
  /// Starts the thread.
  explicit CheckpointWriter(Checkpointer& checkpointer);
  /// Stops the thread (see stop()).
  ~CheckpointWriter();
  CheckpointWriter(const CheckpointWriter&) = delete;
  CheckpointWriter& operator=(const CheckpointWriter&) = delete;

  /// Asks for a journal sync and/or a rewrite; a sync asked for is done first.
  void request(bool sync, bool rewrite);
  /// A rewrite asked for and not yet done, or running.
  bool rewrite_pending() const;
  /// Ends the thread after what it is doing; what is still asked for is left to the caller's
  /// final rewrite. Idempotent.
  void stop();

 private:
  void loop();

  Checkpointer& checkpointer_;
  mutable std::mutex mutex_;  // guards the four flags
  std::condition_variable wake_;
  bool sync_wanted_ = false, rewrite_wanted_ = false, rewrite_running_ = false, quit_ = false;
  std::thread thread_;  // last: started once the fields above exist
};

}  // namespace rigid::campaign
