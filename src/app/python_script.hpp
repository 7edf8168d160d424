#pragma once
/// The one launcher of the Python helpers of src/python (Debian's /usr/bin/python3 with numpy,
/// h5py and matplotlib): finding a script, the interpreter, and running it either as a child
/// process (commands that go on after the plot: `rigid study`) or in place of this process
/// (`rigid plot`, plot_command.cpp).
#include <string>
#include <vector>

namespace rigid::app {

/// $RIGID_PYTHON, else /usr/bin/python3 (a `python3` first on PATH often lacks the packages).
std::string python_interpreter();

/// Where src/python/NAME may be, in this order: the source tree this file was compiled from
/// (CMake compiles with absolute paths, so a build anywhere finds its checkout), then beside the
/// executable (EXE_DIR/../../src/python, a checkout's build/bin; EXE_DIR/../share/rigid, an
/// installed tree). Normalised paths; existence not checked.
std::vector<std::string> plot_helper_candidates(const std::string& name);

/// The first of these paths that is a regular file; empty if none is.
std::string first_file(const std::vector<std::string>& paths);

/// first_file(plot_helper_candidates(name)).
std::string find_plot_helper(const std::string& name);

/// Runs PYTHON SCRIPT ARGS... and waits; returns its exit status, or -1 if it could not start.
int run_python(const std::string& script, const std::vector<std::string>& args);

/// Replaces this process with PYTHON SCRIPT ARGS... (execv), so the script's output, signals and
/// exit status are the caller's own. Returns only by throwing: InputError when the interpreter
/// does not exist (the message names the packages `needs` describes), std::runtime_error else.
[[noreturn]] void exec_python(const std::string& script, const std::vector<std::string>& args,
                              const std::string& needs);

}  // namespace rigid::app
