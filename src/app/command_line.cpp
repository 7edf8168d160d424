#include "command_line.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#include "nearest_name.hpp"

namespace rigid::app {
namespace {

std::vector<std::string>& queued_notes() {
  static std::vector<std::string> notes;
  return notes;
}

// The subcommands the line named, from the root down.
std::vector<const CLI::App*> parsed_chain(const CLI::App& root) {
  std::vector<const CLI::App*> chain{&root};
  for (auto subs = root.get_subcommands(); !subs.empty(); subs = subs.front()->get_subcommands()) {
    chain.push_back(subs.front());
  }
  return chain;
}

// `rigid model import`: the root's own name is argv[0], which may be a path
std::string command_name(const std::vector<const CLI::App*>& chain) {
  std::string name = "rigid";
  for (std::size_t k = 1; k < chain.size(); ++k) name += " " + chain[k]->get_name();
  return name;
}

// The subcommands of `app` a user may type (option groups have no name).
std::vector<std::string> subcommand_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::App* sub : app.get_subcommands([](const CLI::App* s) { return !s->get_name().empty(); })) {
    names.push_back(sub->get_name());
  }
  return names;
}

// The option names of `app` as typed (--name, -n), hidden ones (old spellings) left out.
std::vector<std::string> option_names(const CLI::App& app) {
  std::vector<std::string> names;
  for (const CLI::Option* opt : app.get_options()) {
    if (opt->get_group().empty()) continue;
    for (const std::string& l : opt->get_lnames()) names.push_back("--" + l);
    for (const std::string& s : opt->get_snames()) names.push_back("-" + s);
  }
  return names;
}

std::string unknown(const std::string& what, const std::string& typed, const std::vector<std::string>& known) {
  const std::string near = nearest_name(typed, known);
  return "unknown " + what + " '" + typed + "'" + (near.empty() ? "" : "; did you mean '" + near + "'?");
}

// "a, b or c"
std::string listed(const std::vector<std::string>& names) {
  std::string text;
  for (std::size_t k = 0; k < names.size(); ++k) {
    text += (k == 0 ? "" : k + 1 == names.size() ? " or " : ", ") + names[k];
  }
  return text;
}

}  // namespace

void CommandLine::pre_callback() {
  if (first_rank()) {
    for (const std::string& note : queued_notes()) std::fprintf(stderr, "rigid: note: %s\n", note.c_str());
  }
  queued_notes().clear();
}

void queue_note(const std::string& text) {
  auto& notes = queued_notes();
  if (std::find(notes.begin(), notes.end(), text) == notes.end()) notes.push_back(text);
}

std::string usage_problem(const CLI::App& app, const CLI::ParseError& error) {
  const std::vector<const CLI::App*> chain = parsed_chain(app);
  const CLI::App& last = *chain.back();
  const std::string help = " (see " + command_name(chain) + " --help)";
  // the first word no command took, looked for from the last command named up to the root
  for (auto it = chain.rbegin(); it != chain.rend(); ++it) {
    const std::vector<std::string> left = (*it)->remaining(false);
    if (left.empty()) continue;
    const std::string& word = left.front();
    if (word.size() > 1 && word[0] == '-') {
      return unknown("option", word.substr(0, word.find('=')), option_names(**it)) + help;
    }
    if (!subcommand_names(last).empty() && last.get_subcommands().empty()) {
      return unknown("command", word, subcommand_names(last)) + help;
    }
    break;
  }
  if (const auto commands = subcommand_names(last); !commands.empty() && last.get_subcommands().empty()) {
    return command_name(chain) + " needs a command: " + listed(commands) + help;
  }
  std::string message = error.what();
  std::replace(message.begin(), message.end(), '\n', ' ');
  return message + help;
}

bool first_rank() {
  // Open MPI, PMIx launchers (Slurm's srun among them) and MPICH-style PMI
  for (const char* name : {"OMPI_COMM_WORLD_RANK", "PMIX_RANK", "PMI_RANK"}) {
    if (const char* rank = std::getenv(name); rank != nullptr && *rank != '\0') return std::string(rank) == "0";
  }
  return true;
}

}  // namespace rigid::app
