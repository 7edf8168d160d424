#include "rigid/job/run_overrides.hpp"

#include <cmath>
#include <cstdio>

#include "rigid/core/error.hpp"
#include "rigid/scenario/accuracy.hpp"

namespace rigid::job {
namespace {

// How a text-valued setting's error reads: in a job file its [run] key with the values quoted
// (and, for some, the value given); on a command line the flag with the values plain.
struct TextSettingInfo {
  const char* key;
  std::string quoted_values;
  std::string plain_values;
  bool names_value;  ///< a job file's error ends with ", not VALUE"
};

TextSettingInfo info_of(Setting setting) {
  switch (setting) {
    case Setting::model:
      return {"model", "\"dem3d\" or \"rocking2d\"", "dem3d or rocking2d", true};
    case Setting::contact:
      return {"contact", "\"rigid\" or \"penalty\"", "rigid or penalty", false};
    case Setting::effects:
      return {"effects", "\"auto\" or \"all\"", "auto or all", true};
    case Setting::accuracy:
      return {"accuracy", scenario::accuracy_preset_list(), scenario::accuracy_preset_list(), true};
    case Setting::integrator:
      return {"integrator", "\"splitting\" or \"rk4\"", "splitting or rk4", false};
    default:
      return {"", "", "", false};
  }
}

// Parses `text` into the setting's field; false when it is not one of the setting's values.
bool parse_into(RunOverrides& o, Setting setting, const std::string& text) {
  switch (setting) {
    case Setting::model:
      o.engine = scenario::parse_engine(text);
      return o.engine.has_value();
    case Setting::contact: {
      contact::ContactMethod model;
      if (!contact::parse_contact_method(text, model)) return false;
      o.contact = model;
      return true;
    }
    case Setting::effects:
      if (text != "auto" && text != "all") return false;
      o.select_effects = text == "auto";
      return true;
    case Setting::accuracy:
      if (!scenario::find_accuracy_preset(text)) return false;
      o.accuracy = text;
      return true;
    case Setting::integrator:
      o.integrator = scenario::parse_integrator(text);
      return o.integrator.has_value();
    default:
      return false;
  }
}

}  // namespace

void set_text_setting(RunOverrides& o, Setting setting, const std::optional<std::string>& text,
                      const SettingSource& source) {
  if (text && parse_into(o, setting, *text)) {
    if (!source.flag.empty()) o.flags_given.emplace_back(setting, source.flag + " " + *text);
    return;
  }
  const TextSettingInfo info = info_of(setting);
  if (!source.flag.empty()) throw InputError("", 0, source.flag + " must be " + info.plain_values);
  std::string problem = std::string(info.key) + " must be " + info.quoted_values;
  if (info.names_value) problem += ", not " + (text ? "\"" + *text + "\"" : std::string("a non-string"));
  throw InputError(source.file, source.line, problem);
}

std::string numbers_problem(const RunOverrides& o) {
  const auto negative = [](const std::optional<double>& v) { return v && *v < 0; };
  if (negative(o.duration) || negative(o.free_time) || negative(o.dt) || (o.safety && !(*o.safety > 0))) {
    return "durations and dt must not be negative, safety must be positive";
  }
  return "";
}

std::string solver_problem(const RunOverrides& o) {
  if (o.solver_tolerance && !(*o.solver_tolerance > 0 && *o.solver_tolerance < 1)) {
    return "solver_tolerance must be a number in (0, 1), a fraction of g dt";
  }
  if (o.solver_max_sweeps) {
    const double sweeps = *o.solver_max_sweeps;
    if (!(sweeps >= 1 && sweeps <= 1e9 && sweeps == std::floor(sweeps))) {
      return "solver_max_sweeps must be a whole number from 1 to 1e9";
    }
  }
  return "";
}

void set_number_setting(RunOverrides& o, Setting setting, double value, const std::string& flag) {
  RunOverrides given;
  if (setting == Setting::solver_tolerance) given.solver_tolerance = value;
  if (setting == Setting::solver_max_sweeps) given.solver_max_sweeps = value;
  std::string problem = solver_problem(given);
  if (!problem.empty()) {
    // the flag's own words: "--solver-tolerance must be ..."
    throw InputError("", 0, flag + problem.substr(problem.find(' ')));
  }
  if (setting == Setting::solver_tolerance) o.solver_tolerance = value;
  if (setting == Setting::solver_max_sweeps) o.solver_max_sweeps = value;
  char text[64];
  std::snprintf(text, sizeof text, "%.17g", value);
  o.flags_given.emplace_back(setting, flag + " " + text);
}

RunOverrides merged(RunOverrides base, const RunOverrides& over) {
  const auto take = [](auto& to, const auto& from) {
    if (from) to = from;
  };
  take(base.engine, over.engine);
  take(base.contact, over.contact);
  take(base.select_effects, over.select_effects);
  take(base.accuracy, over.accuracy);
  take(base.integrator, over.integrator);
  take(base.duration, over.duration);
  take(base.free_time, over.free_time);
  take(base.dt, over.dt);
  take(base.safety, over.safety);
  take(base.solver_tolerance, over.solver_tolerance);
  take(base.solver_max_sweeps, over.solver_max_sweeps);
  base.flags_given.insert(base.flags_given.end(), over.flags_given.begin(), over.flags_given.end());
  return base;
}

std::string accuracy_name(const RunOverrides& o) { return o.accuracy.value_or(scenario::kDefaultAccuracy); }

scenario::RunSettings run_settings(const RunOverrides& o) {
  scenario::RunSettings settings;
  scenario::AccuracyOverrides step;
  step.dt = o.dt;
  step.safety = o.safety;
  step.rotation = o.integrator;
  step.solver_tolerance = o.solver_tolerance;
  if (o.solver_max_sweeps) step.solver_max_sweeps = static_cast<int>(*o.solver_max_sweeps);
  scenario::apply_accuracy(*scenario::find_accuracy_preset(accuracy_name(o)), step, settings);
  if (o.duration) settings.duration = *o.duration;
  if (o.free_time) settings.free_time = *o.free_time;
  if (o.select_effects) settings.select_effects = *o.select_effects;
  return settings;
}

}  // namespace rigid::job
