#pragma once
/// The model a job's cases run on: every object's scene (with its saved state, the job's contact
/// model and its variant) and every record, windowed; and the per-record metadata a cube stores.
#include <vector>

#include "rigid/io/cube.hpp"
#include "rigid/job/job.hpp"
#include "rigid/motion/ground_motion.hpp"
#include "rigid/scenario/case.hpp"
#include "rigid/scenario/scene.hpp"

namespace rigid::job {

/// Builds the job's model from its scenes (one per object, as loaded: the job's contact model and
/// each object's variant are applied here) and records. A variant an object cannot take is an
/// InputError at the variant's line; a run that breaks the run bounds, one at the job's step
/// line (for a job with no file, the bounds error as it is, naming no file).
scenario::Model assemble_model(const Job& job, std::vector<scenario::Scene> scenes,
                               std::vector<motion::GroundMotion> records, std::vector<double> pga_factor_per_g = {});

/// Reads every object's scene and state and every record, then assemble_model. Throws
/// rigid::InputError for a bad scene, state or record (naming the file), for a record with no
/// horizontal acceleration (it cannot be scaled to a target PGA), and for scenes the job's model
/// cannot simulate.
scenario::Model load_model(const Job& job);

/// Name, source, window, alignment and GMRotI50 measures of each of the model's records.
std::vector<io::RecordMeta> record_metadata(const Job& job, const scenario::Model& model);

}  // namespace rigid::job
