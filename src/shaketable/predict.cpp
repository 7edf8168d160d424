#include "rigid/shaketable/predict.hpp"

#include <cstdio>
#include <filesystem>

#include "rigid/core/error.hpp"
#include "rigid/io/csv.hpp"
#include "rigid/io/output_file.hpp"

namespace rigid::shaketable {
namespace {
namespace fs = std::filesystem;
}

Predictor::Predictor(PredictionSettings settings, Callbacks callbacks)
    : settings_(std::move(settings)), callbacks_(std::move(callbacks)) {}

std::optional<campaign::CampaignOptions> Predictor::next(const campaign::CampaignResult*) {
  if (prepared_) return std::nullopt;
  prepared_ = true;
  const PredictionSettings& o = settings_;
  tests_ = io::read_lab_tests(o.tests);
  lab_ = lab_input(o.lab_format);
  ensemble_ = load_ensemble(o.scene);
  const Ensemble& e = ensemble_;
  io::JobFile job = ensemble_job(o.scene, e, lab_);
  std::vector<std::string> scenes = e.scenes;
  scenes.push_back(job.objects.front().scene);
  // every output checked against every input before the first write
  const std::string work = o.out + ".work";
  const io::InputFiles inputs = command_inputs(o.tests, tests_, lab_, scenes, {e.json});
  inputs.refuse_as_output(o.out);
  inputs.refuse_folder(work);
  job.records = strong_motion_records(tests_, lab_, window_level_g(scenes));
  std::error_code ec;
  fs::create_directories(work, ec);
  if (ec) throw InputError(work, 0, "cannot create the prediction's folder: " + ec.message());
  campaign::CampaignOptions options;
  options.job = (fs::path(work) / "predict.toml").string();
  options.output = (fs::path(work) / "predict.h5").string();
  io::write_job_file(options.job, job,
                     "rigid shaketable predict " + o.scene + " --tests " + o.tests +
                         "\n(written by the command; run again to resume)");
  if (callbacks_.on_campaign) callbacks_.on_campaign(options, "shaketable predict");
  char line[256];
  std::snprintf(line, sizeof line, "shaketable: %zu tests x %zu ensemble scenes x %zu headings = %zu runs%s",
                tests_.tests.size(), e.scenes.size(), e.rotations_deg.size(),
                tests_.tests.size() * e.scenes.size() * e.rotations_deg.size(),
                e.json.empty() ? " (no calibration file beside the scene: one run per test)" : "");
  callbacks_.tell(line);
  return options;
}

PredictionSummary Predictor::finish(const io::Cube& cube) const {
  const PredictionSettings& o = settings_;
  const int tests = int(cube.records.size());
  const int headings = cube.rotations;
  PredictionSummary s;
  for (int t = 0; t < tests; ++t) {
    s.probability.push_back(ensemble_.probability([&](int variant, int rotation) {
      const io::ObjectCube& object = cube.objects[std::size_t(variant)];
      const auto code = static_cast<io::CellOutcome>(object.outcome[std::size_t(t * headings + rotation)]);
      if (code != io::CellOutcome::survived && code != io::CellOutcome::overturned)
        throw InputError(o.out, 0,
                         "test " + std::to_string(tests_.tests[std::size_t(t)].test_no) + " was not simulated (" +
                             io::outcome_name(std::int8_t(code)) + ")");
      return code == io::CellOutcome::overturned;
    }));
  }
  io::write_output_file(o.out, [&](std::ostream& out) {
    io::CsvWriter csv(out);
    csv.row({"test_no", "record", "measured_pga_g", "measured_pgv_over_pga_s", "p_overturn", "predicted"});
    for (int t = 0; t < tests; ++t) {
      const io::LabTest& test = tests_.tests[std::size_t(t)];
      const io::RecordMeta& meta = cube.records[std::size_t(t)];
      const double p = s.probability[std::size_t(t)];
      csv.field(test.test_no).field(test.record).fixed(meta.gmroti_pga_g, 5).fixed(meta.pgv_pga_s, 5).fixed(p, 6);
      csv.field(p >= 0.5 ? 1 : 0).end_row();
    }
  });
  s.tests = tests;
  s.members = ensemble_.members.size();
  s.calibration = ensemble_.json;
  // only now the outcomes, if the list has them
  if (tests_.has_outcomes) {
    std::vector<int> observed;
    for (const io::LabTest& t : tests_.tests) observed.push_back(*t.overturned);
    s.scores = calibration::score(s.probability, observed);
    s.reliability = calibration::reliability(s.probability, observed);
  }
  return s;
}

}  // namespace rigid::shaketable
