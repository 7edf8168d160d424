#pragma once
// The end of a calibration: the fit on the final stage's grid, cross-validation, the calibrated
// scene and OUT.calibration.json (docs/validation-shaketable.md says what each field means).
#include <string>
#include <utility>
#include <vector>

#include "rigid/calibration/outcome_model.hpp"
#include "rigid/shaketable/calibrate.hpp"
#include "rigid/shaketable/physics.hpp"

namespace rigid::shaketable {

struct CalibrationReport {
  std::string scan, tests_csv, out, lab_format_file;
  std::string command_line;  ///< what the document says made it
  std::vector<int> observed, group;
  std::vector<std::string> records;  ///< each test's recorded motion (group names it)
  /// each stage's outcome grid and the physics of its variants, and what the stage did
  std::vector<std::pair<const calibration::OutcomeGrid*, std::vector<Physics>>> stages;
  std::vector<std::string> stage_purposes;
  /// what is fitted: stage 2 and the extension stages joined, and the candidates searched
  const calibration::OutcomeGrid* fitted = nullptr;
  std::vector<Physics> fitted_physics;
  calibration::SearchSettings search;
  /// the law's numeric parameters and the lapse: values tried along the best's line, status
  std::vector<ParameterReport> parameters;
  PhysicalLimits limits;
  double wall_s = 0;
};

/// Writes OUT.toml, the members' scenes, OUT.calibration.json and the figure's likelihood table
/// OUT.calibration/likelihood.csv; returns what it found.
CalibrationSummary write_calibration(const CalibrationReport& report);

}  // namespace rigid::shaketable
