#pragma once
// The end of a calibration: the fit on the final stage's grid, cross-validation, the calibrated
// scene and OUT.calibration.json (docs/validation-shaketable.md says what each field means).
#include <string>
#include <utility>
#include <vector>

#include "shaketable.hpp"

namespace rigid::app::shaketable {

struct CalibrationReport {
  std::string scan, tests_csv, out, lab_format_file;
  const io::LabTestList* tests = nullptr;
  std::vector<int> observed, group;
  /// each stage's outcome grid and the physics of its variants; the last one is fitted
  std::vector<std::pair<const calibration::OutcomeGrid*, std::vector<Physics>>> stages;
  std::vector<io::DesignJob::Record> windows;
  double wall_s = 0;
};

void write_calibration(const CalibrationReport& report);

/// Prints scores as the commands report them (one block of lines).
void print_scores(const char* title, const calibration::Scores& s);

}  // namespace rigid::app::shaketable
