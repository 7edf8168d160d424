#pragma once
// printf-style formatting of the workflow's log lines and file names, one line each (private to
// rigid_shaketable).
#include <cstdio>
#include <string>

namespace rigid::shaketable {

/// `fmt` with `args`, as snprintf writes it; cut at 511 characters.
std::string format(const char* fmt, auto... args) {
  char text[512];
  std::snprintf(text, sizeof text, fmt, args...);
  return text;
}

}  // namespace rigid::shaketable
