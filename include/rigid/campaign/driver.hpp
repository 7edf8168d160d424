#pragma once
/// The campaign driver: MPI start-up, the job and its model on every rank, the output lock and
/// resume on rank 0, then the master (rank 0) and the workers. The only part of Rigid that knows
/// MPI, with campaign/transport.
#include <optional>

#include "rigid/campaign/master.hpp"
#include "rigid/campaign/options.hpp"

namespace rigid::campaign {

struct CampaignResult {
  int status = 0;                  ///< process exit status (see run_campaign)
  std::optional<io::Cube> cube;    ///< on rank 0, the final cube of a completed campaign
  std::string output;              ///< the cube's path
};

/// Runs (or resumes) a campaign under MPI (a single process works without mpirun). status: 0
/// complete (or a dry run), kExitInterrupted after a stop signal (checkpoint written),
/// kExitIoFailure after a failed write (one line `rigid: error: ...` printed). Bad input, changed
/// inputs on resume and a second campaign on the same output throw rigid::InputError on rank 0;
/// other ranks return status 2 quietly.
CampaignResult run_campaign(int& argc, char**& argv, const CampaignOptions& options);

}  // namespace rigid::campaign
