#include "python_script.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <filesystem>

namespace rigid::app {

namespace fs = std::filesystem;

std::string python_interpreter() {
  const char* env = std::getenv("RIGID_PYTHON");
  return (env != nullptr && *env != '\0') ? env : "/usr/bin/python3";
}

std::string find_plot_helper(const std::string& name) {
  std::vector<fs::path> candidates;
  candidates.push_back(fs::path(__FILE__).parent_path().parent_path() / "plot" / name);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path dir = exe.parent_path();
    candidates.push_back(dir.parent_path().parent_path() / "src" / "plot" / name);
    candidates.push_back(dir.parent_path() / "share" / "rigid" / name);
  }
  for (const fs::path& c : candidates) {
    if (fs::is_regular_file(c, ec)) return c.lexically_normal().string();
  }
  return "";
}

int run_python(const std::string& script, const std::vector<std::string>& args) {
  const std::string python = python_interpreter();
  std::vector<std::string> storage{python, script};
  storage.insert(storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    ::execv(python.c_str(), argv.data());
    std::_Exit(127);
  }
  int status = 0;
  if (::waitpid(pid, &status, 0) < 0) return -1;
  if (WIFEXITED(status)) return WEXITSTATUS(status) == 127 ? -1 : WEXITSTATUS(status);
  return -1;
}

}  // namespace rigid::app
