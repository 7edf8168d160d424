#pragma once
/// `rigid shaketable fragility` as a workflow: the campaign of the (calibrated) scene's fragility
/// from the lab's recorded motions scaled over a grid of PGAs, and the inputs of the fit that puts
/// it beside the lab's own (src/python/rigidpy/shaketable.py).
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "rigid/campaign/driver.hpp"
#include "rigid/shaketable/ensemble.hpp"
#include "rigid/shaketable/workflow.hpp"

namespace rigid::shaketable {

struct FragilitySettings {
  std::string scene, tests, out, lab_format;  ///< out: prefix DIR/NAME of OUT.fragility.*
  double min_pga_g = 0.02;
  double max_pga_g = 0;  ///< 0: 1.25 x the largest measured PGA
  int per_decade = 24;
  std::string figure_format = "png";  ///< OUT.fragility.FORMAT: png, pdf or svg
  /// PGV/PGA bin edges (unit: s), at least two, positive, increasing; empty: three bins of a third
  /// of the motions each (chosen by the fit)
  std::vector<double> bins_s;
};

/// Throws InputError naming the flag when the settings cannot be run (checked before the campaign).
void check_settings(const FragilitySettings& s);

/// A geometric grid from `low` to at least `high` (the lognormal's own spacing: as many points
/// below the median as above it), each value rounded to 4 significant digits so that the job
/// states it, and the cube stores it, exactly.
std::vector<double> pga_grid(double low, double high, int per_decade);

class FragilityDesign {
 public:
  FragilityDesign(FragilitySettings settings, Callbacks callbacks);
  std::optional<campaign::CampaignOptions> next(const campaign::CampaignResult* previous);
  /// Rank 0, after the campaign: what the fit reads beside the cube (the tests as measured, which
  /// test each motion is, the ensemble's P(overturn) per motion and PGA); returns the work folder.
  std::filesystem::path write_fit_inputs(const io::Cube& cube) const;
  std::string cube_path() const { return (work_ / "fragility.h5").string(); }
  /// The physics the model runs, in one line for the figure's title: the calibration's, or the
  /// scene's own when no calibration file lies beside it.
  std::string physics_title() const;

 private:
  struct Measured {
    double pga_g = 0, pgv_pga_s = 0;
  };
  FragilitySettings settings_;
  Callbacks callbacks_;
  io::LabTestList tests_;
  LabInput lab_;
  Ensemble ensemble_;
  std::vector<Measured> measured_;        ///< per test
  std::vector<std::size_t> motion_test_;  ///< per motion (cube record): the test whose recording it is
  std::filesystem::path work_;
  bool prepared_ = false;
};

}  // namespace rigid::shaketable
