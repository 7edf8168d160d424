#pragma once
/// What a calibrated scene's predictions average over (SCENE.calibration.json beside it), and the
/// designed job that simulates it.
#include <functional>
#include <string>
#include <vector>

#include "rigid/io/job_file.hpp"
#include "rigid/shaketable/lab.hpp"

namespace rigid::shaketable {

/// Each member is one physics variant (a scene) seen over a window of headings, with a weight and
/// the lapse rate the fit found. Without a calibration file: the scene alone at heading 0, weight
/// 1, no lapse.
struct Ensemble {
  struct Member {
    int variant = 0;             ///< index into scenes
    std::vector<int> rotations;  ///< indices into rotations_deg
    double weight = 1, lapse = 0;
  };
  std::string json;                   ///< the calibration file read ("" when none)
  std::string json_sha256;            ///< its SHA-256 ("" when none): what a transfer or a cube records
  std::string physics;                ///< the calibrated physics in words (the file's "physics"; "" when none)
  std::vector<std::string> scenes;    ///< absolute paths, one per variant (the scene itself without a file)
  std::vector<double> rotations_deg;  ///< every member's headings, sorted, as turns of the motion
  std::vector<Member> members;
  /// The weighted mean over members of calibration::member_probability (the share of the
  /// member's headings that overturned, `overturned(variant, rotation)`, with its lapse). The
  /// lapse is the lab's, not the rock's: `with_lapse` false leaves it out (a fragility).
  double probability(const std::function<bool(int, int)>& overturned, bool with_lapse = true) const;
  /// Each scene's share of the members' weight (sums to 1), one per scene: what a field campaign
  /// weights its physics variants by (headings there are random, so members of one scene merge).
  std::vector<double> scene_weights() const;
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
