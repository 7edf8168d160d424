#pragma once
/// Each subcommand registers itself on the CLI11 app; main() only dispatches and maps errors to
/// exit codes (2 = bad input, 1 = internal failure).
#include <CLI/CLI.hpp>

namespace rigid::app {

void register_run_command(CLI::App& app);
void register_inspect_command(CLI::App& app);
void register_motion_command(CLI::App& app);
void register_bench_command(CLI::App& app);
void register_model_command(CLI::App& app);
void add_library_subcommand(CLI::App& model_command);
void add_import_subcommand(CLI::App& model_command);
void register_campaign_command(CLI::App& app);
void register_plot_command(CLI::App& app);
/// `rigid fragility` and `rigid hazard` (src/python/rigid_fragility.py).
void register_fragility_commands(CLI::App& app);
void register_study_command(CLI::App& app);
void register_export_command(CLI::App& app);
/// `rigid shaketable calibrate|predict`: a scanned rock against shake-table tests.
void register_shaketable_command(CLI::App& app);
/// The campaign initialises MPI, which wants main()'s arguments.
void set_campaign_arguments(int& argc, char**& argv);
/// main()'s arguments, for the commands that start MPI.
int& campaign_argc();
char**& campaign_argv();

}  // namespace rigid::app
