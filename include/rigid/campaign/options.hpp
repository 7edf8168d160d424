#pragma once
/// What `rigid campaign` is asked to do, and how a job file plus those options become the job
/// that runs (the command-line overrides enter the job's text and hash, so a resume under other
/// settings is refused).
#include <functional>
#include <string>

#include "rigid/job/job.hpp"
#include "rigid/job/run_overrides.hpp"
#include "rigid/scenario/case.hpp"

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

/// The caller's ways out of a refused output, as its command line words them (the library names
/// no flag of its own): e.g. "--force" and "--out". Empty: that remedy is not offered.
struct OutputRemedies {
  std::string start_anew;    ///< starts anew over an output written by another job or inputs
  std::string other_output;  ///< writes to another output
};

struct CampaignOptions {
  std::string job;       ///< job file
  std::string output;    ///< overrides the job's output path when not empty
  bool force = false;    ///< start anew over an output written by another job
  bool dry_run = false;  ///< run nothing; call on_dry_run on rank 0
  bool noop = false;     ///< tasks return at once (measures dispatch throughput)
  /// The run settings given with the command (model, contact, effects, accuracy), over the job
  /// file's [run]; called on every rank after the job file is read, so a bad value is reported
  /// as a job's error is (empty: none). The caller parses them (job::set_text_setting) and names
  /// its own flags in their errors.
  std::function<job::RunOverrides()> read_overrides;
  double checkpoint_interval_s = 0;  ///< overrides the job's when > 0 (unit: s)
  double grace_s = -1;               ///< overrides the job's when >= 0 (unit: s)
  OutputRemedies remedies;           ///< offered in the errors about a refused output
  bool verbose = false;              ///< also log dispatch internals (messages, checkpoint costs)
  /// Called on rank 0 about every progress_interval seconds and once at the end (may be empty).
  std::function<void(const ProgressReport&)> on_progress;
  double progress_interval = 10;  ///< unit: s
  /// With dry_run: called on rank 0 with the job and its loaded model; returns the exit status.
  std::function<int(const job::Job&, const scenario::Model&)> on_dry_run;
};

/// Reads the job file and applies the options' overrides (output, read_overrides). Throws
/// rigid::InputError for a bad job file or a bad override value.
job::Job load_campaign_job(const CampaignOptions& options);

}  // namespace rigid::campaign
