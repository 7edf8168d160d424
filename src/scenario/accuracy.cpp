#include "rigid/scenario/accuracy.hpp"

namespace rigid::scenario {

const std::vector<AccuracyPreset>& accuracy_presets() {
  using dynamics::RotationIntegrator;
  // The values come from `rigid study accuracy` and the validation-subset campaigns
  // (docs/accuracy.md, where the errors and costs of each preset are measured). The rotation
  // integrator stays splitting: for the planar rocking of the study's blocks RK4 gives the same
  // trajectories at the same cost, and in the 3D geode drop it breaks the symmetry sooner. The
  // at-rest tolerances also decide when blocks fall asleep (RunSettings::select_effects), so the
  // fast preset keeps balanced's: looser ones cost up to 20 % trajectory error for little time.
  static const std::vector<AccuracyPreset> presets = {
      {"fast", 0.4, RotationIntegrator::splitting, 1e-3, 1e-3, 0.5, 1e-7, 200,
       "safety 0.4, splitting, at-rest stop 1 mm/s, 1 mrad/s for 0.5 s, contact solve to 1e-7 g dt in 200 sweeps"},
      {"balanced", 0.2, RotationIntegrator::splitting, 1e-3, 1e-3, 0.5, 1e-7, 200,
       "safety 0.2, splitting, at-rest stop 1 mm/s, 1 mrad/s for 0.5 s, contact solve to 1e-7 g dt in 200 sweeps "
       "(the engine's defaults)"},
      // the oracle: a contact solve to 1e-10 g dt with no practical cap on its sweeps
      {"reference", 0.05, RotationIntegrator::splitting, 1e-4, 1e-4, 1.0, 1e-10, 100000,
       "safety 0.05, splitting, tight at-rest stop (0.1 mm/s, 0.1 mrad/s for 1 s), contact solve to 1e-10 g dt in "
       "up to 100,000 sweeps"},
  };
  return presets;
}

const AccuracyPreset* find_accuracy_preset(std::string_view name) {
  for (const auto& p : accuracy_presets()) {
    if (p.name == name) return &p;
  }
  return nullptr;
}

std::string accuracy_preset_list() {
  const auto& p = accuracy_presets();
  std::string out;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (i > 0) out += i + 1 == p.size() ? " or " : ", ";
    out += p[i].name;
  }
  return out;
}

void apply_accuracy(const AccuracyPreset& preset, const AccuracyOverrides& overrides, RunSettings& settings) {
  settings.step.dt = 0;
  settings.step.safety = preset.safety;
  settings.step.rotation = preset.rotation;
  settings.rest_speed = preset.rest_speed;
  settings.rest_angular_speed = preset.rest_angular_speed;
  settings.rest_time = preset.rest_time;
  settings.step.solver_tolerance = overrides.solver_tolerance.value_or(preset.solver_tolerance);
  settings.step.solver_max_sweeps = overrides.solver_max_sweeps.value_or(preset.solver_max_sweeps);
  if (overrides.dt) settings.step.dt = *overrides.dt;
  if (overrides.safety) settings.step.safety = *overrides.safety;
  if (overrides.rotation) settings.step.rotation = *overrides.rotation;
}

const char* integrator_name(dynamics::RotationIntegrator rotation) {
  return rotation == dynamics::RotationIntegrator::rk4 ? "rk4" : "splitting";
}

std::optional<dynamics::RotationIntegrator> parse_integrator(std::string_view name) {
  if (name == "splitting") return dynamics::RotationIntegrator::splitting;
  if (name == "rk4") return dynamics::RotationIntegrator::rk4;
  return std::nullopt;
}

}  // namespace rigid::scenario
