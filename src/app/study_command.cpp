// `rigid study accuracy`: what accuracy costs in time (docs/accuracy.md). Finds and reads
// the real record, runs the study (rigid/study/accuracy_study.hpp: cases, oracles, sweep), writes
// DIR/accuracy.csv, then DIR/accuracy_pareto.png and DIR/accuracy_table.md with
// src/python/accuracy_plot.py.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "commands.hpp"
#include "output_options.hpp"
#include "python_script.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/at2.hpp"
#include "rigid/io/csv.hpp"
#include "rigid/io/output_file.hpp"
#include "rigid/scenario/accuracy.hpp"
#include "rigid/study/accuracy_study.hpp"

namespace rigid::app {
namespace {

namespace fs = std::filesystem;
using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

// What the study sweeps (study::StudyOptions) and where its output goes.
struct StudyCommandOptions {
  study::StudyOptions sweep;
  std::string out = "out/accuracy";
  std::string record;
  bool plot = true;
  std::string figure_format = "png";
};

// "%.6g", empty when not finite (not computed)
std::string csv_number(double v) {
  if (!std::isfinite(v)) return "";
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

std::string csv_bool(const std::optional<bool>& b) { return b ? (*b ? "1" : "0") : ""; }

void write_csv(const std::string& path, const study::StudyResult& result) {
  io::write_output_file(path, [&](std::ostream& out) {
    io::CsvWriter csv(out);
    csv.row({"scene",
             "motion",
             "axis",
             "setting",
             "contact",
             "preset",
             "safety",
             "integrator",
             "stiffness_n_m",
             "rest_speed",
             "rest_time_s",
             "effects",
             "dt_s",
             "steps",
             "simulated_s",
             "overturned",
             "failure_time_s",
             "max_tilt_deg",
             "outcome_match",
             "failure_time_err_s",
             "max_tilt_err_deg",
             "traj_tilt_rms_deg",
             "traj_pos_rms_mm",
             "traj_rel_err",
             "error",
             "energy_err",
             "model_quantity",
             "model_value",
             "model_ref_err",
             "oracle",
             "oracle_value",
             "oracle_err",
             "wall_s",
             "search_wall_s",
             "repeats"});
    for (const study::Row& r : result.rows) {
      const study::Case& c = result.cases[r.case_index];
      const study::Setting& s = result.settings[r.setting_index];
      csv.row({c.scene,
               c.motion,
               s.axis,
               s.label,
               contact::contact_method_name(s.contact),
               s.preset,
               csv_number(s.safety),
               scenario::integrator_name(s.rotation),
               csv_number(s.stiffness),
               csv_number(s.rest_speed),
               csv_number(s.rest_time),
               s.select_effects ? "auto" : "all",
               csv_number(r.dt),
               std::to_string(r.steps),
               csv_number(r.simulated),
               csv_bool(r.overturned),
               csv_number(r.failure_time),
               csv_number(r.max_tilt_deg),
               csv_bool(r.outcome_match),
               csv_number(r.failure_time_err),
               csv_number(r.max_tilt_err),
               csv_number(r.tilt_rms),
               csv_number(r.pos_rms),
               csv_number(r.traj_rel),
               csv_number(r.error),
               csv_number(r.energy_err),
               c.model_quantity,
               csv_number(r.model_value),
               csv_number(r.model_ref_err),
               study::oracle_name(c.oracle),
               csv_number(c.oracle_value),
               csv_number(r.oracle_err),
               csv_number(r.wall),
               csv_number(r.search_wall),
               std::to_string(r.repeats)});
    }
  });
}

// The real record: the Rinaldi Receiving Station fault-normal component (Northridge 1994) from
// ../shared beside the checkout, else the bundled synthetic record (a fresh clone has no ../shared).
std::string find_record(const std::string& given) {
  if (!given.empty()) return given;
  const fs::path source = fs::path(__FILE__).parent_path().parent_path().parent_path();
  std::vector<fs::path> roots{source};
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) roots.push_back(exe.parent_path().parent_path().parent_path());
  roots.push_back(fs::current_path());
  for (const auto& root : roots) {
    const fs::path p = root / ".." / "shared" / "waveforms" / "peer" / "NORTHR" / "Rinaldi228.AT2";
    if (fs::is_regular_file(p, ec)) return p.lexically_normal().string();
  }
  for (const auto& root : roots) {
    const fs::path p = root / "waveforms" / "demo" / "stochastic_s1-X.AT2";
    if (fs::is_regular_file(p, ec)) return p.lexically_normal().string();
  }
  throw InputError("", 0,
                   "no record found (../shared/waveforms/peer/NORTHR/Rinaldi228.AT2 or waveforms/demo); give --record");
}

void study_accuracy(const StudyCommandOptions& options) {
  const study::StudyOptions& o = options.sweep;
  if (o.repeat < 1) throw InputError("", 0, "--repeat must be at least 1");
  if (o.contact != "rigid" && o.contact != "penalty" && o.contact != "both") {
    throw InputError("", 0, "--contact must be rigid, penalty or both");
  }
  if (!(o.reference_safety > 0)) throw InputError("", 0, "--reference-safety must be positive");
  const auto study_start = Clock::now();
  const std::string record_path = find_record(options.record);
  const motion::GroundMotion record = motion::windowed(io::read_motion_set("x=" + record_path), 0.0, 20.0);
  std::vector<study::Case> cases = study::study_cases(o, record);
  if (cases.empty()) throw InputError("", 0, "--only selects no case");
  std::vector<study::Setting> settings = study::study_settings(o);
  fs::create_directories(options.out);
  std::printf("rigid study accuracy: %zu cases x %zu settings; record %s\n", cases.size(), settings.size(),
              record_path.c_str());
  const study::StudyResult result =
      study::run_study(o, std::move(cases), std::move(settings), [](const study::Case& c, double seconds) {
        std::printf("  %-8s %-12s %5.1f s  (oracle %s = %s)\n", c.scene.c_str(), c.motion.c_str(), seconds,
                    c.oracle == study::Oracle::none ? "-" : study::oracle_name(c.oracle),
                    csv_number(c.oracle_value).c_str());
        std::fflush(stdout);
      });

  const std::string csv = (fs::path(options.out) / "accuracy.csv").string();
  write_csv(csv, result);
  std::printf("wrote %s (%zu rows) in %.1f s\n", csv.c_str(), result.rows.size(), seconds_since(study_start));
  if (!options.plot) return;
  const std::string script = find_plot_helper("accuracy_plot.py");
  if (script.empty()) {
    std::fprintf(stderr, "rigid study: warning: src/python/accuracy_plot.py not found; no plot\n");
    return;
  }
  const std::string figure = (fs::path(options.out) / ("accuracy_pareto." + options.figure_format)).string();
  const std::string md = (fs::path(options.out) / "accuracy_table.md").string();
  const int status = run_python(script, {csv, "--figure", figure, "--table", md});
  if (status != 0) {
    std::fprintf(stderr, "rigid study: warning: %s %s failed (status %d); the CSV is complete\n",
                 python_interpreter().c_str(), script.c_str(), status);
  }
}

}  // namespace

void register_study_command(CLI::App& app) {
  CLI::App* study = app.add_subcommand("study", "Studies of the engine itself: `rigid study accuracy`");
  study->require_subcommand(1);
  auto o = std::make_shared<StudyCommandOptions>();
  CLI::App* acc = study->add_subcommand(
      "accuracy",
      "What accuracy costs in time: reference scenes (slender and stocky blocks under a one-sine pulse, a real "
      "record and a quasi-static ramp; a two-block stack; a sliding block; the geode drop) run with every "
      "time-step safety factor, rotation integrator, at-rest tolerance, contact stiffness and accuracy preset, "
      "measured against a converged reference run and the analytic oracles. Writes DIR/accuracy.csv, "
      "DIR/accuracy_pareto.FORMAT and DIR/accuracy_table.md (docs/accuracy.md)");
  add_output_directory(*acc, o->out, "accuracy.csv, accuracy_pareto.FORMAT, accuracy_table.md")->capture_default_str();
  acc->add_flag("--quick", o->sweep.quick, "A small subset (CI smoke test, well under a minute)");
  acc->add_option("--repeat", o->sweep.repeat, "Runs per timing; the median wall time is reported (1 with --quick)")
      ->capture_default_str();
  acc->add_option("--reference-safety", o->sweep.reference_safety, "Safety factor of the converged reference run")
      ->capture_default_str();
  acc->add_option("--record", o->record,
                  "AT2 file of the real record (x component); default ../shared/waveforms/peer/NORTHR/Rinaldi228.AT2 "
                  "beside the checkout, else waveforms/demo/stochastic_s1-X.AT2");
  acc->add_option("--only", o->sweep.only,
                  "Only these scenes (slender, stocky, stack, sliding, geode) or SCENE/MOTION cases");
  acc->add_flag("!--no-plot", o->plot, "Write the CSV only");
  acc->add_option("--figure-format", o->figure_format, "The figure accuracy_pareto.FORMAT: png, pdf or svg")
      ->capture_default_str()
      ->check(CLI::IsMember({"png", "pdf", "svg"}));
  acc->add_option("--contact", o->sweep.contact,
                  "Contact models on the model axis: rigid (at safety 0.05-0.8), penalty (stiffness 1e8-1e10) or both")
      ->capture_default_str();
  acc->callback([o] { study_accuracy(*o); });
}

}  // namespace rigid::app
