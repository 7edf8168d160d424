#pragma once
/// One campaign per output: rank 0 holds an exclusive flock on OUTPUT.lock for the whole run, so a
/// second campaign on the same output is refused instead of interleaving checkpoints with the first.
#include <string>

namespace rigid::campaign {

class OutputLock {
 public:
  /// Takes the lock on `output` + ".lock" without waiting. Throws rigid::InputError naming the
  /// lock file when another process holds it. Where the file system has no flock (some NFS or
  /// Lustre mounts) it warns on stderr and goes on unlocked. `other_output`: how the caller's
  /// command line writes elsewhere ("--out"), offered in the error; empty: not offered.
  OutputLock(const std::string& output, const std::string& other_output);
  /// Removes the lock file and releases the lock.
  ~OutputLock();
  OutputLock(const OutputLock&) = delete;
  OutputLock& operator=(const OutputLock&) = delete;

 private:
  std::string path_;
  int fd_ = -1;
};

}  // namespace rigid::campaign
