#pragma once
/// `rigid shaketable calibrate` as a workflow: fits a scanned rock's uncertain physics (its
/// heading on the table, the model of its rough base, the contact law and its compliance,
/// restitution, friction) to observed shake-table outcomes by maximum likelihood, over campaigns
/// it designs in stages: (1) every base model and contact law at a coarse ring of headings,
/// (2) the best of those, crossed with the impact law and friction, at a finer ring around their
/// best headings, (3...) edge extension: the values beside the best wherever it sits at an edge of
/// the design (design_extension.hpp), on stage 2's headings. The campaigns are ordinary campaigns (MPI, checkpoints,
/// resume); the caller runs each one `next` returns (docs/validation-shaketable.md).
#include <chrono>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "rigid/calibration/outcome_model.hpp"
#include "rigid/campaign/driver.hpp"
#include "rigid/campaign/output_lock.hpp"
#include "rigid/shaketable/design_extension.hpp"
#include "rigid/shaketable/lab.hpp"
#include "rigid/shaketable/physics.hpp"
#include "rigid/shaketable/workflow.hpp"

namespace rigid::shaketable {

/// One contact law a design compares: rigid, or the penalty model at this K_N.
struct ContactChoice {
  contact::ContactMethod method = contact::ContactMethod::rigid;
  double normal_stiffness = 0;  ///< penalty only (unit: N/m^1.5)
};

/// What a calibration compares and how (each value's range: check_settings).
struct CalibrationSettings {
  std::string scan, tests, out, lab_format;  ///< out: DIR/NAME
  std::string command_line;                  ///< the command as typed: the calibration file records it
  double scale = 1.0;                        ///< scan units to metres
  std::string up = "z";
  std::vector<double> flatten_base_m{0.005};  ///< base models (unit: m)
  std::vector<ContactChoice> contact_models{{contact::ContactMethod::rigid, 0},
                                            {contact::ContactMethod::penalty, 5e5},
                                            {contact::ContactMethod::penalty, 1e6},
                                            {contact::ContactMethod::penalty, 2e6}};
  std::vector<double> restitution{0.0, 0.5};
  std::vector<double> damping{2.0, 1.0, 4.0};  ///< unit: s/m
  std::vector<double> friction{0.6, 0.9};
  int headings = 12;             ///< stage 1: a full ring
  int keep = 1;                  ///< stage 2: the best stage-1 variants refined
  double refine_step_deg = 10;   ///< stage 2: heading step around each kept variant's best heading
  double tilt_deg = 30;          ///< overturned = tilted beyond this angle
  int max_vertices = 64;         ///< the rock's hull
  double pedestal_margin = 0.5;  ///< the table: overhang of the box under the rock (unit: m)
  /// Edge extension: at most this many stages after stage 2 (each a campaign of a few variants on
  /// stage 2's headings); 0 = none, the edges are then marked "at edge (budget)"
  int extend_stages = 3;
  /// Start over: the work folder of an earlier calibration into the same OUT is removed first (it
  /// is otherwise resumed, and refused when its inputs or settings differ)
  bool restart = false;
  std::string figure_format = "png";  ///< OUT.calibration.FORMAT: png, pdf or svg
};

/// Throws InputError naming the setting (as its flag) when a value is outside its range.
void check_settings(const CalibrationSettings& s);

/// What a calibration's work folder was started with, one "what: value" line each: the settings,
/// the SHA-256 of the scan, of the lab format and of the test list without its outcomes, and of
/// the outcomes on their own line (the second stage is designed on them). A rerun resumes only
/// where every line is the same.
std::string calibration_manifest(const CalibrationSettings& s, const io::LabTestList& tests);

/// A contact law as the command line names it: "rigid" or a penalty stiffness K_N in
/// [1e5, 1e13] N/m^1.5. Nothing for any other text.
std::optional<ContactChoice> parse_contact_choice(const std::string& text);

/// The import of `scan` as one base model (its base cut flat `flatten_m` above its lowest point)
/// into the scene prefix `out`, with the import settings of `s` (scale, up, hull, pedestal, tilt
/// rule): what calibrate and transfer import alike.
scan::ImportOptions base_model_import(const CalibrationSettings& s, const std::string& scan, double flatten_m,
                                      const std::string& out);

/// "flat_5mm": a base model's name from its depth.
std::string base_name(double flatten_m);

/// `count` headings on a full ring from 0 (unit: deg).
std::vector<double> heading_ring(int count);

/// Stage 1: every base model (its scene) with every contact law, the first impact law and friction.
std::vector<Physics> first_stage_physics(const std::map<double, std::string>& base_scenes,
                                         const CalibrationSettings& s);

/// Stage 2 from the stage-1 grid: the `keep` best variants, each crossed with every value of its
/// impact law (restitution for rigid, damping for penalty) and friction, at the headings within
/// two refine steps of its best heading.
struct SecondStage {
  std::vector<Physics> physics;
  std::vector<double> headings_deg;
  std::vector<std::string> kept;  ///< one line per kept variant, for the log
};
SecondStage second_stage_design(const calibration::OutcomeGrid& grid, const std::vector<int>& observed,
                                const std::vector<Physics>& stage1, const CalibrationSettings& s);

/// What each stage of a calibration does, for its progress lines, job file and JSON:
/// "stage 1 (every base model x contact law on a ring of 12 headings)".
std::string first_stage_purpose(const CalibrationSettings& s);
std::string second_stage_purpose();

/// The stiffness limits of every base model's scene together (the strictest of each), with the
/// other parameters' fixed limits: what edge extension stops at.
PhysicalLimits design_limits(const std::vector<std::string>& base_scenes);

/// What a finished calibration found, for the command to print.
struct CalibrationSummary {
  std::string label;  ///< the chosen physics
  double heading_deg = 0, heading_low_deg = 0, heading_high_deg = 0, spread_deg = 0, lapse = 0;
  calibration::Scores in_sample;
  /// Leave-one-motion-out; nothing with fewer than calibration::kMinCrossValidationGroups motions
  std::optional<calibration::Scores> cross_validated;
  std::string scene, json;
  std::string likelihood_table;  ///< what the calibration figure draws beside the JSON
  double wall_s = 0;
  std::vector<ParameterReport> parameters;  ///< the law's numeric parameters and the lapse, with their status
};

/// The calibration's stages: `next` returns each designed campaign in turn (nothing when done),
/// given the previous one's result; `finish` (rank 0, after the last) writes OUT.toml and
/// OUT.calibration.json.
class Calibrator {
 public:
  Calibrator(CalibrationSettings settings, Callbacks callbacks);
  std::optional<campaign::CampaignOptions> next(const campaign::CampaignResult* previous);
  CalibrationSummary finish() const;

