#pragma once
/// `rigid shaketable predict` as a workflow: P(overturn) of each listed shake-table test for a
/// (calibrated) scene, averaged over the calibration's ensemble (heading window, lapse, the
/// physics left uncertain) when SCENE.calibration.json lies beside it. The outcome column is not
/// read until the predictions are written.
#include <optional>
#include <string>
#include <vector>

#include "rigid/campaign/driver.hpp"
#include "rigid/shaketable/ensemble.hpp"
#include "rigid/shaketable/workflow.hpp"

namespace rigid::shaketable {

struct PredictionSettings {
  std::string scene, tests, out, lab_format;  ///< out: the predictions CSV
};

/// The predictions, once written, and their scores when the list has outcomes.
struct PredictionSummary {
  int tests = 0;
  std::size_t members = 0;
  std::string calibration;  ///< the calibration file averaged over ("" when none)
  std::vector<double> probability;
  std::optional<calibration::Scores> scores;
  /// Predicted P in ten bins against the observed share (with outcomes only)
  std::vector<calibration::ReliabilityBin> reliability;
};

class Predictor {
 public:
  Predictor(PredictionSettings settings, Callbacks callbacks);
  std::optional<campaign::CampaignOptions> next(const campaign::CampaignResult* previous);
  /// Rank 0, after the campaign: writes the CSV (test_no, record, the recording's measured
  /// GMRotI50 PGA and PGV/PGA, p_overturn, predicted), then scores it against the outcomes.
  PredictionSummary finish(const io::Cube& cube) const;

 private:
  PredictionSettings settings_;
  Callbacks callbacks_;
  io::LabTestList tests_;
  LabInput lab_;
  Ensemble ensemble_;
  bool prepared_ = false;
};

}  // namespace rigid::shaketable
