// The `rigid` command line: subcommands register themselves (commands.hpp); errors in user input
// print one line `rigid: error: ...` and exit 2 (usage errors: command_line.hpp).
#include <cstdio>
#include <exception>
#include <string>

#include "command_line.hpp"
#include "commands.hpp"
#include "rigid/core/error.hpp"

int main(int argc, char** argv) {
  rigid::app::CommandLine app{"Rigid " RIGID_VERSION " (" RIGID_GIT_HASH
                              "): 3D rigid-block DEM fragilities of "
                              "precariously balanced rocks. SI units unless an option says otherwise."};
  app.set_version_flag("--version", RIGID_VERSION " (" RIGID_GIT_HASH ")");
  app.require_subcommand(1);
  rigid::app::register_run_command(app);
  rigid::app::register_inspect_command(app);
  rigid::app::register_motion_command(app);
  rigid::app::register_bench_command(app);
  rigid::app::register_model_command(app);
  rigid::app::register_campaign_command(app);
  rigid::app::register_plot_command(app);
  rigid::app::register_fragility_commands(app);
  rigid::app::register_study_command(app);
  rigid::app::register_export_command(app);
  rigid::app::register_shaketable_command(app);
  rigid::app::set_campaign_arguments(argc, argv);
  if (argc <= 1) {
    std::fputs(app.help().c_str(), stdout);
    return 0;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    // usage errors in the one-line format of every other input error, exit 2 (CLI11's own codes
    // are 100+ and its message two lines). Under mpirun every rank parses the same line: rank 0
    // prints and fails; the others leave quietly, since a failing rank makes mpirun stop the job,
    // which could kill rank 0 before it printed (mpirun's status is then rank 0's 2)
    if (!rigid::app::first_rank()) return 0;
    std::fprintf(stderr, "rigid: error: %s\n", rigid::app::usage_problem(app, e).c_str());
    return 2;
  } catch (const rigid::InputError& e) {
    std::fprintf(stderr, "rigid: error: %s\n", e.what());
    return 2;
  } catch (const std::invalid_argument& e) {
    std::fprintf(stderr, "rigid: error: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "rigid: internal error: %s\n", e.what());
    return 1;
  }
  return 0;
}
