#pragma once
/// Accuracy presets (measured in docs/accuracy.md): named sets of the numerical settings
/// that trade accuracy for time. A preset sets the time-step safety factor (physics.md §10), the
/// rotation integrator (physics.md §8) and the tolerances of the at-rest stop (RunSettings::
/// rest_speed, rest_angular_speed, rest_time). It never touches the physics of a scene (density,
/// stiffness, friction, damping): those belong to the scene file. Explicit settings (`--safety`,
/// `--integrator`, `--dt`, or the [run] keys safety, integrator, dt_s) take precedence over the
/// preset's values; so do `--solver-tolerance` and `--solver-max-sweeps` ([run] solver_tolerance,
/// solver_max_sweeps) over its contact-solve settings.
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "rigid/scenario/scene.hpp"

namespace rigid::scenario {

struct AccuracyPreset {
  std::string name;
  /// Fraction of the critical step of the automatic time step (StepSettings::safety).
  double safety = 0.2;
  dynamics::RotationIntegrator rotation = dynamics::RotationIntegrator::splitting;
  /// At-rest stop after the motion: every free block below these speeds for rest_time
  /// (units: m/s, rad/s, s).
  double rest_speed = 1e-3;
  double rest_angular_speed = 1e-3;
  double rest_time = 0.5;
  /// The rigid contact solve's tolerance (a fraction of g dt) and sweep cap
  /// (StepSettings::solver_tolerance, solver_max_sweeps).
  double solver_tolerance = 1e-7;
  int solver_max_sweeps = 200;
  std::string summary;  ///< one line for --help and the docs
};

/// The presets, cheapest first: fast, balanced, reference.
const std::vector<AccuracyPreset>& accuracy_presets();

/// The preset `run`, `campaign` and job files use when none is named: the cheapest preset whose
/// campaign outcomes agree with the reference preset's as well as the slower presets' do
/// (docs/accuracy.md, "The default"). The library's own defaults (RunSettings{}) are balanced's.
inline constexpr const char* kDefaultAccuracy = "fast";

/// The preset of that name, or nullptr.
const AccuracyPreset* find_accuracy_preset(std::string_view name);

/// "fast, balanced or reference", for messages.
std::string accuracy_preset_list();

/// Settings given explicitly, which override the preset's.
struct AccuracyOverrides {
  std::optional<double> dt;      ///< fixed time step (unit: s)
  std::optional<double> safety;  ///< safety factor of the automatic step (unit: 1)
  std::optional<dynamics::RotationIntegrator> rotation;
  std::optional<double> solver_tolerance;  ///< fraction of g dt (unit: 1)
  std::optional<int> solver_max_sweeps;
};

/// Sets the preset's numerical settings in `settings`, then the overrides. Physics, durations and
/// observers are left as they are.
void apply_accuracy(const AccuracyPreset& preset, const AccuracyOverrides& overrides, RunSettings& settings);

/// "splitting" or "rk4".
const char* integrator_name(dynamics::RotationIntegrator rotation);
/// Parses "splitting" or "rk4".
std::optional<dynamics::RotationIntegrator> parse_integrator(std::string_view name);

}  // namespace rigid::scenario
