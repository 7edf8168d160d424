#pragma once
/// A campaign job as read from a job file: which objects, which records, which scales and
/// rotations, how to simulate, where to write. Plain data; rigid::io::load_job fills it.
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "rigid/motion/lab_format.hpp"
#include "rigid/scenario/accuracy.hpp"
#include "rigid/scenario/case.hpp"
#include "rigid/scenario/scene.hpp"
#include "rigid/scenario/variant.hpp"

namespace rigid::scenario {

/// One object (a scene) of a campaign, in one of the job's variants.
struct JobObject {
  std::string name;   ///< the [[object]]'s name, unique among them; the HDF5 group name
  std::string scene;  ///< the [[object]]'s scene file (resolved path)
  /// The variant's alternative scene file (another model of the same rock), "" when it has none:
  /// what is simulated when given.
  std::string variant_scene;
  /// The file simulated: the variant's alternative scene, else the object's.
  const std::string& simulated_scene() const { return variant_scene.empty() ? scene : variant_scene; }
  std::string state;  ///< saved equilibrium state to start from (resolved path), may be empty
  int base = -1;      ///< index of the [[object]] in the job file; -1: the object's own index
  int variant = -1;   ///< index in Job::variants, -1 when the job has none
  /// "NAME" without variants, "NAME [vK]" with them: how tables and messages name it.
  std::string label() const { return variant < 0 ? name : name + " [v" + std::to_string(variant) + "]"; }
};

/// One record (a ground-motion set) of a campaign.
struct JobRecord {
  std::string name;        ///< unique record name
  std::string spec;        ///< motion-set spec with resolved paths (see io::resolve_set); lab: the file
  /// A lab recording ([[record]] lab = "FILE"), read with Job::lab_format, instead of an AT2 set
  bool lab = false;
  double start = 0;        ///< window start (unit: s)
  double end = std::numeric_limits<double>::infinity();  ///< window end (unit: s)
  std::string earthquake;  ///< from the record list, may be empty
  double listed_pga_g = 0;     ///< GMRotI PGA given by the list, 0 if none (unit: g)
  double listed_pgv_cm_s = 0;  ///< GMRotI PGV given by the list, 0 if none (unit: cm/s)
  /// align = "resample": components of unequal dt or length resampled to a common dt and padded
  /// (else only lengths within 1 % at equal dt are padded, motion::make_ground_motion)
  bool resample = false;
  std::string origin_file;  ///< where the record is given (job file or record list), for messages
  long origin_line = 0;     ///< its line there
};

/// The one scale of a campaign "as recorded" ([campaign] scales = "as recorded"): each record at
/// factor 1, no PGA scaling (a target PGA of 0 scales nothing, scenario::case_motion).
inline constexpr double kAsRecordedScale = 0.0;

struct Job {
  std::string path;        ///< the job file
  std::string text;        ///< its contents, stored in the cube
  std::string hash;        ///< hex hash of text (FNV-1a 64): a changed job is refused on resume
  std::string output;      ///< HDF5 cube path
  std::uint64_t seed = 1;  ///< keys the rotation angles
  /// What the campaign simulates: every [[object]] in every variant, object-major (index
  /// base * variants + variant), so the plan, stop rule, journal and cube work per variant.
  std::vector<JobObject> objects;
  /// The [sweep] or [[variant]] tables: count() == 0 when the job has none.
  VariantSpace variants;
  /// Line of the [sweep] table or of each [[variant]] (one entry for a sweep): where errors about
  /// a variant that a scene cannot take point.
  std::vector<long> variant_lines;
  /// Variants per [[object]] (1 when the job has none).
  int variant_count() const { return variants.count() > 0 ? variants.count() : 1; }
  /// Number of [[object]]s.
  int base_objects() const { return static_cast<int>(objects.size()) / variant_count(); }
  std::vector<JobRecord> records;
  std::string record_list;        ///< the record-list file (resolved path), empty for [[record]] tables
  std::vector<double> scales_g;   ///< target GMRotI50 PGA of each scale, increasing (unit: g)
  /// scales = "as recorded": scales_g is {kAsRecordedScale}, every record simulated as it is
  bool as_recorded() const { return scales_g.size() == 1 && scales_g[0] == kAsRecordedScale; }
  /// The job's [lab] table: how its lab records ([[record]] lab = ...) are read and processed
  motion::LabFormat lab_format;
  /// The target PGA each scale's simulations are driven with, when not scales_g itself (empty):
  /// a "start:stop:step" range keeps its float sums start + i * step (0.30000000000000004), which
  /// the campaigns before scales_g held the stated decimals ran with. One ulp more or less in the
  /// drive changes the chaotic outcome of a few cells, so the sums keep those cubes reproducible.
  std::vector<double> drive_scales_g;
  /// The target PGA (g) the simulations of scale s are driven with.
  double drive_scale_g(std::size_t s) const { return drive_scales_g.empty() ? scales_g[s] : drive_scales_g[s]; }
  int rotations = 2;              ///< random rotations per (record, scale)
  /// Fixed rotation angles instead of random ones ([campaign] rotation_angles_deg; unit: deg):
  /// one per rotation index, e.g. [0.0] drives every block with the x component along x, as the
  /// study's 2D comparison did. Empty: random angles keyed by the seed.
  std::vector<double> rotation_angles_deg;
  /// Stop raising the scale for a record once this many consecutive scales overturned at every
  /// rotation (the study's rule); 0 disables it.
  int stop_after = 10;
  RunSettings run;                ///< physics and accuracy settings of every simulation
  /// Accuracy preset of `run` (scenario/accuracy.hpp): [run] accuracy, or --accuracy; load_job and
  /// the campaign driver apply it (with accuracy_overrides) to `run`.
  std::string accuracy = kDefaultAccuracy;
  /// The [run] keys dt_s, safety and integrator, which override the preset's values.
  AccuracyOverrides accuracy_overrides;
  /// Which model simulates: the engine, or the 2D Housner reference (driven by the record's x
  /// component; scenes must admit it). [run] model = "dem3d" | "rocking2d", or --model.
  ModelKind model = ModelKind::dem3d;
  /// Contact model for every object ("rigid" or "penalty"), from [run] contact or --contact;
  /// empty: each scene's own [physics] contact.
  std::string contact;
  /// Line of the job's dt_s (else safety, else [run]) key: where errors about the step point.
  long run_line = 0;
  double checkpoint_interval = 30;  ///< unit: s
  double grace = 30;              ///< time in-flight tasks get after a stop signal (unit: s)
  /// What the reader left out and the user should hear of, one line each (an optional object
  /// whose scene does not exist: [[object]] optional = true).
  std::vector<std::string> notes;
};

}  // namespace rigid::scenario
