// `rigid run`: one scene, one ground motion, one answer; `rigid settle`: save an equilibrium.
#include <unistd.h>

#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <stdexcept>
#include <utility>

#include "commands.hpp"
#include "motion_input.hpp"
#include "number_checks.hpp"
#include "output_options.hpp"
#include "python_script.hpp"
#include "rigid/core/error.hpp"
#include "rigid/io/history_csv.hpp"
#include "rigid/io/json.hpp"
#include "rigid/io/output_file.hpp"
#include "rigid/io/scene_file.hpp"
#include "rigid/io/trajectory.hpp"
#include "rigid/job/job.hpp"
#include "rigid/job/model.hpp"
#include "rigid/scenario/accuracy.hpp"
#include "rigid/scenario/case.hpp"
#include "rigid/scenario/history.hpp"
#include "rigid/scenario/rocking2d.hpp"
#include "rigid/scenario/scene.hpp"
#include "scene_input.hpp"
#include "solver_options.hpp"

namespace rigid::app {
namespace {

struct RunOptions {
  std::string scene;
  std::string state;
  MotionOptions motion;
  double duration = 0;
  double free_time = 5.0;
  double dt = 0;
  double safety = 0;
  double solver_tolerance = 0;   // 0: the preset's
  double solver_max_sweeps = 0;  // 0: the preset's
  std::string integrator;        // empty: the preset's
  std::string accuracy = scenario::kDefaultAccuracy;
  std::string model = "dem3d";
  std::string contact;  // empty: the scene's
  std::string effects = "auto";
  std::string trajectory;
  double trajectory_interval = 0.02;
  std::string history;  // the time history as CSV (io/history_csv.hpp)
  std::string plot;     // its figure (pdf, svg, png), drawn by rigidpy
  std::string animate;  // its animation (gif)
  double history_interval = 0.01;
  bool json = false;
  bool wants_history() const { return !history.empty() || !plot.empty() || !animate.empty(); }
};

const char* end_name(scenario::ActiveEffects::End end) {
  switch (end) {
    case scenario::ActiveEffects::End::failure:
      return "failure";
    case scenario::ActiveEffects::End::at_rest:
      return "at_rest";
    default:
      return "full_duration";
  }
}

// The effects a run simulated (docs/engine.md, effect selection), as the "effects" object of --json.
io::Json effects_json(const scenario::ActiveEffects& e) {
  io::Json j;
  j["selected"] = e.selected;
  j["vertical_motion"] = e.vertical_motion;
  j["pairs_total"] = e.pairs_total;
  j["pairs_fixed_fixed"] = e.pairs_fixed_fixed;
  j["pairs_never_tested"] = e.pairs_never_tested;
  j["pair_steps_culled"] = e.pair_steps_culled;
  j["sleep_possible"] = e.sleep_possible;
  j["sleep_intervals"] = e.sleep_intervals;
  j["asleep_s"] = e.asleep_s;
  j["steps_skipped"] = e.steps_skipped;
  j["sliding"] = e.sliding;
  j["contact_steps"] = e.contact_steps;
  j["sliding_steps"] = e.sliding_steps;
  j["end"] = end_name(e.end);
  j["time_saved_s"] = e.time_saved_s;
  return j;
}

std::string effects_line(const scenario::ActiveEffects& e) {
  char buf[512];
  std::snprintf(buf, sizeof buf,
                "effects (%s): vertical %s; pairs %ld (%ld fixed-fixed never tested, %ld others never tested); "
                "asleep %.3f s in %ld intervals (%ld steps skipped); slip bookkeeping in %ld of %ld contact "
                "evaluations; end: %s, %.3f s before the requested duration",
                e.selected ? "auto" : "all", e.vertical_motion ? "yes" : "no", e.pairs_total, e.pairs_fixed_fixed,
                e.pairs_never_tested, e.asleep_s, e.sleep_intervals, e.steps_skipped, e.sliding_steps, e.contact_steps,
                end_name(e.end), e.time_saved_s);
  return buf;
}

// The run settings given as flags, parsed where a job file's are (job::set_text_setting).
job::RunOverrides run_overrides(const RunOptions& o) {
  job::RunOverrides overrides;
  const auto text = [&](job::Setting setting, const char* flag, const std::string& value) {
    job::set_text_setting(overrides, setting, value, {"", 0, flag});
  };
  text(job::Setting::accuracy, "--accuracy", o.accuracy);
  // 0 = the option was not given (its validator refuses 0)
  if (o.dt != 0) overrides.dt = o.dt;
  if (o.safety != 0) overrides.safety = o.safety;
  if (!o.integrator.empty()) text(job::Setting::integrator, "--integrator", o.integrator);
  if (o.solver_tolerance != 0)
    job::set_number_setting(overrides, job::Setting::solver_tolerance, o.solver_tolerance, "--solver-tolerance");
  if (o.solver_max_sweeps != 0)
    job::set_number_setting(overrides, job::Setting::solver_max_sweeps, o.solver_max_sweeps, "--solver-max-sweeps");
  overrides.duration = o.duration;
  overrides.free_time = o.free_time;
  text(job::Setting::effects, "--effects", o.effects);
  text(job::Setting::model, "--model", o.model);
  return overrides;
}

// The run's bounds (scenario/run_bounds.hpp) broken by a command-line value: the error names it.
scenario::Model checked_model(const job::Job& job, scenario::Scene scene, motion::GroundMotion m, const RunOptions& o) {
  try {
    return job::assemble_model(job, {std::move(scene)}, {std::move(m)});
  } catch (const InputError& e) {
    if (!e.file().empty()) throw;
    const char* option = o.dt != 0 ? "--dt" : o.safety != 0 ? "--safety" : o.duration != 0 ? "--duration" : "";
    throw InputError("", 0, (*option ? std::string(option) + ": " : std::string()) + e.problem());
  }
}

// --plot and --animate by extension, before any work: what matplotlib can draw here (an mp4 would
// need ffmpeg, which the project does not install; PillowWriter writes gif with python3-pil)
void check_history_outputs(const RunOptions& o, bool block2d) {
  if (o.wants_history() && !o.trajectory.empty()) {
    throw InputError("", 0,
                     "--trajectory and --history/--plot/--animate sample the run each at its own interval: give one");
  }
  if (o.wants_history() && block2d) {
    throw InputError("", 0, "--history, --plot and --animate record the 3D engine's blocks: use --model dem3d");
  }
  const auto extension = [](const std::string& path) {
    std::string e = std::filesystem::path(path).extension().string();
    for (char& c : e) c = char(std::tolower(static_cast<unsigned char>(c)));
    return e;
  };
  if (!o.plot.empty() && extension(o.plot) != ".pdf" && extension(o.plot) != ".svg" && extension(o.plot) != ".png") {
    throw InputError("", 0, "--plot " + o.plot + ": the figure's format comes from its extension: .pdf, .svg or .png");
  }
  if (!o.animate.empty() && extension(o.animate) != ".gif") {
    throw InputError("", 0, "--animate " + o.animate + ": only .gif (matplotlib's PillowWriter; an .mp4 needs ffmpeg)");
  }
  for (const std::string* path : {&o.history, &o.plot, &o.animate}) {
    if (!path->empty()) io::refuse_output_over_inputs(*path, {o.scene, o.state});
  }
}

// The history as CSV (--history, or a private temporary for the figure), then the figure and the
// animation, drawn by src/python/rigid_run_plot.py (rigidpy's figure of rigidpy.run's Dataset).
void write_history_outputs(const RunOptions& o, const scenario::History& history, const scenario::RunOutcome& r) {
  namespace fs = std::filesystem;
  const bool temporary = o.history.empty();
  const std::string csv =
      temporary ? (fs::temp_directory_path() / ("rigid_run_history_" + std::to_string(::getpid()) + ".csv")).string()
                : o.history;
  io::write_output_file(csv, [&](std::ostream& out) { io::write_history_csv(out, history); });
  if (o.plot.empty() && o.animate.empty()) return;
  std::vector<std::string> args{csv, "--title", fs::path(o.scene).filename().string()};
  if (r.failure_time_s) args.insert(args.end(), {"--overturned-at", std::to_string(*r.failure_time_s)});
  if (!o.plot.empty()) args.insert(args.end(), {"--plot", o.plot});
  if (!o.animate.empty()) args.insert(args.end(), {"--animate", o.animate});
  if (o.json) args.push_back("--quiet");  // standard output stays one JSON object
  const std::string script = find_plot_helper("rigid_run_plot.py");
  const int status = script.empty() ? -1 : run_python(script, args);
  if (temporary) fs::remove(csv);
  if (status == 2) throw InputError("", 0, "--plot/--animate: not drawn (the line above says why)");
  if (status != 0) {
    throw std::runtime_error(
        "--plot/--animate: " +
        (script.empty() ? std::string("src/python/rigid_run_plot.py not found")
                        : python_interpreter() + " " + script + " failed (status " + std::to_string(status) + ")") +
        "; it needs Debian's python3 with python3-matplotlib (and python3-pil for --animate)");
  }
}

// One scene, one motion: a job of one cell, its model built and its case made as a campaign's are.
void run(const RunOptions& o) {
  scenario::Scene scene = load_scene_with_warnings(o.scene);
  if (!o.state.empty()) io::apply_state(o.state, scene);
  job::RunOverrides overrides;
  if (!o.contact.empty()) job::set_text_setting(overrides, job::Setting::contact, o.contact, {"", 0, "--contact"});
  overrides = job::merged(std::move(overrides), run_overrides(o));
  job::Job job = job::one_cell_job(overrides);
  const bool block2d = job.engine == scenario::Engine::rocking2d;
  if (block2d) {
    // the 2D model integrates the rocking equation with its own fixed step (rocking::RockingOptions):
    // a step option given for the 3D engine would be silently ignored
    for (const auto& [option, given] : {std::pair{"--dt", o.dt != 0}, std::pair{"--safety", o.safety != 0},
                                        std::pair{"--integrator", !o.integrator.empty()}}) {
      if (given)
        throw InputError("", 0,
                         std::string(option) +
                             " does not apply to --model rocking2d (its integrator takes "
                             "fixed steps of its own); leave it out or use --model dem3d");
    }
    scenario::rocking_block_of(scene);  // the scene is checked before any motion is read
  }
  check_history_outputs(o, block2d);
  motion::GroundMotion m;
  reject_lab_flags_without_file(o.motion.lab);
  if (o.motion.given()) m = load_motion(o.motion);

  io::TrajectoryRecorder recorder;
  scenario::HistoryRecorder history(m);  // refers to m: the model below takes a copy
  if (!o.trajectory.empty() && !block2d) {
    job.run.observer = [&recorder](const dynamics::World& w) { recorder.record(w); };
    job.run.observe_interval = o.trajectory_interval;
  } else if (o.wants_history()) {
    job.run.observer = [&history](const dynamics::World& w) { history.record(w); };
    job.run.observe_interval = o.history_interval;
  }
  // the motion is already windowed, scaled and rotated (load_motion): the one cell takes it as
  // it is (scale "as recorded", rotation 0)
  const scenario::Model model = checked_model(job, std::move(scene), m, o);
  const auto start = std::chrono::steady_clock::now();
  const scenario::RunOutcome r = job::simulate_one_cell(job, model);
  if (!o.trajectory.empty() && !block2d) recorder.write(o.trajectory);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (o.wants_history()) write_history_outputs(o, history.history(), r);

  if (o.json) {
    io::Json j;
    j["overturned"] = r.overturned;
    j["failure_time_s"] = io::json_or_null(r.failure_time_s);
    j["failed_block"] = r.failed_block;
    j["steps"] = r.steps;
    j["dt_s"] = r.dt_s;
    j["simulated_s"] = r.simulated_s;
    j["wall_s"] = wall;
    j["max_tilt_deg"] = r.max_tilt_rad * 180.0 / kPi;
    j["max_slip_m"] = r.max_slip_m;
    j["max_overlap_m"] = r.max_overlap_m;
    j["ended_at_rest"] = r.ended_at_rest;
    j["finite"] = r.finite;
    j["unconverged_steps"] = r.unconverged_steps;
    j["max_solver_sweeps"] = r.max_solver_sweeps;
    j["solver_solves"] = r.solver_solves;
    j["solver_sweeps"] = r.solver_sweeps;
    if (!block2d) j["effects"] = effects_json(r.effects);
    std::printf("%s\n", io::json_line(j).c_str());
  } else {
    std::printf("%s after %.3f s simulated (%ld steps of %.3g s, %.3f s wall)\n",
                r.overturned ? "OVERTURNED" : "survived", r.simulated_s, r.steps, r.dt_s, wall);
    if (r.failure_time_s) std::printf("failure: %s at %.4f s\n", r.failed_block.c_str(), *r.failure_time_s);
    std::printf("max tilt %.3f deg, max slip %.4g m\n", r.max_tilt_rad * 180.0 / kPi, r.max_slip_m);
    if (r.unconverged_steps > 0) {
      std::printf("contact solver: %ld steps stopped at the sweep cap without converging (most sweeps %d)\n",
                  r.unconverged_steps, r.max_solver_sweeps);
    }
    if (!block2d) std::printf("%s\n", effects_line(r.effects).c_str());
  }
}

}  // namespace

void register_run_command(CLI::App& app) {
  auto o = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "Shake one scene with one ground motion and report whether it overturned");
  cmd->add_option("scene", o->scene, "Scene: a Rigid model file or a .toml scene file")->required();
  add_motion_options(*cmd, o->motion);
  cmd->add_option("--state", o->state, "Start from this saved equilibrium state (TOML from `rigid settle`)");
  cmd->add_option("--duration", o->duration, "Simulated time (s); default: motion duration + --free-time")
      ->check(positive_number());
  cmd->add_option("--free-time", o->free_time,
                  "Time left to rock after the motion ends, when --duration is not given (s)")
      ->capture_default_str()
      ->check(non_negative_number());
  cmd->add_option("--dt", o->dt,
                  "Time step (s); default: automatic from block masses and contact stiffness; at most the automatic "
                  "step at safety 1")
      ->check(positive_number());
  cmd->add_option("--safety", o->safety,
                  "Safety factor on the critical time step for the automatic step (default: the preset's; at most 1)")
      ->check(positive_number());
  cmd->add_option("--integrator", o->integrator,
                  "Rotation integrator: splitting (symplectic) or rk4 (default: the preset's)");
  cmd->add_option("--accuracy", o->accuracy,
                  "Accuracy preset: fast, balanced or reference (time-step safety, integrator, at-rest stop, "
                  "contact solve; docs/accuracy.md); --dt, --safety, --integrator, --solver-tolerance and "
                  "--solver-max-sweeps override its values")
      ->capture_default_str();
  add_solver_options(*cmd, o->solver_tolerance, o->solver_max_sweeps);
  cmd->add_option("--contact", o->contact,
                  "Contact model: rigid (non-penetrating, Moreau-Jean) or penalty (the study's springs); "
                  "default: the scene's [physics] contact");
  cmd->add_option("--model", o->model,
                  "dem3d (the 3D engine) or rocking2d (the 2D Housner reference, for a box block on a box "
                  "pedestal, driven by the x component; overturned = on its side)")
      ->capture_default_str();
  cmd->add_option("--trajectory", o->trajectory,
                  "Write block poses over time to this .xdmf (with a .h5 beside it) for ParaView (dem3d only)");
  cmd->add_option("--trajectory-interval", o->trajectory_interval, "Time between trajectory frames (s)")
      ->capture_default_str()
      ->check(positive_number());
  cmd->add_option("--effects", o->effects,
                  "auto: simulate only the effects the scene and motion call for (sleeping on a quiet "
                  "pedestal, pair culling, no vertical work without a vertical component, early end); "
                  "all: every effect, the reference")
      ->capture_default_str();
  cmd->add_option("--history", o->history,
                  "Write the time history to this CSV: per frame the table's motion and each free block's tilt, "
                  "slip, contacts and pose (dem3d only)");
  cmd->add_option("--plot", o->plot,
                  "Draw the time history (tilt, slip, table acceleration vs time) to this .pdf, .svg or .png "
                  "(dem3d only; rigidpy, /usr/bin/python3 with matplotlib)");
  cmd->add_option("--animate", o->animate,
                  "Animate the run to this .gif: the blocks from the side and the tilt as it grows (dem3d only; "
                  "matplotlib with python3-pil)");
  cmd->add_option("--history-interval", o->history_interval, "Time between history frames (s)")
      ->capture_default_str()
      ->check(positive_number());
  cmd->add_flag("--json", o->json, "Print one JSON object");
  cmd->callback([o] { run(*o); });

  auto settle_scene = std::make_shared<std::string>();
  auto settle_out = std::make_shared<std::string>();
  auto settle_time = std::make_shared<double>(20.0);
  CLI::App* settle = app.add_subcommand(
      "settle", "Settle a scene with no ground motion (local damping) and save its equilibrium state");
  settle->add_option("scene", *settle_scene, "Scene: a Rigid model file or a .toml scene file")->required();
  add_output_file(*settle, *settle_out, "the equilibrium state (TOML)")->required();
  settle->add_option("--max-time", *settle_time, "Longest settling time (s)")
      ->capture_default_str()
      ->check(positive_number());
  settle->callback([settle_scene, settle_out, settle_time] {
    const scenario::Scene scene = load_scene_with_warnings(*settle_scene);
    const scenario::Settled settled = scenario::settle(scene, dynamics::StepSettings{}, *settle_time);
    if (settled.loose) {
      throw InputError(*settle_scene, 0, scenario::describe(*settled.loose) + ": is it above a fixed block?");
    }
    io::save_state(*settle_out, settled.scene);
    std::printf("equilibrium state written to %s\n", settle_out->c_str());
  });
}

}  // namespace rigid::app
