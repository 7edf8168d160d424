#pragma once
/// Reads what a job's cases run on: every object's scene (with its saved state and the job's
/// contact model) and every record, windowed, as one scenario::Model; and the per-record
/// metadata a cube stores.
#include <vector>

#include "rigid/io/cube.hpp"
#include "rigid/scenario/case.hpp"
#include "rigid/scenario/job.hpp"

namespace rigid::io {

/// Throws rigid::InputError for a bad scene, state or record (naming the file), for a record with
/// no horizontal acceleration (it cannot be scaled to a target PGA), and for scenes the job's
/// model cannot simulate.
scenario::Model load_model(const scenario::Job& job);

/// Name, source, window, alignment and GMRotI50 measures of each of the model's records.
std::vector<RecordMeta> record_metadata(const scenario::Job& job, const scenario::Model& model);

}  // namespace rigid::io
