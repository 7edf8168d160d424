// `rigid plot ARGS...`: fragility maps, per-record curves, the probit fit, difference maps and
// scenario tables from campaign cubes. The work is done by the Python package src/python/rigidpy
// (numpy, h5py, matplotlib: Debian packages of /usr/bin/python3) through its launcher
// src/python/rigid_plot.py; this command only finds the launcher and
// replaces itself with `PYTHON SCRIPT ARGS...` (execv), so the script's output, signals and exit
// status (0 done, 2 bad input, 1 internal error) are rigid's own. Every argument after `plot`,
// --help included, goes to the script unchanged.
//
// The script is the first of these that exists:
//   1. $RIGID_PLOT_SCRIPT (an error if set to a missing file);
//   2. the source tree this file was compiled from: dirname(__FILE__)/../python/rigid_plot.py
//      (CMake compiles with absolute source paths, so a build anywhere finds its checkout);
//   3. beside the executable: EXE_DIR/../../src/python/rigid_plot.py (build/bin/rigid in a checkout)
//      and EXE_DIR/../share/rigid/rigid_plot.py (an installed tree, with rigidpy/ beside it).
// The interpreter is $RIGID_PYTHON, else /usr/bin/python3 (a `python3` first on PATH, e.g. pyenv,
// usually lacks the Debian packages).
#include <cstdlib>
#include <string>
#include <vector>

#include "commands.hpp"
#include "python_script.hpp"
#include "rigid/core/error.hpp"

namespace rigid::app {

namespace {

std::string find_plot_script() {
  if (const char* env = std::getenv("RIGID_PLOT_SCRIPT"); env != nullptr && *env != '\0') {
    if (first_file({env}).empty()) throw InputError("", 0, std::string("RIGID_PLOT_SCRIPT=") + env + ": no such file");
    return env;
  }
  const std::vector<std::string> candidates = plot_helper_candidates("rigid_plot.py");
  if (std::string found = first_file(candidates); !found.empty()) return found;
  std::string tried;
  for (const std::string& c : candidates) tried += (tried.empty() ? "" : ", ") + c;
  throw InputError("", 0, "cannot find rigid_plot.py (tried " + tried + "); set RIGID_PLOT_SCRIPT");
}

}  // namespace

void register_plot_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand(
      "plot",
      "Fragility maps (PGA x PGV/PGA bins) with this project's probit fit and its 1/50/99 % "
      "contours, per-record curves, difference maps of two cubes and scenario tables (PNG, JSON, CSV, "
      "markdown): `rigid plot maps|diff|table ...`; `rigid plot --help` for the options. Runs "
      "src/python/rigid_plot.py with /usr/bin/python3 (numpy, h5py, matplotlib)");
  // Everything after `plot` belongs to the script, --help included.
  cmd->prefix_command();
  cmd->set_help_flag();
  cmd->callback([cmd] {
    exec_python(find_plot_script(), cmd->remaining(),
                "`rigid plot` needs Debian's python3 with python3-numpy, python3-h5py, python3-matplotlib and "
                "python3-scipy (setup.sh installs them)");
  });
}

}  // namespace rigid::app
