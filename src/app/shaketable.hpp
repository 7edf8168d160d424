#pragma once
// What the `rigid shaketable` commands share at the command line: the recording options, the
// workflows' callbacks (lines to stdout, campaign progress, the import's report), the MPI session
// their designed campaigns run in, and how scores are printed. The workflows themselves are the
// shaketable module's (include/rigid/shaketable).
#include <functional>
#include <optional>
#include <string>

#include <CLI/CLI.hpp>

#include "rigid/calibration/outcome_model.hpp"
#include "rigid/campaign/driver.hpp"
#include "rigid/shaketable/calibrate.hpp"
#include "rigid/shaketable/workflow.hpp"

namespace rigid::app::shaketable {

/// The options every shaketable command shares: --lab-format FILE (the recordings' format) and
/// --progress (auto, bar, log or none).
void add_recording_options(CLI::App& cmd, std::string& lab_format, std::string& progress);

/// How a scan becomes the rock's scene, as calibrate and transfer import it: --scale, --up,
/// --tilt-rule (old spelling --tilt-deg), --max-vertices, --pedestal-margin, into those fields of
/// `s` (their defaults are CalibrationSettings').
void add_scan_import_options(CLI::App& cmd, rigid::shaketable::CalibrationSettings& s);

/// Lines to stdout, campaign progress in `progress` mode, scans imported with their report.
rigid::shaketable::Callbacks command_callbacks(const std::string& progress);

/// Runs a workflow's designed campaigns in one MPI session (campaign::run_campaign_sequence), then
/// `finish` on rank 0 once they all completed; ends the process with the campaigns' status
/// (75 interrupted, 1 failed write) after MPI has ended.
void run_designed_campaigns(
    const std::function<std::optional<campaign::CampaignOptions>(const campaign::CampaignResult*)>& next,
    const std::function<void(const campaign::CampaignResult&)>& finish);

/// Prints scores as the commands report them (one block of lines).
void print_scores(const char* title, const calibration::Scores& s);

}  // namespace rigid::app::shaketable
