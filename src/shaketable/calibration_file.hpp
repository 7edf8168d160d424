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
  /// each stage's outcome grid and the physics of its variants; the last one is fitted
  std::vector<std::pair<const calibration::OutcomeGrid*, std::vector<Physics>>> stages;
  double wall_s = 0;
};

/// Writes OUT.toml, the members' scenes, OUT.calibration.json and the figure's likelihood table
/// OUT.calibration/likelihood.csv; returns what it found.
CalibrationSummary write_calibration(const CalibrationReport& report);

}  // namespace rigid::shaketable
