#pragma once
/// Rank 0 of a campaign: hands out tasks, records and journals every result, fsyncs the journal
/// every checkpoint interval, rewrites the cube on a background thread (amortized: see
/// src/campaign/checkpointer.cpp), on a stop signal and at the end, and stops cleanly on a signal
/// or a failed write. Wired from task_pool, local_worker, dispatcher, checkpointer and
/// checkpoint_writer (src/campaign/master.cpp).
#include <optional>
#include <vector>

#include "rigid/campaign/options.hpp"
#include "rigid/campaign/session.hpp"

namespace rigid::campaign {

/// Exit status of an interrupted (resumable) campaign: EX_TEMPFAIL.
inline constexpr int kExitInterrupted = 75;
/// Exit status when writing a checkpoint or the journal failed (disk full, unwritable output):
/// every rank ended cleanly, the last good cube and the journal are kept; run again to resume.
inline constexpr int kExitIoFailure = 1;

struct MasterResult {
  int status = 0;                ///< 0, kExitInterrupted or kExitIoFailure
  std::optional<io::Cube> cube;  ///< the final cube when the campaign completed
};

/// Runs the campaign from the plan's restored state with `ranks - 1` worker ranks; the master
/// simulates too, on a second thread. `carried`: the old journal's results, kept in the new one
/// until the first checkpoint.
MasterResult run_master(const CampaignContext& context, const CampaignOptions& options, Plan& plan,
                        const std::vector<TaskResult>& carried, int ranks);

}  // namespace rigid::campaign
