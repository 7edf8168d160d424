#pragma once
// The import writes into a private directory inside the output directory and moves its files
// into place only once every check has passed: a failed import leaves neither half a model nor a
// directory it created.
#include <filesystem>
#include <string>
#include <vector>

namespace rigid::scan {

class Staging {
 public:
  /// Creates `dir` (and its missing parents) and a private folder in it for the files of `name`.
  /// Throws InputError naming --out when either cannot be made.
  Staging(const std::filesystem::path& dir, const std::string& name);
  Staging(const Staging&) = delete;
  Staging& operator=(const Staging&) = delete;
  /// Removes the private folder, and the directories it created unless committed.
  ~Staging();
  const std::filesystem::path& path() const { return path_; }
  /// Moves every staged file to the output directory (replacing the files of an earlier import);
  /// returns their new paths, sorted.
  std::vector<std::string> commit();

 private:
  void remove_created();
  std::filesystem::path dir_, path_;
  std::vector<std::filesystem::path> created_;  // directories this import created, innermost first
  bool committed_ = false;
};

}  // namespace rigid::scan
