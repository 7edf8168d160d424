// `rigid shaketable predict`: P(overturn) of each listed shake-table test for a (calibrated)
// scene, averaged over the calibration's ensemble (heading window, lapse, the physics left
// uncertain) when SCENE.calibration.json lies beside it. Never reads the outcome column until the
// predictions are written; then scores them against it.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

#include "campaign_report.hpp"
#include "commands.hpp"
#include "rigid/campaign/driver.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/json.hpp"
#include "rigid/io/output_file.hpp"
#include "shaketable.hpp"
#include "shaketable_report.hpp"

namespace rigid::app {
namespace {

namespace fs = std::filesystem;

struct PredictOptions {
  std::string scene, tests, out, lab_format, progress = "auto";
};

struct Prediction {
  io::LabTestList tests;
  shaketable::LabInput lab;
  shaketable::Ensemble ensemble;
  int stage = 0;
};

campaign::CampaignOptions prepare(Prediction& p, const PredictOptions& o) {
  io::refuse_output_over_inputs(o.out, {o.tests, o.scene});
  p.tests = io::read_lab_tests(o.tests);
  p.lab = shaketable::lab_input(o.lab_format);
  p.ensemble = shaketable::load_ensemble(o.scene);
  const shaketable::Ensemble& e = p.ensemble;
  io::DesignJob job = shaketable::ensemble_job(o.scene, e, o.lab_format);
  job.comment = "rigid shaketable predict " + o.scene + " --tests " + o.tests + "\n(written by the command; run again to resume)";
  std::vector<std::string> scenes = e.scenes;
  scenes.push_back(job.scene);
  job.records = shaketable::strong_motion_windows(p.tests, p.lab, shaketable::window_level_g(scenes));
  const std::string work = o.out + ".work";
  std::error_code ec;
  fs::create_directories(work, ec);
  if (ec) throw InputError(work, 0, "cannot create the prediction's folder: " + ec.message());
  campaign::CampaignOptions options;
  options.job = (fs::path(work) / "predict.toml").string();
  options.output = (fs::path(work) / "predict.h5").string();
  io::write_design_job(options.job, job);
  attach_progress(options, o.progress, 10);
  std::printf("shaketable: %zu tests x %zu ensemble scenes x %zu headings = %zu runs%s\n", p.tests.tests.size(),
              e.scenes.size(), e.rotations_deg.size(), p.tests.tests.size() * e.scenes.size() * e.rotations_deg.size(),
              e.json.empty() ? " (no calibration file beside the scene: one run per test)" : "");
  std::fflush(stdout);
  p.stage = 1;
  return options;
}

void finish(const Prediction& p, const PredictOptions& o, const io::Cube& cube) {
  const int tests = int(cube.records.size());
  const int headings = cube.rotations;
  std::vector<double> probability;
  for (int t = 0; t < tests; ++t) {
    probability.push_back(p.ensemble.probability([&](int variant, int rotation) {
      const io::ObjectCube& object = cube.objects[std::size_t(variant)];
      const auto code = static_cast<io::CellOutcome>(object.outcome[std::size_t(t * headings + rotation)]);
      if (code != io::CellOutcome::survived && code != io::CellOutcome::overturned)
        throw InputError(o.out, 0, "test " + std::to_string(p.tests.tests[std::size_t(t)].test_no) + " was not simulated (" +
                                       io::outcome_name(std::int8_t(code)) + ")");
      return code == io::CellOutcome::overturned;
    }));
  }
  std::ostringstream csv;
  csv << "test_no,record,pga_g,pgv_over_pga_s,p_overturn,predicted\n";
  for (int t = 0; t < tests; ++t) {
    const io::LabTest& test = p.tests.tests[std::size_t(t)];
    const io::RecordMeta& meta = cube.records[std::size_t(t)];
    char line[512];
    std::snprintf(line, sizeof line, "%ld,%s,%.5f,%.5f,%.6f,%d\n", test.test_no, test.record.c_str(), meta.gmroti_pga_g,
                  meta.pgv_pga_s, probability[std::size_t(t)], probability[std::size_t(t)] >= 0.5 ? 1 : 0);
    csv << line;
  }
  io::write_output_file(o.out, [&](std::ostream& out) { out << csv.str(); });
  std::printf("wrote %s (%d tests; P(overturn) over %zu ensemble members%s)\n", o.out.c_str(), tests,
              p.ensemble.members.size(), p.ensemble.json.empty() ? "" : (" from " + p.ensemble.json).c_str());
  // only now the outcomes, if the list has them
  if (p.tests.has_outcomes) {
    std::vector<int> observed;
    for (const io::LabTest& t : p.tests.tests) observed.push_back(*t.overturned);
    shaketable::print_scores("against the observed outcomes", calibration::score(probability, observed));
  }
}

}  // namespace

void add_shaketable_predict(CLI::App& parent) {
  auto o = std::make_shared<PredictOptions>();
  CLI::App* cmd = parent.add_subcommand(
      "predict",
      "P(overturn) of each shake-table test for a scene (a calibrated one averages over its calibration's ensemble); "
      "writes one CSV row per test; scores the predictions when the list has an overturned column (never read before)");
  cmd->add_option("scene", o->scene, "The scene, e.g. OUT.toml of rigid shaketable calibrate")->required();
  cmd->add_option("--tests", o->tests, "Test list CSV (test_no,record,...,file[,overturned]); file relative to the CSV")->required();
  cmd->add_option("--out", o->out, "Predictions CSV: test_no,record,pga_g,pgv_over_pga_s,p_overturn,predicted")->required();
  shaketable::add_recording_options(*cmd, o->lab_format, o->progress);
  cmd->callback([o] {
    Prediction p;
    shaketable::run_designed_campaigns(
        [&](const campaign::CampaignResult*) -> std::optional<campaign::CampaignOptions> {
          if (p.stage == 0) return prepare(p, *o);
          return std::nullopt;
        },
        [&](const campaign::CampaignResult& result) { finish(p, *o, *result.cube); });
  });
}

void add_shaketable_calibrate(CLI::App& parent);
void add_shaketable_fragility(CLI::App& parent);

void register_shaketable_command(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("shaketable", "A scanned rock against shake-table tests: calibrate its physics on "
                                                   "observed outcomes, predict others (docs/validation-shaketable.md)");
  cmd->require_subcommand(1);
  add_shaketable_calibrate(*cmd);
  add_shaketable_predict(*cmd);
  add_shaketable_fragility(*cmd);
}

}  // namespace rigid::app
