// `rigid shaketable fragility`: the shake-table rock's fragility two ways, side by side. The lab's
// outcomes give an empirical one (the project's probit fit per PGV/PGA bin on each test's measured
// PGA); the calibrated model gives one from the same recorded motions scaled over a grid of PGAs
// (a designed campaign over the calibration's ensemble). The fits, the table of medians and the
// figure are src/python/shaketable_fragility.py's, run once the campaign has ended
// (docs/validation-shaketable.md).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>
#include <sstream>

#include "campaign_report.hpp"
#include "commands.hpp"
#include "python_script.hpp"
#include "rigid/core/error.hpp"
#include "rigid/core/types.hpp"
#include "rigid/io/json.hpp"
#include "rigid/io/lab_recording.hpp"
#include "rigid/io/output_file.hpp"
#include "shaketable.hpp"

namespace rigid::app {
namespace {

namespace fs = std::filesystem;

struct FragilityOptions {
  std::string scene, tests, out, lab_format, bins, format = "png", progress = "auto";
  double min_pga_g = 0.02;
  double max_pga_g = 0;  ///< 0: 1.25 x the largest measured PGA
  int per_decade = 24;
  int bootstrap = 1000;
  long seed = 1;
};

// One test's recorded table motion, measured as the campaign processes it.
struct Measured {
  double pga_g = 0, pgv_pga_s = 0;
};

struct Design {
  io::LabTestList tests;
  shaketable::LabInput lab;
  shaketable::Ensemble ensemble;
  std::vector<Measured> measured;        ///< per test
  std::vector<std::size_t> motion_test;  ///< per motion (cube record): the test whose recording it is
  fs::path work;
  std::string cube;
  bool fitted = false;
};

// A geometric grid from `low` to at least `high` (the lognormal's own spacing: as many points
// below the median as above it), each value rounded to 4 significant digits so that the job
// states it, and the cube stores it, exactly.
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

campaign::CampaignOptions prepare(Design& d, const FragilityOptions& o) {
  d.tests = io::read_lab_tests(o.tests);
  if (!d.tests.has_outcomes)
    throw InputError(o.tests, 1, "has no overturned column: the lab's fragility is fitted on the observed outcomes");
  d.lab = shaketable::lab_input(o.lab_format);
  d.ensemble = shaketable::load_ensemble(o.scene);
  const shaketable::Ensemble& e = d.ensemble;

  // one recording per motion: its median test by measured PGA. The table does not reproduce a
  // motion alike at every amplitude (its hardest tests add high-frequency content: PGV/PGA falls
  // by up to 10x), so the recording in the middle of the tested range, where the lab placed its
  // tests around the rock's threshold, stands for the motion; chosen without the outcomes.
  std::map<std::string, std::vector<std::size_t>> tests_of;
  for (std::size_t t = 0; t < d.tests.tests.size(); ++t) {
    const io::LabTest& test = d.tests.tests[t];
    const motion::GroundMotion m = io::read_lab_motion(test.file, d.lab.format);
    const motion::Peaks p = motion::peaks(m.x, m.dt);
    d.measured.push_back({p.pga / kGravity, p.pgv / p.pga});
    tests_of[test.record].push_back(t);
  }
  for (auto& [record, list] : tests_of) {
    std::stable_sort(list.begin(), list.end(),
                     [&](std::size_t a, std::size_t b) { return d.measured[a].pga_g < d.measured[b].pga_g; });
    d.motion_test.push_back(list[(list.size() - 1) / 2]);
  }
  std::sort(d.motion_test.begin(), d.motion_test.end());

  double top = 0;
  for (const Measured& m : d.measured) top = std::max(top, m.pga_g);
  const double max_pga = o.max_pga_g > 0 ? o.max_pga_g : 1.25 * top;
  if (!(max_pga > o.min_pga_g)) throw InputError("", 0, "--max-pga must exceed --min-pga");
  const std::vector<double> grid = pga_grid(o.min_pga_g, max_pga, o.per_decade);
  if (grid.size() > 200) throw InputError("", 0, "--min-pga, --max-pga and --per-decade give more than 200 PGAs");

  io::DesignJob job = shaketable::ensemble_job(o.scene, e, o.lab_format);
  job.comment = "rigid shaketable fragility " + o.scene + " --tests " + o.tests +
                "\n(written by the command; run again to resume)";
  std::vector<std::string> scenes = e.scenes;
  scenes.push_back(job.scene);
  const double level_g = shaketable::window_level_g(scenes);
  // at the grid's top PGA a recording is scaled by max_pga / PGA: the window's level in the
  // recording's own units keeps every part of it that could move the rock at any scale of the grid
  for (std::size_t t : d.motion_test) {
    const io::LabTest& test = d.tests.tests[t];
    const double level = level_g * d.measured[t].pga_g / max_pga;
    job.records.push_back(
        shaketable::strong_motion_window(io::read_lab_motion(test.file, d.lab.format), test.file, level));
  }
  job.scale_list_g = grid;
  // the grid reaches well past the rock's strength: above three scales that overturned it under
  // every heading, the rest of a motion's scales are inferred, not run (the fits leave them out, as
  // `rigid fragility` does)
  job.stop_after = 3;

  d.work = o.out + ".fragility.work";
  std::error_code ec;
  fs::create_directories(d.work, ec);
  if (ec) throw InputError(d.work.string(), 0, "cannot create the fragility's folder: " + ec.message());
  campaign::CampaignOptions options;
  options.job = (d.work / "fragility.toml").string();
  options.output = (d.work / "fragility.h5").string();
  d.cube = options.output;
  io::write_design_job(options.job, job);
  attach_progress(options, o.progress, 10);
  const std::size_t scales = grid.size();
  std::printf(
      "shaketable fragility: %zu motions (the median test of each by PGA) x %zu PGAs (%.3g-%.3g g) x %zu ensemble "
      "scenes x %zu headings = at most %zu runs (3 scales overturned at every heading end a motion)\n",
      d.motion_test.size(), scales, grid.front(), grid.back(), e.scenes.size(), e.rotations_deg.size(),
      d.motion_test.size() * scales * e.scenes.size() * e.rotations_deg.size());
  std::fflush(stdout);
  return options;
}

// What the fit reads beside the cube: the tests as measured, which test each motion is, and the
// ensemble's members as (variant, rotation indices, weight).
void write_fit_inputs(const Design& d) {
  io::write_output_file((d.work / "lab_tests.csv").string(), [&](std::ostream& out) {
    out << "test_no,record,pga_g,pgv_over_pga_s,overturned\n";
    for (std::size_t t = 0; t < d.tests.tests.size(); ++t) {
      const io::LabTest& test = d.tests.tests[t];
      char line[512];
      std::snprintf(line, sizeof line, "%ld,%s,%.6f,%.6f,%d\n", test.test_no, test.record.c_str(), d.measured[t].pga_g,
                    d.measured[t].pgv_pga_s, *test.overturned);
      out << line;
    }
  });
  io::write_output_file((d.work / "motions.csv").string(), [&](std::ostream& out) {
    out << "record,test_no,pga_g,pgv_over_pga_s\n";
    for (std::size_t t : d.motion_test) {
      const io::LabTest& test = d.tests.tests[t];
      char line[512];
      std::snprintf(line, sizeof line, "%s,%ld,%.6f,%.6f\n", test.record.c_str(), test.test_no, d.measured[t].pga_g,
                    d.measured[t].pgv_pga_s);
      out << line;
    }
  });
  io::Json members = io::Json::array();
  for (const shaketable::Ensemble::Member& m : d.ensemble.members) {
    io::Json j;
    j["variant"] = m.variant;
    j["rotations"] = m.rotations;
    j["weight"] = m.weight;
    members.push_back(j);
  }
  io::write_output_file((d.work / "members.json").string(), [&](std::ostream& out) { out << members.dump(1) << "\n"; });
}

}  // namespace

void add_shaketable_fragility(CLI::App& parent) {
  auto o = std::make_shared<FragilityOptions>();
  CLI::App* cmd = parent.add_subcommand(
      "fragility",
      "The rock's fragility two ways: the lab's (probit fit per PGV/PGA bin on the tests' measured PGA and outcomes) "
      "beside the (calibrated) scene's, from the same recorded motions scaled over a PGA grid; writes "
      "OUT.fragility.csv "
      "(medians with intervals) and the figure OUT.fragility.png");
  cmd->add_option("scene", o->scene, "The scene, e.g. OUT.toml of rigid shaketable calibrate")->required();
  cmd->add_option("--tests", o->tests, "Test list CSV with an overturned column; file relative to the CSV")->required();
  cmd->add_option("--out", o->out,
                  "Prefix of the outputs: OUT.fragility.csv, OUT.fragility.FORMAT, OUT.fragility.work/")
      ->required();
  cmd->add_option("--min-pga", o->min_pga_g, "Bottom of the PGA grid (g)")
      ->capture_default_str()
      ->check(CLI::Range(0.001, 5.0));
  cmd->add_option("--max-pga", o->max_pga_g, "Top of the PGA grid (g); default 1.25 x the largest measured PGA")
      ->check(CLI::Range(0.01, 20.0));
  cmd->add_option("--per-decade", o->per_decade, "PGAs per decade of the geometric grid")
      ->capture_default_str()
      ->check(CLI::Range(2, 100));
  cmd->add_option("--bins", o->bins,
                  "PGV/PGA bin edges (s), comma-separated, e.g. 0.02,0.06,0.1,0.3; default: three bins holding a "
                  "third of the motions each");
  cmd->add_option("--bootstrap", o->bootstrap, "Bootstrap replicates of the 90 % intervals")
      ->capture_default_str()
      ->check(CLI::Range(0, 100000));
  cmd->add_option("--seed", o->seed, "Seed of the bootstrap")->capture_default_str()->check(CLI::Range(0L, 1L << 62));
  cmd->add_option("--format", o->format, "Figure format: png, pdf or svg")
      ->capture_default_str()
      ->check(CLI::IsMember({"png", "pdf", "svg"}));
  shaketable::add_recording_options(*cmd, o->lab_format, o->progress);
  cmd->callback([o] {
    io::refuse_output_over_inputs(o->out + ".fragility.csv", {o->tests, o->scene});
    io::refuse_output_over_inputs(o->out + ".fragility." + o->format, {o->tests, o->scene});
    Design d;
    bool prepared = false;
    shaketable::run_designed_campaigns(
        [&](const campaign::CampaignResult*) -> std::optional<campaign::CampaignOptions> {
          if (prepared) return std::nullopt;
          prepared = true;
          return prepare(d, *o);
        },
        [&](const campaign::CampaignResult&) {
          write_fit_inputs(d);
          d.fitted = true;
        });
    if (!d.fitted) return;  // not rank 0
    // after MPI has ended: the fit replaces this process, its exit status is the command's
    const std::string script = find_plot_helper("shaketable_fragility.py");
    if (script.empty()) throw InputError("", 0, "cannot find shaketable_fragility.py (src/python beside the build)");
    std::vector<std::string> args{d.cube,
                                  "--lab",
                                  (d.work / "lab_tests.csv").string(),
                                  "--motions",
                                  (d.work / "motions.csv").string(),
                                  "--members",
                                  (d.work / "members.json").string(),
                                  "--out",
                                  o->out,
                                  "--bootstrap",
                                  std::to_string(o->bootstrap),
                                  "--seed",
                                  std::to_string(o->seed),
                                  "--format",
                                  o->format};
    if (!o->bins.empty()) {
      args.push_back("--bins");
      args.push_back(o->bins);
    }
    exec_python(script, args,
                "`rigid shaketable fragility` needs Debian's python3 with python3-numpy, python3-h5py, python3-scipy "
                "and python3-matplotlib (setup.sh installs them)");
  });
}

}  // namespace rigid::app
