// `rigid plot ARGS...`: fragility maps, per-record curves, the probit fit, difference maps and
// scenario tables from campaign cubes. The work is done by src/plot/rigid_plot.py (numpy, h5py,
// matplotlib: Debian packages of /usr/bin/python3); this command only finds the script and
// replaces itself with `PYTHON SCRIPT ARGS...` (execv), so the script's output, signals and exit
// status (0 done, 2 bad input, 1 internal error) are rigid's own. Every argument after `plot`,
// --help included, goes to the script unchanged.
//
// The script is the first of these that exists:
//   1. $RIGID_PLOT_SCRIPT (an error if set to a missing file);
//   2. the compile definition RIGID_PLOT_SCRIPT, when the build gives one;
//   3. the source tree this file was compiled from: dirname(__FILE__)/../plot/rigid_plot.py
//      (CMake compiles with absolute source paths, so a build anywhere finds its checkout);
//   4. beside the executable: EXE_DIR/../../src/plot/rigid_plot.py (build/bin/rigid in a checkout)
//      and EXE_DIR/../share/rigid/rigid_plot.py (an installed tree).
// The interpreter is $RIGID_PYTHON, else /usr/bin/python3 (a `python3` first on PATH, e.g. pyenv,
// usually lacks the Debian packages).
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "rigid/core/error.hpp"

namespace rigid::app {

namespace {

namespace fs = std::filesystem;

bool is_file(const fs::path& p) {
  std::error_code ec;
  return fs::is_regular_file(p, ec);
}

std::string find_plot_script() {
  if (const char* env = std::getenv("RIGID_PLOT_SCRIPT"); env != nullptr && *env != '\0') {
    if (!is_file(env))
      throw InputError("", 0, std::string("RIGID_PLOT_SCRIPT=") + env + ": no such file");
    return env;
  }
  std::vector<fs::path> candidates;
#ifdef RIGID_PLOT_SCRIPT
  candidates.emplace_back(RIGID_PLOT_SCRIPT);
#endif
  candidates.push_back(fs::path(__FILE__).parent_path().parent_path() / "plot" / "rigid_plot.py");
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    const fs::path dir = exe.parent_path();
    candidates.push_back(dir.parent_path().parent_path() / "src" / "plot" / "rigid_plot.py");
    candidates.push_back(dir.parent_path() / "share" / "rigid" / "rigid_plot.py");
  }
  std::string tried;
  for (const fs::path& c : candidates) {
    if (is_file(c)) return c.lexically_normal().string();
    tried += (tried.empty() ? "" : ", ") + c.lexically_normal().string();
  }
  throw InputError("", 0, "cannot find rigid_plot.py (tried " + tried + "); set RIGID_PLOT_SCRIPT");
}

[[noreturn]] void exec_plot(const std::vector<std::string>& args) {
  const char* env_python = std::getenv("RIGID_PYTHON");
  const std::string python = (env_python != nullptr && *env_python != '\0') ? env_python : "/usr/bin/python3";
  const std::string script = find_plot_script();
  std::vector<std::string> storage{python, script};
  storage.insert(storage.end(), args.begin(), args.end());
  std::vector<char*> argv;
  argv.reserve(storage.size() + 1);
  for (std::string& s : storage) argv.push_back(s.data());
  argv.push_back(nullptr);
  std::fflush(stdout);
  std::fflush(stderr);
  ::execv(python.c_str(), argv.data());
  const int err = errno;  // only reached when execv failed
  if (err == ENOENT)
    throw InputError("", 0, python + ": not found; `rigid plot` needs Debian's python3 with python3-numpy, "
                            "python3-h5py, python3-matplotlib and python3-scipy (setup.sh installs them), or set RIGID_PYTHON");
  throw std::runtime_error("cannot run " + python + ": " + std::strerror(err));
}

}  // namespace

void register_plot_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "plot",
      "Fragility maps (PGA x PGV/PGA bins) with this project's probit fit and its 1/50/99 % "
      "contours, per-record curves, difference maps of two cubes and scenario tables (PNG, JSON, CSV, "
      "markdown): `rigid plot maps|diff|table ...`; `rigid plot --help` for the options. Runs "
      "src/plot/rigid_plot.py with /usr/bin/python3 (numpy, h5py, matplotlib)");
  // Everything after `plot` belongs to the script, --help included.
  cmd->prefix_command();
  cmd->set_help_flag();
  cmd->callback([cmd] { exec_plot(cmd->remaining()); });
}

}  // namespace rigid::app
