#pragma once
// What `rigid campaign` prints: progress while it runs, the probability table when it completes,
// and the estimate of a dry run.
#include <string>

#include "rigid/campaign/options.hpp"
#include "rigid/io/cube.hpp"

namespace rigid::app {

/// A progress printer for CampaignOptions::on_progress: mode auto (a bar on a terminal, log lines
/// otherwise), bar, log or none. Sets options.on_progress and options.progress_interval. A `label`
/// (e.g. "shaketable: stage 3 (extend K_N down to 2.5e5)") leads each line.
void attach_progress(campaign::CampaignOptions& options, const std::string& mode, double log_interval,
                     const std::string& label = "");

/// The overturning probability per object and scale (mean over records), at most 16 columns.
void print_summary(const io::Cube& cube, const std::string& output);

/// The failed cells with their error text, the first few of them.
void print_failures(const io::Cube& cube);

/// One line: how many simulated cells had steps whose contact solve stopped at the sweep cap, and
/// how many such steps; nothing when there are none. `solver_max_sweeps`: the cap
/// (campaign::CampaignResult).
void print_unconverged(const io::Cube& cube, int solver_max_sweeps);

/// Task count and an estimate of the work: every object's first record at its smallest scale is
/// simulated for a few seconds to measure this machine's cost per step.
int print_dry_run(const job::Job& job, const scenario::Model& model);

}  // namespace rigid::app
