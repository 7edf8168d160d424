#include "rigid/shaketable/fragility.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <map>

#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/io/csv.hpp"
#include "rigid/io/lab_recording.hpp"
#include "rigid/io/output_file.hpp"
#include "rigid/motion/measures.hpp"
#include "rigid/motion/strong_motion.hpp"

namespace rigid::shaketable {
namespace {
namespace fs = std::filesystem;
}

std::vector<double> pga_grid(double low, double high, int per_decade) {
  std::vector<double> grid;
  const double ratio = std::pow(10.0, 1.0 / per_decade);
  for (double v = low; grid.empty() || grid.back() < high; v *= ratio) {
    const double digits = std::pow(10.0, 3 - std::floor(std::log10(v)));
    const double rounded = std::round(v * digits) / digits;
    if (grid.empty() || rounded > grid.back()) grid.push_back(rounded);
  }
  return grid;
}

void check_settings(const FragilitySettings& s) {
  if (!s.bins_s.empty()) {
    bool increasing = s.bins_s.size() >= 2;
    for (std::size_t i = 0; i < s.bins_s.size(); ++i)
      increasing =
          increasing && std::isfinite(s.bins_s[i]) && s.bins_s[i] > 0 && (i == 0 || s.bins_s[i] > s.bins_s[i - 1]);
    if (!increasing) throw InputError("", 0, "--bins: at least two positive, strictly increasing edges (s)");
  }
  if (s.figure_format != "png" && s.figure_format != "pdf" && s.figure_format != "svg")
    throw InputError("", 0, "--format must be png, pdf or svg");
}

FragilityDesign::FragilityDesign(FragilitySettings settings, Callbacks callbacks)
    : settings_(std::move(settings)), callbacks_(std::move(callbacks)) {}

std::optional<campaign::CampaignOptions> FragilityDesign::next(const campaign::CampaignResult*) {
  if (prepared_) return std::nullopt;
  prepared_ = true;
  const FragilitySettings& o = settings_;
  check_settings(o);
  tests_ = io::read_lab_tests(o.tests);
  io::require_outcomes(tests_, "the lab's fragility is fitted on the observed outcomes");
  lab_ = lab_input(o.lab_format);
  ensemble_ = load_ensemble(o.scene);
  const Ensemble& e = ensemble_;
  work_ = o.out + ".fragility.work";
  {  // every output checked against every input before the first write
    std::vector<std::string> scenes = e.scenes;
    scenes.push_back(o.scene);
    const io::InputFiles inputs = command_inputs(o.tests, tests_, lab_, scenes, {e.json});
    inputs.refuse_as_output(o.out + ".fragility.csv");
    inputs.refuse_as_output(o.out + ".fragility." + o.figure_format);
    inputs.refuse_folder(work_.string());
  }

  // one recording per motion: its median test by measured PGA. The table does not reproduce a
  // motion alike at every amplitude (its hardest tests add high-frequency content: PGV/PGA falls
  // by up to 10x), so the recording in the middle of the tested range, where the lab placed its
  // tests around the rock's threshold, stands for the motion; chosen without the outcomes.
  std::map<std::string, std::vector<std::size_t>> tests_of;
  for (std::size_t t = 0; t < tests_.tests.size(); ++t) {
    const io::LabTest& test = tests_.tests[t];
    const motion::GroundMotion m = io::read_lab_motion(test.file, lab_.format);
    const motion::Peaks p = motion::peaks(m.x, m.dt);
    measured_.push_back({p.pga / kGravity, p.pgv / p.pga});
    tests_of[test.record].push_back(t);
  }
  for (auto& [record, list] : tests_of) {
    std::stable_sort(list.begin(), list.end(),
                     [&](std::size_t a, std::size_t b) { return measured_[a].pga_g < measured_[b].pga_g; });
    motion_test_.push_back(list[(list.size() - 1) / 2]);
  }
  std::sort(motion_test_.begin(), motion_test_.end());

  double top = 0;
  for (const Measured& m : measured_) top = std::max(top, m.pga_g);
  const double max_pga = o.max_pga_g > 0 ? o.max_pga_g : 1.25 * top;
  if (!(max_pga > o.min_pga_g)) throw InputError("", 0, "--max-pga must exceed --min-pga");
  const std::vector<double> grid = pga_grid(o.min_pga_g, max_pga, o.per_decade);
  if (grid.size() > 200) throw InputError("", 0, "--min-pga, --max-pga and --per-decade give more than 200 PGAs");

  io::JobFile job = ensemble_job(o.scene, e, lab_);
  std::vector<std::string> scenes = e.scenes;
  scenes.push_back(job.objects.front().scene);
  const double level_g = window_level_g(scenes);
  // at the grid's top PGA a recording is scaled by max_pga / PGA: the window's level in the
  // recording's own units keeps every part of it that could move the rock at any scale of the grid
  for (std::size_t t : motion_test_) {
    const io::LabTest& test = tests_.tests[t];
    const double level = level_g * measured_[t].pga_g / max_pga;
    const motion::TimeWindow w = motion::strong_motion_window(io::read_lab_motion(test.file, lab_.format), level);
    job.records.push_back(lab_record(test.file, w.start_s, w.end_s));
  }
  job.scales_g = grid;
  // the grid reaches well past the rock's strength: above three scales that overturned it under
  // every heading, the rest of a motion's scales are inferred, not run (the fits leave them out, as
  // `rigid fragility` does)
  job.stop_after = 3;

  std::error_code ec;
  fs::create_directories(work_, ec);
  if (ec) throw InputError(work_.string(), 0, "cannot create the fragility's folder: " + ec.message());
  campaign::CampaignOptions options;
  options.job = (work_ / "fragility.toml").string();
  options.output = cube_path();
  io::write_job_file(options.job, job,
                     "rigid shaketable fragility " + o.scene + " --tests " + o.tests +
                         "\n(written by the command; run again to resume)");
  if (callbacks_.on_campaign) callbacks_.on_campaign(options, "shaketable fragility");
  char line[400];
  std::snprintf(line, sizeof line,
                "shaketable fragility: %zu motions (the median test of each by PGA) x %zu PGAs (%.3g-%.3g g) x %zu "
                "ensemble scenes x %zu headings = at most %zu runs (3 scales overturned at every heading end a motion)",
                motion_test_.size(), grid.size(), grid.front(), grid.back(), e.scenes.size(), e.rotations_deg.size(),
                motion_test_.size() * grid.size() * e.scenes.size() * e.rotations_deg.size());
  callbacks_.tell(line);
  return options;
}

fs::path FragilityDesign::write_fit_inputs(const io::Cube& cube) const {
  io::write_output_file((work_ / "lab_tests.csv").string(), [&](std::ostream& out) {
    io::CsvWriter csv(out);
    csv.row({"test_no", "record", "measured_pga_g", "measured_pgv_over_pga_s", "overturned"});
    for (std::size_t t = 0; t < tests_.tests.size(); ++t) {
      const io::LabTest& test = tests_.tests[t];
      csv.field(test.test_no).field(test.record).fixed(measured_[t].pga_g, 6).fixed(measured_[t].pgv_pga_s, 6);
      csv.field(*test.overturned).end_row();
    }
  });
  io::write_output_file((work_ / "motions.csv").string(), [&](std::ostream& out) {
    io::CsvWriter csv(out);
    csv.row({"record", "test_no", "measured_pga_g", "measured_pgv_over_pga_s"});
    for (std::size_t t : motion_test_) {
      const io::LabTest& test = tests_.tests[t];
      csv.field(test.record).field(test.test_no).fixed(measured_[t].pga_g, 6).fixed(measured_[t].pgv_pga_s, 6);
      csv.end_row();
    }
  });
  // The model's P(overturn) per (motion, PGA): the ensemble's rule, without the lab's lapse (a
  // fragility is the rock's), with the weight of the mean number of headings a member sees. Cells
  // the stop rule inferred count as it says, overturned: above three scales that overturned the
  // rock at every heading, so does the rest. A (motion, PGA) is known where every member's cells
  // are (simulated or inferred); `simulated` marks those run throughout, the only ones the fit
  // reads (fit.py: inferred cells are the rule's assumption, not simulations).
  const std::size_t records = cube.records.size(), scales = cube.scales_g.size();
  const int rotations = cube.rotations;
  double headings = 0;
  for (const Ensemble::Member& m : ensemble_.members) headings += double(m.rotations.size());
  headings /= double(ensemble_.members.size());
  io::write_output_file((work_ / "model.csv").string(), [&](std::ostream& out) {
    out << "record_index,scale_g,p_overturn,cells,simulated\n";
    for (std::size_t r = 0; r < records; ++r) {
      for (std::size_t s = 0; s < scales; ++s) {
        bool known = true, simulated = true;
        const double p = ensemble_.probability(
            [&](int variant, int rotation) {
              const auto code = static_cast<io::CellOutcome>(
                  cube.objects[std::size_t(variant)]
                      .outcome[(r * scales + s) * std::size_t(rotations) + std::size_t(rotation)]);
              const bool ran = code == io::CellOutcome::survived || code == io::CellOutcome::overturned;
              simulated = simulated && ran;
              known = known && (ran || code == io::CellOutcome::inferred);
              return code == io::CellOutcome::overturned || code == io::CellOutcome::inferred;
            },
            false);
        char line[160];
        std::snprintf(line, sizeof line, "%zu,%.17g,%.17g,%.17g,%d\n", r, cube.scales_g[s], known ? p : 0.0,
                      known ? headings : 0.0, known && simulated ? 1 : 0);
        out << line;
      }
    }
  });
  return work_;
}

std::string FragilityDesign::physics_title() const {
  if (ensemble_.json.empty()) return "uncalibrated: the scene's own physics (no calibration file beside it)";
  const std::string file = fs::path(ensemble_.json).filename().string();
  const std::string members =
      std::to_string(ensemble_.members.size()) + " member" + (ensemble_.members.size() == 1 ? "" : "s");
  if (ensemble_.physics.empty()) return "calibrated physics of " + file + " (" + members + ")";
  return "calibrated physics: " + ensemble_.physics + " (" + file + ", " + members + ")";
}

}  // namespace rigid::shaketable
