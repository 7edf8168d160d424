#pragma once
/// Running the Python helpers of src/plot (Debian's /usr/bin/python3 with numpy, h5py and
/// matplotlib) as child processes, for commands that go on after the plot (`rigid study`).
/// `rigid plot` itself replaces the process instead (plot_command.cpp).
#include <string>
#include <vector>

namespace rigid::app {

/// $RIGID_PYTHON, else /usr/bin/python3 (a `python3` first on PATH often lacks the packages).
std::string python_interpreter();

/// Path of src/plot/NAME: in the source tree this file was compiled from, else beside the
/// executable (EXE_DIR/../../src/plot, EXE_DIR/../share/rigid). Empty if none exists.
std::string find_plot_helper(const std::string& name);

/// Runs PYTHON SCRIPT ARGS... and waits; returns its exit status, or -1 if it could not start.
int run_python(const std::string& script, const std::vector<std::string>& args);

}  // namespace rigid::app
