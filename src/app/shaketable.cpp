#include "shaketable.hpp"

#include <cstdio>
#include <cstdlib>

#include "campaign_report.hpp"
#include "commands.hpp"
#include "import_report.hpp"
#include "old_spellings.hpp"

namespace rigid::app::shaketable {

void add_recording_options(CLI::App& cmd, std::string& lab_format, std::string& progress) {
  cmd.add_option("--lab-format", lab_format,
                 "TOML file whose [lab] table says how to read the recordings (default: the lab export of "
                 "docs/ground-motions.md: tab-separated, time, acceleration in g, displacement in V)");
  cmd.add_option("--progress", progress, "auto, bar, log or none")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "bar", "log", "none"}));
}

void add_scan_import_options(CLI::App& cmd, rigid::shaketable::CalibrationSettings& s) {
  cmd.add_option("--scale", s.scale, "Scan units to metres, as for rigid model import")->capture_default_str();
  cmd.add_option("--up", s.up, "The scan's up axis, as for rigid model import")->capture_default_str();
  CLI::Option* tilt = cmd.add_option("--tilt-rule", s.tilt_deg,
                                     "Overturned = tilted beyond this angle (deg), as for rigid model import")
                          ->capture_default_str();
  add_old_spelling(cmd, *tilt, {"--tilt-deg", "", {}});
  cmd.add_option("--max-vertices", s.max_vertices, "Vertex budget of the rock's hull")->capture_default_str();
  cmd.add_option("--pedestal-margin", s.pedestal_margin, "The table: overhang of the box under the rock (m)")
      ->capture_default_str();
}

rigid::shaketable::Callbacks command_callbacks(const std::string& progress) {
  rigid::shaketable::Callbacks c;
  c.say = [](const std::string& line) {
    std::printf("%s\n", line.c_str());
    std::fflush(stdout);
  };
  c.on_campaign = [progress](campaign::CampaignOptions& options, const std::string& what) {
    attach_progress(options, progress, 10, what);
  };
  c.import_scan = [](const scan::ImportOptions& o) { import_and_report(o); };
  return c;
}

void run_designed_campaigns(
    const std::function<std::optional<campaign::CampaignOptions>(const campaign::CampaignResult*)>& next,
    const std::function<void(const campaign::CampaignResult&)>& finish) {
  int status = 0;
  {
    const campaign::MpiSession session(campaign_argc(), campaign_argv());
    const campaign::CampaignResult result = campaign::run_campaign_sequence(session, next);
    if (session.rank() == 0 && result.status == 0) finish(result);
    status = result.status;
  }  // MPI ends with the session, before the exit status is set
  if (status != 0) std::exit(status);
}

void print_scores(const char* title, const calibration::Scores& s) {
  std::printf("%s: accuracy %.3f, balanced accuracy %.3f, precision %.3f, recall %.3f, Brier %.3f, log loss %.3f\n",
              title, s.accuracy, s.balanced_accuracy, s.precision, s.recall, s.brier, s.log_loss);
  std::printf("  confusion (rows observed, columns predicted): overturned %d | %d   stood %d | %d\n", s.true_positive,
              s.false_negative, s.false_positive, s.true_negative);
}

}  // namespace rigid::app::shaketable
