#include "rigid/job/load.hpp"

#include <cstdio>
#include <utility>

#include "rigid/core/error.hpp"
#include "rigid/job/variants.hpp"

namespace rigid::job {
namespace {

// Most cells one job may have: a cell's plan entry, result and journal record cost some
// hundred bytes, so 1e7 cells is about a gigabyte (and years of simulation).
constexpr double kMaxCells = 1e7;

// Refuses a job too large to plan (the plan and results live in memory) before anything is allocated.
void check_cell_count(const Job& job, long campaign_line) {
  const double cells = job.cells().size_estimate();
  if (cells > kMaxCells) {
    char buf[160];
    std::snprintf(buf, sizeof buf,
                  "the job has %.3g cells (objects x variants x records x scales x rotations), more than 1e7", cells);
    throw InputError(job.path, campaign_line, buf);
  }
}

}  // namespace

RunOverrides overrides_of(const io::RunTable& run, const std::string& path) {
  RunOverrides o;
  const auto text = [&](Setting setting, const std::optional<io::RunText>& given) {
    if (given) set_text_setting(o, setting, given->text, {path, given->line, ""});
  };
  text(Setting::contact, run.contact);
  text(Setting::model, run.model);
  o.duration = run.duration_s;
  o.free_time = run.free_time_s;
  o.dt = run.dt_s;
  o.safety = run.safety;
  if (const std::string problem = numbers_problem(o); !problem.empty()) throw InputError(path, run.line, problem);
  o.solver_tolerance = run.solver_tolerance;
  o.solver_max_sweeps = run.solver_max_sweeps;
  if (const std::string problem = solver_problem(o); !problem.empty()) throw InputError(path, run.solver_line, problem);
  text(Setting::integrator, run.integrator);
  text(Setting::accuracy, run.accuracy);
  text(Setting::effects, run.effects);
  return o;
}

Job load_job(const std::string& path) {
  io::JobFile file = io::read_job_file(path);
  Job job;
  job.path = file.path;
  job.text = std::move(file.text);
  job.output = std::move(file.output);
  job.seed = file.seed;
  job.scales_g = std::move(file.scales_g);
  job.drive_scales_g = std::move(file.drive_scales_g);
  job.rotations = file.rotations;
  job.rotation_angles_deg = std::move(file.rotation_angles_deg);
  job.stop_after = file.stop_after;
  job.checkpoint_interval_s = file.checkpoint_interval_s;
  job.grace_s = file.grace_s;
  job.objects = expand_variants(file.objects, file.variants);
  job.variants = std::move(file.variants);
  job.calibration = std::move(file.calibration);
  job.variant_lines = std::move(file.variant_lines);
  job.records = std::move(file.records);
  job.record_list = std::move(file.record_list);
  job.lab_format = std::move(file.lab_format);
  job.notes = std::move(file.notes);
  job.overrides = overrides_of(file.run, path);
  job.run_line = file.run.step_line;
  for (const auto& [key, problem] :
       {std::pair{"checkpoint_interval_s", checkpoint_interval_problem(job.checkpoint_interval_s)},
        std::pair{"grace_s", grace_problem(job.grace_s)}}) {
    if (!problem.empty()) throw InputError(job.path, file.campaign_line, std::string(key) + " " + problem);
  }
  check_cell_count(job, file.campaign_line);
  apply_overrides(job);
  job.hash = job_hash(job);
  return job;
}

void apply_command_line(Job& job, const RunOverrides& flags) {
  for (const auto& [setting, written] : flags.flags_given) {
    // the preset enters the hash through job.accuracy (job_settings_text)
    if (setting == Setting::accuracy) continue;
    if (setting == Setting::effects && flags.select_effects == job.run.select_effects) continue;
    job.text += "\n# command line: " + written + "\n";
  }
  job.overrides = merged(std::move(job.overrides), flags);
  apply_overrides(job);
  job.hash = job_hash(job);
}

}  // namespace rigid::job
