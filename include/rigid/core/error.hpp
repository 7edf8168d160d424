#pragma once
/// Errors in user input: where (file, line) and what. Printed by the CLI as one line
/// `rigid: error: FILE:LINE: WHAT` with exit status 2.
#include <stdexcept>
#include <string>

namespace rigid {

class InputError : public std::runtime_error {
 public:
  /// line = 0 means "no particular line" (the file as a whole).
  InputError(std::string file, long line, const std::string& what)
      : std::runtime_error(format(file, line, what)), file_(std::move(file)), line_(line), problem_(what) {}
  const std::string& file() const { return file_; }
  long line() const { return line_; }
  /// The problem alone, without FILE:LINE (to re-raise it under another file or option).
  const std::string& problem() const { return problem_; }

 private:
  static std::string format(const std::string& file, long line, const std::string& what) {
    std::string s = file.empty() ? std::string() : file + ":";
    if (!file.empty() && line > 0) s += std::to_string(line) + ":";
    if (!s.empty()) s += " ";
    return s + what;
  }
  std::string file_;
  long line_;
  std::string problem_;
};

}  // namespace rigid
