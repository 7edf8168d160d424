#pragma once
/// What a calibrated scene's predictions average over (SCENE.calibration.json beside it), and the
/// designed job that simulates it.
#include <functional>
#include <string>
#include <vector>

#include "rigid/io/calibration_ensemble.hpp"
#include "rigid/io/job_file.hpp"
#include "rigid/shaketable/lab.hpp"

namespace rigid::shaketable {

/// A calibration's ensemble (io::CalibrationEnsemble, read by io: one owner of the document's
/// format) with what the shake-table predictions make of it. Without a calibration file: the scene
/// alone at heading 0, weight 1, no lapse.
struct Ensemble : io::CalibrationEnsemble {
  /// The weighted mean over members of calibration::member_probability (the share of the
  /// member's headings that overturned, `overturned(variant, rotation)`, with its lapse). The
  /// lapse is the lab's, not the rock's: `with_lapse` false leaves it out (a fragility).
  double probability(const std::function<bool(int, int)>& overturned, bool with_lapse = true) const;
};

/// The ensemble of a calibration file (read_calibration_document: whole, unedited, this format
/// version). Throws InputError naming the file for anything else, and for a member scene that
/// does not exist.
Ensemble load_calibration(const std::string& calibration_json);

/// The ensemble of the calibration file beside `scene` (SCENE.calibration.json: load_calibration),
/// or the scene alone.
Ensemble load_ensemble(const std::string& scene);

/// The designed job of a scene over its ensemble, as predict and fragility run it: the object
/// "rock" is the scene, each ensemble scene a variant (none without a calibration file), the
/// ensemble's headings its rotations, `lab` its recordings' format, each record "as recorded",
/// 5 s of free time. Records and scales are the caller's.
io::JobFile ensemble_job(const std::string& scene, const Ensemble& ensemble, const LabInput& lab);

/// The job every designed campaign starts from: one object "rock" on `scene`, seed 1, no stop
/// rule, scales "as recorded", 5 s of free time after each window, `lab`'s format.
io::JobFile designed_job(const std::string& scene, const LabInput& lab);

}  // namespace rigid::shaketable
