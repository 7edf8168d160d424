#pragma once
/// What `rigid campaign` is asked to do, and how a job file plus those options become the job
/// that runs (the command-line overrides enter the job's text and hash, so a resume under other
/// settings is refused).
#include <functional>
#include <string>

#include "rigid/scenario/case.hpp"
#include "rigid/scenario/job.hpp"

namespace rigid::campaign {

/// Progress of a running campaign, as reported to CampaignOptions::on_progress.
struct ProgressReport {
  long done = 0;           ///< tasks done (any outcome), including those restored
  long settled = 0;        ///< cells needing no more work: simulated, or inferred by the stop rule
  long remaining = 0;      ///< tasks still to simulate (inferred cells not counted)
  long failures = 0;       ///< failed tasks
  long done_at_start = 0;  ///< tasks restored from the cube and journal
  long total = 0;          ///< cells in the campaign
  double elapsed_s = 0;    ///< since dispatch started (unit: s)
  bool final = false;      ///< the last report
};

struct CampaignOptions {
  std::string job;              ///< job file
  std::string output;           ///< overrides the job's output path when not empty
  bool force = false;           ///< start anew over an output written by another job
  bool dry_run = false;         ///< run nothing; call on_dry_run on rank 0
  bool noop = false;            ///< tasks return at once (measures dispatch throughput)
  std::string model;            ///< overrides the job's [run] model when not empty
  std::string accuracy;         ///< overrides the job's [run] accuracy preset when not empty
  std::string contact;          ///< overrides the job's contact model when not empty
  std::string effects;          ///< "auto" or "all": overrides the job's [run] effects when not empty
  double checkpoint_interval = 0;  ///< overrides the job's when > 0 (unit: s)
  double grace = -1;            ///< overrides the job's when >= 0 (unit: s)
  bool verbose = false;         ///< also log dispatch internals (messages, checkpoint costs)
  /// Called on rank 0 about every progress_interval seconds and once at the end (may be empty).
  std::function<void(const ProgressReport&)> on_progress;
  double progress_interval = 10;  ///< unit: s
  /// With dry_run: called on rank 0 with the job and its loaded model; returns the exit status.
  std::function<int(const scenario::Job&, const scenario::Model&)> on_dry_run;
};

/// Reads the job file and applies the options' overrides (output, model, contact, effects,
/// accuracy). Throws rigid::InputError for a bad job file or a bad override value.
scenario::Job load_campaign_job(const CampaignOptions& options);

}  // namespace rigid::campaign
