#pragma once
/// A job: which objects, which records, which scales and rotations, how to simulate, where to
/// write. A campaign reads one from a job file (job/load.hpp); `rigid run` is a job of one cell
/// (one_cell_job). Plain data, with the cases of its cells.
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "rigid/io/job_file.hpp"
#include "rigid/job/cells.hpp"
#include "rigid/job/run_overrides.hpp"
#include "rigid/motion/lab_format.hpp"
#include "rigid/scenario/accuracy.hpp"
#include "rigid/scenario/case.hpp"
#include "rigid/scenario/variant.hpp"

namespace rigid::job {

/// One record (a ground-motion set) of a job, as the job file gives it.
using JobRecord = io::JobRecord;
using io::kAsRecordedScale;

/// One object (a scene) of a job, in one of the job's variants.
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

struct Job {
  std::string path;        ///< the job file ("" for a job built in memory)
  std::string text;        ///< its contents, stored in the cube
  std::string hash;        ///< job_hash: a changed job is refused on resume
  std::string output;      ///< HDF5 cube path
  std::uint64_t seed = 1;  ///< keys the rotation angles
  /// What the campaign simulates: every [[object]] in every variant, object-major (index
  /// base * variants + variant), so the plan, stop rule, journal and cube work per variant.
  std::vector<JobObject> objects;
  /// The [sweep] or [[variant]] tables, or a calibrated object's members: count() == 0 when the
  /// job has none.
  scenario::VariantSpace variants;
  /// The calibrated object's calibration (then the job's only object; its variants are the
  /// calibration's member scenes, weighted): nothing when no object takes one.
  std::optional<io::JobCalibration> calibration;
  /// Line of the [sweep] table or of each [[variant]] (one entry for a sweep): where errors about
  /// a variant that a scene cannot take point.
  std::vector<long> variant_lines;
  /// Variants per [[object]] (1 when the job has none).
  int variant_count() const { return variants.count() > 0 ? variants.count() : 1; }
  /// Number of [[object]]s.
  int base_objects() const { return static_cast<int>(objects.size()) / variant_count(); }
  std::vector<JobRecord> records;
  std::string record_list;       ///< the record-list file (resolved path), empty for [[record]] tables
  std::vector<double> scales_g;  ///< target GMRotI50 PGA of each scale, increasing (unit: g)
  /// scales = "as recorded": scales_g is {kAsRecordedScale}, every record simulated as it is
  bool as_recorded() const { return scales_g.size() == 1 && scales_g[0] == kAsRecordedScale; }
  /// The job's [lab] table: how its lab records ([[record]] lab = ...) are read and processed
  motion::LabFormat lab_format;
  /// The target PGA each scale's simulations are driven with, when not scales_g itself (empty);
  /// see io::JobFile::drive_scales_g.
  std::vector<double> drive_scales_g;
  /// The target PGA (g) the simulations of scale s are driven with.
  double drive_scale_g(std::size_t s) const { return drive_scales_g.empty() ? scales_g[s] : drive_scales_g[s]; }
  int rotations = 2;  ///< random rotations per (record, scale)
  /// Fixed rotation angles instead of random ones (unit: deg), one per rotation index; empty:
  /// random angles keyed by the seed.
  std::vector<double> rotation_angles_deg;
  /// Stop raising the scale for a record once this many consecutive scales overturned at every
  /// rotation (the study's rule); 0 disables it.
  int stop_after = 10;
  /// What the job file's [run] table and the command line set; apply_overrides() derives the
  /// four fields below from it.
  RunOverrides overrides;
  scenario::RunSettings run;                          ///< physics and accuracy settings of every simulation
  std::string accuracy = scenario::kDefaultAccuracy;  ///< accuracy preset of `run`
  /// Which model simulates: the engine, or the 2D Housner reference (driven by the record's x
  /// component; scenes must admit it).
  scenario::Engine engine = scenario::Engine::dem3d;
  /// Contact model for every object; nothing: each scene's own [physics] contact.
  std::optional<contact::ContactMethod> contact;
  /// Line of the job's dt_s (else safety, else [run]) key: where errors about the step point.
  long run_line = 0;
  double checkpoint_interval_s = 30;  ///< unit: s
  double grace_s = 30;                ///< time in-flight tasks get after a stop signal (unit: s)
  /// What the reader left out and the user should hear of, one line each (an optional object
  /// whose scene does not exist: [[object]] optional = true).
  std::vector<std::string> notes;

  /// The job's cells: objects (with variants) x records x scales x rotations.
  CellGrid cells() const { return {int(objects.size()), int(records.size()), int(scales_g.size()), rotations}; }
};

/// Sets the job's run settings, model, contact model and accuracy preset from its overrides:
/// the one place a job's overrides are applied.
void apply_overrides(Job& job);

/// The one rule of the campaign's checkpoint interval and grace period (unit: s), whether a job
/// file or a flag gives them: "" when admissible, else what is wrong ("must be ...").
std::string checkpoint_interval_problem(double interval_s);
std::string grace_problem(double grace_s);

/// A job of one cell: one object, one record simulated as it is (no PGA scaling, no rotation),
/// with these overrides applied. `rigid run` simulates such a job.
Job one_cell_job(const RunOverrides& overrides);

/// The one cell of a one_cell_job simulated on its model (`rigid run` and rigidpy.run): its run,
/// or the simulation's error rethrown; a non-finite state is std::runtime_error, never an
/// outcome ("survived" would be a wrong answer).
scenario::RunOutcome simulate_one_cell(const Job& job, const scenario::Model& model);

/// The rotation of a cell: its fixed angle when the job lists them, else the random one of its
/// [[object]] (the same for all of the object's variants).
double cell_rotation_deg(const Job& job, const Cell& cell);

/// The case of a cell: the job's scale as target PGA, the cell's rotation.
scenario::Case case_of(const Job& job, const Cell& cell);

/// What job_hash hashes: the job text (with the command-line overrides appended) and the
/// accuracy preset, i.e. every physics-relevant setting that is not in an input file.
std::string job_settings_text(const Job& job);

/// The hash that identifies a job's results (Job::hash): the SHA-256 (io::sha256_hex, 64 hex
/// digits) of job_settings_text. A resume with other settings or another preset is refused.
std::string job_hash(const Job& job);

/// The hash cubes written before the SHA-256 one carry (FNV-1a 64 of the same text, 16 hex
/// digits): such a cube still resumes with the job that wrote it.
std::string legacy_job_hash(const Job& job);

}  // namespace rigid::job
