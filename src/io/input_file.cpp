#include "input_file.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "rigid/core/error.hpp"

namespace rigid::io {
namespace fs = std::filesystem;

std::string input_file_problem(const std::string& path) {
  std::error_code ec;
  // status() follows links but opens nothing: a FIFO is named, never waited on
  const fs::file_status status = fs::status(path, ec);
  switch (status.type()) {
    case fs::file_type::regular:
      return "";
    case fs::file_type::not_found:
      return "not found";
    case fs::file_type::directory:
      return "is a directory, not a file";
    case fs::file_type::fifo:
      return "is a FIFO (named pipe), not a regular file";
    case fs::file_type::character:
      return "is a character device, not a regular file";
    case fs::file_type::block:
      return "is a block device, not a regular file";
    case fs::file_type::socket:
      return "is a socket, not a regular file";
    default:
      return ec ? "cannot read file: " + ec.message() : std::string("not a regular file");
  }
}

void check_input_file(const std::string& path, std::uintmax_t max_bytes) {
  const std::string problem = input_file_problem(path);
  if (problem == "not found") throw InputError(path, 0, "cannot open file: not found");
  if (!problem.empty()) throw InputError(path, 0, problem);
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw InputError(path, 0, "cannot read file: " + ec.message());
  if (size > max_bytes) throw InputError(path, 0, "file larger than " + std::to_string(max_bytes >> 20) + " MB");
}

std::string read_input_file(const std::string& path, std::uintmax_t max_bytes) {
  check_input_file(path, max_bytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, std::string("cannot open file: ") + std::strerror(errno));
  // read into a string of the file's size (a stringstream's copy would double the limit's cost);
  // a file that grows meanwhile is read only up to the limit, and then refused
  std::string text;
  std::error_code ec;
  const std::uintmax_t size = fs::file_size(path, ec);
  text.reserve(ec ? 0 : std::size_t(std::min(size, max_bytes)));
  char buf[1 << 16];
  while (in.read(buf, sizeof buf) || in.gcount() > 0) {
    text.append(buf, std::size_t(in.gcount()));
    if (text.size() > max_bytes)
      throw InputError(path, 0, "file larger than " + std::to_string(max_bytes >> 20) + " MB");
  }
  if (in.bad()) throw InputError(path, 0, "read error");
  return text;
}

}  // namespace rigid::io