 private:
  campaign::CampaignOptions prepare();
  /// Takes OUT's lock, then resumes the work folder only over the same inputs and settings (or
  /// starts it anew with --restart): all before the first write.
  void claim_work_folder(const std::string& manifest);
  campaign::CampaignOptions stage_options(int stage, const std::vector<Physics>& physics,
                                          const std::vector<double>& headings, const std::string& purpose) const;
  /// After stage 2 and each extension stage: the next extension stage, or nothing when done.
  std::optional<campaign::CampaignOptions> extend(const campaign::CampaignResult& previous);
  struct Stage {
    std::string purpose;
    std::vector<Physics> physics;
    std::vector<double> headings;
    std::optional<calibration::OutcomeGrid> grid;
  };
  CalibrationSettings settings_;
  Callbacks callbacks_;
  io::LabTestList tests_;
  std::vector<int> observed_, group_;
  std::vector<io::JobRecord> windows_;
  LabInput lab_;
  std::string work_;
  std::map<double, std::string> bases_;  ///< each base model's scene before settling, by depth
  PhysicalLimits limits_;
  std::vector<Stage> stages_;
  /// what is fitted: stage 2 and the extension stages joined (one heading list)
  std::optional<calibration::OutcomeGrid> fitted_;
  std::vector<Physics> fitted_physics_;
  calibration::SearchSettings search_;
  std::vector<ParameterReport> parameters_;
  bool done_ = false;
  std::unique_ptr<campaign::OutputLock> lock_;  ///< OUT.lock, held for the whole calibration
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

}  // namespace rigid::shaketable
