// `rigid shaketable predict`: the flags of the prediction workflow (rigid::shaketable::Predictor),
// what it prints, and the `rigid shaketable` command itself.
#include <cstdio>
#include <memory>

#include "commands.hpp"
#include "output_options.hpp"
#include "rigid/shaketable/predict.hpp"
#include "shaketable.hpp"

namespace rigid::app {
namespace {

struct PredictFlags {
  rigid::shaketable::PredictionSettings settings;
  std::string progress = "auto";
};

void print_summary(const rigid::shaketable::PredictionSummary& s, const std::string& out) {
  std::printf("wrote %s (%d tests; P(overturn) over %zu ensemble members%s)\n", out.c_str(), s.tests, s.members,
              s.calibration.empty() ? "" : (" from " + s.calibration).c_str());
  if (!s.scores) return;
  shaketable::print_scores("against the observed outcomes", *s.scores);
  std::printf("  reliability (predicted P: tests, mean P, share overturned [95 %% Wilson interval]):\n");
  for (const calibration::ReliabilityBin& b : s.reliability) {
    if (b.tests == 0) continue;
    std::printf("    %.1f-%.1f: %3d tests, mean P %.3f, overturned %.3f [%.3f, %.3f]\n", b.lower, b.upper, b.tests,
                b.mean_probability, b.frequency, b.interval_low, b.interval_high);
  }
}

}  // namespace

void add_shaketable_predict(CLI::App& parent) {
  auto f = std::make_shared<PredictFlags>();
  rigid::shaketable::PredictionSettings& o = f->settings;
  CLI::App* cmd = parent.add_subcommand(
      "predict",
      "P(overturn) of each shake-table test for a scene (a calibrated one averages over its calibration's ensemble); "
      "writes one CSV row per test; scores the predictions when the list has an overturned column (never read before)");
  cmd->add_option("scene", o.scene, "The scene, e.g. OUT.toml of rigid shaketable calibrate")->required();
  cmd->add_option("--tests", o.tests, "Test list CSV (test_no,record,...,file[,overturned]); file relative to the CSV")
      ->required();
  add_output_file(
      *cmd, o.out,
      "the predictions CSV: test_no,record,measured_pga_g,measured_pgv_over_pga_s (GMRotI50 of the table's recording), "
      "p_overturn,predicted (the campaign works "
      "in OUT.work/)")
      ->required();
  shaketable::add_recording_options(*cmd, o.lab_format, f->progress);
  cmd->callback([f] {
    std::unique_ptr<rigid::shaketable::Predictor> predictor;
    shaketable::run_designed_campaigns(
        [&](const campaign::CampaignResult* previous) -> std::optional<campaign::CampaignOptions> {
          if (!predictor)
            predictor =
                std::make_unique<rigid::shaketable::Predictor>(f->settings, shaketable::command_callbacks(f->progress));
          return predictor->next(previous);
        },
        [&](const campaign::CampaignResult& result) {
          print_summary(predictor->finish(*result.cube), f->settings.out);
        });
  });
}

void add_shaketable_calibrate(CLI::App& parent);
void add_shaketable_fragility(CLI::App& parent);
void add_shaketable_transfer(CLI::App& parent);

void register_shaketable_command(CLI::App& app) {
  CLI::App* cmd =
      app.add_subcommand("shaketable",
                         "A scanned rock against shake-table tests: calibrate its physics on "
                         "observed outcomes, carry it to another rock, predict others (docs/validation-shaketable.md)");
  cmd->require_subcommand(1);
  add_shaketable_calibrate(*cmd);
  add_shaketable_transfer(*cmd);
  add_shaketable_predict(*cmd);
  add_shaketable_fragility(*cmd);
}

}  // namespace rigid::app
