#pragma once
/// The campaign driver: MPI master/worker over the task plan, checkpoints and resume, signals,
/// progress. The only part of Rigid that knows MPI.
#include <string>

namespace rigid::campaign {

/// Exit status of an interrupted (resumable) campaign: EX_TEMPFAIL.
inline constexpr int kExitInterrupted = 75;
/// Exit status when writing a checkpoint or the journal failed (disk full, unwritable output):
/// every rank ended cleanly, the last good cube and the journal are kept; run again to resume.
inline constexpr int kExitIoFailure = 1;

struct CampaignOptions {
  std::string job;              ///< job file
  std::string output;           ///< overrides the job's output path when not empty
  bool force = false;           ///< start anew over an output written by another job
  bool dry_run = false;         ///< print the task count and an estimate, run nothing
  bool noop = false;            ///< tasks return at once (measures dispatch throughput)
  std::string model;            ///< overrides the job's [run] model when not empty
  std::string accuracy;         ///< overrides the job's [run] accuracy preset when not empty
  std::string contact;          ///< overrides the job's contact model when not empty
  std::string effects;          ///< "auto" or "all": overrides the job's [run] effects when not empty
  std::string progress = "auto";  ///< auto | bar | log | none
  double log_interval = 10;     ///< seconds between plain progress lines (unit: s)
  double checkpoint_interval = 0;  ///< overrides the job's when > 0 (unit: s)
  double grace = -1;            ///< overrides the job's when >= 0 (unit: s)
};

/// Runs (or resumes) a campaign under MPI (a single process works without mpirun). Returns the
/// process exit status: 0 complete, kExitInterrupted after a stop signal (checkpoint written),
/// kExitIoFailure after a failed write (one line `rigid: error: ...` printed). Bad input, changed
/// inputs on resume and a second campaign on the same output throw rigid::InputError on rank 0;
/// other ranks return 2 quietly.
int run_campaign(int& argc, char**& argv, const CampaignOptions& options);

}  // namespace rigid::campaign
