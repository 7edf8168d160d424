#include "staging.hpp"

#include <unistd.h>

#include <algorithm>
#include <system_error>

#include "rigid/core/error.hpp"

namespace rigid::scan {

namespace fs = std::filesystem;

Staging::Staging(const fs::path& dir, const std::string& name) : dir_(dir.empty() ? fs::path(".") : dir) {
  std::error_code ec;
  for (fs::path level = dir_; !level.empty() && !fs::exists(level, ec); level = level.parent_path()) {
    created_.push_back(level);
    if (level == level.parent_path()) break;
  }
  fs::create_directories(dir_, ec);
  if (ec) {
    remove_created();
    throw InputError("", 0, "--out: cannot create directory " + dir_.string() + ": " + ec.message());
  }
  path_ = dir_ / ("." + name + ".import-" + std::to_string(::getpid()));
  fs::remove_all(path_, ec);
  if (!fs::create_directory(path_, ec) || ec) {
    remove_created();
    throw InputError(
        "", 0,
        "--out: cannot write in directory " + dir_.string() + ": " + (ec ? ec.message() : std::string("it exists")));
  }
}

Staging::~Staging() {
  std::error_code ec;
  fs::remove_all(path_, ec);
  if (!committed_) remove_created();
}

std::vector<std::string> Staging::commit() {
  std::vector<std::string> moved;
  for (const auto& entry : fs::directory_iterator(path_)) {
    const fs::path target = dir_ / entry.path().filename();
    std::error_code ec;
    fs::rename(entry.path(), target, ec);
    if (ec) throw InputError(target.string(), 0, "cannot write it: " + ec.message());
    moved.push_back(target.string());
  }
  committed_ = true;
  std::sort(moved.begin(), moved.end());
  return moved;
}

void Staging::remove_created() {
  std::error_code ec;
  for (const fs::path& level : created_) fs::remove(level, ec);  // innermost first; only if empty
}

}  // namespace rigid::scan
