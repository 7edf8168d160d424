#pragma once
/// The settings a user may give for how every case of a job (or the one case of `rigid run`)
/// simulates, typed: filled at the edge (a job file's [run] table, or command-line flags) and
/// turned into a run's settings by run_settings() alone. Every text-valued setting is parsed and
/// checked by set_text_setting(), whichever edge gives it.
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "rigid/contact/contact.hpp"
#include "rigid/scenario/case.hpp"
#include "rigid/scenario/scene.hpp"

namespace rigid::job {

/// A setting a user may override.
enum class Setting {
  model,
  contact,
  effects,
  accuracy,
  integrator,
  duration,
  free_time,
  dt,
  safety,
  solver_tolerance,
  solver_max_sweeps
};

/// Where a setting's value was given, for its error: a command-line flag (flag not empty), else a
/// job file and line.
struct SettingSource {
  std::string file;
  long line = 0;
  std::string flag;  ///< e.g. "--contact"; the edge that reads flags names them
};

struct RunOverrides {
  std::optional<scenario::Engine> engine;         ///< dem3d or rocking2d (the `model` key)
  std::optional<contact::ContactMethod> contact;  ///< every object's contact model; none: each scene's
  std::optional<bool> select_effects;             ///< effects "auto" (true) or "all" (false)
  std::optional<std::string> accuracy;            ///< accuracy preset name (scenario/accuracy.hpp)
  std::optional<dynamics::RotationIntegrator> integrator;
  std::optional<double> duration;   ///< unit: s; 0 = the record plus free_time
  std::optional<double> free_time;  ///< unit: s
  std::optional<double> dt;         ///< fixed time step (unit: s); 0 = automatic
  std::optional<double> safety;     ///< safety factor of the automatic step
  /// The rigid contact solve's tolerance, a fraction of g dt (StepSettings::solver_tolerance)
  std::optional<double> solver_tolerance;
  /// Its sweep cap, as given (a whole number >= 1 once solver_problem() has passed it)
  std::optional<double> solver_max_sweeps;
  /// The settings given by a flag, as written ("--model rocking2d"), in the order given: what a
  /// campaign records in its job text, so a resume under other values is refused.
  std::vector<std::pair<Setting, std::string>> flags_given;
};

/// Parses a text-valued setting (model, contact, effects, accuracy, integrator) into `o`; `text`
/// is nothing when the value is not a string. Throws rigid::InputError naming the flag, or the
/// file and line, with the values the setting admits.
void set_text_setting(RunOverrides& o, Setting setting, const std::optional<std::string>& text,
                      const SettingSource& source);

/// The problem with the numeric settings given (a negative duration, free time or step, a
/// safety that is not positive), "" when there is none.
std::string numbers_problem(const RunOverrides& o);

/// The problem with the contact-solve settings given (a tolerance that is not a finite number
/// in (0, 1), a sweep cap that is not a whole number from 1 to 1e9), "" when there is none.
std::string solver_problem(const RunOverrides& o);

/// Sets a numeric setting given by a command-line flag (solver_tolerance, solver_max_sweeps),
/// recording it in flags_given. Throws rigid::InputError naming the flag when solver_problem
/// refuses it.
void set_number_setting(RunOverrides& o, Setting setting, double value, const std::string& flag);

/// `over`'s settings on top of `base`'s.
RunOverrides merged(RunOverrides base, const RunOverrides& over);

/// The accuracy preset named, or the default one (kDefaultAccuracy).
std::string accuracy_name(const RunOverrides& o);

/// The settings of a run: the accuracy preset, then dt, safety and integrator over it, then the
/// durations and the effect selection (observers left empty).
scenario::RunSettings run_settings(const RunOverrides& o);

}  // namespace rigid::job
