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

/// Throws rigid::InputError(output, 0, ...) when `output` is the same file as one of `inputs`
/// (hard links and other spellings included). Paths that do not exist compare unequal.
void refuse_output_over_inputs(const std::string& output, const std::vector<std::string>& inputs);

/// Writes `path` atomically: `write` fills a stream on a private temporary (mkstemp in the same
/// directory), which is flushed to disk and renamed over `path`. Throws rigid::InputError(path,
/// 0, ...) and leaves no temporary when anything fails (a full disk, an exception of `write`).
void write_output_file(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace rigid::io
