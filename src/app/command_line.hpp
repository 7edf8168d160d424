#pragma once
/// The `rigid` command line's own rules over CLI11: a usage error is one line that names the problem,
/// the nearest known command or option ("did you mean") and the --help of the subcommand concerned;
/// notes (old spellings, old_spellings.hpp) print once the whole line has parsed; under mpirun both
/// print once, on rank 0.
#include <CLI/CLI.hpp>
#include <string>

namespace rigid::app {

/// The root of the command line. It prints the queued notes (queue_note) after the whole line has
/// parsed and before any command runs, so a line with an error prints the error alone.
class CommandLine : public CLI::App {
 public:
  using CLI::App::App;

 protected:
  void pre_callback() override;
};

/// Queues `rigid: note: TEXT` for stderr (printed by CommandLine, once per text).
void queue_note(const std::string& text);

/// What is wrong with a command line `app` failed to parse, in one line without the "rigid: error: "
/// in front: an unknown command or option with the nearest known one, a missing command with the
/// choices, or CLI11's message; each ends with the --help of the subcommand concerned.
std::string usage_problem(const CLI::App& app, const CLI::ParseError& error);

/// False when an MPI launcher started this process as a rank other than 0. Usage errors and notes
/// come before MPI starts, so the launcher's environment says which rank prints them.
bool first_rank();

}  // namespace rigid::app
