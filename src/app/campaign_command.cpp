// `rigid campaign`: run or resume a fragility campaign (MPI master/worker; see campaign/driver).
#include <cstdlib>
#include <memory>
#include <tuple>

#include "campaign_report.hpp"
#include "commands.hpp"
#include "number_checks.hpp"
#include "output_options.hpp"
#include "rigid/campaign/driver.hpp"
#include "rigid/job/job.hpp"
#include "rigid/job/run_overrides.hpp"
#include "solver_options.hpp"

namespace rigid::app {

namespace {
int* g_argc = nullptr;
char*** g_argv = nullptr;
}  // namespace

void set_campaign_arguments(int& argc, char**& argv) {
  g_argc = &argc;
  g_argv = &argv;
}

int& campaign_argc() { return *g_argc; }
char**& campaign_argv() { return *g_argv; }

struct CampaignCommand {
  campaign::CampaignOptions options;
  // the run settings given as flags, empty when not given (parsed by job::set_text_setting)
  std::string model, contact, accuracy, effects;
  double solver_tolerance = 0, solver_max_sweeps = 0;  // 0: not given
  std::string progress = "auto";                       // auto | bar | log | none
  double log_interval = 10;                            // seconds between plain progress lines (unit: s)
};

void register_campaign_command(CLI::App& app) {
  auto command = std::make_shared<CampaignCommand>();
  campaign::CampaignOptions* o = &command->options;
  CLI::App* cmd = app.add_subcommand(
      "campaign",
      "Run a fragility campaign from a job file, or resume it when its output exists. Run under "
      "`mpirun -np N` or as one process. Exit status: 0 complete, 75 stopped by SIGTERM/SIGINT/SIGUSR1 "
      "(checkpoint written; run the same command to resume), 2 bad input, inputs changed since the campaign "
      "started, or another campaign on the same output, 1 a failed checkpoint or journal write (results kept; "
      "run again to resume) or an internal error");
  cmd->add_option("job", o->job, "Job file (TOML)")->required();
  add_output_file(*cmd, o->output, "the HDF5 cube (default: the job's output)");
  cmd->add_flag("--force", o->force,
                "Start anew over an output written by a different job file, other settings or inputs (scenes, meshes, "
                "states, records) that changed since");
  cmd->add_flag("--dry-run", o->dry_run, "Print the task count and an estimate of the work, run nothing");
  cmd->add_flag("--noop", o->noop,
                "Tasks return at once without simulating; with several ranks only the workers take tasks, so this "
                "measures the master's dispatch rate");
  cmd->add_option("--model", command->model,
                  "dem3d or rocking2d: overrides the job's [run] model (recorded in the cube)");
  cmd->add_option("--contact", command->contact,
                  "Contact model rigid or penalty for every object: overrides the scenes' [physics] contact and "
                  "the job's [run] contact (recorded in the cube)");
  cmd->add_option("--accuracy", command->accuracy,
                  "Accuracy preset fast, balanced or reference: overrides the job's [run] accuracy; the job's explicit "
                  "safety, integrator, dt_s and solver settings still apply (recorded in the cube; docs/accuracy.md)");
  add_solver_options(*cmd, command->solver_tolerance, command->solver_max_sweeps);
  cmd->add_option("--effects", command->effects,
                  "auto (simulate only the effects the scenes and motions call for) or all (every effect, the "
                  "reference): overrides the job's [run] effects (recorded in the cube)");
  cmd->add_option("--progress", command->progress,
                  "auto (a live line when a person watches: stderr is a terminal, or mpirun's is; log lines "
                  "otherwise), bar, log or none")
      ->capture_default_str()
      ->check(CLI::IsMember({"auto", "bar", "log", "none"}));
  cmd->add_option("--log-interval", command->log_interval,
                  "Seconds between progress log lines when not on a terminal (s)")
      ->capture_default_str()
      ->check(positive_number());
  cmd->add_flag("--verbose", o->verbose,
                "Also log the dispatch internals at the end (messages sent to worker ranks, checkpoint counts and "
                "costs, the longest hold of the dispatch lock)");
  cmd->add_option("--checkpoint-interval", o->checkpoint_interval_s,
                  "Seconds between checkpoints (a journal fsync; the whole cube is rewritten only when that takes at "
                  "most 5 % of the time); default: the job's (30 s)")
      ->check(number_admitted_by(job::checkpoint_interval_problem));
  cmd->add_option("--grace", o->grace_s, "Seconds in-flight tasks get after a stop signal; default: the job's (30 s)")
      ->check(number_admitted_by(job::grace_problem));
  cmd->callback([command] {
    campaign::CampaignOptions& options = command->options;
    attach_progress(options, command->progress, command->log_interval);
    options.remedies = {"--force", "--out"};
    options.read_overrides = [command] {
      job::RunOverrides flags;
      for (const auto& [setting, flag, text] : {std::tuple{job::Setting::model, "--model", &command->model},
                                                std::tuple{job::Setting::contact, "--contact", &command->contact},
                                                std::tuple{job::Setting::effects, "--effects", &command->effects},
                                                std::tuple{job::Setting::accuracy, "--accuracy", &command->accuracy}}) {
        if (!text->empty()) job::set_text_setting(flags, setting, *text, {"", 0, flag});
      }
      for (const auto& [setting, flag, value] :
           {std::tuple{job::Setting::solver_tolerance, "--solver-tolerance", command->solver_tolerance},
            std::tuple{job::Setting::solver_max_sweeps, "--solver-max-sweeps", command->solver_max_sweeps}}) {
        if (value != 0) job::set_number_setting(flags, setting, value, flag);
      }
      return flags;
    };
    options.on_dry_run = print_dry_run;
    const campaign::CampaignResult result = campaign::run_campaign(campaign_argc(), campaign_argv(), options);
    if (result.cube) {
      print_summary(*result.cube, result.output);
      print_failures(*result.cube);
      print_unconverged(*result.cube, result.solver_max_sweeps);
    }
    if (result.status != 0) std::exit(result.status);
  });
}

}  // namespace rigid::app
