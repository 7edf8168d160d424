#include "input_file.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "rigid/core/error.hpp"

namespace rigid::io {
namespace fs = std::filesystem;

void check_input_file(const std::string& path, std::uintmax_t max_bytes) {
  std::error_code ec;
  const fs::file_status status = fs::status(path, ec);
  if (status.type() == fs::file_type::not_found) throw InputError(path, 0, "cannot open file: not found");
  if (status.type() == fs::file_type::directory) throw InputError(path, 0, "is a directory, not a file");
  if (status.type() != fs::file_type::regular) {
    throw InputError(path, 0, ec ? "cannot read file: " + ec.message()
                                 : std::string("not a regular file (a FIFO, device or socket)"));
  }
  const std::uintmax_t size = fs::file_size(path, ec);
  if (ec) throw InputError(path, 0, "cannot read file: " + ec.message());
  if (size > max_bytes) throw InputError(path, 0, "file larger than " + std::to_string(max_bytes >> 20) + " MB");
}

std::string read_input_file(const std::string& path, std::uintmax_t max_bytes) {
  check_input_file(path, max_bytes);
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, std::string("cannot open file: ") + std::strerror(errno));
  std::ostringstream s;
  s << in.rdbuf();
  if (in.bad()) throw InputError(path, 0, "read error");
  return s.str();
}

}  // namespace rigid::io
