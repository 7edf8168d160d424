// `rigid shaketable calibrate`: the flags of the calibration workflow (rigid::shaketable::Calibrator)
// and what it prints.
#include <cstdio>
#include <memory>
#include <optional>
#include <string>

#include "commands.hpp"
#include "old_spellings.hpp"
#include "output_options.hpp"
#include "python_script.hpp"
#include "rigid/core/error.hpp"
#include "rigid/shaketable/calibrate.hpp"
#include "rigid/shaketable/calibration_document.hpp"
#include "shaketable.hpp"

namespace rigid::app {
namespace {

using rigid::shaketable::CalibrationSettings;

struct CalibrateFlags {
  CalibrationSettings settings;
  std::vector<std::string> contact_models{"rigid", "5e5", "1e6", "2e6"};
  std::string progress = "auto";
};

void print_summary(const rigid::shaketable::CalibrationSummary& s) {
  std::printf("\ncalibrated: %s, heading %.1f deg [%.1f, %.1f] (spread %.0f deg, lapse %.2f)\n", s.label.c_str(),
              s.heading_deg, s.heading_low_deg, s.heading_high_deg, s.spread_deg, s.lapse);
  shaketable::print_scores("in sample", s.in_sample);
  if (s.cross_validated) {
    shaketable::print_scores("cross-validated (one recorded motion left out at a time)", *s.cross_validated);
  } else {
    std::printf("cross-validated: not available (fewer than %d recorded motions)\n",
                calibration::kMinCrossValidationGroups);
  }
  for (const auto& p : s.parameters)
    std::printf("  %s %.3g: %s\n", p.name.c_str(), p.value, rigid::shaketable::status_text(p.status));
  std::printf("wrote %s, %s (%.0f s)\n", s.scene.c_str(), s.json.c_str(), s.wall_s);
}

// The diagnostic figure, drawn by src/python/shaketable_calibration.py from what the calibration
// wrote (after MPI has ended). The calibration stands without it: a figure that cannot be drawn
// is a warning, not a failed command.
void draw_figure(const rigid::shaketable::CalibrationSummary& s, const CalibrationSettings& o) {
  const std::string figure = o.out + ".calibration." + o.figure_format;
  const std::string script = find_plot_helper("shaketable_calibration.py");
  const int status = script.empty() ? -1
                                    : run_python(script, {s.json, "--likelihood", s.likelihood_table, "--out", figure,
                                                          "--format", o.figure_format});
  if (status != 0) {
    std::fprintf(
        stderr,
        "rigid: warning: %s not drawn (%s); the calibration is complete. It needs Debian's python3 with "
        "python3-numpy and python3-matplotlib (setup.sh installs them)\n",
        figure.c_str(),
        script.empty() ? "cannot find shaketable_calibration.py" : ("status " + std::to_string(status)).c_str());
  }
}

// The flags as the workflow's settings: contact laws parsed.
CalibrationSettings settings_of(const CalibrateFlags& f) {
  CalibrationSettings s = f.settings;
  s.command_line = rigid::shaketable::command_line_text(campaign_argc(), campaign_argv());
  s.contact_models.clear();
  for (const std::string& text : f.contact_models) {
    const auto choice = rigid::shaketable::parse_contact_choice(text);
    if (!choice)
      throw InputError(
          "", 0,
          "--contact-models: '" + text + "' is neither rigid nor a penalty stiffness K_N in [1e5, 1e13] N/m^1.5");
    s.contact_models.push_back(*choice);
  }
  return s;
}

}  // namespace

void add_shaketable_calibrate(CLI::App& parent) {
  auto f = std::make_shared<CalibrateFlags>();
  CalibrationSettings& o = f->settings;
  CLI::App* cmd = parent.add_subcommand(
      "calibrate",
      "Fit a scanned rock's heading on the table, base model, contact law and its compliance, restitution and "
      "friction to observed shake-table outcomes by maximum likelihood (run under mpirun like a campaign; run again to "
      "resume). Writes OUT.toml (the calibrated scene), OUT.calibration.json and the work folder OUT.calibration/");
  cmd->add_option("scan", o.scan, "The rock's scan (OBJ, PLY, STL), as for rigid model import")->required();
  cmd->add_option("--tests", o.tests,
                  "Test list CSV: test_no,record,pgv_over_pga_s,pga_g,file,overturned (file relative to the CSV)")
      ->required();
  add_output_prefix(*cmd, o.out,
                    "NAME.toml (the calibrated scene), NAME.calibration.json, the work folder NAME.calibration/")
      ->required();
  shaketable::add_scan_import_options(*cmd, o);
  CLI::Option* flatten = cmd->add_option("--flatten-base", o.flatten_base_m,
                                         "Base models to compare: the rough base cut flat this far above its "
                                         "lowest point (m), as for rigid model import")
                             ->delimiter(',')
                             ->capture_default_str();
  add_old_spelling(*cmd, *flatten, {"--flatten-mm", "m", value_divided_by(1000)});
  cmd->add_option("--contact-models", f->contact_models,
                  "Contact laws to compare: rigid, or a penalty stiffness K_N (N/m^1.5, e.g. 1e7)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--restitution", o.restitution,
                  "Restitution values of the rigid contact (the first in stage 1, all in stage 2)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--damping", o.damping,
                  "Damping D of the penalty contact (s/m; the first in stage 1, all in stage 2)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--friction", o.friction, "Friction coefficients (the first in stage 1, all in stage 2)")
      ->delimiter(',')
      ->capture_default_str();
  cmd->add_option("--extend-stages", o.extend_stages,
                  "Edge extension: at most this many stages after stage 2 that try the values beyond the best where "
                  "it sits at an edge of the design (0: none)")
      ->capture_default_str();
  cmd->add_option("--headings", o.headings, "Stage 1: headings on a full ring")->capture_default_str();
  cmd->add_option("--keep", o.keep, "Stage 2: the best stage-1 variants refined")->capture_default_str();
  cmd->add_option("--refine-step", o.refine_step_deg,
                  "Stage 2: heading step around each kept variant's best heading (deg)")
      ->capture_default_str();
  cmd->add_flag("--restart", o.restart,
                "Start over: remove the work folder OUT.calibration/ of an earlier calibration into the same OUT (a "
                "rerun otherwise resumes it, and is refused when its inputs, settings or outcomes changed)");
  shaketable::add_recording_options(*cmd, o.lab_format, f->progress);
  cmd->add_option("--figure-format", o.figure_format, "The diagnostic figure OUT.calibration.FORMAT: png, pdf or svg")
      ->capture_default_str()
      ->check(CLI::IsMember({"png", "pdf", "svg"}));
  cmd->callback([f] {
    std::unique_ptr<rigid::shaketable::Calibrator> calibrator;
    std::optional<rigid::shaketable::CalibrationSummary> summary;
    shaketable::run_designed_campaigns(
        [&](const campaign::CampaignResult* previous) -> std::optional<campaign::CampaignOptions> {
          // rank 0 only: the flags are checked where the work starts, so that one rank says it
          if (!calibrator)
            calibrator = std::make_unique<rigid::shaketable::Calibrator>(settings_of(*f),
                                                                         shaketable::command_callbacks(f->progress));
          return calibrator->next(previous);
        },
        [&](const campaign::CampaignResult&) {
          summary = calibrator->finish();
          print_summary(*summary);
        });
    if (summary) draw_figure(*summary, f->settings);  // rank 0
  });
}

}  // namespace rigid::app
