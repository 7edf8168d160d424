#include "rigid/io/output_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "rigid/core/error.hpp"

namespace rigid::io {

void refuse_output_over_inputs(const std::string& output, const std::vector<std::string>& inputs) {
  InputFiles files;
  files.add(inputs);
  files.refuse_as_output(output);
}

void InputFiles::add(const std::string& path) {
  struct stat in {};
  if (::stat(path.c_str(), &in) != 0) return;
  for (const Identity& f : files_) {
    if (f.device == in.st_dev && f.inode == in.st_ino) return;
  }
  files_.push_back({static_cast<unsigned long long>(in.st_dev), static_cast<unsigned long long>(in.st_ino), path});
}

void InputFiles::add(const std::vector<std::string>& paths) {
  for (const std::string& p : paths) add(p);
}

void InputFiles::refuse_as_output(const std::string& output) const {
  struct stat out {};
  if (::stat(output.c_str(), &out) != 0) return;
  if (S_ISDIR(out.st_mode)) throw InputError(output, 0, "is a directory; an output file cannot replace it");
  for (const Identity& f : files_) {
    if (f.device == static_cast<unsigned long long>(out.st_dev) &&
        f.inode == static_cast<unsigned long long>(out.st_ino))
      throw InputError(output, 0, "is the input " + f.path + "; choose another output file");
  }
}

void InputFiles::refuse_folder(const std::string& folder) const {
  std::error_code ec;
  const std::filesystem::path dir = std::filesystem::weakly_canonical(folder, ec);
  if (ec) return;
  for (const Identity& f : files_) {
    const std::filesystem::path in = std::filesystem::weakly_canonical(f.path, ec);
    if (ec) continue;
    const auto [d, i] = std::mismatch(dir.begin(), dir.end(), in.begin(), in.end());
    if (d == dir.end())
      throw InputError(folder, 0,
                       "holds the input " + f.path + ", and the command writes into it; choose another --out");
  }
}

namespace {

/// Removes the temporary unless released: every way out of write_output_file but success.
class TemporaryFile {
 public:
  explicit TemporaryFile(std::string path) : path_(std::move(path)) {}
  ~TemporaryFile() {
    if (!path_.empty()) ::unlink(path_.c_str());
  }
  TemporaryFile(const TemporaryFile&) = delete;
  TemporaryFile& operator=(const TemporaryFile&) = delete;
  const std::string& path() const { return path_; }
  void release() { path_.clear(); }

 private:
  std::string path_;
};

}  // namespace

void write_output_file(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::filesystem::path target(path);
  const std::string dir = target.has_parent_path() ? target.parent_path().string() : ".";
  std::string name = dir + "/." + target.filename().string() + ".XXXXXX";
  const int fd = ::mkstemp(name.data());
  if (fd < 0) throw InputError(path, 0, std::string("cannot create the output: ") + std::strerror(errno));
  TemporaryFile temp(name);
  // an ordinary file's permissions, not mkstemp's private 0600
  const mode_t mask = ::umask(0);
  ::umask(mask);
  const bool mode_set = ::fchmod(fd, 0666 & ~mask) == 0;
  ::close(fd);
  if (!mode_set) throw InputError(path, 0, std::string("cannot create the output: ") + std::strerror(errno));
  {
    std::ofstream out(temp.path(), std::ios::binary | std::ios::trunc);
    if (!out) throw InputError(path, 0, "cannot create the output");
    write(out);
    out.close();
    if (!out) throw InputError(path, 0, "cannot write the output (disk full?)");
  }
  const int sync_fd = ::open(temp.path().c_str(), O_RDONLY | O_CLOEXEC);
  const bool synced = sync_fd >= 0 && ::fsync(sync_fd) == 0;
  if (sync_fd >= 0) ::close(sync_fd);
  if (!synced) throw InputError(path, 0, std::string("cannot write the output: ") + std::strerror(errno));
  if (::rename(temp.path().c_str(), path.c_str()) != 0)
    throw InputError(path, 0, std::string("cannot write the output: ") + std::strerror(errno));
  temp.release();
}

}  // namespace rigid::io
