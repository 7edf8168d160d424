#pragma once
/// The physics ensemble a calibration document carries (rigid/io/calibration_document.hpp): its
/// member scenes, headings, weights and lapses, read once here for the shake-table workflow
/// (shaketable::Ensemble) and for a campaign's calibrated object (job file `calibration = ...`).
#include <string>
#include <vector>

#include "rigid/io/json.hpp"

namespace rigid::io {

/// Each member is one physics variant (a scene) seen over a window of headings, with a weight and
/// the lapse rate the fit found.
struct CalibrationEnsemble {
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
  /// Each scene's share of the members' weight (sums to 1), one per scene: what a field campaign
  /// weights its physics variants by (headings there are random, so members of one scene merge).
  std::vector<double> scene_weights() const;
};

/// The ensemble of a calibration file (read_calibration_document: whole, unedited, this format
/// version). Throws InputError naming the file for anything else, and for a member scene that
/// does not exist.
CalibrationEnsemble read_calibration_ensemble(const std::string& calibration_json);

/// An ensemble member's field `key` as a finite number. Throws InputError naming `file` otherwise.
double member_number(const Json& member, const char* key, const std::string& file);

/// What a cube records of a calibration: the envelope's rigid_version and created, its scene, the
/// physics in words, the chosen physics (`parameters`) and the scores present (in_sample,
/// cross_validated), as one JSON object.
Json calibration_summary(const Json& document);

}  // namespace rigid::io
