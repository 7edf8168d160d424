#pragma once
/// The campaign driver: MPI start-up, the job and its model on every rank, the output lock and
/// resume on rank 0, then the master (rank 0) and the workers. The only part of Rigid that knows
/// MPI, with campaign/transport.
#include <functional>
#include <optional>

#include "rigid/campaign/master.hpp"
#include "rigid/campaign/options.hpp"

namespace rigid::campaign {

struct CampaignResult {
  int status = 0;                ///< process exit status (see run_campaign)
  std::optional<io::Cube> cube;  ///< on rank 0, the final cube of a completed campaign
  std::string output;            ///< the cube's path
  /// The rigid contact solve's sweep cap the runs had (a cell's unconverged_steps stopped at it).
  int solver_max_sweeps = 0;
};

/// MPI for the life of a command (under mpirun or as one process): initialised by the
/// constructor, finalised by the destructor, so a command may run several campaigns in turn.
class MpiSession {
 public:
  MpiSession(int& argc, char**& argv);
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  int rank() const { return rank_; }
  int ranks() const { return ranks_; }

 private:
  int rank_ = 0;
  int ranks_ = 1;
};

/// Runs (or resumes) a campaign under MPI (a single process works without mpirun). status: 0
/// complete (or a dry run), kExitInterrupted after a stop signal (checkpoint written),
/// kExitIoFailure after a failed write (one line `rigid: error: ...` printed). Bad input, changed
/// inputs on resume and a second campaign on the same output throw rigid::InputError on rank 0;
/// other ranks return status 2 quietly.
CampaignResult run_campaign(int& argc, char**& argv, const CampaignOptions& options);

/// The same within a session every rank entered (every rank calls it with the same job).
CampaignResult run_campaign(const MpiSession& session, const CampaignOptions& options);

/// Campaigns in sequence, each chosen on rank 0 from the results of the ones before (a sequential
/// design): `next` runs on rank 0 only and returns the next campaign's options, or nothing to end.
/// Workers learn the job and output paths from rank 0 and take part in every campaign. A `next`
/// that throws InputError ends the sequence on every rank (rank 0 rethrows; others return 2). The
/// result is the last campaign's; the sequence ends early at a non-zero status.
CampaignResult run_campaign_sequence(const MpiSession& session,
                                     const std::function<std::optional<CampaignOptions>(const CampaignResult*)>& next);

}  // namespace rigid::campaign
