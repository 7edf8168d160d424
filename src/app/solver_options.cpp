#include "solver_options.hpp"

#include <cmath>
#include <string>

#include "number_checks.hpp"
#include "rigid/job/run_overrides.hpp"

namespace rigid::app {
namespace {

// A number the setting's own rule (job::solver_problem) admits; `wanted` names it in the message.
CLI::Validator number_where_admitted(job::Setting setting, const std::string& wanted) {
  return CLI::Validator(
      [setting, wanted](std::string& text) -> std::string {
        const std::optional<double> v = whole_number(text);
        job::RunOverrides given;
        (setting == job::Setting::solver_tolerance ? given.solver_tolerance : given.solver_max_sweeps) =
            v.value_or(std::nan(""));
        if (v && job::solver_problem(given).empty()) return {};
        return "'" + text + "' is not " + wanted;
      },
      "");
}

}  // namespace

void add_solver_options(CLI::App& cmd, double& tolerance, double& max_sweeps) {
  // the rule is job::solver_problem's, the settings' one parser; here only its wording per flag
  cmd.add_option("--solver-tolerance", tolerance,
                 "Rigid contact solve: converged when a sweep changes no velocity by more than this fraction of "
                 "g dt, the velocity gravity adds in one step (default: the preset's, 1e-7; reference 1e-10)")
      ->check(number_where_admitted(job::Setting::solver_tolerance, "a number in (0, 1)"));
  cmd.add_option("--solver-max-sweeps", max_sweeps,
                 "Rigid contact solve: sweeps before a step's solve stops unconverged (counted per cell; "
                 "default: the preset's, 200; reference 100000)")
      ->check(number_where_admitted(job::Setting::solver_max_sweeps, "a whole number from 1 to 1e9"));
}

}  // namespace rigid::app
