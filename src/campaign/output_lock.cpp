#include "rigid/campaign/output_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>

#include "rigid/campaign/log.hpp"
#include "rigid/core/error.hpp"

namespace rigid::campaign {

OutputLock::OutputLock(const std::string& output, const std::string& other_output) : path_(output + ".lock") {
  for (;;) {
    const int fd = ::open(path_.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
    if (fd < 0) throw InputError(path_, 0, std::string("cannot create the lock file: ") + std::strerror(errno));
    if (::flock(fd, LOCK_EX | LOCK_NB) != 0) {
      const int err = errno;
      ::close(fd);
      if (err == EWOULDBLOCK) {
        throw InputError(path_, 0,
                         "another campaign is running on " + output + " (it holds this lock); wait for it to end" +
                             (other_output.empty() ? "" : " or use another " + other_output));
      }
      if (err == EINTR) continue;
      log_warning(path_ + ": no file locking here (" + std::strerror(err) +
                  "); nothing stops a second campaign on this output");
      return;
    }
    // the holder before us may have removed the file after we opened it: then our lock is on a
    // file nobody else can see, and the path must be locked again
    struct stat on_disk {
    }, ours{};
    if (::stat(path_.c_str(), &on_disk) == 0 && ::fstat(fd, &ours) == 0 && on_disk.st_ino == ours.st_ino &&
        on_disk.st_dev == ours.st_dev) {
      fd_ = fd;
      return;
    }
    ::close(fd);
  }
}

OutputLock::~OutputLock() {
  if (fd_ < 0) return;
  ::unlink(path_.c_str());  // while still held, so no one locks the file being removed
  ::close(fd_);
}

}  // namespace rigid::campaign
