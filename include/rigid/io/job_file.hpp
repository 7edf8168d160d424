#pragma once
/// Campaign job files (TOML), read as written: one reader per section, each checking what the
/// file's format alone decides (unknown keys, types, missing files, an empty or non-increasing
/// scale list, bad windows), naming the file and line. What the values mean for a run (the
/// [run] settings, the variants of each object, the cell count) is the job module's
/// (rigid/job/load.hpp), which turns a JobFile into a job::Job.
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "rigid/motion/lab_format.hpp"
#include "rigid/scenario/variant.hpp"

namespace rigid::io {

/// The one scale of a campaign "as recorded" ([campaign] scales = "as recorded"): each record at
/// factor 1, no PGA scaling (a target PGA of 0 scales nothing, scenario::case_motion).
inline constexpr double kAsRecordedScale = 0.0;

/// One [[object]] as written (paths resolved against the job file).
struct JobFileObject {
  std::string name;   ///< its name (default: the scene's stem), checked as an HDF5 group name
  std::string scene;  ///< scene file (resolved path)
  std::string state;  ///< saved equilibrium state (resolved path), may be empty
};

/// An object whose physics comes from a shake-table calibration ([[object]] calibration = "FILE"):
/// the ensemble's distinct member scenes are the job's variants (key `scene`), each weighted by
/// its members' share of the weight. The members' headings and lapse are the lab's and are not
/// used: a field rock's heading is unknown, so its rotations stay random as for any object.
struct JobCalibration {
  std::string path;             ///< the calibration file (resolved path)
  std::string sha256;           ///< its SHA-256 as read: one of the job's input digests
  std::vector<double> weights;  ///< each variant's weight (io::CalibrationEnsemble::scene_weights)
  std::string summary_json;     ///< io::calibration_summary of the document, compact JSON
  long line = 0;                ///< the [[object]]'s line in the job file
};

/// One record (a ground-motion set) of a campaign.
struct JobRecord {
  std::string name;  ///< unique record name
  std::string spec;  ///< motion-set spec with resolved paths (see io::resolve_set); lab: the file
  /// A lab recording ([[record]] lab = "FILE"), read with the job's lab format, instead of an AT2 set
  bool lab = false;
  double start = 0;                                      ///< window start (unit: s)
  double end = std::numeric_limits<double>::infinity();  ///< window end (unit: s)
  std::string earthquake;                                ///< from the record list, may be empty
  double listed_pga_g = 0;                               ///< GMRotI PGA given by the list, 0 if none (unit: g)
  double listed_pgv_cm_s = 0;                            ///< GMRotI PGV given by the list, 0 if none (unit: cm/s)
  /// align = "resample": components of unequal dt or length resampled to a common dt and padded
  /// (else only lengths within 1 % at equal dt are padded, motion::make_ground_motion)
  bool resample = false;
  std::string origin_file;  ///< where the record is given (job file or record list), for messages
  long origin_line = 0;     ///< its line there
};

/// A text-valued [run] key as written: `text` is nothing when the value is not a string.
struct RunText {
  std::optional<std::string> text;
  long line = 0;  ///< where an error about its value points
};

/// The [run] table as written (every key optional).
struct RunTable {
  std::optional<RunText> model, contact, effects, accuracy, integrator;
  std::optional<double> duration_s, free_time_s, dt_s, safety;
  std::optional<double> solver_tolerance, solver_max_sweeps;
  long line = 0;         ///< the [run] table's line (0 when the job has none)
  long solver_line = 0;  ///< line of solver_tolerance, else solver_max_sweeps, else [run]
  long step_line = 0;    ///< line of dt_s, else safety, else [run]: where errors about the step point
};

/// A job file as written.
struct JobFile {
  std::string path;    ///< the job file
  std::string text;    ///< its contents, with a note per optional object left out
  std::string output;  ///< [campaign] output, default: the job file's stem + ".h5"
  std::uint64_t seed = 1;
  long campaign_line = 0;        ///< line of [campaign]
  std::vector<double> scales_g;  ///< stated scales (g), increasing; {kAsRecordedScale} for "as recorded"
  /// A "start:stop:step" range's float sums start + i * step (0.30000000000000004), which the
  /// campaigns before scales_g held the stated decimals ran with: one ulp more or less in the
  /// drive changes the chaotic outcome of a few cells, so the sums keep those cubes reproducible.
  /// Empty for a list.
  std::vector<double> drive_scales_g;
  int rotations = 2;
  std::vector<double> rotation_angles_deg;  ///< unit: deg; empty: random angles
  int stop_after = 10;
  double checkpoint_interval_s = 30;   ///< unit: s
  double grace_s = 30;                 ///< unit: s
  std::vector<JobFileObject> objects;  ///< the [[object]]s present (optional absent ones left out)
  scenario::VariantSpace variants;     ///< [sweep] or [[variant]]; count() == 0 without
  std::vector<long> variant_lines;     ///< line of the [sweep] or of each [[variant]]
  std::vector<JobRecord> records;      ///< names made unique
  std::string record_list;             ///< the record-list file (resolved path), or empty
  motion::LabFormat lab_format;        ///< the [lab] table
  RunTable run;
  std::vector<std::string> notes;  ///< what was left out, one line each
  /// The calibrated object's calibration (a job has at most one, and then no other object and no
  /// [sweep] or [[variant]]: its members are the variant axis)
  std::optional<JobCalibration> calibration;
};

/// Reads a job file. Scene, state and record-list paths are relative to the job file; the
/// output path is relative to the current directory. Throws rigid::InputError naming file and line.
JobFile read_job_file(const std::string& path);

/// The mirror of read_job_file: writes `job` as a job file that read_job_file reads back as the same
/// settings, objects, variants, records, [lab] and [run] (paths written absolute; a sampled
/// [sweep] as the [[variant]] list it drew; a record list by its file). Keys at the reader's
/// defaults are left out, but for seed and stop_after, which a reader of the file should see.
/// `comment` becomes `#` lines at the top. Written through a temporary file renamed into place
/// (a half-written job never stands under the name); InputError naming the path when it cannot be.
void write_job_file(const std::string& path, const JobFile& job, const std::string& comment = "");

}  // namespace rigid::io
