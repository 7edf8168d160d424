#pragma once
/// The fragility cube of a campaign: one HDF5 file per job, one group per object, datasets
/// indexed [record, scale, rotation], led by [variant] when the job sweeps parameters. Written
/// whole to FILE.tmp, flushed, then renamed over FILE, so a kill at any instant leaves either
/// the previous or the new complete file.
#include <cstddef>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "rigid/scenario/case.hpp"
#include "rigid/statistics/cells.hpp"
#include "rigid/statistics/fragility_surface.hpp"

namespace rigid::io {

/// The values of a cube's `outcome` dataset (defined with the case they come from).
using CellOutcome = scenario::CellOutcome;

/// Per-record metadata stored beside the cube.
struct RecordMeta {
  std::string name;            ///< record (set) name, e.g. "stochastic_s1"
  std::string source;          ///< the set spec the motion was read from
  std::string earthquake;      ///< from the record list, may be empty
  double start_s = 0;          ///< time window start (unit: s)
  double end_s = 0;            ///< time window end (unit: s)
  double gmroti_pga_g = 0;     ///< GMRotI50 PGA of the windowed record as computed (unit: g)
  double gmroti_pgv_cm_s = 0;  ///< GMRotI50 PGV (unit: cm/s)
  double pgv_pga_s = 0;        ///< PGV/PGA (unit: s)
  double listed_pga_g = 0;     ///< GMRotI PGA given by the record list, 0 if none (unit: g)
  double listed_pgv_cm_s = 0;  ///< GMRotI PGV given by the record list, 0 if none (unit: cm/s)
  std::string inputs;          ///< SHA-256 of its motion files, sha256sum lines (io/provenance.hpp)
  std::string alignment;       ///< how its components were aligned, "" when they matched
};

/// One parameter of a campaign's variant axis (the job's [sweep] or [[variant]] tables): its
/// value in each variant. Stored as /variants/<name>, so the name must be a valid HDF5 link name.
struct VariantParameter {
  std::string name;                 ///< the job file's name, e.g. "friction"
  std::string units;                ///< UDUNITS-2 ("1", "m", "kg m-3", "s m-1", ...); "" for text
  std::string description;          ///< one line for the file's readers
  std::vector<double> values;       ///< [variant]; empty for a text parameter
  std::vector<std::string> labels;  ///< [variant]; empty for a numeric parameter (e.g. contact)
};

/// The variant axis of a campaign: every object is simulated once per variant, with the
/// parameters' values of that variant. count 0: the job has no variants (the cube's layout is
/// then schema_version 1, as before the axis existed).
struct VariantTable {
  std::string method;                        ///< how the values were drawn: "lhs", "grid" or "list"
  std::uint64_t seed = 0;                    ///< the sweep's seed, so a draw can be repeated
  int count = 0;                             ///< number of variants V; 0: the job has no variants
  std::vector<VariantParameter> parameters;  ///< in job order
};

/// Results of one object (scene) of the campaign, or with variants of one (object, variant).
/// Every array has records.size() * scales_g.size() * rotations elements, row-major
/// [record][scale][rotation].
struct ObjectCube {
  std::string name;   ///< object name (HDF5 group name), the base object's
  std::string scene;  ///< scene file as given in the job, the base object's
  /// Variant index 0..count-1 (Cube::variants), -1 in a cube without variants. With variants the
  /// fields below all belong to this variant: physics, rocking parameters and cells differ.
  int variant = -1;
  /// SHA-256 of every file the object was built from (scene, model, STLs, state), sha256sum lines
  std::string inputs;
  /// The object's own physics and run settings (contact model and law, density, failure rule,
  /// time step, accuracy, effects) as a JSON object; empty in cubes written before it existed
  std::string physics_json;
  /// Rocking parameters of a single-block object (analysis::rocking_parameters), NaN when the
  /// object has none (stacks): written as attributes alpha_rad, p_rad_s only when finite.
  double alpha_rad = std::numeric_limits<double>::quiet_NaN();
  double p_rad_s = std::numeric_limits<double>::quiet_NaN();
  /// ...and the rest of them, written only with alpha_rad: R, the weakest direction, alpha per
  /// azimuth of the ground acceleration (RockingParameters::alpha_by_azimuth, azimuth k * 360 / n
  /// degrees) and the support polygon's corners relative to the centroid, flattened x0 y0 x1 y1...
  double rocking_radius_m = std::numeric_limits<double>::quiet_NaN();
  double weakest_azimuth_deg = std::numeric_limits<double>::quiet_NaN();
  std::vector<double> alpha_by_azimuth_rad;
  std::vector<double> support_polygon_m;
  std::vector<std::int8_t> outcome;          ///< CellOutcome values
  std::vector<double> rotation_deg;          ///< rotation of the horizontals about z (unit: deg)
  std::vector<double> failure_time_s;        ///< NaN when none (unit: s)
  std::vector<double> max_tilt_deg;          ///< NaN when not simulated (unit: deg)
  std::vector<double> max_slip_m;            ///< NaN when not simulated (unit: m)
  std::vector<double> wall_s;                ///< wall time of the simulation, NaN when none (unit: s)
  std::vector<std::int32_t> failure_reason;  ///< scenario::FailureReason codes
  /// The error's text of each failed cell, "" elsewhere; empty vector: none stored (older cubes)
  std::vector<std::string> failure_message;
  /// Steps of each cell's run whose contact solve stopped at its sweep cap without converging
  /// (scenario::RunOutcome::unconverged_steps; 0 for penalty contact and the 2D model), -1 where
  /// not simulated or not recorded; empty vector: none stored (older cubes). A diagnostic, outside
  /// the cells' checksum.
  std::vector<std::int32_t> unconverged_steps;
};

/// The calibration a calibrated object's physics comes from (job file `calibration = ...`),
/// written as attributes of its group: calibration, calibration_sha256, calibration_weights (one
/// per variant) and calibration_summary (JSON: the document's rigid_version, created, scene,
/// physics in words, chosen parameters and scores).
struct CubeCalibration {
  std::string path;
  std::string sha256;
  std::vector<double> weights;
  std::string summary_json;
};

/// Everything written to the file.
struct Cube {
  std::vector<RecordMeta> records;
  std::vector<double> scales_g;  ///< target GMRotI50 PGA of each scale (unit: g)
  int rotations = 2;             ///< rotations per (record, scale)
  /// The variant axis; variants.count == 0 when the job has none.
  VariantTable variants;
  /// With a calibrated object (the cube's only one, its variants the calibration's member
  /// scenes): where its physics comes from. Not read back by read_cube.
  std::optional<CubeCalibration> calibration;
  /// Without variants one per object, in job order. With variants variants.count per base object,
  /// consecutive and in variant order (variant 0..count-1, same name and scene): the campaign's
  /// internal object o * count + v is base object o in variant v.
  std::vector<ObjectCube> objects;
  // provenance and settings, stored as root attributes
  std::string job_text;          ///< the job file as read
  std::string job_hash;          ///< hex SHA-256 of the job settings (job::job_hash; 16 hex digits: an older cube)
  std::string software_version;  ///< e.g. "0.1.0 (abc1234)"
  std::string physics_json;      ///< physics and accuracy settings as a JSON object
  /// SHA-256 of the job's settings (job_settings_text) and its files (job file, record list),
  /// sha256sum lines; the settings line has the path "(settings)"
  std::string job_inputs;
  /// SHA-256 over job_inputs and every object's and record's inputs: one digest that changes
  /// when any input of any cell does (empty in cubes written before it existed)
  std::string inputs_sha256;
  std::uint64_t seed = 0;
  /// Edges of the PGV/PGA bins of the fragility surface (unit: s), 10 edges = 9 bins.
  std::vector<double> pgv_pga_edges_s;
  /// The schema_version read_cube found in the file (0: not read from a file); write_cube always
  /// writes kCubeSchemaVersion.
  int schema_version = 0;
};

/// Versions of the file layout (root attribute `schema_version`; the layouts are described at the
/// top of src/io/cube.cpp): 1, a cube without variants; 2, one with variants; 3, either (the
/// variant axis present when /variants is) with checksums that every reader verifies over
/// everything a result depends on: the axes, the records and the variant table (root attribute
/// axes_sha256) and each object's cells (datasets_sha256). write_cube writes 3; read_cube reads
/// 1 to 3 (a cube of version 1 or 2 without a checksum is one written before it existed:
/// old_cube_warning) and rejects newer versions.
inline constexpr int kCubeSchemaVersionWithoutVariants = 1;
inline constexpr int kCubeSchemaVersionWithVariants = 2;
inline constexpr int kCubeSchemaVersionChecksummed = 3;
inline constexpr int kCubeSchemaVersion = kCubeSchemaVersionChecksummed;  ///< written, and the newest read

/// What a reader should say of a cube read_cube returned: "" for a cube of the current schema
/// (every checksum present and verified), else a warning that its axes and records (and, before
/// the cell checksums existed, its cells) could not be checked.
std::string old_cube_warning(const std::string& path, const Cube& cube);

/// How tables name an object: its name, followed by " [vK]" for variant K in a cube with variants
/// (e.g. "rock [v3]"), so rows of one base object's variants stay apart.
std::string object_label(const ObjectCube& object);

/// Name of an `outcome` code as in the cube's flag_meanings ("not_run", "survived", "overturned",
/// "inferred", "failed"); "unknown" for any other code.
const char* outcome_name(int code);

/// Name of a `failure_reason` code as in the cube's flag_meanings ("none", "exception",
/// "non_finite", "worker_lost"); "unknown" for any other code.
const char* failure_reason_name(int code);

/// The edges a cube uses: cube.pgv_pga_edges_s, or statistics::default_pgv_pga_edges() when it is
/// empty.
std::vector<double> pgv_pga_edges(const Cube& cube);

/// The shape of each object's cell arrays: records x scales x rotations (0 rotations when the
/// cube's count is negative).
statistics::CellShape cell_shape(const Cube& cube);

/// Problems that make a cube unwritable (array sizes, object names, bin edges, outcome codes, the
/// variant table and the objects' variant order), one message; empty when the cube is
/// consistent. write_cube and the derived products check this.
std::string cube_problem(const Cube& cube);

// The derived products of one object: the cube's arrays handed to the rules of the statistics
// module (statistics/overturn.hpp, statistics/fragility_surface.hpp), after the checks of
// cube_problem. Each throws std::invalid_argument when the cube's rotations or edges, or
// `object`'s arrays, are inconsistent.

/// statistics::overturn_probability of the object's outcomes: per (record, scale), row-major
/// [record][scale], overturned / known cells over the rotations, NaN where none is known.
std::vector<double> overturn_probability(const Cube& cube, const ObjectCube& object);

/// statistics::mean_over_records of overturn_probability: per scale, the mean over the records
/// whose probability is known (the campaign summary's table).
std::vector<double> mean_overturn_probability(const Cube& cube, const ObjectCube& object);

using FragilitySurface = statistics::FragilitySurface;

/// statistics::fragility_surface of overturn_probability, binned by each record's
/// RecordMeta::pgv_pga_s with pgv_pga_edges(cube).
FragilitySurface fragility_surface(const Cube& cube, const ObjectCube& object);

/// Writes the cube atomically (PATH.tmp then rename) with dimension scales, units and
/// descriptions on every dataset, and the derived products (layout: src/io/cube.cpp):
/// /objects/<object>/probability [record, scale] (overturned / (overturned + survived + inferred
/// counted as overturned), NaN where nothing is known) and /objects/<object>/fragility
/// [scale, pgv_pga bin] (mean probability of the records in each PGV/PGA bin, NaN for empty bins).
/// Throws rigid::InputError(path, 0, ...) on failure.
void write_cube(const std::string& path, const Cube& cube);

/// Switches off HDF5's automatic printing of its error stack for the rest of the process (also at
/// library shutdown, when a file left open by a failed write is closed): our one-line messages
/// carry its gist. The campaign calls it once at start.
void silence_hdf5_errors();

/// Reads a cube written by write_cube (for resume and tests). Throws rigid::InputError when the
/// file is missing, not HDF5, or not a Rigid cube.
/// Objects come back in the order they were written; pgv_pga_edges_s holds the edges stored in
/// the file (the defaults when the written cube had none). A cube with variants comes back as
/// written: `count` ObjectCubes per base object, in object then variant order.
Cube read_cube(const std::string& path);

}  // namespace rigid::io
