#pragma once
// Reading an input file whole, safely: a FIFO, device or directory given as an input would block
// or grow memory without bound, so only regular files up to a size limit are read (docs/robustness.md). Private to
// rigid_io.
#include <cstdint>
#include <string>

namespace rigid::io {

/// Size limits (unit: bytes): text inputs (TOML, model files, record lists) and bulk inputs
/// (STL meshes, AT2 records; a 1e6-facet binary STL is 50 MB).
inline constexpr std::uintmax_t kMaxTextFileBytes = std::uintmax_t(64) << 20;
inline constexpr std::uintmax_t kMaxBulkFileBytes = std::uintmax_t(256) << 20;
/// Scans (rigid model import): an ASCII PLY or OBJ of a few million facets.
inline constexpr std::uintmax_t kMaxMeshFileBytes = std::uintmax_t(512) << 20;

/// "" for a regular file (links followed); otherwise what the path is: "not found", "is a
/// directory, not a file", "is a FIFO (named pipe), not a regular file", "is a character device,
/// not a regular file", ... Nothing is opened, so a FIFO never blocks.
std::string input_file_problem(const std::string& path);

/// Throws rigid::InputError(path, 0, ...) unless path is an existing regular file of at most
/// max_bytes: "cannot open file: not found", or input_file_problem's answer, or "file larger than N MB".
void check_input_file(const std::string& path, std::uintmax_t max_bytes);

/// check_input_file, then the whole content.
std::string read_input_file(const std::string& path, std::uintmax_t max_bytes);

}  // namespace rigid::io
