#pragma once
/// A derived output (a table, a plot) written beside the files it comes from without ever
/// damaging them: refused when the output path is one of the inputs (same device and inode, not
/// the same spelling), written under a private temporary name in the output's directory, then
/// renamed into place; any failure removes the temporary.
#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace rigid::io {

/// The files a command reads, known by device and inode, so that none of its outputs replaces one
/// of them whatever the spelling of its path (hard links, symbolic links, ../).
class InputFiles {
 public:
  /// A file the command reads; one that does not exist (yet) is not recorded.
  void add(const std::string& path);
  void add(const std::vector<std::string>& paths);
  /// Throws rigid::InputError(output, 0, ...) when `output` is one of the inputs, or a directory
  /// (an output file cannot replace it).
  void refuse_as_output(const std::string& output) const;
  /// Throws rigid::InputError(folder, 0, ...) when an input lies inside `folder`, which the command
  /// writes into.
  void refuse_folder(const std::string& folder) const;

 private:
  struct Identity {
    unsigned long long device = 0, inode = 0;
    std::string path;
  };
  std::vector<Identity> files_;
};

/// InputFiles of `inputs`, refuse_as_output(output): for a command with a few inputs.
void refuse_output_over_inputs(const std::string& output, const std::vector<std::string>& inputs);

/// Writes `path` atomically: `write` fills a stream on a private temporary (mkstemp in the same
/// directory), which is flushed to disk and renamed over `path`. Throws rigid::InputError(path,
/// 0, ...) and leaves no temporary when anything fails (a full disk, an exception of `write`).
void write_output_file(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace rigid::io
