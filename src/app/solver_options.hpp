#pragma once
/// The contact-solve flags shared by `rigid run` and `rigid campaign`.
#include <CLI/CLI.hpp>

namespace rigid::app {

/// --solver-tolerance and --solver-max-sweeps into `tolerance` and `max_sweeps` (left 0 when not
/// given); the values job::solver_problem refuses are usage errors naming the flag.
void add_solver_options(CLI::App& cmd, double& tolerance, double& max_sweeps);

}  // namespace rigid::app
