#pragma once
/// A campaign's state on disk: the digests of its inputs, the cube built from the plan, and the
/// restore of a resumed campaign from its cube and journal (refused when inputs changed).
#include <string>
#include <vector>

#include "rigid/campaign/options.hpp"
#include "rigid/campaign/plan.hpp"
#include "rigid/io/cube.hpp"
#include "rigid/io/provenance.hpp"
#include "rigid/job/job.hpp"
#include "rigid/scenario/case.hpp"

namespace rigid::campaign {

/// SHA-256 of everything a cell depends on besides the code: the settings (job text with the
/// command-line overrides, accuracy preset), the job file, the record list, every object's files
/// and every record's motion files.
struct Inputs {
  io::Digests job;                   ///< (settings), job file, record list
  std::vector<io::Digests> objects;  ///< per object: scene, model, STLs, state
  std::vector<io::Digests> records;  ///< per record: motion files
  std::string combined;              ///< over the contents only: the same files elsewhere match
};

/// Reads every input file once more (after the model was loaded from them).
Inputs collect_inputs(const job::Job& job, const scenario::Model& model);

/// What a campaign writes besides the results: the job, its model and its inputs.
struct CampaignContext {
  const job::Job& job;
  const scenario::Model& model;
  const std::vector<io::RecordMeta>& records;
  const Inputs& inputs;
};

/// The cube of the plan's current state (the caller holds whatever guards the plan).
io::Cube make_cube(const CampaignContext& context, const Plan& plan);

/// Results already on disk: the cube's simulated cells are restored into the plan, then the
/// journal's, which are also returned (the new journal carries them until the first checkpoint).
/// Inputs changed since the cube was written: throws rigid::InputError naming the changed file,
/// touching neither the cube nor the journal, unless `force`, which removes both and starts anew.
/// The errors offer the caller's remedies (CampaignOptions::remedies).
std::vector<TaskResult> restore(const std::string& output, const job::Job& job, const Inputs& inputs, Plan& plan,
                                bool force, const OutputRemedies& remedies);

}  // namespace rigid::campaign
