#include "python_script.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "rigid/core/error.hpp"

namespace rigid::app {

namespace {

namespace fs = std::filesystem;

// PYTHON SCRIPT ARGS..., with stdout and stderr flushed so that the script's output follows ours
std::vector<std::string> python_command(const std::string& python, const std::string& script,
                                        const std::vector<std::string>& args) {
  std::vector<std::string> command{python, script};
  command.insert(command.end(), args.begin(), args.end());
  std::fflush(stdout);
  std::fflush(stderr);
  return command;
}

// argv for execv: pointers into storage, null-terminated
std::vector<char*> python_argv(std::vector<std::string>& storage) {
  std::vector<char*> argv;
  argv.reserve(storage.size() + 1);
  for (std::string& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);
  return argv;
}

}  // namespace

std::string python_interpreter() {
  const char* env = std::getenv("RIGID_PYTHON");
  return (env != nullptr && *env != '\0') ? env : "/usr/bin/python3";
}

std::vector<std::string> plot_helper_candidates(const std::string& name) {
  std::vector<fs::path> candidates;
  candidates.push_back(fs::path(__FILE__).parent_path().parent_path() / "python" / name);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path dir = exe.parent_path();
    candidates.push_back(dir.parent_path().parent_path() / "src" / "python" / name);
    candidates.push_back(dir.parent_path() / "share" / "rigid" / name);
  }
  std::vector<std::string> out;
  for (const fs::path& c : candidates) out.push_back(c.lexically_normal().string());
  return out;
}

std::string first_file(const std::vector<std::string>& paths) {
  for (const std::string& p : paths) {
    std::error_code ec;
    if (fs::is_regular_file(p, ec)) return p;
  }
  return "";
}

std::string find_plot_helper(const std::string& name) { return first_file(plot_helper_candidates(name)); }

int run_python(const std::string& script, const std::vector<std::string>& args) {
  const std::string python = python_interpreter();
  std::vector<std::string> command = python_command(python, script, args);
  const std::vector<char*> argv = python_argv(command);
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

void exec_python(const std::string& script, const std::vector<std::string>& args, const std::string& needs) {
  const std::string python = python_interpreter();
  std::vector<std::string> command = python_command(python, script, args);
  const std::vector<char*> argv = python_argv(command);
  ::execv(python.c_str(), argv.data());
  const int err = errno;  // only reached when execv failed
  if (err == ENOENT) throw InputError("", 0, python + ": not found; " + needs + ", or set RIGID_PYTHON");
  throw std::runtime_error("cannot run " + python + ": " + std::strerror(err));
}

}  // namespace rigid::app
