#pragma once
// What `rigid shaketable calibrate`, `predict` and `fragility` share: the physics a design varies,
// the calibration's ensemble, the strong-motion windows of the recorded table motions, the
// designed campaigns and the outcome grid read back from their cubes
// (docs/validation-shaketable.md).
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "rigid/calibration/outcome_model.hpp"
#include "rigid/campaign/driver.hpp"
#include "rigid/io/cube.hpp"
#include "rigid/io/design_job.hpp"
#include "rigid/io/lab_tests.hpp"
#include "rigid/motion/ground_motion.hpp"
#include "rigid/motion/lab_format.hpp"

namespace rigid::app::shaketable {

/// One physics variant of a design: which model of the scanned base, and the contact law.
struct Physics {
  std::string base;          ///< the base model's name (e.g. "flat_5mm")
  std::string base_scene;    ///< the scene of the base and contact model, settled with that contact (absolute path)
  double flatten_m = 0;      ///< how the base model was made: --flatten-base (unit: m)
  std::string contact = "rigid";
  double normal_stiffness = 1e8;  ///< penalty only: K_N = K_S (unit: N/m^1.5)
  double damping = 2;        ///< penalty only: Hunt-Crossley D (unit: s/m)
  double restitution = 0;    ///< rigid only (unit: 1)
  double friction = 0.6;     ///< unit: 1
  /// One line for tables: "flat_5mm penalty K=1e+06 D=2 mu=0.60".
  std::string label() const;
  /// The scene's [physics] keys of the contact law: contact and, for the penalty model, its
  /// stiffnesses (K_S = K_N) and damping.
  std::vector<std::pair<std::string, std::variant<double, std::string>>> contact_law_table() const;
  /// contact_law_table with friction and, for rigid contact, restitution: the whole law.
  std::vector<std::pair<std::string, std::variant<double, std::string>>> physics_table() const;
  /// The job's [[variant]] table: the scene (base and contact model) and the law's other values.
  std::vector<std::pair<std::string, std::variant<double, std::string>>> variant_table() const;
};

/// What a calibrated scene's predictions average over (SCENE.calibration.json beside it): each
/// member is one physics variant (a scene) seen over a window of headings, with a weight and the
/// lapse rate the fit found. Without that file: the scene alone at heading 0, weight 1, no lapse.
struct Ensemble {
  struct Member {
    int variant = 0;              ///< index into scenes
    std::vector<int> rotations;   ///< indices into rotations_deg
    double weight = 1, lapse = 0;
  };
  std::string json;                 ///< the calibration file read ("" when none)
  std::vector<std::string> scenes;  ///< absolute paths, one per variant (the scene itself without a file)
  std::vector<double> rotations_deg;  ///< every member's headings, sorted, as turns of the motion
  std::vector<Member> members;
  /// The weighted mean over members of lapse/2 + (1 - lapse) x (share of the member's headings
  /// that overturned); `overturned(variant, rotation)` says whether that cell overturned. The
  /// lapse is the lab's, not the rock's: `with_lapse` false leaves it out (a fragility).
  double probability(const std::function<bool(int, int)>& overturned, bool with_lapse = true) const;
};
Ensemble load_ensemble(const std::string& scene);

/// The designed job of a scene over its ensemble, as predict and fragility run it: the object
/// "rock" is the scene, each ensemble scene a variant (none without a calibration file), the
/// ensemble's headings its rotations, `lab_format_file` its recordings' format ("" the default).
/// Records, scales and the comment are the caller's.
io::DesignJob ensemble_job(const std::string& scene, const Ensemble& ensemble, const std::string& lab_format_file);

/// The options every shaketable command shares: --lab-format FILE (the recordings' format) and
/// --progress (auto, bar, log or none).
void add_recording_options(CLI::App& cmd, std::string& lab_format, std::string& progress);

/// The recordings' format: a TOML file's [lab] table, or the default (this lab's export).
struct LabInput {
  std::string format_file;
  motion::LabFormat format;
};
LabInput lab_input(const std::string& format_file);

/// The part of each test's motion that can move the rock: from 1 s before the first sample whose
/// acceleration exceeds `level_g` to 1 s after the last (the whole record when none does: 2 s).
/// A rock at rest on its base cannot start to rock or slide below its quasi-static toppling
/// acceleration, so with level = half of it nothing is cut that could decide the outcome, and the
/// run's free time after the window lets a rocking rock settle or fall.
io::DesignJob::Record strong_motion_window(const motion::GroundMotion& motion, const std::string& file, double level_g);
std::vector<io::DesignJob::Record> strong_motion_windows(const io::LabTestList& tests, const LabInput& lab,
                                                         double level_g);

/// The smallest quasi-static toppling acceleration of a scene's free block (unit: g).
double static_toppling_g(const std::string& scene);

/// The level of the strong-motion windows for these scenes (unit: g): half the weakest static
/// toppling acceleration when every scene has rigid contact (a rock at rest on a rigid support
/// cannot start to move below it); a tenth of it when one has penalty contact, whose compliant
/// support lets the rock rock below that acceleration: the window then only drops the table's
/// quiet lead-in and tail (docs/validation-shaketable.md measures what it changes).
double window_level_g(bool rigid_contact_only, double weakest_static_toppling_g);
/// window_level_g of these scenes' contact laws and their weakest static toppling.
double window_level_g(const std::vector<std::string>& scenes);

/// The outcome grid of a designed campaign's cube: variant v, test t (record t), heading h
/// (rotation index h). Throws InputError if a cell is not simulated or failed.
calibration::OutcomeGrid outcome_grid(const io::Cube& cube, const std::vector<double>& headings_deg);


/// Runs a command's designed campaigns in one MPI session (campaign::run_campaign_sequence), then
/// `finish` on rank 0 once they all completed; ends the process with the campaigns' status
/// (75 interrupted, 1 failed write) after MPI has ended.
void run_designed_campaigns(
    const std::function<std::optional<campaign::CampaignOptions>(const campaign::CampaignResult*)>& next,
    const std::function<void(const campaign::CampaignResult&)>& finish);

}  // namespace rigid::app::shaketable
